//! Provenance (DESIGN section 9): every `--json` document carries
//! `tool_version` (the package version) and `model_sha256`, the SHA-256 of
//! the model file's bytes (of the built-in model's JSON text without a
//! file), computed here independently with the sha2 crate; so does the
//! ID line of the UFF files `impulse` and `modal` export.

mod common;
use common::run_ok;
use serde_json::Value;
use sha2::{Digest, Sha256};
use std::ffi::OsString;
use std::path::{Path, PathBuf};

fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn model_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(name)
}

fn json_of(args: &[&str], model: Option<&Path>) -> Value {
    let mut all: Vec<OsString> = args.iter().map(OsString::from).collect();
    all.extend(model.map(OsString::from));
    all.push("--json".into());
    serde_json::from_slice(&run_ok(all)).unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

fn check(doc: &Value, expected_sha: &str, what: &str) {
    assert_eq!(
        doc["tool_version"],
        env!("CARGO_PKG_VERSION"),
        "{what}: tool_version"
    );
    assert_eq!(doc["model_sha256"], expected_sha, "{what}: model_sha256");
}

#[test]
fn every_json_document_names_the_tool_and_the_model() {
    let cantilever = model_path("cantilever.json");
    let sha = sha256(&std::fs::read(&cantilever).unwrap());
    let short = ["--end-time", "0.002"];
    let commands: Vec<Vec<&str>> = vec![
        vec!["modal"],
        vec!["modal", "--prestress"],
        vec!["static"],
        vec!["impulse", short[0], short[1]],
        vec!["transient", short[0], short[1]],
        vec!["identify", short[0], short[1]],
        vec!["calibrate", "--target", "1100", "--param", "young"],
        vec!["convergence", "--max-elements", "4", "--modes", "1"],
    ];
    for args in &commands {
        check(&json_of(args, Some(&cantilever)), &sha, &args.join(" "));
    }
    // Without a file: the built-in model's JSON text.
    let builtin = sha256(&std::fs::read(model_path("rcbo_free_free.json")).unwrap());
    check(&json_of(&["modal"], None), &builtin, "modal (built-in)");
}

#[test]
fn exported_uff_files_carry_the_provenance() {
    let cantilever = model_path("cantilever.json");
    let sha = sha256(&std::fs::read(&cantilever).unwrap());
    let dir = tempfile::tempdir().unwrap();
    for (cmd, extra) in [("impulse", vec!["--end-time", "0.002"]), ("modal", vec![])] {
        let uff = dir.path().join(format!("{cmd}.uff"));
        let mut args: Vec<OsString> = vec![cmd.into(), cantilever.clone().into()];
        args.extend(extra.iter().map(OsString::from));
        args.extend(["--uff".into(), uff.clone().into()]);
        run_ok(args);
        let text = std::fs::read_to_string(&uff).unwrap();
        for line in [
            format!("ancf-modal {}", env!("CARGO_PKG_VERSION")),
            format!("model_sha256 {sha}"),
        ] {
            assert!(
                text.lines().any(|l| l.trim_end() == line),
                "{cmd}: no ID line `{line}`"
            );
        }
    }
}
