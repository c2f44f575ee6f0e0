//! `ancf-modal switch-off`: maps the flags to
//! [`ancf_modal::commands::switch_off`] and renders its output: the paper's
//! switch-off experiment (Figs. 7–9) on a model, by default the built-in
//! `models/rcbo_switch_off.json`.

use super::common::{command_error, print_document, write_output, Warnings};
use super::output::Output;
use ancf_modal::commands::switch_off::{parse_point, run as switch_off, SwitchOffRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::model::PointSpec;
use ancf_modal::output::plot::Format;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SwitchOffArgs {
    /// Model file (JSON); the built-in switch-off assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// End time [s].
    #[arg(long, value_name = "S", default_value_t = SwitchOffRequest::default().end_time, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: f64,
    /// Time step [s].
    #[arg(long, value_name = "S", default_value_t = SwitchOffRequest::default().step, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: f64,
    /// Travel distance of the tracked point [m].
    #[arg(long, value_name = "M", default_value_t = SwitchOffRequest::default().distance, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub distance: f64,
    /// Travel direction `DX,DY` (global).
    #[arg(long, value_name = "DX,DY", default_value_t = Pair(SwitchOffRequest::default().direction), value_parser = parse_pair, allow_hyphen_values = true)]
    pub direction: Pair,
    /// Tracked point: `BEAM:S` (arc length in m) or `BODY` (default: node 0 of the first beam).
    #[arg(long, value_name = "POINT", value_parser = parse_point)]
    pub point: Option<PointSpec>,
    /// Output sample rate [Hz] (the paper's camera: 67.2 kHz).
    #[arg(long, value_name = "HZ", default_value_t = SwitchOffRequest::default().sample_rate, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Also run the model with every beam rigid (the paper's rigid model).
    #[arg(long)]
    pub compare_rigid: bool,
    /// Skip the check run at half the step.
    #[arg(long)]
    pub no_step_check: bool,
    /// Also run the paper's Fig. 10 study: the pre-stress ×2, c_t = 1 N m/rad and the spring's
    /// ground point −1 mm in y, each alone and all three together (predictions).
    #[arg(long)]
    pub fig10: bool,
}

/// Two numbers written `A,B`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair(pub [f64; 2]);

impl std::fmt::Display for Pair {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{}", self.0[0], self.0[1])
    }
}

fn parse_pair(s: &str) -> Result<Pair, String> {
    let parts: Vec<&str> = s.split(',').collect();
    let [a, b] = parts[..] else {
        return Err(format!("`{s}` is not DX,DY"));
    };
    let num = |t: &str| {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("`{t}` is not a finite number"))
    };
    Ok(Pair([num(a)?, num(b)?]))
}

pub fn run(args: SwitchOffArgs) -> Result<Warnings> {
    args.output
        .only("switch-off", &[Output::Json, Output::Csv, Output::Plot])?;
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let input = ModelInput::load_switch_off(args.model.as_deref())?;
    let request = SwitchOffRequest {
        end_time: args.end_time,
        step: args.step,
        distance: args.distance,
        direction: args.direction.0,
        point: args.point.clone(),
        sample_rate: args.sample_rate,
        compare_rigid: args.compare_rigid,
        no_step_check: args.no_step_check,
        fig10: args.fig10,
    };
    let run = switch_off(&input, &request).map_err(command_error)?;
    if let Some(path) = &args.output.csv {
        write_output(path, &run.csv())?;
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
