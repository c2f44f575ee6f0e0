//! Provenance of every JSON document and exported file: the tool's version
//! and the SHA-256 of the model it describes (of the file's bytes, or of
//! the built-in model's JSON text).

use sha2::{Digest, Sha256};

/// This build's version (Cargo package version).
pub fn tool_version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// SHA-256 of the model a command describes: of the file's bytes, or of the
/// built-in model's JSON text when no file is given.
pub fn model_sha256(path: Option<&std::path::Path>) -> std::io::Result<String> {
    model_sha256_or(path, crate::model::DEFAULT_MODEL_JSON)
}

/// As [`model_sha256`], for a command whose built-in model is `builtin`
/// (e.g. `switch-off`'s assembly).
pub fn model_sha256_or(path: Option<&std::path::Path>, builtin: &str) -> std::io::Result<String> {
    Ok(match path {
        Some(p) => sha256_hex(&std::fs::read(p)?),
        None => sha256_hex(builtin.as_bytes()),
    })
}

/// The provenance of an exported file's header: two lines of at most 80
/// characters (UFF ID lines), `ancf-modal VERSION` and
/// `model_sha256 HEX`.
pub fn header_lines(model_sha256: &str) -> [String; 2] {
    [
        format!("ancf-modal {}", tool_version()),
        format!("model_sha256 {model_sha256}"),
    ]
}
