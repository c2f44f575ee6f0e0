//! The simulated measurement is one (issue 35): force and response pass
//! through the same acquisition (the anti-aliasing low-pass, the same
//! delay, the same sampling), so the H1 of an `impulse` record is the
//! model's own FRF, modal superposition with the same Rayleigh damping
//! (`frf --model`), away from the resonances.
//!
//! Near a resonance the record's peak sits where the integrator puts it
//! (its period error), so the comparison leaves out ±3 half-power
//! bandwidths (2ζf each) of every mode, and the band the acquisition's
//! low-pass rolls off (above 0.4 f_s). Outside them H1 equals the model's
//! FRF to 1e-3 plus the flank the period error moves ([`allowed`]): at
//! 1 µs steps a mode at 3 kHz with ζ = 0.16 % is 1.2e-3 off three
//! bandwidths from its peak (measured; the 1e-3 of the issue needs the
//! step that makes (ωh)²/12 small against ζ). The record lasts 1 s at
//! 10,240 Hz so that the first mode has died out (no leakage). At the
//! resonances the poles `frf` fits are the model's ([`Deviations::poles`]).

mod common;

use ancf_modal::analysis::impulse::ImpulseResult;
use ancf_modal::analysis::transient::dispersion::GenAlpha;
use ancf_modal::commands::frf::{run as frf, FrfRecords, FrfRequest};
use ancf_modal::commands::impulse::{run as impulse, ImpulseRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use ancf_modal::signal::fit::FittedMode;
use proptest::prelude::*;
use serde_json::json;
use std::f64::consts::PI;

/// A clamped strip of `length` [m] with a tip mass, Rayleigh-damped, struck
/// by a half-sine near the clamp and read by a velocity sensor at the tip.
fn strip(length: f64, tip_mass: f64, alpha: f64, beta: f64) -> ModelInput {
    let v = json!({
        "name": "damped_strip",
        "damping": {"alpha": alpha, "beta": beta},
        "beams": [{"id": "b", "start": [0, 0], "angle_deg": 0, "length": length,
                   "elements": 8,
                   "section": {"height": length / 40.0, "width": length / 8.0},
                   "material": {"young": 70e9, "density": 2700}}],
        "point_masses": [{"id": "tip", "mass": tip_mass, "position": [length, 0]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0, 0]}, "b": {"beam": "b", "s": 0}},
            {"id": "glue", "type": "pin", "a": {"beam": "b", "s": length}, "b": {"body": "tip"}}
        ],
        "loads": [{"id": "hammer", "at": {"beam": "b", "s": length / 4.0}, "force": [0, 1],
                   "time": {"half_sine": {"duration": 5e-5}}}],
        "sensors": [{"id": "v", "at": {"beam": "b", "s": length}, "quantity": "velocity",
                     "frame": "global", "direction": [0, 1]}]
    });
    ModelInput::parse(&v.to_string(), Source::BuiltIn).unwrap()
}

/// The deviation allowed at `f` [Hz]: 1e-3, plus what the integrator's
/// period error moves each lightly damped mode's flank: generalized-α
/// lowers a mode's frequency by δ = (ω_n h)²/12, which changes a
/// single-mode FRF at f by |ΔH/H| ≈ 2δ f_n²/|f_n² − f²| ≈ δ f_n/|f_n − f|
/// (twice that allowed).
fn allowed(f: f64, modes: &[(f64, f64)], step: f64) -> f64 {
    let shift: f64 = modes
        .iter()
        .filter(|&&(_, z)| z < 1.0 / 6.0)
        .map(|&(fn_, _)| {
            let delta = (2.0 * std::f64::consts::PI * fn_ * step).powi(2) / 12.0;
            2.0 * delta * fn_ / (f - fn_).abs()
        })
        .sum();
    1e-3 + shift
}

/// The worst of a simulated record's comparisons with its model, each as
/// a fraction of what is allowed (under 1 passes).
struct Deviations {
    /// |H1 − H_model| / |H_model| over the lines away from every
    /// resonance and inside the pass band ([`allowed`]).
    h1: f64,
    /// The poles `frf` fits at the resonances: the frequency, the
    /// integrator's period error taken back
    /// ([`GenAlpha::true_frequency_from_observed`]), against the
    /// eigenfrequency within 5e-5 (measured 2.5e-6 … 1.6e-5: a fit on
    /// lines 1 Hz apart), and the damping ratio against the Rayleigh
    /// formula α/(2ω) + βω/2 within 1 % (measured 2e-5 … 3.9e-3).
    poles: f64,
}

fn worst_deviation(input: &ModelInput, request: &ImpulseRequest) -> Deviations {
    let run = impulse(input, request).unwrap();
    let r = &run.result;
    let damping = input.model.damping.unwrap();
    let modes: Vec<(f64, f64)> = r
        .modal
        .modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .map(|m| {
            let w = 2.0 * std::f64::consts::PI * m.frequency_hz;
            (m.frequency_hz, damping.ratio(w))
        })
        .collect();
    let fr = FrfRequest {
        records: FrfRecords::Arrays {
            force: vec![r.force.clone()],
            response: vec![r.signal.clone()],
            fs: r.sample_rate_hz,
        },
        at: Some("v".into()),
        ..FrfRequest::default()
    };
    let out = frf(Some(input), &fr).unwrap();
    let model = out.overlay.expect("the model's FRF").h;
    let a = &out.analysis;
    let pass = 0.4 * r.sample_rate_hz;
    let mut worst = 0.0f64;
    let mut compared = 0;
    for ((f, h), m) in a.frequency_hz.iter().zip(&a.h1).zip(&model) {
        // (a mode damped past ζ = 1/6 has no peak to leave out)
        let near = modes
            .iter()
            .any(|&(fn_, z)| z < 1.0 / 6.0 && (f - fn_).abs() <= 3.0 * 2.0 * z * fn_);
        if *f <= 0.0 || *f > pass || near || !h.re.is_finite() {
            continue;
        }
        compared += 1;
        let e = (h - m).norm() / m.norm();
        worst = worst.max(e / allowed(*f, &modes, request.step));
    }
    assert!(compared > 100, "{compared} lines compared");
    Deviations {
        h1: worst,
        poles: worst_pole(
            r,
            &a.fit.modes,
            a.band,
            (damping.alpha, damping.beta),
            request,
        ),
    }
}

/// The worst identified pole against its model mode, as a fraction of
/// what is allowed ([`Deviations::poles`]); every mode in the fit band is
/// compared with the fitted pole nearest it.
fn worst_pole(
    r: &ImpulseResult,
    fitted: &[FittedMode],
    (lo, hi): (f64, f64),
    (alpha, beta): (f64, f64),
    request: &ImpulseRequest,
) -> f64 {
    let scheme = GenAlpha::from_spectral_radius(request.spectral_radius).unwrap();
    let mut worst = 0.0f64;
    let mut compared = 0;
    for m in r.modal.modes.iter().filter(|m| !m.kind.is_zero()) {
        let (f, w) = (m.frequency_hz, 2.0 * PI * m.frequency_hz);
        if f < lo || f > hi {
            continue;
        }
        let zeta = alpha / (2.0 * w) + beta * w / 2.0;
        let distance = |x: &&FittedMode| (x.frequency_hz - f).abs();
        let found = fitted
            .iter()
            .min_by(|a, b| distance(a).total_cmp(&distance(b)))
            .unwrap_or_else(|| panic!("no pole near {f} Hz"));
        let undamped = scheme
            .true_frequency_from_observed(2.0 * PI * found.frequency_hz, request.step)
            .unwrap()
            / (2.0 * PI);
        compared += 1;
        worst = worst
            .max((undamped / f - 1.0).abs() / 5e-5)
            .max((found.damping_ratio / zeta - 1.0).abs() / 1e-2);
    }
    assert!(compared >= 2, "{compared} modes in the band {lo}..{hi} Hz");
    worst
}

#[test]
fn h1_of_a_damped_strip_is_the_model_frf() {
    let input = strip(0.05, 2e-3, 50.0, 2e-7);
    let request = ImpulseRequest {
        end_time: 1.0,
        sample_rate: 10_240.0,
        ..ImpulseRequest::default()
    };
    let worst = worst_deviation(&input, &request);
    assert!(
        worst.h1 < 1.0,
        "H1 against the model's FRF: {:e} of the allowed",
        worst.h1
    );
    assert!(
        worst.poles < 1.0,
        "the poles against the model's: {:e} of the allowed",
        worst.poles
    );
}

proptest! {
    #![proptest_config(common::fixed_cases(3, "ACQUISITION_SEED", 35))]

    #[test]
    fn h1_is_the_model_frf_on_generated_strips(
        length in 0.03f64..0.12,
        tip in 1e-4f64..5e-3,
        zeta_scale in 0.5f64..2.0,
    ) {
        let input = strip(length, tip, 50.0 * zeta_scale, 2e-7 * zeta_scale);
        let request = ImpulseRequest {
            end_time: 1.0,
            sample_rate: 10_240.0,
            ..ImpulseRequest::default()
        };
        let worst = worst_deviation(&input, &request);
        prop_assert!(worst.h1 < 1.0, "H1 against the model's FRF: {:e} of the allowed", worst.h1);
        prop_assert!(worst.poles < 1.0, "the poles against the model's: {:e} of the allowed", worst.poles);
    }
}
