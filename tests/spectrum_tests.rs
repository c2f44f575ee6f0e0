//! Tests of the spectrum module. Expected values are signal parameters, the
//! closed-form SDOF receptance, or analytic bounds stated next to them (the
//! windows' own constants are checked in `signal_windows.rs`).

use std::f64::consts::PI;

use ancf_modal::signal::frf::frf_h1;
use ancf_modal::signal::resample::resample_uniform;
use ancf_modal::signal::spectrum::{
    amplitude_spectrum, dominant_peak_in, find_peaks, PeakSettings, Spectrum, SpectrumError,
    SpectrumSettings, MIN_SAMPLES,
};
use ancf_modal::signal::Window;

const FS: f64 = 51_200.0;
const N: usize = 5_120; // 100 ms

fn tones(components: &[(f64, f64, f64)], offset: f64) -> Vec<f64> {
    (0..N)
        .map(|i| {
            let t = i as f64 / FS;
            offset
                + components
                    .iter()
                    .map(|(a, f, ph)| a * (2.0 * PI * f * t + ph).cos())
                    .sum::<f64>()
        })
        .collect()
}

/// Analytic bound of the log-parabola bias for a Hann window, in Hz:
/// (b/a)·(2/(3√12))·d³ bins of 1/T, a = π²/6 − 1, b = π⁴/180 − ½, d = n/L.
fn hann_bias_bound_hz(n: usize, fft_len: usize, fs: f64) -> f64 {
    let a = PI * PI / 6.0 - 1.0;
    let b = PI.powi(4) / 180.0 - 0.5;
    let d = n as f64 / fft_len as f64;
    b / a * 2.0 / (3.0 * 12f64.sqrt()) * d.powi(3) * fs / n as f64
}

#[test]
fn single_sine_frequency_and_amplitude() {
    let (amp, f) = (2.5, 4603.37);
    let x = tones(&[(amp, f, 0.7)], 0.0);
    let spec = amplitude_spectrum(&x, FS, &SpectrumSettings::default()).unwrap();
    assert_eq!(spec.df, FS / 65_536.0);
    assert_eq!(spec.resolution_hz, 10.0);
    let peaks = find_peaks(&spec, &PeakSettings::default());
    assert_eq!(peaks.len(), 1, "side lobes must not count: {peaks:?}");
    let p = peaks[0];
    // Bound 5.86e-5 Hz (1.3e-8 relative); +10 % for higher-order terms.
    let tol = 1.1 * hann_bias_bound_hz(N, 65_536, FS);
    println!(
        "freq error {:.3e} Hz (tol {tol:.3e} Hz)",
        p.frequency_hz - f
    );
    assert!((p.frequency_hz - f).abs() <= tol);
    // Scalloping of Hann at half a padded bin is 1 − exp(−(π²/6−1)(d/2)²) ≈ 1e-3,
    // before interpolation.
    assert!((p.magnitude / amp - 1.0).abs() < 1e-3, "{}", p.magnitude);
}

#[test]
fn every_window_gives_the_amplitude() {
    let (amp, f) = (0.8, 7777.7);
    let x = tones(&[(amp, f, 0.2)], 0.0);
    for window in [
        Window::Hann,
        Window::Rectangular,
        Window::FlatTop,
        Window::Blackman,
    ] {
        let settings = SpectrumSettings {
            window,
            ..Default::default()
        };
        let spec = amplitude_spectrum(&x, FS, &settings).unwrap();
        let p = dominant_peak_in(&spec, f - 50.0, f + 50.0).unwrap();
        assert!(
            (p.magnitude / amp - 1.0).abs() < 1e-3,
            "{window}: {}",
            p.magnitude
        );
        // The flat top's main lobe has passband ripple: its maximum is not
        // at the tone, so it only locates frequencies to a fraction of 1/T.
        let tol = if window == Window::FlatTop {
            0.5 * spec.resolution_hz
        } else {
            1e-3
        };
        assert!(
            (p.frequency_hz - f).abs() < tol,
            "{window}: {}",
            p.frequency_hz
        );
    }
}

#[test]
fn two_sines_found_in_order() {
    let x = tones(&[(0.1, 13_000.0, 1.0), (1.0, 4_600.0, 0.3)], 0.0);
    let spec = amplitude_spectrum(&x, FS, &SpectrumSettings::default()).unwrap();
    let peaks = find_peaks(&spec, &PeakSettings::default());
    assert_eq!(peaks.len(), 2, "{peaks:?}");
    let tol = 1.1 * hann_bias_bound_hz(N, 65_536, FS);
    assert!((peaks[0].frequency_hz - 4_600.0).abs() <= tol);
    assert!((peaks[1].frequency_hz - 13_000.0).abs() <= tol);
    assert!((peaks[0].magnitude - 1.0).abs() < 1e-3);
    assert!((peaks[1].magnitude - 0.1).abs() < 1e-4);
    // max_peaks keeps the strongest; a high threshold drops the weak one.
    let one = find_peaks(
        &spec,
        &PeakSettings {
            max_peaks: Some(1),
            ..Default::default()
        },
    );
    assert_eq!(one.len(), 1);
    assert!((one[0].frequency_hz - 4_600.0).abs() <= tol);
    let strong = PeakSettings {
        threshold_db: -15.0,
        ..Default::default()
    };
    assert_eq!(find_peaks(&spec, &strong).len(), 1);
    // Band search: finds each tone, but not a flank.
    let p = dominant_peak_in(&spec, 12_900.0, 13_100.0).unwrap();
    assert!((p.frequency_hz - 13_000.0).abs() <= tol);
    assert!(dominant_peak_in(&spec, 4_610.0, 4_700.0).is_none());
    assert!(dominant_peak_in(&spec, 5_000.0, 4_000.0).is_none());
}

#[test]
fn decaying_sine_peaks_at_damped_frequency() {
    let (fn_hz, zeta): (f64, f64) = (4_600.0, 1e-3);
    let wn = 2.0 * PI * fn_hz;
    let wd = wn * (1.0 - zeta * zeta).sqrt();
    let fd = wd / (2.0 * PI);
    let x: Vec<f64> = (0..N)
        .map(|i| {
            let t = i as f64 / FS;
            (-zeta * wn * t).exp() * (wd * t).cos()
        })
        .collect();
    let spec = amplitude_spectrum(&x, FS, &SpectrumSettings::default()).unwrap();
    let peaks = find_peaks(&spec, &PeakSettings::default());
    assert_eq!(peaks.len(), 1, "{peaks:?}");
    // |FT| of (window × envelope) is even in frequency, so the peak sits at
    // f_d. f_n − f_d = 2.3e-3 Hz: the tolerance must be well below that.
    let err = peaks[0].frequency_hz - fd;
    println!(
        "damped peak error {err:.3e} Hz, f_n - f_d = {:.3e} Hz",
        fn_hz - fd
    );
    assert!(err.abs() < 0.2 * (fn_hz - fd));
}

#[test]
fn mean_removal_suppresses_dc() {
    let x = tones(&[(1.0, 1_234.5, 0.0)], 100.0);
    let with = amplitude_spectrum(&x, FS, &SpectrumSettings::default()).unwrap();
    let low = PeakSettings {
        min_frequency_hz: 0.0,
        ..Default::default()
    };
    let peaks = find_peaks(&with, &low);
    assert_eq!(peaks.len(), 1, "{peaks:?}");
    assert!((peaks[0].frequency_hz - 1_234.5).abs() < 1e-3);
    let dc_max = with
        .frequency_hz
        .iter()
        .zip(&with.magnitude)
        .filter(|(f, _)| **f < 100.0)
        .map(|(_, m)| *m)
        .fold(0.0, f64::max);
    // What is left at 0 Hz is the partial-cycle mean of the tone itself,
    // |sin(π f T)| / (π f T) ≤ 1 / (π f T) = 2.6e-3 for 123.45 cycles.
    assert!(dc_max <= 1.0 / (PI * 1_234.5 * 0.1), "{dc_max}");

    let without = SpectrumSettings {
        remove_mean: false,
        ..Default::default()
    };
    let raw = amplitude_spectrum(&x, FS, &without).unwrap();
    // The offset appears at 0 Hz with its own value (amplitude correction).
    assert!(
        (raw.magnitude[0] - 100.0).abs() < 1e-3,
        "{}",
        raw.magnitude[0]
    );
    let peaks = find_peaks(&raw, &low);
    assert_eq!(peaks.len(), 1, "{peaks:?}");
    let db = raw.magnitude_db();
    assert!((db[0] - 40.0).abs() < 1e-4);
    assert!(db.iter().all(|v| v.is_finite()));
}

/// Displacement of m x'' + c x' + k x = f(t), sampled at FS, integrated with
/// RK4 on 16 sub-steps per sample (ω h = 3.8e-3).
fn sdof_response(m: f64, wn: f64, zeta: f64, force: impl Fn(f64) -> f64, n: usize) -> Vec<f64> {
    let sub = 16;
    let h = 1.0 / (FS * sub as f64);
    let rhs = |t: f64, x: f64, v: f64| (v, force(t) / m - 2.0 * zeta * wn * v - wn * wn * x);
    let (mut x, mut v) = (0.0, 0.0);
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        out.push(x);
        for j in 0..sub {
            let t = (i * sub + j) as f64 * h;
            let k1 = rhs(t, x, v);
            let k2 = rhs(t + h / 2.0, x + h / 2.0 * k1.0, v + h / 2.0 * k1.1);
            let k3 = rhs(t + h / 2.0, x + h / 2.0 * k2.0, v + h / 2.0 * k2.1);
            let k4 = rhs(t + h, x + h * k3.0, v + h * k3.1);
            x += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
    }
    out
}

#[test]
fn frf_h1_matches_sdof_receptance() {
    let (m, fn_hz, zeta) = (2.0, 500.0, 0.02);
    let wn = 2.0 * PI * fn_hz;
    // Raised-cosine impact, 0.5 ms long, from t = 1 ms: its spectrum falls
    // as 1/f³, so sampling at 51.2 kHz aliases little (see below).
    let (t0, tau) = (1e-3, 5e-4);
    let pulse = |t: f64| {
        if t > t0 && t < t0 + tau {
            50.0 * (1.0 - (2.0 * PI * (t - t0) / tau).cos())
        } else {
            0.0
        }
    };
    let n = 25_600; // 0.5 s: the response decays by exp(−ζ ω t) = e^-31
    let force: Vec<f64> = (0..n).map(|i| pulse(i as f64 / FS)).collect();
    let resp = sdof_response(m, wn, zeta, pulse, n);
    let settings = SpectrumSettings {
        window: Window::Rectangular,
        zero_pad_factor: 2,
        remove_mean: false,
    };
    let frf = frf_h1(&force, &resp, FS, &settings).unwrap();
    let (mag, phase) = (frf.magnitude(), frf.phase_rad());
    let mut worst = (0.0f64, 0.0f64);
    let half_power = 2.0 * zeta * fn_hz;
    for (k, &f) in frf.frequency_hz.iter().enumerate() {
        if (f - fn_hz).abs() > 3.0 * half_power {
            continue;
        }
        let w = 2.0 * PI * f;
        let den = m * ((wn * wn - w * w).powi(2) + (2.0 * zeta * wn * w).powi(2)).sqrt();
        let exact_phase = -(2.0 * zeta * wn * w).atan2(wn * wn - w * w);
        worst.0 = worst.0.max((mag[k] * den - 1.0).abs());
        worst.1 = worst.1.max((phase[k] - exact_phase).abs());
    }
    println!(
        "H1 worst relative magnitude error {:.2e}, phase {:.2e} rad",
        worst.0, worst.1
    );
    // Aliasing of the sampled pulse: |F(fs − f)/F(f)| ≈ 2e-5 at 500 Hz.
    assert!(worst.0 < 1e-4 && worst.1 < 1e-4, "{worst:?}");
    // Peak of |H1| at the displacement-resonance frequency f_n √(1 − 2ζ²).
    let spec_like = Spectrum {
        frequency_hz: frf.frequency_hz.clone(),
        magnitude: mag
            .iter()
            .map(|v| if v.is_finite() { *v } else { 0.0 })
            .collect(),
        df: frf.df,
        resolution_hz: FS / n as f64,
        window: Window::Rectangular,
    };
    let p = dominant_peak_in(&spec_like, 400.0, 600.0).unwrap();
    let f_res = fn_hz * (1.0 - 2.0 * zeta * zeta).sqrt();
    assert!((p.frequency_hz - f_res).abs() < 0.05, "{}", p.frequency_hz);
    assert!((p.magnitude * 2.0 * zeta * m * wn * wn - 1.0).abs() < 5e-3);
}

#[test]
fn typed_errors() {
    let s = SpectrumSettings::default();
    assert_eq!(
        amplitude_spectrum(&[], FS, &s),
        Err(SpectrumError::TooFewSamples {
            n: 0,
            min: MIN_SAMPLES
        })
    );
    let mut x = tones(&[(1.0, 100.0, 0.0)], 0.0);
    x[17] = f64::NAN;
    assert_eq!(
        amplitude_spectrum(&x, FS, &s),
        Err(SpectrumError::NonFinite {
            signal: "samples",
            index: 17
        })
    );
    x[17] = 0.0;
    for bad in [0.0, -FS, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            amplitude_spectrum(&x, bad, &s),
            Err(SpectrumError::NonPositiveSampleRate(_))
        ));
    }
    let no_pad = SpectrumSettings {
        zero_pad_factor: 0,
        ..s
    };
    assert_eq!(
        amplitude_spectrum(&x, FS, &no_pad),
        Err(SpectrumError::InvalidZeroPadFactor(0))
    );
    assert!(matches!(
        frf_h1(&x, &x[1..], FS, &s),
        Err(SpectrumError::LengthMismatch { .. })
    ));
    let mut y = x.clone();
    y[3] = f64::INFINITY;
    assert_eq!(
        frf_h1(&x, &y, FS, &s),
        Err(SpectrumError::NonFinite {
            signal: "response",
            index: 3
        })
    );
    assert!(matches!(
        resample_uniform(&[0.0, 1.0, 1.0], &[0.0; 3], 10.0),
        Err(SpectrumError::NonIncreasingTime { index: 2 })
    ));
    assert!(matches!(
        resample_uniform(&[0.0], &[0.0], 10.0),
        Err(SpectrumError::TooFewSamples { .. })
    ));
    assert!(matches!(
        resample_uniform(&[0.0, 1.0], &[0.0, 1.0], -1.0),
        Err(SpectrumError::NonPositiveSampleRate(_))
    ));
}

#[test]
fn resample_linear_function_is_exact() {
    // Strictly increasing, non-uniform: dt = 0.01 + 0.003 (sin(i+1) − sin i) > 0.
    let t: Vec<f64> = (0..500)
        .map(|i| 0.2 + 0.01 * i as f64 + 0.003 * (i as f64).sin())
        .collect();
    let x: Vec<f64> = t.iter().map(|t| 3.0 - 2.0 * t).collect();
    let rate = 250.0;
    let y = resample_uniform(&t, &x, rate).unwrap();
    let span = t[t.len() - 1] - t[0];
    assert_eq!(y.len(), (span * rate).floor() as usize + 1);
    for (k, v) in y.iter().enumerate() {
        let tq = t[0] + k as f64 / rate;
        assert!((v - (3.0 - 2.0 * tq)).abs() < 1e-12, "k {k}");
    }
    // A grid that lands exactly on the last time stamp includes it.
    let y = resample_uniform(&[0.0, 0.5, 1.0], &[1.0, 2.0, 3.0], 4.0).unwrap();
    assert_eq!(y, vec![1.0, 1.5, 2.0, 2.5, 3.0]);
}
