//! `ancf-modal impulse`: maps the flags to [`ancf_modal::commands::impulse`]
//! and renders its output: the paper's time-domain frequency test. Its
//! flags of the experiment are shared with `calibrate --method impulse`,
//! `identify` and `report`.

use super::common::{command_error, print_document, write_output, Warnings};
use ancf_modal::commands::impulse::{run_with_progress, spectrum_path, ImpulseRequest};
use ancf_modal::commands::ModelInput;
use ancf_modal::output::plot::Format;
use ancf_modal::signal::Window;
use anyhow::Result;
use clap::Args;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;

/// Flags of the experiment, shared with `identify`.
#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// Pulse amplitude F0 [N] (default: the model's, 4 N for the paper's assembly).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = super::values::non_zero)]
    pub amplitude: Option<f64>,
    /// Pulse duration tF [s] (default: the model's, 1e-4 s).
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub duration: Option<f64>,
    /// End time [s] (`calibrate --quantity`/`--trajectory`: the switch-off's 0.003 s when left out) [default: 0.1]
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: Option<f64>,
    /// Time step [s] [default: 0.000001]
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: Option<f64>,
    /// Spectral radius at infinity of generalized-α (1 = no numerical damping).
    #[arg(long, value_name = "R", default_value_t = ImpulseRequest::default().spectral_radius, allow_hyphen_values = true, value_parser = super::values::unit_interval)]
    pub spectral_radius: f64,
    /// Sensor sampling rate [Hz]; 0 records every step.
    #[arg(long, value_name = "HZ", default_value_t = ImpulseRequest::default().sample_rate, allow_hyphen_values = true, value_parser = super::values::non_negative)]
    pub sample_rate: f64,
    /// Sensor id (default: the model's first sensor).
    #[arg(long)]
    pub sensor: Option<String>,
    /// FFT window: hann, rect, blackman, flattop (or force:P, exponential:P,
    /// as `frf --window`).
    #[arg(long, default_value_t = ImpulseRequest::default().window)]
    pub window: Window,
    /// Strike the reference configuration, whatever acts on it (by default
    /// the blow strikes the static equilibrium under the loads at t = 0⁻:
    /// constant loads, preloads and gravity; the reference itself when it
    /// balances them).
    #[arg(long)]
    pub from_reference: bool,
}

impl ExperimentArgs {
    /// The experiment the flags ask for.
    pub fn request(&self) -> ImpulseRequest {
        ImpulseRequest {
            amplitude: self.amplitude,
            duration: self.duration,
            end_time: self.end_time.unwrap_or(ImpulseRequest::default().end_time),
            step: self.step.unwrap_or(ImpulseRequest::default().step),
            spectral_radius: self.spectral_radius,
            sample_rate: self.sample_rate,
            sensor: self.sensor.clone(),
            window: self.window,
            start: ancf_modal::analysis::statics::start::Start::from_reference(self.from_reference),
        }
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

/// A progress line on stderr while a run that lasts integrates (on a
/// terminal only).
struct Progress {
    tty: bool,
    started: std::time::Instant,
}

impl Progress {
    fn new() -> Self {
        Progress {
            tty: std::io::stderr().is_terminal(),
            started: std::time::Instant::now(),
        }
    }

    fn shown(&self) -> bool {
        self.tty && self.started.elapsed().as_secs_f64() > 0.5
    }

    fn update(&self, fraction: f64) {
        if self.shown() {
            eprint!("\rintegrating… {:3.0} %", 100.0 * fraction);
            let _ = std::io::stderr().flush();
        }
    }

    fn clear(&self) {
        if self.shown() {
            eprint!("\r{:30}\r", "");
        }
    }
}

pub fn run(args: ImpulseArgs) -> Result<Warnings> {
    if let Some(path) = &args.output.plot {
        Format::from_path(path)?;
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let progress = Progress::new();
    let run = run_with_progress(&input, &args.experiment.request(), &mut |f| {
        progress.update(f)
    });
    progress.clear();
    let run = run.map_err(command_error)?;
    if let Some(path) = &args.output.csv {
        write_output(path, &run.signal_csv())?;
        write_output(&spectrum_path(path), &run.spectrum_csv())?;
    }
    if let Some(path) = &args.output.uff {
        write_output(path, &run.uff())?;
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
