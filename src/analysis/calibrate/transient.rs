//! Calibration to a transient: model parameters fitted so that the
//! switch-off experiment ([`crate::analysis::switch_off`]: the ON state,
//! the release, the transient) reproduces a measured time [SI: s] for the
//! tracked point to travel its distance, or a measured trajectory (t, x, y)
//! [SI: s, m] of that point.
//!
//! - One parameter and a time: Brent's bracketing root finder ([`super::brent`])
//!   on t(p) − t_target, started by a Newton step from a finite-difference
//!   slope. Stops when |t − t_target| ≤ the tolerance.
//! - A trajectory: least squares over the samples, r = (x(tₖ) − xₖ,
//!   y(tₖ) − yₖ) [SI: m], the model's point interpolated linearly between
//!   its steps; Levenberg–Marquardt ([`crate::signal::lm`]) in p/p₀ with a
//!   central-difference Jacobian. Each parameter's standard error is
//!   √(s²[(JᵀJ)⁻¹]ᵢᵢ), s² = |r|²/(m − n), from the Jacobian and the
//!   residual at the fit (m samples × 2, n parameters).
//!
//! Every run integrates with a fixed step (no shorter step at contact
//! onset), so the time and the path are smooth functions of the
//! parameters. Parameters are named as `sweep` names them (a JSON path of
//! the model file, or a short name); values are SI.
//!
//! The spring's preload may be tied to the ON-state balance
//! ([`crate::analysis::moment_balance`]): with `balance`, each candidate's
//! preload is the one that keeps the contact's force of the starting
//! model's balance, so moving a load changes the spring's share of the
//! moments as the measured forces say it must.

use super::brent::{self, BrentOutcome, BrentSettings, Sample};
use super::{Algorithm, FittedParameter};
use crate::analysis::moment_balance::{balance_contact_force, balanced_preload, BalanceError};
use crate::analysis::sweep::error::{PointError, SweepError};
use crate::analysis::sweep::param::{apply, Parameter};
use crate::analysis::switch_off::{run_switch_off, Calibrated, SwitchOffSettings};
use crate::model::path::NumberPath;
use crate::model::{Model, ValidModel};
use crate::signal::lm;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// A parameter of a transient fit, as named (`loads[F_x2].at.s`), with
/// optional bounds [SI].
#[derive(Debug, Clone, PartialEq)]
pub struct TransientParameter {
    pub name: String,
    pub bounds: Option<(f64, f64)>,
}

/// A measured trajectory of the tracked point.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// What the outputs call it (the file).
    pub label: String,
    /// Sample times [SI: s], increasing, within the run.
    pub time_s: Vec<f64>,
    /// Absolute coordinates of the tracked point [SI: m].
    pub x_m: Vec<f64>,
    pub y_m: Vec<f64>,
}

/// What the fit matches.
#[derive(Debug, Clone, PartialEq)]
pub enum TransientTarget {
    /// The time to the distance [SI: s].
    TimeToDistance {
        seconds: f64,
        source: String,
    },
    Trajectory(Trajectory),
}

/// A spring's preload tied to the ON-state balance with a contact.
#[derive(Debug, Clone, PartialEq)]
pub struct Balance {
    pub spring: String,
    pub contact: String,
}

/// A transient calibration.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientFit {
    pub parameters: Vec<TransientParameter>,
    pub target: TransientTarget,
    pub balance: Option<Balance>,
    /// The experiment (its step is kept fixed).
    pub experiment: SwitchOffSettings,
    /// Stop a time fit when |t − target| ≤ this [SI: s].
    pub tolerance_s: f64,
    /// Most experiments run.
    pub max_evaluations: usize,
}

/// Why a transient calibration failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TransientFitError {
    #[error(transparent)]
    Parameter(#[from] SweepError),
    #[error("`{name}` is not a number the model holds")]
    NoValue { name: String },
    #[error("`{name}` starts at {initial:e}: give its bounds (NAME=LO:HI), the default ×/÷ 4 needs a positive value")]
    NeedsBounds { name: String, initial: f64 },
    #[error("`{name}`: bounds [{lower:e}, {upper:e}] must be finite, increasing and hold its value {initial:e}")]
    Bounds {
        name: String,
        lower: f64,
        upper: f64,
        initial: f64,
    },
    #[error("a time fit moves one parameter ({given} given); fit several to a trajectory")]
    OneParameter { given: usize },
    #[error("the target time must be positive and finite, got {value:e} s")]
    Target { value: f64 },
    #[error("the trajectory needs more samples ({samples}) than half the parameters ({parameters}) and increasing times within the run")]
    Samples { samples: usize, parameters: usize },
    #[error("{at}: {source}")]
    Point {
        at: String,
        #[source]
        source: PointError,
    },
    #[error("the balance: {0}")]
    Balance(#[from] BalanceError),
    #[error(
        "the time to distance stays {low:e} … {high:e} s between the bounds, not {target:e} s"
    )]
    Unreachable { low: f64, high: f64, target: f64 },
    #[error("the time to distance jumps over {target:e} s at {at:e} (closest {best:e} s): no parameter value within the bounds gives it")]
    Jump { at: f64, best: f64, target: f64 },
    #[error("the samples do not determine `{name}`: {} (rms residual {rms:.4e} m): a parameter without effect on the path, or samples in other units than seconds and metres", undetermined(*standard_error, *width))]
    Undetermined {
        name: String,
        standard_error: Option<f64>,
        width: f64,
        rms: f64,
    },
    #[error("the trajectory fit used its {evaluations} experiments before reaching a least-squares optimum (rms residual {rms:e} m); allow more")]
    TrajectoryExhausted { evaluations: usize, rms: f64 },
    #[error("no fit within {evaluations} experiments (best {best:e} s against {target:e} s)")]
    Exhausted {
        evaluations: usize,
        best: f64,
        target: f64,
    },
}

/// One experiment run.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct TransientEvaluation {
    /// Parameter values [SI], in request order.
    pub parameters: Vec<f64>,
    /// Time to distance [SI: s] (`None`: not reached), or the rms residual
    /// of a trajectory [SI: m].
    pub value: Option<f64>,
}

/// The tied spring's preload, initial and fitted.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct BalanceRecord {
    /// The spring whose preload is tied (its id).
    pub spring: String,
    /// The contact whose ON-state force the balance keeps (its id).
    pub contact: String,
    /// The contact force the balance keeps [SI: N].
    pub contact_force_n: f64,
    /// Preload at the start [SI: N, tension positive].
    pub initial_preload_n: f64,
    /// Preload of the fitted model [SI: N, tension positive].
    pub fitted_preload_n: f64,
}

/// The outcome.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct TransientCalibration {
    /// `time_to_distance_s` or `trajectory`.
    pub quantity: &'static str,
    pub algorithm: Algorithm,
    /// The fixed step of every run [SI: s].
    pub step_s: f64,
    /// Each parameter: initial, fitted, bounds [SI].
    pub parameters: Vec<FittedParameter>,
    /// What was fitted, to what, and how well.
    pub calibrated: Vec<Calibrated>,
    /// The spring preload tied to the ON-state balance, if any.
    pub balance: Option<BalanceRecord>,
    /// Time to distance of the starting model [SI: s] at the fixed step
    /// (`None`: not reached).
    pub initial_time_s: Option<f64>,
    /// Time to distance of the fitted model [SI: s] at the fixed step.
    pub achieved_time_s: Option<f64>,
    /// Trajectory fit: the samples (0 for a time fit).
    pub samples: usize,
    /// Trajectory fit: rms residual of the starting model [SI: m].
    pub initial_rms_m: Option<f64>,
    /// Trajectory fit: rms residual at the fit [SI: m].
    pub rms_m: Option<f64>,
    /// Every experiment run, in order.
    pub history: Vec<TransientEvaluation>,
    #[serde(skip)]
    pub fitted_model: ValidModel,
}

struct Resolved {
    params: Vec<Parameter>,
    names: Vec<String>,
    initial: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
}

fn resolve(model: &Model, specs: &[TransientParameter]) -> Result<Resolved, TransientFitError> {
    let json = serde_json::to_value(model).expect("a model serializes");
    let mut r = Resolved {
        params: Vec::new(),
        names: Vec::new(),
        initial: Vec::new(),
        lower: Vec::new(),
        upper: Vec::new(),
    };
    for spec in specs {
        let path = NumberPath::resolve(model, &json, &spec.name).map_err(SweepError::Path)?;
        let initial = path
            .number(&json)
            .ok_or_else(|| TransientFitError::NoValue {
                name: spec.name.clone(),
            })?;
        let p = Parameter::at(model, &json, &spec.name, initial)?;
        crate::analysis::sweep::param::add_distinct(&mut r.params, p)?;
        let (lower, upper) = match spec.bounds {
            Some(b) => b,
            None if initial > 0.0 => (initial / 4.0, initial * 4.0),
            None => {
                return Err(TransientFitError::NeedsBounds {
                    name: spec.name.clone(),
                    initial,
                })
            }
        };
        if !(lower.is_finite()
            && upper.is_finite()
            && lower < upper
            && (lower..=upper).contains(&initial))
        {
            return Err(TransientFitError::Bounds {
                name: spec.name.clone(),
                lower,
                upper,
                initial,
            });
        }
        r.names.push(path.to_string());
        r.initial.push(initial);
        r.lower.push(lower);
        r.upper.push(upper);
    }
    Ok(r)
}

/// The runs of one fit: how values become a model, and the experiment
/// (its ON state continued from the built-in switch-off model's when the
/// model is a design of it, as `switch-off` does).
struct Runs<'a> {
    json: serde_json::Value,
    resolved: Resolved,
    balance: Option<(&'a Balance, f64)>,
    settings: SwitchOffSettings,
    history: Vec<TransientEvaluation>,
}

impl Runs<'_> {
    fn model(&self, values: &[f64]) -> Result<ValidModel, TransientFitError> {
        let at = || {
            let v: Vec<String> = (self.resolved.names.iter().zip(values))
                .map(|(n, v)| format!("{n} = {v:e}"))
                .collect();
            v.join(", ")
        };
        let m = apply(&self.json, &self.resolved.params, values)
            .map_err(|source| TransientFitError::Point { at: at(), source })?;
        let Some((b, force)) = self.balance else {
            return Ok(m);
        };
        let preload = balanced_preload(&m, &b.spring, &b.contact, force)?;
        let mut model = m.into_model();
        for s in &mut model.springs {
            if s.id.as_deref() == Some(b.spring.as_str()) {
                s.preload = Some(preload);
            }
        }
        model.validated().map_err(|e| TransientFitError::Point {
            at: at(),
            source: PointError::Invalid {
                path: e.path,
                problem: e.problem,
            },
        })
    }

    /// The run's tracked point: (step times, x, y, time to distance).
    fn run(
        &mut self,
        values: &[f64],
    ) -> Result<crate::analysis::switch_off::SwitchOffRun, TransientFitError> {
        let model = self.model(values)?;
        let r = run_switch_off(&model, &self.settings).map_err(|e| TransientFitError::Point {
            at: format!("{values:?}"),
            source: PointError::Simulation(e),
        })?;
        Ok(r.flexible)
    }
}

/// The samples of a run at `times`, by linear interpolation [SI: m].
fn interpolate(run_t: &[f64], v: &[f64], times: &[f64]) -> Vec<f64> {
    times
        .iter()
        .map(|&t| {
            let k = run_t.partition_point(|&s| s <= t).clamp(1, run_t.len() - 1);
            let w = (t - run_t[k - 1]) / (run_t[k] - run_t[k - 1]);
            v[k - 1] + w * (v[k] - v[k - 1])
        })
        .collect()
}

/// Fits `fit` on `model` (module doc).
pub fn calibrate_transient(
    model: &ValidModel,
    fit: &TransientFit,
) -> Result<TransientCalibration, TransientFitError> {
    let resolved = resolve(model, &fit.parameters)?;
    let balance = match &fit.balance {
        Some(b) => Some((b, balance_contact_force(model, &b.spring, &b.contact)?)),
        None => None,
    };
    let settings = SwitchOffSettings {
        fixed_step: true,
        compare_rigid: false,
        halve_step: false,
        sample_rate: 0.0,
        ..fit.experiment.clone()
    };
    let mut runs = Runs {
        json: serde_json::to_value(model.to_model()).expect("a model serializes"),
        resolved,
        balance,
        settings,
        history: Vec::new(),
    };
    let (values, calibrated, algorithm, samples, rms) = match &fit.target {
        TransientTarget::TimeToDistance { seconds, source } => {
            let (v, c) = fit_time(&mut runs, fit, *seconds, source)?;
            (v, c, Algorithm::Brent, 0, None)
        }
        TransientTarget::Trajectory(tr) => {
            let (v, c, rms) = fit_trajectory(&mut runs, fit, tr)?;
            (
                v,
                c,
                Algorithm::LevenbergMarquardt,
                tr.time_s.len(),
                Some(rms),
            )
        }
    };
    // The fitted model says what was fitted (model::calibrated).
    let fitted_model = runs
        .model(&values)?
        .into_model()
        .with_calibrations(&calibrated)
        .validated()
        .map_err(|e| TransientFitError::Point {
            at: String::from("the fitted model"),
            source: PointError::Invalid {
                path: e.path,
                problem: e.problem,
            },
        })?;
    // The records as the fitted model holds them (stamped with its design).
    let calibrated: Vec<Calibrated> = fitted_model
        .calibrated
        .iter()
        .filter(|r| calibrated.iter().any(|c| c.name == r.name))
        .cloned()
        .collect();
    let times = |values: &[f64], runs: &mut Runs| runs.run(values).map(|r| r.time_to_distance_s);
    let initial = runs.resolved.initial.clone();
    let initial_time_s = times(&initial, &mut runs)?;
    let achieved_time_s = times(&values, &mut runs)?;
    let preload = |m: &ValidModel, b: &Balance| {
        m.springs
            .iter()
            .find(|s| s.id.as_deref() == Some(b.spring.as_str()))
            .and_then(|s| s.preload)
            .unwrap_or(f64::NAN)
    };
    let balance = runs.balance.map(|(b, force)| BalanceRecord {
        spring: b.spring.clone(),
        contact: b.contact.clone(),
        contact_force_n: force,
        initial_preload_n: preload(model, b),
        fitted_preload_n: preload(&fitted_model, b),
    });
    let r = &runs.resolved;
    let parameters = (0..r.names.len())
        .map(|k| FittedParameter {
            name: r.names[k].clone(),
            unit: "SI",
            initial: r.initial[k],
            fitted: values[k],
            lower: r.lower[k],
            upper: r.upper[k],
            change_percent: super::change_percent(r.initial[k], values[k]),
        })
        .collect();
    Ok(TransientCalibration {
        quantity: match fit.target {
            TransientTarget::TimeToDistance { .. } => "time_to_distance_s",
            TransientTarget::Trajectory(_) => "trajectory",
        },
        algorithm,
        step_s: runs.settings.step,
        parameters,
        calibrated,
        balance,
        initial_time_s,
        achieved_time_s,
        samples,
        initial_rms_m: rms.map(|r| r.0),
        rms_m: rms.map(|r| r.1),
        history: runs.history,
        fitted_model,
    })
}

fn fit_time(
    runs: &mut Runs,
    fit: &TransientFit,
    target: f64,
    source: &str,
) -> Result<(Vec<f64>, Vec<Calibrated>), TransientFitError> {
    if runs.resolved.names.len() != 1 {
        return Err(TransientFitError::OneParameter {
            given: runs.resolved.names.len(),
        });
    }
    if !(target.is_finite() && target > 0.0) {
        return Err(TransientFitError::Target { value: target });
    }
    let (lo, hi) = (runs.resolved.lower[0], runs.resolved.upper[0]);
    // Not reaching the distance counts as "later than the end".
    let end = runs.settings.end_time;
    let g = |x: f64, runs: &mut Runs| -> Result<f64, TransientFitError> {
        let t = runs.run(&[x])?.time_to_distance_s;
        runs.history.push(TransientEvaluation {
            parameters: vec![x],
            value: t,
        });
        Ok(t.unwrap_or(2.0 * end) - target)
    };
    let x0 = runs.resolved.initial[0];
    let g0 = g(x0, runs)?;
    // The slope by a forward difference of 5 % of the bracket, towards its
    // wider side: only the first step's direction and size; a step of a
    // few µm beside a node would mesh an element of that length.
    let h = 0.05 * (hi - lo) * if hi - x0 >= x0 - lo { 1.0 } else { -1.0 };
    let slope = (g(x0 + h, runs)? - g0) / h;
    let settings = BrentSettings {
        g_tolerance: fit.tolerance_s,
        x_tolerance: 1e-12,
        max_evaluations: fit.max_evaluations.saturating_sub(1).max(2),
    };
    let start = Sample {
        x: x0,
        g: g0,
        slope: Some(slope),
    };
    let outcome = brent::solve(start, lo, hi, &settings, |x| {
        g(x, runs).map(|g| Sample { x, g, slope: None })
    })?;
    let best = match outcome {
        BrentOutcome::Root(s) if s.g.abs() <= fit.tolerance_s => s,
        BrentOutcome::Root(s) => {
            return Err(TransientFitError::Jump {
                at: s.x,
                best: s.g + target,
                target,
            })
        }
        BrentOutcome::NoSignChange { lower, upper } => {
            return Err(TransientFitError::Unreachable {
                low: (lower.g + target).min(upper.g + target),
                high: (lower.g + target).max(upper.g + target),
                target,
            })
        }
        BrentOutcome::Exhausted(s) => {
            return Err(TransientFitError::Exhausted {
                evaluations: runs.history.len(),
                best: s.g + target,
                target,
            })
        }
    };
    let calibrated = vec![Calibrated {
        name: runs.resolved.names[0].clone(),
        value: best.x,
        target: format!("time_to_distance_s = {target:.6e} s ({source})"),
        achieved: format!("time_to_distance_s = {:.6e} s", best.g + target),
        standard_error: None,
        design_sha256: None,
    }];
    Ok((vec![best.x], calibrated))
}

/// LM settings of a trajectory fit (unknowns p/p₀ of order 1).
fn lm_settings(max_evaluations: usize) -> lm::Settings {
    lm::Settings {
        initial_damping: lm::Scale::Relative(1e-3),
        grow: 10.0,
        shrink: 10.0,
        damping_floor: lm::Scale::Relative(1e-12),
        damping_ceiling: 1e16,
        max_rejections: 20,
        step_tolerance: 1e-10,
        min_relative_decrease: 1e-10,
        max_evaluations,
        max_iterations: usize::MAX,
    }
}

impl Runs<'_> {
    /// The run's path at the trajectory's times [SI: m], recorded in the
    /// history with its rms misfit.
    fn path_at(
        &mut self,
        values: &[f64],
        tr: &Trajectory,
    ) -> Result<DVector<f64>, TransientFitError> {
        let run = self.run(values)?;
        let end = *run.time_s.last().unwrap_or(&0.0);
        if tr.time_s.last().is_some_and(|&t| t > end) || run.time_s.len() < 2 {
            return Err(TransientFitError::Samples {
                samples: tr.time_s.len(),
                parameters: values.len(),
            });
        }
        let x = interpolate(&run.time_s, &run.x_m, &tr.time_s);
        let y = interpolate(&run.time_s, &run.y_m, &tr.time_s);
        let m = tr.time_s.len();
        let r = DVector::from_fn(2 * m, |i, _| match i < m {
            true => x[i] - tr.x_m[i],
            false => y[i - m] - tr.y_m[i - m],
        });
        self.history.push(TransientEvaluation {
            parameters: values.to_vec(),
            value: Some((r.norm_squared() / (2 * m) as f64).sqrt()),
        });
        Ok(r)
    }
}

/// The trajectory misfit as a least-squares problem in u = p/p₀ (p₀ the
/// starting value, or 1 where it is 0).
struct Misfit<'r, 'a> {
    runs: &'r mut Runs<'a>,
    trajectory: &'r Trajectory,
    scale: Vec<f64>,
}

impl Misfit<'_, '_> {
    fn values(&self, u: &[f64]) -> Vec<f64> {
        u.iter().zip(&self.scale).map(|(u, s)| u * s).collect()
    }
}

impl lm::Problem for Misfit<'_, '_> {
    type Point = DVector<f64>;
    type Error = TransientFitError;

    fn evaluate(&mut self, u: &[f64]) -> Result<DVector<f64>, TransientFitError> {
        let p = self.values(u);
        self.runs.path_at(&p, self.trajectory)
    }

    fn residuals(&self, r: &DVector<f64>) -> DVector<f64> {
        r.clone()
    }

    /// Central differences of 1e-5 in each u (the runs are smooth: fixed
    /// step).
    fn jacobian(
        &mut self,
        u: &[f64],
        r: &DVector<f64>,
        _: &DVector<f64>,
    ) -> Result<DMatrix<f64>, TransientFitError> {
        const H: f64 = 1e-5;
        let mut j = DMatrix::zeros(r.len(), u.len());
        for k in 0..u.len() {
            let mut a = u.to_vec();
            let mut b = u.to_vec();
            a[k] += H;
            b[k] -= H;
            let (ra, rb) = (self.evaluate(&a)?, self.evaluate(&b)?);
            j.set_column(k, &((ra - rb) / (2.0 * H)));
        }
        Ok(j)
    }
}

/// Why a parameter is undetermined, in words.
fn undetermined(standard_error: Option<f64>, width: f64) -> String {
    match standard_error {
        Some(e) => format!("its standard error {e:.4e} is not below its bounds' width {width:.4e}"),
        None => String::from("the path does not change with it (its standard error is unbounded)"),
    }
}

/// (fitted values, calibrated records, (initial rms, fitted rms) [SI: m]).
type TrajectoryFit = (Vec<f64>, Vec<Calibrated>, (f64, f64));

fn fit_trajectory(
    runs: &mut Runs,
    fit: &TransientFit,
    tr: &Trajectory,
) -> Result<TrajectoryFit, TransientFitError> {
    let n = runs.resolved.names.len();
    let m = tr.time_s.len();
    let increasing = tr.time_s.windows(2).all(|w| w[1] > w[0]);
    let sizes = tr.x_m.len() == m && tr.y_m.len() == m;
    if 2 * m <= n || !increasing || !sizes || tr.time_s.first().is_some_and(|&t| t < 0.0) {
        return Err(TransientFitError::Samples {
            samples: m,
            parameters: n,
        });
    }
    let r = &runs.resolved;
    let scale: Vec<f64> = r
        .initial
        .iter()
        .map(|&p| if p != 0.0 { p } else { 1.0 })
        .collect();
    let lower: Vec<f64> = r.lower.iter().zip(&scale).map(|(l, s)| l / s).collect();
    let upper: Vec<f64> = r.upper.iter().zip(&scale).map(|(l, s)| l / s).collect();
    let (lower, upper): (Vec<f64>, Vec<f64>) = lower
        .iter()
        .zip(&upper)
        .map(|(a, b)| (a.min(*b), a.max(*b)))
        .unzip();
    let u0: Vec<f64> = r.initial.iter().zip(&scale).map(|(p, s)| p / s).collect();
    let mut problem = Misfit {
        runs,
        trajectory: tr,
        scale: scale.clone(),
    };
    let start = lm::Problem::evaluate(&mut problem, &u0)?;
    let rms = |r: &DVector<f64>| (r.norm_squared() / (2 * m) as f64).sqrt();
    let initial_rms = rms(&start);
    let settings = lm_settings(fit.max_evaluations);
    let outcome = lm::solve(&mut problem, u0, start, &lower, &upper, &settings)?;
    // Standard errors mean something only at an optimum.
    if outcome.stop == lm::Stop::Exhausted {
        return Err(TransientFitError::TrajectoryExhausted {
            evaluations: outcome.evaluations,
            rms: rms(&outcome.best),
        });
    }
    let values = problem.values(&outcome.x);
    // Standard errors from the Jacobian and the residual at the fit.
    let j = lm::Problem::jacobian(&mut problem, &outcome.x, &outcome.best, &outcome.best)?;
    let dof = (2 * m - n) as f64;
    let s2 = outcome.best.norm_squared() / dof;
    let jtj = j.transpose() * &j;
    let cov = jtj.try_inverse();
    let fitted_rms = rms(&outcome.best);
    let error = |k: usize| {
        cov.as_ref()
            .map(|c| (s2 * c[(k, k)]).max(0.0).sqrt() * scale[k].abs())
    };
    // A parameter the samples do not determine (no effect on them, or an
    // error wider than its bounds: samples in other units than metres, a
    // model that does not follow them) is no calibration.
    // With JᵀJ singular, the parameter named is the one the path moves
    // least with (its Jacobian column the shortest).
    let order: Vec<usize> = if cov.is_some() {
        (0..n).collect()
    } else {
        let mut o: Vec<usize> = (0..n).collect();
        o.sort_by(|&a, &b| j.column(a).norm().total_cmp(&j.column(b).norm()));
        o
    };
    for k in order {
        let (lo, hi) = (
            problem.runs.resolved.lower[k],
            problem.runs.resolved.upper[k],
        );
        let width = (hi - lo).abs();
        if !error(k).is_some_and(|e| e.is_finite() && e < width) {
            return Err(TransientFitError::Undetermined {
                name: problem.runs.resolved.names[k].clone(),
                standard_error: error(k),
                width,
                rms: fitted_rms,
            });
        }
    }
    let calibrated = (0..n)
        .map(|k| Calibrated {
            name: problem.runs.resolved.names[k].clone(),
            value: values[k],
            target: format!("the trajectory {} ({m} samples of t, x, y)", tr.label),
            achieved: format!("rms residual {fitted_rms:.4e} m (start {initial_rms:.4e} m)"),
            standard_error: error(k),
            design_sha256: None,
        })
        .collect();
    Ok((values, calibrated, (initial_rms, fitted_rms)))
}
