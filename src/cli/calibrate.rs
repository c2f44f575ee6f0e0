//! `ancf-modal calibrate`: maps the flags to
//! [`ancf_modal::commands::calibrate`] and renders its output: model
//! parameters fitted to measured frequencies (the paper's "equivalent
//! geometry").

use super::common::{command_error, print_document, write_output, Warnings};
use super::impulse::ExperimentArgs;
use super::output::Output;
use ancf_modal::analysis::calibrate::{CalibrationError, ParameterSpec};
use ancf_modal::commands::calibrate::{run as calibrate, CalibrateRequest, Method, TargetKind};
use ancf_modal::commands::{CommandError, ModelInput};
use ancf_modal::output::plot::{write_atomic, Format};
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

impl From<KindArg> for TargetKind {
    fn from(k: KindArg) -> Self {
        match k {
            KindArg::Bending => TargetKind::Bending,
            KindArg::Axial => TargetKind::Axial,
            KindArg::Spring => TargetKind::Spring,
        }
    }
}

impl From<TargetKind> for KindArg {
    fn from(k: TargetKind) -> Self {
        match k {
            TargetKind::Bending => KindArg::Bending,
            TargetKind::Axial => KindArg::Axial,
            TargetKind::Spring => KindArg::Spring,
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

impl From<MethodArg> for Method {
    fn from(m: MethodArg) -> Self {
        match m {
            MethodArg::Eigen => Method::Eigen,
            MethodArg::Impulse => Method::Impulse,
        }
    }
}

impl From<Method> for MethodArg {
    fn from(m: Method) -> Self {
        match m {
            Method::Eigen => MethodArg::Eigen,
            Method::Impulse => MethodArg::Impulse,
        }
    }
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
    /// Fit the modes at the static equilibrium under the model's loads,
    /// preloads and gravity (pre-stressed, as `modal --prestress`) instead
    /// of the reference; implied by a load's force (ID.force_x,
    /// ID.force_y) among the parameters.
    #[arg(long)]
    pub prestress: bool,
    /// Kind of the modes the targets refer to.
    #[arg(long, value_enum, default_value_t = KindArg::from(CalibrateRequest::default().mode_kind))]
    pub mode_kind: KindArg,
    /// Mode numbers (1-based, among the modes of --mode-kind), one per
    /// target; default 1, 2, ….
    #[arg(long, value_name = "N[,N...]", value_delimiter = ',',
          allow_hyphen_values = true, value_parser = super::values::at_least_one)]
    pub mode: Vec<u64>,
    /// How each candidate is evaluated.
    #[arg(long, value_enum, default_value_t = MethodArg::from(CalibrateRequest::default().method))]
    pub method: MethodArg,
    /// Stop when every frequency is this close to its target [Hz]
    /// (default 1e-10 × target; 1e-3 Hz with --method impulse).
    #[arg(long, value_name = "HZ", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub tolerance: Option<f64>,
    /// Most model evaluations.
    #[arg(long, default_value_t = CalibrateRequest::default().max_evaluations as u64, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(10_000)))]
    pub max_evaluations: u64,
    /// Write the calibrated model (a valid model file) here.
    #[arg(long, value_name = "FITTED.json")]
    pub out: Option<PathBuf>,
    /// Calibrate to a transient: the switch-off quantity the --target is
    /// (time_to_distance_s, in s), one --param (Brent; fixed step).
    #[arg(long, value_name = "Q", conflicts_with_all = ["trajectory", "target_from"])]
    pub quantity: Option<String>,
    /// Calibrate to a measured trajectory of the tracked point: a CSV of
    /// t [s], x [m], y [m] (least squares, Levenberg–Marquardt; standard
    /// errors from the Jacobian and residual; fixed step).
    #[arg(long, value_name = "FILE.csv", conflicts_with = "target_from")]
    pub trajectory: Option<PathBuf>,
    /// With --quantity or --trajectory: the spring's preload follows the
    /// ON-state balance of moments that keeps the contact's force.
    #[arg(long, value_name = "SPRING:CONTACT")]
    pub balance: Option<String>,
    /// Settings of the experiment for --method impulse.
    #[command(flatten, next_help_heading = "Impulse method (--method impulse)")]
    pub experiment: ExperimentArgs,
}

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

/// The request from the flags.
pub fn request(args: &CalibrateArgs) -> Result<CalibrateRequest> {
    Ok(CalibrateRequest {
        targets_hz: args.target.clone(),
        target_from: args.target_from.clone(),
        params: args.params.clone(),
        keep_mass: args.keep_mass,
        mode_kind: args.mode_kind.into(),
        modes: args.mode.iter().map(|&n| n as usize).collect(),
        method: args.method.into(),
        tolerance: args.tolerance,
        max_evaluations: args.max_evaluations as usize,
        experiment: args.experiment.request(),
        prestress: args.prestress,
    })
}

pub fn run(args: CalibrateArgs) -> Result<Warnings> {
    args.output
        .only("calibrate", &[Output::Json, Output::Plot])?;
    let plot_format = args
        .output
        .plot
        .as_deref()
        .map(Format::from_path)
        .transpose()?;
    if args.quantity.is_some() || args.trajectory.is_some() {
        // A transient fit runs the switch-off: its built-in assembly.
        let input = ModelInput::load_switch_off(args.model.as_deref())?;
        return run_transient(&args, &input);
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let run = calibrate(&input, &request(&args)?).map_err(|e| match e {
        CommandError::Calibration { source, .. } => flagged(source),
        e => command_error(e),
    })?;
    // Everything is computed before any file is written.
    let plot_bytes = match plot_format {
        Some(f) => Some(run.plot(f)?),
        None => None,
    };
    if let Some(path) = &args.out {
        write_output(path, &run.fitted_json())?;
    }
    if let (Some(path), Some(bytes)) = (&args.output.plot, plot_bytes) {
        write_atomic(path, &bytes)?;
    }
    print_fit(&args, &run.document, &run.text())
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

/// `calibrate --quantity` / `--trajectory`: the transient request.
fn run_transient(args: &CalibrateArgs, input: &ModelInput) -> Result<Warnings> {
    use ancf_modal::commands::calibrate_transient::{
        run, CalibrateTransientRequest, TrajectoryInput,
    };
    args.output.only("calibrate", &[Output::Json])?;
    if args.target.len() > 1 {
        anyhow::bail!(
            "--target: a transient fit takes one time [s], got {} values",
            args.target.len()
        );
    }
    let request = CalibrateTransientRequest {
        quantity: args.quantity.clone(),
        target_s: args.target.first().copied(),
        trajectory: args.trajectory.clone().map(TrajectoryInput::File),
        params: args.params.clone(),
        balance: args.balance.clone(),
        tolerance_s: args.tolerance,
        max_evaluations: args.max_evaluations as usize,
        step: args
            .experiment
            .step
            .unwrap_or(CalibrateTransientRequest::default().step),
        end_time: args
            .experiment
            .end_time
            .unwrap_or(CalibrateTransientRequest::default().end_time),
        ..CalibrateTransientRequest::default()
    };
    let run = run(input, &request).map_err(|e| match e {
        CommandError::Argument {
            name,
            value,
            allowed,
        } => {
            anyhow::anyhow!(
                "--{}: `{value}`: {allowed}",
                name.replace('_', "-").replace("params", "param")
            )
        }
        e => command_error(e),
    })?;
    if let Some(path) = &args.out {
        write_output(path, &run.fitted_json())?;
    }
    print_fit(args, &run.document, &run.text())
}

/// The document (`--json`) or the report and where the model went.
fn print_fit<T: serde::Serialize>(
    args: &CalibrateArgs,
    document: &ancf_modal::commands::Run<T>,
    text: &str,
) -> Result<Warnings> {
    if args.output.json {
        print_document(document)?;
    } else {
        out!("{}", text);
        if let Some(path) = &args.out {
            outln!("calibrated model written to {}", path.display());
        }
    }
    Ok(document.warnings.clone())
}
