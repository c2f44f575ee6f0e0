//! `Model.modal(...)` and its result, `ancf_modal.ModalResult`.
//!
//! [`ModalOutcome::document`] is the one place that builds `to_dict()`.

use crate::errors::{compute, Failure};
use crate::model::{choice, equilibrium, finite, PyModel};
use ancf::analysis::damped_modes::{mode_damping, ModeDamping};
use ancf::analysis::prestress::{modal_at_equilibrium, PrestressedModal};
use ancf::analysis::{modal_at_reference, EigenMethod, ModalResult, ModalSettings};
use ancf::model::{Model, ValidModel};
use ancf::output::modal_uff::{export_nodes, translations};
use ancf::System;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;
use std::sync::Arc;

/// What a modal analysis computed: at the reference, or at the
/// equilibrium beside the reference.
pub enum ModalOutcome {
    Reference(ModalResult),
    Prestressed(Box<PrestressedModal>),
}

impl ModalOutcome {
    /// The modes reported (the pre-stressed ones when pre-stressed).
    pub fn result(&self) -> &ModalResult {
        match self {
            ModalOutcome::Reference(r) => r,
            ModalOutcome::Prestressed(p) => &p.prestressed,
        }
    }

    /// The state the modes are linearized at.
    fn q<'a>(&'a self, system: &'a System) -> &'a [f64] {
        match self {
            ModalOutcome::Reference(_) => &system.q0,
            ModalOutcome::Prestressed(p) => &p.equilibrium.q,
        }
    }

    /// The document `modal --json` prints: the typed result
    /// ([`ancf::results::ModalOutput`], or [`ancf::results::PrestressedOutput`])
    /// with the provenance block.
    fn document(
        &self,
        model: &Model,
        label: &str,
        damping: &[ModeDamping],
        sha256: &str,
    ) -> serde_json::Value {
        let source = Some((model, label));
        match self {
            ModalOutcome::Reference(r) => crate::document_with(
                &ancf::results::ModalOutput::new(model, r, damping),
                source,
                Some(sha256),
                self.warnings(),
            ),
            ModalOutcome::Prestressed(p) => crate::document_with(
                &ancf::results::PrestressedOutput::new(model, p, damping),
                source,
                Some(sha256),
                self.warnings(),
            ),
        }
    }

    /// The analysis's own warnings, as the command line gives them: not an
    /// equilibrium, unstable, then (at the reference) the beam theory's.
    fn warnings(&self) -> Vec<String> {
        match self {
            ModalOutcome::Reference(r) => {
                let mut w = ancf::results::modal::reference_warnings(r);
                w.extend(ancf::analysis::shear::beam_theory_warnings(r));
                w
            }
            ModalOutcome::Prestressed(p) => ancf::results::modal::prestressed_warnings(p),
        }
    }

    /// The command line's table.
    fn table(&self, model: &Model) -> String {
        match self {
            ModalOutcome::Reference(r) => ancf::output::modal_report::modal_table(model, r),
            ModalOutcome::Prestressed(p) => {
                ancf::output::modal_report::prestress_table(&model.name, p)
            }
        }
    }
}

/// The result of `Model.modal`: frequencies, shapes and the command
/// line's table and document.
#[pyclass(name = "ModalResult", module = "ancf_modal", frozen)]
pub struct PyModalResult {
    model: Arc<ValidModel>,
    source: String,
    sha256: String,
    outcome: ModalOutcome,
    damping: Vec<ModeDamping>,
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
    if modes < 1 {
        return Err(Failure::argument("modes", modes, "must be a whole number ≥ 1").into());
    }
    let method = match choice("solver", solver, &["auto", "dense", "sparse"])? {
        "dense" => EigenMethod::Dense,
        "sparse" => EigenMethod::Sparse,
        _ => EigenMethod::Auto,
    };
    let load_scale = finite("load_scale", load_scale)?;
    let settings = ModalSettings {
        modes: Some(modes as usize),
        method,
    };
    let shared = Arc::clone(&model.model);
    let label = model.label();
    let (outcome, damping) = compute(py, move || {
        let model = shared;
        let system = System::new(&model);
        let fail = |e: ancf::AnalysisError| Failure::analysis(&label, &e);
        if prestress {
            let eq = equilibrium(&label, &system, load_scale)?;
            let prestressed = modal_at_equilibrium(&system, &eq, &settings).map_err(fail)?;
            let reference = modal_at_reference(&system, &settings).map_err(fail)?;
            let damping = mode_damping(&system, &eq.linearization(), &prestressed, model.damping)
                .map_err(fail)?;
            let p = PrestressedModal::new(&system, eq, reference, prestressed);
            Ok((ModalOutcome::Prestressed(Box::new(p)), damping))
        } else {
            let mut r = modal_at_reference(&system, &settings).map_err(fail)?;
            ancf::analysis::shear::annotate(&model, &system, &mut r);
            let damping =
                mode_damping(&system, &system.reference(), &r, model.damping).map_err(fail)?;
            Ok((ModalOutcome::Reference(r), damping))
        }
    })?;
    // The analysis's warnings (not an equilibrium, unstable) as Python
    // warnings (`RuntimeWarning`), named by the model's source as the
    // command line names them; `to_dict()["warnings"]` lists them too.
    let own = match &outcome {
        ModalOutcome::Reference(r) => ancf::results::modal::reference_warnings(r),
        ModalOutcome::Prestressed(p) => ancf::results::modal::prestressed_warnings(p),
    };
    for w in own {
        let text = std::ffi::CString::new(format!("{}: {w}", model.label()))
            .map_err(|e| Failure::Analysis(e.to_string()))?;
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(),
            &text,
            1,
        )?;
    }
    Ok(PyModalResult {
        model: Arc::clone(&model.model),
        source: model.label(),
        sha256: model.sha256.clone(),
        outcome,
        damping,
    })
}

impl PyModalResult {
    /// The elastic modes' translations at the export nodes (beam nodes,
    /// body points), as `modal --mac` and `--uff` use them.
    fn elastic_translations(&self, system: &System) -> (Vec<f64>, Vec<Vec<f64>>) {
        let nodes = export_nodes(system);
        let elastic: Vec<_> = self
            .outcome
            .result()
            .modes
            .iter()
            .filter(|m| !m.kind.is_zero())
            .collect();
        (
            elastic.iter().map(|m| m.frequency_hz).collect(),
            elastic
                .iter()
                .map(|m| translations(&nodes, &m.shape))
                .collect(),
        )
    }

    fn column(&self, f: impl Fn(usize, &ancf::analysis::Mode) -> f64) -> Vec<f64> {
        self.outcome
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
        let d = &self.damping;
        PyArray1::from_vec(
            py,
            self.column(|i, _| d.get(i).and_then(|d| d.damping_ratio).unwrap_or(f64::NAN)),
        )
    }

    /// Each mode's kind: `rigid`, `mechanism`, `bending`, `axial`, `spring`.
    #[getter]
    fn kinds(&self) -> Vec<String> {
        let r = self.outcome.result();
        r.modes.iter().map(|m| m.kind.to_string()).collect()
    }

    /// Number of zero-frequency modes (rigid motions and mechanisms, also
    /// those beyond `modes`).
    #[getter]
    fn rigid_modes(&self) -> usize {
        self.outcome.result().rigid_modes
    }

    /// How many of the zero-frequency modes are mechanisms of the joints.
    #[getter]
    fn mechanism_modes(&self) -> usize {
        self.outcome.result().mechanism_modes
    }

    /// Reported modes of kind `unstable` (negative ω² at a verified
    /// equilibrium).
    #[getter]
    fn unstable_modes(&self) -> usize {
        self.outcome.result().unstable_modes
    }

    /// Reported modes of kind `negative` (negative ω² at a state that is
    /// not an equilibrium).
    #[getter]
    fn negative_modes(&self) -> usize {
        self.outcome.result().negative_modes
    }

    /// Whether the modes' state is an equilibrium, as a dict (the
    /// document's `equilibrium` at the reference).
    #[getter]
    fn equilibrium<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = serde_json::to_value(&self.outcome.result().equilibrium)
            .map_err(|e| Failure::Analysis(e.to_string()))?;
        crate::json_to_python(py, &v)
    }

    /// Which eigensolver ran (`dense` or `sparse shift-invert Lanczos`).
    #[getter]
    fn solver(&self) -> &'static str {
        self.outcome.result().solver
    }

    /// Mode shapes, one row per mode, in the model's coordinates q (see
    /// `Model.coordinates()`), mass-normalized: φᵀMφ = 1 with M of
    /// `Model.matrices()` [1/√kg in position coordinates].
    #[getter]
    fn shapes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self
            .outcome
            .result()
            .modes
            .iter()
            .map(|m| m.shape.clone())
            .collect();
        if rows.is_empty() {
            return Ok(PyArray2::zeros(py, [0, self.outcome.result().dofs], false));
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
        let (mine, theirs) = (Arc::clone(&self.model), Arc::clone(&other.model));
        let other_source = other.source.clone();
        let (a, b) = (self, other);
        let m = compute(py, || {
            let (sa, sb) = (System::new(&mine), System::new(&theirs));
            let (na, nb) = (export_nodes(&sa).len(), export_nodes(&sb).len());
            if na != nb {
                return Err(Failure::Input(format!(
                    "{other_source}: {nb} export nodes, this model has {na}: the MAC needs the same nodes"
                )));
            }
            let (_, x) = a.elastic_translations(&sa);
            let (_, y) = b.elastic_translations(&sb);
            let m = ancf::signal::mac::mac(&x, &y);
            Ok((0..m.nrows())
                .map(|i| m.row(i).iter().copied().collect::<Vec<f64>>())
                .collect::<Vec<_>>())
        })?;
        if m.is_empty() {
            return Ok(PyArray2::zeros(py, [0, 0], false));
        }
        PyArray2::from_vec2(py, &m).map_err(|e| Failure::Analysis(e.to_string()).into())
    }

    /// The result as the library's JSON document (`modal --json`) as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::json_to_python(
            py,
            &self
                .outcome
                .document(&self.model, &self.source, &self.damping, &self.sha256),
        )
    }

    /// Writes the elastic modes as UFF 15 (nodes) and 55 (mass-normalised
    /// translations) to `path`, as `modal --uff`.
    fn write_uff(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            let system = System::new(&self.model);
            let provenance = ancf::results::provenance::header_lines(&self.sha256);
            let text =
                ancf::output::modal_uff::modal_uff(&system, self.outcome.result(), &provenance);
            ancf::output::files::write_atomic(&path, text.as_bytes())
                .map_err(|e| Failure::input(&e))
        })
    }

    /// Draws the first six elastic mode shapes to `path` (.svg or .png),
    /// as `modal --plot`.
    fn plot(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        compute(py, || {
            let system = System::new(&self.model);
            ancf::output::figures::write_mode_shapes(
                &system,
                self.outcome.q(&system),
                self.outcome.result(),
                &path,
            )
            .map_err(|e| Failure::input(&e))
        })
    }

    fn __repr__(&self) -> String {
        self.outcome.table(&self.model)
    }
}
