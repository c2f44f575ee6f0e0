//! `ancf-modal transient`: maps the flags to
//! [`ancf_modal::commands::transient`] and renders its output: the general
//! time integration of a model, with its sensors, contact statistics and
//! energy balance.

use super::common::{command_error, print_document, write_output, Warnings};
use ancf_modal::commands::transient::{run as transient, TransientRequest};
use ancf_modal::commands::{CommandError, ModelInput};
use ancf_modal::error::SimulationError;
use ancf_modal::output::plot::Format;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct TransientArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// End time [s].
    #[arg(long, value_name = "S", default_value_t = TransientRequest::default().end_time, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: f64,
    /// Time step [s] (shortened automatically at contact onsets).
    #[arg(long, value_name = "S", default_value_t = TransientRequest::default().step, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: f64,
    /// Spectral radius at infinity of generalized-α (1 = no numerical damping).
    #[arg(long, value_name = "R", default_value_t = TransientRequest::default().spectral_radius, allow_hyphen_values = true, value_parser = super::values::unit_interval)]
    pub spectral_radius: f64,
    /// Start at rest in the reference configuration, whatever acts on it
    /// (by default a run starts from the static equilibrium under the
    /// loads at t = 0⁻: constant loads, preloads and gravity; the
    /// reference itself when it balances them).
    #[arg(long, conflicts_with = "from_equilibrium")]
    pub from_reference: bool,
    /// Start from the static equilibrium: the default, kept for scripts.
    #[arg(long, hide = true)]
    pub from_equilibrium: bool,
    /// Output sample rate [Hz]; 0 keeps every step.
    #[arg(long, value_name = "HZ", default_value_t = TransientRequest::default().sample_rate, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Model every beam as a rigid body.
    #[arg(long)]
    pub rigid_beams: bool,
}

pub fn run(args: TransientArgs) -> Result<Warnings> {
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    if args.output.uff.is_some() && args.sample_rate <= 0.0 {
        anyhow::bail!(
            "--uff needs --sample-rate above 0 (UFF 58 time data are evenly sampled), got {}",
            args.sample_rate
        );
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let request = TransientRequest {
        end_time: args.end_time,
        step: args.step,
        spectral_radius: args.spectral_radius,
        start: ancf_modal::analysis::statics::start::Start::from_reference(args.from_reference),
        sample_rate: args.sample_rate,
        rigid_beams: args.rigid_beams,
    };
    let run = transient(&input, &request).map_err(|e| match e {
        // The flag that starts from the reference, named after the
        // library's words.
        CommandError::Simulation {
            model,
            source: e @ SimulationError::ReleaseNeedsEquilibrium { .. },
        } => anyhow::anyhow!("{e} (drop --from-reference)").context(model),
        e => command_error(e),
    })?;
    if let Some(path) = &args.output.csv {
        write_output(path, &run.csv())?;
    }
    if let Some(path) = &args.output.uff {
        write_output(path, &run.uff()?)?;
    }
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
