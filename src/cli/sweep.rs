//! `ancf-modal sweep`: a quantity over a grid of model parameters, in
//! parallel, optionally one shard of it. Also `modal --sweep-load`, which is
//! this command with one `load_scale:` parameter over all loads.

use super::args::{ModalArgs, Solver, Sweep as LoadRange};
use super::common::{load_model, write_output};
use super::output::{Output, OutputArgs};
use ancf_modal::analysis::sweep::param::load_labels;
use ancf_modal::analysis::sweep::{
    Execution, Quantity, Shard, Sweep, SweepDocument, SweepRun, SweepSettings,
    DEFAULT_TRACKED_MODES,
};
use ancf_modal::output::figures::sweep::{check_plottable, write_sweep_figure};
use ancf_modal::output::sweep_report::{sweep_csv, sweep_table};
use ancf_modal::results::provenance::tool_version;
use anyhow::{anyhow, bail, Context, Result};
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
    /// static equilibrium). Values SI: LO:HI:N from LO to HI (`:log` spaces
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
    #[arg(long, value_name = "N", default_value_t = DEFAULT_TRACKED_MODES, allow_hyphen_values = true, value_parser = super::values::at_least_one_usize)]
    pub modes: usize,
    /// Linearize at the static equilibrium under the model's constant loads
    /// and gravity (implied by a load_scale parameter).
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

pub fn run(args: SweepArgs) -> Result<()> {
    args.outputs.only("sweep", SWEEP_OUTPUTS)?;
    let quantity = match &args.quantity {
        Some(q) => Quantity::parse(q).map_err(|e| anyhow!("--quantity: {e}"))?,
        None => bail!(
            "--quantity is required (one of: {})",
            ancf_modal::analysis::sweep::quantity::AVAILABLE.join(", ")
        ),
    };
    let model = match (&args.model, &quantity) {
        (None, Quantity::TimeToDistance) => ancf_modal::Model::switch_off_builtin(),
        _ => load_model(args.model.as_deref())?,
    };
    let shard = args
        .shard
        .as_deref()
        .map(Shard::parse)
        .transpose()
        .map_err(|e| anyhow!("--shard: {e}"))?;
    let settings = SweepSettings {
        tracked_modes: args.modes,
        prestress: args.prestress,
        method: args.solver.into(),
        step: args.step,
        end_time: args.end_time,
        ..SweepSettings::new(quantity)
    };
    let sweep = Sweep::new(&model, &args.params, settings).map_err(|e| anyhow!("--param: {e}"))?;
    if let Some(path) = &args.outputs.plot {
        if shard.is_some() {
            bail!("--plot: a shard is part of a sweep; draw the merged sweep (`ancf-modal sweep-merge SHARD.json... --plot FILE`)");
        }
        check_plottable(path, sweep.parameters.len()).map_err(|e| anyhow!("--plot: {e}"))?;
    }
    let sha = model_sha256(
        args.model.as_deref(),
        sweep.settings.quantity == Quantity::TimeToDistance,
    )?;
    let run = compute(&sweep, shard, args.threads)?;
    for p in &run.points {
        for w in &p.warnings {
            super::common::warn(format!("point {}: {w}", p.index));
        }
    }
    let doc = SweepDocument {
        tool_version: Some(tool_version().to_string()),
        model_sha256: Some(sha),
        warnings: super::common::warnings(),
        ..run.document()
    };
    emit(&doc, &args.outputs)
}

/// SHA-256 of the model file, or of the built-in model's text (the
/// switch-off assembly for a switch-off quantity).
fn model_sha256(path: Option<&std::path::Path>, switch_off: bool) -> Result<String> {
    let builtin = if switch_off {
        ancf_modal::model::SWITCH_OFF_MODEL_JSON
    } else {
        ancf_modal::model::DEFAULT_MODEL_JSON
    };
    super::common::model_sha256_or(path, builtin)
}

/// Runs the sweep on `threads` workers (all cores by default) with a
/// progress bar when stderr is a terminal.
fn compute(sweep: &Sweep, shard: Option<Shard>, threads: Option<usize>) -> Result<SweepRun> {
    let count = sweep.indices(shard).len() as u64;
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(count);
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {pos}/{len} points, {elapsed} (eta {eta})")
                .expect("a valid template"),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let progress = || bar.inc(1);
    let run = match threads {
        Some(1) => sweep.run(shard, Execution::Serial, &progress),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .context("--threads: cannot start the worker threads")?
            .install(|| sweep.run(shard, Execution::Parallel, &progress)),
        None => sweep.run(shard, Execution::Parallel, &progress),
    };
    bar.finish_and_clear();
    Ok(run)
}

/// Writes the CSV and the plot, prints the document or the table, and
/// fails (exit code 1) when any point failed — after everything is out.
pub fn emit(doc: &SweepDocument, out: &OutputArgs) -> Result<()> {
    if let Some(path) = &out.csv {
        write_output(path, &sweep_csv(doc))?;
    }
    if let Some(path) = &out.plot {
        write_sweep_figure(doc, path)?;
    }
    if out.json {
        outln!("{}", serde_json::to_string_pretty(doc)?);
    } else {
        out!("{}", sweep_table(doc));
    }
    if doc.failed_points > 0 {
        let first = doc
            .points
            .iter()
            .find_map(|p| p.error.as_deref().map(|e| (p.index, e)));
        let (index, message) = first.unwrap_or((0, ""));
        bail!(
            "{} of {} points failed (first: point {index}: {message})",
            doc.failed_points,
            doc.points.len()
        );
    }
    Ok(())
}

/// `modal --sweep-load A:B:N`: `sweep` with `load_scale:` over every load
/// and `frequency:1`, tracking the first min(--modes, 6) elastic modes.
pub fn run_load_sweep(args: &ModalArgs, range: LoadRange) -> Result<()> {
    let model = load_model(args.model.as_deref())?;
    if model.loads.is_empty() {
        bail!("--sweep-load: the model has no loads to scale");
    }
    let loads = load_labels(&model);
    let param = format!(
        "load_scale:{}={:?}:{:?}:{}",
        loads.join(","),
        range.from,
        range.to,
        range.count
    );
    run(SweepArgs {
        model: args.model.clone(),
        params: vec![param],
        quantity: Some(String::from("frequency:1")),
        step: None,
        end_time: None,
        modes: (args.modes as usize).min(6),
        prestress: true,
        solver: args.solver,
        shard: None,
        threads: None,
        outputs: args.output.clone(),
    })
}
