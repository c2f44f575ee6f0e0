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
        let iw = Complex64::new(0.0, 2.0 * PI * f);
        match self {
            PoleBasis::Continuous | PoleBasis::Filtered { .. } => 1.0 / (iw - s),
            PoleBasis::Sampled { interval_s: dt } => dt / (1.0 - ((s - iw) * dt).exp()),
        }
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
        let g = self.term(f, s);
        match self {
            PoleBasis::Continuous | PoleBasis::Filtered { .. } => g * g,
            PoleBasis::Sampled { interval_s: dt } => {
                let iw = Complex64::new(0.0, 2.0 * PI * f);
                g * g * ((s - iw) * dt).exp()
            }
        }
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
        r * self.term(f, s) + r.conj() * self.term(f, s.conj())
    }
}
