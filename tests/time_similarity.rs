//! Similarity of the time domain (issue 35, `DESIGN.md` §10): scale every
//! length of an assembly by λ, point masses by λ³, inertias by λ⁵, forces
//! by λ² (density and Young's modulus unchanged, so stresses are the
//! same), and the time step, the end time and the pulse by λ. Newton's
//! second law then holds for the scaled motion x(t) = λ·x₁(t/λ): a
//! velocity record is the same at every scale, a displacement scales by λ,
//! a frequency by 1/λ. Checked for `transient`, `static`, `impulse` and
//! `sweep` on a proof mass on two clamped beams (a MEMS resonator at
//! λ ~ 1e-2, a 15 m structure at 1e3), to 1e-9 of the record's largest
//! value.
//!
//! The MEMS resonator itself (1.9e-9 kg, 1.24e-17 kg m², silicon beams
//! 150 × 3 × 20 µm) is a fixed case: its iteration matrix was once
//! refused as singular at every step from 1e-6 to 1e-9 s; its impulse's
//! corrected FFT peak meets `modal`'s first frequency.

use ancf_modal::commands::impulse::{run as impulse, ImpulseRequest};
use ancf_modal::commands::statics::{run as statics, StaticRequest};
use ancf_modal::commands::transient::{run as transient, TransientRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use proptest::prelude::*;

mod common;

/// The proof mass on two clamped beams, at scale `lambda` of a 15 mm
/// device (λ = 0.01: the MEMS resonator); its load is a half-sine of
/// 2 µs·λ·100, or constant.
fn resonator(lambda: f64, constant: bool) -> ModelInput {
    let k = 100.0 * lambda;
    let (l, gap, h, w) = (150e-6 * k, 10e-6 * k, 3e-6 * k, 20e-6 * k);
    let (mass, inertia) = (1.9e-9 * k.powi(3), 1.24e-17 * k.powi(5));
    let force = 1e-6 * k * k;
    let time = if constant {
        r#""constant""#.to_string()
    } else {
        format!(r#"{{"half_sine": {{"duration": {:e}}}}}"#, 2e-6 * k)
    };
    let beam = |id: &str, x0: f64| {
        format!(
            r#"{{"id": "{id}", "start": [{x0:e}, 0.0], "angle_deg": 0.0, "length": {l:e}, "elements": 4,
              "section": {{"height": {h:e}, "width": {w:e}}}, "material": {{"young": 169e9, "density": 2330.0}}}}"#
        )
    };
    let text = format!(
        r#"{{"name": "resonator", "beams": [{}, {}],
  "rigid_bodies": [{{"id": "mass", "mass": {mass:e}, "inertia": {inertia:e}, "position": [0.0, 0.0]}}],
  "joints": [
    {{"id": "cl", "type": "weld", "a": {{"ground": [{xl:e}, 0.0]}}, "b": {{"beam": "left", "s": 0.0}}}},
    {{"id": "cr", "type": "weld", "a": {{"ground": [{xr:e}, 0.0]}}, "b": {{"beam": "right", "s": {l:e}}}}},
    {{"id": "ml", "type": "weld", "a": {{"beam": "left", "s": {l:e}}}, "b": {{"body": "mass"}}}},
    {{"id": "mr", "type": "weld", "a": {{"beam": "right", "s": 0.0}}, "b": {{"body": "mass"}}}}],
  "loads": [{{"id": "hit", "at": {{"body": "mass"}}, "frame": "global", "force": [0.0, {force:e}], "time": {time}}}],
  "sensors": [{{"id": "v", "at": {{"body": "mass"}}, "quantity": "velocity", "frame": "global", "direction": [0.0, 1.0]}},
              {{"id": "y", "at": {{"beam": "left", "s": {half:e}}}, "quantity": "displacement", "frame": "global", "direction": [0.0, 1.0]}}]}}"#,
        beam("left", -(gap + l)),
        beam("right", gap),
        xl = -(gap + l),
        xr = gap + l,
        half = 0.5 * l,
    );
    ModelInput::parse(&text, Source::BuiltIn).unwrap()
}

/// The sensors' records of 200 steps of λ·1e-6 s (a few periods of the
/// first mode at λ = 0.01).
fn records(lambda: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
    let k = 100.0 * lambda;
    let request = TransientRequest {
        step: 1e-7 * k,
        end_time: 2e-5 * k,
        sample_rate: 0.0,
        ..TransientRequest::default()
    };
    let run = transient(&resonator(lambda, false), &request).unwrap();
    let s = run.simulation;
    (s.time, s.sensors.into_iter().map(|(_, v)| v).collect())
}

proptest! {
    #![proptest_config(common::fixed_cases(6, "TIME_SIMILARITY_SEED", 35))]

    #[test]
    fn a_scaled_transient_is_the_same_motion(log_lambda in -4.0f64..3.0) {
        let lambda = 10f64.powf(log_lambda);
        let (t1, r1) = records(1.0);
        let (t, r) = records(lambda);
        prop_assert_eq!(t.len(), t1.len());
        // Times ×λ, velocity ×1, displacement ×λ.
        prop_assert!(common::scaled_off(&t, &t1, lambda) < 1e-12);
        prop_assert!(common::scaled_off(&r[0], &r1[0], 1.0) < 1e-9, "velocity off by {:e}", common::scaled_off(&r[0], &r1[0], 1.0));
        prop_assert!(common::scaled_off(&r[1], &r1[1], lambda) < 1e-9, "displacement off by {:e}", common::scaled_off(&r[1], &r1[1], lambda));
    }

    #[test]
    fn a_scaled_static_deflection_scales_with_the_length(log_lambda in -4.0f64..3.0) {
        let lambda = 10f64.powf(log_lambda);
        let q = |lambda: f64| {
            let run = statics(&resonator(lambda, true), &StaticRequest::default()).unwrap();
            run.equilibrium.q.clone()
        };
        let (q1, q) = (q(1.0), q(lambda));
        // The body's deflection y (its coordinates are the last three:
        // x, y, angle; x and the angle are zero by symmetry).
        let (y1, y) = (q1[q1.len() - 2], q[q.len() - 2]);
        prop_assert!(y1.abs() > 0.0, "the load deflects the body");
        prop_assert!((y - y1 * lambda).abs() <= 1e-9 * (y1 * lambda).abs(), "{y:e} against {:e}", y1 * lambda);
    }
}

#[test]
fn the_mems_resonators_impulse_meets_its_first_frequency() {
    let input = resonator(0.01, false);
    let request = ImpulseRequest {
        step: 2e-7,
        end_time: 0.004,
        sample_rate: 500_000.0,
        ..ImpulseRequest::default()
    };
    let run = impulse(&input, &request).unwrap();
    let first = run.result.first_bending.expect("the first bending peak");
    let eigen = run.result.modal.modes[0].frequency_hz;
    assert!(
        ((first.corrected_hz - eigen) / eigen).abs() < 1e-6,
        "corrected {} Hz against the eigenvalue {eigen} Hz",
        first.corrected_hz
    );
}

/// The defaults are the paper's 4.6 kHz contact's: struck with them, the
/// 27 kHz resonator's first mode lies above the 51.2 kHz acquisition's
/// pass band (0.4 f_s = 20.5 kHz), and the run says so and names a rate;
/// at that rate the mode is recorded and identified.
#[test]
fn defaults_that_do_not_fit_the_resonator_are_named_with_a_setting_that_does() {
    let input = resonator(0.01, false);
    let request = ImpulseRequest {
        end_time: 0.004,
        ..ImpulseRequest::default()
    };
    let run = impulse(&input, &request).unwrap();
    let eigen = run.result.modal.first_bending().unwrap().frequency_hz;
    assert!(eigen > 0.4 * request.sample_rate, "{eigen} Hz");
    let warnings = run.document.own_warnings();
    let said = warnings
        .iter()
        .find(|w| w.contains("above the acquisition's pass band"))
        .unwrap_or_else(|| panic!("{warnings:?}"));
    let rate: f64 = said
        .split("a sample rate of ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|v| v.parse().ok())
        .unwrap();
    assert!(rate * 0.4 > eigen, "{rate} Hz suggested for {eigen} Hz");
    let fitting = ImpulseRequest {
        sample_rate: rate,
        ..request
    };
    let run = impulse(&input, &fitting).unwrap();
    assert!(
        run.document.own_warnings().is_empty(),
        "{:?}",
        run.document.own_warnings()
    );
    let first = run.result.first_bending.expect("the first bending peak");
    assert!(
        ((first.corrected_hz - eigen) / eigen).abs() < 1e-5,
        "corrected {} Hz against the eigenvalue {eigen} Hz",
        first.corrected_hz
    );
}

/// The impulse experiment on the resonator at scale λ: step, end time,
/// pulse ×λ and the sample rate ×1/λ (the 27 kHz mode at λ = 0.01
/// recorded at 500 kHz, 400 periods).
fn impulse_at(lambda: f64) -> ancf_modal::analysis::impulse::ImpulseResult {
    let k = 100.0 * lambda;
    let request = ImpulseRequest {
        step: 2e-7 * k,
        end_time: 0.015 * k,
        sample_rate: 5e5 / k,
        ..ImpulseRequest::default()
    };
    impulse(&resonator(lambda, false), &request).unwrap().result
}

proptest! {
    #![proptest_config(common::fixed_cases(3, "TIME_SIMILARITY_SEED", 35))]

    /// `impulse` is similar: the velocity record is the same, the
    /// identified frequency ×1/λ, to 1e-9.
    #[test]
    fn a_scaled_impulse_identifies_the_scaled_frequency(log_lambda in -4.0f64..3.0) {
        let lambda = 10f64.powf(log_lambda);
        let (one, r) = (impulse_at(1.0), impulse_at(lambda));
        prop_assert_eq!(r.signal.len(), one.signal.len());
        prop_assert!(common::scaled_off(&r.signal, &one.signal, 1.0) < 1e-9, "velocity off by {:e}", common::scaled_off(&r.signal, &one.signal, 1.0));
        let (f, f1) = (r.first_bending.unwrap(), one.first_bending.unwrap());
        for (a, b) in [(f.raw_hz, f1.raw_hz), (f.corrected_hz, f1.corrected_hz), (f.eigen_hz, f1.eigen_hz)] {
            prop_assert!((a * lambda - b).abs() <= 1e-9 * b, "{:e} Hz × λ against {:e} Hz", a, b);
        }
    }

    /// `sweep` is similar: a sweep of the beams' Young's modulus (scale
    /// free) gives frequencies ×1/λ at every point, to 1e-9.
    #[test]
    fn a_scaled_sweep_gives_the_scaled_frequencies(log_lambda in -4.0f64..3.0) {
        use ancf_modal::analysis::sweep::Quantity;
        use ancf_modal::commands::sweep::{run as sweep, SweepRequest};
        let lambda = 10f64.powf(log_lambda);
        let request = SweepRequest {
            params: vec!["left.young=100e9:200e9:3".into()],
            quantity: Some(Quantity::Frequency { mode: 1 }),
            threads: Some(1),
            ..SweepRequest::default()
        };
        let at = |lambda: f64| -> Vec<f64> {
            let run = sweep(&resonator(lambda, false), &request, &|| {}).unwrap();
            run.document.output.points.iter().map(|p| p.result.unwrap()).collect()
        };
        let (one, scaled) = (at(1.0), at(lambda));
        for (a, b) in scaled.iter().zip(&one) {
            prop_assert!((a * lambda - b).abs() <= 1e-9 * b, "{:e} Hz × λ against {:e} Hz", a, b);
        }
    }
}
