//! `ancf-modal` command line: parse, validate, run, print.

mod cli;

use clap::error::{ContextKind, ContextValue};
use clap::Parser;

fn main() {
    use clap::error::ErrorKind;
    let args = match cli::Cli::try_parse() {
        Ok(args) => args,
        Err(e) if e.kind() == ErrorKind::ValueValidation => {
            eprintln!("Error: {}", bad_value_line(&e));
            std::process::exit(1);
        }
        Err(e)
            if matches!(
                e.kind(),
                ErrorKind::DisplayHelp
                    | ErrorKind::DisplayVersion
                    | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
            ) =>
        {
            e.exit()
        }
        Err(e) => {
            eprintln!("Error: {}", usage_line(&e));
            std::process::exit(1);
        }
    };
    match cli::run(args) {
        Ok(warnings) => cli::print_warnings(&warnings),
        Err(e) => {
            eprintln!("Error: {}", one_line(&e));
            std::process::exit(1);
        }
    }
}

/// The error and its causes on one line, `a: b: c` (each error names its
/// own context once and leaves its cause to the chain).
fn one_line(e: &anyhow::Error) -> String {
    e.chain().map(as_flag).collect::<Vec<_>>().join(": ")
}

/// One error of the chain; a request field the library names
/// (`sample_rate`) is named as its flag (`--sample-rate`).
fn as_flag(e: &(dyn std::error::Error + 'static)) -> String {
    use ancf_modal::commands::CommandError;
    match e.downcast_ref::<CommandError>() {
        Some(CommandError::Argument {
            name,
            value,
            allowed,
        }) => format!("--{} `{value}`: {allowed}", name.replace('_', "-")),
        _ => e.to_string(),
    }
}

/// A flag's value out of its range, as one line: the flag, the value
/// given and what is allowed (``--step `-1e-6`: must be a number > 0``). Bad input, like a bad model file: exit code 1.
fn bad_value_line(e: &clap::Error) -> String {
    use std::error::Error;
    let context = |kind| match e.get(kind) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let flag = context(ContextKind::InvalidArg)
        .map(|a| a.split_whitespace().next().unwrap_or_default().to_string());
    let value = context(ContextKind::InvalidValue);
    let why = e.source().map(|s| s.to_string());
    match (flag, value, why) {
        (Some(flag), Some(value), Some(why)) => format!("{flag} `{value}`: {why}"),
        _ => e
            .render()
            .to_string()
            .lines()
            .next()
            .unwrap_or_default()
            .trim_start_matches("error: ")
            .to_string(),
    }
}

/// Any other mistake on the command line (an unknown flag, command or
/// choice, a missing or conflicting flag) as one line: clap's explanation
/// with its hints, without the usage and help lines. Bad input: exit
/// code 1, as for a bad value or a bad model file.
fn usage_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let parts: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with("Usage:") && !l.starts_with("For more information")
        })
        .collect();
    parts.join(" ").trim_start_matches("error: ").to_string()
}
