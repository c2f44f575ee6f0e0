//! `calibrate`: model parameters (section height and width [m], Young's
//! modulus [Pa], density [kg/m³], masses [kg], inertias [kg m²],
//! stiffnesses [N/m, N m/rad]) fitted so that chosen modes reach measured
//! frequencies [Hz], the paper's "equivalent geometry"
//! ([`crate::analysis::calibrate`]). Each candidate is evaluated by the
//! eigenproblem at the reference (analytic sensitivities: several
//! parameters and targets), or by the impulse experiment and its FFT (the
//! first bending mode, one parameter; about a second per evaluation).

use super::impulse::ImpulseRequest;
use super::{CommandError, ModelInput, Run};
use crate::analysis::calibrate::{
    calibrate, calibrate_with, sweep, CalibrationError, CalibrationRequest, CalibrationResult,
    CalibrationSettings, EigenFrequencies, ImpulseFrequency, ModeSelection, ParameterSet,
    ParameterSpec,
};
use crate::analysis::statics::start::reference_balances;
use crate::analysis::ModeKind;
use crate::model::path::{available_names, PathError};
use crate::output::calibrate_report::{calibrate_table, calibration_plot};
use crate::output::plot::{calibration_figure, render, Figure, Format, PlotSize};
use crate::results::CalibrationOutput;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The parameter fitted when the request names none: the section height
/// (of the model's one beam; several beams must be named).
pub const DEFAULT_PARAMETER: &str = "height";

/// Default stopping tolerance of the impulse method [Hz]: well inside the
/// 0.01 Hz acceptance, and above the resolution of the FFT peak
/// interpolation so the bracketing does not chase its noise.
pub const IMPULSE_TOLERANCE_HZ: f64 = 1e-3;

/// The kind of the modes the targets refer to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TargetKind {
    Bending,
    Axial,
    Spring,
}

impl From<TargetKind> for ModeKind {
    fn from(k: TargetKind) -> Self {
        match k {
            TargetKind::Bending => ModeKind::Bending,
            TargetKind::Axial => ModeKind::Axial,
            TargetKind::Spring => ModeKind::Spring,
        }
    }
}

/// How each candidate parameter value is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The eigenproblem at the reference (analytic sensitivities).
    Eigen,
    /// The impulse experiment and its FFT (first bending, one parameter).
    Impulse,
}

/// What `calibrate` fits, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrateRequest {
    /// Measured frequencies [Hz], one per mode; empty: those of
    /// `target_from`, else the model's `reference.first_bending_hz`.
    pub targets_hz: Vec<f64>,
    /// An `frf` document (JSON) whose `peaks` are the targets: in order of
    /// frequency, as many as `modes` lists (all when it lists none).
    /// Not with `targets_hz`.
    pub target_from: Option<PathBuf>,
    /// The parameters, optionally with bounds [SI]; empty:
    /// [`DEFAULT_PARAMETER`].
    pub params: Vec<ParameterSpec>,
    /// Keep each beam's mass while its section changes (the density
    /// follows).
    pub keep_mass: bool,
    /// Kind of the modes the targets refer to.
    pub mode_kind: TargetKind,
    /// Mode numbers (1-based among the modes of `mode_kind`), one per
    /// target; empty: 1, 2, ….
    pub modes: Vec<usize>,
    /// How each candidate is evaluated.
    pub method: Method,
    /// Stop when every frequency is this close to its target [Hz] (> 0);
    /// `None`: 1e-10 × target, [`IMPULSE_TOLERANCE_HZ`] with the impulse
    /// method.
    pub tolerance: Option<f64>,
    /// Most model evaluations (2 to 10000).
    pub max_evaluations: usize,
    /// The experiment of the impulse method.
    pub experiment: ImpulseRequest,
    /// Fit the eigen method's modes at the static equilibrium under the
    /// loads and gravity (pre-stressed) instead of the reference; implied
    /// by a load's force among the parameters. (The impulse method strikes
    /// that equilibrium unless its experiment starts at the reference.)
    pub prestress: bool,
}

impl Default for CalibrateRequest {
    fn default() -> Self {
        CalibrateRequest {
            targets_hz: Vec::new(),
            target_from: None,
            params: Vec::new(),
            keep_mass: false,
            mode_kind: TargetKind::Bending,
            modes: Vec::new(),
            method: Method::Eigen,
            tolerance: None,
            max_evaluations: CalibrationSettings::default().max_evaluations,
            experiment: ImpulseRequest::default(),
            prestress: false,
        }
    }
}

/// `calibrate`'s output: the fit, what it was asked, and the document.
#[derive(Debug)]
pub struct CalibrateRun {
    /// The model calibrated.
    pub model: Arc<crate::model::ValidModel>,
    /// The fit as the library took it (defaults filled in).
    pub request: CalibrationRequest,
    /// The numerical settings it ran with.
    pub settings: CalibrationSettings,
    /// The fitted parameters and model, the evaluations.
    pub result: CalibrationResult,
    /// The document with the run's warnings.
    pub document: Run<CalibrationOutput>,
}

/// Checks the request's own ranges (named as the request names them).
fn check(request: &CalibrateRequest) -> Result<(), CommandError> {
    if let Some(&n) = request.modes.iter().find(|&&n| n < 1) {
        return Err(CommandError::argument(
            "mode",
            n,
            "must be a whole number ≥ 1",
        ));
    }
    if let Some(t) = request.tolerance {
        if !(t.is_finite() && t > 0.0) {
            return Err(CommandError::argument(
                "tolerance",
                t,
                "must be a number > 0",
            ));
        }
    }
    if !(2..=10_000).contains(&request.max_evaluations) {
        return Err(CommandError::argument(
            "max_evaluations",
            request.max_evaluations,
            "must be a whole number from 2 to 10000",
        ));
    }
    Ok(())
}

/// Runs `calibrate` on `input`.
pub fn run(input: &ModelInput, request: &CalibrateRequest) -> Result<CalibrateRun, CommandError> {
    check(request)?;
    let model = &input.model;
    let fail = |e| CommandError::calibration(input.label(), e);
    let targets_hz = match (
        &request.targets_hz[..],
        &request.target_from,
        &model.reference,
    ) {
        ([], Some(file), _) => targets_from(file, request.modes.len())?,
        ([], None, Some(r)) => vec![r.first_bending_hz],
        ([], None, None) => return Err(fail(CalibrationError::NoTargets)),
        (_, Some(file), _) => {
            return Err(CommandError::argument(
                "target_from",
                file.display(),
                "takes the targets from a file: not with targets given",
            ))
        }
        (given, None, _) => given.to_vec(),
    };
    let parameters = match request.params.is_empty() {
        true => vec![ParameterSpec::named(DEFAULT_PARAMETER)],
        false => request.params.clone(),
    };
    let fit = CalibrationRequest {
        parameters,
        targets_hz,
        modes: ModeSelection {
            kind: request.mode_kind.into(),
            numbers: request.modes.clone(),
        },
        keep_mass: request.keep_mass,
        prestress: request.prestress,
    };
    let impulse = request.method == Method::Impulse;
    let settings = CalibrationSettings {
        tolerance_hz: request
            .tolerance
            .or(impulse.then_some(IMPULSE_TOLERANCE_HZ)),
        max_evaluations: request.max_evaluations,
        ..CalibrationSettings::default()
    };
    let result = match request.method {
        Method::Eigen => calibrate(model, &fit, &settings)
            .map_err(|e| fail(with_prestress_hint(model, &fit, e)))?,
        Method::Impulse => {
            request.experiment.check()?;
            let eval =
                ImpulseFrequency::new(&fit.modes, request.experiment.settings()).map_err(fail)?;
            calibrate_with(model, &fit, &settings, &eval, &[1]).map_err(fail)?
        }
    };
    let output = CalibrationOutput::new(&model.name, &result);
    let own = unstressed_warning(model, &result);
    Ok(CalibrateRun {
        model: model.clone(),
        request: fit,
        settings,
        result,
        document: Run::of(input, output).warn(input, own),
    })
}

/// `e` with the pre-stress named when an unreachable target, or a missing
/// mode, was sought among the unstressed modes of a pre-stressed model (the fit was not
/// asked to be pre-stressed, and the reference does not balance the
/// loads).
fn with_prestress_hint(
    model: &crate::model::ValidModel,
    fit: &CalibrationRequest,
    mut e: CalibrationError,
) -> CalibrationError {
    if let CalibrationError::Unreachable {
        unstressed_of_prestressed,
        ..
    }
    | CalibrationError::ModeNotFound {
        unstressed_of_prestressed,
        ..
    } = &mut e
    {
        // A pre-stressed fit asked for, or implied by a load's force among
        // the parameters, sought the pre-stressed modes.
        let asked = crate::analysis::calibrate::params::ParameterSet::resolve(
            model,
            &fit.parameters,
            fit.keep_mass,
        )
        .map_or(fit.prestress, |set| fit.prestressed(&set));
        // Loads or gravity carried by the joints stress a model whose
        // reference balances them too (a pendulum: its unstressed mode is a
        // free rotation at 0 Hz).
        let system = crate::System::new(model);
        *unstressed_of_prestressed = !asked
            && (crate::analysis::statics::start::loads_act_at_start(&system)
                || !reference_balances(&system));
    }
    e
}

/// The warning of a fit to the unstressed modes of a model whose
/// reference does not balance its loads (a pre-stressed model).
fn unstressed_warning(
    model: &crate::model::ValidModel,
    result: &CalibrationResult,
) -> Option<String> {
    let system = crate::System::new(model);
    (!result.prestressed && !reference_balances(&system)).then(|| {
        String::from(
            "the model is pre-stressed (its reference does not balance its loads, preloads and gravity), and the fit is to the unstressed modes at the reference: the pre-stressed fit (prestress) fits the modes of the static equilibrium, as modal's pre-stressed analysis computes them",
        )
    })
}

impl CalibrateRun {
    /// The command line's table.
    pub fn text(&self) -> String {
        calibrate_table(&self.model.name, &self.result)
    }

    /// The calibrated model as a model file's text (`--out`).
    pub fn fitted_json(&self) -> String {
        self.result.fitted_model.to_json() + "\n"
    }

    /// The figure of the fit (`--plot`) in `format`: the first target's
    /// frequency over the first parameter about the iterates (padded), the
    /// other parameters at their fitted values. The curve is always the
    /// eigenvalue's (cheap); with the impulse method the iterates are the
    /// experiment's, which agree with it to ~1e-6.
    pub fn plot(&self, format: Format) -> Result<Vec<u8>, CommandError> {
        let fail = |e| CommandError::calibration(self.model.name.clone(), e);
        let request = &self.request;
        let set = ParameterSet::resolve(&self.model, &request.parameters, request.keep_mass)
            .map_err(fail)?;
        let eval = EigenFrequencies::new(
            &self.model,
            &request.modes,
            request.targets_hz.len(),
            self.settings.modal,
            self.result.prestressed && self.result.method == "eigen",
        )
        .map_err(fail)?;
        let result = &self.result;
        let fitted: Vec<f64> = result.parameters.iter().map(|p| p.fitted).collect();
        let xs = result.history.iter().map(|h| h.parameters[0]);
        let (lo, hi) = xs.fold((fitted[0], fitted[0]), |(a, b), x| (a.min(x), b.max(x)));
        let p = &set.params[0];
        let pad = 0.15 * (hi - lo).max(0.02 * fitted[0]);
        let (lo, hi) = ((lo - pad).max(p.lower), (hi + pad).min(p.upper));
        const POINTS: usize = 25;
        let values: Vec<f64> = (0..POINTS)
            .map(|k| lo + (hi - lo) * k as f64 / (POINTS - 1) as f64)
            .collect();
        let data = sweep(&set, &eval, &fitted, 0, &values);
        let figure = calibration_figure(&calibration_plot(&self.model.name, result, data));
        Ok(render(&Figure::from(figure), format, PlotSize::default())?)
    }

    /// Draws the fit to `path` (.svg or .png), as `--plot`.
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        let bytes = self.plot(Format::from_path(path)?)?;
        crate::output::files::write_atomic(path, &bytes)?;
        Ok(())
    }
}

/// The first beam's height fitted by the eigenproblem so that the first
/// bending frequency is `target_hz` [Hz] (`identify --calibrate`).
pub fn equivalent_height(
    model: &crate::model::ValidModel,
    target_hz: f64,
) -> Result<CalibrationResult, CalibrationError> {
    let beam = model
        .beams
        .first()
        .ok_or(PathError::UnknownShortName {
            name: String::from(DEFAULT_PARAMETER),
            available: available_names(model),
        })
        .map_err(CalibrationError::from)?;
    let request = CalibrationRequest {
        parameters: vec![ParameterSpec::named(format!("{}.height", beam.id))],
        targets_hz: vec![target_hz],
        modes: ModeSelection::default(),
        keep_mass: false,
        prestress: false,
    };
    calibrate(model, &request, &CalibrationSettings::default())
}

/// Why the targets cannot be taken from an `frf` document.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TargetsFromError {
    #[error("not a JSON document: {0}")]
    NotJson(String),
    #[error("no `peaks` array (write it with `ancf-modal frf --json`)")]
    NoPeaks,
    #[error("peaks[{index}].frequency_hz is not a positive number")]
    NotAFrequency { index: usize },
    #[error("the frf result holds no peak to calibrate to")]
    Empty,
    #[error("{found} peak(s), but {wanted} modes are to be fitted")]
    TooFew { found: usize, wanted: usize },
}

/// The frequencies [Hz] of the `peaks` of the `frf` document `file`,
/// ascending; the first `count` of them (all when `count` is 0).
pub fn targets_from(file: &Path, count: usize) -> Result<Vec<f64>, CommandError> {
    let text = std::fs::read_to_string(file).map_err(|io| CommandError::ReadFile {
        file: file.to_path_buf(),
        io,
    })?;
    let fail = |source| CommandError::TargetsFrom {
        file: file.to_path_buf(),
        source,
    };
    let doc: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| fail(TargetsFromError::NotJson(e.to_string())))?;
    let peaks = doc["peaks"]
        .as_array()
        .ok_or(fail(TargetsFromError::NoPeaks))?;
    let mut f = Vec::with_capacity(peaks.len());
    for (index, p) in peaks.iter().enumerate() {
        match p["frequency_hz"].as_f64() {
            Some(v) if v.is_finite() && v > 0.0 => f.push(v),
            _ => return Err(fail(TargetsFromError::NotAFrequency { index })),
        }
    }
    if f.is_empty() {
        return Err(fail(TargetsFromError::Empty));
    }
    f.sort_by(f64::total_cmp);
    if count > 0 {
        if f.len() < count {
            return Err(fail(TargetsFromError::TooFew {
                found: f.len(),
                wanted: count,
            }));
        }
        f.truncate(count);
    }
    Ok(f)
}
