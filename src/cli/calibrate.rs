//! `ancf-modal calibrate`: fit model parameters to measured frequencies
//! (the paper's "equivalent geometry").

use super::common::{load_model, print_json, write_output};
use super::impulse::ExperimentArgs;
use super::output::Output;
use ancf_modal::analysis::calibrate::{
    calibrate, calibrate_with, sweep, CalibrationError, CalibrationRequest, CalibrationResult,
    CalibrationSettings, EigenFrequencies, ImpulseFrequency, ModeSelection, ParameterSet,
    ParameterSpec,
};
use ancf_modal::analysis::ModeKind;
use ancf_modal::model::Model;
use ancf_modal::output::calibrate_report::{calibrate_table, calibration_plot};
use ancf_modal::output::plot::{
    calibration_figure, render, write_atomic, Figure, Format, PlotSize,
};
use ancf_modal::results::CalibrationOutput;
use anyhow::Result;
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// Mode kinds a target can refer to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum KindArg {
    Bending,
    Axial,
    Spring,
}

impl From<KindArg> for ModeKind {
    fn from(k: KindArg) -> Self {
        match k {
            KindArg::Bending => ModeKind::Bending,
            KindArg::Axial => ModeKind::Axial,
            KindArg::Spring => ModeKind::Spring,
        }
    }
}

/// How each candidate parameter value is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Eigenproblem at the reference (analytic sensitivities).
    Eigen,
    /// The impulse experiment and its FFT for each candidate (first
    /// bending, one parameter; about a second per evaluation).
    Impulse,
}

#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Measured frequencies [Hz], comma-separated, one per mode; default:
    /// the model's `reference.first_bending_hz`.
    #[arg(
        long,
        value_name = "HZ[,HZ...]",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub target: Vec<f64>,
    /// Take the targets from the `peaks` of an `frf --json` result (in
    /// order of frequency; as many as --mode lists, or all).
    #[arg(long, value_name = "RESULT.json", conflicts_with = "target")]
    pub target_from: Option<PathBuf>,
    /// Parameter to fit, repeatable: height, width, young, density,
    /// ID.mass, ID.inertia, ID.torsion_stiffness, ID.stiffness (or
    /// BEAM.height, …), optionally with bounds in SI units: NAME=LO:HI.
    /// Default: height.
    #[arg(long = "param", value_name = "NAME[=LO:HI]", value_parser = parse_param)]
    pub params: Vec<ParameterSpec>,
    /// Keep each beam's mass while its section changes (density adjusts).
    #[arg(long)]
    pub keep_mass: bool,
    /// Kind of the modes the targets refer to.
    #[arg(long, value_enum, default_value_t = KindArg::Bending)]
    pub mode_kind: KindArg,
    /// Mode numbers (1-based, among the modes of --mode-kind), one per
    /// target; default 1, 2, ….
    #[arg(long, value_name = "N[,N...]", value_delimiter = ',',
          allow_hyphen_values = true, value_parser = super::values::at_least_one)]
    pub mode: Vec<u64>,
    /// How each candidate is evaluated.
    #[arg(long, value_enum, default_value_t = MethodArg::Eigen)]
    pub method: MethodArg,
    /// Stop when every frequency is this close to its target [Hz]
    /// (default 1e-10 × target; 1e-3 Hz with --method impulse).
    #[arg(long, value_name = "HZ", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub tolerance: Option<f64>,
    /// Most model evaluations.
    #[arg(long, default_value_t = 60, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(10_000)))]
    pub max_evaluations: u64,
    /// Write the calibrated model (a valid model file) here.
    #[arg(long, value_name = "FITTED.json")]
    pub out: Option<PathBuf>,
    /// Settings of the experiment for --method impulse.
    #[command(flatten, next_help_heading = "Impulse method (--method impulse)")]
    pub experiment: ExperimentArgs,
}

/// Default stopping tolerance of the impulse method [Hz]: well inside the
/// 0.01 Hz acceptance, and above the resolution of the FFT peak
/// interpolation so the bracketing does not chase its noise.
const IMPULSE_TOLERANCE_HZ: f64 = 1e-3;

/// `NAME` or `NAME=LO:HI`.
fn parse_param(s: &str) -> Result<ParameterSpec, String> {
    let Some((name, range)) = s.split_once('=') else {
        return Ok(ParameterSpec::named(s));
    };
    let (lo, hi) = range
        .split_once(':')
        .ok_or_else(|| format!("bounds must be LO:HI, got `{range}`"))?;
    let num = |v: &str| {
        v.trim()
            .parse::<f64>()
            .map_err(|e| format!("bound `{v}`: {e}"))
    };
    Ok(ParameterSpec {
        name: name.to_string(),
        bounds: Some((num(lo)?, num(hi)?)),
    })
}

/// Frequencies of the `peaks` of an `frf --json` document, ascending; the
/// first `count` of them (all when `count` is 0).
fn targets_from(path: &std::path::Path, count: usize) -> Result<Vec<f64>> {
    use anyhow::Context;
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read the file", path.display()))?;
    let doc: serde_json::Value = serde_json::from_str(&text)
        .with_context(|| format!("{}: not a JSON document", path.display()))?;
    let peaks = doc["peaks"].as_array().with_context(|| {
        format!(
            "{}: no `peaks` array (write it with `ancf-modal frf --json`)",
            path.display()
        )
    })?;
    let mut f = peaks
        .iter()
        .enumerate()
        .map(|(i, p)| {
            p["frequency_hz"]
                .as_f64()
                .filter(|f| f.is_finite() && *f > 0.0)
                .with_context(|| {
                    format!(
                        "{}: peaks[{i}].frequency_hz is not a positive number",
                        path.display()
                    )
                })
        })
        .collect::<Result<Vec<f64>>>()?;
    if f.is_empty() {
        anyhow::bail!(
            "{}: the frf result holds no peak to calibrate to",
            path.display()
        );
    }
    f.sort_by(f64::total_cmp);
    if count > 0 {
        if f.len() < count {
            anyhow::bail!(
                "{}: {} peak(s), but --mode lists {count} modes",
                path.display(),
                f.len()
            );
        }
        f.truncate(count);
    }
    Ok(f)
}

/// The request from the flags and the model.
pub fn request(args: &CalibrateArgs, model: &Model) -> Result<CalibrationRequest> {
    let targets_hz = if let Some(path) = &args.target_from {
        targets_from(path, args.mode.len())?
    } else if args.target.is_empty() {
        match &model.reference {
            Some(r) => vec![r.first_bending_hz],
            None => return Err(flagged(CalibrationError::NoTargets)),
        }
    } else {
        args.target.clone()
    };
    let parameters = if args.params.is_empty() {
        vec![ParameterSpec::named("height")]
    } else {
        args.params.clone()
    };
    Ok(CalibrationRequest {
        parameters,
        targets_hz,
        modes: ModeSelection {
            kind: args.mode_kind.into(),
            numbers: args.mode.iter().map(|&n| n as usize).collect(),
        },
        keep_mass: args.keep_mass,
    })
}

pub fn run(args: CalibrateArgs) -> Result<()> {
    args.output
        .only("calibrate", &[Output::Json, Output::Plot])?;
    let plot_format = args
        .output
        .plot
        .as_deref()
        .map(Format::from_path)
        .transpose()?;
    let model = load_model(args.model.as_deref())?;
    let request = request(&args, &model)?;
    let impulse = args.method == MethodArg::Impulse;
    let settings = CalibrationSettings {
        tolerance_hz: args.tolerance.or(impulse.then_some(IMPULSE_TOLERANCE_HZ)),
        max_evaluations: args.max_evaluations as usize,
        ..CalibrationSettings::default()
    };
    let result = match args.method {
        MethodArg::Eigen => calibrate(&model, &request, &settings).map_err(flagged)?,
        MethodArg::Impulse => {
            let experiment = args.experiment.settings();
            experiment.transient.validate()?;
            let eval = ImpulseFrequency::new(&request.modes, experiment).map_err(flagged)?;
            calibrate_with(&model, &request, &settings, &eval, &[1]).map_err(flagged)?
        }
    };
    // Everything is computed before any file is written.
    let plot_bytes = match (&args.output.plot, plot_format) {
        (Some(_), Some(format)) => {
            let data = plot_data(&model, &request, &settings, &result)?;
            let figure = calibration_figure(&calibration_plot(&model.name, &result, data));
            Some(render(&Figure::from(figure), format, PlotSize::default())?)
        }
        _ => None,
    };
    if let Some(path) = &args.out {
        write_output(path, &(result.fitted_model.to_json() + "\n"))?;
    }
    if let (Some(path), Some(bytes)) = (&args.output.plot, plot_bytes) {
        write_atomic(path, &bytes)?;
    }
    if args.output.json {
        print_json(
            CalibrationOutput::new(&model.name, &result),
            args.model.as_deref(),
        )?;
    } else {
        out!("{}", calibrate_table(&model.name, &result));
        if let Some(path) = &args.out {
            outln!("calibrated model written to {}", path.display());
        }
    }
    Ok(())
}

/// A sweep of the first parameter over the span of the iterates (padded),
/// the other parameters at their fitted values. The sweep is always the
/// eigenvalue curve (cheap); with --method impulse the iterates are the
/// experiment's, which agree with it to ~1e-6.
fn plot_data(
    model: &Model,
    request: &CalibrationRequest,
    settings: &CalibrationSettings,
    result: &CalibrationResult,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let set = ParameterSet::resolve(model, &request.parameters, request.keep_mass)?;
    let eval = EigenFrequencies::new(
        model,
        &request.modes,
        request.targets_hz.len(),
        settings.modal,
    )?;
    let fitted: Vec<f64> = result.parameters.iter().map(|p| p.fitted).collect();
    let xs = result.history.iter().map(|h| h.parameters[0]);
    let (lo, hi) = xs.fold((fitted[0], fitted[0]), |(a, b), x| (a.min(x), b.max(x)));
    let p = &set.params[0];
    let pad = 0.15 * (hi - lo).max(0.02 * fitted[0]);
    let (lo, hi) = ((lo - pad).max(p.lower), (hi + pad).min(p.upper));
    const POINTS: usize = 25;
    let values: Vec<f64> = (0..POINTS)
        .map(|k| lo + (hi - lo) * k as f64 / (POINTS - 1) as f64)
        .collect();
    Ok(sweep(&set, &eval, &fitted, 0, &values))
}

/// A calibration error with the flag it concerns in front (`--param: …`);
/// the library names quantities, not flags.
fn flagged(e: CalibrationError) -> anyhow::Error {
    use CalibrationError as E;
    let flag = match &e {
        E::NoParameters
        | E::Parameter(_)
        | E::DuplicateParameter { .. }
        | E::InvalidBounds { .. }
        | E::Unreachable { .. } => "--param",
        E::NoTargets | E::TargetNotPositive { .. } => "--target",
        E::DensityWithKeepMass { .. } => "--keep-mass",
        E::ModeCount { .. } | E::ModeNotFound { .. } => "--mode",
        E::ImpulseMode { .. } | E::NeedsSensitivities { .. } => "--method",
        _ => return e.into(),
    };
    anyhow::Error::new(e).context(flag)
}
