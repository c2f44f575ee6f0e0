//! `ancf-modal identify`: the main job. Modal analysis, the impulse
//! experiment with its spectrum, and the paper's Table 3 side by side.

use super::common::{load_model, source_label, write_output};
use super::impulse::{experiment, ExperimentArgs};
use ancf_modal::analysis::convergence::{mesh_convergence_with, with_elements, Reference};
use ancf_modal::analysis::impulse::ImpulseResult;
use ancf_modal::analysis::{modal_at_reference, ModalResult, ModalSettings};
use ancf_modal::output::calibrate_report::calibrate_json;
use ancf_modal::output::figures::{
    convergence_figure, response_figure, spectrum_figure, write_figure, write_mode_shapes,
};
use ancf_modal::output::impulse_report::{impulse_json, signal_csv, spectrum_csv};
use ancf_modal::output::modal_report::{modal_csv, modal_json};
use ancf_modal::output::plot::{Figure, PlotSize};
use ancf_modal::reference::{self, Errors};
use ancf_modal::{Model, System};
use anyhow::{Context, Result};
use clap::Args;
use serde_json::json;
use std::fmt::Write;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct IdentifyArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// Directory for the data files and figures (created if missing):
    /// summary.json, modes.csv, signal.csv, spectrum.csv and modes,
    /// response, spectrum, convergence as .svg and .png.
    #[arg(long, value_name = "DIR")]
    pub out_dir: Option<PathBuf>,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
    /// Print one JSON document instead of the report.
    #[arg(long)]
    pub json: bool,
    /// Also fit the equivalent beam height that matches the experiment's
    /// first bending frequency (eigenvalue-based `calibrate`); with
    /// --out-dir the calibrated model is written as calibrated.json.
    #[arg(long)]
    pub calibrate: bool,
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
    let response: Figure = response_figure(&model.name, impulse).into();
    for ext in ["svg", "png"] {
        let path = |name: &str| dir.join(format!("{name}.{ext}"));
        write_mode_shapes(system, &system.q0, modal, &path("modes"))?;
        write_figure(&response, &path("response"), PlotSize::default())?;
        write_figure(&spectrum, &path("spectrum"), PlotSize::default())?;
        write_figure(&convergence, &path("convergence"), PlotSize::default())?;
    }
    Ok(())
}

pub fn run(args: IdentifyArgs) -> Result<()> {
    let model = load_model(args.model.as_deref())?;
    args.experiment.settings().transient.validate()?;
    let system = System::new(&model);
    let modal = modal_at_reference(
        &system,
        &ModalSettings {
            modes: Some(12),
            ..ModalSettings::default()
        },
    )
    .with_context(|| source_label(args.model.as_deref()))?;
    let impulse = experiment(&model, args.model.as_deref(), &args.experiment)?;
    let table3 = reference::table3();
    let experiment_hz = model
        .reference
        .as_ref()
        .map_or(table3.experiment_hz, |r| r.first_bending_hz);
    let calibration = if args.calibrate {
        Some(super::calibrate::equivalent_height(&model, experiment_hz)?)
    } else {
        None
    };
    let eigen = modal.first_bending().map(|m| m.frequency_hz);
    let fft = impulse.first_bending.map(|f| f.corrected_hz);
    let rows: Vec<(&str, Option<f64>)> = vec![
        ("experiment (paper Table 3)", Some(experiment_hz)),
        ("this tool, eigenvalue", eigen),
        ("this tool, impulse + FFT (corrected)", fft),
        (
            "this tool, impulse + FFT (raw)",
            impulse.first_bending.map(|f| f.raw_hz),
        ),
        ("paper, ANCF", Some(table3.ancf_hz)),
        ("paper, ANSYS BEAM188", Some(table3.ansys_hz)),
    ];
    let summary = json!({
        "model": model.name,
        "experiment_hz": experiment_hz,
        "table": rows.iter().map(|(name, f)| json!({
            "source": name,
            "first_bending_hz": f,
            "error_percent": f.map(|f| Errors::new(f, experiment_hz).error_percent),
            "paper_error_percent": f.map(|f| Errors::new(f, experiment_hz).paper_error_percent),
        })).collect::<Vec<_>>(),
        "reference_source": reference::source(),
        "modal": modal_json(&model.name, &modal),
        "impulse": impulse_json(&model.name, &impulse, Some(experiment_hz)),
        "calibration": calibration.as_ref().map(|c| calibrate_json(&model.name, c)),
    });
    if let Some(dir) = &args.out_dir {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the output directory", dir.display()))?;
        write_output(
            &dir.join("summary.json"),
            &serde_json::to_string_pretty(&summary)?,
        )?;
        write_output(&dir.join("modes.csv"), &modal_csv(&modal))?;
        write_output(&dir.join("signal.csv"), &signal_csv(&impulse))?;
        write_output(&dir.join("spectrum.csv"), &spectrum_csv(&impulse))?;
        if let Some(c) = &calibration {
            write_output(
                &dir.join("calibrated.json"),
                &(c.fitted_model.to_json() + "\n"),
            )?;
        }
        write_figures(dir, &model, &system, &modal, &impulse)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&summary)?);
        return Ok(());
    }
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: first bending frequency, free-free (paper Table 3)",
        model.name
    );
    let _ = writeln!(
        s,
        "{:<40} {:>12} {:>14} {:>16}",
        "", "f [Hz]", "(f−exp)/exp", "paper: (exp−f)/f"
    );
    for (name, f) in &rows {
        match f {
            Some(f) => {
                let e = Errors::new(*f, experiment_hz);
                let _ = writeln!(
                    s,
                    "{name:<40} {f:>12.2} {:>13.2}% {:>15.2}%",
                    e.error_percent, e.paper_error_percent
                );
            }
            None => {
                let _ = writeln!(s, "{name:<40} {:>12}", "–");
            }
        }
    }
    if let Some(fb) = impulse.first_bending {
        let _ = writeln!(
            s,
            "FFT vs eigenvalue: raw {:+.2e}, corrected {:+.2e} (integrator period error removed)",
            fb.raw_error(),
            fb.corrected_error()
        );
    }
    if let Some(c) = &calibration {
        let p = &c.parameters[0];
        let _ = writeln!(
            s,
            "equivalent geometry: {} = {:.4} mm ({:+.2} % on {:.4} mm) gives {:.3} Hz (eigenvalue, {} evaluations)",
            p.name,
            1e3 * p.fitted,
            p.change_percent,
            1e3 * p.initial,
            c.achieved_hz[0],
            c.evaluations
        );
    }
    let st = &impulse.stats;
    let _ = writeln!(
        s,
        "impulse: {} steps of {:.1e} s, {:.2} Newton iterations/step, joints held to {:.1e} m",
        st.steps,
        args.experiment.step,
        st.newton_iterations as f64 / st.steps.max(1) as f64,
        st.max_length_residual
    );
    if let Some(dir) = &args.out_dir {
        let _ = writeln!(
            s,
            "data written to {}: summary.json, modes.csv, signal.csv, spectrum.csv{}, {}",
            dir.display(),
            if calibration.is_some() {
                ", calibrated.json"
            } else {
                ""
            },
            FIGURES.map(|f| format!("{f}.svg/.png")).join(", ")
        );
    }
    print!("{s}");
    Ok(())
}
