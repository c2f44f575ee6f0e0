//! Helpers every subcommand uses: loading the model, naming it in
//! messages, writing output files.

use ancf_modal::model::Model;
use anyhow::Result;
use std::path::Path;

/// The model file, or the built-in default when none is given.
pub fn load_model(path: Option<&Path>) -> Result<Model> {
    Ok(match path {
        Some(p) => Model::from_file(p)?,
        None => Model::builtin(),
    })
}

/// SHA-256 of the model's bytes (the file, or the built-in model's text),
/// for the provenance of JSON documents and exported files.
pub fn model_sha256(path: Option<&Path>) -> Result<String> {
    model_sha256_or(path, ancf_modal::model::DEFAULT_MODEL_JSON)
}

/// As [`model_sha256`] for a command whose built-in model is `builtin`.
pub fn model_sha256_or(path: Option<&Path>, builtin: &str) -> Result<String> {
    use anyhow::Context;
    ancf_modal::output::provenance::model_sha256_or(path, builtin)
        .with_context(|| format!("{}: cannot read the file", source_label(path)))
}

/// Prints `doc` with `tool_version` and `model_sha256` as pretty JSON.
pub fn print_json(doc: impl serde::Serialize, path: Option<&Path>) -> Result<()> {
    print_json_sha(doc, &model_sha256(path)?)
}

/// Prints `doc` stamped with this build's version and `model_sha256`.
pub fn print_json_sha(doc: impl serde::Serialize, model_sha256: &str) -> Result<()> {
    let mut doc = serde_json::to_value(doc)?;
    ancf_modal::output::provenance::stamp(&mut doc, model_sha256);
    outln!("{}", serde_json::to_string_pretty(&doc)?);
    Ok(())
}

/// The model's name in messages: its path, or `<built-in model>`.
pub fn source_label(path: Option<&Path>) -> String {
    match path {
        Some(p) => ancf_modal::error::Source::File(p.to_path_buf()).to_string(),
        None => ancf_modal::error::Source::BuiltIn.to_string(),
    }
}

/// Write text to a file atomically.
pub fn write_output(path: &Path, text: &str) -> Result<()> {
    ancf_modal::output::files::write_atomic(path, text.as_bytes())?;
    Ok(())
}

/// Writes `text` to standard output. A reader that closed the pipe (`| head`)
/// has all it wants: the program ends quietly with success, as Unix tools
/// do, instead of panicking in `print!`.
pub fn emit(text: &str) -> Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => std::process::exit(0),
        other => Ok(other?),
    }
}

/// Writes `damping_ratio` (and a complex mode's `damped_frequency_hz`)
/// into the JSON entries of the modes.
pub fn add_damping(
    modes: &mut [serde_json::Value],
    damping: &[ancf_modal::analysis::damped_modes::ModeDamping],
) {
    for (entry, d) in modes.iter_mut().zip(damping) {
        entry["damping_ratio"] = serde_json::json!(d.damping_ratio);
        if d.complex {
            entry["damped_frequency_hz"] = serde_json::json!(d.damped_frequency_hz);
        }
    }
}
