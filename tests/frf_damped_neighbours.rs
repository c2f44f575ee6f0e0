//! Closely spaced, heavily damped modes among strong modes above the band
//! (second outside-eyes trial of issue 35: a steel portal frame's record,
//! its 592 Hz mode 7e-3 off in f and −15 % in ζ; a zoom band on it found
//! no mode at all).
//!
//! The FRF is the closed-form modal sum of the portal's own modes (60 of
//! them, mass-normalized from `modal`, Rayleigh damping ζ = α/(2ω) + βω/2),
//! as an accelerance from mid-girder to its quarter point: noise-free, on
//! a frequency axis. In the band to 800 Hz it holds eight modes; the 592 Hz
//! one is 7.5 × weaker than its neighbour at 625 Hz, 33 Hz away, where
//! each half-power band is 45 Hz wide; modes at 1090, 1173 and 1323 Hz
//! with ζ 7–8 % reach into the band. The fit must find the eight and no
//! other, with f and ζ within what its residual terms allow: the weak
//! shoulder within 3e-3 in f and 8 % in ζ (with the three residual terms
//! of before: 1.2e-2 and −10 %), the others within 1e-3 and 3 %.
//! A zoom band (400–750 Hz), whose LSCF normal equations cannot be solved
//! past order 18, must find its four.

use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::error::Source;
use ancf_modal::model::Model;
use ancf_modal::signal::fit::{fit, FitSettings, PoleBasis};
use ancf_modal::system::System;
use realfft::num_complex::Complex64;
use serde_json::json;
use std::f64::consts::PI;

const ALPHA: f64 = 0.5;
const BETA: f64 = 2e-5;

/// (f Hz, ζ, φ_sensor φ_load) of the portal's first 60 modes.
fn portal_modes() -> Vec<(f64, f64, f64)> {
    let beam = |id: &str, start: [f64; 2], angle: f64, length: f64| {
        json!({"id": id, "start": start, "angle_deg": angle, "length": length, "elements": 8,
               "section": {"height": 0.15, "width": 0.1},
               "material": {"young": 210e9, "density": 7850.0}})
    };
    let weld = |a: serde_json::Value, b: serde_json::Value| json!({"type": "weld", "a": a, "b": b});
    let model = json!({
        "name": "portal",
        "beams": [beam("col_l", [0.0, 0.0], 90.0, 3.0), beam("girder", [0.0, 3.0], 0.0, 4.0),
                  beam("col_r", [4.0, 0.0], 90.0, 3.0)],
        "joints": [
            weld(json!({"ground": [0.0, 0.0]}), json!({"beam": "col_l", "s": 0.0})),
            weld(json!({"ground": [4.0, 0.0]}), json!({"beam": "col_r", "s": 0.0})),
            weld(json!({"beam": "col_l", "s": 3.0}), json!({"beam": "girder", "s": 0.0})),
            weld(json!({"beam": "col_r", "s": 3.0}), json!({"beam": "girder", "s": 4.0}))
        ]
    });
    let model = Model::from_json(&model.to_string(), Source::BuiltIn).unwrap();
    let sys = System::new(&model);
    let settings = ModalSettings {
        modes: Some(60),
        ..ModalSettings::default()
    };
    let modes = modal_at_reference(&sys, &settings).unwrap();
    let girder = &sys.beams[1];
    let y = |node: usize| girder.dof0 + 4 * node + 1;
    assert!((girder.node_s[4] - 2.0).abs() < 1e-12 && (girder.node_s[2] - 1.0).abs() < 1e-12);
    modes
        .modes
        .iter()
        .map(|m| {
            let w = 2.0 * PI * m.frequency_hz;
            let zeta = ALPHA / (2.0 * w) + BETA * w / 2.0;
            (m.frequency_hz, zeta, m.shape[y(2)] * m.shape[y(4)])
        })
        .collect()
}

/// The accelerance Σ −ω² a/(ω_r² − ω² + 2iζ_r ω_r ω) at 0.25 Hz lines to
/// 1000 Hz.
fn accelerance(modes: &[(f64, f64, f64)]) -> (Vec<f64>, Vec<Complex64>) {
    let f: Vec<f64> = (1..=4000).map(|k| 0.25 * k as f64).collect();
    let h = f
        .iter()
        .map(|fk| {
            let w = 2.0 * PI * fk;
            modes
                .iter()
                .map(|(fr, z, a)| {
                    let wr = 2.0 * PI * fr;
                    -w * w * a / Complex64::new(wr * wr - w * w, 2.0 * z * wr * w)
                })
                .sum()
        })
        .collect();
    (f, h)
}

/// Fits `band` and checks that it finds exactly the modes of `truth` with
/// frequencies in it whose residue is at least 1 % of the band's largest;
/// `weak` is the frequency of the weak shoulder.
fn check(band: (f64, f64), truth: &[(f64, f64, f64)], weak: f64) {
    let (f, h) = accelerance(truth);
    let result = fit(
        &f,
        &h,
        &FitSettings {
            f_lo: band.0,
            f_hi: band.1,
            max_order: 40,
            window_decay_rate: 0.0,
            basis: PoleBasis::Continuous,
        },
    );
    let in_band: Vec<_> = truth
        .iter()
        .filter(|m| m.0 > band.0 && m.0 < band.1)
        .collect();
    let largest = in_band.iter().map(|m| m.2.abs()).fold(0.0, f64::max);
    let expected: Vec<_> = in_band
        .into_iter()
        .filter(|m| m.2.abs() >= 0.01 * largest)
        .collect();
    let found: Vec<(f64, f64)> = result
        .modes
        .iter()
        .map(|m| (m.frequency_hz, m.damping_ratio))
        .collect();
    assert_eq!(
        found.len(),
        expected.len(),
        "band {band:?}: found {found:?}, expected {expected:?}"
    );
    for ((fr, z, _), (ff, zf)) in expected.iter().zip(&found) {
        let (ef, ez) = ((ff - fr) / fr, (zf - z) / z);
        let (tf, tz) = if (fr - weak).abs() < 1.0 {
            (3e-3, 0.08)
        } else {
            (1e-3, 0.03)
        };
        assert!(
            ef.abs() < tf && ez.abs() < tz,
            "band {band:?}: mode {fr:.3} Hz, ζ {z:.5}: fitted {ff:.3} Hz ({ef:+.1e}), ζ {zf:.5} ({ez:+.2e})"
        );
    }
}

#[test]
fn a_weak_heavily_damped_shoulder_beside_a_strong_mode() {
    let truth = portal_modes();
    let weak = truth
        .iter()
        .find(|m| (m.0 - 592.4).abs() < 1.0)
        .expect("the portal's 592 Hz mode")
        .0;
    check((0.5, 800.0), &truth, weak);
    check((400.0, 750.0), &truth, weak);
}
