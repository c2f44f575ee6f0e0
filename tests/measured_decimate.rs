//! The anti-aliasing resampler: 1 MHz → 51.2 kHz, as the simulated
//! vibrometer. A tone above the new Nyquist frequency is attenuated by at
//! least the designed stop band; a tone in the pass band passes within the
//! pass-band ripple.

use ancf_modal::signal::resample::{resample, AntiAlias};
use std::f64::consts::PI;

const F_IN: f64 = 1.0e6;
const F_OUT: f64 = 51_200.0;

fn tone(f: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| (2.0 * PI * f * k as f64 / F_IN).sin())
        .collect()
}

/// Largest |y − expected| away from the record's ends (where the kernel is
/// cut).
fn worst(y: &[f64], expected: impl Fn(f64) -> f64, skip: usize) -> f64 {
    y.iter()
        .enumerate()
        .skip(skip)
        .take(y.len() - 2 * skip)
        .map(|(m, v)| (v - expected(m as f64 / F_OUT)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn tone_above_the_new_nyquist_frequency_is_stopped() {
    let design = AntiAlias::default();
    let skip = (design.half_length(F_OUT) * F_OUT).ceil() as usize + 1;
    // Modes 6 and 7 of the paper's assembly: 29.3 and 30.6 kHz; and one
    // just past the stop-band edge.
    for f in [25_700.0, 29_300.0, 30_600.0, 100_000.0] {
        let y = resample(&tone(f, 100_000), F_IN, F_OUT, &design);
        let peak = worst(&y, |_| 0.0, skip);
        let db = 20.0 * peak.log10();
        eprintln!("{f} Hz: {db:.1} dB");
        assert!(
            db <= -design.attenuation_db + 3.0,
            "{f} Hz leaks at {db:.1} dB"
        );
    }
}

#[test]
fn tone_in_the_pass_band_passes_within_the_ripple() {
    let design = AntiAlias::default();
    let skip = (design.half_length(F_OUT) * F_OUT).ceil() as usize + 1;
    for f in [500.0, 4_600.0, 15_000.0, 20_000.0] {
        let y = resample(&tone(f, 100_000), F_IN, F_OUT, &design);
        assert_eq!(y.len(), (99_999.0 * F_OUT / F_IN) as usize + 1);
        let err = worst(&y, |t| (2.0 * PI * f * t).sin(), skip);
        eprintln!("{f} Hz: error {err:.2e}");
        assert!(err <= 2.0 * design.ripple(), "{f} Hz: error {err:e}");
    }
}

#[test]
fn without_the_filter_the_tone_would_fold() {
    // Control: picking the nearest input sample aliases 29.3 kHz to
    // 51.2 − 29.3 = 21.9 kHz at full amplitude.
    let x = tone(29_300.0, 100_000);
    let picked: Vec<f64> = (0..5_000)
        .map(|m| x[(m as f64 * F_IN / F_OUT).round() as usize])
        .collect();
    assert!(picked.iter().fold(0.0f64, |a, v| a.max(v.abs())) > 0.9);
}
