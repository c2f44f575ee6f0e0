//! `ancf-modal report`: maps the flags to [`ancf_modal::commands::report`]
//! and writes its page: for a model with an excitation everything
//! `identify` computes (comparison, impulse, calibration, measured
//! records); for any model the assembly and the animated modes, the
//! pre-stressed modes beside them (`--prestress`) and the switch-off when
//! the model releases something.

use super::common::Warnings;
use super::identify::{progress_line, request, ComparisonArgs};
use super::impulse::ExperimentArgs;
use ancf_modal::commands::report::{run_with_progress, ReportRequest};
use ancf_modal::commands::ModelInput;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// The HTML file to write.
    #[arg(long, value_name = "FILE.html", default_value_os_t = ReportRequest::default().out)]
    pub out: PathBuf,
    /// Also the modes at the static equilibrium under the model's loads,
    /// beside the unstressed ones.
    #[arg(long)]
    pub prestress: bool,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
    #[command(flatten)]
    pub comparison: ComparisonArgs,
}

/// The request of `report`'s flags, `identify --html`'s with `out`.
pub fn report_request(out: PathBuf, prestress: bool) -> ReportRequest {
    ReportRequest {
        out,
        prestress,
        command_line: command_line(std::env::args()),
        ..ReportRequest::default()
    }
}

/// The command as a user types it: the program by its file name (not the
/// path it ran from, which is the machine's, not the command's), each
/// argument with a space or a quote in single quotes.
fn command_line(args: impl Iterator<Item = String>) -> String {
    args.enumerate()
        .map(|(i, a)| {
            if i == 0 {
                let name = std::path::Path::new(&a).file_name();
                name.map_or(a.clone(), |n| n.to_string_lossy().into_owned())
            } else if a.is_empty() || a.contains([' ', '\'', '"', '\t']) {
                format!("'{}'", a.replace('\'', "'\\''"))
            } else {
                a
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

pub fn run(args: ReportArgs) -> Result<Warnings> {
    let input = ModelInput::load(args.model.as_deref())?;
    let request = ReportRequest {
        identify: request(&args.experiment, &args.comparison),
        ..report_request(args.out, args.prestress)
    };
    let page = progress_line(|progress| Ok(run_with_progress(&input, &request, progress)?))?;
    page.write()?;
    outln!("report written to {}", page.out.display());
    Ok(page.warnings)
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_command_line_names_the_program_not_its_path() {
        let args = [
            "/home/me/build/target/release/ancf-modal",
            "report",
            "my model.json",
        ];
        assert_eq!(
            super::command_line(args.iter().map(|s| s.to_string())),
            "ancf-modal report 'my model.json'"
        );
    }
}
