//! `ancf-modal sweep`: maps the flags to [`ancf_modal::commands::sweep`]
//! and renders its output (table or JSON, CSV, plot), with a progress bar
//! on a terminal. Also `modal --sweep-load`, which is this command with one
//! `load_scale:` parameter over all loads.

use super::args::{ModalArgs, Solver, Sweep as LoadRange};
use super::common::{write_output, Warnings};
use super::output::{Output, OutputArgs};
use ancf_modal::analysis::sweep::{Quantity, Shard};
use ancf_modal::commands::sweep::{input, prepare, SweepJob, SweepRequest, SweepRun};
use ancf_modal::commands::{CommandError, ModelInput};
use anyhow::{anyhow, bail, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct SweepArgs {
    /// Model file (JSON); the built-in paper assembly when omitted.
    pub model: Option<PathBuf>,
    /// A parameter and its values, repeatable (several make a full grid,
    /// the first varying slowest). NAME is a JSON path to a number of the
    /// model (`beams[blade].section.height`, `springs[0].stiffness`), a
    /// short name of `calibrate --param` (`height`, `blade.young`), or
    /// `load_scale:ID[,ID...]` (multiplies those loads; linearizes at the
    /// static equilibrium, as a load's force, a spring's preload or gravity
    /// does). Values SI: LO:HI:N from LO to HI (`:log` spaces
    /// them geometrically), or V1,V2,... as listed.
    #[arg(
        long = "param",
        value_name = "NAME=LO:HI:N[:log]|V1,V2,...",
        allow_hyphen_values = true
    )]
    pub params: Vec<String>,
    /// What to compute at each point: first_bending_hz, frequency:K (the
    /// K-th elastic mode, tracked by MAC across the points),
    /// time_to_distance_s (the switch-off; the built-in switch-off assembly
    /// when no model is given) or peak:SENSOR (largest |reading| over a
    /// transient run).
    #[arg(long, value_name = "QUANTITY")]
    pub quantity: Option<String>,
    /// Time step of transient quantities [s] (default 1e-6).
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub step: Option<f64>,
    /// End time of transient quantities [s] (default 3e-3).
    #[arg(long, value_name = "S", allow_hyphen_values = true, value_parser = super::values::positive)]
    pub end_time: Option<f64>,
    /// Elastic modes tracked for frequency:K (at least K; all are drawn by
    /// --plot and written by --csv).
    #[arg(long, value_name = "N", default_value_t = SweepRequest::default().modes, allow_hyphen_values = true, value_parser = super::values::at_least_one_usize)]
    pub modes: usize,
    /// Linearize at the static equilibrium under the model's constant loads
    /// and gravity (implied by a load_scale parameter and by a parameter
    /// that is a load's force, a spring's preload or gravity).
    #[arg(long)]
    pub prestress: bool,
    /// Eigensolver (as for `modal`).
    #[arg(long, value_enum, default_value_t = Solver::Auto)]
    pub solver: Solver,
    /// Compute only shard K of N (1-based): the points whose index is
    /// K−1 modulo N; join the shards' --json documents with `sweep-merge`.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<String>,
    /// Worker threads (default: all cores; 1 runs the points serially).
    #[arg(long, value_name = "N", allow_hyphen_values = true, value_parser = super::values::at_least_one_usize)]
    pub threads: Option<usize>,
    #[command(flatten)]
    pub outputs: OutputArgs,
}

/// The outputs of `sweep` and `sweep-merge`.
pub const SWEEP_OUTPUTS: &[Output] = &[Output::Json, Output::Csv, Output::Plot];

pub fn run(args: SweepArgs) -> Result<Warnings> {
    args.outputs.only("sweep", SWEEP_OUTPUTS)?;
    let quantity = args
        .quantity
        .as_deref()
        .map(Quantity::parse)
        .transpose()
        .map_err(|e| anyhow!("--quantity: {e}"))?;
    let input = input(args.model.as_deref(), quantity.as_ref())?;
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()
        .map_err(|e| anyhow!("--shard: {e}"))?;
    let request = SweepRequest {
        params: args.params,
        quantity,
        step: args.step,
        end_time: args.end_time,
        modes: args.modes,
        prestress: args.prestress,
        solver: args.solver.into(),
        shard,
        threads: args.threads,
    };
    run_request(&input, &request, &args.outputs)
}

/// Prepares the sweep, checks the plot, computes and renders.
fn run_request(input: &ModelInput, request: &SweepRequest, out: &OutputArgs) -> Result<Warnings> {
    let job = prepare(input, request).map_err(flagged)?;
    if let Some(path) = &out.plot {
        if request.shard.is_some() {
            bail!("--plot: a shard is part of a sweep; draw the merged sweep (`ancf-modal sweep-merge SHARD.json... --plot FILE`)");
        }
        job.check_plot(path).map_err(|e| anyhow!("--plot: {e}"))?;
    }
    let run = compute(&job);
    emit(&run, out)?;
    Ok(run.document.warnings)
}

/// A sweep's error with the flag it concerns in front (`--param: …`,
/// `--quantity is required …`); the library names request fields.
fn flagged(e: CommandError) -> anyhow::Error {
    match e {
        CommandError::SweepParams(e) => anyhow!("--param: {e}"),
        CommandError::Required { name, one_of } => {
            anyhow!("--{name} is required (one of: {one_of})")
        }
        e => e.into(),
    }
}

/// Computes the job's points with a progress bar when stderr is a
/// terminal.
fn compute(job: &SweepJob) -> SweepRun {
    let indices = job.indices();
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(indices.len() as u64);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} points, {elapsed} (eta {eta})")
                .expect("a valid template"),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let points = job.points(&indices, &|| bar.inc(1));
    bar.finish_and_clear();
    job.finish(points)
}

/// Writes the CSV and the plot, prints the document or the table, and
/// fails (exit code 1) when any point failed — after everything is out.
pub fn emit(run: &SweepRun, out: &OutputArgs) -> Result<()> {
    if let Some(path) = &out.csv {
        write_output(path, &run.csv())?;
    }
    if let Some(path) = &out.plot {
        run.write_plot(path)?;
    }
    if out.json {
        outln!("{}", serde_json::to_string_pretty(&run.stamped())?);
    } else {
        out!("{}", run.text());
    }
    match run.failure() {
        Some(e) => Err(e.into()),
        None => Ok(()),
    }
}

/// `modal --sweep-load A:B:N`: `sweep` with `load_scale:` over every load
/// and `frequency:1`, tracking the first min(--modes, 6) elastic modes.
pub fn run_load_sweep(args: &ModalArgs, range: LoadRange) -> Result<Warnings> {
    let input = ModelInput::load(args.model.as_deref())?;
    let request = SweepRequest::load_sweep(
        &input.model,
        (range.from, range.to, range.count),
        args.modes as usize,
        args.solver.into(),
    )
    .map_err(|e| anyhow::Error::new(e).context("--sweep-load"))?;
    args.output.only("sweep", SWEEP_OUTPUTS)?;
    run_request(&input, &request, &args.output)
}
