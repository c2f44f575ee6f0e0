//! `ancf_modal.sweep(..., client=...)`: a parameter study on a Dask
//! cluster. The request is checked here as a local sweep checks it (same
//! errors, before anything is sent); the pure-Python `ancf_modal._dask`
//! scatters the model, runs the grid's shards on the workers — each task
//! `sweep(..., threads=1, shard=(k, n))`, the local sweep's own evaluation
//! of its points on one thread — and gathers them; [`SweepJob::join`]
//! joins them here and tracks the modes in index order, so the result is
//! the local run's, number for number, warnings included.
//!
//! [`SweepJob::join`]: ancf::commands::sweep::SweepJob::join

use crate::errors::{compute, Failure};
use crate::model::PyModel;
use crate::sweep::{PySweepResult, Request};
use ancf::commands::sweep::{prepare, SweepRequest};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Runs the sweep `request` (from the keyword arguments `r`) on `client`'s
/// workers.
pub fn run(
    py: Python<'_>,
    model: &Bound<'_, PyModel>,
    params: &Bound<'_, PyDict>,
    r: &Request<'_>,
    mut request: SweepRequest,
    client: &Bound<'_, PyAny>,
) -> PyResult<PySweepResult> {
    if let Some(t) = r.threads {
        let why = "with a client each task runs its points on one thread (the workers' threads set how many run at once)";
        return Err(Failure::argument("threads", t, why).into());
    }
    if let Some((k, n)) = r.shard {
        let why =
            "with a client the grid is split into shards by the client; give one or the other";
        return Err(Failure::argument("shard", format!("({k}, {n})"), why).into());
    }
    request.threads = Some(1);
    let input = model.get().input();
    let job = compute(py, move || prepare(&input, &request).map_err(Failure::from))?;
    let total = job.indices().len();
    let options = PyDict::new(py);
    options.set_item("modes", r.modes)?;
    options.set_item("prestress", r.prestress)?;
    options.set_item("solver", r.solver)?;
    options.set_item("step", r.step)?;
    options.set_item("end_time", r.end_time)?;
    let shards = py
        .import("ancf_modal._dask")?
        .getattr("run_shards")?
        .call1((
            client, model, params, r.quantity, options, total, r.progress,
        ))?;
    let mut docs = Vec::new();
    for item in shards.try_iter()? {
        let doc = item?.cast::<PySweepResult>()?.get().run.stamped();
        let name = match doc.shard {
            Some(s) => format!("the task of shard {}/{}", s.index, s.count),
            None => String::from("a task's result"),
        };
        docs.push((name, doc));
    }
    let j = &job;
    let run = compute(py, move || j.join(&docs).map_err(Failure::from))?;
    PySweepResult::warned(py, run)
}
