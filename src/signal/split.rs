//! Two modes the LSCF seeds merged into one pole, told apart (see
//! [`super::fit`]).
//!
//! Two modes closer than their half-power widths, in a wide band with
//! noise, can reach the refinement as one pole: LSCF resolves them only at
//! orders the band's noise does not allow (a 1000 and a 1012 Hz mode at
//! ζ 0.5 %, 0.3 % noise, a 0–1600 Hz band, order 40). The one pole then
//! fits neither: it leaves a residual in its half-power band far above the
//! noise, and may even be rejected as not significant against that
//! residual, while the residual search ([`super::residual_search`]) leaves
//! a fitted pole's neighbourhood alone.
//!
//! **Test.** The noise power σ² is the median of the weighted residual's
//! |r|² over the band divided by ln 2 (an exponential law's mean from its
//! median). A pole (kept, or rejected as not significant) whose half-power
//! band f_d ± max(ζf, 2Δf) has a mean |r|²/σ² over [`SPLIT_RATIO`] is
//! replaced by two seeds at its half-power points (when that band spans
//! at least [`MIN_HALF_POWER_BINS`] lines each side: two modes inside a
//! narrower one are not told apart, and a mode ringing past the record's
//! end leaves a misfit there that is no second mode), ω_d ± σ with half its
//! decay, and the poles are chosen again ([`lsfd::select`]). The split is
//! kept when more poles survive the choice than before, two of them within
//! twice the pole's decay rate of it, no broader than twice its decay and
//! apart by more than either's decay rate (half-power half-width), and
//! they leave a mean |r|²/σ² under [`SPLIT_RATIO`] there: a single
//! mode split in two loses one as redundant or not significant, and a
//! noisy mode's misfit is not taken for a broad second mode beside it.

use std::f64::consts::PI;

use realfft::num_complex::Complex64;

use super::fit::{FitSettings, RejectReason};
use super::lsfd::{self, bins_near, project, Band, Rejection, MIN_HALF_POWER_BINS};
use super::residual_search::upper_median;

/// Mean |r|²/σ² over a pole's half-power band above which it is tried as
/// two modes (module doc). Noise alone averages to 1 there.
pub const SPLIT_RATIO: f64 = 10.0;
/// Most splits tried in one fit.
pub const MAX_SPLITS: usize = 4;

/// The poles after trying to split those that fit their band badly
/// (module doc), with the rejections the new choices made.
pub fn split_merged(
    band: Band<'_>,
    mut kept: Vec<Complex64>,
    mut rejected: Vec<Rejection>,
    settings: &FitSettings,
) -> (Vec<Complex64>, Vec<Rejection>) {
    let Some(line) = band.line_hz() else {
        return (kept, rejected);
    };
    // The mean of `power` over the half-power band of pole `p`.
    let near = |power: &[f64], p: Complex64| {
        let half = (-p.re / (2.0 * PI)).max(MIN_HALF_POWER_BINS * line);
        let (sum, count) = bins_near(band.bins, p.im / (2.0 * PI), half)
            .fold((0.0, 0usize), |(s, c), k| (s + power[k], c + 1));
        sum / count.max(1) as f64
    };
    let mut tried: Vec<Complex64> = Vec::new();
    while tried.len() < MAX_SPLITS {
        let residual = project(band, &kept).residual;
        let power: Vec<f64> = residual.iter().map(|r| r.norm_sqr()).collect();
        let noise = upper_median(&power) / std::f64::consts::LN_2;
        if noise <= 0.0 {
            break;
        }
        let not_significant = rejected
            .iter()
            .filter(|(_, why)| *why == RejectReason::NotSignificant)
            .map(|(p, _)| *p);
        let Some((worst, ratio)) = kept
            .iter()
            .copied()
            .chain(not_significant)
            .filter(|p| !tried.contains(p) && -p.re / (2.0 * PI) >= MIN_HALF_POWER_BINS * line)
            .map(|p| (p, near(&power, p) / noise))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            break;
        };
        if ratio < SPLIT_RATIO {
            break;
        }
        tried.push(worst);
        let sigma = -worst.re;
        let mut trial: Vec<Complex64> = kept.iter().copied().filter(|p| *p != worst).collect();
        for side in [-1.0, 1.0] {
            trial.push(Complex64::new(-0.5 * sigma, worst.im + side * sigma));
        }
        let (more, left_out) = lsfd::select(band, &trial, settings);
        // Two modes where the pole was, neither broader than it, that
        // explain its misfit (a single mode's noisy fit is not split into
        // a mode and a broad pole beside it).
        let within: Vec<&Complex64> = more
            .iter()
            .filter(|p| (p.im - worst.im).abs() <= 2.0 * sigma.max(2.0 * PI * line))
            .collect();
        // ... and apart by more than either's half-power half-width: two
        // poles closer than that fit one mode's noise (2840.4 and 2841.4 Hz
        // for one 2840 Hz mode at ζ 2.8 % under force noise).
        let apart = |a: &Complex64, b: &Complex64| (a.im - b.im).abs() > (-a.re).max(-b.re);
        let two = within.len() >= 2
            && within.iter().all(|p| -p.re <= 2.0 * sigma)
            && within
                .iter()
                .enumerate()
                .all(|(i, a)| within[i + 1..].iter().all(|b| apart(a, b)));
        let explained = || {
            let after: Vec<f64> = (project(band, &more).residual.iter())
                .map(|r| r.norm_sqr())
                .collect();
            near(&after, worst) / noise < SPLIT_RATIO
        };
        if more.len() > kept.len() && two && explained() {
            kept = more;
            rejected.retain(|(p, _)| *p != worst);
            rejected.extend(left_out);
        }
    }
    (kept, rejected)
}
