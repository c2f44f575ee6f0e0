//! Pre-stress is honoured by every command (issue 35): a taut string, a
//! steel wire pinned at one end and tensioned by a dead load T at the
//! other end, which slides along the wire's axis.
//!
//! The reference is the closed form of a pinned-pinned beam under tension,
//! corrected for the stretch: under T the wire is λ = 1 + T/EA times
//! longer and its mass per length ρA/λ, so
//!
//! ```text
//! ω_n² = (k⁴ EI + k² T) / (ρA/λ),   k = nπ/(λL).
//! ```
//!
//! - `impulse` strikes the tensioned equilibrium: its corrected FFT peak is
//!   the pre-stressed eigenvalue (from the reference it was the slack
//!   string's fall into tension);
//! - `calibrate` with `prestress` writes a model whose pre-stressed first
//!   frequency is the target;
//! - a sweep over the load's value linearizes at the equilibrium.

mod common;

use ancf_modal::analysis::statics::start::Start;
use ancf_modal::analysis::statics::{prestress::prestressed_modal, StaticSettings};
use ancf_modal::analysis::sweep::Quantity;
use ancf_modal::analysis::ModalSettings;
use ancf_modal::commands::calibrate::CalibrateRequest;
use ancf_modal::commands::impulse::ImpulseRequest;
use ancf_modal::commands::sweep::SweepRequest;
use ancf_modal::commands::transient::TransientRequest;
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use ancf_modal::model::ValidModel;
use ancf_modal::System;
use proptest::prelude::*;
use serde_json::json;
use std::f64::consts::PI;

const E: f64 = 2e11;
const RHO: f64 = 7850.0;
const SIDE: f64 = 4e-4;
const LENGTH: f64 = 0.65;

/// The string tensioned by `tension` [N], struck at a fifth of its length.
fn string(tension: f64, elements: usize) -> String {
    let v = json!({
        "name": "taut_string",
        "beams": [{"id": "s", "start": [0, 0], "angle_deg": 0, "length": LENGTH,
                   "elements": elements,
                   "section": {"height": SIDE, "width": SIDE},
                   "material": {"young": E, "density": RHO}}],
        "joints": [
            {"id": "nut", "type": "pin", "a": {"ground": [0, 0]}, "b": {"beam": "s", "s": 0}},
            {"id": "bridge", "type": "slider", "a": {"ground": [LENGTH, 0]},
             "b": {"beam": "s", "s": LENGTH}, "axis": [1, 0]}
        ],
        "loads": [
            {"id": "T", "at": {"beam": "s", "s": LENGTH}, "force": [tension, 0]},
            {"id": "pluck", "at": {"beam": "s", "s": LENGTH / 5.0}, "force": [0, 0.5],
             "time": {"half_sine": {"duration": 2e-4}}}
        ],
        "sensors": [{"id": "p", "at": {"beam": "s", "s": LENGTH / 5.0},
                     "quantity": "velocity", "frame": "global", "direction": [0, 1]}]
    });
    v.to_string()
}

fn input(text: String) -> ModelInput {
    ModelInput::parse(&text, Source::BuiltIn).unwrap()
}

/// The closed form above [Hz].
fn closed_form_hz(tension: f64, n: usize) -> f64 {
    let (a, i) = (SIDE * SIDE, SIDE.powi(4) / 12.0);
    let stretch = 1.0 + tension / (E * a);
    let k = n as f64 * PI / (stretch * LENGTH);
    let omega2 = (k.powi(4) * E * i + k * k * tension) / (RHO * a / stretch);
    omega2.sqrt() / (2.0 * PI)
}

/// The first bending frequency at the static equilibrium [Hz].
fn prestressed_hz(m: &ValidModel) -> f64 {
    let r = prestressed_modal(
        &System::new(m),
        &StaticSettings::default(),
        &ModalSettings::default(),
    )
    .unwrap();
    r.prestressed.first_bending().unwrap().frequency_hz
}

#[test]
fn the_closed_form_is_the_prestressed_modal() {
    // The reference of the two tests below: 20 elements meet it to 1.6e-7.
    let m = input(string(80.0, 20)).model;
    let (f, c) = (prestressed_hz(&m), closed_form_hz(80.0, 1));
    assert!(((f - c) / c).abs() < 1e-6, "{f} Hz against {c} Hz");
}

#[test]
fn impulse_strikes_the_tensioned_string() {
    let request = ImpulseRequest {
        step: 2e-5,
        end_time: 0.5,
        sample_rate: 10_000.0,
        ..ImpulseRequest::default()
    };
    let model = string(80.0, 20);
    let run = ancf_modal::commands::impulse::run(&input(model.clone()), &request).unwrap();
    let fb = run.result.first_bending.unwrap();
    let c = closed_form_hz(80.0, 1);
    assert!(run.result.equilibrium_iterations.is_some());
    assert_eq!(fb.eigen_hz, prestressed_hz(&input(model.clone()).model));
    assert!(
        ((fb.corrected_hz - c) / c).abs() < 1e-4,
        "corrected FFT peak {} Hz against the taut string's {c} Hz",
        fb.corrected_hz
    );
    // From the reference the slack string falls into tension: its record
    // is not the vibration about the equilibrium, and the eigenvalue it is
    // compared with is the slack string's.
    // (Short: the sudden tension defeats Newton's iteration at 0.52 ms.)
    let slack = ImpulseRequest {
        start: Start::Reference,
        end_time: 4e-4,
        ..request
    };
    let run = ancf_modal::commands::impulse::run(&input(model), &slack).unwrap();
    assert!(run.result.equilibrium_iterations.is_none());
    let slack_hz = run.result.modal.first_bending().unwrap().frequency_hz;
    assert!(slack_hz < 0.1 * c, "{slack_hz} Hz");
}

#[test]
fn calibrate_prestress_fits_the_tensioned_frequency() {
    let request = CalibrateRequest {
        targets_hz: vec![110.0],
        params: vec![ancf_modal::analysis::calibrate::ParameterSpec {
            name: "density".into(),
            bounds: Some((1.0, 1e5)),
        }],
        prestress: true,
        ..CalibrateRequest::default()
    };
    let run = ancf_modal::commands::calibrate::run(&input(string(80.0, 20)), &request).unwrap();
    assert!(run.result.prestressed);
    assert!(run.document.own_warnings().is_empty());
    let fitted = input(run.fitted_json()).model;
    let f = prestressed_hz(&fitted);
    assert!(((f - 110.0) / 110.0).abs() < 1e-9, "fitted model: {f} Hz");
    // ρ·f² is the same for every density (f ∝ 1/√ρ): the fit lands where
    // the scaling puts it.
    let rho = fitted.beams[0].material.density;
    let f0 = prestressed_hz(&input(string(80.0, 20)).model);
    assert!(((rho * 110.0 * 110.0) / (RHO * f0 * f0) - 1.0).abs() < 1e-8);

    // Without it the fit is the slack string's, and the run says so.
    let unstressed = CalibrateRequest {
        prestress: false,
        ..request.clone()
    };
    let run = ancf_modal::commands::calibrate::run(&input(string(80.0, 20)), &unstressed).unwrap();
    assert!(!run.result.prestressed);
    assert!(run
        .document
        .own_warnings()
        .iter()
        .any(|w| w.contains("pre-stressed")));

    // The slack string's first mode cannot reach 110 Hz by its height:
    // the refusal names the pre-stress.
    let out_of_reach = CalibrateRequest {
        targets_hz: vec![110.0],
        prestress: false,
        ..CalibrateRequest::default()
    };
    let e =
        ancf_modal::commands::calibrate::run(&input(string(80.0, 20)), &out_of_reach).unwrap_err();
    let text = ancf_modal::error::chain_text(&e);
    assert!(
        text.contains("unstressed modes of a pre-stressed model"),
        "{text}"
    );
    // Asked for the pre-stressed fit, an unreachable target is refused
    // without that hint (the trial's pendulum was told its pre-stressed
    // modes were unstressed).
    let stressed_out_of_reach = CalibrateRequest {
        targets_hz: vec![1e6],
        prestress: true,
        ..CalibrateRequest::default()
    };
    let e = ancf_modal::commands::calibrate::run(&input(string(80.0, 20)), &stressed_out_of_reach)
        .unwrap_err();
    let text = ancf_modal::error::chain_text(&e);
    assert!(
        text.contains("out of reach") && !text.contains("unstressed"),
        "{text}"
    );

    // The load's value as the parameter: pre-stressed without asking.
    let by_load = CalibrateRequest {
        targets_hz: vec![150.0],
        params: vec![ancf_modal::analysis::calibrate::ParameterSpec::named(
            "T.force_x",
        )],
        ..CalibrateRequest::default()
    };
    let run = ancf_modal::commands::calibrate::run(&input(string(80.0, 20)), &by_load).unwrap();
    assert!(run.result.prestressed);
    let t = run.result.parameters[0].fitted;
    let c = closed_form_hz(t, 1);
    assert!(((c - 150.0) / 150.0).abs() < 1e-6, "T = {t} N gives {c} Hz");
}

proptest! {
    #![proptest_config(common::fixed_cases(6, "PRESTRESS_TIME_SEED", 35))]

    /// A sweep over the load's value (its JSON path or its short name)
    /// linearizes at the equilibrium: the closed form to 1e-6.
    #[test]
    fn load_value_sweep_is_the_taut_string(
        low in 1.0f64..50.0,
        ratio in 2.0f64..20.0,
        short in any::<bool>(),
    ) {
        let name = if short { "T.force_x" } else { "loads[0].force[0]" };
        let request = SweepRequest {
            params: vec![format!("{name}={low},{}", low * ratio)],
            quantity: Some(Quantity::FirstBendingHz),
            threads: Some(1),
            ..SweepRequest::default()
        };
        let run = ancf_modal::commands::sweep::run(&input(string(80.0, 20)), &request, &|| {})
            .unwrap();
        let doc = &run.document.output;
        prop_assert!(doc.prestress);
        for p in &doc.points {
            let (t, f) = (p.values[0], p.result.unwrap());
            let c = closed_form_hz(t, 1);
            prop_assert!(((f - c) / c).abs() < 1e-6, "T = {} N: {} Hz against {} Hz", t, f, c);
        }
    }
}

#[test]
fn a_sensor_that_cannot_see_the_first_bending_mode_says_where_one_would() {
    // The sensor reads the string's axial velocity: bending moves its
    // points across the string only, so the record holds no bending peak.
    let mut v: serde_json::Value = serde_json::from_str(&string(80.0, 20)).unwrap();
    v["sensors"][0]["direction"] = json!([1, 0]);
    let request = ImpulseRequest {
        step: 2e-5,
        end_time: 0.2,
        sample_rate: 10_000.0,
        ..ImpulseRequest::default()
    };
    let run = ancf_modal::commands::impulse::run(&input(v.to_string()), &request).unwrap();
    let sight = run.result.sight.clone().unwrap();
    assert!(sight.blind(), "{sight:?}");
    assert!(run.result.first_bending.is_none());
    // sin(πx/L) moves most at x = L/2 (a node of the 20-element mesh),
    // across the string.
    assert_eq!(
        sight.best_point,
        format!("beam `s` at s = {:.4e} m", LENGTH / 2.0)
    );
    assert!(sight.best_direction[1].abs() > 1.0 - 1e-9);
    let warned = run
        .document
        .own_warnings()
        .iter()
        .any(|w| w.contains("does not see the first bending mode") && w.contains("beam `s`"));
    assert!(warned, "{:?}", run.document.own_warnings());
    // Across the string at a fifth of its length it sees the mode:
    // sin(π/5) = 0.588 of the largest motion.
    let run = ancf_modal::commands::impulse::run(&input(string(80.0, 20)), &request).unwrap();
    let sight = run.result.sight.unwrap();
    assert!((sight.ratio - (PI / 5.0).sin()).abs() < 1e-3, "{sight:?}");
    assert!(run.result.first_bending.is_some());
}

#[test]
fn a_transient_that_fails_keeps_what_it_computed() {
    // The slack string jerked into tension from the reference defeats
    // Newton's iteration within the first millisecond at 20 µs steps.
    let h = 2e-5;
    let request = TransientRequest {
        step: h,
        end_time: 0.01,
        start: Start::Reference,
        sample_rate: 0.0,
        ..TransientRequest::default()
    };
    let run = ancf_modal::commands::transient::run(&input(string(80.0, 20)), &request).unwrap();
    let sim = &run.simulation;
    let failure = sim.failure.clone().expect("the run stops early");
    let last = *sim.step_time.last().unwrap();
    assert!(last < 0.01);
    assert_eq!(*sim.time.last().unwrap(), last, "every accepted step kept");
    let ancf_modal::error::TransientError::NewtonFailure { time, .. } = failure else {
        panic!("{failure:?}")
    };
    assert!(
        ((time - (last + h)) / h).abs() < 1e-9,
        "failed at {time}, last accepted {last}"
    );
    let doc = run.document.document();
    assert_eq!(doc["ended_at_s"].as_f64(), Some(last));
    assert!(run
        .document
        .own_warnings()
        .iter()
        .any(|w| w.contains("stopped early")));
    // From the equilibrium (the default) the same string runs to the end.
    let settled = TransientRequest {
        start: Start::Equilibrium,
        end_time: 0.002,
        ..request
    };
    let run = ancf_modal::commands::transient::run(&input(string(80.0, 20)), &settled).unwrap();
    assert!(run.simulation.failure.is_none());
}

#[test]
fn plain_modal_of_the_tensioned_string_says_it_left_the_tension_out() {
    use ancf_modal::commands::modal::{run, ModalRequest};
    let text = string(80.0, 20);
    let plain = run(&input(text.clone()), &ModalRequest::default()).unwrap();
    let said: Vec<&String> = plain
        .document
        .own_warnings()
        .iter()
        .filter(|w| w.contains("constant loads") && w.contains("8.000e1 N"))
        .collect();
    assert_eq!(said.len(), 1, "{:?}", plain.document.own_warnings());
    let prestressed = ModalRequest {
        prestress: true,
        ..ModalRequest::default()
    };
    let run = run(&input(text), &prestressed).unwrap();
    assert!(!run
        .document
        .own_warnings()
        .iter()
        .any(|w| w.contains("constant loads")));
}
