//! `Model.reduce(...)` (the command line's `reduce`) and its result,
//! `ancf_modal.ReducedBody`: the reduced flexible body, its check against
//! the full model and its 3D node form (`ancf_modal.exudyn` imports it).
//!
//! A front end over [`ancf::commands::reduce`].

use crate::errors::{compute, Failure};
use crate::model::{choice, PyModel};
use ancf::analysis::reduce::ReductionMethod;
use ancf::commands::reduce::{run as reduce, ReduceRequest, ReduceRun};
use numpy::{PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A reduced flexible body.
#[pyclass(name = "ReducedBody", module = "ancf_modal", frozen)]
pub struct PyReducedBody {
    run: ReduceRun,
}

/// The reduction of `model` (the command line's `reduce`).
#[allow(clippy::too_many_arguments)]
pub fn run(
    model: &PyModel,
    py: Python<'_>,
    interface: Vec<(String, f64)>,
    modes: i64,
    method: &str,
    prestress: bool,
    keep_supports: bool,
    load_scale: f64,
) -> PyResult<PyReducedBody> {
    let method = match choice("method", method, &["craig-bampton", "free-interface"])? {
        "free-interface" => ReductionMethod::FreeInterface,
        _ => ReductionMethod::CraigBampton,
    };
    if modes < 1 {
        return Err(Failure::argument("modes", modes, "must be a whole number ≥ 1").into());
    }
    let request = ReduceRequest {
        interface,
        modes: usize::try_from(modes).unwrap_or(0),
        method,
        prestress,
        load_scale,
        keep_supports,
    };
    let input = model.input();
    let run = compute(py, move || reduce(&input, &request).map_err(Failure::from))?;
    crate::warn(py, run.document.own_warnings())?;
    Ok(PyReducedBody { run })
}

fn matrix<'py>(py: Python<'py>, rows: &[Vec<f64>], ncols: usize) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    numpy::PyArray1::from_vec(py, flat)
        .reshape([rows.len(), ncols])
        .expect("rows of equal length")
}

#[pymethods]
impl PyReducedBody {
    /// The reduced mass ΨᵀMΨ (m × m; Ψ is M-normalized: the identity).
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let m = &self.run.document.output.mass;
        matrix(py, m, m.len())
    }

    /// The reduced stiffness ΨᵀKΨ (m × m) [rad²/s²].
    #[getter]
    fn stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let k = &self.run.document.output.stiffness;
        matrix(py, k, k.len())
    }

    /// The flexible basis Ψ over the model's coordinates (n × m), as
    /// `Model.coordinates()` orders them (with the interface points as
    /// mesh nodes).
    #[getter]
    fn basis<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let b = &self.run.document.output.basis;
        matrix(py, b, self.run.reduction.size())
    }

    /// The rigid motions the floating frame carries (n × r), M-orthonormal.
    #[getter]
    fn rigid<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let r = &self.run.document.output.rigid;
        matrix(py, r, self.run.reduction.rigid.ncols())
    }

    /// The check: the reduced body against the full model under the other
    /// boundary condition (`condition`, `zero_modes`, `full_hz`,
    /// `reduced_hz`, `relative_error`).
    #[getter]
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let doc = serde_json::to_value(&self.run.document.output.check)
            .map_err(|e| Failure::Analysis(e.to_string()))?;
        crate::json_to_python(py, &doc)
    }

    /// The reduced body as the library's document (what `save` writes to
    /// a .json file).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(py, &self.run.document.document())
    }

    /// Writes the body to `path`, as the command line's `--out` does:
    /// `.json` (the document) or `.npz` (numpy arrays: `mass`,
    /// `stiffness`, `basis`, `rigid`, `q`, `origin`,
    /// `interface_coordinates`, `interface_nodes`, `node_positions`,
    /// `node_mass`, `node_stiffness` (rows [row, column, value]),
    /// `node_basis`, `total_mass_kg`, `inertia_kg_m2`, `component_hz`,
    /// `basis_hz`, `load_scale`, `check_full_hz`, `check_reduced_hz`,
    /// `check_relative_error`, `check_frame_hz`).
    fn save(&self, path: PathBuf) -> PyResult<()> {
        let ext = path.extension().and_then(|e| e.to_str());
        match ext.map(str::to_ascii_lowercase).as_deref() {
            Some("json" | "npz") => {
                self.run.write(&path).map_err(Failure::from)?;
                Ok(())
            }
            _ => Err(Failure::argument("path", path.display(), "must end in .json or .npz").into()),
        }
    }

    /// The command line's report, then its `warning:` lines.
    fn __repr__(&self) -> String {
        crate::with_warnings(self.run.text(), &self.run.document.warnings)
    }
}
