//! `ancf-modal identify`: the main job. Modal analysis, the impulse
//! experiment with its spectrum, and the paper's Table 3 side by side.

use super::common::{load_model, source_label, write_output};
use super::impulse::{experiment, ExperimentArgs};
use super::output::Output;
use ancf_modal::analysis::convergence::{mesh_convergence_with, with_elements, Reference};
use ancf_modal::analysis::impulse::ImpulseResult;
use ancf_modal::analysis::{ModalResult, ModalSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::output::figures::{
    convergence_figure, response_figure, spectrum_figure, write_figure, write_mode_shapes,
};
use ancf_modal::output::impulse_report::{signal_csv, spectrum_csv};
use ancf_modal::output::modal_report::modal_csv;
use ancf_modal::output::plot::{Figure, PlotSize};
use ancf_modal::results::identify::{choose_experiment, IDENTIFY_MODES};
use ancf_modal::results::IdentifyOutput;
use ancf_modal::{Model, System};
use anyhow::{Context, Result};
use clap::Args;
use std::fmt::Write;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct IdentifyArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    /// Directory for the data files and figures (created if missing):
    /// summary.json, modes.csv, signal.csv, spectrum.csv and modes,
    /// response, spectrum, convergence as .svg and .png.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
    #[command(flatten)]
    pub comparison: ComparisonArgs,
    /// Also write everything as one self-contained HTML report (see `report`).
    #[arg(long, value_name = "FILE.html")]
    pub html: Option<PathBuf>,
}

/// What the model is compared with and fitted to (`identify`, `report`).
#[derive(Debug, Args)]
pub struct ComparisonArgs {
    /// Also fit the equivalent beam height that matches the experiment's
    /// first bending frequency (eigenvalue-based `calibrate`); with
    /// `identify --out-dir` the calibrated model is written as calibrated.json.
    #[arg(long)]
    pub calibrate: bool,
    /// Measured hammer records (CSV or UFF 58, as for `frf`): their fitted
    /// mode nearest the model's first bending frequency replaces the
    /// model's `reference` as the experiment.
    #[arg(long, value_name = "FILE", num_args = 1..)]
    pub measured: Vec<PathBuf>,
    /// Window of the measured records (see `frf --window`).
    #[arg(long, value_name = "W", default_value = "rect", requires = "measured")]
    pub measured_window: ancf_modal::signal::Window,
    /// Fit band of the measured records, LO:HI in Hz (see `frf --band`).
    #[arg(long, value_name = "LO:HI", requires = "measured", allow_hyphen_values = true, value_parser = super::frf::parse_band)]
    pub measured_band: Option<(f64, f64)>,
}

/// What `identify` computed.
pub struct Identified {
    pub model: ValidModel,
    pub system: System,
    pub modal: ModalResult,
    pub impulse: ImpulseResult,
    pub measured: Option<ancf_modal::measured::analysis::FrfAnalysis>,
    pub output: IdentifyOutput,
    /// The comparison is the paper's Table 3.
    pub paper: bool,
}

/// Figures `--out-dir` holds, each as .svg and .png.
const FIGURES: [&str; 4] = ["modes", "response", "spectrum", "convergence"];

/// Mode shapes, impulse response, spectrum and a quick mesh convergence
/// (2…32 elements per beam against the 32-element mesh), in both formats.
fn write_figures(
    dir: &Path,
    model: &Model,
    system: &System,
    modal: &ModalResult,
    impulse: &ImpulseResult,
) -> Result<()> {
    let data = mesh_convergence_with(
        |n| with_elements(model, n),
        Reference::FinestMesh { modes: 3 },
        &[2, 4, 8, 16, 32],
    )
    .context("mesh convergence for the figure")?;
    let convergence: Figure = convergence_figure(&data).into();
    let spectrum: Figure = spectrum_figure(model, impulse).into();
    let response: Figure = response_figure(&model.name, impulse);
    for ext in ["svg", "png"] {
        let path = |name: &str| dir.join(format!("{name}.{ext}"));
        write_mode_shapes(system, &system.q0, modal, &path("modes"))?;
        write_figure(&response, &path("response"), PlotSize::default())?;
        write_figure(&spectrum, &path("spectrum"), PlotSize::default())?;
        write_figure(&convergence, &path("convergence"), PlotSize::default())?;
    }
    Ok(())
}

/// The modal analysis, the impulse experiment, the measured records and
/// the calibration `args` ask for, and the comparison.
pub fn compute(args: &IdentifyArgs) -> Result<Identified> {
    let model = load_model(args.model.as_deref())?;
    args.experiment.settings().transient.validate()?;
    let system = System::new(&model);
    let settings = ModalSettings {
        modes: Some(IDENTIFY_MODES),
        ..ModalSettings::default()
    };
    let (modal, modal_output) = ancf_modal::results::modal::modal(&model, &system, &settings)
        .with_context(|| source_label(args.model.as_deref()))?;
    let impulse = experiment(&model, args.model.as_deref(), &args.experiment)?;
    let c = &args.comparison;
    let measured = if c.measured.is_empty() {
        None
    } else {
        let m = super::frf::MeasuredArgs {
            force: None,
            response: None,
            response_quantity: super::frf::Quantity::Velocity,
            window: c.measured_window,
            estimator: super::frf::EstimatorArg::H1,
            band: c.measured_band,
            max_order: 40,
        };
        Some(m.analyse(&c.measured)?)
    };
    let (experiment, paper) =
        choose_experiment(&model, modal_output.first_bending_hz, measured.as_ref());
    let calibration = match (c.calibrate, &experiment) {
        (true, Some(e)) => Some(ancf_modal::commands::calibrate::equivalent_height(&model, e.frequency_hz)?),
        (true, None) => anyhow::bail!(
            "--calibrate needs an experiment: the model has no `reference` and no --measured records were given"
        ),
        _ => None,
    };
    let output = IdentifyOutput::new(
        &model,
        modal_output,
        &impulse,
        measured.as_ref(),
        calibration.as_ref(),
    );
    Ok(Identified {
        model,
        system,
        modal,
        impulse,
        measured,
        output,
        paper,
    })
}

pub fn run(args: IdentifyArgs) -> Result<()> {
    args.output.only("identify", &[Output::Json])?;
    let id = compute(&args)?;
    let Identified {
        model,
        system,
        modal,
        impulse,
        output,
        paper,
        ..
    } = &id;
    let summary = ancf_modal::results::document(
        &output,
        Some(&super::common::model_sha256(args.model.as_deref())?),
        &super::common::warnings(),
    )?;
    if let Some(dir) = &args.out_dir {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the output directory", dir.display()))?;
        write_output(
            &dir.join("summary.json"),
            &serde_json::to_string_pretty(&summary)?,
        )?;
        write_output(&dir.join("modes.csv"), &modal_csv(modal))?;
        write_output(&dir.join("signal.csv"), &signal_csv(impulse))?;
        write_output(&dir.join("spectrum.csv"), &spectrum_csv(impulse))?;
        if let Some(c) = &output.calibration {
            write_output(
                &dir.join("calibrated.json"),
                &(c.result.fitted_model.to_json() + "\n"),
            )?;
        }
        write_figures(dir, model, system, modal, impulse)?;
    }
    if let Some(path) = &args.html {
        super::report::write_report(path, &id, args.model.as_deref(), false)?;
    }
    if args.output.json {
        outln!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    out!("{}", report(output, *paper, args.out_dir.as_deref()));
    Ok(())
}

/// The printed report: the comparison table, the measured modes, the
/// FFT's agreement with the eigenvalue, the calibration and the run's
/// figures, all from the typed result.
fn report(output: &IdentifyOutput, paper: bool, out_dir: Option<&Path>) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: first bending frequency, {}{}",
        output.model,
        output.supports,
        if paper { " (paper Table 3)" } else { "" }
    );
    let _ = writeln!(
        s,
        "{:<40} {:>12} {:>14} {:>16}",
        "", "f [Hz]", "(f−exp)/exp", "paper: (exp−f)/f"
    );
    for row in &output.table {
        let name = &row.source;
        match (
            row.first_bending_hz,
            row.error_percent,
            row.paper_error_percent,
        ) {
            (Some(f), Some(e), Some(p)) => {
                let _ = writeln!(s, "{name:<40} {f:>12.2} {e:>13.2}% {p:>15.2}%");
            }
            (Some(f), _, _) => {
                let _ = writeln!(s, "{name:<40} {f:>12.2}");
            }
            (None, _, _) => {
                let _ = writeln!(s, "{name:<40} {:>12}", "–");
            }
        }
    }
    if output.experiment_hz.is_none() {
        let _ = writeln!(
            s,
            "no experiment to compare with: give the model a `reference` or measured records with --measured"
        );
    }
    if let Some(m) = &output.measured {
        let _ = writeln!(
            s,
            "measured modes ({} over {:.0}–{:.0} Hz): {}",
            m.files.len(),
            m.band_hz[0],
            m.band_hz[1],
            m.peaks
                .iter()
                .map(|p| format!(
                    "{:.1} Hz (ζ {:.3} %)",
                    p.frequency_hz,
                    100.0 * p.damping_ratio
                ))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    let i = &output.impulse;
    if let (Some(raw), Some(corrected)) = (i.raw_vs_eigen, i.corrected_vs_eigen) {
        let _ = writeln!(
            s,
            "FFT vs eigenvalue: raw {raw:+.2e}, corrected {corrected:+.2e} (integrator period error removed)"
        );
    }
    if let Some(c) = &output.calibration {
        let p = &c.result.parameters[0];
        let _ = writeln!(
            s,
            "equivalent geometry: {} = {:.4} mm ({:+.2} % on {:.4} mm) gives {:.3} Hz (eigenvalue, {} evaluations)",
            p.name,
            1e3 * p.fitted,
            p.change_percent,
            1e3 * p.initial,
            c.result.achieved_hz[0],
            c.result.evaluations
        );
    }
    let _ = writeln!(
        s,
        "impulse: {} steps of {:.1e} s, {:.2} Newton iterations/step, joints held to {:.1e} m",
        i.steps,
        i.step_s,
        i.newton_iterations as f64 / i.steps.max(1) as f64,
        i.max_joint_residual_m
    );
    if let Some(dir) = out_dir {
        let _ = writeln!(
            s,
            "data written to {}: summary.json, modes.csv, signal.csv, spectrum.csv{}, {}",
            dir.display(),
            if output.calibration.is_some() {
                ", calibrated.json"
            } else {
                ""
            },
            FIGURES.map(|f| format!("{f}.svg/.png")).join(", ")
        );
    }
    s
}
