//! `ancf-modal switch-off`: the paper's switch-off experiment (Figs. 7–9)
//! on a model, by default the built-in `models/rcbo_switch_off.json`.

use super::common::{source_label, write_output};
use super::output::Output;
use ancf_modal::analysis::switch_off::{run_switch_off, SwitchOffSettings};
use ancf_modal::model::{Model, PointSpec};
use ancf_modal::output::figures::switch_off::write_switch_off_figures;
use ancf_modal::output::plot::{Format, PlotSize};
use ancf_modal::output::switch_off_report::{switch_off_csv, switch_off_table};
use ancf_modal::results::SwitchOffOutput;
use anyhow::{Context, Result};
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SwitchOffArgs {
    /// Model file (JSON); the built-in switch-off assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// End time [s].
    #[arg(long, value_name = "S", default_value_t = 3e-3, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: f64,
    /// Time step [s].
    #[arg(long, value_name = "S", default_value_t = 1e-6, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: f64,
    /// Travel distance of the tracked point [m].
    #[arg(long, value_name = "M", default_value_t = 2e-3, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub distance: f64,
    /// Travel direction `DX,DY` (global).
    #[arg(long, value_name = "DX,DY", default_value = "1,0", value_parser = parse_pair, allow_hyphen_values = true)]
    pub direction: [f64; 2],
    /// Tracked point: `BEAM:S` (arc length in m) or `BODY` (default: node 0 of the first beam).
    #[arg(long, value_name = "POINT", value_parser = parse_point)]
    pub point: Option<PointSpec>,
    /// Output sample rate [Hz] (the paper's camera: 67.2 kHz).
    #[arg(long, value_name = "HZ", default_value_t = 67_200.0, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Also run the model with every beam rigid (the paper's rigid model).
    #[arg(long)]
    pub compare_rigid: bool,
    /// Skip the check run at half the step.
    #[arg(long)]
    pub no_step_check: bool,
}

fn parse_pair(s: &str) -> Result<[f64; 2], String> {
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
    Ok([num(a)?, num(b)?])
}

fn parse_point(s: &str) -> Result<PointSpec, String> {
    match s.split_once(':') {
        Some((beam, arc)) => {
            let s_val: f64 = arc
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| format!("`{arc}` is not an arc length in m"))?;
            Ok(PointSpec {
                beam: Some(beam.to_string()),
                s: Some(s_val),
                ..PointSpec::default()
            })
        }
        None => Ok(PointSpec {
            body: Some(s.to_string()),
            ..PointSpec::default()
        }),
    }
}

pub fn run(args: SwitchOffArgs) -> Result<()> {
    args.output
        .only("switch-off", &[Output::Json, Output::Csv, Output::Plot])?;
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let model = match &args.model {
        Some(p) => Model::from_file(p)?,
        None => Model::switch_off_builtin(),
    };
    super::common::check_units(&model, args.model.as_deref());
    let settings = SwitchOffSettings {
        step: args.step,
        end_time: args.end_time,
        sample_rate: args.sample_rate,
        distance: args.distance,
        direction: args.direction,
        point: args.point.clone(),
        compare_rigid: args.compare_rigid,
        halve_step: !args.no_step_check,
        ..SwitchOffSettings::default()
    };
    let result = run_switch_off(&model, &settings)
        .map_err(super::common::simulation_error)
        .with_context(|| source_label(args.model.as_deref()))?;
    if let Some(path) = &args.output.csv {
        write_output(path, &switch_off_csv(&result))?;
    }
    if let Some(path) = &args.output.plot {
        write_switch_off_figures(&result, path, PlotSize::default())?;
    }
    if args.output.json {
        let sha = super::common::model_sha256_or(
            args.model.as_deref(),
            ancf_modal::model::SWITCH_OFF_MODEL_JSON,
        )?;
        super::common::print_json_sha(SwitchOffOutput::new(&result), &sha)?;
    } else {
        out!("{}", switch_off_table(&result));
    }
    Ok(())
}
