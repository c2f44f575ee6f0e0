//! `ancf_modal.sweep(...)` (the command line's `sweep`) and its result,
//! `ancf_modal.SweepResult`.
//!
//! The points run in chunks, each with the GIL released and in parallel;
//! between chunks a pending `KeyboardInterrupt` (or other signal) stops the
//! sweep. A chunk grows while its points are quick, so it takes about a
//! quarter of a second at most.
//!
//! [`PySweepResult::document`] is the one place that builds `to_dict()`.

use crate::errors::{compute, one_line, Failure};
use crate::model::{choice, PyModel};
use ancf::analysis::sweep::{Quantity, RawPoint, Sweep, SweepDocument, SweepRun, SweepSettings};
use ancf::analysis::EigenMethod;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use rayon::prelude::*;
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
}

/// The points `indices`, in parallel on `pool` (serially when `None`).
fn points(sweep: &Sweep, indices: &[usize], pool: Option<&rayon::ThreadPool>) -> Vec<RawPoint> {
    match pool {
        None => indices.iter().map(|&i| sweep.point(i)).collect(),
        Some(pool) => pool.install(|| indices.par_iter().map(|&i| sweep.point(i)).collect()),
    }
}

/// A parameter study of `model`.
pub fn run(
    py: Python<'_>,
    model: &PyModel,
    params: &Bound<'_, PyDict>,
    r: Request<'_>,
) -> PyResult<PySweepResult> {
    let quantity = Quantity::parse(r.quantity)
        .map_err(|e| Failure::argument("quantity", r.quantity, &one_line(&e)))?;
    if r.modes < 1 {
        return Err(Failure::argument("modes", r.modes, "must be a whole number ≥ 1").into());
    }
    for (name, v) in [("step", r.step), ("end_time", r.end_time)] {
        if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(Failure::argument(name, v, "must be a number > 0").into());
        }
    }
    let threads = match r.threads {
        Some(n) if n < 1 => {
            return Err(Failure::argument("threads", n, "must be a whole number ≥ 1").into())
        }
        Some(n) => Some(n as usize),
        None => None,
    };
    let method = match choice("solver", r.solver, &["auto", "dense", "sparse"])? {
        "dense" => EigenMethod::Dense,
        "sparse" => EigenMethod::Sparse,
        _ => EigenMethod::Auto,
    };
    let mut specs = Vec::with_capacity(params.len());
    for (k, v) in params.iter() {
        specs.push(spec(&k.extract::<String>()?, &v)?);
    }
    let settings = SweepSettings {
        tracked_modes: r.modes as usize,
        prestress: r.prestress,
        method,
        step: r.step,
        end_time: r.end_time,
        ..SweepSettings::new(quantity)
    };
    let shared = model.model.clone();
    let sweep = compute(py, move || {
        Sweep::new(&shared, &specs, settings)
            .map_err(|e| Failure::Input(format!("params: {}", one_line(&e))))
    })?;
    let pool = match threads {
        Some(1) => None,
        n => Some(
            rayon::ThreadPoolBuilder::new()
                .num_threads(n.unwrap_or(0))
                .build()
                .map_err(|e| Failure::argument("threads", n.unwrap_or(0), &e.to_string()))?,
        ),
    };
    let indices = sweep.indices(None);
    let mut chunk = pool.as_ref().map_or(1, |p| p.current_num_threads());
    let mut done: Vec<RawPoint> = Vec::with_capacity(indices.len());
    let mut start = 0;
    while start < indices.len() {
        let end = (start + chunk).min(indices.len());
        let started = Instant::now();
        let (s, pool_ref, part) = (&sweep, pool.as_ref(), &indices[start..end]);
        done.extend(compute(py, move || Ok(points(s, part, pool_ref)))?);
        py.check_signals()?;
        if started.elapsed() < CHUNK_TIME / 4 {
            chunk *= 2;
        }
        start = end;
    }
    let mut warnings = Vec::new();
    for p in &done {
        for w in &p.warnings {
            warnings.push(format!("point {}: {w}", p.index));
        }
    }
    let run = SweepRun {
        header: sweep.header.clone(),
        shard: None,
        points: done,
    };
    let document = compute(py, move || {
        Ok(SweepDocument {
            tool_version: Some(ancf::results::provenance::tool_version().to_string()),
            model_sha256: Some(model.sha256.clone()),
            warnings,
            ..run.document()
        })
    })?;
    Ok(PySweepResult { document })
}

/// The result of `ancf_modal.sweep`: the grid, the quantity at each point
/// and, for a tracked quantity, the tracked frequencies.
#[pyclass(name = "SweepResult", module = "ancf_modal", frozen)]
pub struct PySweepResult {
    document: SweepDocument,
}

impl PySweepResult {
    /// The sweep's JSON document (`sweep --json`).
    fn document(&self) -> &SweepDocument {
        &self.document
    }
}

#[pymethods]
impl PySweepResult {
    /// The parameters' names, in the order of `values`' columns.
    #[getter]
    fn names(&self) -> Vec<String> {
        let p = &self.document.parameters;
        p.iter().map(|p| p.name.clone()).collect()
    }

    /// Each point's parameter values [SI], points × parameters, in the
    /// grid's row-major order (the first parameter varies slowest).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .document
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
            .document
            .points
            .iter()
            .map(|p| p.result.unwrap_or(f64::NAN));
        PyArray1::from_vec(py, r.collect())
    }

    /// Each point's error message, None where it succeeded.
    #[getter]
    fn errors(&self) -> Vec<Option<String>> {
        self.document
            .points
            .iter()
            .map(|p| p.error.clone())
            .collect()
    }

    /// Points that failed.
    #[getter]
    fn failed_points(&self) -> usize {
        self.document.failed_points
    }

    /// The tracked modes' frequencies [Hz], points × tracked modes (NaN
    /// where a mode was not found); None for an untracked quantity.
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyArray2<f64>>>> {
        let Some(k) = self.document.tracked_modes else {
            return Ok(None);
        };
        let rows: Vec<Vec<f64>> = self
            .document
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
        let doc =
            serde_json::to_value(self.document()).map_err(|e| Failure::Analysis(e.to_string()))?;
        crate::json_to_python(py, &doc)
    }

    fn __repr__(&self) -> String {
        ancf::output::sweep_report::sweep_table(&self.document)
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
/// integration, `threads` workers (default all cores; 1 = serial). A point
/// that fails is recorded (`errors`, NaN in `result`) and the sweep goes
/// on; KeyboardInterrupt stops it.
#[pyfunction(name = "sweep")]
#[pyo3(signature = (model, params, quantity, modes = 6, prestress = false, solver = "auto", step = None, end_time = None, threads = None))]
#[allow(clippy::too_many_arguments)]
pub fn sweep_function(
    py: Python<'_>,
    model: PyRef<'_, PyModel>,
    params: &Bound<'_, PyDict>,
    quantity: &str,
    modes: i64,
    prestress: bool,
    solver: &str,
    step: Option<f64>,
    end_time: Option<f64>,
    threads: Option<i64>,
) -> PyResult<PySweepResult> {
    let r = Request {
        quantity,
        modes,
        prestress,
        solver,
        step,
        end_time,
        threads,
    };
    run(py, &model, params, r)
}
