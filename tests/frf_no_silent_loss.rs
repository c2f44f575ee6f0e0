//! No silent loss (README, `frf`): a mode in the band that the fit does not
//! report is listed among the rejected poles. The second outside-eyes
//! trial of this round found the opposite on an undamped clamped–clamped
//! beam: 9 of its 16 modes in the band, 50–650 × above their background,
//! were neither reported nor listed, once the fit's eight residual seeds
//! were spent. What the residual still holds then is listed as `unfitted`.
//!
//! The FRF: 14 well-separated modes of a closed-form modal sum (receptance
//! of modes at ζ 0.2 %, residues spread over 20 dB), noise-free, fitted
//! with LSCF limited to order 6 so that its seeds find at most three and
//! the residual search cannot reach all the others. Every true mode must
//! be reported, or listed within 1 % of its frequency.

use ancf_modal::signal::fit::{fit, FitSettings, PoleBasis};
use realfft::num_complex::Complex64;
use std::f64::consts::PI;

#[test]
fn every_mode_is_reported_or_listed() {
    let modes: Vec<(f64, f64)> = (0..14)
        .map(|k| (100.0 + 70.0 * k as f64, 10f64.powf(-(k % 3) as f64)))
        .collect();
    let f: Vec<f64> = (1..=4000).map(|k| 0.25 * k as f64).collect();
    let h: Vec<Complex64> = f
        .iter()
        .map(|fk| {
            let w = 2.0 * PI * fk;
            modes
                .iter()
                .map(|(fr, a)| {
                    let wr = 2.0 * PI * fr;
                    a / Complex64::new(wr * wr - w * w, 2.0 * 0.002 * wr * w)
                })
                .sum()
        })
        .collect();
    let result = fit(
        &f,
        &h,
        &FitSettings {
            f_lo: 50.0,
            f_hi: 1000.0,
            max_order: 6,
            window_decay_rate: 0.0,
            basis: PoleBasis::Continuous,
        },
    );
    let near = |x: f64, fr: f64| (x / fr - 1.0).abs() < 0.01;
    let listed = |fr: f64| {
        result.modes.iter().any(|m| near(m.frequency_hz, fr))
            || result.rejected.iter().any(|r| near(r.frequency_hz, fr))
    };
    let lost: Vec<f64> = (modes.iter().map(|m| m.0))
        .filter(|&fr| fr < 1000.0 && !listed(fr))
        .collect();
    assert!(
        lost.is_empty(),
        "modes neither reported nor listed: {lost:?}; reported {:?}, rejected {:?}",
        result
            .modes
            .iter()
            .map(|m| m.frequency_hz)
            .collect::<Vec<_>>(),
        result.rejected
    );
    // The listing is not a guess: the fit reported fewer than all, so the
    // check above had something to find.
    assert!(
        result.modes.len() < modes.len(),
        "all fitted: a weaker test"
    );
}
