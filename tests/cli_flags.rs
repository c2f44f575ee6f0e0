//! Flag values a user gets wrong, end to end through the binary: a negative
//! number is read as a value and checked like any other; every range error
//! is one line naming the flag, the value and the allowed range in words
//! (exit code 1, no output file); an unknown id lists the model's ids; a
//! sample rate read from a record's time column prints with the digits its
//! source has.

mod measured_support;

use assert_cmd::cargo::cargo_bin_cmd;
use serde_json::json;
use std::path::Path;

/// Runs the tool in `dir`; (exit code, stdout, stderr).
fn run(dir: &Path, args: &[&str]) -> (Option<i32>, String, String) {
    let out = cargo_bin_cmd!("ancf-modal")
        .current_dir(dir)
        .args(args)
        .output()
        .expect("the binary runs");
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Asserts one `Error: ` line with exit code 1 containing every fragment,
/// nothing on stdout and no `out.svg` drawn; returns the line.
fn fails(args: &[&str], fragments: &[&str]) -> String {
    let dir = tempfile::tempdir().expect("a temp dir");
    let mut all = args.to_vec();
    all.extend(["--plot", "out.svg"]);
    let (code, stdout, stderr) = run(dir.path(), &all);
    assert_eq!(code, Some(1), "{args:?}: exit code 1, stderr {stderr:?}");
    assert!(stdout.is_empty(), "{args:?}: nothing on stdout");
    assert_eq!(stderr.lines().count(), 1, "{args:?}: one line: {stderr:?}");
    assert!(stderr.starts_with("Error: "), "{args:?}: {stderr:?}");
    for f in fragments {
        assert!(stderr.contains(f), "{args:?}: expected {f:?} in {stderr:?}");
    }
    assert!(
        !dir.path().join("out.svg").exists(),
        "{args:?}: no output file"
    );
    stderr
}

#[test]
fn negative_numbers_are_values_checked_against_their_range() {
    fails(
        &["impulse", "--step", "-1e-6"],
        &["--step `-1e-6`", "must be a number > 0"],
    );
    fails(
        &["impulse", "--sample-rate", "-5"],
        &["--sample-rate `-5`", "≥ 0"],
    );
    fails(
        &["transient", "--end-time", "-0.01"],
        &["--end-time `-0.01`", "> 0"],
    );
    fails(
        &["switch-off", "--distance", "-2e-3"],
        &["--distance `-2e-3`", "> 0"],
    );
    fails(
        &["sweep", "--param", "height=1e-3:2e-3:2", "--step", "-1"],
        &["--step `-1`", "> 0"],
    );
}

#[test]
fn ranges_are_stated_in_words() {
    let line = fails(
        &["modal", "--modes", "0"],
        &["--modes `0`", "a whole number ≥ 1"],
    );
    assert!(
        !line.contains("18446744073709551615"),
        "no machine limit as the range: {line}"
    );
    fails(&["modal", "--modes", "-3"], &["--modes `-3`", "≥ 1"]);
    fails(
        &["impulse", "--spectral-radius", "1.5"],
        &["--spectral-radius `1.5`", "from 0 to 1"],
    );
    fails(
        &["transient", "--spectral-radius", "-0.1"],
        &["--spectral-radius `-0.1`", "from 0 to 1"],
    );
    fails(
        &["convergence", "--max-elements", "300"],
        &["--max-elements `300`", "from 2 to 256"],
    );
    fails(
        &["sweep", "--param", "height=1e-3:2e-3:2", "--threads", "0"],
        &["--threads `0`", "≥ 1"],
    );
    fails(
        &["calibrate", "--target", "4600", "--tolerance", "-1"],
        &["--tolerance `-1`", "> 0"],
    );
}

#[test]
fn an_unknown_id_lists_the_models_ids() {
    // The built-in paper assembly: one sensor `vibrometer`, one beam
    // `blade`, the rigid body `slot` and the point mass `pad`.
    fails(
        &["impulse", "--sensor", "tipp"],
        &["no sensor `tipp`", "vibrometer"],
    );
    let dir = tempfile::tempdir().expect("a temp dir");
    let model = json!({
        "name": "two beams",
        "beams": [
            {"id": "left", "start": [0.0, 0.0], "angle_deg": 0.0, "length": 0.02, "elements": 2,
             "section": {"height": 1e-3, "width": 5e-3},
             "material": {"young": 2.1e11, "density": 7850.0}},
            {"id": "right", "start": [0.02, 0.0], "angle_deg": 0.0, "length": 0.02, "elements": 2,
             "section": {"height": 1e-3, "width": 5e-3},
             "material": {"young": 2.1e11, "density": 7850.0}}
        ],
        "joints": [{"type": "weld", "a": {"beam": "left", "s": 0.02}, "b": {"beam": "rigth", "s": 0.0}}]
    });
    let path = dir.path().join("m.json");
    std::fs::write(&path, model.to_string()).unwrap();
    let (code, _, stderr) = run(dir.path(), &["modal", "m.json"]);
    assert_eq!(code, Some(1), "{stderr}");
    assert!(
        stderr.contains("no beam with id `rigth`") && stderr.contains("left, right"),
        "the beams are listed: {stderr}"
    );
    let line = fails(
        &["switch-off", "--point", "plate"],
        &["`plate`", "slot", "pad"],
    );
    assert!(line.contains("--point"), "{line}");
}

#[test]
fn a_sample_rate_read_from_times_prints_with_its_digits() {
    // Times written with 10 significant digits at 10.24 kHz: 1/Δt from them
    // is 10240 to about 1e-9, and prints as 10240.
    let dir = tempfile::tempdir().expect("a temp dir");
    let files = measured_support::write_csv_hits(dir.path(), &measured_support::two_modes(), 1, 3);
    let (code, stdout, stderr) = run(dir.path(), &["frf", files[0].to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.contains("samples at 10240 Hz"),
        "the rate prints as 10240 Hz:\n{stdout}"
    );
}

#[test]
fn impulse_names_its_hammer_and_refuses_a_released_preload() {
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let dir = tempfile::tempdir().expect("a temp dir");
    // The paper's assembly: its half-sine load `hammer` is the hammer.
    let (code, stdout, stderr) = run(dir.path(), &["impulse", "--end-time", "0.001"]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.contains("hammer (half-sine loads): hammer"),
        "{stdout}"
    );
    // The switch-off assembly has only a released preload F_x2 (F_c is a contact):
    // not a hammer blow.
    let model = models.join("rcbo_switch_off.json");
    let line = fails(
        &["impulse", model.to_str().unwrap(), "--end-time", "0.001"],
        &["no half-sine load", "(F_x2)", "releases"],
    );
    assert!(!line.contains("panicked"), "{line}");
    // The cantilever has a step load only: used, and said so.
    let model = models.join("cantilever.json");
    let (code, stdout, stderr) = run(
        dir.path(),
        &[
            "impulse",
            model.to_str().unwrap(),
            "--end-time",
            "0.001",
            "--json",
        ],
    );
    assert_eq!(code, Some(0), "{stderr}");
    let doc: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(doc["excitation"], "step");
    assert_eq!(doc["excitation_loads"], json!(["tip_load"]));
}
