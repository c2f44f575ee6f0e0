//! `ancf_modal.sweep(...)` and `ancf_modal.sweep_merge(...)` (the command
//! line's `sweep` and `sweep-merge`) and their result,
//! `ancf_modal.SweepResult`: front ends over [`ancf::commands::sweep`] and
//! [`ancf::commands::sweep_merge`].
//!
//! The points run in chunks, each with the GIL released and in parallel;
//! between chunks a pending `KeyboardInterrupt` (or other signal) stops the
//! sweep. A chunk grows while its points are quick, so it takes about a
//! quarter of a second at most. Given a Dask client, the points run on its
//! cluster instead ([`crate::sweep_dask`]); a `SweepResult` pickles as its
//! document, so that the workers' shards come back exact.

use crate::errors::{compute, one_line, Failure};
use crate::model::{choice, PyModel};
use ancf::analysis::sweep::{Quantity, RawPoint, Shard};
use ancf::analysis::EigenMethod;
use ancf::commands::sweep::{prepare, SweepRequest, SweepRun};
use ancf::commands::sweep_merge::{self, SweepMergeRequest};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// A chunk of points may take this long before the next signal check.
const CHUNK_TIME: Duration = Duration::from_millis(250);

/// `NAME=LO:HI:N[:log]` or `NAME=V1,V2,…` from a key and a value
/// "LO:HI:N[:log]", a tuple (LO, HI, N[, "log"]), or a list (or 1-D
/// array) of the values.
fn spec(name: &str, value: &Bound<'_, PyAny>) -> PyResult<String> {
    if let Ok(text) = value.cast::<PyString>() {
        return Ok(format!("{name}={}", text.to_cow()?));
    }
    if !value.is_instance_of::<pyo3::types::PyTuple>() {
        if let Ok(values) = value.extract::<Vec<f64>>() {
            let text: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
            return Ok(format!("{name}={}", text.join(",")));
        }
    }
    if let Ok((lo, hi, n)) = value.extract::<(f64, f64, i64)>() {
        return Ok(format!("{name}={lo:?}:{hi:?}:{n}"));
    }
    let (lo, hi, n, spacing): (f64, f64, i64, String) = value.extract().map_err(|_| {
        Failure::argument(
            "params",
            value.repr().map(|r| r.to_string()).unwrap_or_default(),
            &format!("the value of `{name}` must be \"LO:HI:N[:log]\", (LO, HI, N[, \"log\"]) or a list of values"),
        )
    })?;
    Ok(format!("{name}={lo:?}:{hi:?}:{n}:{spacing}"))
}

/// The sweep's keyword arguments.
pub struct Request<'a> {
    pub quantity: &'a str,
    pub modes: i64,
    pub prestress: bool,
    pub solver: &'a str,
    pub step: Option<f64>,
    pub end_time: Option<f64>,
    pub threads: Option<i64>,
    pub shard: Option<(i64, i64)>,
    /// Dask's progress bar (with a client).
    pub progress: bool,
}

/// A count argument: negative values are out of range as 0 is.
fn count(v: i64) -> usize {
    usize::try_from(v).unwrap_or(0)
}

/// The command's request from the keyword arguments.
fn request(params: &Bound<'_, PyDict>, r: &Request<'_>) -> PyResult<SweepRequest> {
    let quantity = Quantity::parse(r.quantity)
        .map_err(|e| Failure::argument("quantity", r.quantity, &one_line(&e)))?;
    let solver = match choice("solver", r.solver, &["auto", "dense", "sparse"])? {
        "dense" => EigenMethod::Dense,
        "sparse" => EigenMethod::Sparse,
        _ => EigenMethod::Auto,
    };
    let mut specs = Vec::with_capacity(params.len());
    for (k, v) in params.iter() {
        specs.push(spec(&k.extract::<String>()?, &v)?);
    }
    Ok(SweepRequest {
        params: specs,
        quantity: Some(quantity),
        step: r.step,
        end_time: r.end_time,
        modes: count(r.modes),
        prestress: r.prestress,
        solver,
        shard: r.shard.map(|(k, n)| Shard {
            index: count(k),
            count: count(n),
        }),
        threads: r.threads.map(count),
    })
}

/// A parameter study of `model`, here or, given a client, on its cluster.
pub fn run(
    py: Python<'_>,
    model: &Bound<'_, PyModel>,
    params: &Bound<'_, PyDict>,
    r: Request<'_>,
    client: Option<&Bound<'_, PyAny>>,
) -> PyResult<PySweepResult> {
    let request = request(params, &r)?;
    if let Some(client) = client {
        return crate::sweep_dask::run(py, model, params, &r, request, client);
    }
    let input = model.get().input();
    let job = compute(py, move || prepare(&input, &request).map_err(Failure::from))?;
    let indices = job.indices();
    let mut chunk = job.workers();
    let mut done: Vec<RawPoint> = Vec::with_capacity(indices.len());
    let mut start = 0;
    while start < indices.len() {
        let end = (start + chunk).min(indices.len());
        let started = Instant::now();
        let (j, part) = (&job, &indices[start..end]);
        done.extend(compute(py, move || Ok(j.points(part, &|| {})))?);
        py.check_signals()?;
        if started.elapsed() < CHUNK_TIME / 4 {
            chunk *= 2;
        }
        start = end;
    }
    let j = &job;
    let run = compute(py, move || Ok(j.finish(done)))?;
    PySweepResult::warned(py, run)
}

/// A shard for `sweep_merge`, as given.
enum GivenShard {
    /// A result of `sweep(..., shard=(k, n))`.
    Result(Box<ancf::analysis::sweep::SweepDocument>),
    /// Its `to_dict()`, as JSON text.
    Json(String),
    /// A file of `sweep --shard K/N --json`.
    File(PathBuf),
}

/// Joins shards (results, their dicts or files) into the complete sweep.
pub fn merge(py: Python<'_>, shards: &Bound<'_, PyAny>) -> PyResult<PySweepResult> {
    if shards.is_instance_of::<PyString>() || shards.is_instance_of::<PyDict>() {
        return Err(Failure::argument(
            "shards",
            shards.repr().map(|r| r.to_string()).unwrap_or_default(),
            "must be a sequence of shards (SweepResults, their to_dict()s or file paths)",
        )
        .into());
    }
    let mut given = Vec::new();
    for item in shards.try_iter()? {
        let item = item?;
        given.push(if let Ok(r) = item.cast::<PySweepResult>() {
            GivenShard::Result(Box::new(r.get().run.stamped()))
        } else if item.is_instance_of::<PyDict>() {
            let text = py.import("json")?.call_method1("dumps", (&item,))?;
            GivenShard::Json(text.extract()?)
        } else {
            GivenShard::File(item.extract().map_err(|_| {
                Failure::argument(
                    "shards",
                    item.repr().map(|r| r.to_string()).unwrap_or_default(),
                    "each shard must be a SweepResult, its to_dict() or a file path",
                )
            })?)
        });
    }
    let run = compute(py, move || {
        let mut request = SweepMergeRequest::default();
        for (i, shard) in given.into_iter().enumerate() {
            let name = format!("shards[{i}]");
            request.shards.push(match shard {
                GivenShard::Result(doc) => (name, *doc),
                GivenShard::Json(text) => {
                    let doc = sweep_merge::parse(&name, &text).map_err(Failure::from)?;
                    (name, doc)
                }
                GivenShard::File(path) => sweep_merge::read(&path).map_err(Failure::from)?,
            });
        }
        sweep_merge::run(&request).map_err(Failure::from)
    })?;
    Ok(PySweepResult { run })
}

/// The result of `ancf_modal.sweep`: the grid, the quantity at each point
/// and, for a tracked quantity, the tracked frequencies.
#[pyclass(name = "SweepResult", module = "ancf_modal", frozen)]
pub struct PySweepResult {
    pub run: SweepRun,
}

impl PySweepResult {
    /// The result of `run`, after raising the points' own warnings as
    /// Python warnings (`ModelWarning`); the model's were given when it
    /// was read.
    pub fn warned(py: Python<'_>, run: SweepRun) -> PyResult<PySweepResult> {
        crate::warn(py, run.document.own_warnings())?;
        Ok(PySweepResult { run })
    }

    /// The sweep without its provenance (the points, the parameters).
    fn document(&self) -> &ancf::analysis::sweep::SweepDocument {
        &self.run.document.output
    }
}

#[pymethods]
impl PySweepResult {
    /// The parameters' names, in the order of `values`' columns.
    #[getter]
    fn names(&self) -> Vec<String> {
        let p = &self.document().parameters;
        p.iter().map(|p| p.name.clone()).collect()
    }

    /// Each point's parameter values [SI], points × parameters, in the
    /// grid's row-major order (the first parameter varies slowest).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .document()
            .points
            .iter()
            .map(|p| p.values.clone())
            .collect();
        PyArray2::from_vec2(py, &rows).map_err(|e| Failure::Analysis(e.to_string()).into())
    }

    /// The quantity at each point [Hz or s]; NaN where the point failed.
    #[getter]
    fn result<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let r = self
            .document()
            .points
            .iter()
            .map(|p| p.result.unwrap_or(f64::NAN));
        PyArray1::from_vec(py, r.collect())
    }

    /// Each point's error message, None where it succeeded.
    #[getter]
    fn errors(&self) -> Vec<Option<String>> {
        self.document()
            .points
            .iter()
            .map(|p| p.error.clone())
            .collect()
    }

    /// Points that failed.
    #[getter]
    fn failed_points(&self) -> usize {
        self.document().failed_points
    }

    /// The tracked modes' frequencies [Hz], points × tracked modes (NaN
    /// where a mode was not found); None for an untracked quantity.
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let Some(k) = self.document().tracked_modes else {
            return Ok(None);
        };
        let rows: Vec<Vec<f64>> = self
            .document()
            .points
            .iter()
            .map(|p| match &p.frequencies_hz {
                Some(f) => f.iter().map(|v| v.unwrap_or(f64::NAN)).collect(),
                None => vec![f64::NAN; k],
            })
            .collect();
        PyArray2::from_vec2(py, &rows)
            .map(Some)
            .map_err(|e| Failure::Analysis(e.to_string()).into())
    }

    /// The sweep's JSON document (`sweep --json`) as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let doc = serde_json::to_value(self.run.stamped())
            .map_err(|e| Failure::Analysis(e.to_string()))?;
        crate::json_to_python(py, &doc)
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }

    /// Pickles as its document (`to_dict()`'s JSON, every number exact)
    /// and how many of its warnings are the model's.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, usize))> {
        let run = &slf.get().run;
        let text =
            serde_json::to_string(&run.stamped()).map_err(|e| Failure::Analysis(e.to_string()))?;
        let restore = slf.get_type().getattr("_from_state")?;
        Ok((restore, (text, run.document.model_warnings)))
    }

    /// The result pickled by `__reduce__`.
    #[classmethod]
    fn _from_state(
        _cls: &Bound<'_, pyo3::types::PyType>,
        text: &str,
        model_warnings: usize,
    ) -> PyResult<PySweepResult> {
        let stamped = sweep_merge::parse("a pickled SweepResult", text).map_err(Failure::from)?;
        Ok(PySweepResult {
            run: SweepRun::unstamped(stamped, model_warnings),
        })
    }
}

/// A parameter study (the command line's `sweep`): `quantity`
/// (`first_bending_hz` [Hz], `frequency:K` [Hz] tracked by MAC,
/// `time_to_distance_s` [s], `peak:SENSOR`) over the full grid of
/// `params` — {name: "LO:HI:N[:log]" or (LO, HI, N[, "log"])}, names as
/// `sweep --param` (a JSON path, a calibration short name,
/// `load_scale:ID,...`; a name ending in `+` offsets the model's value),
/// values SI. `modes` tracked modes [count], `prestress` linearizes at the
/// equilibrium, `step` and `end_time` [s] set transient quantities'
/// integration, `threads` workers (default all cores; 1 = serial),
/// `shard=(k, n)` computes only the points whose index is k − 1 modulo n
/// (as `--shard K/N`; join the shards with `sweep_merge`). A point that
/// fails is recorded (`errors`, NaN in `result`) and the sweep goes on;
/// KeyboardInterrupt stops it. `client`, a `dask.distributed.Client`,
/// runs the points on its cluster (one thread per task; `progress` shows
/// Dask's progress bar) and gives the same result.
#[pyfunction(name = "sweep")]
#[pyo3(signature = (model, params, quantity, modes = 6, prestress = false, solver = "auto", step = None, end_time = None, threads = None, shard = None, client = None, progress = false))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_function(
    py: Python<'_>,
    model: &Bound<'_, PyModel>,
    params: &Bound<'_, PyDict>,
    quantity: &str,
    modes: i64,
    prestress: bool,
    solver: &str,
    step: Option<f64>,
    end_time: Option<f64>,
    threads: Option<i64>,
    shard: Option<Vec<i64>>,
    client: Option<&Bound<'_, PyAny>>,
    progress: bool,
) -> PyResult<PySweepResult> {
    // A pair as a tuple or a list, as `params` takes either.
    let shard = match shard.as_deref() {
        None => None,
        Some(&[k, n]) => Some((k, n)),
        Some(other) => {
            return Err(Failure::argument(
                "shard",
                format!("{other:?}"),
                "must be a pair (k, n): part k of n",
            )
            .into())
        }
    };
    if progress && client.is_none() {
        let why = "shows the progress of the Dask tasks, so it needs a client";
        return Err(Failure::argument("progress", "True", why).into());
    }
    let r = Request {
        quantity,
        modes,
        prestress,
        solver,
        step,
        end_time,
        threads,
        shard,
        progress,
    };
    run(py, model, params, r, client)
}

/// Joins the shards of a sweep (the command line's `sweep-merge`) into the
/// result one run of the whole grid gives: `shards` is a sequence of
/// `SweepResult`s of `sweep(..., shard=(k, n))`, their `to_dict()`s, or
/// paths of `sweep --shard K/N --json` files (mixed as you like). The
/// merged result's `to_dict()` is `sweep-merge --json`'s document.
#[pyfunction(name = "sweep_merge")]
pub fn sweep_merge_function(py: Python<'_>, shards: &Bound<'_, PyAny>) -> PyResult<PySweepResult> {
    merge(py, shards)
}
