//! Resampling: onto a uniform grid, and to a lower rate.
//!
//! **Onto a uniform grid.** [`resample_uniform`] interpolates linearly
//! non-uniformly stepped samples (an adaptive integrator's output) onto the
//! uniform grid t₀ + k/f that the FFT needs.
//!
//! **To a lower rate.** Sampling at f_s folds every component above the Nyquist frequency f_s/2
//! back into the band: a mode at 29.3 kHz sampled at 51.2 kHz appears at
//! 21.9 kHz. Acquisition hardware therefore low-pass filters before it
//! samples; a simulated measurement must do the same.
//!
//! [`resample`] evaluates, at every output instant t_m = m/f_out, the
//! convolution of the input samples with a continuous Kaiser-windowed sinc
//! kernel (band-limited interpolation, J. O. Smith's "bandlimited
//! interpolation" resampler):
//!
//!   y(t_m) = Σ_k x_k h(t_m − k/f_in) / Σ_k h(t_m − k/f_in),
//!   h(τ) = sinc(2 f_c τ) · I₀(β √(1 − (τ/T)²)) / I₀(β),  |τ| ≤ T.
//!
//! It filters and interpolates in one step, so the ratio f_in/f_out need not
//! be a whole number (1 MHz → 51.2 kHz is 19.53). The normalisation by
//! Σh gives unit gain at 0 Hz exactly.
//!
//! Design ([`AntiAlias`], Kaiser's formulas): pass band up to f_p, stop band
//! from f_st with attenuation A dB; cutoff f_c = (f_p + f_st)/2,
//! β = 0.1102 (A − 8.7) for A > 50, half length T = (A − 7.95) /
//! (2.285 · 2π (f_st − f_p)) · ... in seconds (the tap count Kaiser gives
//! for a transition of f_st − f_p, halved). The pass-band ripple is about
//! 10^(−A/20) in amplitude. Default: f_p = 0.40 f_out, f_st = 0.50 f_out
//! (the new Nyquist frequency: nothing above it survives to fold), A = 90 dB,
//! so the −6 dB point is at 0.45 f_out.

use super::spectrum::{check_rate, SpectrumError};

/// Linear interpolation of `(t, x)` onto `t[0] + k / rate_hz`,
/// `k = 0, 1, …` up to the last time stamp (inclusive when it falls on the
/// grid). `t` must be strictly increasing; at least two points are needed.
pub fn resample_uniform(t: &[f64], x: &[f64], rate_hz: f64) -> Result<Vec<f64>, SpectrumError> {
    check_rate(rate_hz)?;
    if t.len() != x.len() {
        return Err(SpectrumError::LengthMismatch {
            first: "time",
            first_len: t.len(),
            second: "values",
            second_len: x.len(),
        });
    }
    if t.len() < 2 {
        return Err(SpectrumError::TooFewSamples { n: t.len(), min: 2 });
    }
    if let Some(index) = t.iter().position(|v| !v.is_finite()) {
        return Err(SpectrumError::NonFinite {
            signal: "time",
            index,
        });
    }
    if let Some(index) = x.iter().position(|v| !v.is_finite()) {
        return Err(SpectrumError::NonFinite {
            signal: "values",
            index,
        });
    }
    if let Some(index) = (1..t.len()).find(|&i| t[i] <= t[i - 1]) {
        return Err(SpectrumError::NonIncreasingTime { index });
    }
    let (t0, t_end) = (t[0], t[t.len() - 1]);
    let count = ((t_end - t0) * rate_hz * (1.0 + 4.0 * f64::EPSILON)).floor() as usize + 1;
    let mut out = Vec::with_capacity(count);
    let mut j = 0;
    for k in 0..count {
        let tq = (t0 + k as f64 / rate_hz).min(t_end);
        while j + 2 < t.len() && t[j + 1] < tq {
            j += 1;
        }
        let s = (tq - t[j]) / (t[j + 1] - t[j]);
        out.push(x[j] + s * (x[j + 1] - x[j]));
    }
    Ok(out)
}

/// An anti-aliasing design relative to the output rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AntiAlias {
    /// Pass-band edge as a fraction of the output rate.
    pub pass: f64,
    /// Stop-band edge as a fraction of the output rate (≤ 0.5: no alias).
    pub stop: f64,
    /// Stop-band attenuation, dB.
    pub attenuation_db: f64,
}

impl Default for AntiAlias {
    fn default() -> Self {
        AntiAlias {
            pass: 0.40,
            stop: 0.50,
            attenuation_db: 90.0,
        }
    }
}

impl AntiAlias {
    /// Kaiser's β for the attenuation.
    pub fn beta(&self) -> f64 {
        let a = self.attenuation_db;
        if a > 50.0 {
            0.1102 * (a - 8.7)
        } else if a >= 21.0 {
            0.5842 * (a - 21.0).powf(0.4) + 0.07886 * (a - 21.0)
        } else {
            0.0
        }
    }

    /// Half length T of the kernel, s, for output rate `f_out`.
    pub fn half_length(&self, f_out: f64) -> f64 {
        let transition = (self.stop - self.pass) * f_out;
        // Kaiser: N taps at rate f_in span N/f_in = (A − 7.95)/(2.285·2π·Δf).
        let span = (self.attenuation_db - 7.95) / (2.285 * 2.0 * std::f64::consts::PI * transition);
        0.5 * span
    }

    /// Pass-band ripple to expect, as an amplitude fraction.
    pub fn ripple(&self) -> f64 {
        10f64.powf(-self.attenuation_db / 20.0)
    }
}

/// Modified Bessel function of the first kind, order 0 (power series; all
/// terms positive, converges for every argument used here, β < 20).
pub fn bessel_i0(x: f64) -> f64 {
    let q = 0.25 * x * x;
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..200 {
        term *= q / (k * k) as f64;
        sum += term;
        if term < 1e-17 * sum {
            break;
        }
    }
    sum
}

/// The Kaiser window I₀(β√(1 − r²))/I₀(β) on r ∈ [0, 1], tabulated
/// (linear interpolation between 4097 points: error below 1e-6, under the
/// −90 dB stop band).
struct KaiserTable(Vec<f64>);

impl KaiserTable {
    const POINTS: usize = 4096;

    fn new(beta: f64) -> Self {
        let i0b = bessel_i0(beta);
        KaiserTable(
            (0..=Self::POINTS)
                .map(|i| {
                    let r = i as f64 / Self::POINTS as f64;
                    bessel_i0(beta * (1.0 - r * r).max(0.0).sqrt()) / i0b
                })
                .collect(),
        )
    }

    fn at(&self, r: f64) -> f64 {
        let x = r * Self::POINTS as f64;
        // r ≥ 0: truncation is the floor.
        let i = (x as usize).min(Self::POINTS - 1);
        let f = x - i as f64;
        self.0[i] * (1.0 - f) + self.0[i + 1] * f
    }
}

/// Samples of `x` (taken at `f_in` from t = 0) at `f_out` < `f_in`, behind
/// the low-pass `design`; outputs cover the input's duration
/// (floor((n−1)·f_out/f_in) + 1 samples). Near the ends the kernel is cut
/// by the record's edges (renormalised), as if the signal were extended
/// smoothly; impact records start and end near zero, where this is exact.
pub fn resample(x: &[f64], f_in: f64, f_out: f64, design: &AntiAlias) -> Vec<f64> {
    if x.is_empty() {
        return Vec::new();
    }
    filter_onto(
        x,
        None,
        f_in,
        f_out,
        design,
        0,
        output_count(x.len(), f_in, f_out),
    )
}

/// A record that starts at rest, resampled as an acquisition system with a
/// pre-trigger records it: `x` (taken at `f_in` from t = 0) held at `rest`
/// before t = 0, sampled at f_out from t = −P/f_out, P = [`pre_trigger`]
/// samples, for as many samples as [`resample`] gives. The kernel is
/// never cut, so both channels of a hit pass one linear filter: the
/// low-pass's response to the blow (its ringing ahead of the blow, the
/// kernel being symmetric) is kept, not renormalised away, and the ratio
/// of the two channels' spectra is the structure's FRF. Returns the
/// samples; the first is at t = −P/f_out.
pub fn resample_from_rest(
    x: &[f64],
    rest: f64,
    f_in: f64,
    f_out: f64,
    design: &AntiAlias,
) -> Vec<f64> {
    if x.is_empty() {
        return Vec::new();
    }
    filter_onto(
        x,
        Some(rest),
        f_in,
        f_out,
        design,
        pre_trigger(design, f_out),
        output_count(x.len(), f_in, f_out),
    )
}

/// floor((n − 1)·f_out/f_in) + 1 output samples of `n` inputs, the ratio
/// taken a few ulps up: a duration that is a whole number of output
/// periods in exact arithmetic (15 ms at 500 kHz) gives its last sample
/// whatever the rounding of the rates (as at every scale of a model).
fn output_count(n: usize, f_in: f64, f_out: f64) -> usize {
    ((n - 1) as f64 * f_out / f_in * (1.0 + 4.0 * f64::EPSILON)).floor() as usize + 1
}

/// Samples ahead of t = 0 that [`resample_from_rest`] records: the
/// kernel's half length in output samples, rounded up (29 at the default
/// design, whatever the rate).
pub fn pre_trigger(design: &AntiAlias, f_out: f64) -> usize {
    // A few ulps down: a whole number of samples stays whole at any rate.
    (design.half_length(f_out) * f_out * (1.0 - 4.0 * f64::EPSILON)).ceil() as usize
}

/// Most phases [`Polyphase`] tabulates: a ratio f_in/f_out = p/q with a
/// larger q (or one that is no such fraction) takes the direct path.
const MAX_PHASES: usize = 1024;

/// `n_out` samples of `x` behind the low-pass at t_m = (m − lead)/f_out;
/// taps before the input's start take `before` (or are cut and the kernel
/// renormalised), taps past its end are cut. A rational ratio f_in/f_out =
/// p/q with few phases q (1 MHz → 51.2 kHz: 625/32) takes the kernel from
/// a table of its q phases ([`Polyphase`]); any other ratio evaluates it at
/// every tap ([`filter_direct`]).
fn filter_onto(
    x: &[f64],
    before: Option<f64>,
    f_in: f64,
    f_out: f64,
    design: &AntiAlias,
    lead: usize,
    n_out: usize,
) -> Vec<f64> {
    match Polyphase::new(f_in, f_out, design, lead, n_out) {
        Some(table) => table.filter(x, before, lead, n_out),
        None => filter_direct(x, before, f_in, f_out, design, lead, n_out),
    }
}

/// The kernel of a rational resampling ratio f_in/f_out = p/q, tabulated
/// once for each of its q phases: output m sits at input position
/// (m − lead)·p/q = b + u/q (b whole, 0 ≤ u < q), so its taps are the
/// inputs b + j at τ = (u/q − j)/f_in, the same q sets of offsets for every
/// output. The kernel is the one [`filter_direct`] evaluates at every tap
/// (the same sinc and Kaiser table at the same τ), each tap's sine taken
/// directly; the two differ by rounding only (on the built-in assembly's
/// impulse records by at most ~1e-13 of the record's largest value: the
/// unit test `polyphase_is_the_direct_filter`).
struct Polyphase {
    p: i64,
    q: i64,
    /// Per phase u, the offset j of its first nonzero tap and the taps.
    phases: Vec<(i64, Vec<f64>)>,
}

impl Polyphase {
    /// The table, if f_in/f_out is p/q with q ≤ [`MAX_PHASES`] and q ≤
    /// `n_out` (tabulating more phases than outputs saves nothing), to
    /// within 1e-9 input samples at the last output.
    fn new(f_in: f64, f_out: f64, design: &AntiAlias, lead: usize, n_out: usize) -> Option<Self> {
        let ratio = f_in / f_out;
        let span = (n_out + lead) as f64;
        let q = (1..=MAX_PHASES.min(n_out)).find(|&q| {
            let p = (ratio * q as f64).round();
            p >= 1.0 && (ratio - p / q as f64).abs() * span <= 1e-9
        })?;
        let p = (ratio * q as f64).round() as i64;
        let q = q as i64;
        let fc = 0.5 * (design.pass + design.stop) * f_out;
        let half = design.half_length(f_out);
        let window = KaiserTable::new(design.beta());
        let reach = (half * f_in).ceil() as i64 + 1;
        let r_per_theta = 1.0 / (2.0 * std::f64::consts::PI * fc * half);
        let phases = (0..q)
            .map(|u| {
                let offset = u as f64 / q as f64;
                let taps: Vec<(i64, f64)> = (-reach..=reach)
                    .filter_map(|j| {
                        let tau = (offset - j as f64) / f_in;
                        let theta = 2.0 * std::f64::consts::PI * fc * tau;
                        let r = (theta * r_per_theta).abs();
                        (r < 1.0).then(|| {
                            let sinc = if theta.abs() < 1e-8 {
                                1.0
                            } else {
                                theta.sin() / theta
                            };
                            (j, sinc * window.at(r))
                        })
                    })
                    .collect();
                let first = taps.first().map_or(0, |t| t.0);
                (first, taps.into_iter().map(|t| t.1).collect())
            })
            .collect();
        Some(Polyphase { p, q, phases })
    }

    fn filter(&self, x: &[f64], before: Option<f64>, lead: usize, n_out: usize) -> Vec<f64> {
        let len = x.len() as i64;
        (0..n_out)
            .map(|m| {
                let s = (m as i64 - lead as i64) * self.p;
                let (base, u) = (s.div_euclid(self.q), s.rem_euclid(self.q));
                let (first, taps) = &self.phases[u as usize];
                let k0 = base + first;
                // Taps on inputs before 0, on 0..len, past the end (cut).
                let ahead = ((-k0).max(0) as usize).min(taps.len());
                let inside = ((len - k0.max(0)).max(0) as usize).min(taps.len() - ahead);
                let (mut acc, mut norm) = (0.0, 0.0);
                if let Some(rest) = before {
                    let held: f64 = taps[..ahead].iter().sum();
                    acc += rest * held;
                    norm += held;
                }
                let start = k0.max(0) as usize;
                let (a, n) = dot_and_sum(
                    &taps[ahead..ahead + inside],
                    &x[start.min(x.len())..(start + inside).min(x.len())],
                );
                acc += a;
                norm += n;
                if norm != 0.0 {
                    acc / norm
                } else {
                    0.0
                }
            })
            .collect()
    }
}

/// (Σ hᵢxᵢ, Σ hᵢ) over equal-length slices, in four partial sums (one a
/// lane of an AVX2 register where the CPU has them: the same sums, the
/// same bits).
fn dot_and_sum(h: &[f64], x: &[f64]) -> (f64, f64) {
    pulp::Arch::new().dispatch(DotAndSum { h, x })
}

struct DotAndSum<'a> {
    h: &'a [f64],
    x: &'a [f64],
}

impl pulp::WithSimd for DotAndSum<'_> {
    type Output = (f64, f64);

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, simd: S) -> (f64, f64) {
        let n = self.h.len().min(self.x.len());
        let (h, x) = (&self.h[..n], &self.x[..n]);
        let whole = h.len() / 4 * 4;
        let (mut acc, mut norm) = ([0.0; 4], [0.0; 4]);
        if std::mem::size_of::<S::f64s>() == std::mem::size_of::<[f64; 4]>() {
            let (hv, xv) = (
                S::as_simd_f64s(&h[..whole]).0,
                S::as_simd_f64s(&x[..whole]).0,
            );
            let (mut a, mut n) = (simd.splat_f64s(0.0), simd.splat_f64s(0.0));
            for (&h4, &x4) in hv.iter().zip(xv) {
                a = simd.add_f64s(a, simd.mul_f64s(h4, x4));
                n = simd.add_f64s(n, h4);
            }
            S::as_mut_simd_f64s(&mut acc).0[0] = a;
            S::as_mut_simd_f64s(&mut norm).0[0] = n;
        } else {
            for (h4, x4) in h[..whole].chunks_exact(4).zip(x[..whole].chunks_exact(4)) {
                for i in 0..4 {
                    acc[i] += h4[i] * x4[i];
                    norm[i] += h4[i];
                }
            }
        }
        let (mut a, mut n) = (
            (acc[0] + acc[1]) + (acc[2] + acc[3]),
            (norm[0] + norm[1]) + (norm[2] + norm[3]),
        );
        for (h, x) in h[whole..].iter().zip(&x[whole..]) {
            a += h * x;
            n += h;
        }
        (a, n)
    }
}

/// [`filter_onto`] for any ratio: the kernel evaluated at every tap.
fn filter_direct(
    x: &[f64],
    before: Option<f64>,
    f_in: f64,
    f_out: f64,
    design: &AntiAlias,
    lead: usize,
    n_out: usize,
) -> Vec<f64> {
    let fc = 0.5 * (design.pass + design.stop) * f_out;
    let half = design.half_length(f_out);
    let window = KaiserTable::new(design.beta());
    let reach = (half * f_in).ceil() as isize;
    let first = if before.is_some() { isize::MIN } else { 0 };
    let mut y = Vec::with_capacity(n_out);
    for m in 0..n_out {
        let t = (m as f64 - lead as f64) / f_out;
        let centre = (t * f_in).round() as isize;
        let lo = (centre - reach).max(first);
        let hi = (centre + reach).min(x.len() as isize - 1);
        let (mut acc, mut norm) = (0.0, 0.0);
        // sin θ_k, θ_k = 2π f_c τ_k, by rotation from k = lo (τ falls by
        // 1/f_in per tap): one sin_cos per output sample instead of one sin
        // per tap; the recurrence's drift over ~10³ taps is ~1e-13.
        let step = 2.0 * std::f64::consts::PI * fc / f_in;
        let (ds, dc) = step.sin_cos();
        let theta0 = 2.0 * std::f64::consts::PI * fc * (t - lo as f64 / f_in);
        let (mut sn, mut cs) = theta0.sin_cos();
        // r = τ/T = θ/(2π f_c T).
        let r_per_theta = 1.0 / (2.0 * std::f64::consts::PI * fc * half);
        let mut theta = theta0;
        for k in lo..=hi {
            let xk = match usize::try_from(k) {
                Ok(k) => x[k],
                Err(_) => before.unwrap_or(0.0),
            };
            let r = (theta * r_per_theta).abs();
            if r < 1.0 {
                let sinc = if theta.abs() < 1e-8 { 1.0 } else { sn / theta };
                let h = sinc * window.at(r);
                acc += h * xk;
                norm += h;
            }
            (sn, cs) = (sn * dc - cs * ds, cs * dc + sn * ds);
            theta -= step;
        }
        y.push(if norm != 0.0 { acc / norm } else { 0.0 });
    }
    y
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest |a − b| relative to the largest |b|.
    fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
        assert_eq!(a.len(), b.len());
        let scale = b.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = (a.iter().zip(b)).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        diff / scale
    }

    #[test]
    fn polyphase_is_the_direct_filter() {
        // A record like the built-in assembly's impulse: every step of
        // 1 µs for 100 ms, a 4568.9 Hz ring-down and a 0.1 ms half-sine
        // blow, to 51.2 kHz (625/32: 32 phases) and 48 kHz (125/6).
        let f_in = 1e6;
        let t = |i: usize| i as f64 / f_in;
        let w = 2.0 * std::f64::consts::PI * 4568.9;
        let signal: Vec<f64> = (0..100_000)
            .map(|i| 0.15 * (-20.0 * t(i)).exp() * (w * t(i)).sin())
            .collect();
        let force: Vec<f64> = (0..100_000)
            .map(|i| {
                let s = t(i) / 1e-4;
                if s < 1.0 {
                    4.0 * (std::f64::consts::PI * s).sin()
                } else {
                    0.0
                }
            })
            .collect();
        let design = AntiAlias::default();
        for f_out in [51_200.0, 48_000.0] {
            let lead = pre_trigger(&design, f_out);
            let n_out = output_count(signal.len(), f_in, f_out);
            assert!(Polyphase::new(f_in, f_out, &design, lead, n_out).is_some());
            for (x, before) in [(&signal, Some(signal[0])), (&force, Some(0.0))] {
                for (before, lead) in [(before, lead), (None, 0)] {
                    let fast = filter_onto(x, before, f_in, f_out, &design, lead, n_out);
                    let direct = filter_direct(x, before, f_in, f_out, &design, lead, n_out);
                    let d = relative_difference(&fast, &direct);
                    eprintln!(
                        "{f_out} Hz, rest {before:?}: max |difference| / max |record| = {d:.1e}"
                    );
                    assert!(d < 1e-12, "{d:e}");
                }
            }
        }
    }

    #[test]
    fn an_irrational_ratio_takes_the_direct_path() {
        let design = AntiAlias::default();
        assert!(
            Polyphase::new(1e6, 51_200.0 * std::f64::consts::SQRT_2, &design, 0, 1000).is_none()
        );
        let x: Vec<f64> = (0..5000).map(|i| (i as f64 * 0.01).sin()).collect();
        let y = resample(&x, 1e6, 51_200.0 * std::f64::consts::SQRT_2, &design);
        assert_eq!(
            y.len(),
            output_count(5000, 1e6, 51_200.0 * std::f64::consts::SQRT_2)
        );
    }
}
