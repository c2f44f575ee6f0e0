//! `ancf-modal convergence`: maps the flags to
//! [`ancf_modal::commands::convergence`] and renders its output.

use super::common::{print_document, Warnings};
use super::output::Output;
use ancf_modal::commands::convergence::{run as convergence, ConvergenceRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::output::plot::Format;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ConvergenceArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Finest mesh: elements per beam 2, 4, 8, … up to this number.
    #[arg(long, default_value_t = ConvergenceRequest::default().max_elements as u64, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(256)))]
    pub max_elements: u64,
    /// Number of bending modes compared.
    #[arg(long, default_value_t = ConvergenceRequest::default().modes as u64, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 1, Some(10)))]
    pub modes: u64,
}

pub fn run(args: ConvergenceArgs) -> Result<Warnings> {
    args.output
        .only("convergence", &[Output::Json, Output::Plot])?;
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let request = ConvergenceRequest {
        max_elements: args.max_elements as usize,
        modes: args.modes as usize,
    };
    let run = convergence(&input, &request)?;
    if let Some(path) = &args.output.plot {
        run.write_plot(path)?;
    }
    if args.output.json {
        print_document(&run.document)?;
    } else {
        out!("{}", run.text());
    }
    Ok(run.document.warnings)
}
