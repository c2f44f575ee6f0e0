//! How a pole enters the modal model of a band: the term g(ω, s) of a unit
//! residue, by where the FRF comes from (an FRF on a frequency axis, records
//! sampled without a low-pass, records filtered before sampling). The
//! physics of the choice is in [`super::lsfd`]'s module doc.

use std::f64::consts::PI;

use realfft::num_complex::Complex64;

/// How a pole enters the modal model ([`super::lsfd`]'s module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PoleBasis {
    /// g = 1/(iω − s): an FRF given on a frequency axis (a UFF file).
    Continuous,
    /// g = Δt/(1 − e^((s − iω)Δt)): the DFT of a record sampled every
    /// `interval_s` seconds.
    Sampled { interval_s: f64 },
    /// g = 1/(iω − s) for the modes, the sampled g for the decays cut off
    /// at the end of the records: records whose channels were low-pass
    /// filtered before sampling ([`super::lsfd`]'s module doc).
    Filtered { interval_s: f64 },
}

impl PoleBasis {
    /// The term g(ω, s) of a unit residue, at `f` Hz.
    pub fn term(self, f: f64, s: Complex64) -> Complex64 {
        self.at(f).term(self.factor(s))
    }

    /// The factors of the terms at `f` Hz shared by every pole: one
    /// evaluation per bin, where a term per pole and bin costs a division.
    pub fn at(self, f: f64) -> BinTerms {
        let iw = Complex64::new(0.0, 2.0 * PI * f);
        let shift = match self {
            PoleBasis::Continuous => Complex64::new(1.0, 0.0),
            PoleBasis::Sampled { interval_s: dt } | PoleBasis::Filtered { interval_s: dt } => {
                (-iw * dt).exp()
            }
        };
        BinTerms {
            basis: self,
            iw,
            shift,
        }
    }

    /// The factor e^(sΔt) of the pole `s` in the sampled term (1 on a
    /// continuous axis): one evaluation per pole.
    pub fn factor(self, s: Complex64) -> PoleFactor {
        let growth = match self {
            PoleBasis::Continuous => Complex64::new(1.0, 0.0),
            PoleBasis::Sampled { interval_s: dt } | PoleBasis::Filtered { interval_s: dt } => {
                (s * dt).exp()
            }
        };
        PoleFactor { s, growth }
    }

    /// The basis of the decays the records' end cut off: the tail is a
    /// sampled decay however the records were made.
    pub fn cutoff(self) -> PoleBasis {
        match self {
            PoleBasis::Filtered { interval_s } => PoleBasis::Sampled { interval_s },
            other => other,
        }
    }

    /// ∂g/∂s at `f` Hz (g is holomorphic in s).
    pub fn term_derivative(self, f: f64, s: Complex64) -> Complex64 {
        self.at(f).term_derivative(self.factor(s))
    }

    /// A key for outputs: `continuous`, `sampled` or `filtered`.
    pub fn key(self) -> &'static str {
        match self {
            PoleBasis::Continuous => "continuous",
            PoleBasis::Sampled { .. } => "sampled",
            PoleBasis::Filtered { .. } => "filtered",
        }
    }

    /// What the basis takes the data for, in words.
    pub fn describe(self) -> &'static str {
        match self {
            PoleBasis::Continuous => "an FRF on a frequency axis (continuous-time poles)",
            PoleBasis::Sampled { .. } => {
                "records sampled without a low-pass (discrete-time poles; the better fit of the two)"
            }
            PoleBasis::Filtered { .. } => {
                "records low-pass filtered before sampling (continuous-time poles; the better fit of the two)"
            }
        }
    }

    /// The bases a fit of this origin tries: records may or may not have
    /// been low-pass filtered before sampling, an FRF on a frequency axis
    /// is continuous.
    pub fn candidates(self) -> Vec<PoleBasis> {
        match self {
            PoleBasis::Continuous => vec![PoleBasis::Continuous],
            PoleBasis::Sampled { interval_s } | PoleBasis::Filtered { interval_s } => vec![
                PoleBasis::Sampled { interval_s },
                PoleBasis::Filtered { interval_s },
            ],
        }
    }

    /// A pole pair's contribution R g(ω, s) + R̄ g(ω, s̄) at `f` Hz.
    pub fn pair(self, f: f64, s: Complex64, r: Complex64) -> Complex64 {
        self.at(f).pair(self.factor(s), r)
    }
}

/// A pole s with its factor e^(sΔt) ([`PoleBasis::factor`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoleFactor {
    /// The pole, 1/s.
    pub s: Complex64,
    /// e^(sΔt) (1 on a continuous axis).
    growth: Complex64,
}

impl PoleFactor {
    /// The conjugate pole s̄ and its factor.
    pub fn conj(self) -> PoleFactor {
        PoleFactor {
            s: self.s.conj(),
            growth: self.growth.conj(),
        }
    }
}

/// The pole terms at one frequency ([`PoleBasis::at`]): iω, and
/// e^(−iωΔt) for the sampled term Δt/(1 − e^(sΔt)·e^(−iωΔt)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BinTerms {
    basis: PoleBasis,
    iw: Complex64,
    shift: Complex64,
}

impl BinTerms {
    /// The term g(ω, s) of a unit residue.
    pub fn term(&self, p: PoleFactor) -> Complex64 {
        match self.basis {
            PoleBasis::Continuous | PoleBasis::Filtered { .. } => 1.0 / (self.iw - p.s),
            PoleBasis::Sampled { interval_s: dt } => dt / (1.0 - p.growth * self.shift),
        }
    }

    /// ∂g/∂s (g is holomorphic in s).
    pub fn term_derivative(&self, p: PoleFactor) -> Complex64 {
        let g = self.term(p);
        match self.basis {
            PoleBasis::Continuous | PoleBasis::Filtered { .. } => g * g,
            PoleBasis::Sampled { .. } => g * g * p.growth * self.shift,
        }
    }

    /// The same frequency in the basis of the cut-off decays
    /// ([`PoleBasis::cutoff`]).
    pub fn cutoff(&self) -> BinTerms {
        BinTerms {
            basis: self.basis.cutoff(),
            ..*self
        }
    }

    /// A pole pair's contribution R g(ω, s) + R̄ g(ω, s̄).
    pub fn pair(&self, p: PoleFactor, r: Complex64) -> Complex64 {
        r * self.term(p) + r.conj() * self.term(p.conj())
    }
}
