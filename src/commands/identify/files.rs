//! What `identify` shows and writes: the printed report (the comparison
//! of first bending frequencies [Hz] with the errors [%], the measured
//! modes, the calibration), and the output directory's data files
//! (`summary.json`, `modes.csv`, `signal.csv` [s, sensor unit],
//! `spectrum.csv` [Hz, sensor unit], `calibrated.json`) and figures (the
//! mode shapes, the impulse response, its spectrum and a quick mesh
//! convergence, as .svg and .png).

use super::{CommandError, IdentifyRun};
use crate::analysis::convergence::{mesh_convergence_with, with_elements, Reference};
use crate::output::figures::{
    convergence_figure, response_figure, spectrum_figure, write_figure, write_mode_shapes,
};
use crate::output::files::write_atomic;
use crate::output::impulse_report::{signal_csv, spectrum_csv};
use crate::output::modal_report::modal_csv;
use crate::output::plot::{Figure, PlotSize};
use std::fmt::Write;
use std::path::Path;

/// Figures the output directory holds, each as .svg and .png.
pub const FIGURES: [&str; 4] = ["modes", "response", "spectrum", "convergence"];

impl IdentifyRun {
    /// The document as the output directory's `summary.json` holds it
    /// (pretty JSON, as `--json` prints it).
    pub fn summary_json(&self) -> String {
        serde_json::to_string_pretty(&self.document.document())
            .unwrap_or_else(|e| format!("unserializable result: {e}"))
    }

    /// The output directory's data files: name and text.
    pub fn data_files(&self) -> Vec<(&'static str, String)> {
        let mut files = vec![
            ("summary.json", self.summary_json()),
            ("modes.csv", modal_csv(&self.modal)),
            ("signal.csv", signal_csv(&self.impulse)),
            ("spectrum.csv", spectrum_csv(&self.impulse)),
        ];
        if let Some(c) = &self.document.output.calibration {
            files.push(("calibrated.json", c.result.fitted_model.to_json() + "\n"));
        }
        files
    }

    /// Writes the data files and the figures into `dir` (created if
    /// missing), as `--out-dir` does.
    pub fn write_out_dir(&self, dir: &Path) -> Result<(), CommandError> {
        std::fs::create_dir_all(dir).map_err(|io| CommandError::OutputDir {
            dir: dir.to_path_buf(),
            io,
        })?;
        for (name, text) in self.data_files() {
            write_atomic(&dir.join(name), text.as_bytes())?;
        }
        self.write_figures(dir)
    }

    /// Mode shapes, impulse response, spectrum and a quick mesh
    /// convergence (2…32 elements per beam against the 32-element mesh)
    /// into `dir`, each as .svg and .png.
    pub fn write_figures(&self, dir: &Path) -> Result<(), CommandError> {
        let model = &self.model;
        let data = mesh_convergence_with(
            |n| with_elements(model, n),
            Reference::FinestMesh { modes: 3 },
            &[2, 4, 8, 16, 32],
        )
        .map_err(|e| CommandError::analysis("mesh convergence for the figure", e))?;
        let convergence: Figure = convergence_figure(&data).into();
        let spectrum: Figure = spectrum_figure(model, &self.impulse).into();
        let response: Figure = response_figure(&model.name, &self.impulse);
        let system = &self.system;
        for ext in ["svg", "png"] {
            let path = |name: &str| dir.join(format!("{name}.{ext}"));
            write_mode_shapes(system, &system.q0, &self.modal, &path("modes"))?;
            write_figure(&response, &path("response"), PlotSize::default())?;
            write_figure(&spectrum, &path("spectrum"), PlotSize::default())?;
            write_figure(&convergence, &path("convergence"), PlotSize::default())?;
        }
        Ok(())
    }

    /// The printed report: the comparison table, the measured modes, the
    /// FFT's agreement with the eigenvalue, the calibration and, with
    /// `out_dir`, the files written there.
    pub fn text(&self, out_dir: Option<&Path>) -> String {
        let output = &self.document.output;
        let mut s = String::new();
        let _ = writeln!(
            s,
            "model {}: first bending frequency, {}{}",
            output.model,
            output.supports,
            if self.paper { " (paper Table 3)" } else { "" }
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
        match (output.experiment_hz, &output.measured) {
            (Some(_), _) => {}
            (None, Some(_)) => {
                let _ = writeln!(
                    s,
                    "no experiment to compare with: the measured records show no mode to take as the first bending (see the warnings)"
                );
            }
            (None, None) => {
                let _ = writeln!(
                    s,
                    "no experiment to compare with: give the model a `reference` or measured records with --measured"
                );
            }
        }
        if let Some(m) = &output.measured {
            let modes = if m.peaks.is_empty() {
                "none".to_string()
            } else {
                (m.peaks.iter())
                    .map(|p| {
                        format!(
                            "{:.1} Hz (ζ {:.3} %)",
                            p.frequency_hz,
                            100.0 * p.damping_ratio
                        )
                    })
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let records = match m.files.len() {
                1 => "1 record".to_string(),
                n => format!("{n} records"),
            };
            let _ = writeln!(
                s,
                "measured modes over {:.0}–{:.0} Hz ({records}): {modes}",
                m.band_hz[0], m.band_hz[1],
            );
        }
        let i = &output.impulse;
        if let (Some(raw), Some(corrected)) = (i.raw_vs_eigen, i.corrected_vs_eigen) {
            let _ = writeln!(
                s,
                "FFT vs eigenvalue: raw {raw:+.2e}, corrected {corrected:+.2e} (integrator period error removed)"
            );
        }
        let calibrated = output.calibration.as_ref().and_then(|c| {
            Some((
                c,
                c.result.parameters.first()?,
                c.result.achieved_hz.first()?,
            ))
        });
        if let Some((c, p, achieved_hz)) = calibrated {
            let _ = writeln!(
                s,
                "equivalent geometry: {} = {:.4} mm ({:+.2} % on {:.4} mm) gives {:.3} Hz (eigenvalue, {} evaluations)",
                p.name,
                1e3 * p.fitted,
                p.change_percent.unwrap_or(f64::NAN),
                1e3 * p.initial,
                achieved_hz,
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
}
