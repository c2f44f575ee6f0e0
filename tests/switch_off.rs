//! The switch-off experiment: rigid beams against the flexible ones (mass,
//! centre, inertia, and the E → ∞ limit), the spring attachment's effect,
//! and the `switch-off` / `transient` command lines (the built-in model's
//! prediction is in `switch_off_prediction.rs`).

mod common;
use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings, HALF_STEP_TOLERANCE};
use ancf_modal::model::ValidModel;
use ancf_modal::model::{Contact, Model};
use ancf_modal::System;
use assert_cmd::Command;
use common::model;
use serde_json::{json, Value};

/// A beam hanging from a pin with a torsion spring, held turned by a tip
/// load that is released at t = 0.
fn pendulum(rigid: bool, young: f64) -> ValidModel {
    model(json!({
        "name": "pendulum",
        "beams": [{"id": "b", "start": [0.0, 0.0], "angle_deg": -90.0, "length": 0.05,
                   "elements": 6, "rigid": rigid,
                   "section": {"height": 1e-3, "width": 4e-3},
                   "material": {"young": young, "density": 7800.0}}],
        "joints": [{"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0},
                    "torsion_stiffness": 1.0}],
        "loads": [{"at": {"beam": "b", "s": 0.05}, "force": [2.0, 0.0], "time": {"until": 0.0}}]
    }))
}

/// q̇ of a rigid rotation at rate ω about the model's origin (the system
/// works about the centre of mass, `sys.origin` in the model's frame).
fn spin(sys: &System, omega: f64) -> Vec<f64> {
    let q = &sys.q0;
    let o = [sys.origin.x, sys.origin.y];
    let mut v = vec![0.0; sys.ndof()];
    for b in &sys.beams {
        for k in 0..b.node_count() {
            let i = b.dof0 + 4 * k;
            v[i] = -omega * (q[i + 1] + o[1]);
            v[i + 1] = omega * (q[i] + o[0]);
            v[i + 2] = -omega * q[i + 3];
            v[i + 3] = omega * q[i + 2];
        }
    }
    for r in &sys.rigid_bodies {
        let i = r.dof0;
        v[i] = -omega * (q[i + 1] + o[1]);
        v[i + 1] = omega * (q[i] + o[0]);
        v[i + 2] = omega;
    }
    v
}

#[test]
fn a_rigid_beam_has_the_mass_centre_and_inertia_of_the_flexible_one() {
    let flexible = System::new(&pendulum(false, 2e11));
    let rigid = System::new(&pendulum(true, 2e11));
    let m_f = flexible.total_mass();
    let m_r = rigid.total_mass();
    assert!(((m_r - m_f) / m_f).abs() < 1e-14, "mass {m_r} vs {m_f}");
    // A rigid rotation ω about the origin: p = m ω × c gives the centre,
    // L = I_O ω the inertia.
    let (p_f, l_f) = flexible.momentum(&flexible.q0, &spin(&flexible, 2.0));
    let (p_r, l_r) = rigid.momentum(&rigid.q0, &spin(&rigid, 2.0));
    assert!(p_f.norm() > 0.0);
    assert!(
        (p_r - p_f).norm() <= 1e-12 * p_f.norm(),
        "momentum {p_r} vs {p_f}: the centres differ"
    );
    assert!(
        ((l_r - l_f) / l_f).abs() < 1e-12,
        "angular momentum {l_r} vs {l_f}: the inertias differ"
    );
}

#[test]
fn a_stiffening_flexible_release_converges_to_the_rigid_one() {
    let settings = SwitchOffSettings {
        end_time: 3e-3,
        step: 1e-6,
        distance: 4e-3,
        direction: [-1.0, 0.0],
        point: Some(ancf_modal::model::PointSpec {
            beam: Some("b".into()),
            s: Some(0.05),
            ..Default::default()
        }),
        ..SwitchOffSettings::default()
    };
    let time = |m: &ValidModel| {
        run_switch_off(m, &settings)
            .unwrap()
            .flexible
            .time_to_distance_s
            .expect("the tip travels 4 mm back")
    };
    let rigid = time(&pendulum(true, 2e11));
    let errors: Vec<f64> = [2e11, 2e12, 2e13]
        .iter()
        .map(|&e| ((time(&pendulum(false, e)) - rigid) / rigid).abs())
        .collect();
    assert!(
        errors[1] < errors[0] && errors[2] < errors[1],
        "the flexible time approaches the rigid one as E grows: {errors:?}"
    );
    assert!(
        errors[2] < 1e-2,
        "E = 2e13 Pa: {:.2e} from the rigid time",
        errors[2]
    );
}

fn bin() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

#[test]
fn switch_off_json_has_the_designed_keys() {
    let out = bin()
        .args(["switch-off", "--compare-rigid", "--no-step-check", "--json"])
        .assert()
        .success();
    let doc: Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    for key in [
        "model",
        "distance_m",
        "time_to_distance_s",
        "node0",
        "max_penetration_m",
        "energy",
        "rigid",
    ] {
        assert!(doc.get(key).is_some(), "key `{key}` missing");
    }
    let n = doc["node0"]["time_s"].as_array().unwrap().len();
    assert_eq!(doc["node0"]["x_m"].as_array().unwrap().len(), n);
    // 3 ms at the camera's 67.2 kHz.
    assert_eq!(n, (3e-3f64 * 67.2e3).floor() as usize + 1);
    assert!(doc["rigid"]["time_to_distance_s"].is_number());
    assert!(doc["rigid"]["departure_s"].is_number());
    // In y alone the paths can part no earlier than in the plane (|Δy| ≤
    // |Δ|), and the departure in y is the first camera sample where the
    // two runs' y displacements are 0.1 mm apart (recomputed here from the
    // samples).
    let (plane, in_y) = (
        doc["rigid"]["departure_s"].as_f64().unwrap(),
        doc["rigid"]["departure_y_s"].as_f64().unwrap(),
    );
    assert!(in_y >= plane, "y {in_y:e} before the plane {plane:e}");
    let ys = |v: &Value| -> Vec<f64> {
        let y: Vec<f64> = v["y_m"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        y.iter().map(|&v| v - y[0]).collect()
    };
    let (fy, ry) = (ys(&doc["node0"]), ys(&doc["rigid"]["node0"]));
    let k = (0..n)
        .find(|&k| (fy[k] - ry[k]).abs() > 0.05 * 2e-3)
        .unwrap();
    assert_eq!(doc["node0"]["time_s"][k].as_f64().unwrap(), in_y);
    // One number of the built-in model is a fit, where F_x² acts, and the
    // document says so with its value in the model.
    let model = ancf_modal::Model::switch_off_builtin();
    let calibrated = doc["calibrated"].as_array().unwrap();
    assert_eq!(calibrated.len(), 1, "{calibrated:?}");
    assert_eq!(calibrated[0]["name"], "loads[0].at.s");
    assert_eq!(calibrated[0]["value"].as_f64(), model.loads[0].at.s);
    assert!(doc["uncalibrated"]["time_to_distance_s"].is_number());
    assert!(doc["paper"]["time_to_distance_s"].is_number());
    assert_eq!(doc["tracked_point"], "node 0 of blade");
    // Contact forces and the released load at the sample times.
    for c in doc["contacts"].as_array().unwrap() {
        assert_eq!(c["force_n"].as_array().unwrap().len(), n, "{}", c["id"]);
    }
    let fx2 = doc["released_loads"]["F_x2"].as_array().unwrap();
    assert_eq!(fx2.len(), n);
    assert_eq!(fx2[0], 11.77, "F_x² (Table 4) acts in the ON state");
    assert!(fx2[1..].iter().all(|f| f == 0.0), "and is gone after t = 0");
    // Provenance: the built-in switch-off assembly is models/rcbo_switch_off.json.
    use sha2::Digest;
    let sha: String = sha2::Sha256::digest(std::fs::read("models/rcbo_switch_off.json").unwrap())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(doc["model_sha256"], sha.as_str());
    assert_eq!(doc["tool_version"], env!("CARGO_PKG_VERSION"));
}

#[test]
fn transient_json_reports_sensors_and_contacts() {
    let out = bin()
        .args([
            "transient",
            "models/rcbo_switch_off.json",
            "--from-equilibrium",
            "--end-time",
            "5e-4",
            "--json",
        ])
        .assert()
        .success();
    let doc: Value = serde_json::from_slice(&out.get_output().stdout).unwrap();
    let n = doc["time_s"].as_array().unwrap().len();
    assert_eq!(doc["sensors"]["node0_x"].as_array().unwrap().len(), n);
    let c = &doc["contacts"][0];
    assert_eq!(c["id"], "pin_in_slot");
    assert!(
        c["max_penetration_m"].as_f64().unwrap() > 0.0,
        "the ON state presses the pin"
    );
    assert!(c["impacts"].is_number() && c["max_force_n"].is_number());
    // Each contact's normal force at the sample times; the pad's starts at
    // the ON state's F_c (Table 4: 2.92 N) and falls to 0 as it opens.
    let pad = &doc["contacts"][1];
    assert_eq!(pad["id"], "fixed_contact");
    let f: Vec<f64> = serde_json::from_value(pad["force_n"].clone()).unwrap();
    assert_eq!(f.len(), n);
    assert!(((f[0] - 2.92) / 2.92).abs() < 0.01, "ON pad force {}", f[0]);
    assert_eq!(*f.last().unwrap(), 0.0, "open after 0.5 ms");
}

#[test]
fn bad_switch_off_settings_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("x.csv");
    let out = bin()
        .args(["switch-off", "--distance", "0", "--csv"])
        .arg(&csv)
        .assert()
        .code(1);
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        err.starts_with("Error: ") && err.contains("--distance"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(!csv.exists(), "no output file on error");
    let out = bin()
        .args(["switch-off", "--point", "nope:0.0"])
        .assert()
        .code(1);
    let err = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(err.contains("--point") && err.contains("nope"), "{err}");
}

/// The ON-state moment about the contact pin of the helical spring's force
/// on the blade [N m, counter-clockwise = opening], from the model's
/// geometry with the spring's ground point moved by `dy`: the spring's
/// tension k (L − L_f) along the line to the ground point, L_f from the
/// preload at the reference length.
fn spring_opening_moment(m: &ValidModel, dy: f64) -> f64 {
    let blade = &m.beams[0];
    let spring = &m.springs[0];
    let s = spring.b.s.unwrap();
    let (sin, cos) = blade.angle_deg.to_radians().sin_cos();
    let b = [blade.start[0] + s * cos, blade.start[1] + s * sin];
    let g0 = spring.a.ground.unwrap();
    let pin = match &m.contacts[0] {
        Contact::PinSlot { pin, .. } => pin.ground.unwrap(),
        other => panic!("the built-in contact is a pin in a slot, not {other:?}"),
    };
    let len = |g: [f64; 2]| (b[0] - g[0]).hypot(b[1] - g[1]);
    let free = len(g0) - spring.preload.unwrap() / spring.stiffness;
    let g = [g0[0], g0[1] + dy];
    let l = len(g);
    let tension = spring.stiffness * (l - free);
    let f = [tension * (g[0] - b[0]) / l, tension * (g[1] - b[1]) / l];
    (b[0] - pin[0]) * f[1] - (b[1] - pin[1]) * f[0]
}

#[test]
fn moving_the_spring_attachment_moves_the_switch_off_time_against_its_opening_moment() {
    // Fig. 10's third panel: the spring's ground point 0 → ±1 mm in y. The
    // fixed contact takes what the changed spring leaves in each ON state;
    // the spring's opening moment about the pin, computed here from the
    // geometry alone, orders the times.
    let base = Model::switch_off_builtin();
    let mut runs = Vec::new();
    for dy in [-1e-3, 0.0, 1e-3] {
        let mut m = base.to_model();
        let g = m.springs[0].a.ground.as_mut().unwrap();
        g[1] += dy;
        let m = m.validated().expect("a valid design");
        let t = run_switch_off(&m, &SwitchOffSettings::default())
            .unwrap()
            .flexible
            .time_to_distance_s
            .expect("2 mm reached");
        runs.push((dy, spring_opening_moment(&base, dy), t));
    }
    for w in runs.windows(2) {
        let ((dy0, m0, t0), (dy1, m1, t1)) = (w[0], w[1]);
        assert!(
            m0 > 0.0 && m1 > 0.0,
            "the spring opens: {m0:.4e}, {m1:.4e} N m"
        );
        assert!(
            (m1 - m0) * (t1 - t0) < 0.0,
            "attachment {dy0:+.0e} → {dy1:+.0e} m: opening moment {m0:.5e} → {m1:.5e} N m but time to 2 mm {t0:.6e} → {t1:.6e} s"
        );
    }
}

/// The re-check of issue 33: with the spring's blade end moved to 15 mm,
/// the tracked point turns back after 0.1895 mm. Asked for 0.19 mm, the
/// run said "not reached" while the half-step run printed 1.3386 ms, with
/// no word. Over distances up to just past the point's largest travel,
/// every answer is consistent or warned: whenever exactly one of the two
/// runs reaches the distance, or their times differ by more than 1e-3 (the
/// README's own check of the built-in run), a warning names the half step;
/// and a result without that warning has both times within 1e-3 or
/// neither.
#[test]
fn a_half_step_run_that_disagrees_is_said() {
    let mut m = Model::switch_off_builtin().to_model();
    m.springs[0].b.s = Some(0.015);
    let m = m.validated().expect("a valid design");
    let probe = run_switch_off(&m, &SwitchOffSettings::default()).expect("the run");
    assert!(
        probe.flexible.time_to_distance_s.is_none(),
        "2 mm is out of reach"
    );
    let peak = probe.flexible.max_travel_m([1.0, 0.0]);
    let mut warned = 0;
    for fraction in [0.5, 0.9, 0.99, 0.999, 0.9995, 1.0005, 1.002, 1.01] {
        let settings = SwitchOffSettings {
            distance: fraction * peak,
            halve_step: true,
            ..SwitchOffSettings::default()
        };
        let r = run_switch_off(&m, &settings).expect("the run");
        let half_step = r.warnings.iter().any(|w| w.contains("half the step"));
        let consistent = match (r.flexible.time_to_distance_s, r.half_step_time_s) {
            (Some(a), Some(b)) => ((b - a) / a).abs() <= HALF_STEP_TOLERANCE,
            (None, None) => true,
            _ => false,
        };
        assert_eq!(
            half_step, !consistent,
            "distance {fraction} × peak: times {:?} and {:?} at half the step, warnings {:?}",
            r.flexible.time_to_distance_s, r.half_step_time_s, r.warnings
        );
        warned += usize::from(half_step);
    }
    // The distances within the step's error of the peak do disagree.
    assert!(warned > 0, "no distance near the peak was warned");
}
