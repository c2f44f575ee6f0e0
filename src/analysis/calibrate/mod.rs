//! Equivalent-geometry calibration: tune model parameters until the model's
//! natural frequencies [SI: Hz] match measured ones.
//!
//! The paper gives its blade an "equivalent geometry" so that the model has
//! the measured first bending frequency (4600 Hz); this does that for any
//! fittable parameter (see [`params`]) and one or several targets:
//!
//! - one parameter, one target: a bracketing root finder (Brent, [`brent`])
//!   on f(p) − f_target;
//! - otherwise damped Gauss–Newton (Levenberg–Marquardt, [`crate::signal::lm`]) in ln p on
//!   relative residuals, with the analytic sensitivities of
//!   [`sensitivity`]. More parameters than targets, or a Jacobian whose
//!   relative singular values fall below
//!   [`CalibrationSettings::identifiability`], is reported as not
//!   identifiable (with the sensitivities and singular values) instead of
//!   returning one of infinitely many fits.
//!
//! Each evaluation builds a fresh [`crate::System`] from a modified clone of
//! the model; the input model is never changed and the fitted model is a new
//! one ([`CalibrationResult::fitted_model`]). The evaluator is a
//! [`FrequencyModel`]: the eigenproblem with mode tracking by MAC
//! ([`EigenFrequencies`]), or any other (e.g. a time-domain experiment).

pub mod brent;
mod error;
pub mod evaluate;
pub mod params;
pub mod sensitivity;
pub mod transient;

pub use error::CalibrationError;
pub use evaluate::{
    EigenFrequencies, Evaluation, FrequencyModel, ImpulseFrequency, ModeSelection, SingleFrequency,
};
pub use params::{ParamTarget, Parameter, ParameterSet, ParameterSpec};

use crate::analysis::{ModalSettings, ModeKind};
use crate::model::{Model, ValidModel};
use crate::signal::lm;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// What to fit and to what.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrationRequest {
    pub parameters: Vec<ParameterSpec>,
    /// Measured frequencies [SI: Hz], one per tracked mode.
    pub targets_hz: Vec<f64>,
    pub modes: ModeSelection,
    /// Keep each beam's mass when its section changes (density adjusts).
    pub keep_mass: bool,
    /// Fit the modes at the static equilibrium under the loads and gravity
    /// (pre-stressed, as `modal --prestress`) instead of the reference;
    /// implied by a load's force among the parameters.
    pub prestress: bool,
}

impl CalibrationRequest {
    /// Whether the fit is pre-stressed: asked for, or implied by a load's
    /// force among the parameters `set` (it acts only through the
    /// equilibrium).
    pub fn prestressed(&self, set: &ParameterSet) -> bool {
        self.prestress
            || set
                .params
                .iter()
                .any(|p| matches!(p.target, ParamTarget::LoadForce(..)))
    }
}

/// Numerical settings.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrationSettings {
    /// Stop when every |f − target| is below this [SI: Hz]; `None` =
    /// 1e-10 × target.
    pub tolerance_hz: Option<f64>,
    /// A fit that ends farther than this from a target (square problems)
    /// is an error [SI: Hz].
    pub accept_hz: f64,
    /// Most evaluations (eigen-solves or experiments).
    pub max_evaluations: usize,
    /// Smallest relative singular value (σ/σ_max) of the relative
    /// Jacobian ∂ln f/∂ln p for the parameters to count as identifiable;
    /// with one parameter, the smallest |∂ln f/∂ln p| that counts as an effect.
    pub identifiability: f64,
    /// Modal settings of the eigen evaluator.
    pub modal: ModalSettings,
}

impl Default for CalibrationSettings {
    fn default() -> Self {
        CalibrationSettings {
            tolerance_hz: None,
            accept_hz: 0.01,
            max_evaluations: 60,
            identifiability: 1e-6,
            modal: ModalSettings::default(),
        }
    }
}

/// The numerical method used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Algorithm {
    Brent,
    LevenbergMarquardt,
}

/// One fitted (or derived) parameter.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct FittedParameter {
    /// Its name (short name or JSON path in the model).
    pub name: String,
    /// SI unit.
    pub unit: &'static str,
    /// Value in the model [SI, `unit`].
    pub initial: f64,
    /// Fitted value [SI, `unit`].
    pub fitted: f64,
    /// Lower bound of the search [SI, `unit`].
    pub lower: f64,
    /// Upper bound of the search [SI, `unit`].
    pub upper: f64,
    /// (fitted − initial)/initial × 100; null when the initial value is 0.
    pub change_percent: Option<f64>,
}

/// (fitted − initial)/initial × 100, `None` from an initial 0.
pub fn change_percent(initial: f64, fitted: f64) -> Option<f64> {
    (initial != 0.0).then(|| 100.0 * (fitted - initial) / initial)
}

/// One evaluation of the model.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct HistoryEntry {
    /// Parameter values, in request order.
    pub parameters: Vec<f64>,
    /// Frequencies of the tracked modes [SI: Hz].
    pub frequencies_hz: Vec<f64>,
    /// Whether this point was taken as an iterate (Levenberg–Marquardt); every
    /// Brent point is.
    pub accepted: bool,
}

/// Conditioning of the relative Jacobian ∂ln f/∂ln p.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Conditioning {
    /// Singular values, descending.
    pub singular_values: Vec<f64>,
    /// σ_max/σ_min (infinite when fewer targets than parameters).
    pub condition_number: f64,
}

/// The outcome of a calibration.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct CalibrationResult {
    /// Evaluator (`eigen`, `impulse`).
    pub method: &'static str,
    /// The fitting algorithm (Brent for one parameter and target, else
    /// Levenberg–Marquardt).
    pub algorithm: Algorithm,
    /// The fitted parameters (name, SI unit, initial and fitted value, bounds).
    pub parameters: Vec<FittedParameter>,
    /// Values that follow the fitted ones (densities under `keep_mass`).
    pub derived: Vec<FittedParameter>,
    /// Whether each beam's mass was kept (density follows the section).
    pub keep_mass: bool,
    /// Whether the frequencies are those at the static equilibrium under
    /// the loads and gravity (pre-stressed), else at the reference.
    pub prestressed: bool,
    /// Kind of the target modes.
    pub mode_kind: ModeKind,
    /// 1-based numbers of the tracked modes among their kind (start) [–].
    pub mode_numbers: Vec<usize>,
    /// Target frequencies [SI: Hz].
    pub targets_hz: Vec<f64>,
    /// The modes' frequencies at the initial values [SI: Hz].
    pub initial_hz: Vec<f64>,
    /// The modes' frequencies at the fitted values [SI: Hz].
    pub achieved_hz: Vec<f64>,
    /// achieved − target [SI: Hz].
    pub residuals_hz: Vec<f64>,
    /// More targets than parameters: the fit is a least-squares compromise.
    pub least_squares: bool,
    /// Iterates after the start (Brent steps, or accepted LM steps) [–].
    pub iterations: usize,
    /// Model evaluations, the start included [–].
    pub evaluations: usize,
    /// Every evaluation: parameter values [SI] and frequencies [SI: Hz].
    pub history: Vec<HistoryEntry>,
    /// ∂fᵢ/∂ln pⱼ at the fit [SI: Hz per unit relative change], when the
    /// evaluator has sensitivities; else null.
    pub sensitivities_hz: Option<Vec<Vec<f64>>>,
    /// Conditioning of the relative sensitivities; null without them.
    pub conditioning: Option<Conditioning>,
    /// The calibrated model (a valid model file).
    #[serde(skip)]
    pub fitted_model: ValidModel,
}

/// Calibrate with the eigenproblem as evaluator.
pub fn calibrate(
    model: &ValidModel,
    request: &CalibrationRequest,
    settings: &CalibrationSettings,
) -> Result<CalibrationResult, CalibrationError> {
    check_targets(&request.targets_hz)?;
    // Resolve the names first: a bad name is reported before any solve.
    let set = ParameterSet::resolve(model, &request.parameters, request.keep_mass)?;
    let eval = EigenFrequencies::new(
        model,
        &request.modes,
        request.targets_hz.len(),
        settings.modal,
        request.prestressed(&set),
    )?;
    calibrate_with(model, request, settings, &eval, eval.numbers())
}

fn check_targets(targets: &[f64]) -> Result<(), CalibrationError> {
    if targets.is_empty() {
        return Err(CalibrationError::NoTargets);
    }
    for &t in targets {
        if !(t > 0.0 && t.is_finite()) {
            return Err(CalibrationError::TargetNotPositive { value: t });
        }
    }
    Ok(())
}

/// Calibrate with any evaluator; `mode_numbers` is reported as given.
pub fn calibrate_with(
    model: &ValidModel,
    request: &CalibrationRequest,
    settings: &CalibrationSettings,
    evaluator: &dyn FrequencyModel,
    mode_numbers: &[usize],
) -> Result<CalibrationResult, CalibrationError> {
    check_targets(&request.targets_hz)?;
    let set = ParameterSet::resolve(model, &request.parameters, request.keep_mass)?;
    let targets = &request.targets_hz;
    let mut run = Run {
        set: &set,
        evaluator,
        history: Vec::new(),
        evaluations: Vec::new(),
    };
    let p0 = set.start();
    let e0 = run.eval(&p0)?;
    let (p_fit, algorithm, iterations) = if set.len() == 1 && targets.len() == 1 {
        let p = fit_one(&mut run, &e0, targets[0], settings)?;
        let iterations = run.history.len() - 1;
        (p, Algorithm::Brent, iterations)
    } else {
        let (p, accepted) = fit_many(&mut run, &e0, targets, settings)?;
        for i in accepted.iter().copied() {
            run.history[i].accepted = true;
        }
        (p, Algorithm::LevenbergMarquardt, accepted.len() - 1)
    };
    let e_fit = run
        .evaluations
        .iter()
        .rev()
        .find(|(p, _)| *p == p_fit)
        .map(|(_, e)| e.clone())
        .expect("the fitted point was evaluated");
    let fitted_model = fitted_model(&set, &p_fit, targets, evaluator.method())?;
    let fitted_params = set
        .params
        .iter()
        .zip(&p_fit)
        .map(|(p, &v)| FittedParameter {
            name: p.name.clone(),
            unit: p.target.unit(),
            initial: p.initial,
            fitted: v,
            lower: p.lower,
            upper: p.upper,
            change_percent: change_percent(p.initial, v),
        })
        .collect();
    let sensitivities_hz = e_fit
        .sensitivities
        .as_ref()
        .map(|s| log_sensitivities(s, &p_fit));
    let conditioning = sensitivities_hz
        .as_ref()
        .map(|s| conditioning(s, e_fit.frequencies_hz.as_slice()));
    Ok(CalibrationResult {
        method: evaluator.method(),
        algorithm,
        parameters: fitted_params,
        derived: derived(&set, &fitted_model),
        keep_mass: request.keep_mass,
        prestressed: evaluator.prestressed(model),
        mode_kind: request.modes.kind,
        mode_numbers: mode_numbers.to_vec(),
        targets_hz: targets.clone(),
        initial_hz: e0.frequencies_hz.clone(),
        residuals_hz: e_fit
            .frequencies_hz
            .iter()
            .zip(targets)
            .map(|(f, t)| f - t)
            .collect(),
        achieved_hz: e_fit.frequencies_hz.clone(),
        least_squares: targets.len() > set.len(),
        iterations,
        evaluations: run.history.len(),
        history: run.history,
        sensitivities_hz,
        conditioning,
        fitted_model,
    })
}

/// Frequency of the first tracked mode as parameter `index` sweeps `values`
/// (the others at `at`), for plots. Points whose evaluation fails are left out.
pub fn sweep(
    set: &ParameterSet,
    evaluator: &dyn FrequencyModel,
    at: &[f64],
    index: usize,
    values: &[f64],
) -> (Vec<f64>, Vec<f64>) {
    let mut xs = Vec::with_capacity(values.len());
    let mut fs = Vec::with_capacity(values.len());
    for &v in values {
        let mut p = at.to_vec();
        p[index] = v;
        if let Ok(f) = set.apply(&p).and_then(|m| evaluator.frequencies(&m)) {
            xs.push(v);
            fs.push(f[0]);
        }
    }
    (xs, fs)
}

/// Bookkeeping of the evaluations of one calibration.
struct Run<'a> {
    set: &'a ParameterSet,
    evaluator: &'a dyn FrequencyModel,
    history: Vec<HistoryEntry>,
    evaluations: Vec<(Vec<f64>, Evaluation)>,
}

impl Run<'_> {
    fn eval(&mut self, p: &[f64]) -> Result<Evaluation, CalibrationError> {
        let e = self.evaluator.evaluate(&self.set.apply(p)?, self.set)?;
        self.history.push(HistoryEntry {
            parameters: p.to_vec(),
            frequencies_hz: e.frequencies_hz.clone(),
            accepted: true,
        });
        self.evaluations.push((p.to_vec(), e.clone()));
        Ok(e)
    }
}

fn tolerance(settings: &CalibrationSettings, target: f64) -> f64 {
    settings.tolerance_hz.unwrap_or(1e-10 * target)
}

/// Brent on the single parameter.
fn fit_one(
    run: &mut Run,
    e0: &Evaluation,
    target: f64,
    settings: &CalibrationSettings,
) -> Result<Vec<f64>, CalibrationError> {
    let p = run.set.params[0].clone();
    let p0 = run.history[0].parameters[0];
    let f0 = e0.frequencies_hz[0];
    let slope = e0.sensitivities.as_ref().map(|s| s[0][0]);
    if let Some(d) = slope {
        let relative = d * p0 / f0;
        if relative.abs() < settings.identifiability {
            return Err(CalibrationError::NoEffect {
                parameter: p.name.clone(),
                frequency_hz: f0,
                relative_sensitivity: relative,
            });
        }
    }
    let sample = |x: f64, e: &Evaluation| brent::Sample {
        x,
        g: e.frequencies_hz[0] - target,
        slope: e.sensitivities.as_ref().map(|s| s[0][0]),
    };
    let bs = brent::BrentSettings {
        g_tolerance: tolerance(settings, target),
        x_tolerance: 1e-14,
        max_evaluations: settings.max_evaluations,
    };
    let start = sample(p0, e0);
    let outcome = brent::solve(start, p.lower, p.upper, &bs, |x| {
        let e = run.eval(&[x])?;
        Ok::<_, CalibrationError>(sample(x, &e))
    })?;
    let best = match outcome {
        brent::BrentOutcome::Root(s) | brent::BrentOutcome::Exhausted(s) => s,
        brent::BrentOutcome::NoSignChange { lower, upper } => {
            let (fl, fu) = (lower.g + target, upper.g + target);
            if (fu - fl).abs() <= settings.identifiability * fl.abs().max(fu.abs()) {
                return Err(CalibrationError::NoEffect {
                    parameter: p.name.clone(),
                    frequency_hz: f0,
                    relative_sensitivity: 0.0,
                });
            }
            // Past the bound nearer the target, where the model can be
            // solved there: does the mode get there at all?
            let x = if (fl - target).abs() < (fu - target).abs() {
                p.lower / error::BEYOND_BOUNDS
            } else {
                p.upper * error::BEYOND_BOUNDS
            };
            let beyond = (x > 0.0 && p.lower > 0.0)
                .then(|| run.eval(&[x]).ok())
                .flatten()
                .map(|e| Box::new((x, e.frequencies_hz[0])));
            return Err(CalibrationError::Unreachable {
                parameter: p.name.clone(),
                target_hz: target,
                lower: p.lower,
                upper: p.upper,
                lower_hz: fl,
                upper_hz: fu,
                unstressed_of_prestressed: false,
                beyond,
            });
        }
    };
    if best.g.abs() > settings.accept_hz.max(tolerance(settings, target)) {
        return Err(CalibrationError::NotConverged {
            evaluations: run.history.len(),
            residual_hz: best.g,
        });
    }
    Ok(vec![best.x])
}

/// ∂fᵢ/∂ln pⱼ = pⱼ ∂fᵢ/∂pⱼ.
fn log_sensitivities(dfdp: &[Vec<f64>], p: &[f64]) -> Vec<Vec<f64>> {
    dfdp.iter()
        .map(|row| row.iter().zip(p).map(|(d, p)| d * p).collect())
        .collect()
}

/// Singular values of ∂ln f/∂ln p.
fn conditioning(dfdlnp: &[Vec<f64>], f: &[f64]) -> Conditioning {
    let m = dfdlnp.len();
    let n = dfdlnp.first().map_or(0, Vec::len);
    let j = nalgebra::DMatrix::from_fn(m, n, |i, k| dfdlnp[i][k] / f[i]);
    let mut s: Vec<f64> = j
        .svd(false, false)
        .singular_values
        .iter()
        .copied()
        .collect();
    s.sort_by(|a, b| b.total_cmp(a));
    let smax = s.first().copied().unwrap_or(0.0);
    let smin = if n > m {
        0.0
    } else {
        s.last().copied().unwrap_or(0.0)
    };
    Conditioning {
        singular_values: s,
        condition_number: if smin > 0.0 {
            smax / smin
        } else {
            f64::INFINITY
        },
    }
}

/// Levenberg–Marquardt on all parameters; returns the fit and the accepted
/// evaluations.
fn fit_many(
    run: &mut Run,
    e0: &Evaluation,
    targets: &[f64],
    settings: &CalibrationSettings,
) -> Result<(Vec<f64>, Vec<usize>), CalibrationError> {
    let dfdp = e0
        .sensitivities
        .clone()
        .ok_or(CalibrationError::NeedsSensitivities {
            method: run.evaluator.method(),
        })?;
    let p0 = run.history[0].parameters.clone();
    let names: Vec<String> = run.set.params.iter().map(|p| p.name.clone()).collect();
    let s0 = log_sensitivities(&dfdp, &p0);
    let c0 = conditioning(&s0, &e0.frequencies_hz);
    let smax = c0.singular_values.first().copied().unwrap_or(0.0);
    let weak = c0
        .singular_values
        .iter()
        .any(|s| *s <= settings.identifiability * smax);
    if names.len() > targets.len() || weak || smax == 0.0 {
        return Err(CalibrationError::NotIdentifiable {
            parameters: names,
            frequencies_hz: e0.frequencies_hz.clone(),
            sensitivities_hz: s0,
            singular_values: c0.singular_values,
        });
    }
    let tolerance_hz = targets.iter().map(|&t| tolerance(settings, t)).collect();
    let (lower, upper): (Vec<f64>, Vec<f64>) = run
        .set
        .params
        .iter()
        .map(|p| (p.lower.ln(), p.upper.ln()))
        .unzip();
    let mut problem = Frequencies {
        run,
        targets,
        tolerance_hz,
    };
    let start = (p0.clone(), e0.clone());
    let u0 = p0.iter().map(|p| p.ln()).collect();
    let lm_settings = lm::Settings {
        max_evaluations: settings.max_evaluations,
        ..LM
    };
    let out = lm::solve(&mut problem, u0, start, &lower, &upper, &lm_settings)?;
    let (best_p, best) = out.best;
    let worst = best
        .frequencies_hz
        .iter()
        .zip(targets)
        .map(|(f, t)| (f - t).abs())
        .fold(0.0, f64::max);
    let square = targets.len() == names.len();
    let failed = match out.stop {
        lm::Stop::Converged => false,
        lm::Stop::Stalled => square && worst > settings.accept_hz,
        lm::Stop::Exhausted => !square || worst > settings.accept_hz,
    };
    if failed {
        if out.stop == lm::Stop::Stalled {
            return Err(CalibrationError::NotReached {
                parameters: names.into_iter().zip(best_p.iter().copied()).collect(),
                targets_hz: targets.to_vec(),
                achieved_hz: best.frequencies_hz,
            });
        }
        return Err(CalibrationError::NotConverged {
            evaluations: out.evaluations,
            residual_hz: worst,
        });
    }
    Ok((best_p, out.accepted))
}

/// The Levenberg–Marquardt settings of a calibration: μ from 10⁻³ of the
/// largest diagonal of JᵀJ, ×10 on a rejected trial, ÷10 (down to 10⁻¹²
/// of it) on a taken step, stalled above 10¹⁶ of it, after a step below
/// 10⁻¹³ in every ln p, or a taken step that lowers |r|² by 10⁻¹² of
/// itself; the evaluation budget is set per calibration.
const LM: lm::Settings = lm::Settings {
    initial_damping: lm::Scale::Relative(1e-3),
    grow: 10.0,
    shrink: 10.0,
    damping_floor: lm::Scale::Relative(1e-12),
    damping_ceiling: 1e16,
    max_rejections: usize::MAX,
    step_tolerance: 1e-13,
    min_relative_decrease: 1e-12,
    max_evaluations: usize::MAX,
    max_iterations: usize::MAX,
};

/// The frequencies' relative misfit as a least-squares problem in u = ln p
/// (parameters stay positive, bounds are ratios, parameters of different
/// units weigh alike): rᵢ = (fᵢ − tᵢ)/tᵢ, Jᵢⱼ = pⱼ (∂fᵢ/∂pⱼ)/tᵢ from the
/// analytic sensitivities.
struct Frequencies<'r, 'a> {
    run: &'r mut Run<'a>,
    targets: &'r [f64],
    /// Converged when every |fᵢ − tᵢ| ≤ tolerance_hz[i].
    tolerance_hz: Vec<f64>,
}

impl lm::Problem for Frequencies<'_, '_> {
    type Point = (Vec<f64>, Evaluation);
    type Error = CalibrationError;

    fn evaluate(&mut self, u: &[f64]) -> Result<Self::Point, CalibrationError> {
        let p: Vec<f64> = u.iter().map(|v| v.exp()).collect();
        let e = self.run.eval(&p)?;
        Ok((p, e))
    }

    fn residuals(&self, (_, e): &Self::Point) -> DVector<f64> {
        let t = self.targets;
        DVector::from_fn(t.len(), |i, _| (e.frequencies_hz[i] - t[i]) / t[i])
    }

    fn jacobian(
        &mut self,
        _: &[f64],
        (p, e): &Self::Point,
        _: &DVector<f64>,
    ) -> Result<DMatrix<f64>, CalibrationError> {
        let dfdp = e
            .sensitivities
            .as_ref()
            .ok_or(CalibrationError::NeedsSensitivities {
                method: self.run.evaluator.method(),
            })?;
        let t = self.targets;
        Ok(DMatrix::from_fn(t.len(), p.len(), |i, k| {
            p[k] * dfdp[i][k] / t[i]
        }))
    }

    fn converged(&self, (_, e): &Self::Point) -> bool {
        e.frequencies_hz
            .iter()
            .zip(self.targets)
            .zip(&self.tolerance_hz)
            .all(|((f, t), tol)| (f - t).abs() <= *tol)
    }
}

/// Densities that `keep_mass` changed.
fn derived(set: &ParameterSet, fitted: &Model) -> Vec<FittedParameter> {
    if !set.keep_mass {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (i, (b0, b)) in set.base().beams.iter().zip(&fitted.beams).enumerate() {
        if set
            .params
            .iter()
            .any(|p| p.target.section_beam() == Some(i))
        {
            let (r0, r) = (b0.material.density, b.material.density);
            out.push(FittedParameter {
                name: format!("{}.density", b.id),
                unit: "kg/m³",
                initial: r0,
                fitted: r,
                lower: r,
                upper: r,
                change_percent: change_percent(r0, r),
            });
        }
    }
    out
}

/// The calibrated model: renamed, with the calibration in its description.
fn fitted_model(
    set: &ParameterSet,
    p: &[f64],
    targets: &[f64],
    method: &str,
) -> Result<ValidModel, CalibrationError> {
    let mut m = set.model_at(p);
    let changes: Vec<String> = set
        .params
        .iter()
        .zip(p)
        .map(|(q, v)| format!("{} {:e} -> {:e} {}", q.name, q.initial, v, q.target.unit()))
        .collect();
    let targets: Vec<String> = targets.iter().map(|t| format!("{t} Hz")).collect();
    let note = format!(
        "Calibrated by ancf-modal calibrate ({method}{}): {} to match {}.",
        if set.keep_mass {
            ", beam mass kept"
        } else {
            ""
        },
        changes.join(", "),
        targets.join(", ")
    );
    m.description = if m.description.is_empty() {
        note
    } else {
        format!("{} {note}", m.description)
    };
    if !m.name.ends_with("_calibrated") {
        m.name.push_str("_calibrated");
    }
    m.validated()
        .map_err(|source| CalibrationError::InvalidModel {
            at: set.describe(p),
            source: Box::new(source),
        })
}
