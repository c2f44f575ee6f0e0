//! Rayleigh damping in the model: `modal` reports ζ = α/(2ω) + βω/2 per
//! elastic mode, null for rigid modes, 0 without damping.

use assert_cmd::Command;
use serde_json::Value;
use std::path::Path;

fn with_damping(dir: &Path, model: &str, damping: Option<&str>) -> std::path::PathBuf {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(model);
    let mut doc: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    if let Some(d) = damping {
        doc["damping"] = serde_json::from_str(d).unwrap();
    }
    let p = dir.join(model);
    std::fs::write(&p, doc.to_string()).unwrap();
    p
}

fn modal_json(model: &Path) -> Value {
    let out = Command::cargo_bin("ancf-modal")
        .unwrap()
        .arg("modal")
        .arg(model)
        .args(["--modes", "8", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn damping_ratio_is_alpha_over_two_omega_plus_beta_omega_over_two() {
    let dir = tempfile::tempdir().unwrap();
    let (alpha, beta) = (40.0, 2e-8);
    let p = with_damping(
        dir.path(),
        "rcbo_free_free.json",
        Some(r#"{"alpha": 40.0, "beta": 2e-8}"#),
    );
    let doc = modal_json(&p);
    let mut elastic = 0;
    for m in doc["modes"].as_array().unwrap() {
        if m["kind"] == "rigid" {
            assert!(m["damping_ratio"].is_null());
            continue;
        }
        let w = 2.0 * std::f64::consts::PI * m["frequency_hz"].as_f64().unwrap();
        let expect = alpha / (2.0 * w) + beta * w / 2.0;
        let z = m["damping_ratio"].as_f64().unwrap();
        assert!(
            (z - expect).abs() <= 1e-12 * expect,
            "ζ = {z}, expected {expect}"
        );
        elastic += 1;
    }
    assert_eq!(elastic, 5);
    // Without damping: 0 for elastic modes.
    let p = with_damping(dir.path(), "cantilever.json", None);
    let doc = modal_json(&p);
    assert!(doc["modes"]
        .as_array()
        .unwrap()
        .iter()
        .all(|m| m["damping_ratio"] == 0.0));
}

#[test]
fn negative_damping_is_a_model_error() {
    let dir = tempfile::tempdir().unwrap();
    let p = with_damping(
        dir.path(),
        "cantilever.json",
        Some(r#"{"alpha": -1.0, "beta": 0.0}"#),
    );
    let out = Command::cargo_bin("ancf-modal")
        .unwrap()
        .arg("modal")
        .arg(&p)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(err.contains("damping.alpha"), "{err}");
}
