//! The model file's JSON Schema (generated from the serde types): every
//! model in `models/` conforms, and it rejects what the parser rejects
//! (an unknown key, a wrong type, an unknown contact law).

use ancf_modal::Model;
use serde_json::{json, Value};

fn validator() -> jsonschema::Validator {
    jsonschema::validator_for(&Model::json_schema()).expect("the schema is a valid JSON Schema")
}

#[test]
fn every_model_file_conforms_to_the_schema() {
    let v = validator();
    let mut count = 0;
    for entry in std::fs::read_dir("models").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let doc: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let errors: Vec<String> = v.iter_errors(&doc).map(|e| e.to_string()).collect();
        assert!(errors.is_empty(), "{}: {errors:?}", path.display());
        // And the parser agrees.
        Model::from_file(&path).unwrap();
        count += 1;
    }
    assert!(
        count >= 5,
        "models/ holds the shipped models ({count} found)"
    );
}

#[test]
fn the_schema_rejects_what_the_parser_rejects() {
    let v = validator();
    let good = json!({
        "name": "m",
        "point_masses": [{"id": "p", "mass": 1.0, "position": [0.0, 0.0]}],
        "contacts": [{"id": "c", "type": "point_line", "point": {"body": "p"}, "radius": 0.0,
                      "line": {"ground": true, "from": [-1.0, -1.0], "to": [1.0, -1.0]},
                      "law": {"model": "hertz", "stiffness": 1e9}}]
    });
    assert!(v.is_valid(&good));
    let mut unknown_key = good.clone();
    unknown_key["gravty"] = json!([0.0, -9.81]);
    let mut wrong_type = good.clone();
    wrong_type["point_masses"][0]["mass"] = json!("heavy");
    let mut bad_law = good.clone();
    bad_law["contacts"][0]["law"]["model"] = json!("nonsense");
    for (what, doc) in [
        ("unknown key", unknown_key),
        ("wrong type", wrong_type),
        ("unknown law", bad_law),
    ] {
        assert!(
            !v.is_valid(&doc),
            "the schema accepts a model with an {what}"
        );
        assert!(
            Model::from_json(&doc.to_string(), ancf_modal::error::Source::BuiltIn).is_err(),
            "the parser accepts a model with an {what}"
        );
    }
}
