//! `ancf-modal static`: maps the flags to [`ancf_modal::commands::statics`]
//! and renders its output: the static equilibrium under the model's loads
//! (node positions, joint reactions, spring forces).

use super::args::finite;
use super::common::{print_document, Warnings};
use super::output::Output;
use ancf_modal::commands::statics::{run as statics, StaticRequest};
use ancf_modal::commands::ModelInput;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct StaticArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Factor on the applied loads (gravity is not scaled). Loads act with
    /// their value at t = 0: constant loads and steps from 0 in full,
    /// half-sine pulses not at all.
    #[arg(long, default_value_t = StaticRequest::default().load_scale, value_name = "S", allow_negative_numbers = true, value_parser = finite)]
    pub load_scale: f64,
}

pub fn run(args: StaticArgs) -> Result<Warnings> {
    args.output.only("static", &[Output::Json, Output::Plot])?;
    let input = ModelInput::load(args.model.as_deref())?;
    let request = StaticRequest {
        load_scale: args.load_scale,
    };
    let run = statics(&input, &request)?;
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
