//! `ancf-modal identify`: maps the flags to
//! [`ancf_modal::commands::identify`] and renders its output: the modal
//! analysis, the impulse experiment with its spectrum, and the paper's
//! Table 3 side by side.

use super::common::{print_document, Warnings};
use super::impulse::ExperimentArgs;
use super::output::Output;
use ancf_modal::commands::identify::{run_with_progress, IdentifyRequest};
use ancf_modal::commands::ModelInput;
use anyhow::Result;
use clap::Args;
use std::io::{IsTerminal, Write};
use std::path::PathBuf;

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
    /// mode nearest the model's first bending frequency, of those that are
    /// a peak of the fitted spectrum, replaces the model's `reference` as
    /// the experiment (a warning when the records show no peak there or the
    /// fit misses them around it).
    #[arg(long, value_name = "FILE", num_args = 1..)]
    pub measured: Vec<PathBuf>,
    /// Window of the measured records (see `frf --window`).
    #[arg(long, value_name = "W", default_value_t = IdentifyRequest::default().measured_window, requires = "measured")]
    pub measured_window: ancf_modal::signal::Window,
    /// Fit band of the measured records, LO:HI in Hz (see `frf --band`).
    #[arg(long, value_name = "LO:HI", requires = "measured", allow_hyphen_values = true, value_parser = super::frf::parse_band)]
    pub measured_band: Option<(f64, f64)>,
}

/// The request of the experiment's and the comparison's flags.
pub fn request(e: &ExperimentArgs, c: &ComparisonArgs) -> IdentifyRequest {
    IdentifyRequest {
        experiment: e.request(),
        calibrate: c.calibrate,
        measured: c.measured.clone(),
        measured_window: c.measured_window,
        measured_band: c.measured_band,
    }
}

/// Runs `work` with a progress line on a terminal while it integrates
/// (`work` tells its progress the fraction of the steps done).
pub fn progress_line<T>(work: impl FnOnce(&mut dyn FnMut(f64)) -> Result<T>) -> Result<T> {
    let tty = std::io::stderr().is_terminal();
    let started = std::time::Instant::now();
    let mut progress = |fraction: f64| {
        if tty && started.elapsed().as_secs_f64() > 0.5 {
            eprint!("\rintegrating… {:3.0} %", 100.0 * fraction);
            let _ = std::io::stderr().flush();
        }
    };
    let run = work(&mut progress);
    if tty && started.elapsed().as_secs_f64() > 0.5 {
        eprint!("\r{:30}\r", "");
    }
    run
}

pub fn run(args: IdentifyArgs) -> Result<Warnings> {
    args.output.only("identify", &[Output::Json])?;
    if let Some(path) = &args.html {
        ancf_modal::commands::report::check_out("html", path)?;
    }
    let input = ModelInput::load(args.model.as_deref())?;
    let request = request(&args.experiment, &args.comparison);
    let run = progress_line(|progress| Ok(run_with_progress(&input, &request, progress)?))?;
    if let Some(dir) = &args.out_dir {
        run.write_out_dir(dir)?;
    }
    if let Some(path) = &args.html {
        let request = super::report::report_request(path.clone(), false);
        ancf_modal::commands::report::of_identified(&input, &run, &request)?.write()?;
    }
    if args.output.json {
        print_document(&run.document)?;
    } else {
        out!("{}", run.text(args.out_dir.as_deref()));
    }
    Ok(run.document.warnings)
}
