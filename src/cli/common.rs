//! Helpers every subcommand uses: loading the model, naming it in
//! messages, warnings, writing output files.

use ancf_modal::model::{Model, ValidModel};
use anyhow::Result;
use std::path::Path;
use std::sync::Mutex;

/// The warnings of this run, in the order given: every `--json` document
/// carries them all, and a run that succeeds prints them on stderr at its
/// end ([`print_warnings`]); a run that fails prints its one error line.
static WARNINGS: Mutex<Vec<String>> = Mutex::new(Vec::new());

/// Keeps `text` for the JSON document and the `warning: …` lines. Never
/// changes the exit code.
pub fn warn(text: String) {
    WARNINGS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .push(text);
}

/// A run's warnings, printed as `warning: …` lines at its end.
pub type Warnings = Vec<String>;

/// Prints each of `warnings` as one `warning: …` line on stderr.
pub fn print_warnings(warnings: &[String]) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// Prints a command's document (result, provenance, the run's warnings)
/// as pretty JSON.
pub fn print_document<T: serde::Serialize>(run: &ancf_modal::commands::Run<T>) -> Result<()> {
    outln!("{}", serde_json::to_string_pretty(&run.document())?);
    Ok(())
}

/// The warnings given so far.
pub fn warnings() -> Vec<String> {
    WARNINGS
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
        .clone()
}

/// Warns of the model's implausible units ([`Model::unit_warnings`]),
/// naming the model file.
pub fn check_units(model: &Model, path: Option<&Path>) {
    for w in model.unit_warnings() {
        warn(format!("{}: {w}", source_label(path)));
    }
}

/// The model file, or the built-in default when none is given; its unit
/// warnings are given ([`check_units`]).
pub fn load_model(path: Option<&Path>) -> Result<ValidModel> {
    let model = match path {
        Some(p) => Model::from_file(p)?,
        None => Model::builtin(),
    };
    check_units(&model, path);
    Ok(model)
}

/// SHA-256 of the model's bytes (the file, or the built-in model's text),
/// for the provenance of JSON documents and exported files.
pub fn model_sha256(path: Option<&Path>) -> Result<String> {
    model_sha256_or(path, ancf_modal::model::DEFAULT_MODEL_JSON)
}

/// As [`model_sha256`] for a command whose built-in model is `builtin`.
pub fn model_sha256_or(path: Option<&Path>, builtin: &str) -> Result<String> {
    use anyhow::Context;
    ancf_modal::results::provenance::model_sha256_or(path, builtin)
        .with_context(|| format!("{}: cannot read the file", source_label(path)))
}

/// Prints `doc` with `tool_version` and `model_sha256` as pretty JSON.
pub fn print_json(doc: impl serde::Serialize, path: Option<&Path>) -> Result<()> {
    print_json_sha(doc, &model_sha256(path)?)
}

/// Prints `doc` stamped with this build's version, `model_sha256` and the
/// run's `warnings`.
pub fn print_json_sha(doc: impl serde::Serialize, model_sha256: &str) -> Result<()> {
    let doc = ancf_modal::results::document(&doc, Some(model_sha256), &warnings())?;
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

/// A command's error as the command line prints it: a simulation's
/// setting or tracked point names its flag after the model (`<model>:
/// --step: …`, [`simulation_error`]); the rest as the library words it.
pub fn command_error(e: ancf_modal::commands::CommandError) -> anyhow::Error {
    use ancf_modal::commands::CommandError;
    match e {
        CommandError::Simulation { model, source } => simulation_error(source).context(model),
        e => anyhow::Error::new(e),
    }
}

/// A simulation error with the flag it concerns in front (`--point: …`,
/// `--step: …`); the library names settings, not flags.
pub fn simulation_error(e: ancf_modal::error::SimulationError) -> anyhow::Error {
    use ancf_modal::error::{Setting, SimulationError};
    let flag = match &e {
        SimulationError::InvalidPoint { .. } => Some("--point"),
        SimulationError::InvalidSetting { setting, .. } => Some(match setting {
            Setting::Step => "--step",
            Setting::EndTime => "--end-time",
            Setting::Distance => "--distance",
            Setting::Direction => "--direction",
            Setting::SampleRate => "--sample-rate",
        }),
        _ => None,
    };
    match flag {
        Some(flag) => anyhow::Error::new(e).context(flag),
        None => anyhow::Error::new(e),
    }
}
