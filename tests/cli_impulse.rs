//! `impulse` and `identify` from the command line: the report, the JSON keys,
//! the data files, and one-line errors (exit 1, no output file) for bad
//! settings and a Newton failure.

use assert_cmd::Command;
use serde_json::Value;

fn tool() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

/// Runs `impulse` with extra flags and `--csv` into a temp dir; asserts a
/// one-line error with exit code 1 that contains `expect`, and no file.
fn fails_with(flags: &[&str], expect: &str) {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("out.csv");
    let out = tool()
        .arg("impulse")
        .args(flags)
        .arg("--csv")
        .arg(&csv)
        .env("RUST_BACKTRACE", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{flags:?}: exit code 1, stderr: {stderr}"
    );
    assert_eq!(
        stderr.lines().count(),
        1,
        "{flags:?}: exactly one line: {stderr}"
    );
    assert!(
        stderr.starts_with("Error: ") && stderr.contains(expect),
        "{flags:?}: expected `{expect}` in: {stderr}"
    );
    assert!(
        !stderr.contains("panicked"),
        "{flags:?}: no panic: {stderr}"
    );
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "{flags:?}: no output file left behind"
    );
}

#[test]
fn bad_settings_are_one_line_errors() {
    fails_with(&["--step", "0"], "--step `0`: must be a number > 0");
    fails_with(&["--step=-1e-6"], "--step `-1e-6`: must be a number > 0");
    fails_with(
        &["--end-time", "1e-6"],
        "--end-time `0.000001`: must be longer than one step (0.000001 s)",
    );
    fails_with(
        &["--sample-rate", "2e6"],
        "--sample-rate `2000000`: must be at most 1/step = 1000000 Hz (or 0 to record every step)",
    );
    fails_with(&["--duration", "1e-6"], "shorter than two steps");
    fails_with(&["--spectral-radius", "1.5"], "--spectral-radius `1.5`");
    fails_with(&["--amplitude", "0"], "--amplitude `0`");
    fails_with(
        &["--sensor", "nope"],
        "no sensor `nope` (its sensors: vibrometer)",
    );
}

#[test]
fn newton_failure_names_the_time_and_the_residual() {
    fails_with(
        &["--amplitude", "1e9", "--end-time", "1e-3"],
        "Newton iteration failed at t = ",
    );
    fails_with(&["--amplitude", "1e9", "--end-time", "1e-3"], "(residual ");
}

#[test]
fn impulse_json_has_the_design_keys_and_the_csv_files_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("tip.csv");
    let out = tool()
        .args(["impulse", "--end-time", "0.02", "--json", "--csv"])
        .arg(&csv)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    for key in [
        "first_bending_hz",
        "eigen_first_bending_hz",
        "peaks",
        "reference_hz",
        "error_percent",
        "steps",
    ] {
        assert!(v.get(key).is_some(), "JSON key `{key}`");
    }
    assert_eq!(
        v["reference_hz"], 4600.0,
        "reference from the built-in model (paper Table 3)"
    );
    assert_eq!(v["steps"], 20000, "0.02 s at 1 µs");
    let f = v["first_bending_hz"].as_f64().unwrap();
    let e = v["eigen_first_bending_hz"].as_f64().unwrap();
    // 20 ms gives a 50 Hz bin; the interpolated peak is still within 1e-3.
    assert!(((f - e) / e).abs() < 1e-3, "FFT {f} Hz vs eigen {e} Hz");
    let expected_error = 100.0 * (f - 4600.0) / 4600.0;
    assert!(
        (v["error_percent"].as_f64().unwrap() - expected_error).abs() < 1e-9,
        "error_percent = (model − exp)/exp"
    );
    let signal = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(
        signal.lines().count(),
        1 + 1025,
        "header + 51.2 kHz × 20 ms + 1 samples"
    );
    let spectrum = std::fs::read_to_string(dir.path().join("tip.spectrum.csv")).unwrap();
    assert!(
        spectrum.starts_with("frequency_hz,magnitude,magnitude_db"),
        "spectrum CSV header"
    );
}

#[test]
fn identify_prints_table_3_and_writes_its_data() {
    let dir = tempfile::tempdir().unwrap();
    let out = tool()
        .args(["identify", "--end-time", "0.02", "--out-dir"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    for row in [
        "experiment (paper Table 3)",
        "4600.00",
        "this tool, eigenvalue",
        "paper, ANCF",
        "4724.00",
        "paper, ANSYS BEAM188",
        "4971.00",
        "-2.62%",
        "-7.46%",
    ] {
        assert!(text.contains(row), "identify report shows `{row}`:\n{text}");
    }
    for file in ["summary.json", "modes.csv", "signal.csv", "spectrum.csv"] {
        assert!(dir.path().join(file).exists(), "{file} written");
    }
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("summary.json")).unwrap())
            .unwrap();
    assert_eq!(
        summary["table"].as_array().unwrap().len(),
        6,
        "six rows of the comparison"
    );
}
