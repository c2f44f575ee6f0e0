//! `sweep`: a quantity over a grid of model parameters — the first bending
//! frequency [Hz], the K-th elastic mode's frequency [Hz] tracked by MAC
//! across the points, the switch-off's time to distance [s] or a sensor's
//! peak over a transient run [the sensor's SI unit]. Each parameter is a
//! number of the model file (a JSON path, a calibration short name, or a
//! load factor `load_scale:ID,...` [–]) over an axis `LO:HI:N[:log]` or
//! listed values `V1,V2,...`, SI as in the model file; several make the
//! full grid, the first varying slowest. The points are independent and
//! run in parallel; a shard `K/N` computes every N-th point and
//! [`super::sweep_merge`] joins the shards into the document of one run.
//!
//! A point that fails is recorded with its message and the sweep goes on;
//! [`SweepRun::failure`] says whether any did. `modal --sweep-load` is a
//! sweep too ([`SweepRequest::load_sweep`]).
//!
//! Front ends that must stay responsive (Python's KeyboardInterrupt) run
//! the points in parts: [`prepare`], then [`SweepJob::points`] on parts of
//! [`SweepJob::indices`], then [`SweepJob::finish`]; [`run`] does all
//! three. Front ends that run the points elsewhere (Python on a Dask
//! cluster) compute shards there and [`SweepJob::join`] them here.

use super::{CommandError, ModelInput, Run};
use crate::analysis::sweep::param::load_labels;
use crate::analysis::sweep::{
    merge, quantity::AVAILABLE, Quantity, RawPoint, Shard, Sweep, SweepDocument, SweepError,
    SweepSettings, DEFAULT_TRACKED_MODES,
};
use crate::analysis::EigenMethod;
use crate::error::ModelError;
use crate::model::{DEFAULT_MODEL_JSON, SWITCH_OFF_MODEL_JSON};
use crate::output::figures::sweep::{check_plottable, write_sweep_figure};
use crate::output::sweep_report::{sweep_csv, sweep_table};
use rayon::prelude::*;
use std::path::Path;

/// What `sweep` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRequest {
    /// The parameters and their values, `NAME=LO:HI:N[:log]` or
    /// `NAME=V1,V2,...` (a name ending in `+` offsets the model's value),
    /// values SI; several make the full grid, the first varying slowest.
    pub params: Vec<String>,
    /// What each point computes; required.
    pub quantity: Option<Quantity>,
    /// Time step of transient quantities [s] (`None`: 1e-6 s).
    pub step: Option<f64>,
    /// End time of transient quantities [s] (`None`: 3e-3 s).
    pub end_time: Option<f64>,
    /// Elastic modes tracked for `frequency:K` (at least K) [–].
    pub modes: usize,
    /// Linearize at the static equilibrium under the model's loads and
    /// gravity (implied by a `load_scale:` parameter).
    pub prestress: bool,
    /// The eigensolver (as `modal`'s).
    pub solver: EigenMethod,
    /// Only the points of this shard (K of N).
    pub shard: Option<Shard>,
    /// Worker threads (`None`: all cores; 1 runs the points serially).
    pub threads: Option<usize>,
}

impl Default for SweepRequest {
    fn default() -> Self {
        SweepRequest {
            params: Vec::new(),
            quantity: None,
            step: None,
            end_time: None,
            modes: DEFAULT_TRACKED_MODES,
            prestress: false,
            solver: EigenMethod::Auto,
            shard: None,
            threads: None,
        }
    }
}

/// The most modes `modal --sweep-load` tracks.
pub const LOAD_SWEEP_MODES: usize = 6;

impl SweepRequest {
    /// `modal --sweep-load FROM:TO:COUNT`: every load of `model` scaled
    /// together from `from` to `to` in `count` steps [–], the equilibrium's
    /// `frequency:1` with the first min(`modes`, 6) elastic modes tracked.
    pub fn load_sweep(
        model: &crate::Model,
        (from, to, count): (f64, f64, usize),
        modes: usize,
        solver: EigenMethod,
    ) -> Result<SweepRequest, CommandError> {
        if model.loads.is_empty() {
            return Err(CommandError::NoLoadsToScale);
        }
        let param = format!(
            "load_scale:{}={from:?}:{to:?}:{count}",
            load_labels(model).join(",")
        );
        Ok(SweepRequest {
            params: vec![param],
            quantity: Some(Quantity::Frequency { mode: 1 }),
            modes: modes.min(LOAD_SWEEP_MODES),
            prestress: true,
            solver,
            ..SweepRequest::default()
        })
    }
}

/// The model file at `path`; without one the built-in model, which for the
/// switch-off's `time_to_distance_s` is the switch-off assembly.
pub fn input(path: Option<&Path>, quantity: Option<&Quantity>) -> Result<ModelInput, ModelError> {
    let builtin = match quantity {
        Some(Quantity::TimeToDistance) => SWITCH_OFF_MODEL_JSON,
        _ => DEFAULT_MODEL_JSON,
    };
    ModelInput::file_or(path, builtin)
}

/// Who computes the points.
#[derive(Debug)]
enum Workers {
    /// rayon's global pool (all cores).
    Global,
    /// One after another on the calling thread.
    Serial,
    /// A pool of the asked number of threads.
    Pool(rayon::ThreadPool),
}

/// A resolved sweep, ready to compute its points.
#[derive(Debug)]
pub struct SweepJob {
    input: ModelInput,
    sweep: Sweep,
    shard: Option<Shard>,
    workers: Workers,
}

/// Checks `request` and resolves its parameters against `input`'s model.
pub fn prepare(input: &ModelInput, request: &SweepRequest) -> Result<SweepJob, CommandError> {
    let quantity = request.quantity.clone().ok_or(CommandError::Required {
        name: "quantity",
        one_of: AVAILABLE.join(", "),
    })?;
    if request.modes < 1 {
        return Err(CommandError::argument(
            "modes",
            request.modes,
            "must be a whole number ≥ 1",
        ));
    }
    for (name, v) in [("step", request.step), ("end_time", request.end_time)] {
        if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(CommandError::argument(name, v, "must be a number > 0"));
        }
    }
    if let Some(s) = request.shard {
        if s.index < 1 || s.index > s.count {
            return Err(CommandError::argument(
                "shard",
                s,
                "must be K/N with 1 ≤ K ≤ N (1-based)",
            ));
        }
    }
    let workers = match request.threads {
        None => Workers::Global,
        Some(0) => {
            return Err(CommandError::argument(
                "threads",
                0,
                "must be a whole number ≥ 1",
            ))
        }
        Some(1) => Workers::Serial,
        Some(n) => Workers::Pool(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .map_err(|e| {
                    CommandError::argument(
                        "threads",
                        n,
                        format!("cannot start the worker threads: {e}"),
                    )
                })?,
        ),
    };
    let settings = SweepSettings {
        tracked_modes: request.modes,
        prestress: request.prestress,
        method: request.solver,
        step: request.step,
        end_time: request.end_time,
        ..SweepSettings::new(quantity)
    };
    let sweep =
        Sweep::new(&input.model, &request.params, settings).map_err(CommandError::SweepParams)?;
    Ok(SweepJob {
        input: input.clone(),
        sweep,
        shard: request.shard,
        workers,
    })
}

impl SweepJob {
    /// The indices of the points to compute (the shard's, or all).
    pub fn indices(&self) -> Vec<usize> {
        self.sweep.indices(self.shard)
    }

    /// How many points run at once.
    pub fn workers(&self) -> usize {
        match &self.workers {
            Workers::Global => rayon::current_num_threads(),
            Workers::Serial => 1,
            Workers::Pool(p) => p.current_num_threads(),
        }
    }

    /// Whether the sweep can be drawn to `path` (its format; one or two
    /// parameters).
    pub fn check_plot(&self, path: &Path) -> Result<(), CommandError> {
        Ok(check_plottable(path, self.sweep.parameters.len())?)
    }

    /// Computes the points `indices`; `progress` is called after each (from
    /// the worker threads).
    pub fn points(&self, indices: &[usize], progress: &(dyn Fn() + Sync)) -> Vec<RawPoint> {
        let one = |&i: &usize| {
            let p = self.sweep.point(i);
            progress();
            p
        };
        match &self.workers {
            Workers::Serial => indices.iter().map(one).collect(),
            Workers::Global => indices.par_iter().map(one).collect(),
            Workers::Pool(pool) => pool.install(|| indices.par_iter().map(one).collect()),
        }
    }

    /// The run of the computed `points` (in index order): the document
    /// (tracked when complete, with the modes when a shard) and the
    /// warnings, the model's and then each point's.
    pub fn finish(&self, points: Vec<RawPoint>) -> SweepRun {
        self.finish_as(points, self.shard)
    }

    /// The run of the whole grid from `shards`, documents of this sweep's
    /// shards computed elsewhere (each with its name for messages): joined
    /// and checked as `sweep-merge` joins them, then finished as a run of
    /// every point here ([`SweepJob::finish`]: tracked in index order, the
    /// model's warnings and then each point's), so that it is the run
    /// [`run`] gives. Refuses shards of another sweep (`sweep_id`).
    pub fn join(&self, shards: &[(String, SweepDocument)]) -> Result<SweepRun, CommandError> {
        let merged = merge(shards)?;
        let expected = &self.sweep.header.sweep_id;
        if &merged.header.sweep_id != expected {
            let (file, _) = &shards[0];
            return Err(CommandError::SweepMerge(SweepError::DifferentSweep {
                file: file.clone(),
                found: merged.header.sweep_id,
                expected: expected.clone(),
                first: String::from("the sweep asked for"),
            }));
        }
        Ok(self.finish_as(merged.points, None))
    }

    fn finish_as(&self, points: Vec<RawPoint>, shard: Option<Shard>) -> SweepRun {
        let own: Vec<String> = points
            .iter()
            .flat_map(|p| p.warnings.iter().map(|w| format!("point {}: {w}", p.index)))
            .collect();
        let run = crate::analysis::sweep::SweepRun {
            header: self.sweep.header.clone(),
            shard,
            points,
        };
        SweepRun {
            document: Run::of(&self.input, run.document()).warn(&self.input, own),
        }
    }
}

/// Runs `sweep` on `input`; `progress` is called after each point.
pub fn run(
    input: &ModelInput,
    request: &SweepRequest,
    progress: &(dyn Fn() + Sync),
) -> Result<SweepRun, CommandError> {
    let job = prepare(input, request)?;
    let points = job.points(&job.indices(), progress);
    Ok(job.finish(points))
}

/// The output of `sweep` and `sweep-merge`: the document with the run's
/// warnings. `document.output` has no provenance of its own; [`stamped`]
/// (`SweepRun::stamped`) puts it in.
///
/// [`stamped`]: SweepRun::stamped
#[derive(Debug, Clone)]
pub struct SweepRun {
    pub document: Run<SweepDocument>,
}

impl SweepRun {
    /// The `--json` document: the sweep with this build's version, the
    /// model's hash and the run's warnings in its own fields (the form
    /// `sweep-merge` reads back).
    pub fn stamped(&self) -> SweepDocument {
        SweepDocument {
            tool_version: Some(crate::results::provenance::tool_version().to_string()),
            model_sha256: self.document.model_sha256.clone(),
            warnings: self.document.warnings.clone(),
            ..self.document.output.clone()
        }
    }

    /// The run whose [`SweepRun::stamped`] document is `stamped`, the
    /// first `model_warnings` of its warnings the model's: a saved result
    /// read back (Python's pickle).
    pub fn unstamped(stamped: SweepDocument, model_warnings: usize) -> SweepRun {
        let warnings = stamped.warnings.clone();
        let model_sha256 = stamped.model_sha256.clone();
        SweepRun {
            document: Run {
                output: SweepDocument {
                    tool_version: None,
                    model_sha256: None,
                    warnings: Vec::new(),
                    ..stamped
                },
                warnings,
                model_sha256,
                model_warnings,
            },
        }
    }

    /// The command line's table.
    pub fn text(&self) -> String {
        sweep_table(&self.stamped())
    }

    /// The points as CSV (`--csv`).
    pub fn csv(&self) -> String {
        sweep_csv(&self.stamped())
    }

    /// Whether the sweep can be drawn to `path`.
    pub fn check_plot(&self, path: &Path) -> Result<(), CommandError> {
        Ok(check_plottable(
            path,
            self.document.output.parameters.len(),
        )?)
    }

    /// Draws the sweep to `path` (.svg or .png): lines over one parameter,
    /// a heat map over two.
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        Ok(write_sweep_figure(&self.stamped(), path)?)
    }

    /// The points that failed, as an error naming the first; `None` when
    /// every point succeeded.
    pub fn failure(&self) -> Option<CommandError> {
        let d = &self.document.output;
        if d.failed_points == 0 {
            return None;
        }
        let first = d
            .points
            .iter()
            .find_map(|p| p.error.as_deref().map(|e| (p.index, e)));
        let (index, message) = first.unwrap_or((0, ""));
        Some(CommandError::PointsFailed {
            failed: d.failed_points,
            total: d.points.len(),
            index,
            message: message.to_string(),
        })
    }
}
