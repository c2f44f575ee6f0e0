//! The published schemas of the `--json` documents (`schema --output
//! COMMAND`): a real run of every command conforms to its command's
//! schema; the schema requires each top-level key (the document with any
//! one key removed is rejected) and refuses an unknown one; every field
//! of every document is described (the description carries the unit).

mod common;
use common::run_ok;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn model(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("models")
        .join(name)
        .display()
        .to_string()
}

fn json(args: &[&str]) -> Value {
    serde_json::from_slice(&run_ok(args)).unwrap_or_else(|e| panic!("{args:?}: {e}"))
}

fn schema(command: &str) -> Value {
    json(&["schema", "--output", command])
}

/// `doc` conforms to `command`'s schema, which rejects it with any one
/// top-level key removed, and with a key added.
fn conforms(command: &str, doc: &Value) {
    let schema = schema(command);
    let v = jsonschema::validator_for(&schema).expect("a valid JSON Schema");
    let errors: Vec<String> = v.iter_errors(doc).map(|e| e.to_string()).collect();
    assert!(errors.is_empty(), "{command}: {errors:?}");
    let map = doc.as_object().expect("a JSON object");
    for key in ["tool_version", "model_sha256", "warnings"] {
        assert!(map.contains_key(key), "{command}: no provenance key {key}");
    }
    for key in map.keys() {
        let mut less = doc.clone();
        less.as_object_mut().unwrap().remove(key);
        assert!(
            !v.is_valid(&less),
            "{command}: the schema accepts the document without `{key}`"
        );
    }
    let mut more = doc.clone();
    more["unknown_key"] = Value::Null;
    assert!(!v.is_valid(&more), "{command}: an unknown key is accepted");
}

#[test]
fn modal_documents_conform() {
    conforms("modal", &json(&["modal", "--json"]));
    conforms(
        "modal",
        &json(&[
            "modal",
            &model("rcbo_prestressed.json"),
            "--prestress",
            "--json",
        ]),
    );
    conforms(
        "modal",
        &json(&[
            "modal",
            &model("cantilever.json"),
            "--sweep-load",
            "0:1:2",
            "--json",
        ]),
    );
    // The MAC against the model's own UFF export: a real `mac` table.
    let dir = tempfile::tempdir().unwrap();
    let uff = dir.path().join("modes.uff");
    run_ok(["modal", "--uff", uff.to_str().unwrap()]);
    let doc = json(&["modal", "--json", "--mac", uff.to_str().unwrap()]);
    assert!(doc["mac"]["matrix"].is_array(), "{doc}");
    conforms("modal", &doc);
}

#[test]
fn static_document_conforms() {
    conforms(
        "static",
        &json(&["static", &model("rcbo_prestressed.json"), "--json"]),
    );
}

#[test]
fn time_domain_documents_conform() {
    conforms(
        "impulse",
        &json(&["impulse", "--end-time", "0.01", "--json"]),
    );
    conforms(
        "transient",
        &json(&[
            "transient",
            &model("cantilever.json"),
            "--end-time",
            "0.001",
            "--json",
        ]),
    );
    conforms(
        "switch-off",
        &json(&[
            "switch-off",
            "--end-time",
            "0.0005",
            "--compare-rigid",
            "--fig10",
            "--json",
        ]),
    );
}

#[test]
fn fit_documents_conform() {
    conforms(
        "calibrate",
        &json(&["calibrate", "--target", "4600", "--json"]),
    );
    conforms(
        "calibrate",
        &json(&[
            "calibrate",
            "--quantity",
            "time_to_distance_s",
            "--target",
            "1.8e-3",
            "--param",
            "springs[helical_spring].a.ground[1]=-0.001:0.001",
            "--json",
        ]),
    );
    conforms(
        "convergence",
        &json(&[
            "convergence",
            "--max-elements",
            "8",
            "--modes",
            "2",
            "--json",
        ]),
    );
    let dir = tempfile::tempdir().unwrap();
    let uff: PathBuf = dir.path().join("hit.uff");
    run_ok([
        "impulse",
        "--end-time",
        "0.02",
        "--uff",
        uff.to_str().unwrap(),
    ]);
    let uff = uff.to_str().unwrap();
    conforms("frf", &json(&["frf", uff, "--json"]));
    conforms(
        "frf",
        &json(&[
            "frf",
            uff,
            "--json",
            "--model",
            &model("rcbo_free_free.json"),
            "--at",
            "vibrometer",
        ]),
    );
    conforms(
        "identify",
        &json(&["identify", "--end-time", "0.01", "--calibrate", "--json"]),
    );
    conforms(
        "identify",
        &json(&[
            "identify",
            "--end-time",
            "0.01",
            "--measured",
            uff,
            "--json",
        ]),
    );
}

#[test]
fn sweep_documents_conform() {
    let dir = tempfile::tempdir().unwrap();
    let grid = "height=0.9e-3:1.2e-3:3";
    conforms(
        "sweep",
        &json(&[
            "sweep",
            "--param",
            grid,
            "--quantity",
            "first_bending_hz",
            "--json",
        ]),
    );
    let mut shards = Vec::new();
    for k in 1..=2 {
        let path = dir.path().join(format!("s{k}.json"));
        let out = run_ok([
            "sweep",
            "--param",
            grid,
            "--quantity",
            "frequency:1",
            "--shard",
            &format!("{k}/2"),
            "--json",
        ]);
        std::fs::write(&path, &out).unwrap();
        let doc: Value = serde_json::from_slice(&out).unwrap();
        conforms("sweep", &doc);
        shards.push(path.display().to_string());
    }
    let mut args = vec!["sweep-merge", "--json"];
    args.extend(shards.iter().map(String::as_str));
    conforms("sweep-merge", &json(&args));
}

/// Every property of every object, with its path.
fn properties<'a>(v: &'a Value, path: &str, out: &mut Vec<(String, &'a Value)>) {
    match v {
        Value::Object(map) => {
            if let Some(Value::Object(props)) = map.get("properties") {
                for (k, p) in props {
                    out.push((format!("{path}.{k}"), p));
                }
            }
            for (k, child) in map {
                properties(child, &format!("{path}/{k}"), out);
            }
        }
        Value::Array(items) => items.iter().for_each(|c| properties(c, path, out)),
        _ => {}
    }
}

#[test]
fn every_field_is_required_closed_and_described() {
    let mut undescribed = Vec::new();
    for &command in ancf_modal::results::COMMANDS {
        let schema = schema(command);
        let mut props = Vec::new();
        properties(&schema, command, &mut props);
        assert!(!props.is_empty(), "{command}: no properties");
        for (path, p) in props {
            // A `$ref` property is described by its definition.
            let described = p
                .get("description")
                .and_then(Value::as_str)
                .is_some_and(|d| !d.trim().is_empty());
            if !described && p.get("$ref").is_none() {
                undescribed.push(path);
            }
        }
    }
    undescribed.sort();
    undescribed.dedup();
    assert!(
        undescribed.is_empty(),
        "fields without a description: {undescribed:#?}"
    );
}

#[test]
fn plain_schema_is_still_the_model_schema() {
    let plain = json(&["schema"]);
    assert_eq!(plain, ancf_modal::Model::json_schema());
    assert!(ancf_modal::results::output_schema("no-such-command").is_none());
}

/// `modal --json` is the library's result plus the provenance block, no
/// more and no less.
#[test]
fn modal_json_is_the_library_result_and_the_provenance() {
    let model = ancf_modal::Model::builtin();
    let system = ancf_modal::System::new(&model);
    let settings = ancf_modal::analysis::ModalSettings {
        modes: Some(12),
        ..Default::default()
    };
    let (_, output) = ancf_modal::results::modal::modal(&model, &system, &settings).unwrap();
    let mut cli = json(&["modal", "--json"]);
    let map = cli.as_object_mut().unwrap();
    for key in ["tool_version", "model_sha256", "warnings"] {
        assert!(map.remove(key).is_some(), "no {key}");
    }
    assert_eq!(cli, serde_json::to_value(&output).unwrap());
}
