//! `ancf_modal.Model`: a validated model file, its parameters and its
//! matrices; the analyses are its methods (one module per result kind).

use crate::builtin;
use crate::errors::{compute, Failure};
use crate::matrices;
use ancf::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf::analysis::sweep::param;
use ancf::error::{ModelError, Source};
use ancf::model::{Model, ValidModel};
use ancf::results::provenance::sha256_hex;
use ancf::System;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use std::path::PathBuf;
use std::sync::Arc;

/// A model: an assembly of ANCF beams, rigid bodies and point masses with
/// joints, springs, loads and sensors (the JSON model file, SI units).
#[pyclass(name = "Model", module = "ancf_modal", frozen)]
pub struct PyModel {
    pub model: Arc<ValidModel>,
    /// Where it came from, for messages (`<built-in model>`, the path).
    pub source: Source,
    /// SHA-256 of the JSON text it was read from (`model_sha256`).
    pub sha256: String,
}

impl PyModel {
    /// Parses and validates `text`, read from `source`.
    pub fn parse(text: &str, source: Source) -> Result<PyModel, Failure> {
        let model = Model::from_json(text, source.clone()).map_err(|e| Failure::input(&e))?;
        Ok(PyModel {
            model: Arc::new(model),
            source,
            sha256: sha256_hex(text.as_bytes()),
        })
    }

    /// A model a command made (a fitted one), read from `source`; its
    /// hash is that of its JSON text.
    pub fn made(model: ValidModel, source: &Source) -> PyModel {
        PyModel {
            sha256: sha256_hex(model.to_json().as_bytes()),
            model: Arc::new(model),
            source: source.clone(),
        }
    }

    /// The model as the commands take it.
    pub fn input(&self) -> ancf::commands::ModelInput {
        ancf::commands::ModelInput {
            model: self.model.clone(),
            source: self.source.clone(),
            sha256: self.sha256.clone(),
        }
    }

    /// The model's name in messages: its path or `<built-in model>`.
    pub fn label(&self) -> String {
        self.source.to_string()
    }

    /// The model's unit warnings ([`Model::unit_warnings`]), named by its
    /// source as the command line's `warning:` lines name them.
    fn unit_warnings(&self) -> Vec<String> {
        self.input().unit_warnings()
    }

    /// This model, after raising its unit warnings as `ModelWarning`s (the
    /// result documents' `warnings` and the reprs hold them too).
    fn warned(self, py: Python<'_>) -> PyResult<PyModel> {
        crate::warn(py, &self.unit_warnings())?;
        Ok(self)
    }
}

/// A pickled model: its JSON, its file (`None`: the built-in model) and
/// the SHA-256 of the text it was read from.
type State = (String, Option<PathBuf>, String);

/// An argument's text choice among `allowed`.
pub fn choice<'a>(name: &str, value: &'a str, allowed: &[&str]) -> Result<&'a str, Failure> {
    if allowed.contains(&value) {
        Ok(value)
    } else {
        Err(Failure::argument(
            name,
            value,
            &format!("must be one of {}", allowed.join(", ")),
        ))
    }
}

/// A finite number.
pub fn finite(name: &str, value: f64) -> Result<f64, Failure> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Failure::argument(name, value, "must be a finite number"))
    }
}

/// The static equilibrium under the loads × `load_scale` (their values at
/// t = 0) and gravity, with the model named in its error.
pub fn equilibrium(
    label: &str,
    system: &System,
    load_scale: f64,
) -> Result<ancf::analysis::statics::Equilibrium, Failure> {
    let settings = StaticSettings {
        load_scale,
        ..StaticSettings::default()
    };
    solve_equilibrium(system, &settings).map_err(|e| Failure::analysis(label, &e))
}

#[pymethods]
impl PyModel {
    /// Reads a model: `path_or_text` is a path to a JSON model file (str or
    /// os.PathLike) or the JSON text itself (a str starting with `{`).
    /// Raises ModelError with the command line's message for a file that
    /// cannot be read, malformed JSON or an invalid value.
    #[staticmethod]
    fn from_json(py: Python<'_>, path_or_text: &Bound<'_, PyAny>) -> PyResult<PyModel> {
        if let Ok(s) = path_or_text.cast::<PyString>() {
            let text = s.to_cow()?;
            if text.trim_start().starts_with('{') {
                let text = text.into_owned();
                let source = Source::File(PathBuf::from("<json text>"));
                return compute(py, move || PyModel::parse(&text, source))?.warned(py);
            }
        }
        let path: PathBuf = path_or_text.extract()?;
        compute(py, move || {
            let source = Source::File(path.clone());
            let text = std::fs::read_to_string(&path).map_err(|io| {
                Failure::input(&ModelError::Read {
                    source_name: source.clone(),
                    io,
                })
            })?;
            PyModel::parse(&text, source)
        })?
        .warned(py)
    }

    /// A model shipped with the package, by the file stem of `models/`:
    /// `rcbo_free_free` (the paper's free-free assembly, the command line's
    /// built-in model), `rcbo_prestressed`, `rcbo_switch_off`,
    /// `rcbo_switch_off_uncalibrated`, `beam_free_free`, `cantilever`.
    #[staticmethod]
    #[pyo3(signature = (name = "rcbo_free_free"))]
    fn builtin(py: Python<'_>, name: &str) -> PyResult<PyModel> {
        let text = builtin::text(name).ok_or_else(|| {
            Failure::argument(
                "name",
                name,
                &format!(
                    "no shipped model of that name (there: {})",
                    builtin::names()
                ),
            )
        })?;
        // The default is the command line's built-in model; the others are
        // named as the files the command line reads from the repository.
        let source = if name == "rcbo_free_free" {
            Source::BuiltIn
        } else {
            Source::File(PathBuf::from(format!("models/{name}.json")))
        };
        compute(py, move || PyModel::parse(text, source))?.warned(py)
    }

    /// The names `Model.builtin` accepts.
    #[staticmethod]
    fn builtin_names() -> Vec<&'static str> {
        builtin::MODELS.iter().map(|(n, _)| *n).collect()
    }

    /// The model's `name`.
    #[getter]
    fn name(&self) -> String {
        self.model.name.clone()
    }

    /// Where the model came from: its path, `<built-in model>` or
    /// `<json text>`.
    #[getter]
    fn source(&self) -> String {
        self.label()
    }

    /// SHA-256 of the JSON text the model was read from (the `--json`
    /// documents' `model_sha256`).
    #[getter]
    fn sha256(&self) -> String {
        self.sha256.clone()
    }

    /// The model as pretty JSON: a valid model file.
    fn to_json(&self) -> String {
        self.model.to_json()
    }

    /// A new model with numbers changed: `{"beams[blade].section.height":
    /// 1.2e-3, "young": 130e9, ...}`, keys as `sweep --param` names them (a
    /// JSON path with `[index]` or `[id]`, a short name of `calibrate
    /// --param`, or `load_scale:ID[,ID...]`; a key ending in `+` adds the
    /// value to the model's number), values SI as in the model file. The
    /// new model is validated like a model file.
    fn with_params(&self, py: Python<'_>, params: &Bound<'_, PyDict>) -> PyResult<PyModel> {
        let mut named = Vec::with_capacity(params.len());
        for (k, v) in params.iter() {
            named.push((k.extract::<String>()?, v.extract::<f64>()?));
        }
        let model = Arc::clone(&self.model);
        let source = self.source.clone();
        compute(py, move || {
            let json = serde_json::to_value(&*model).expect("models serialize");
            let resolved = param::at_values(&model, &json, &named).map_err(|e| {
                // The command line names its flag (`--param: …`), this
                // the argument.
                Failure::Input(format!("params: {}", crate::errors::one_line(&e)))
            })?;
            let values: Vec<f64> = named.iter().map(|(_, v)| *v).collect();
            let changed = param::apply(&json, &resolved, &values).map_err(|e| {
                Failure::Input(format!("{source}: {}", crate::errors::one_line(&e)))
            })?;
            let text = changed.to_json();
            Ok(PyModel {
                sha256: sha256_hex(text.as_bytes()),
                model: Arc::new(changed),
                source,
            })
        })?
        .warned(py)
    }

    /// What each coordinate of q is, in order (`beam `blade` node 3 (s =
    /// 9.3750 mm) r'x`, `rigid body `slot` rotation`, ...). Beam nodes have
    /// [rx, ry, r'x, r'y] [m, m, –, –], rigid bodies [x, y, θ] [m, m,
    /// rad], point masses [x, y] [m].
    fn coordinates(&self, py: Python<'_>) -> PyResult<Vec<String>> {
        let model = Arc::clone(&self.model);
        compute(py, move || {
            let system = System::new(&model);
            Ok((0..system.ndof()).map(|i| system.dof_label(i)).collect())
        })
    }

    /// The mass matrix M [kg, kg m, kg m²], the tangent stiffness K [N/m,
    /// ...] and the constraint Jacobian C_q of the linearized system, as a
    /// dict {"M", "K", "C_q"}: scipy.sparse CSR matrices (format="scipy")
    /// or (data, indices, indptr, shape) tuples (format="arrays"). At the
    /// reference configuration, or with prestress=True at the static
    /// equilibrium under the loads × load_scale (and gravity), where K
    /// includes the geometric, load and constraint-force (∂(C_qᵀλ)/∂q)
    /// terms. The modes solve K φ = ω² M φ on C_q φ = 0.
    #[pyo3(signature = (prestress = false, format = "scipy", load_scale = 1.0))]
    fn matrices<'py>(
        &self,
        py: Python<'py>,
        prestress: bool,
        format: &str,
        load_scale: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let format = choice("format", format, &["scipy", "arrays"])?;
        let load_scale = finite("load_scale", load_scale)?;
        let model = Arc::clone(&self.model);
        let label = self.label();
        let m = compute(py, move || {
            let system = System::new(&model);
            let eq = match prestress {
                true => Some(equilibrium(&label, &system, load_scale)?),
                false => None,
            };
            let at = match &eq {
                Some(eq) => eq.linearization(),
                None => system.reference(),
            };
            Ok(matrices::assemble(&system, &at))
        })?;
        m.to_python(py, format == "scipy")
    }

    /// Frequencies and mode shapes (the command line's `modal`): `modes`
    /// modes [count] including the zero-frequency ones, linearized at the
    /// reference configuration or, with prestress=True, at the static
    /// equilibrium under the loads × load_scale [–] and gravity; solver
    /// "auto" (dense up to 300 free coordinates, sparse shift-invert
    /// above), "dense" or "sparse". Raises ModelError for a bad argument,
    /// AnalysisError when the analysis fails.
    #[pyo3(signature = (modes = 12, prestress = false, solver = "auto", load_scale = 1.0))]
    fn modal(
        &self,
        py: Python<'_>,
        modes: i64,
        prestress: bool,
        solver: &str,
        load_scale: f64,
    ) -> PyResult<crate::modal::PyModalResult> {
        crate::modal::run(self, py, modes, prestress, solver, load_scale)
    }

    /// The model as a reduced flexible body (the command line's
    /// `reduce`): `interface` a list of (beam id, arc length [m]) points,
    /// `modes` component modes, `method` "craig-bampton" or
    /// "free-interface", at the static equilibrium with prestress=True
    /// (loads × load_scale), ground supports removed unless keep_supports.
    #[pyo3(signature = (interface, modes = 8, method = "craig-bampton", prestress = false, keep_supports = false, load_scale = 1.0))]
    #[allow(clippy::too_many_arguments)]
    fn reduce(
        &self,
        py: Python<'_>,
        interface: Vec<(String, f64)>,
        modes: i64,
        method: &str,
        prestress: bool,
        keep_supports: bool,
        load_scale: f64,
    ) -> PyResult<crate::reduce::PyReducedBody> {
        crate::reduce::run(
            self,
            py,
            interface,
            modes,
            method,
            prestress,
            keep_supports,
            load_scale,
        )
    }

    /// The paper's time-domain test (the command line's `impulse`): the
    /// model's half-sine loads (the hammer; `amplitude` [N] and `duration`
    /// [s] override them) excite it, generalized-α integrates `end_time`
    /// [s] in steps of `step` [s] with spectral radius `spectral_radius`
    /// [–], the sensor `sensor` (default: the model's first) is recorded at
    /// `sample_rate` [Hz] (0: every step), and its spectrum (`window`:
    /// hann, rect, blackman, flattop) gives the peaks.
    #[pyo3(signature = (amplitude = None, duration = None, end_time = 0.1, step = 1e-6, spectral_radius = 0.9, sample_rate = 51200.0, sensor = None, window = "hann", from_reference = false))]
    #[allow(clippy::too_many_arguments)]
    fn impulse(
        &self,
        py: Python<'_>,
        amplitude: Option<f64>,
        duration: Option<f64>,
        end_time: f64,
        step: f64,
        spectral_radius: f64,
        sample_rate: f64,
        sensor: Option<&str>,
        window: &str,
        from_reference: bool,
    ) -> PyResult<crate::impulse::PyImpulseResult> {
        let e = crate::impulse::Experiment {
            amplitude,
            duration,
            end_time,
            step,
            spectral_radius,
            sample_rate,
            sensor,
            window,
            from_reference,
        };
        crate::impulse::run(self, py, e)
    }

    /// The main job (the command line's `identify`): the modal analysis,
    /// the impulse experiment (its keyword arguments as `impulse`'s:
    /// `amplitude` [N], `duration` [s], `end_time` [s], `step` [s],
    /// `spectral_radius` [–], `sample_rate` [Hz], `sensor`, `window`) and
    /// their first bending frequencies beside the experiment's (the
    /// paper's Table 3 for the paper's model). The experiment is the fitted
    /// mode of the `measured` hammer records (files as for `frf_files`,
    /// with `measured_window` and the fit band `measured_band` (LO, HI)
    /// [Hz]) nearest the first bending frequency, of those that are a
    /// peak of the fitted spectrum, else the model's `reference`; `calibrate` fits the first beam's equivalent height to
    /// it.
    #[pyo3(signature = (amplitude = None, duration = None, end_time = 0.1, step = 1e-6, spectral_radius = 0.9, sample_rate = 51200.0, sensor = None, window = "hann", from_reference = false, calibrate = false, measured = None, measured_window = "rect", measured_band = None))]
    #[allow(clippy::too_many_arguments)]
    fn identify(
        &self,
        py: Python<'_>,
        amplitude: Option<f64>,
        duration: Option<f64>,
        end_time: f64,
        step: f64,
        spectral_radius: f64,
        sample_rate: f64,
        sensor: Option<&str>,
        window: &str,
        from_reference: bool,
        calibrate: bool,
        measured: Option<Vec<PathBuf>>,
        measured_window: &str,
        measured_band: Option<(f64, f64)>,
    ) -> PyResult<crate::identify::PyIdentifyResult> {
        let r = crate::identify::Request {
            experiment: crate::impulse::Experiment {
                amplitude,
                duration,
                end_time,
                step,
                spectral_radius,
                sample_rate,
                sensor,
                window,
                from_reference,
            },
            calibrate,
            measured,
            measured_window,
            measured_band,
        };
        crate::identify::run(self, py, r)
    }

    /// One self-contained HTML file (the command line's `report`) written
    /// to `out`: the assembly and its animated modes (`prestress`: also at
    /// the static equilibrium under the loads, beside them); for a model
    /// with a half-sine or step load everything `identify` computes, its
    /// keyword arguments as `identify`'s; the switch-off when the model
    /// releases something. Other models refuse `calibrate` and `measured`.
    #[pyo3(signature = (out = PathBuf::from("report.html"), prestress = false, amplitude = None, duration = None, end_time = 0.1, step = 1e-6, spectral_radius = 0.9, sample_rate = 51200.0, sensor = None, window = "hann", from_reference = false, calibrate = false, measured = None, measured_window = "rect", measured_band = None))]
    #[allow(clippy::too_many_arguments)]
    fn report(
        &self,
        py: Python<'_>,
        out: PathBuf,
        prestress: bool,
        amplitude: Option<f64>,
        duration: Option<f64>,
        end_time: f64,
        step: f64,
        spectral_radius: f64,
        sample_rate: f64,
        sensor: Option<&str>,
        window: &str,
        from_reference: bool,
        calibrate: bool,
        measured: Option<Vec<PathBuf>>,
        measured_window: &str,
        measured_band: Option<(f64, f64)>,
    ) -> PyResult<()> {
        let r = crate::identify::Request {
            experiment: crate::impulse::Experiment {
                amplitude,
                duration,
                end_time,
                step,
                spectral_radius,
                sample_rate,
                sensor,
                window,
                from_reference,
            },
            calibrate,
            measured,
            measured_window,
            measured_band,
        };
        crate::report::run(self, py, out, prestress, r)
    }

    /// The static equilibrium under the loads × load_scale [–] (their values
    /// at t = 0) and gravity (the command line's `static`). Raises
    /// AnalysisError when there is none (no support, a mechanism, a loss of
    /// stability on the load path).
    #[pyo3(signature = (load_scale = 1.0))]
    fn r#static(
        &self,
        py: Python<'_>,
        load_scale: f64,
    ) -> PyResult<crate::statics::PyStaticResult> {
        crate::statics::run(self, py, load_scale)
    }

    /// The mesh convergence of the first `modes` bending frequencies (the
    /// command line's `convergence`): every beam meshed with 2, 4, 8, …
    /// elements up to `max_elements`, the errors against Euler–Bernoulli
    /// for a single free beam, else against the finest mesh.
    #[pyo3(signature = (max_elements = 64, modes = 3))]
    fn convergence(
        &self,
        py: Python<'_>,
        max_elements: i64,
        modes: i64,
    ) -> PyResult<crate::convergence::PyConvergenceResult> {
        crate::convergence::run(self, py, max_elements, modes)
    }

    /// Fits parameters to measured frequencies (the command line's
    /// `calibrate`): `target_hz` [Hz] one frequency or several (default:
    /// the model's `reference.first_bending_hz`), `params` a name, names,
    /// or {name: (lower, upper) [SI] or None} (default "height"; names as
    /// `calibrate --param`), the targets' modes `mode` (1-based among
    /// `mode_kind`: bending, axial, spring; default 1, 2, …), `keep_mass`
    /// (density follows the section), `prestress` (fit the modes at the
    /// static equilibrium under the loads and gravity; implied by a load's
    /// force, `ID.force_x` or `ID.force_y`, among `params`), `tolerance` [Hz] (default 1e-10 ×
    /// target, 1e-3 Hz by the impulse method), `max_evaluations`. Each
    /// candidate is evaluated by `method` "eigen" (the eigenproblem) or
    /// "impulse" (the experiment of `Model.impulse` with the keyword
    /// arguments from `amplitude` to `window`, its first bending peak; one
    /// parameter, one target). `target_from`: the path of an `frf --json`
    /// document whose `peaks` are the targets (in order of frequency, as
    /// many as `mode` lists, or all), instead of `target_hz`.
    ///
    /// Calibration to a transient (`calibrate --quantity` / `--trajectory`;
    /// returns a `TransientCalibrationResult`): `quantity`
    /// "time_to_distance_s" with `target` [s] fits one parameter so that
    /// the switch-off's tracked point travels its distance in that time
    /// (Brent); `trajectory`, a CSV file's path or (t, x, y) sequences [s,
    /// m, m] of the tracked point, fits one or several (least squares,
    /// each with its standard error). `params` must name them (SI
    /// bounds); `balance` "SPRING:CONTACT" ties that spring's preload to
    /// the ON-state balance; `tolerance` is then in s. Every run is at a
    /// fixed 1 µs step; the impulse keywords do not apply.
    #[pyo3(signature = (target_hz = None, params = None, mode_kind = "bending", mode = None, keep_mass = false, prestress = false, tolerance = None, max_evaluations = 60, method = "eigen", amplitude = None, duration = None, end_time = 0.1, step = 1e-6, spectral_radius = 0.9, sample_rate = 51200.0, sensor = None, window = "hann", from_reference = false, target_from = None, quantity = None, target = None, trajectory = None, balance = None))]
    #[allow(clippy::too_many_arguments)]
    fn calibrate(
        &self,
        py: Python<'_>,
        target_hz: Option<&Bound<'_, PyAny>>,
        params: Option<&Bound<'_, PyAny>>,
        mode_kind: &str,
        mode: Option<Vec<i64>>,
        keep_mass: bool,
        prestress: bool,
        tolerance: Option<f64>,
        max_evaluations: i64,
        method: &str,
        amplitude: Option<f64>,
        duration: Option<f64>,
        end_time: f64,
        step: f64,
        spectral_radius: f64,
        sample_rate: f64,
        sensor: Option<&str>,
        window: &str,
        from_reference: bool,
        target_from: Option<PathBuf>,
        quantity: Option<String>,
        target: Option<f64>,
        trajectory: Option<&Bound<'_, PyAny>>,
        balance: Option<String>,
    ) -> PyResult<Py<PyAny>> {
        if quantity.is_some() || trajectory.is_some() {
            if let Some(t) = target_hz {
                return Err(Failure::argument(
                    "target_hz",
                    t,
                    "a transient fit takes `target` [s] (with `quantity`) or a `trajectory`",
                )
                .into());
            }
            let r = crate::calibrate_transient::Request {
                quantity,
                target,
                trajectory,
                params,
                balance,
                tolerance,
                max_evaluations,
            };
            let result = crate::calibrate_transient::run(self, py, r)?;
            return Ok(Py::new(py, result)?.into_any());
        }
        for (name, given) in [("target", target.is_some()), ("balance", balance.is_some())] {
            if given {
                return Err(Failure::argument(
                    name,
                    "given",
                    "belongs to a transient fit: give `quantity` or `trajectory` too",
                )
                .into());
            }
        }
        let experiment = crate::impulse::Experiment {
            amplitude,
            duration,
            end_time,
            step,
            spectral_radius,
            sample_rate,
            sensor,
            window,
            from_reference,
        };
        let r = crate::calibrate::Request {
            target_hz,
            params,
            mode_kind,
            mode,
            keep_mass,
            prestress,
            tolerance,
            max_evaluations,
            method,
            experiment,
            target_from,
        };
        let result = crate::calibrate::run(self, py, r)?;
        Ok(Py::new(py, result)?.into_any())
    }

    /// The paper's switch-off (the command line's `switch-off`): the
    /// pre-stressed ON equilibrium, the released loads, `end_time` [s] of
    /// transient in steps of `step` [s]; the time for `point` ("BEAM:S"
    /// with S [m], or "BODY"; default node 0 of the first beam) to travel
    /// `distance` [m] along `direction` (dx, dy), sampled at `sample_rate`
    /// [Hz]; `compare_rigid` runs the model with rigid beams beside it,
    /// `no_step_check` skips the run at half the step; `fig10` adds the
    /// paper's Fig. 10 study (`SwitchOffResult.fig10`, predictions).
    #[pyo3(signature = (end_time = 3e-3, step = 1e-6, distance = 2e-3, direction = (1.0, 0.0), point = None, sample_rate = 67200.0, compare_rigid = false, no_step_check = false, fig10 = false))]
    #[allow(clippy::too_many_arguments)]
    fn switch_off(
        &self,
        py: Python<'_>,
        end_time: f64,
        step: f64,
        distance: f64,
        direction: (f64, f64),
        point: Option<&str>,
        sample_rate: f64,
        compare_rigid: bool,
        no_step_check: bool,
        fig10: bool,
    ) -> PyResult<crate::switch_off::PySwitchOffResult> {
        let r = crate::switch_off::Request {
            end_time,
            step,
            distance,
            direction,
            point,
            sample_rate,
            compare_rigid,
            no_step_check,
            fig10,
        };
        crate::switch_off::run(self, py, r)
    }

    /// A general time integration (the command line's `transient`):
    /// generalized-α with spectral radius `spectral_radius` [–] over
    /// `end_time` [s] in steps of `step` [s] (shortened at contact onsets),
    /// from rest at the static equilibrium under the loads at t = 0⁻
    /// (constant loads, preloads, gravity; released supports let go; the
    /// reference when it balances them) or, with `from_reference`, at the
    /// reference; the sensors sampled at `sample_rate` [Hz] (0: every step);
    /// `rigid_beams` models every beam as a rigid body.
    #[pyo3(signature = (end_time = 0.01, step = 1e-6, spectral_radius = 0.9, from_reference = false, sample_rate = 51200.0, rigid_beams = false))]
    #[allow(clippy::too_many_arguments)]
    fn transient(
        &self,
        py: Python<'_>,
        end_time: f64,
        step: f64,
        spectral_radius: f64,
        from_reference: bool,
        sample_rate: f64,
        rigid_beams: bool,
    ) -> PyResult<crate::transient::PyTransientResult> {
        let r = ancf::commands::transient::TransientRequest {
            end_time,
            step,
            spectral_radius,
            start: ancf::analysis::statics::start::Start::from_reference(from_reference),
            sample_rate,
            rigid_beams,
        };
        crate::transient::run(self, py, r)
    }

    /// Pickles as its JSON (`to_json()`, every number exact), its source
    /// and its SHA-256; unpickling raises no warnings (given when read).
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, State)> {
        let m = slf.get();
        let source = match &m.source {
            Source::File(path) => Some(path.clone()),
            Source::BuiltIn => None,
        };
        let state = (m.model.to_json(), source, m.sha256.clone());
        Ok((slf.get_type().getattr("_from_state")?, state))
    }

    /// The model pickled by `__reduce__`.
    #[classmethod]
    fn _from_state(
        _cls: &Bound<'_, pyo3::types::PyType>,
        py: Python<'_>,
        text: String,
        source: Option<PathBuf>,
        sha256: String,
    ) -> PyResult<PyModel> {
        let source = source.map_or(Source::BuiltIn, Source::File);
        let model = compute(py, move || PyModel::parse(&text, source))?;
        Ok(PyModel { sha256, ..model })
    }

    /// `<ancf_modal.Model "name" from SOURCE>`, then one `warning: …` line
    /// per unit warning of the model.
    fn __repr__(&self) -> String {
        let head = format!(
            "<ancf_modal.Model {:?} from {}>",
            self.model.name,
            self.label()
        );
        crate::with_warnings(head, &self.unit_warnings())
            .trim_end()
            .to_string()
    }
}
