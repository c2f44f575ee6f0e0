//! Helpers every subcommand uses: loading the model, naming it in
//! messages, warnings, writing output files.

use anyhow::Result;
use std::path::Path;

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
