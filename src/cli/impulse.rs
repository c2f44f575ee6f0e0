//! `ancf-modal impulse`: the paper's time-domain frequency test.

use super::common::{load_model, print_json, source_label, write_output};
use ancf_modal::analysis::impulse::{run_impulse, ImpulseResult, ImpulseSettings};
use ancf_modal::model::ValidModel;
use ancf_modal::output::figures::{response_path, write_impulse_figures};
use ancf_modal::output::impulse_report::{impulse_table, signal_csv, spectrum_csv};
use ancf_modal::output::plot::{Format, PlotSize};
use ancf_modal::results::ImpulseOutput;
use ancf_modal::signal::Window;
use anyhow::{Context, Result};
use clap::Args;
use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};

/// Flags of the experiment, shared with `identify`.
#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// Pulse amplitude F0 [N] (default: the model's, 4 N for the paper's assembly).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = super::values::non_zero)]
    pub amplitude: Option<f64>,
    /// Pulse duration tF [s] (default: the model's, 1e-4 s).
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub duration: Option<f64>,
    /// End time [s].
    #[arg(long, value_name = "S", default_value_t = 0.1, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: f64,
    /// Time step [s].
    #[arg(long, value_name = "S", default_value_t = 1e-6, allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: f64,
    /// Spectral radius at infinity of generalized-α (1 = no numerical damping).
    #[arg(long, value_name = "R", default_value_t = 0.9, allow_hyphen_values = true, value_parser = super::values::unit_interval)]
    pub spectral_radius: f64,
    /// Sensor sampling rate [Hz]; 0 records every step.
    #[arg(long, value_name = "HZ", default_value_t = 51_200.0, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Sensor id (default: the model's first sensor).
    #[arg(long)]
    pub sensor: Option<String>,
    /// FFT window: hann, rect, blackman, flattop (or force:P, exponential:P,
    /// as `frf --window`).
    #[arg(long, default_value = "hann")]
    pub window: Window,
}

impl ExperimentArgs {
    pub fn settings(&self) -> ImpulseSettings {
        let mut s = ImpulseSettings::default();
        s.transient.step = self.step;
        s.transient.end_time = self.end_time;
        s.transient.spectral_radius = self.spectral_radius;
        s.amplitude = self.amplitude;
        s.duration = self.duration;
        s.sample_rate = (self.sample_rate != 0.0).then_some(self.sample_rate);
        s.sensor = self.sensor.clone();
        s.spectrum.window = self.window;
        s
    }
}

#[derive(Debug, Args)]
pub struct ImpulseArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    #[command(flatten)]
    pub experiment: ExperimentArgs,
}

/// Run the experiment with a progress line on a terminal.
pub fn experiment(
    model: &ValidModel,
    path: Option<&Path>,
    args: &ExperimentArgs,
) -> Result<ImpulseResult> {
    let settings = args.settings();
    let tty = std::io::stderr().is_terminal();
    let started = std::time::Instant::now();
    let mut progress = |fraction: f64| {
        if tty && started.elapsed().as_secs_f64() > 0.5 {
            eprint!("\rintegrating… {:3.0} %", 100.0 * fraction);
            let _ = std::io::stderr().flush();
        }
    };
    let result = run_impulse(model, &settings, &mut progress).with_context(|| source_label(path));
    if tty && started.elapsed().as_secs_f64() > 0.5 {
        eprint!("\r{:30}\r", "");
    }
    result
}

/// `--csv F` → the spectrum file beside it.
pub fn spectrum_path(csv: &Path) -> PathBuf {
    let stem = csv
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    csv.with_file_name(format!("{stem}.spectrum.csv"))
}

pub fn run(args: ImpulseArgs) -> Result<()> {
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let model = load_model(args.model.as_deref())?;
    args.experiment.settings().transient.validate()?;
    let result = experiment(&model, args.model.as_deref(), &args.experiment)?;
    let reference = model.reference.as_ref().map(|r| r.first_bending_hz);
    if let Some(path) = &args.output.csv {
        write_output(path, &signal_csv(&result))?;
        write_output(&spectrum_path(path), &spectrum_csv(&result))?;
    }
    if let Some(path) = &args.output.uff {
        let provenance = ancf_modal::results::provenance::header_lines(
            &super::common::model_sha256(args.model.as_deref())?,
        );
        let text = ancf_modal::output::records_uff::time_records_uff(
            &result.time,
            &result.force,
            &result.signal,
            &result.sensor,
            result.quantity,
            &provenance,
        );
        write_output(path, &text)?;
    }
    if let Some(path) = &args.output.plot {
        let response = response_path(path);
        write_impulse_figures(&model, &result, path, &response, PlotSize::default())?;
    }
    if args.output.json {
        print_json(
            ImpulseOutput::new(&model.name, &result, reference),
            args.model.as_deref(),
        )?;
    } else {
        out!("{}", impulse_table(&model.name, &result, reference));
    }
    Ok(())
}
