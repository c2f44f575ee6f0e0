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
