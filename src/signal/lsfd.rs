//! The modal model of a band and its least-squares fit: residues by linear
//! least squares (LSFD), poles by nonlinear least squares, and the choice
//! of the poles that are physical and significant (see [`super::fit`]).
//!
//! **Model.** H(ω) = Σ_r [R_r g(ω, s_r) + R̄_r g(ω, s̄_r)] + U + L/(iω)²,
//! with R_r in FRF unit × 1/s, s_r in 1/s, U in FRF unit and L in FRF
//! unit × 1/s² (U and L stand for the modes outside the band). The pole
//! term g depends on where H comes from ([`PoleBasis`]):
//! - an FRF on a continuous frequency axis: g = 1/(iω − s);
//! - the DFT of a record sampled every Δt: g = Δt/(1 − e^((s − iω)Δt)),
//!   the transform of the sampled decay R e^(s nΔt). At the DFT bins of
//!   an N-sample record, e^(−iωNΔt) = 1, so a decay cut off at the end of
//!   the record, R e^(s nΔt) for n < N only, transforms to
//!   (1 − e^(sNΔt)) R g(ω, s): the same pole with another residue. This
//!   holds for records sampled without a low-pass, as a discrete-time
//!   system (a closed-form impulse response sampled and convolved).
//! - records whose channels passed one low-pass before sampling, as an
//!   acquisition system filters (and as `impulse` records): the ratio of
//!   their spectra is the structure's continuous FRF, without the pole's
//!   aliases, so g = 1/(iω − s) for the modes; the decay cut off at the
//!   record's end is still a sampled decay, so its term keeps the sampled g
//!   ([`PoleBasis::Filtered`]).
//!
//! Which of the two a pair of records follows is not written in them: the
//! fit of records is run with both and the one with the smaller misfit is
//! kept (and reported). On the issue-33 cantilever record (made by
//! `impulse`) the sampled basis alone left a 925 Hz mode 2.3e-4 off in f
//! and 8 % in ζ, the filtered one 1.9e-5 and 0.5 %; on closed-form
//! discrete-time records the sampled basis is exact. For Δt → 0 the bases
//! agree.
//!
//! **Refinement.** The poles are refined together by Levenberg–Marquardt
//! on the misfit of the model, the residues and residual terms eliminated
//! by linear least squares at every step (variable projection,
//! [`super::projection`], with its exact Jacobian). LSCF's
//! linearised equation error is biased by noise; this output error is not
//! (for noise of equal variance across the band).
//!
//! **Choice.** A refined pole that grows by less than [`DECAY_RESOLUTION`]
//! standard errors, and stands above the noise as a ringing mode does
//! ([`RINGING_SIGNIFICANCE`]), is put on the stability boundary when no
//! exponential window is applied: the record shows no decay, and its
//! damping is reported as a bound. After each refinement one pole at a
//! time is rejected, and
//! the rest refined again from their seeds: first a pole the refinement
//! made unstable, overdamped or moved off the positive frequencies
//! (`failed_refinement`, shown at its seed), then one it moved out of the
//! band (`left_band`, shown where it went), then the one whose damping the
//! record resolves least, while its decay rate ζω is under
//! [`DECAY_RESOLUTION`] = 3 standard errors of the fit
//! (`unresolved_damping`), then one of two poles in one half-power band
//! that the fit does not need beyond noise (`redundant`), then the least
//! significant while its significance is under [`SIGNIFICANCE`]
//! (`not_significant`).
//!
//! **Significance** is a test against the noise estimated from the data:
//! the RMS of a pole's modal contribution R g(ω, s) + R̄ g(ω, s̄) over its
//! half-power band (the bins within f_d ± max(ζf, 2Δf)) divided by the RMS
//! of the fit residual H − Ĥ over the same bins. The residual holds what
//! the model cannot explain there: measurement noise, a spurious pole's
//! misfit. A mode whose peak stands k times above the noise has a
//! significance of about 0.86 k (its contribution falls to 1/√2 of the
//! peak across the band), so a mode 3 × above the noise passes; a pole
//! that fits noise explains only the few numbers it has (a pole and a
//! residue) of the 2m in its m bins and stays near 1. No ratio to the
//! largest peak enters: a weak mode of noise-free data is reported.

use std::f64::consts::PI;

use nalgebra::DMatrix;
use realfft::num_complex::Complex64;

use super::fit::{FitSettings, RejectReason, MAX_DAMPING};
use super::projection::{design, pole_jacobian};
pub use super::projection::{project, refine, Projection};

pub use super::pole_basis::PoleBasis;

/// Smallest significance of a reported mode: the RMS of its modal
/// contribution over its half-power band, in units of the RMS fit residual
/// there (module doc).
pub const SIGNIFICANCE: f64 = 2.0;
/// Smallest half-width of the half-power band of the significance test, in
/// bins: a lightly damped mode's band ±ζf may hold no bin.
pub const MIN_HALF_POWER_BINS: f64 = 2.0;

/// The measured FRF over the fit band and the model's pole term.
#[derive(Debug, Clone, Copy)]
pub struct Band<'a> {
    /// (f Hz, H) of the bins in the band.
    pub bins: &'a [(f64, Complex64)],
    pub basis: PoleBasis,
    /// Per bin, the weight W of the decays the records' end cut off
    /// ([`crate::signal::frf::CrossSpectra::truncation_weight`]), when H
    /// comes from records: each pole then also has a term
    /// W (D g(ω, s) + D̄ g(ω, s̄)).
    pub truncation: Option<&'a [Complex64]>,
    /// Length of the records, s: a pole whose decay e^(Re s·T) is under
    /// [`TRUNCATION_FLOOR`] at their end has no cut-off term.
    pub record_s: f64,
    /// Powers of iω of the residual terms beside U and L
    /// ([`RESIDUAL_POWERS`], or [`POLISH_POWERS`] in the last refinement).
    pub powers: &'a [i32],
    /// Per bin, the weight of its equation, when H is the H1 of records:
    /// √(Σ|F_i|²) relative to its mean. H1's error (N_X − H N_F)/F has a
    /// variance ∝ 1/|F|²: where the force is weak (or a noisy force dips)
    /// H is poor, and weighted by |F| every bin's error has one law
    /// (least squares is then the maximum-likelihood fit).
    pub rows: Option<&'a [f64]>,
}

/// The smallest decay e^(Re s·T) left at the end of the records for which
/// a pole gets its cut-off term. Below it the term is too small to fit,
/// and its free coefficient, weighted by a W that noise on the force makes
/// vary across the peak, would trade off against the pole's frequency.
pub const TRUNCATION_FLOOR: f64 = 1e-6;

impl Band<'_> {
    /// The weight of bin `k`'s equation (1 without records).
    pub(crate) fn row(&self, k: usize) -> f64 {
        self.rows.and_then(|w| w.get(k).copied()).unwrap_or(1.0)
    }

    /// [`RECORD_DECAY_FLOOR`] over the records' length [1/s]: their
    /// `record_s`, or without records the 1/Δf an FRF of that line spacing
    /// comes from (0 when neither is known).
    pub(crate) fn record_decay_floor(&self) -> f64 {
        let length = if self.record_s > 0.0 {
            self.record_s
        } else {
            self.line_hz().map_or(0.0, |df| 1.0 / df)
        };
        if length > 0.0 && length.is_finite() {
            RECORD_DECAY_FLOOR / length
        } else {
            0.0
        }
    }

    /// The spacing of the band's lines, Hz (`None` under two bins).
    pub(crate) fn line_hz(&self) -> Option<f64> {
        match self.bins {
            [first, .., last] => Some((last.0 - first.0) / (self.bins.len() - 1) as f64),
            _ => None,
        }
    }

    /// The truncation weight at bin `k` (zero without records).
    pub(crate) fn weight(&self, k: usize) -> Complex64 {
        self.truncation
            .and_then(|w| w.get(k).copied())
            .unwrap_or(Complex64::new(0.0, 0.0))
    }

    /// Real columns per pole in the linear fit: R, and D with records.
    pub(crate) fn per_pole(&self) -> usize {
        if self.truncation.is_some() {
            4
        } else {
            2
        }
    }

    /// Pole `j`'s part of the model at bin `k`: its modal term and its
    /// cut-off decay.
    fn contribution(&self, k: usize, j: usize, p: Complex64, fitted: &Residues) -> Complex64 {
        let f = self.bins[k].0;
        let mut c = self.basis.pair(f, p, fitted.residues[j]);
        if let Some(d) = fitted.truncation.get(j) {
            c += self.weight(k) * self.basis.cutoff().pair(f, p, *d);
        }
        c
    }
}

/// The weighted sum of squares of the misfit of `poles` over the band,
/// their residues fitted.
pub fn misfit(band: Band<'_>, poles: &[Complex64]) -> f64 {
    project(band, poles)
        .residual
        .iter()
        .map(|r| r.norm_sqr())
        .sum()
}

/// The fitted model: residues and residual terms U, L of given poles.
#[derive(Debug, Clone, PartialEq)]
pub struct Residues {
    pub residues: Vec<Complex64>,
    /// The coefficients D of the cut-off decays, per pole (empty without
    /// records).
    pub truncation: Vec<Complex64>,
    pub upper: f64,
    pub lower: f64,
    /// (power of iω, coefficient) of the band's other residual terms
    /// ([`Band::powers`]).
    pub powers: Vec<(i32, f64)>,
}

/// Powers of iω of the residual terms beside U and L/(iω)²: the modes
/// outside the band enter a receptance as U + L/(iω)², a mobility as
/// iω·U + L/(iω), an accelerance as (iω)²·U + L. All five are fitted,
/// whatever the response quantity (a mobility fitted with U alone left a
/// 3817 Hz mode 4e-4 off in f).
pub const RESIDUAL_POWERS: [i32; 3] = [1, 2, -1];

/// The residual terms of the last refinement of the chosen poles
/// ([`super::fit`]): the next terms of the modes above the band, (iω)³
/// and (iω)⁴ (U₂ as it enters a mobility or an accelerance; (iω)² is a
/// receptance's). Strong, heavily damped modes just above the band bend
/// it more than U alone can follow: on a steel portal frame's record
/// (modes of ζ 7–8 % at 1.36–1.65 × the band's top) a weak mode beside a
/// strong one came out 7e-3 off in f and −15 % in ζ with the three terms,
/// 2e-3 and +3 % with these. They are not used to choose the poles: their
/// freedom at the band's top let an undamped record's weak harmonic run
/// away in the refinement.
pub const POLISH_POWERS: [i32; 5] = [1, 2, -1, 3, 4];

/// The modal model with residual terms at `f` Hz: the FRF of the structure
/// (an endless record), without the cut-off decays.
pub fn model_at(basis: PoleBasis, f: f64, poles: &[Complex64], fitted: &Residues) -> Complex64 {
    let iw = 2.0 * PI * f;
    let mut m = Complex64::new(fitted.upper, 0.0);
    if f != 0.0 {
        m -= fitted.lower / (iw * iw);
        let jw = Complex64::new(0.0, iw);
        for (n, c) in &fitted.powers {
            m += c * jw.powi(*n);
        }
    }
    for (p, r) in poles.iter().zip(&fitted.residues) {
        m += basis.pair(f, *p, *r);
    }
    m
}

/// Residues R_r and residual terms U, L of `poles` by linear least squares
/// (LSFD).
pub fn residues(band: Band<'_>, poles: &[Complex64]) -> Residues {
    project(band, poles).fitted
}

/// Standard error of each pole's real part −σ = −ζω: the linearised
/// least-squares covariance (JᵀJ)⁻¹ over all unknowns (poles, residues,
/// U, L), with each pole's noise variance the mean |H − Ĥ|²/2 per real
/// number over ±[`NOISE_WINDOW_BINS`] bins of it, times the residual's
/// correlation length ℓ in bins ([`super::residual_search`]: noise spread
/// over ℓ bins by a window tells ℓ times less), at most the pole's
/// half-power bandwidth 2ζf/Δf in bins (noise smoother than the peak is a
/// background to it).
pub fn decay_standard_errors(band: Band<'_>, poles: &[Complex64]) -> Vec<f64> {
    let Projection {
        fitted,
        residual: r,
        ..
    } = project(band, poles);
    let jp = pole_jacobian(band, poles, &fitted);
    let a = design(band, poles);
    // The linear unknowns in play: a pole without a cut-off term has zero
    // columns for it.
    let live: Vec<usize> = (0..a.ncols())
        .filter(|&c| a.column(c).norm() > 0.0)
        .collect();
    let (rows, np, na) = (jp.nrows(), jp.ncols(), live.len());
    let mut j = DMatrix::<f64>::zeros(rows, np + na);
    j.view_mut((0, 0), (rows, np)).copy_from(&jp);
    for (c, &col) in live.iter().enumerate() {
        j.set_column(np + c, &a.column(col));
    }
    let norms: Vec<f64> = (0..np + na)
        .map(|c| j.column(c).norm().max(f64::MIN_POSITIVE))
        .collect();
    for (c, nc) in norms.iter().enumerate() {
        j.column_mut(c).scale_mut(1.0 / nc);
    }
    let Some(cov) = (j.transpose() * &j).try_inverse() else {
        return vec![f64::INFINITY; poles.len()];
    };
    let r2: Vec<f64> = r.iter().map(|v| v.norm_sqr()).collect();
    // Noise correlated over ℓ bins carries 1/ℓ of the information of
    // independent noise: the variance of the estimate grows by ℓ.
    let ell = super::residual_search::correlation_length(&r);
    let n = band.bins.len();
    let df = match (band.bins.first(), band.bins.last()) {
        (Some(a), Some(b)) if n > 1 => (b.0 - a.0) / (n - 1) as f64,
        _ => 1.0,
    };
    poles
        .iter()
        .enumerate()
        .map(|(q, p)| {
            let fd = p.im / (2.0 * PI);
            let k = band
                .bins
                .iter()
                .position(|(f, _)| *f >= fd)
                .unwrap_or(n.saturating_sub(1));
            let (lo, hi) = (
                k.saturating_sub(NOISE_WINDOW_BINS),
                (k + NOISE_WINDOW_BINS + 1).min(n),
            );
            // Noise correlated over more bins than the pole's half-power
            // band is smooth across it: a background, not a change of
            // shape. The inflation stops at the band's width in bins.
            let width = (-p.re / PI / df).max(1.0);
            let var =
                ell.min(width) * r2[lo..hi].iter().sum::<f64>() / (2 * (hi - lo).max(1)) as f64;
            (var * cov[(2 * q, 2 * q)]).sqrt() / norms[2 * q]
        })
        .collect()
}

/// The bins of `band` within `f0` ± `half` Hz.
pub(crate) fn bins_near(
    bins: &[(f64, Complex64)],
    f0: f64,
    half: f64,
) -> impl Iterator<Item = usize> + '_ {
    bins.iter()
        .enumerate()
        .filter(move |(_, (f, _))| (f - f0).abs() <= half)
        .map(|(k, _)| k)
}

/// Largest ratio of the polished misfit to the chosen one for which the
/// polish is taken: the extra terms must explain most of what was left
/// (the portal frame's record: 0.04; a tuning fork's 0.5 s record: 0.29).
/// Where they explain little (0.96 on the paper's own record, 1.0 on a
/// close pair beside a mode) they would only trade the record's own errors
/// (the integrator's) between the poles: on `impulse` records of
/// cantilevers the median ζ error grew from 9.1e-4 to 1.5e-3.
pub const POLISH_GAIN: f64 = 0.5;

/// The last refinement of the chosen `poles` with the residual terms of
/// [`POLISH_POWERS`]. It is taken when it leaves under [`POLISH_GAIN`] of
/// the misfit, and every pole stays physical in the band and within its
/// own half-power band (|Re s|, at least two lines) of where it was;
/// otherwise the poles stay as they were chosen. Returns
/// the band of the poles returned and the poles.
pub fn polish<'a>(
    band: Band<'a>,
    poles: Vec<Complex64>,
    settings: &FitSettings,
) -> (Band<'a>, Vec<Complex64>) {
    let extended = Band {
        powers: &POLISH_POWERS,
        ..band
    };
    let Some(line) = band.line_hz().map(|df| 2.0 * PI * df) else {
        return (band, poles);
    };
    let mut polished = poles.clone();
    refine(extended, &mut polished);
    let kept = misfit(extended, &polished) < POLISH_GAIN * misfit(band, &poles)
        && polished.iter().zip(&poles).all(|(p, q)| {
            unphysical(*p, settings).is_none() && (p - q).norm() <= q.re.abs().max(2.0 * line)
        });
    if kept {
        (extended, polished)
    } else {
        (band, poles)
    }
}

/// Why the refined pole `p` (of the windowed FRF) is not physical in the
/// band, if it is not.
pub(crate) fn unphysical(p: Complex64, settings: &FitSettings) -> Option<RejectReason> {
    // The pole of the structure: the window's decay added back.
    let p = p + settings.window_decay_rate;
    let w = p.norm();
    let zeta = -p.re / w;
    if !(p.im > 0.0 && zeta > 0.0 && zeta < MAX_DAMPING && w.is_finite()) {
        return Some(RejectReason::FailedRefinement);
    }
    let f = w / (2.0 * PI);
    (f < settings.f_lo || f > settings.f_hi).then_some(RejectReason::LeftBand)
}

/// Puts on the stability boundary each refined pole whose decay rate came
/// out negative but within [`DECAY_RESOLUTION`] standard errors of zero: a
/// mode that rings through the record with no decay it can measure (a
/// near-undamped structure; the cut-off record's own error then tips the
/// fitted decay either way), and that stands above the noise as a
/// ringing mode does ([`RINGING_SIGNIFICANCE`]). Rejected as unstable,
/// such modes were lost: six of seven on the re-check's cantilever with
/// α = 0.01 1/s. Their damping is then reported as the bound the record
/// allows ([`unresolved_decay_bounds`]), or as the decay a later
/// refinement finds.
fn settle_undamped(band: Band<'_>, poles: &mut [Complex64], settings: &FitSettings) {
    // Under an exponential window the record decays at the window's rate
    // whatever the structure does: a pole decaying slower than the window
    // is a misfit there, not a mode ringing through the record (settled,
    // the combination tones of the paper's undamped record stayed in the
    // model and a weaker artifact of its integrator, gone at half the
    // step, came out as a mode).
    if settings.window_decay_rate != 0.0 {
        return;
    }
    let growing = |p: &Complex64| p.im > 0.0 && p.norm().is_finite() && p.re >= 0.0;
    if !poles.iter().any(growing) {
        return;
    }
    let se = decay_standard_errors(band, poles);
    let sig = significance(band, poles);
    for ((p, se), sig) in poles.iter_mut().zip(se).zip(sig) {
        if growing(p) && p.re < DECAY_RESOLUTION * se && sig >= RINGING_SIGNIFICANCE {
            p.re = -f64::EPSILON * p.im;
        }
    }
}

/// Significance of each pole (module doc), divided by
/// √(max(1, min(ℓ, w)/4)) for a pole w bins wide when the residual is
/// correlated over ℓ bins ([`super::residual_search::correlation_length`]):
/// such noise bends H over the pole's band as a pole would.
pub fn significance(band: Band<'_>, poles: &[Complex64]) -> Vec<f64> {
    let Projection {
        fitted,
        residual: resid,
        ..
    } = project(band, poles);
    let df = match (band.bins.first(), band.bins.last()) {
        (Some(a), Some(b)) if band.bins.len() > 1 => (b.0 - a.0) / (band.bins.len() - 1) as f64,
        _ => 0.0,
    };
    let ell = super::residual_search::correlation_length(&resid);
    poles
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let fd = p.im / (2.0 * PI);
            let half = (-p.re / (2.0 * PI)).max(MIN_HALF_POWER_BINS * df);
            let (mut c2, mut e2, mut m) = (0.0, 0.0, 0usize);
            for k in bins_near(band.bins, fd, half) {
                c2 += (band.row(k) * band.contribution(k, j, *p, &fitted)).norm_sqr();
                e2 += resid[k].norm_sqr();
                m += 1;
            }
            // The noise around the pole as well: the median residual power
            // over ±NOISE_WINDOW_BINS (/ln 2), where a pole fitted to a
            // bend of correlated noise left the rest of that bend.
            let centre = band.bins.iter().position(|(f, _)| *f >= fd).unwrap_or(0);
            let (lo, hi) = (
                centre.saturating_sub(4 * NOISE_WINDOW_BINS),
                (centre + 4 * NOISE_WINDOW_BINS + 1).min(resid.len()),
            );
            let around: Vec<f64> = resid[lo..hi].iter().map(|v| v.norm_sqr()).collect();
            let floor = if around.is_empty() {
                0.0
            } else {
                super::residual_search::upper_median(&around) / std::f64::consts::LN_2
            };
            e2 = e2.max(floor * m as f64);
            // Noise correlated over ℓ bins bends H over the pole's band
            // as a pole would: a pole as wide as that bend must stand
            // √(min(ℓ, width)/4) times higher (width in bins).
            let width = 2.0 * half / df.max(f64::MIN_POSITIVE);
            let bend = (ell.min(width) / 4.0).max(1.0).sqrt();
            if e2 > 0.0 {
                (c2 / e2).sqrt() / bend
            } else if c2 > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        })
        .collect()
}

/// Half-width, in bins, of the window whose mean residual is a pole's
/// noise variance in [`decay_standard_errors`].
pub const NOISE_WINDOW_BINS: usize = 32;

/// Fewest standard errors by which a reported pole's decay rate in the
/// record, σ = ζω plus the window's decay, must stand above zero
/// ([`decay_standard_errors`]): the record shows a decaying response, and
/// an undamped structure under an exponential window is still a mode; a pole whose damping
/// the record does not resolve, such as one fitted to a single noisy bin
/// (a sinusoid of a whole number of periods in the record holds one bin
/// whatever its decay), is not a mode the record shows.
pub const DECAY_RESOLUTION: f64 = 3.0;

/// Significance ([`significance`]) from which a pole whose damping the
/// record does not resolve is a mode all the same: a mode still ringing at
/// the records' end (undamped, or decaying too slowly for their length)
/// shows no decay, yet stands out of the residual by orders (the paper's
/// undamped blade, 0.1 s at 51.2 kHz: 7418 and 148), where a pole fitted to
/// a noisy bin stands near [`SIGNIFICANCE`]. It is reported with its
/// damping's upper bound instead of a value ([`unresolved_decay_bounds`]).
pub const RINGING_SIGNIFICANCE: f64 = 20.0;

/// The level of χ² with four degrees of freedom (a pole and its residue)
/// that noise passes with probability about 1e-6: e^(−x/2)(1 + x/2) at
/// x = 33 is 1.2e-6.
pub const REDUNDANT_CHI2: f64 = 33.0;

/// A pole of a close pair that the fit does not need: of two poles within
/// one half-power band max(ζf, 2Δf) of each other, the one whose removal
/// (the rest refined again) raises the weighted misfit least, when that
/// rise is under [`REDUNDANT_CHI2`] times the noise variance per real
/// number (the mean |r|²/2 over ±[`NOISE_WINDOW_BINS`] bins of the pair,
/// times the residual's correlation length, at most the pair's half-power
/// band in bins): noise that bends one peak is fitted by two poles that
/// share it, and the second is not a mode. Two poles closer than one bin Δf
/// are never both kept: the record cannot tell them apart.
fn redundant(band: Band<'_>, poles: &[Complex64]) -> Option<usize> {
    let n = band.bins.len();
    if poles.len() < 2 || n < 2 {
        return None;
    }
    let df = (band.bins[n - 1].0 - band.bins[0].0) / (n - 1) as f64;
    let half = |p: &Complex64| (-p.re / (2.0 * PI)).max(MIN_HALF_POWER_BINS * df);
    let fd = |p: &Complex64| p.im / (2.0 * PI);
    let misfit = |ps: &[Complex64]| -> (f64, Vec<Complex64>) {
        let r = project(band, ps).residual;
        (r.iter().map(|v| v.norm_sqr()).sum(), r)
    };
    let (all, r) = misfit(poles);
    let ell = super::residual_search::correlation_length(&r);
    let mut best: Option<(f64, usize)> = None;
    for i in 0..poles.len() {
        for j in i + 1..poles.len() {
            let width = half(&poles[i]).max(half(&poles[j]));
            if (fd(&poles[i]) - fd(&poles[j])).abs() > width {
                continue;
            }
            let centre = 0.5 * (fd(&poles[i]) + fd(&poles[j]));
            let k = band
                .bins
                .iter()
                .position(|(f, _)| *f >= centre)
                .unwrap_or(n - 1);
            let (lo, hi) = (
                k.saturating_sub(NOISE_WINDOW_BINS),
                (k + NOISE_WINDOW_BINS + 1).min(n),
            );
            let var = r[lo..hi].iter().map(|v| v.norm_sqr()).sum::<f64>() / (2 * (hi - lo)) as f64
                * ell.min((2.0 * width / df).max(1.0));
            // Closer than one bin, two poles are not told apart by the
            // record whatever the misfit says.
            let level = if (fd(&poles[i]) - fd(&poles[j])).abs() < df {
                f64::INFINITY
            } else {
                REDUNDANT_CHI2
            };
            for drop in [i, j] {
                let mut rest: Vec<Complex64> = poles.to_vec();
                rest.remove(drop);
                refine(band, &mut rest);
                let rise = (misfit(&rest).0 - all) / var.max(f64::MIN_POSITIVE);
                if rise < level && best.is_none_or(|(b, _)| rise < b) {
                    best = Some((rise, drop));
                }
            }
        }
    }
    best.map(|(_, i)| i)
}

/// Whether pole `i` of `poles`, as they stand, is a mode beyond doubt:
/// significant ([`SIGNIFICANCE`]) with its decay resolved
/// ([`DECAY_RESOLUTION`] standard errors, and the record's floor
/// [`RECORD_DECAY_FLOOR`]). Stricter than [`select`], which also keeps a
/// ringing mode: a pole admitted without the whole band's refinement
/// (`zoom::admit`) has only this test to pass.
pub fn admissible(band: Band<'_>, poles: &[Complex64], i: usize) -> bool {
    let sig = significance(band, poles)[i];
    let se = decay_standard_errors(band, poles)[i];
    let sigma = -poles[i].re;
    sig >= SIGNIFICANCE && sigma >= DECAY_RESOLUTION * se && sigma >= band.record_decay_floor()
}

/// The pole whose damping the record resolves least, among those under
/// [`DECAY_RESOLUTION`] that do not ring ([`RINGING_SIGNIFICANCE`]).
fn least_resolved(band: Band<'_>, poles: &[Complex64]) -> Option<usize> {
    let unresolved: Vec<(usize, f64)> = decay_standard_errors(band, poles)
        .into_iter()
        .zip(poles)
        .map(|(se, p)| -p.re / se)
        .enumerate()
        .filter(|(_, t)| t.is_nan() || *t < DECAY_RESOLUTION)
        .collect();
    if unresolved.is_empty() {
        return None;
    }
    let sig = significance(band, poles);
    unresolved
        .into_iter()
        .filter(|&(i, t)| t.is_nan() || sig[i].is_nan() || sig[i] < RINGING_SIGNIFICANCE)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}

/// The upper bound of each pole's decay rate the record allows, σ + 3
/// standard errors [1/s], where the record does not resolve it (under
/// [`DECAY_RESOLUTION`] standard errors); `None` where it does.
///
/// Nor is a decay the record hardly shows, σT under [`RECORD_DECAY_FLOOR`]
/// over its length T, whatever its standard error says: there the misfit
/// of the record's own making (its integrator, its sampling, the leakage of
/// its end) is no noise, and it sets the fitted σ (the trial's clamped beam
/// with α = 0.01 1/s, 0.2 s: ζ 2e-6 fitted at 3761 Hz, 2.1e-7 true; at
/// 116 Hz over 0.5 s, a bound of 4.1e-6 against 6.8e-6 true). The bound
/// is then at least that floor's σ. Under an exponential window of decay
/// rate `window_decay` [1/s] the floor applies to the structure's own
/// decay, σ less the window's.
pub fn unresolved_decay_bounds(
    band: Band<'_>,
    poles: &[Complex64],
    window_decay: f64,
) -> Vec<Option<f64>> {
    let floor = band.record_decay_floor();
    decay_standard_errors(band, poles)
        .into_iter()
        .zip(poles)
        .map(|(se, p)| {
            let bound = -p.re + DECAY_RESOLUTION * se;
            (-p.re < DECAY_RESOLUTION * se || -p.re - window_decay < floor)
                .then(|| bound.max(floor + window_decay))
        })
        .collect()
}

/// The smallest decay over the record's length T, σT, that a fit reports
/// as a value ([`unresolved_decay_bounds`]): the response falls by 5 % over
/// the record. A mode decaying less rings through it, and its damping is
/// given as a bound.
pub const RECORD_DECAY_FLOOR: f64 = 0.05;

/// A pole the choice left out, where it is shown, and why.
pub type Rejection = (Complex64, RejectReason);

/// The modes among the stable seeds (module doc): refined together; a pole
/// the refinement makes unphysical or moves out of the band is rejected,
/// then the least significant pole while it is under [`SIGNIFICANCE`], one
/// at a time, the rest refined again from their seeds after each
/// rejection. Returns the refined modes and the rejected poles.
pub fn select(
    band: Band<'_>,
    seeds: &[Complex64],
    settings: &FitSettings,
) -> (Vec<Complex64>, Vec<Rejection>) {
    let mut seeds = seeds.to_vec();
    let mut rejected = Vec::new();
    while !seeds.is_empty() {
        let mut poles = seeds.clone();
        refine(band, &mut poles);
        settle_undamped(band, &mut poles, settings);
        let bad = poles
            .iter()
            .enumerate()
            .find_map(|(i, p)| unphysical(*p, settings).map(|why| (i, why)));
        if let Some((i, why)) = bad {
            let shown = if why == RejectReason::FailedRefinement {
                seeds[i]
            } else {
                poles[i]
            };
            rejected.push((shown, why));
            seeds.remove(i);
            continue;
        }
        if let Some(i) = least_resolved(band, &poles) {
            rejected.push((poles[i], RejectReason::UnresolvedDamping));
            seeds.remove(i);
            continue;
        }
        if let Some(i) = redundant(band, &poles) {
            rejected.push((poles[i], RejectReason::Redundant));
            seeds.remove(i);
            continue;
        }
        let weakest = significance(band, &poles)
            .into_iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1));
        match weakest {
            Some((i, s)) if s < SIGNIFICANCE => {
                rejected.push((poles[i], RejectReason::NotSignificant));
                seeds.remove(i);
            }
            _ => return (poles, rejected),
        }
    }
    (Vec::new(), rejected)
}
