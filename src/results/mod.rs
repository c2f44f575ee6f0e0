//! Typed results of every analysis, as the front ends receive them.
//!
//! Each command's `--json` document is one of the types here (or a type of
//! its analysis module re-exported here), printed with the provenance block
//! ([`Provenance`]: `tool_version`, `model_sha256`, `warnings`). The same
//! types are what the Python package wraps and the HTML report renders, so
//! a library user gets a result without going through the command line:
//!
//! | command | entry function → document | result |
//! |---|---|---|
//! | `modal` | [`modal::modal`] | [`ModalOutput`] |
//! | `modal --prestress` | [`modal::prestressed`] | [`PrestressedOutput`] |
//! | `static` | [`crate::analysis::statics::solve_equilibrium`] → [`static_report`] | [`StaticReport`] |
//! | `impulse` | [`crate::analysis::impulse::run_impulse`] → [`ImpulseOutput::new`] | [`ImpulseOutput`] |
//! | `transient` | [`crate::analysis::simulate::simulate`] → [`TransientOutput::new`] | [`TransientOutput`] |
//! | `switch-off` | [`crate::analysis::switch_off::run_switch_off`] → [`SwitchOffOutput::new`] | [`SwitchOffOutput`] |
//! | `calibrate` | [`crate::analysis::calibrate::calibrate`] → [`CalibrationOutput::new`] | [`CalibrationOutput`] |
//! | `calibrate --quantity`, `--trajectory` | [`crate::analysis::calibrate::transient::calibrate_transient`] | [`TransientCalibrationOutput`] |
//! | `convergence` | [`crate::analysis::convergence::mesh_convergence`] → [`ConvergenceOutput::new`] | [`ConvergenceOutput`] |
//! | `sweep`, `sweep-merge` | [`crate::analysis::sweep::Sweep::run`], [`crate::analysis::sweep::merge`] | [`SweepDocument`] |
//! | `frf` | [`crate::measured::analysis::analyse`] → [`FrfOutput::new`] ([`ModelOverlay::new`] for `--model`) | [`FrfOutput`] |
//! | `identify` | [`modal::modal`], `run_impulse`, [`identify::choose_experiment`] → [`IdentifyOutput::new`] | [`IdentifyOutput`] |
//!
//! [`output_schema`] gives the JSON Schema of a command's document
//! (`ancf-modal schema --output COMMAND`): every key is required (an
//! absent value is `null`, never an omitted key) and no other key is
//! allowed. Units are in each field's description, `[Hz]`, `[s]`, `[–]`.

pub mod fit;
pub mod identify;
pub mod modal;
pub mod provenance;
pub mod reduce;
pub mod statics;
pub mod time;

pub use crate::analysis::sweep::SweepDocument;
pub use fit::{
    CalibrateJson, CalibrationOutput, ConvergenceOutput, FrfOutput, ModelOverlay,
    TransientCalibrationOutput,
};
pub use identify::IdentifyOutput;
pub use modal::{ModalJson, ModalOutput, ModeEntry, PrestressedOutput};
pub use statics::{static_report, StaticReport};
pub use time::{ImpulseOutput, SwitchOffOutput, TransientOutput};

use schemars::JsonSchema;
use serde::Serialize;
use serde_json::Value;

/// The provenance block every `--json` document carries beside its result.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Provenance {
    /// Version of ancf-modal that wrote the document (Cargo package version).
    pub tool_version: String,
    /// SHA-256 (lower-case hex) of the model's bytes: the file, or the
    /// built-in model's JSON text; null where no model is involved (`frf`
    /// without `--model`).
    pub model_sha256: Option<String>,
    /// The run's warnings, one sentence each: the analysis's own first,
    /// then those about the model (units, beam theory).
    pub warnings: Vec<String>,
}

/// The commands with a `--json` document, as `schema --output` names them.
pub const COMMANDS: &[&str] = &[
    "modal",
    "static",
    "impulse",
    "transient",
    "switch-off",
    "calibrate",
    "convergence",
    "sweep",
    "sweep-merge",
    "frf",
    "identify",
];

/// The JSON Schema of `command`'s `--json` document (result and
/// provenance), or `None` for a command without one.
pub fn output_schema(command: &str) -> Option<Value> {
    let schema = match command {
        "modal" => schema::<ModalJson>(),
        "static" => schema::<StaticReport>(),
        "impulse" => schema::<ImpulseOutput>(),
        "transient" => schema::<TransientOutput>(),
        "switch-off" => schema::<SwitchOffOutput>(),
        "calibrate" => schema::<CalibrateJson>(),
        "convergence" => schema::<ConvergenceOutput>(),
        "sweep" | "sweep-merge" => schema::<SweepDocument>(),
        "frf" => schema::<FrfOutput>(),
        "identify" => schema::<IdentifyOutput>(),
        _ => return None,
    };
    Some(with_provenance(schema))
}

/// The schema of `T` with every object closed: all its keys required, no
/// other key allowed.
fn schema<T: JsonSchema>() -> Value {
    let mut v = serde_json::to_value(schemars::schema_for!(T)).expect("a schema serializes");
    close_objects(&mut v);
    v
}

/// Makes every object schema (one with `properties`) require all of its
/// keys and refuse others, recursively (`$defs` included).
fn close_objects(v: &mut Value) {
    match v {
        Value::Object(map) => {
            if let Some(Value::Object(props)) = map.get("properties") {
                let keys: Vec<Value> = props.keys().cloned().map(Value::from).collect();
                map.insert("required".into(), Value::Array(keys));
                map.insert("additionalProperties".into(), Value::Bool(false));
            }
            map.values_mut().for_each(close_objects);
        }
        Value::Array(items) => items.iter_mut().for_each(close_objects),
        _ => {}
    }
}

/// Adds the provenance keys to the root object, or to each alternative of a
/// root `anyOf` (a command with several document shapes).
fn with_provenance(mut schema: Value) -> Value {
    let provenance = serde_json::to_value(schemars::schema_for!(Provenance))
        .expect("a schema serializes")["properties"]
        .clone();
    let add = |obj: &mut Value| {
        if let (Some(props), Some(Value::Object(extra))) = (
            obj.get_mut("properties").and_then(Value::as_object_mut),
            Some(&provenance),
        ) {
            for (k, v) in extra {
                props.entry(k.clone()).or_insert_with(|| v.clone());
            }
            let keys: Vec<Value> = props.keys().cloned().map(Value::from).collect();
            obj["required"] = Value::Array(keys);
        }
    };
    let alternatives: Vec<String> = schema
        .get("anyOf")
        .and_then(Value::as_array)
        .map(|a| {
            a.iter()
                .filter_map(|s| s.get("$ref").and_then(Value::as_str))
                .map(|r| r.trim_start_matches("#/$defs/").to_string())
                .collect()
        })
        .unwrap_or_default();
    if alternatives.is_empty() {
        add(&mut schema);
    } else {
        // Each alternative is a document of its own: give it the block in
        // place (a definition used only at the root).
        for name in alternatives {
            if let Some(def) = schema.get_mut("$defs").and_then(|d| d.get_mut(&name)) {
                add(def);
            }
        }
    }
    schema
}

/// `result` as a JSON object with the provenance block: `warnings` holds
/// the result's own warnings (if it has a `warnings` list) followed by
/// `extra_warnings`.
pub fn document(
    result: &impl Serialize,
    model_sha256: Option<&str>,
    extra_warnings: &[String],
) -> Result<Value, serde_json::Error> {
    let mut doc = serde_json::to_value(result)?;
    if let Some(map) = doc.as_object_mut() {
        let mut all: Vec<Value> = match map.remove("warnings") {
            Some(Value::Array(own)) => own,
            _ => Vec::new(),
        };
        all.extend(extra_warnings.iter().cloned().map(Value::from));
        map.insert("warnings".into(), Value::Array(all));
        map.insert(
            "tool_version".into(),
            Value::from(crate::results::provenance::tool_version()),
        );
        map.insert("model_sha256".into(), Value::from(model_sha256));
    }
    Ok(doc)
}

/// A finite number, or `None` (JSON has no NaN or infinity: serde_json
/// writes them as null, which the schema then says).
pub(crate) fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}
