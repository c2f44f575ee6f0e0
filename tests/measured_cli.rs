//! `ancf-modal frf` end to end on CSV hammer records written by the
//! synthetic generator (tests/measured_support), and its one-line errors.

mod measured_support;

use assert_cmd::Command;
use measured_support::{write_csv_hits, TestMode};
use std::fmt::Write;
use std::path::{Path, PathBuf};

const N: usize = 5_120;

fn modes() -> Vec<TestMode> {
    measured_support::two_modes()
}

fn write_hits(dir: &Path, hits: usize) -> Vec<PathBuf> {
    write_csv_hits(dir, &modes(), hits, 5)
}

fn bin() -> Command {
    Command::cargo_bin("ancf-modal").unwrap()
}

#[test]
fn frf_on_csv_hits_finds_both_modes_and_writes_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let files = write_hits(dir.path(), 3);
    let out = bin()
        .arg("frf")
        .args(&files)
        .args([
            "--window",
            "force:0.02",
            "--response-quantity",
            "displacement",
            "--json",
        ])
        .arg("--csv")
        .arg(dir.path().join("frf.csv"))
        .arg("--plot")
        .arg(dir.path().join("frf.svg"))
        .arg("--uff")
        .arg(dir.path().join("frf.uff"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["tool_version"], env!("CARGO_PKG_VERSION"));
    assert!(doc.get("model_sha256").is_some());
    assert_eq!(doc["averages"], 3);
    let n = doc["frequency_hz"].as_array().unwrap().len();
    assert_eq!(n, N / 2 + 1);
    assert_eq!(doc["h1"].as_array().unwrap().len(), n);
    assert_eq!(doc["h2"].as_array().unwrap().len(), n);
    assert_eq!(doc["coherence"].as_array().unwrap().len(), n);
    let peaks = doc["peaks"].as_array().unwrap();
    assert_eq!(peaks.len(), 2, "{peaks:?}");
    for (p, m) in peaks.iter().zip(modes()) {
        let f = p["frequency_hz"].as_f64().unwrap();
        let z = p["damping_ratio"].as_f64().unwrap();
        assert!((f - m.f).abs() < 3e-4 * m.f, "f = {f}");
        assert!((z - m.zeta).abs() < 0.05 * m.zeta, "ζ = {z}");
        assert!(p["magnitude"].as_f64().unwrap() > 0.0);
    }
    let csv = std::fs::read_to_string(dir.path().join("frf.csv")).unwrap();
    assert_eq!(csv.lines().count(), n + 1);
    let svg = std::fs::read_to_string(dir.path().join("frf.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("Coherence"));
    // The UFF export reads back as an FRF with its coherence.
    let uff = dir.path().join("frf.uff");
    let text = std::fs::read_to_string(&uff).unwrap();
    let f = ancf_modal::measured::uff::read_functions(&uff, &text).unwrap();
    assert_eq!(f.len(), 2);
    assert_eq!(f[0].function_type.code(), 4);
    assert_eq!(f[1].function_type.code(), 6);
    assert_eq!(f[0].ordinate.len(), n);
    // ... and `frf` accepts it as input, finding the same modes.
    let again = bin().arg("frf").arg(&uff).arg("--json").output().unwrap();
    assert!(
        again.status.success(),
        "{}",
        String::from_utf8_lossy(&again.stderr)
    );
    let doc2: serde_json::Value = serde_json::from_slice(&again.stdout).unwrap();
    let p2 = doc2["peaks"].as_array().unwrap();
    assert_eq!(p2.len(), 2);
    // The file holds the FRF without its sampling interval, so it is fitted
    // with continuous-time poles, the records with the sampled basis: two
    // estimators on the same noisy estimate, each held to the truth with the
    // tolerance the record fit meets above.
    for (p, m) in p2.iter().zip(modes()) {
        let f = p["frequency_hz"].as_f64().unwrap();
        let z = p["damping_ratio"].as_f64().unwrap();
        assert!((f - m.f).abs() < 3e-4 * m.f, "file f = {f}");
        assert!((z - m.zeta).abs() < 0.05 * m.zeta, "file ζ = {z}");
    }
    // The table.
    let table = bin().arg("frf").args(&files).output().unwrap();
    let t = String::from_utf8(table.stdout).unwrap();
    assert!(t.contains("3 hit(s)") && t.contains("damping ratio"), "{t}");
}

/// Runs `frf` on `file` with outputs requested; expects exit 1, one line
/// on stderr containing `expect`, and no output file.
fn fails(file: &Path, extra: &[&str], expect: &str) {
    let dir = file.parent().unwrap();
    let csv = dir.join("out.csv");
    let out = bin()
        .arg("frf")
        .arg(file)
        .args(extra)
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("Error: "), "{err}");
    assert!(err.contains(expect), "`{err}` lacks `{expect}`");
    assert!(!csv.exists());
}

fn csv_file(dir: &Path, name: &str, body: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, body).unwrap();
    p
}

fn good_rows(n: usize) -> String {
    let mut s = String::from("t,F,v\n");
    for k in 0..n {
        let f = if k == 1 { 4.0 } else { 0.0 };
        let _ = writeln!(
            s,
            "{},{f},{}",
            k as f64 * 1e-4,
            (k as f64 * 0.3).sin() * 1e-3
        );
    }
    s
}

#[test]
fn bad_measurement_files_are_one_line_errors() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let good = csv_file(d, "good.csv", &good_rows(1000));
    fails(
        &good,
        &["--response", "accel"],
        "good.csv:1: no column `accel` in the header (columns: t, F, v)",
    );
    fails(
        &good,
        &["--response", "7"],
        "good.csv:1: column 7 does not exist",
    );
    let text = good_rows(1000);
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    lines[10] = "0.0009,0,abc".into();
    let p = csv_file(d, "text.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "text.csv:11:3: `abc` is not a number");
    lines = text.lines().map(String::from).collect();
    lines[20] = "0.0019,0".into();
    let p = csv_file(d, "ragged.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "ragged.csv:21: 2 cells, but the header has 3");
    lines = text.lines().map(String::from).collect();
    lines[30] = "0.0029,NaN,0".into();
    let p = csv_file(d, "nan.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "nan.csv:31:2: `NaN` is not a finite number");
    lines = text.lines().map(String::from).collect();
    lines[40] = "0.0001,0,0".into();
    let p = csv_file(d, "time.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "time.csv:41: time 1e-4 s does not increase");
    lines = text.lines().map(String::from).collect();
    lines.remove(40);
    let p = csv_file(d, "gap.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "gap.csv:41: uneven sampling");
    let zero = good_rows(1000).replace(",4,", ",0,");
    let p = csv_file(d, "zero.csv", &zero);
    fails(
        &p,
        &[],
        "zero.csv: the force channel `F` is zero throughout",
    );
    lines = text.lines().map(String::from).collect();
    lines[50] = "0.0049,3.5,0".into();
    let p = csv_file(d, "double.csv", &(lines.join("\n") + "\n"));
    fails(&p, &[], "double.csv:51: double impact");
    let p = csv_file(
        d,
        "weird.uff",
        "    -1\n  2412\n    -1\n    -1\n   777\n 1 2\n    -1\n",
    );
    // Foreign datasets are skipped by their framing, whatever their number
    // (a 2412 and a made-up 777 here): what is left holds no FRF or record.
    fails(&p, &[], "weird.uff: the file holds no dataset 58"); // A negative band edge reaches the band's own check, not clap's hint
                                                               // to write `-- -5` (the outside-eyes trial of issue 33).
    fails(
        &good,
        &["--band", "-5:300"],
        "the band needs 0 ≤ LO < HI, got -5:300",
    );
}

#[test]
fn frf_overlays_the_model_on_its_own_simulated_measurement() {
    let dir = tempfile::tempdir().unwrap();
    let sig = dir.path().join("sig.csv");
    let model = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/rcbo_free_free.json");
    let out = bin()
        .arg("impulse")
        .arg(&model)
        .args(["--end-time", "0.05", "--csv"])
        .arg(&sig)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = bin()
        .arg("frf")
        .arg(&sig)
        .args(["--force", "force_n", "--response", "vibrometer_velocity"])
        .args([
            "--window",
            "exponential:0.01",
            "--json",
            "--at",
            "vibrometer",
            "--model",
        ])
        .arg(&model)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    use sha2::Digest;
    let sha: String = sha2::Sha256::digest(std::fs::read(&model).unwrap())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    assert_eq!(doc["model_sha256"], sha);
    // The model's FRF peaks in the measured first bending bin.
    let f: Vec<f64> = doc["frequency_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let mag = |v: &serde_json::Value| {
        v.as_array().map_or(0.0, |p| {
            p[0].as_f64().unwrap().hypot(p[1].as_f64().unwrap())
        })
    };
    let h = doc["model_frf"]["h"].as_array().unwrap();
    let peak = (0..f.len())
        .filter(|&k| (4_000.0..5_000.0).contains(&f[k]))
        .max_by(|&a, &b| mag(&h[a]).total_cmp(&mag(&h[b])))
        .unwrap();
    let measured = doc["peaks"][0]["frequency_hz"].as_f64().unwrap();
    assert!(
        (f[peak] - measured).abs() <= f[1],
        "model peak {} Hz, measured {measured} Hz",
        f[peak]
    );
    assert!((measured - 4_568.9).abs() < 1.0, "measured {measured}");
}

#[test]
fn impulse_uff_records_are_a_hammer_test_for_frf() {
    let dir = tempfile::tempdir().unwrap();
    let uff = dir.path().join("impulse.uff");
    let out = bin()
        .args(["impulse", "--end-time", "0.05", "--json", "--uff"])
        .arg(&uff)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let imp: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // The records carry the integrator's numerical frequency (the raw FFT
    // value, before the period-error correction).
    let raw = imp["first_bending_raw_hz"].as_f64().unwrap();
    let text = std::fs::read_to_string(&uff).unwrap();
    let f = ancf_modal::measured::uff::read_functions(&uff, &text).unwrap();
    assert_eq!(f.len(), 2);
    assert_eq!((f[0].function_type.code(), f[0].ordinate_type.0), (1, 13));
    assert_eq!((f[1].function_type.code(), f[1].ordinate_type.0), (1, 11));
    assert_eq!(f[0].ordinate.len(), 2_561);
    // dx is written as %13.5e (1.95313e-05 s): the rate reads 2.6e-6 low.
    assert!((1.0 / f[0].dx / 51_200.0 - 1.0).abs() < 5e-6);
    let out = bin()
        .arg("frf")
        .arg(&uff)
        .args(["--window", "exponential:0.01", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f1 = doc["peaks"][0]["frequency_hz"].as_f64().unwrap();
    assert!(
        (f1 - raw).abs() < 0.05,
        "first bending {f1} Hz, impulse's raw FFT {raw} Hz"
    );
}

/// A taper on impact records is warned about (the outside-eyes trial: a
/// Hann window gave damping 4–5× low without a word); rect is not.
#[test]
fn frf_warns_of_a_taper_on_impact_records() {
    let dir = tempfile::tempdir().unwrap();
    let files = write_hits(dir.path(), 1);
    let run = |window: &str| {
        let out = bin()
            .arg("frf")
            .args(&files)
            .args(["--window", window])
            .output()
            .unwrap();
        assert!(out.status.success());
        String::from_utf8(out.stderr).unwrap()
    };
    let hann = run("hann");
    assert!(
        hann.contains("warning") && hann.contains("hann window tapers the blow"),
        "{hann}"
    );
    assert!(!run("rect").contains("tapers"));
}
