//! The model file: JSON input describing an assembly (see `DESIGN` in the
//! README for the format). Parsing maps serde errors to the JSON path of the
//! offending value; [`Model::validate`] then checks physics and references.
//! Reading a model gives a [`ValidModel`], the only kind of model a
//! [`crate::System`] is built from ([`valid`]).

pub mod calibrated;
mod contact;
mod interpolate;
pub mod number;
pub mod path;
mod placement;
pub mod reference;
pub mod resolved;
mod rigid;
pub mod sanity;
mod section;
mod types;
pub mod valid;
pub mod validate;

pub use calibrated::Calibrated;
pub use contact::*;
pub use interpolate::DesignPath;
pub use placement::Placement;
pub use resolved::ResolvedPoint;
pub use sanity::UnitWarning;
pub use types::*;
pub use valid::ValidModel;
pub use validate::PointTarget;

use crate::error::{InvalidModel, ModelError, Source};
use std::path::Path;

/// The paper's free-free assembly, embedded in the binary.
pub const DEFAULT_MODEL_JSON: &str = include_str!("../../models/rcbo_free_free.json");

/// The paper's switch-off assembly (pre-stressed ON state, contacts),
/// embedded in the binary: the default of `switch-off`.
pub const SWITCH_OFF_MODEL_JSON: &str = include_str!("../../models/rcbo_switch_off.json");
/// The built-in switch-off assembly before its calibration.
pub const SWITCH_OFF_UNCALIBRATED_MODEL_JSON: &str =
    include_str!("../../models/rcbo_switch_off_uncalibrated.json");

impl Model {
    /// Parse and validate a model from JSON text.
    pub fn from_json(text: &str, source: Source) -> Result<ValidModel, ModelError> {
        let de = &mut serde_json::Deserializer::from_str(text);
        let model: Model = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
            let path = e.path().to_string();
            let path = if path == "." { String::from("$") } else { path };
            let inner = e.into_inner();
            // serde_json has no public error code; this message is its
            // `NumberOutOfRange` (a literal like `1e999`), which is a value
            // problem rather than malformed JSON, so name the path too.
            if inner.is_syntax() && inner.to_string().starts_with("number out of range") {
                ModelError::NumberOutOfRange {
                    source_name: source.clone(),
                    line: inner.line(),
                    column: inner.column(),
                    path,
                }
            } else if inner.is_syntax() || inner.is_eof() {
                ModelError::Syntax {
                    source_name: source.clone(),
                    line: inner.line(),
                    column: inner.column(),
                    message: strip_position(&inner.to_string()),
                }
            } else {
                ModelError::Schema {
                    source_name: source.clone(),
                    path,
                    message: strip_position(&inner.to_string()),
                }
            }
        })?;
        // Trailing characters after the model (a second document, a stray
        // brace) are malformed JSON too.
        de.end().map_err(|e| ModelError::Syntax {
            source_name: source.clone(),
            line: e.line(),
            column: e.column(),
            message: strip_position(&e.to_string()),
        })?;
        model
            .validated()
            .map_err(|InvalidModel { path, problem }| ModelError::Invalid {
                source_name: source,
                path,
                problem,
            })
    }

    /// Read, parse and validate a model file.
    pub fn from_file(path: &Path) -> Result<ValidModel, ModelError> {
        let source = Source::File(path.to_path_buf());
        let text = std::fs::read_to_string(path).map_err(|io| ModelError::Read {
            source_name: source.clone(),
            io,
        })?;
        Model::from_json(&text, source)
    }

    /// The built-in default: the paper's free-free rigid-flexible assembly.
    pub fn builtin() -> ValidModel {
        Model::from_json(DEFAULT_MODEL_JSON, Source::BuiltIn).expect("the built-in model is valid")
    }

    /// The built-in switch-off assembly.
    pub fn switch_off_builtin() -> ValidModel {
        Model::from_json(SWITCH_OFF_MODEL_JSON, Source::BuiltIn)
            .expect("the built-in switch-off model is valid")
    }

    /// The built-in switch-off assembly before its calibration (F_x² at
    /// the blade tip; its description says what else follows from that).
    pub fn switch_off_uncalibrated_builtin() -> ValidModel {
        Model::from_json(SWITCH_OFF_UNCALIBRATED_MODEL_JSON, Source::BuiltIn)
            .expect("the built-in uncalibrated switch-off model is valid")
    }

    /// The JSON Schema of the model file, generated from these serde types
    /// (`ancf-modal schema`). It checks structure and types; the physics
    /// and cross references are [`Model::validate`]'s.
    pub fn json_schema() -> serde_json::Value {
        serde_json::to_value(schemars::schema_for!(Model)).expect("a schema serializes")
    }

    /// The model as pretty JSON (a valid model file).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("models serialize")
    }

    /// A beam by id.
    pub fn beam(&self, id: &str) -> Option<&Beam> {
        self.beams.iter().find(|b| b.id == id)
    }
}

/// serde_json appends " at line L column C"; the path already locates the value.
fn strip_position(message: &str) -> String {
    match message.rfind(" at line ") {
        Some(i) => message[..i].to_string(),
        None => message.to_string(),
    }
}
