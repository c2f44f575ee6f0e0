//! What every command runs on: a validated model with where it came from
//! (for messages) and the SHA-256 of the bytes it was read from (for the
//! provenance of every document and exported file).

use crate::error::{ModelError, Source};
use crate::model::{Model, ValidModel, DEFAULT_MODEL_JSON, SWITCH_OFF_MODEL_JSON};
use crate::results::provenance::sha256_hex;
use std::path::Path;
use std::sync::Arc;

/// A validated model, its source and its hash. Cheap to clone (the model
/// is shared).
#[derive(Debug, Clone)]
pub struct ModelInput {
    /// The validated model.
    pub model: Arc<ValidModel>,
    /// Where it came from: a file, or the built-in model.
    pub source: Source,
    /// SHA-256 (lower-case hex) of the JSON text it was parsed from.
    pub sha256: String,
}

impl ModelInput {
    /// Parses and validates `text`, read from `source`.
    pub fn parse(text: &str, source: Source) -> Result<ModelInput, ModelError> {
        let model = Model::from_json(text, source.clone())?;
        Ok(ModelInput {
            model: Arc::new(model),
            source,
            sha256: sha256_hex(text.as_bytes()),
        })
    }

    /// Reads, parses and validates the model file at `path`.
    pub fn from_file(path: &Path) -> Result<ModelInput, ModelError> {
        let source = Source::File(path.to_path_buf());
        let text = std::fs::read_to_string(path).map_err(|io| ModelError::Read {
            source_name: source.clone(),
            io,
        })?;
        ModelInput::parse(&text, source)
    }

    /// The model file at `path`, or the built-in model whose JSON text is
    /// `builtin` when there is none.
    pub fn file_or(path: Option<&Path>, builtin: &str) -> Result<ModelInput, ModelError> {
        match path {
            Some(p) => ModelInput::from_file(p),
            None => ModelInput::parse(builtin, Source::BuiltIn),
        }
    }

    /// The model file at `path`, or the paper's free-free assembly.
    pub fn load(path: Option<&Path>) -> Result<ModelInput, ModelError> {
        ModelInput::file_or(path, DEFAULT_MODEL_JSON)
    }

    /// The model file at `path`, or the paper's switch-off assembly.
    pub fn load_switch_off(path: Option<&Path>) -> Result<ModelInput, ModelError> {
        ModelInput::file_or(path, SWITCH_OFF_MODEL_JSON)
    }

    /// A model built in memory (edited parameters): validated, named
    /// `source`, hashed by its JSON text.
    pub fn from_model(model: Model, source: Source) -> Result<ModelInput, ModelError> {
        ModelInput::parse(&model.to_json(), source)
    }

    /// The model's name in messages: its path, or `<built-in model>`.
    pub fn label(&self) -> String {
        self.source.to_string()
    }

    /// The model's unit warnings ([`Model::unit_warnings`]), each named by
    /// the source.
    pub fn unit_warnings(&self) -> Vec<String> {
        let label = self.label();
        self.model
            .unit_warnings()
            .iter()
            .map(|w| format!("{label}: {w}"))
            .collect()
    }
}
