//! `Model.modal(...)` and its result, `ancf_modal.ModalResult`.
//!
//! A front end over [`ancf::commands::modal`]: keyword arguments → request →
//! `run` → wrap; `to_dict()` is the run's document.

use crate::errors::{compute, Failure};
use crate::model::{choice, PyModel};
use ancf::analysis::EigenMethod;
use ancf::commands::modal::{mac_of, run as modal, ModalRequest, ModalRun};
use ancf::results::ModalJson;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The result of `Model.modal`: frequencies, shapes and the command
/// line's table and document.
#[pyclass(name = "ModalResult", module = "ancf_modal", frozen)]
pub struct PyModalResult {
    source: String,
    run: ModalRun,
}

/// The modal analysis of `model` (the command line's `modal`).
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    modes: i64,
    prestress: bool,
    solver: &str,
    load_scale: f64,
) -> PyResult<PyModalResult> {
    let solver = match choice("solver", solver, &["auto", "dense", "sparse"])? {
        "dense" => EigenMethod::Dense,
        "sparse" => EigenMethod::Sparse,
        _ => EigenMethod::Auto,
    };
    let request = ModalRequest {
        modes: usize::try_from(modes).unwrap_or(0),
        solver,
        prestress,
        load_scale,
        mac: None,
    };
    if modes < 1 {
        return Err(Failure::argument("modes", modes, "must be a whole number ≥ 1").into());
    }
    let input = model.input();
    let run = compute(py, move || modal(&input, &request).map_err(Failure::from))?;
    // The analysis's own warnings (not an equilibrium, unstable, beam
    // theory) as Python warnings (`ModelWarning`); the model's were
    // given when it was read. `to_dict()["warnings"]` and the repr list
    // them all.
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyModalResult {
        source: model.label(),
        run,
    })
}

impl PyModalResult {
    fn column(&self, f: impl Fn(usize, &ancf::analysis::Mode) -> f64) -> Vec<f64> {
        self.run
            .outcome
            .result()
            .modes
            .iter()
            .enumerate()
            .map(|(i, m)| f(i, m))
            .collect()
    }
}

#[pymethods]
impl PyModalResult {
    /// Natural frequencies [Hz], ascending; 0 for rigid and mechanism modes;
    /// −√|ω²|/2π for a negative eigenvalue.
    #[getter]
    fn frequencies_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.column(|_, m| m.frequency_hz))
    }

    /// Eigenvalues ω² [rad²/s²].
    #[getter]
    fn eigenvalues<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.column(|_, m| m.eigenvalue))
    }

    /// Bound on each frequency's relative error from the eigen-solve and
    /// round-off [–] (not the mesh's discretization error); NaN for zero
    /// modes.
    #[getter]
    fn error_bound<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.column(|_, m| m.error_bound.unwrap_or(f64::NAN)))
    }

    /// Modal damping ratio ζ [–] (Rayleigh damping, or complex modes with
    /// dampers; 0 for an undamped model); NaN for zero modes.
    #[getter]
    fn damping_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let zeta: Vec<f64> = match &self.run.document.output {
            ModalJson::Reference(o) => o.modes.iter().map(|m| m.damping_ratio).collect(),
            ModalJson::Prestressed(o) => o.modes.iter().map(|m| m.damping_ratio).collect(),
            ModalJson::LoadSweep(_) => Vec::new(),
        }
        .into_iter()
        .map(|z| z.unwrap_or(f64::NAN))
        .collect();
        PyArray1::from_vec(py, zeta)
    }

    /// Each mode's kind: `rigid`, `mechanism`, `bending`, `axial`, `spring`.
    #[getter]
    fn kinds(&self) -> Vec<String> {
        let r = self.run.outcome.result();
        r.modes.iter().map(|m| m.kind.to_string()).collect()
    }

    /// Number of zero-frequency modes (rigid motions and mechanisms, also
    /// those beyond `modes`).
    #[getter]
    fn rigid_modes(&self) -> usize {
        self.run.outcome.result().rigid_modes
    }

    /// How many of the zero-frequency modes are mechanisms of the joints.
    #[getter]
    fn mechanism_modes(&self) -> usize {
        self.run.outcome.result().mechanism_modes
    }

    /// Reported modes of kind `unstable` (negative ω² at a verified
    /// equilibrium).
    #[getter]
    fn unstable_modes(&self) -> usize {
        self.run.outcome.result().unstable_modes
    }

    /// Reported modes of kind `negative` (negative ω² at a state that is
    /// not an equilibrium).
    #[getter]
    fn negative_modes(&self) -> usize {
        self.run.outcome.result().negative_modes
    }

    /// Whether the modes' state is an equilibrium, as a dict (the
    /// document's `equilibrium` at the reference).
    #[getter]
    fn equilibrium<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = serde_json::to_value(&self.run.outcome.result().equilibrium)
            .map_err(|e| Failure::Analysis(e.to_string()))?;
        crate::json_to_python(py, &v)
    }

    /// Which eigensolver ran (`dense` or `sparse shift-invert Lanczos`).
    #[getter]
    fn solver(&self) -> &'static str {
        self.run.outcome.result().solver
    }

    /// Mode shapes, one row per mode, in the model's coordinates q (see
    /// `Model.coordinates()`), mass-normalized: φᵀMφ = 1 with M of
    /// `Model.matrices()` [1/√kg in position coordinates].
    #[getter]
    fn shapes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .run
            .outcome
            .result()
            .modes
            .iter()
            .map(|m| m.shape.clone())
            .collect();
        if rows.is_empty() {
            return Ok(PyArray2::zeros(
                py,
                [0, self.run.outcome.result().dofs],
                false,
            ));
        }
        PyArray2::from_vec2(py, &rows).map_err(|e| Failure::Analysis(e.to_string()).into())
    }

    /// The modal assurance criterion MAC = (φᵀψ)²/(φᵀφ ψᵀψ) of this result's
    /// elastic modes (rows) against `other`'s (columns), on the
    /// translations at the beam nodes and body points (as `modal --mac`).
    fn mac<'py>(
        &self,
        py: Python<'py>,
        other: &PyModalResult,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let other_source = PathBuf::from(&other.source);
        let (a, b) = (&self.run, &other.run);
        let m = compute(py, || {
            mac_of(
                (&a.system, a.outcome.result()),
                (&b.system, b.outcome.result()),
                &other_source,
            )
            .map(|t| t.matrix)
            .map_err(Failure::from)
        })?;
        if m.is_empty() {
            return Ok(PyArray2::zeros(py, [0, 0], false));
        }
        PyArray2::from_vec2(py, &m).map_err(|e| Failure::Analysis(e.to_string()).into())
    }

    /// The result as the library's JSON document (`modal --json`) as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes the elastic modes as UFF 15 (nodes) and 55 (mass-normalised
    /// translations) to `path`, as `modal --uff`.
    fn write_uff(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            ancf::output::files::write_atomic(&path, self.run.uff().as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws the first six elastic mode shapes to `path` (.svg or .png),
    /// as `modal --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || self.run.write_plot(&path).map_err(Failure::from))
    }

    /// The command line's report, then its `warning:` lines (the run's
    /// warnings, as `to_dict()["warnings"]`).
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
