//! Modal parameters from an FRF: the least-squares complex-frequency method
//! (LSCF, Guillaume et al. 2003; the single-reference core of PolyMAX) with a
//! stabilization diagram, then residues by least squares (LSFD).
//!
//! **Why LSCF.** Half-power bandwidths read damping from the width of a
//! single peak: they fail when two modes' half-power bands overlap and when
//! the resolution Δf is not small against 2ζf (0.1 % damping). A
//! common-denominator rational fraction fitted over a band models every
//! mode in it at once, overlapping or not, and its z-domain basis keeps the
//! normal equations well conditioned at the high orders a stabilization
//! diagram needs (a power-of-iω basis does not).
//!
//! **Model.** With Ω_k = e^(−iω_kΔt), Δt = 1/(2 f_hi) over the band
//! [f_lo, f_hi], H(ω_k) ≈ B(Ω_k)/A(Ω_k), A and B real polynomials of degree
//! n. The linearised error W(B − H A) is minimised in least squares; with
//! B eliminated, the normal equations of the denominator are
//! M = 2 (T − Sᵀ R⁻¹ S), where R = Re Σ XᴴX, S = Re Σ XᴴY, T = Re Σ YᴴY,
//! X_k = [Ω_k^j], Y_k = −H_k X_k. The three are Toeplitz (entry (i, j)
//! depends on j − i only), so all orders come from one pass over the data,
//! and the order-n system is the leading (n+1) block. Fixing a_n = 1 gives
//! a; the roots z_r of A give the poles s_r = −ln(z_r)/Δt, f_r = |s_r|/2π,
//! ζ_r = −Re s_r/|s_r|.
//!
//! **Stabilization.** Poles of orders 2, 4, …, n_max are compared with the
//! previous order's: a pole is *stable* when one there lies within 0.5 % in
//! frequency and 5 % in damping. The seeds of the modes are the poles with
//! positive damping below 30 % in the band, stable against the previous
//! order (0.5 % in f, 20 % in ζ), grouped within ±0.25 % in frequency and
//! found in at least a third of the orders; each seed is its group's median.
//!
//! **Refinement.** The seeds are refined together by nonlinear least squares
//! on the modal model
//! H(ω) = Σ_r [R_r/(iω − s_r) + R̄_r/(iω − s̄_r)] + U + L/(iω)², its
//! residues and residual terms (U, L: the modes outside the band) by linear
//! least squares (LSFD) at every step.
//!
//! **A reported pole is a physical pole of the record.** After each
//! refinement, one pole at a time is rejected and the rest refined again
//! from their seeds:
//! 1. a pole the refinement made unstable, overdamped (ζ ≥ 1) or moved off
//!    the positive frequencies (`failed_refinement`, shown at its seed);
//! 2. a pole the refinement moved out of the band [f_lo, f_hi]
//!    (`left_band`, shown where it went);
//! 3. the least significant pole while its significance is under
//!    [`SIGNIFICANCE`] = 2 (`not_significant`).
//!
//! The *significance* of a pole is a test against the noise estimated from
//! the data itself: the RMS of its modal contribution
//! R/(iω − s) + R̄/(iω − s̄) over its half-power band (the bins within
//! f_d ± max(ζf, 2Δf), f_d = Im s/2π) divided by the RMS of the fit
//! residual H − Ĥ over the same bins. The residual holds what the modal
//! model cannot explain there: measurement noise, leakage, a spurious
//! pole's misfit. A mode whose peak stands k times above the noise has a
//! significance of about 0.86 k (its contribution falls from the peak to
//! 1/√2 of it across the half-power band), so a mode 3 × above the noise
//! passes; a pole that fits noise alone explains only the few degrees of
//! freedom it has (a complex pole and residue) of the 2m numbers in its m
//! bins and stays near or under 1. No ratio to the largest peak enters: a
//! weak mode of noise-free data is reported.
//!
//! **No silent loss.** Every seed that does not become a mode is kept in
//! [`ModalFit::rejected`] with its reason. (Modes outside the band are
//! found by `measured::analysis::analyse`, which fits the rest of the
//! spectrum too.)
//!
//! **Exponential window.** Its decay σ_w (see [`super::window::Window::decay_rate`]) is added
//! back to every pole, Re s_r += σ_w, before f and ζ are computed.

use nalgebra::{DMatrix, DVector};
use realfft::num_complex::Complex64;

use super::lm;

/// Settings of [`fit`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitSettings {
    /// Band, Hz.
    pub f_lo: f64,
    pub f_hi: f64,
    /// Highest model order (even), the number of poles of the last fit.
    pub max_order: usize,
    /// Decay rate to remove from the poles, 1/s (exponential window).
    pub window_decay_rate: f64,
}

/// A stability label of the diagram.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Stability {
    /// No pole of the previous order close by.
    New,
    /// Frequency within 0.5 %, damping not within 5 %.
    Frequency,
    /// Frequency and damping stable.
    Stable,
}

/// One pole of one order in the diagram.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct DiagramPole {
    /// Model order of the fit that found it [–].
    pub order: usize,
    /// Undamped natural frequency [Hz].
    pub frequency_hz: f64,
    /// Damping ratio ζ [–].
    pub damping_ratio: f64,
    pub stability: Stability,
}

/// An identified mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedMode {
    /// Undamped natural frequency |s|/2π, Hz.
    pub frequency_hz: f64,
    pub damping_ratio: f64,
    /// The pole s (after the window correction), 1/s.
    pub pole: Complex64,
    /// Residue R of the pole in the measured (windowed) FRF, FRF unit × 1/s.
    pub residue: Complex64,
    /// |H| of the fitted model at the damped frequency.
    pub magnitude: f64,
}

/// Why a pole stable over the orders is not among the modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RejectReason {
    /// Stable in a fit of the spectrum outside the band.
    OutsideBand,
    /// The nonlinear refinement moved it out of the fit band.
    LeftBand,
    /// Its modal contribution over its half-power band is under
    /// [`SIGNIFICANCE`] times the fit residual there: not told apart from
    /// the noise.
    NotSignificant,
    /// The nonlinear refinement made it unstable or overdamped (ζ ≥ 1) or
    /// moved it off the positive frequencies.
    FailedRefinement,
}

impl RejectReason {
    /// The reason in words.
    pub fn describe(self) -> &'static str {
        match self {
            RejectReason::OutsideBand => "outside the fit band",
            RejectReason::LeftBand => "the refinement moved it out of the fit band",
            RejectReason::NotSignificant => {
                "its modal contribution in its half-power band is under 2 × the fit residual there"
            }
            RejectReason::FailedRefinement => {
                "the refinement made it unstable or overdamped (ζ ≥ 1)"
            }
        }
    }
}

/// A pole stable over the orders that is not a mode, with its reason.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct RejectedPole {
    /// Undamped natural frequency, Hz (window-corrected).
    pub frequency_hz: f64,
    pub damping_ratio: f64,
    pub reason: RejectReason,
}

/// Result of [`fit`].
#[derive(Debug, Clone, PartialEq)]
pub struct ModalFit {
    pub modes: Vec<FittedMode>,
    /// Stable poles that are not modes (module doc).
    pub rejected: Vec<RejectedPole>,
    pub diagram: Vec<DiagramPole>,
    /// Residual terms U (FRF unit) and L (FRF unit × 1/s²).
    pub upper_residual: f64,
    pub lower_residual: f64,
    pub settings: FitSettings,
}

impl ModalFit {
    /// The fitted FRF at `f_hz` (modes and residual terms), as measured:
    /// with the window's decay on the poles.
    pub fn evaluate(&self, f_hz: f64) -> Complex64 {
        let iw = Complex64::new(0.0, 2.0 * std::f64::consts::PI * f_hz);
        let mut h = Complex64::new(self.upper_residual, 0.0);
        if iw.im != 0.0 {
            h += self.lower_residual / (iw * iw);
        }
        for m in &self.modes {
            let p = m.pole - self.settings.window_decay_rate;
            h += m.residue / (iw - p) + m.residue.conj() / (iw - p.conj());
        }
        h
    }
}

/// Frequency tolerance of the stability checks (relative).
pub const STABLE_FREQUENCY: f64 = 0.005;
/// Damping tolerance of the stability label (relative).
pub const STABLE_DAMPING: f64 = 0.05;
/// Damping tolerance (relative) of the poles that seed a mode: LSCF's
/// damping wanders with noise more than its frequency, and the refinement
/// settles it.
pub const CLUSTER_DAMPING: f64 = 0.2;
/// Largest damping ratio taken as physical.
pub const MAX_DAMPING: f64 = 0.3;
/// Smallest significance of a reported mode: the RMS of its modal
/// contribution over its half-power band, in units of the RMS fit residual
/// there (module doc).
pub const SIGNIFICANCE: f64 = 2.0;
/// Smallest half-width of the half-power band of the significance test, in
/// bins: a lightly damped mode's band ±ζf may hold no bin.
pub const MIN_HALF_POWER_BINS: f64 = 2.0;

/// Poles (f Hz, ζ, s) of one LSCF order from the Toeplitz lag sums.
fn poles_of_order(
    n: usize,
    r: &DMatrix<f64>,
    s: &DMatrix<f64>,
    t: &DMatrix<f64>,
    dt: f64,
    settings: &FitSettings,
) -> Vec<(f64, f64, Complex64)> {
    let m = n + 1;
    let rr = r.view((0, 0), (m, m)).into_owned();
    let ss = s.view((0, 0), (m, m)).into_owned();
    let tt = t.view((0, 0), (m, m)).into_owned();
    let Some(rinv_s) = rr.cholesky().map(|c| c.solve(&ss)) else {
        return Vec::new();
    };
    let mm = tt - ss.transpose() * rinv_s;
    let a00 = mm.view((0, 0), (n, n)).into_owned();
    let rhs = -mm.view((0, n), (n, 1)).into_owned();
    let Some(a) = a00.lu().solve(&rhs) else {
        return Vec::new();
    };
    // Companion matrix of z^n + a_{n-1} z^{n-1} + … + a_0.
    let mut c = DMatrix::<f64>::zeros(n, n);
    for i in 0..n - 1 {
        c[(i, i + 1)] = 1.0;
    }
    for j in 0..n {
        c[(n - 1, j)] = -a[j];
    }
    c.complex_eigenvalues()
        .iter()
        .filter_map(|z| {
            let z = Complex64::new(z.re, z.im);
            if z.norm() == 0.0 {
                return None;
            }
            let sp = -z.ln() / dt;
            let w = sp.norm();
            let f = w / (2.0 * std::f64::consts::PI);
            let zeta = -sp.re / w;
            (sp.im > 0.0
                && zeta > 0.0
                && zeta < MAX_DAMPING
                && f >= settings.f_lo
                && f <= settings.f_hi)
                .then_some((f, zeta, sp))
        })
        .collect()
}

fn close(a: (f64, f64), b: (f64, f64), zeta_tol: f64) -> (bool, bool) {
    let df = (a.0 - b.0).abs() / a.0;
    let dz = (a.1 - b.1).abs() / a.1;
    (df < STABLE_FREQUENCY, dz < zeta_tol)
}

/// Fits the FRF `h` at `frequency_hz` over the settings' band (non-finite
/// bins are skipped). Returns no modes when the band holds fewer than four
/// usable bins.
pub fn fit(frequency_hz: &[f64], h: &[Complex64], settings: &FitSettings) -> ModalFit {
    let band: Vec<(f64, Complex64)> = frequency_hz
        .iter()
        .zip(h)
        .filter(|(f, h)| {
            **f >= settings.f_lo && **f <= settings.f_hi && h.re.is_finite() && h.im.is_finite()
        })
        .map(|(f, h)| (*f, *h))
        .collect();
    let mut result = ModalFit {
        modes: Vec::new(),
        rejected: Vec::new(),
        diagram: Vec::new(),
        upper_residual: 0.0,
        lower_residual: 0.0,
        settings: *settings,
    };
    let n_max = (settings.max_order.max(2) / 2 * 2).min(2 * (band.len() / 2).saturating_sub(1));
    if band.len() < 4 || n_max < 2 {
        return result;
    }
    let scale = band.iter().map(|(_, h)| h.norm()).fold(0.0, f64::max);
    if scale == 0.0 {
        return result;
    }
    let dt = 0.5 / settings.f_hi;
    // Lag sums Σ Ω^l, Σ H Ω^l, Σ |H|² Ω^l for l = 0..=n_max (Ω^(−l) is the
    // conjugate for the real parts taken below).
    let mut p0 = vec![Complex64::new(0.0, 0.0); n_max + 1];
    let mut p1 = vec![Complex64::new(0.0, 0.0); 2 * n_max + 1];
    let mut p2 = vec![Complex64::new(0.0, 0.0); n_max + 1];
    for (f, hk) in &band {
        let hk = hk / scale;
        let omega = Complex64::from_polar(1.0, -2.0 * std::f64::consts::PI * f * dt);
        let mut pw = Complex64::new(1.0, 0.0);
        let mut pw_inv = Complex64::new(1.0, 0.0);
        for l in 0..=n_max {
            p0[l] += pw;
            p2[l] += hk.norm_sqr() * pw;
            p1[n_max + l] += hk * pw;
            if l > 0 {
                p1[n_max - l] += hk * pw_inv;
            }
            pw *= omega;
            pw_inv *= omega.conj();
        }
    }
    let m = n_max + 1;
    // R_ij = Re Σ Ω^(j−i); S_ij = −Re Σ H Ω^(j−i); T_ij = Re Σ |H|² Ω^(j−i).
    let lag = |v: &[Complex64], i: usize, j: usize| -> f64 {
        if j >= i {
            v[j - i].re
        } else {
            v[i - j].re
        }
    };
    let r = DMatrix::from_fn(m, m, |i, j| lag(&p0, i, j));
    let t = DMatrix::from_fn(m, m, |i, j| lag(&p2, i, j));
    let s = DMatrix::from_fn(m, m, |i, j| {
        -p1[(n_max as isize + j as isize - i as isize) as usize].re
    });
    let orders: Vec<usize> = (2..=n_max).step_by(2).collect();
    let all: Vec<Vec<(f64, f64, Complex64)>> = orders
        .iter()
        .map(|&n| poles_of_order(n, &r, &s, &t, dt, settings))
        .collect();
    for (k, poles) in all.iter().enumerate() {
        for &(f, z, _) in poles {
            let stability = if k == 0 {
                Stability::New
            } else {
                let best = all[k - 1]
                    .iter()
                    .map(|&(f2, z2, _)| close((f, z), (f2, z2), STABLE_DAMPING))
                    .max_by_key(|(a, b)| (*a as u8) * 2 + *b as u8);
                match best {
                    Some((true, true)) => Stability::Stable,
                    Some((true, false)) => Stability::Frequency,
                    _ => Stability::New,
                }
            };
            result.diagram.push(DiagramPole {
                order: orders[k],
                frequency_hz: f,
                damping_ratio: z,
                stability,
            });
        }
    }
    let sigma_w = settings.window_decay_rate;
    let physical = |sp: Complex64| {
        let sp = sp + sigma_w;
        (sp.norm() / (2.0 * std::f64::consts::PI), -sp.re / sp.norm())
    };
    for d in result.diagram.iter_mut() {
        let w = 2.0 * std::f64::consts::PI * d.frequency_hz;
        let (f, z) = physical(Complex64::new(
            -d.damping_ratio * w,
            w * (1.0 - d.damping_ratio.powi(2)).sqrt(),
        ));
        d.frequency_hz = f;
        d.damping_ratio = z;
    }
    let needed = all.len().div_ceil(3).max(2).min(all.len());
    let seeds = clusters(&all, needed);
    let (kept, rejected) = select(&band, &seeds, settings);
    result.rejected = rejected
        .into_iter()
        .map(|(p, reason)| {
            let (frequency_hz, damping_ratio) = physical(p);
            RejectedPole {
                frequency_hz,
                damping_ratio,
                reason,
            }
        })
        .collect();
    let (res, u, l) = residues(&band, &kept);
    result.upper_residual = u;
    result.lower_residual = l;
    result.modes = kept
        .iter()
        .zip(&res)
        .map(|(&raw, &residue)| {
            let (frequency_hz, damping_ratio) = physical(raw);
            FittedMode {
                frequency_hz,
                damping_ratio,
                pole: raw + sigma_w,
                residue,
                magnitude: 0.0,
            }
        })
        .collect();
    let magnitudes: Vec<f64> = result
        .modes
        .iter()
        .map(|m| {
            result
                .evaluate(m.pole.im / (2.0 * std::f64::consts::PI))
                .norm()
        })
        .collect();
    for (m, a) in result.modes.iter_mut().zip(magnitudes) {
        m.magnitude = a;
    }
    result
}

/// The bins of `band` within `f0` ± `half` Hz.
fn bins_near(band: &[(f64, Complex64)], f0: f64, half: f64) -> impl Iterator<Item = usize> + '_ {
    band.iter()
        .enumerate()
        .filter(move |(_, (f, _))| (f - f0).abs() <= half)
        .map(|(k, _)| k)
}

/// Why the refined pole `p` (from the stable seed `seed`) is not physical in
/// the band, if it is not.
fn unphysical(p: Complex64, settings: &FitSettings) -> Option<RejectReason> {
    let w = p.norm();
    let zeta = -p.re / w;
    if !(p.im > 0.0 && zeta > 0.0 && zeta < 1.0 && w.is_finite()) {
        return Some(RejectReason::FailedRefinement);
    }
    let f = w / (2.0 * std::f64::consts::PI);
    (f < settings.f_lo || f > settings.f_hi).then_some(RejectReason::LeftBand)
}

/// Significance of each pole: the RMS of its modal contribution
/// R/(iω − s) + R̄/(iω − s̄) over its half-power band (the bins within
/// f_d ± max(ζf, [`MIN_HALF_POWER_BINS`] Δf)) over the RMS of the fit
/// residual H − Ĥ there.
fn significance(band: &[(f64, Complex64)], poles: &[Complex64]) -> Vec<f64> {
    let (res, u, l) = residues(band, poles);
    let resid: Vec<Complex64> = band
        .iter()
        .map(|(f, h)| h - model_at(*f, poles, &res, u, l))
        .collect();
    let df = match (band.first(), band.last()) {
        (Some(a), Some(b)) if band.len() > 1 => (b.0 - a.0) / (band.len() - 1) as f64,
        _ => 0.0,
    };
    poles
        .iter()
        .zip(&res)
        .map(|(p, r)| {
            let fd = p.im / (2.0 * std::f64::consts::PI);
            let half = (-p.re / (2.0 * std::f64::consts::PI)).max(MIN_HALF_POWER_BINS * df);
            let (mut c2, mut e2) = (0.0, 0.0);
            for k in bins_near(band, fd, half) {
                let iw = Complex64::new(0.0, 2.0 * std::f64::consts::PI * band[k].0);
                c2 += (r / (iw - p) + r.conj() / (iw - p.conj())).norm_sqr();
                e2 += resid[k].norm_sqr();
            }
            if e2 > 0.0 {
                (c2 / e2).sqrt()
            } else if c2 > 0.0 {
                f64::INFINITY
            } else {
                0.0
            }
        })
        .collect()
}

/// The modal model with residual terms at `f` Hz.
fn model_at(f: f64, poles: &[Complex64], res: &[Complex64], u: f64, l: f64) -> Complex64 {
    let iw = Complex64::new(0.0, 2.0 * std::f64::consts::PI * f);
    let mut m = Complex64::new(u, 0.0);
    if f != 0.0 {
        m += l / (iw * iw);
    }
    for (p, r) in poles.iter().zip(res) {
        m += r / (iw - p) + r.conj() / (iw - p.conj());
    }
    m
}

/// The modes among the stable seeds (module doc): refined together; a pole
/// the refinement makes unphysical or moves out of the band is rejected,
/// then the least significant pole while it is under [`SIGNIFICANCE`],
/// one at a time, the rest refined again from their seeds after each
/// rejection. Returns the refined modes and the rejected poles (refined,
/// or the seed where the refinement made it unphysical) with their reason.
#[allow(clippy::type_complexity)]
fn select(
    band: &[(f64, Complex64)],
    seeds: &[Complex64],
    settings: &FitSettings,
) -> (Vec<Complex64>, Vec<(Complex64, RejectReason)>) {
    let mut seeds = seeds.to_vec();
    let mut rejected = Vec::new();
    while !seeds.is_empty() {
        let mut poles = seeds.clone();
        refine(band, &mut poles);
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

/// Residues R_r and residual terms U, L by linear least squares (LSFD).
fn residues(band: &[(f64, Complex64)], poles: &[Complex64]) -> (Vec<Complex64>, f64, f64) {
    let cols = 2 * poles.len() + 2;
    let rows = 2 * band.len();
    let mut a = DMatrix::<f64>::zeros(rows, cols);
    let mut b = DVector::<f64>::zeros(rows);
    for (k, (f, h)) in band.iter().enumerate() {
        let iw = Complex64::new(0.0, 2.0 * std::f64::consts::PI * f);
        for (r, p) in poles.iter().enumerate() {
            // R = x + iy: R/(iw−p) + R̄/(iw−p̄) = x·(g1+g2) + y·i(g1−g2).
            let g1 = 1.0 / (iw - p);
            let g2 = 1.0 / (iw - p.conj());
            let cx = g1 + g2;
            let cy = Complex64::new(0.0, 1.0) * (g1 - g2);
            a[(2 * k, 2 * r)] = cx.re;
            a[(2 * k + 1, 2 * r)] = cx.im;
            a[(2 * k, 2 * r + 1)] = cy.re;
            a[(2 * k + 1, 2 * r + 1)] = cy.im;
        }
        a[(2 * k, cols - 2)] = 1.0;
        let low = if iw.im != 0.0 {
            1.0 / (iw * iw)
        } else {
            Complex64::new(0.0, 0.0)
        };
        a[(2 * k, cols - 1)] = low.re;
        a[(2 * k + 1, cols - 1)] = low.im;
        b[2 * k] = h.re;
        b[2 * k + 1] = h.im;
    }
    // Column scaling for conditioning.
    let norms: Vec<f64> = (0..cols)
        .map(|j| a.column(j).norm().max(f64::MIN_POSITIVE))
        .collect();
    for (j, nj) in norms.iter().enumerate() {
        a.column_mut(j).scale_mut(1.0 / nj);
    }
    let x = a
        .svd(true, true)
        .solve(&b, 1e-12)
        .unwrap_or_else(|_| DVector::zeros(cols));
    let x: Vec<f64> = x.iter().zip(&norms).map(|(v, n)| v / n).collect();
    let res = (0..poles.len())
        .map(|r| Complex64::new(x[2 * r], x[2 * r + 1]))
        .collect();
    (res, x[cols - 2], x[cols - 1])
}

/// Initial poles: groups of poles stable against the previous order (0.5 %
/// in frequency, 20 % in damping) within ±0.25 % in frequency found
/// in at least `needed` orders, densest first; each gives the median of its
/// poles.
fn clusters(all: &[Vec<(f64, f64, Complex64)>], needed: usize) -> Vec<Complex64> {
    let mut stable: Vec<(usize, f64, f64, Complex64)> = Vec::new();
    for k in 1..all.len() {
        for &(f, z, sp) in &all[k] {
            let ok = all[k - 1].iter().any(|&(f2, z2, _)| {
                let (a, b) = close((f, z), (f2, z2), CLUSTER_DAMPING);
                a && b
            });
            if ok {
                stable.push((k, f, z, sp));
            }
        }
    }
    // Densest group first: the stable pole with the most orders within
    // ±0.25 % in frequency, its group removed, repeated.
    let near = |a: f64, b: f64| (a - b).abs() <= 0.5 * STABLE_FREQUENCY * a;
    let mut out = Vec::new();
    loop {
        let count = |f: f64| {
            let mut orders: Vec<usize> = stable
                .iter()
                .filter(|g| near(f, g.1))
                .map(|g| g.0)
                .collect();
            orders.sort_unstable();
            orders.dedup();
            orders.len()
        };
        let Some((best, n)) = stable
            .iter()
            .map(|g| (g.1, count(g.1)))
            .max_by_key(|&(_, n)| n)
        else {
            break;
        };
        if n < needed {
            break;
        }
        let (group, rest): (Vec<_>, Vec<_>) = stable.into_iter().partition(|g| near(best, g.1));
        stable = rest;
        let mut re: Vec<f64> = group.iter().map(|g| g.3.re).collect();
        let mut im: Vec<f64> = group.iter().map(|g| g.3.im).collect();
        re.sort_by(f64::total_cmp);
        im.sort_by(f64::total_cmp);
        out.push(Complex64::new(re[re.len() / 2], im[im.len() / 2]));
    }
    out.sort_by(|a, b| a.im.total_cmp(&b.im));
    out
}

/// The modal model's misfit to the band as a least-squares problem in the
/// poles' real and imaginary parts x = (Re s₁, Im s₁, Re s₂, …), the
/// residues and residual terms eliminated by linear least squares
/// (variable projection).
struct PoleRefinement<'a> {
    band: &'a [(f64, Complex64)],
}

impl PoleRefinement<'_> {
    fn poles(x: &[f64]) -> Vec<Complex64> {
        x.chunks(2).map(|c| Complex64::new(c[0], c[1])).collect()
    }
}

impl lm::Problem for PoleRefinement<'_> {
    type Point = DVector<f64>;
    type Error = std::convert::Infallible;

    /// Model minus measurement, real and imaginary parts per bin.
    fn evaluate(&mut self, x: &[f64]) -> Result<DVector<f64>, Self::Error> {
        let p = Self::poles(x);
        let (res, u, l) = residues(self.band, &p);
        let mut r = DVector::zeros(2 * self.band.len());
        for (k, (f, h)) in self.band.iter().enumerate() {
            let iw = Complex64::new(0.0, 2.0 * std::f64::consts::PI * f);
            let mut m = Complex64::new(u, 0.0) + l / (iw * iw);
            for (pp, rr) in p.iter().zip(&res) {
                m += rr / (iw - pp) + rr.conj() / (iw - pp.conj());
            }
            r[2 * k] = m.re - h.re;
            r[2 * k + 1] = m.im - h.im;
        }
        Ok(r)
    }

    fn residuals(&self, point: &DVector<f64>) -> DVector<f64> {
        point.clone()
    }

    /// Forward differences, step 1e-7 |s| for each pole's parts.
    fn jacobian(
        &mut self,
        x: &[f64],
        _: &DVector<f64>,
        r: &DVector<f64>,
    ) -> Result<DMatrix<f64>, Self::Error> {
        let mut jac = DMatrix::<f64>::zeros(r.len(), x.len());
        for j in 0..x.len() {
            let mut xj = x.to_vec();
            let step = 1e-7 * Complex64::new(x[j / 2 * 2], x[j / 2 * 2 + 1]).norm();
            xj[j] += step;
            let rj = self.evaluate(&xj)?;
            jac.set_column(j, &((rj - r) / step));
        }
        Ok(jac)
    }
}

/// Settings of the refinement's Levenberg–Marquardt loop: μ from 10⁻³,
/// ×4 on a rejected trial, ÷3 (down to 10⁻¹²) on a taken step; at most 50
/// taken steps, 10 rejected trials in a row, or a taken step that lowers
/// the misfit by 10⁻¹² of itself.
const REFINE: lm::Settings = lm::Settings {
    initial_damping: lm::Scale::Absolute(1e-3),
    grow: 4.0,
    shrink: 3.0,
    damping_floor: lm::Scale::Absolute(1e-12),
    damping_ceiling: f64::INFINITY,
    max_rejections: 10,
    step_tolerance: 0.0,
    min_relative_decrease: 1e-12,
    max_evaluations: usize::MAX,
    max_iterations: 50,
};

/// Nonlinear least-squares refinement of the poles (variable projection:
/// residues eliminated linearly; the one Levenberg–Marquardt loop,
/// [`lm::solve`], on the poles' real and imaginary parts with a
/// forward-difference Jacobian). LSCF's linearised equation error is biased
/// by noise; the output error minimised here is not (for noise of equal
/// variance across the band).
fn refine(band: &[(f64, Complex64)], poles: &mut [Complex64]) {
    if poles.is_empty() {
        return;
    }
    let mut problem = PoleRefinement { band };
    let x0: Vec<f64> = poles.iter().flat_map(|p| [p.re, p.im]).collect();
    let unbounded = vec![f64::INFINITY; x0.len()];
    let lower: Vec<f64> = unbounded.iter().map(|v| -v).collect();
    let Ok(start) = lm::Problem::evaluate(&mut problem, &x0);
    let Ok(out) = lm::solve(&mut problem, x0, start, &lower, &unbounded, &REFINE);
    poles.copy_from_slice(&PoleRefinement::poles(&out.x));
}
