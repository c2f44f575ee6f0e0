//! Modes the LSCF seeds missed, found in the fit residual (see
//! [`super::fit`]).
//!
//! LSCF's common denominator can miss a weak mode among the poles that fit
//! the noise of a wide band: one that holds a few bins (ζf near Δf: a
//! lightly damped mode of a short record), or one 60 dB under its
//! neighbours. Once the seeds are refined, such a mode stands in the
//! residual r_k = H_k − Ĥ_k as a stretch of bins above the noise.
//!
//! **Noise model.** The residual is weighted as the fit weighs the bins
//! ([`super::lsfd::Band::rows`]: by |F| for H1, so that noise on the force
//! does not make heavy tails where the force dips). For noise alone, r_k is
//! complex Gaussian: |r_k|²/σ_k²
//! is exponential with mean 1. The noise power σ_k² around bin k is the
//! median of |r|² over ±[`NOISE_WINDOW_BINS`] bins (and at least four
//! widths) divided by ln 2 (an exponential law's mean from its median,
//! robust to the mode itself), or the band's, whichever is smaller: a
//! missed mode's wings, spread by the fit of the others, raise the local
//! median near it. Noise is not always independent from bin to
//! bin: a force or exponential window spreads each time sample's noise
//! over many bins. Its correlation length ℓ = (1 + ρ)/(1 − ρ) bins, with ρ
//! the residual's lag-one correlation |Σ r_k r̄_(k+1)|/Σ|r_k|², counts the
//! bins per independent sample (an AR(1) law's).
//!
//! Noise on the force adds an error −H N_F/F, whose power grows with
//! |H|²: σ_k² gains b|Ĥ_k|², b from the strongest tenth of the bins (the
//! median of |r|² there over ln 2, less the band's level, over their
//! median |Ĥ|²; zero when noise is on the response only).
//!
//! **Test.** The mean of |r|²/σ² over w bins is then Γ(w′)/w′ distributed,
//! w′ = max(1, w/ℓ rounded) independent samples. For each width w of
//! [`SEED_WIDTHS`], a stretch whose mean exceeds the level that noise
//! passes with probability [`SEED_FALSE_ALARM`] is a candidate; the one
//! furthest above its level is returned, centred on its strongest bin, with
//! a pole seeded there (2ζf = wΔf). Noise correlated over ℓ bins bends H
//! smoothly over about that many: when ℓ ≥ 4, only stretches narrower than
//! ℓ/4 are sought. Left out: a stretch within three
//! half-power widths of a fitted pole (that pole's misfit: noise on the
//! force scales with |H|), one already tried, and one whose RMS residual
//! is under [`SEED_PRECISION`] of the band's largest |H| (rounding, not
//! response).

use std::f64::consts::PI;

use realfft::num_complex::Complex64;

use super::lsfd::{project, Band, MIN_HALF_POWER_BINS};

/// Smallest half-width, in bins, of the window whose median residual sets
/// the noise level.
pub const NOISE_WINDOW_BINS: usize = 128;
/// Chance that noise alone passes the test at one stretch of one width.
pub const SEED_FALSE_ALARM: f64 = 1e-6;
/// Smallest RMS residual, relative to the band's largest |H|, taken for a
/// response.
pub const SEED_PRECISION: f64 = 1e-8;
/// Widths, in bins, over which the residual's power is averaged: a mode's
/// half-power band holds about 2ζf/Δf bins.
pub const SEED_WIDTHS: [usize; 5] = [1, 2, 4, 8, 16];
/// Half-power half-widths around a fitted pole where no stretch is sought.
pub const EXCLUSION_WIDTHS: f64 = 1.0;

/// A stretch of the band: centre and half-width, Hz.
pub type Stretch = (f64, f64);

/// The level x that the mean of `w` independent exponential variables of
/// mean 1 exceeds with probability `p`: P(Γ(w, 1) > w x) = p, with
/// P(Γ(w, 1) > y) = e^(−y) Σ_(j<w) y^j/j! (bisection).
pub fn exponential_mean_level(w: usize, p: f64) -> f64 {
    let tail = |y: f64| {
        let (mut term, mut sum) = (1.0, 1.0);
        for j in 1..w {
            term *= y / j as f64;
            sum += term;
        }
        (-y).exp() * sum
    };
    let (mut lo, mut hi) = (0.0, 1e3);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if tail(mid) > p {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    hi / w as f64
}

/// The element at position len/2 of `values` sorted (the upper median),
/// found without sorting them all; `values` must not be empty.
pub fn upper_median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    let mid = v.len() / 2;
    let (_, m, _) = v.select_nth_unstable_by(mid, f64::total_cmp);
    *m
}

/// Per index c, the upper median of `values[c − reach ..= c + reach]`
/// (clipped at the ends), as [`upper_median`] of each window gives, with
/// one sorted window slid along: per index, a binary search and a shift
/// of memory instead of a copy and a selection.
pub fn sliding_upper_median(values: &[f64], reach: usize) -> Vec<f64> {
    let n = values.len();
    let mut window: Vec<f64> = Vec::with_capacity(2 * reach + 1);
    let insert = |w: &mut Vec<f64>, v: f64| {
        let at = w.partition_point(|x| x.total_cmp(&v).is_lt());
        w.insert(at, v);
    };
    let (mut lo, mut hi) = (0, 0);
    let mut out = Vec::with_capacity(n);
    for c in 0..n {
        let (want_lo, want_hi) = (c.saturating_sub(reach), (c + reach + 1).min(n));
        while hi < want_hi {
            insert(&mut window, values[hi]);
            hi += 1;
        }
        while lo < want_lo {
            let v = values[lo];
            let at = window.partition_point(|x| x.total_cmp(&v).is_lt());
            window.remove(at);
            lo += 1;
        }
        out.push(window[window.len() / 2]);
    }
    out
}

/// The correlation length ℓ = (1 + ρ)/(1 − ρ) of the residual `r`, in bins
/// (module doc; ρ at most 0.99).
pub fn correlation_length(r: &[Complex64]) -> f64 {
    let power: f64 = r.iter().map(|v| v.norm_sqr()).sum();
    if power <= 0.0 || r.len() < 2 {
        return 1.0;
    }
    let lag: Complex64 = r.windows(2).map(|p| p[0] * p[1].conj()).sum();
    let rho = (lag.norm() / power).min(0.99);
    (1.0 + rho) / (1.0 - rho)
}

/// The stretch where the residual of `poles` stands highest above the
/// noise, with a pole seeded there, clear of `tried` (module doc); None
/// when no stretch passes.
pub fn residual_peak(
    band: Band<'_>,
    poles: &[Complex64],
    tried: &[Stretch],
) -> Option<(Stretch, Complex64)> {
    let n = band.bins.len();
    if n < 8 {
        return None;
    }
    let r = project(band, poles).residual;
    let r2: Vec<f64> = r.iter().map(|v| v.norm_sqr()).collect();
    let ell = correlation_length(&r);
    let df = (band.bins[n - 1].0 - band.bins[0].0) / (n - 1) as f64;
    let mut prefix = vec![0.0; n + 1];
    for k in 0..n {
        prefix[k + 1] = prefix[k] + r2[k];
    }
    let median_power = |slice: &[f64]| upper_median(slice) / std::f64::consts::LN_2;
    // The band's noise power, and around each bin the smaller of it and
    // the local one: a missed mode's wings, spread by the fit of the
    // others, raise the local median near it.
    let global = median_power(&r2);
    // Noise on the force adds an error ∝ |Ĥ| (module doc): its share b of
    // |Ĥ|², from the strongest tenth of the bins, above the band's level.
    let model2: Vec<f64> = (0..n)
        .map(|k| (band.row(k) * band.bins[k].1 - r[k]).norm_sqr())
        .collect();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|a, b| model2[*b].total_cmp(&model2[*a]));
    let top = &order[..(n / 10).max(1)];
    let top_r2: Vec<f64> = top.iter().map(|&k| r2[k]).collect();
    let mut top_m2: Vec<f64> = top.iter().map(|&k| model2[k]).collect();
    top_m2.sort_by(f64::total_cmp);
    let b = if top_m2[top_m2.len() / 2] > 0.0 {
        ((median_power(&top_r2) - global) / top_m2[top_m2.len() / 2]).max(0.0)
    } else {
        0.0
    };
    let noise_within = |reach: usize| -> Vec<f64> {
        sliding_upper_median(&r2, reach)
            .into_iter()
            .zip(&model2)
            .map(|(m, m2)| (m / std::f64::consts::LN_2).min(global) + b * m2)
            .collect()
    };
    let scale = (0..n).fold(0.0_f64, |a, k| a.max(band.row(k) * band.bins[k].1.norm()));
    let floor = (SEED_PRECISION * scale).powi(2);
    let mut taken: Vec<Stretch> = poles
        .iter()
        .map(|p| {
            let half = (-p.re / (2.0 * PI)).max(MIN_HALF_POWER_BINS * df);
            (p.im / (2.0 * PI), EXCLUSION_WIDTHS * half)
        })
        .collect();
    taken.extend_from_slice(tried);
    let mut noise_by_reach: Vec<(usize, Vec<f64>)> = Vec::new();
    let mut best: Option<(f64, usize, usize)> = None;
    // Noise correlated over ℓ bins bends H smoothly over about ℓ bins: a
    // stretch that narrow is no more a mode than that bend is. Only
    // stretches under ℓ/4 are sought when ℓ ≥ 4.
    let narrow = |w: usize| ell < 4.0 || (w as f64) <= ell / 4.0;
    for w in SEED_WIDTHS.into_iter().filter(|&w| 4 * w <= n && narrow(w)) {
        let samples = ((w as f64 / ell).round() as usize).max(1);
        let level = exponential_mean_level(samples, SEED_FALSE_ALARM);
        let reach = (4 * w).max(NOISE_WINDOW_BINS);
        if noise_by_reach.last().is_none_or(|(r, _)| *r != reach) {
            noise_by_reach.push((reach, noise_within(reach)));
        }
        let Some((_, sigma2)) = noise_by_reach.last() else {
            continue;
        };
        for start in 0..=n - w {
            let mean = (prefix[start + w] - prefix[start]) / w as f64;
            let noise = sigma2[start + w / 2];
            if noise <= 0.0 || mean <= floor {
                continue;
            }
            let excess = mean / noise / level;
            let (f0, f1) = (band.bins[start].0, band.bins[start + w - 1].0);
            let seen = taken
                .iter()
                .any(|(g, half)| f0 <= g + half && f1 >= g - half);
            if excess > 1.0 && !seen && best.is_none_or(|(b, _, _)| excess > b) {
                best = Some((excess, start, w));
            }
        }
    }
    let (_, start, w) = best?;
    let k = (start..start + w).max_by(|&a, &b| r2[a].total_cmp(&r2[b]))?;
    let f = band.bins[k].0;
    let zeta = (w as f64 * df / (2.0 * f)).clamp(1e-4, 0.3);
    let omega = 2.0 * PI * f;
    let seed = Complex64::new(-zeta * omega, omega * (1.0 - zeta * zeta).sqrt());
    Some(((f, (w as f64 / 2.0).max(2.0) * df), seed))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The level against the tail in closed form: w = 1 is e^(−x) = p;
    /// w = 2 is e^(−y)(1 + y) = p at y = 2x.
    #[test]
    fn levels_match_the_gamma_tail() {
        let p: f64 = 1e-6;
        assert!((exponential_mean_level(1, p) - (-p.ln())).abs() < 1e-9);
        let y = 2.0 * exponential_mean_level(2, p);
        assert!(((-y).exp() * (1.0 + y) - p).abs() < 1e-12);
    }

    /// The slid window's medians are the medians of each window taken
    /// whole, ends and repeated values included.
    #[test]
    fn sliding_medians_equal_whole_window_medians() {
        let values: Vec<f64> = (0..300)
            .map(|k| ((k * 7919) % 101) as f64 * if k % 5 == 0 { 1.0 } else { 0.5 })
            .collect();
        for reach in [0, 1, 4, 37, 400] {
            let slid = sliding_upper_median(&values, reach);
            for (c, m) in slid.iter().enumerate() {
                let window = &values[c.saturating_sub(reach)..(c + reach + 1).min(values.len())];
                assert_eq!(*m, upper_median(window), "reach {reach}, index {c}");
            }
        }
    }

    /// White noise has ℓ near 1; a three-bin moving sum of it (ρ = 2/3)
    /// has ℓ = 5.
    #[test]
    fn correlation_length_of_white_and_smoothed_noise() {
        let mut state = 12345_u64;
        let mut gauss = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            let u1 = ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            let u2 = ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
            (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
        };
        let white: Vec<Complex64> = (0..20_000)
            .map(|_| Complex64::new(gauss(), gauss()))
            .collect();
        assert!((correlation_length(&white) - 1.0).abs() < 0.05);
        let smooth: Vec<Complex64> = white.windows(3).map(|w| w[0] + w[1] + w[2]).collect();
        assert!((correlation_length(&smooth) - 5.0).abs() < 0.3);
    }
}
