//! Released supports (`"release"` on a pin or slider): the joint holds in
//! the static equilibrium and its reaction becomes a load that falls with
//! the release function in the transient. Checked on a mass held against a
//! compressed spring, whose released motion has closed forms:
//!
//! - reaction at the equilibrium: the spring's preload P (statics);
//! - `{"until": 0}`: u(t) = (P/k)(1 − cos ωt), ω = √(k/m);
//! - `{"ramp_down": {"start": 0, "duration": T}}`: m ü = P t/T − k u, so
//!   u(t) = (P/k)(t/T − sin(ωt)/(ωT)) for t ≤ T;
//!
//! plus the one-line errors of a weld released and of a transient that
//! does not start from the equilibrium.

mod common;
use ancf_modal::analysis::simulate::{simulate, SimulationSettings};
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::analysis::transient::TransientSettings;
use ancf_modal::model::PointSpec;
use ancf_modal::model::ValidModel;
use ancf_modal::System;
use assert_cmd::Command;
use common::model;
use serde_json::{json, Value};

const MASS: f64 = 0.01; // kg
const K: f64 = 1.0e4; // N/m
const PRELOAD: f64 = 5.0; // N of compression
const STEP: f64 = 2.0e-6; // s; ω h = 2e-3

/// A 10 g mass at the origin, pushed along +x by a spring compressed by
/// `PRELOAD` from the ground at (−10 mm, 0), held by `latch`.
fn latched(latch: Value) -> Value {
    json!({
        "name": "latched_mass",
        "point_masses": [{"id": "m", "mass": MASS, "position": [0.0, 0.0]}],
        "joints": [latch, {"id": "rail", "type": "slider", "a": {"ground": [0.0, 0.0]},
                   "b": {"body": "m"}, "axis": [1.0, 0.0]}],
        "springs": [{"id": "push", "a": {"ground": [-0.01, 0.0]}, "b": {"body": "m"},
                     "stiffness": K, "preload": -PRELOAD}]
    })
}

fn pin_latch(release: Value) -> Value {
    json!({"id": "latch", "type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"body": "m"},
           "release": release})
}

/// A slider on a vertical ground rail: it holds x only.
fn slider_latch(release: Value) -> Value {
    json!({"id": "latch", "type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"body": "m"},
           "axis": [0.0, 1.0], "release": release})
}

/// The mass's x at every step, from the equilibrium, without numerical
/// damping.
fn run(m: &ValidModel, end_time: f64) -> (Vec<f64>, Vec<f64>) {
    let sys = System::new(m);
    let spec = PointSpec {
        body: Some("m".into()),
        ..PointSpec::default()
    };
    let anchor = sys.anchor_of(&m.resolve_point(&spec, "point").unwrap());
    let settings = SimulationSettings {
        transient: TransientSettings {
            step: STEP,
            end_time,
            spectral_radius: 1.0,
            ..TransientSettings::default()
        },
        start: ancf_modal::analysis::statics::start::Start::Equilibrium,
        sample_rate: 0.0,
        keep_partial: false,
    };
    let sim = simulate(sys, &[anchor], &settings).unwrap();
    let [x, _] = sim.step_points.into_iter().next().unwrap();
    (sim.step_time, x)
}

fn omega() -> f64 {
    (K / MASS).sqrt()
}

#[test]
fn the_static_reaction_of_a_latch_is_the_spring_preload() {
    for latch in [
        pin_latch(json!({"until": 0.0})),
        slider_latch(json!({"until": 0.0})),
    ] {
        let m = model(latched(latch));
        let sys = System::new(&m);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).unwrap();
        let c = &sys.constraints[0];
        let row = sys.constraint_rows[0];
        let latch = &sys.released[0];
        assert_eq!(latch.constraint, 0);
        let f = latch
            .joint
            .point_reaction(&eq.q, &eq.lambda[row..row + c.rows()]);
        // The latch pulls the mass back against the spring's push.
        assert!(
            (f.x + PRELOAD).abs() < 1e-9 * PRELOAD && f.y.abs() < 1e-9 * PRELOAD,
            "latch force on the mass {f:?} N vs (−{PRELOAD}, 0)"
        );
        assert!(eq.q[0].abs() < 1e-12, "the latch holds the mass at x = 0");
    }
}

#[test]
fn an_instant_release_oscillates_about_the_free_length() {
    let w = omega();
    let period = 2.0 * std::f64::consts::PI / w;
    for latch in [
        pin_latch(json!({"until": 0.0})),
        slider_latch(json!({"until": 0.0})),
    ] {
        let (t, x) = run(&model(latched(latch)), 1.5 * period);
        let amp = PRELOAD / K;
        let err = |delay: f64| {
            t.iter()
                .zip(&x)
                .map(|(&t, &x)| (x - amp * (1.0 - (w * (t - delay).max(0.0)).cos())).abs())
                .fold(0.0, f64::max)
        };
        // The run starts from the released system's acceleration (the
        // loads at t → 0⁺), so the release is not late: what is left is
        // the trapezoidal rule's phase error ≈ (ωh)²/12 per radian (~2e-6
        // of the amplitude over 1.5 periods); a start at a = 0 would lag
        // by h/2, an error of (P/k)ωh/2 = 1e-3 of it.
        assert!(
            err(0.0) < 1e-5 * amp,
            "released mass: max |x − (P/k)(1 − cos ωt)| = {:.3e} m vs 1e-5 of {amp:.3e} m",
            err(0.0)
        );
    }
}

#[test]
fn a_ramped_release_follows_the_forced_response() {
    let w = omega();
    let ramp = 4.0 * 2.0 * std::f64::consts::PI / w;
    let m = model(latched(slider_latch(
        json!({"ramp_down": {"start": 0.0, "duration": ramp}}),
    )));
    let (t, x) = run(&m, ramp);
    let amp = PRELOAD / K;
    let err = t
        .iter()
        .zip(&x)
        .map(|(&t, &x)| (x - amp * (t / ramp - (w * t).sin() / (w * ramp))).abs())
        .fold(0.0, f64::max);
    assert!(
        err < 1e-5 * amp,
        "ramp release: max |x − (P/k)(t/T − sin ωt/(ωT))| = {err:.3e} m vs 1e-5 of {amp:.3e} m"
    );
    // At the end of the ramp (ωT = 8π) the hold is gone and u(T) = P/k exactly.
    let last = *x.last().unwrap();
    assert!(
        (last - amp).abs() < 1e-5 * amp,
        "x(T) = {last:.3e} vs P/k = {amp:.3e}"
    );
}

fn bin() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

fn one_line_error(file_json: &Value, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.json");
    std::fs::write(&path, file_json.to_string()).unwrap();
    let out = bin().args(args).arg(&path).assert().code(1);
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(err.starts_with("Error: "), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

#[test]
fn a_released_weld_and_a_transient_from_the_reference_are_refused() {
    let weld = json!({
        "name": "released_weld",
        "rigid_bodies": [{"id": "r", "mass": MASS, "inertia": 1e-6, "position": [0.0, 0.0]}],
        "joints": [{"type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"body": "r"},
                    "release": {"until": 0.0}}]
    });
    let err = one_line_error(&weld, &["static"]);
    assert!(err.contains("joints[0].release"), "{err}");
    let err = one_line_error(
        &latched(pin_latch(json!({"until": 0.0}))),
        &["transient", "--from-reference"],
    );
    assert!(
        err.contains("latch") && err.contains("--from-reference"),
        "{err}"
    );
    let constant = latched(pin_latch(json!("constant")));
    let err = one_line_error(&constant, &["static"]);
    assert!(err.contains("joints[0].release"), "{err}");
}
