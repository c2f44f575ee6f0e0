//! The paper's Fig. 10 study (`switch-off --fig10`, issue 38) on the
//! built-in switch-off model: the pre-stress doubled, c_t lowered to
//! 1 N m/rad and the spring's ground point moved −1 mm in y, each alone and
//! all three together.
//!
//! Checked against an independent path: each changed model is written
//! here by editing the model file's JSON (F_x² and the spring's preload
//! ×2, the joint's torsion stiffness, the ground point's y), not through
//! the sweep's parameter texts the study uses, and run by `switch-off`
//! itself. The ratios are recomputed from those runs. Physics: doubling
//! the pre-stress doubles the opening moment about the pin at the release
//! (the released force and the spring's preload, both ×2), so the blade
//! reaches 2 mm sooner (t ≈ √(2θJ/M) for a lever; `tests/switch_off.rs`
//! checks that the time moves against the moment).

use ancf_modal::analysis::switch_off_study::{
    SwitchOffStudy, PAPER_COMBINED_RATIO, PAPER_COMBINED_TIME_S,
};
use ancf_modal::commands::report::ReportRequest;
use ancf_modal::commands::switch_off::{run, SwitchOffRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::error::Source;
use ancf_modal::model::SWITCH_OFF_MODEL_JSON;
use ancf_modal::Model;
use proptest::prelude::*;
use serde_json::Value;
use std::process::Command;

mod common;

/// The built-in model's file with `edit` applied, as an input.
fn edited(edit: impl Fn(&mut Value)) -> ModelInput {
    let mut v: Value = serde_json::from_str(SWITCH_OFF_MODEL_JSON).unwrap();
    edit(&mut v);
    ModelInput::parse(&v.to_string(), Source::BuiltIn).unwrap()
}

/// The element of `list` (a JSON array of objects) with `id`.
fn by_id<'a>(list: &'a mut Value, id: &str) -> &'a mut Value {
    list.as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|x| x["id"] == id)
        .unwrap_or_else(|| panic!("no `{id}` in the built-in model"))
}

fn times_two(v: &mut Value) {
    *v = Value::from(v.as_f64().unwrap() * 2.0);
}

/// F_x² (both components) and the helical spring's preload doubled.
fn prestress(v: &mut Value) {
    let load = by_id(&mut v["loads"], "F_x2");
    for c in load["force"].as_array_mut().unwrap() {
        times_two(c);
    }
    times_two(&mut by_id(&mut v["springs"], "helical_spring")["preload"]);
}

fn lower_ct(v: &mut Value) {
    by_id(&mut v["joints"], "hybrid")["torsion_stiffness"] = Value::from(1.0);
}

fn lower_attachment(v: &mut Value) {
    let y = &mut by_id(&mut v["springs"], "helical_spring")["a"]["ground"][1];
    *y = Value::from(y.as_f64().unwrap() - 1e-3);
}

/// `switch-off`'s flexible time to 2 mm of `input` (no rigid, no half
/// step: the study's runs).
fn time(input: &ModelInput) -> f64 {
    let request = SwitchOffRequest {
        no_step_check: true,
        ..SwitchOffRequest::default()
    };
    run(input, &request)
        .unwrap()
        .result
        .flexible
        .time_to_distance_s
        .expect("the changed model reaches 2 mm")
}

fn study() -> (f64, SwitchOffStudy, Value) {
    let input = ModelInput::load_switch_off(None).unwrap();
    let request = SwitchOffRequest {
        no_step_check: true,
        fig10: true,
        ..SwitchOffRequest::default()
    };
    let r = run(&input, &request).unwrap();
    let document = serde_json::to_value(&r.document.output).unwrap();
    (
        r.result.flexible.time_to_distance_s.unwrap(),
        r.study.expect("fig10 asked for"),
        document,
    )
}

#[test]
fn fig10_rows_are_switch_off_runs_of_the_changed_models() {
    let (reference, study, document) = study();
    let all = |v: &mut Value| {
        prestress(v);
        lower_ct(v);
        lower_attachment(v);
    };
    let edits: [&dyn Fn(&mut Value); 4] = [&prestress, &lower_ct, &lower_attachment, &all];
    assert_eq!(study.rows.len(), 5, "the reference and four changes");
    let first = &study.rows[0];
    assert_eq!(first.time_to_distance_s, Some(reference));
    assert_eq!(first.ratio_to_reference, Some(1.0));
    let mut times = Vec::new();
    for (row, edit) in study.rows[1..].iter().zip(edits) {
        let t = time(&edited(edit));
        let got = row.time_to_distance_s.expect("every change reaches 2 mm");
        assert!(
            ((got - t) / t).abs() < 1e-9,
            "{}: study {got:e} s, the edited model's switch-off {t:e} s",
            row.change
        );
        let q = row.ratio_to_reference.unwrap();
        assert!(
            (q - t / reference).abs() < 1e-9,
            "{}: ratio {q}, runs give {}",
            row.change,
            t / reference
        );
        assert!(row.error.is_none());
        times.push(t);
    }
    // The combined ratio is the combined run over the reference, printed
    // beside the paper's statement (a prediction, not a fit).
    let combined = study.combined_ratio.unwrap();
    assert!((combined - times[3] / reference).abs() < 1e-9);
    assert_eq!(study.paper_combined_ratio, PAPER_COMBINED_RATIO);
    assert_eq!(study.paper_combined_time_s, PAPER_COMBINED_TIME_S);
    // The study says what its model has fitted: the built-in's one record.
    assert_eq!(study.calibrated, Model::switch_off_builtin().calibrated);
    // Physics: twice the opening moment, sooner at 2 mm.
    assert!(
        times[0] < reference,
        "pre-stress ×2: {:e} s, not before the reference's {reference:e} s",
        times[0]
    );
    // The JSON document carries the same study.
    let fig10 = &document["fig10"];
    assert_eq!(fig10["rows"].as_array().unwrap().len(), 5);
    assert_eq!(fig10["combined_ratio"].as_f64(), Some(combined));
    assert_eq!(
        fig10["rows"][4]["time_to_distance_s"].as_f64(),
        Some(times[3])
    );
    // The HTML report of the built-in model has the study: every row's
    // time and the combined ratio as printed.
    let input = ModelInput::load_switch_off(None).unwrap();
    let report = ancf_modal::commands::report::run(&input, &ReportRequest::default()).unwrap();
    assert!(report.html.contains("The paper&#39;s Fig. 10"));
    for t in std::iter::once(reference).chain(times) {
        let shown = format!("{:.4} ms", t * 1e3);
        assert!(report.html.contains(&shown), "the report lacks {shown}");
    }
    assert!(report
        .html
        .contains(&format!("all three together / reference = {combined:.3}")));
}

#[test]
fn fig10_on_a_model_without_the_ids_is_one_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("renamed.json");
    let mut v: Value = serde_json::from_str(SWITCH_OFF_MODEL_JSON).unwrap();
    by_id(&mut v["loads"], "F_x2")["id"] = Value::from("release");
    std::fs::write(&path, v.to_string()).unwrap();
    let json = dir.path().join("out.csv");
    let out = Command::new(env!("CARGO_BIN_EXE_ancf-modal"))
        .args(["switch-off", "--fig10", "--no-step-check", "--csv"])
        .arg(&json)
        .arg(&path)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.starts_with("warning"))
        .collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(
        lines[0].contains("F_x2") && lines[0].contains("release"),
        "{stderr}"
    );
    assert!(!json.exists(), "no file written on error");
    assert!(out.stdout.is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig {
        failure_persistence: None,
        ..common::fixed_cases(3, "SWITCH_OFF_FIG10_SEED", 38)
    })]

    /// On generated designs of the assembly (c_t, the spring's ground
    /// point's y): the reference row is the switch-off's own time, every
    /// ratio is its row's time over the reference's, the combined ratio is
    /// the last row's, and the doubled pre-stress (twice the opening
    /// moment) reaches the distance sooner.
    #[test]
    fn the_study_is_its_runs_over_the_reference(ct in 2.0f64..20.0, dy in -0.5e-3f64..0.5e-3) {
        let input = edited(|v| {
            by_id(&mut v["joints"], "hybrid")["torsion_stiffness"] = Value::from(ct);
            let y = &mut by_id(&mut v["springs"], "helical_spring")["a"]["ground"][1];
            *y = Value::from(y.as_f64().unwrap() + dy);
        });
        let request = SwitchOffRequest {
            no_step_check: true,
            fig10: true,
            ..SwitchOffRequest::default()
        };
        let r = run(&input, &request).unwrap();
        let study = r.study.unwrap();
        let reference = r.result.flexible.time_to_distance_s.unwrap();
        prop_assert_eq!(study.rows[0].time_to_distance_s, Some(reference));
        for row in &study.rows {
            let t = row.time_to_distance_s.unwrap();
            prop_assert!((row.ratio_to_reference.unwrap() - t / reference).abs() < 1e-12);
        }
        prop_assert_eq!(study.combined_ratio, study.rows[4].ratio_to_reference);
        prop_assert!(study.rows[1].time_to_distance_s.unwrap() < reference);
    }
}
