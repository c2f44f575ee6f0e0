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
//!
//! Two modes closer than their half-power widths (outside-eyes trial of
//! issue 33): 1000 and 1012 Hz at ζ 0.5 % (half-power bands 10 Hz wide)
//! beside a 1500 Hz mode at 1 %, on 0.25 Hz lines to 2 kHz, with complex
//! Gaussian noise of 0.1–2 % of the largest |H|. On the full band LSCF at
//! order 40 gave one pole for the pair, rejected as not significant
//! against its own misfit (the 1500 Hz mode then 5.7e-4 off in f); on a
//! 900–1100 Hz zoom no mode was found even without noise. Every mode must
//! be found, and nothing else, within the tolerances for records
//! with noise (1e-3 in f, 5 % in ζ; noise-free: 1e-5 and 0.5 %).

mod measured_support;

use ancf_modal::analysis::{modal_at_reference, ModalSettings};
use ancf_modal::error::Source;
use ancf_modal::model::Model;
use ancf_modal::signal::fit::{fit, FitSettings, PoleBasis};
use ancf_modal::system::System;
use measured_support::Noise;
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

/// The accelerance Σ −ω² a/(ω_r² − ω² + 2iζ_r ω_r ω) of `modes` (f Hz, ζ,
/// a) at `lines` lines 0.25 Hz apart, with complex Gaussian noise of
/// `noise` × the largest |H| (seeded).
fn accelerance(
    modes: &[(f64, f64, f64)],
    lines: usize,
    noise: f64,
    seed: u64,
) -> (Vec<f64>, Vec<Complex64>) {
    let f: Vec<f64> = (1..=lines).map(|k| 0.25 * k as f64).collect();
    let clean: Vec<Complex64> = f
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
    let peak = clean.iter().map(|h| h.norm()).fold(0.0, f64::max);
    let mut rng = Noise::new(seed);
    let sigma = noise * peak / 2f64.sqrt();
    let h = clean
        .into_iter()
        .map(|h| h + Complex64::new(sigma * rng.gauss(), sigma * rng.gauss()))
        .collect();
    (f, h)
}

/// Fits `band` of (`f`, `h`) and checks that it finds exactly `expected`
/// (f Hz, ζ), each within `tolerance(f)` = (relative f, relative ζ).
fn check(
    (f, h): &(Vec<f64>, Vec<Complex64>),
    band: (f64, f64),
    expected: &[(f64, f64)],
    tolerance: impl Fn(f64) -> (f64, f64),
    case: &str,
) {
    let result = fit(
        f,
        h,
        &FitSettings {
            f_lo: band.0,
            f_hi: band.1,
            max_order: 40,
            window_decay_rate: 0.0,
            basis: PoleBasis::Continuous,
        },
    );
    let found: Vec<(f64, f64)> = result
        .modes
        .iter()
        .map(|m| (m.frequency_hz, m.damping_ratio))
        .collect();
    assert_eq!(
        found.len(),
        expected.len(),
        "{case}, band {band:?}: found {found:?}, expected {expected:?}"
    );
    for ((fr, z), (ff, zf)) in expected.iter().zip(&found) {
        let (ef, ez) = ((ff - fr) / fr, (zf - z) / z);
        let (tf, tz) = tolerance(*fr);
        assert!(
            ef.abs() < tf && ez.abs() < tz,
            "{case}, band {band:?}: mode {fr:.3} Hz, ζ {z:.5}: fitted {ff:.3} Hz ({ef:+.1e}), ζ {zf:.5} ({ez:+.2e})"
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
    let data = accelerance(&truth, 4000, 0.0, 1);
    for band in [(0.5, 800.0), (400.0, 750.0)] {
        // The modes in the band whose residue is at least 1 % of the
        // band's largest.
        let in_band: Vec<_> = (truth.iter())
            .filter(|m| m.0 > band.0 && m.0 < band.1)
            .collect();
        let largest = in_band.iter().map(|m| m.2.abs()).fold(0.0, f64::max);
        let expected: Vec<(f64, f64)> = (in_band.into_iter())
            .filter(|m| m.2.abs() >= 0.01 * largest)
            .map(|m| (m.0, m.1))
            .collect();
        let tolerance = |f: f64| {
            if (f - weak).abs() < 1.0 {
                (3e-3, 0.08)
            } else {
                (1e-3, 0.03)
            }
        };
        check(&data, band, &expected, tolerance, "portal");
    }
}

/// (f Hz, ζ, residue scale) of the close pair and its neighbour.
const PAIR: [(f64, f64, f64); 3] = [
    (1000.0, 0.005, 1e4),
    (1012.0, 0.005, 8e3),
    (1500.0, 0.01, 2e4),
];

#[test]
fn a_close_pair_is_two_modes_on_the_full_band_and_on_a_zoom() {
    for band in [(0.25, 1600.0), (900.0, 1100.0), (950.0, 1060.0)] {
        let expected: Vec<(f64, f64)> = (PAIR.iter())
            .filter(|m| m.0 > band.0 && m.0 < band.1)
            .map(|m| (m.0, m.1))
            .collect();
        for (noise, seed) in [
            (0.0, 1),
            (0.001, 1),
            (0.001, 2),
            (0.003, 1),
            (0.003, 2),
            (0.01, 1),
            (0.01, 2),
            (0.02, 1),
            (0.02, 2),
        ] {
            let tolerance = |_| {
                if noise == 0.0 {
                    (1e-5, 0.005)
                } else {
                    (1e-3, 0.05)
                }
            };
            let data = accelerance(&PAIR, 8000, noise, seed);
            check(
                &data,
                band,
                &expected,
                tolerance,
                &format!("noise {noise}, seed {seed}"),
            );
        }
    }
}

/// The close pair at 10:1 (the re-check of issue 33: the 1012 Hz mode, a
/// tenth of its neighbour's residue, 1.2 half-power widths from it, was
/// lost without a word in 28 of 30 records at 1.5 % noise: the residual
/// search left three half-power widths around every fitted pole alone,
/// and the weak mode lies within them). Its peak stands 7–20 × above the
/// noise here: on the full band it must be found, with the others and
/// nothing else, within the tolerances for records with noise
/// (its damping within 15 %). On zoom bands (900–1100 Hz) at 1–1.5 %
/// noise it is still lost: there the noise estimate's |Ĥ|² term is taken
/// from bins its misfit fills.
#[test]
fn a_weak_mode_beside_a_strong_one_is_found_above_the_noise() {
    let modes = [
        (1000.0, 0.005, 1e4),
        (1012.0, 0.005, 1e3),
        (1500.0, 0.005, 2e4),
    ];
    let expected: Vec<(f64, f64)> = modes.iter().map(|m| (m.0, m.1)).collect();
    for noise in [0.005, 0.01, 0.015] {
        for seed in 1..=4 {
            let data = accelerance(&modes, 8000, noise, seed);
            check(
                &data,
                (0.25, 2000.0),
                &expected,
                // The weak mode's damping comes from its 40 lines at 7–20 ×
                // the noise, on its neighbour's flank: measured up to 9 %
                // off (noise 1 %, seed 4), beyond the 5 % for the
                // strong ones.
                |f| {
                    if f == 1012.0 {
                        (1e-3, 0.15)
                    } else {
                        (1e-3, 0.05)
                    }
                },
                &format!("10:1 pair, noise {noise}, seed {seed}"),
            );
        }
    }
}
