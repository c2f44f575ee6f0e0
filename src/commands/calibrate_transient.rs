//! `calibrate` to a transient: model parameters (SI, as in the model file)
//! fitted so that the switch-off experiment gives a measured time to
//! distance [s] (Brent, one parameter) or a measured trajectory of the
//! tracked point (t [s], x, y [m]; least squares, Levenberg–Marquardt, with
//! each parameter's standard error) ([`crate::analysis::calibrate::transient`]).
//! Every run integrates at a fixed step. The CLI's `calibrate --quantity` /
//! `--trajectory` and Python's `calibrate(quantity=…)` map onto this request.

use super::{CommandError, ModelInput, Run};
use crate::analysis::calibrate::transient::{
    calibrate_transient, Balance, Trajectory, TransientCalibration, TransientFit,
    TransientParameter, TransientTarget,
};
use crate::analysis::calibrate::ParameterSpec;
use crate::analysis::switch_off::SwitchOffSettings;
use crate::model::PointSpec;
pub use crate::results::TransientCalibrationOutput;
use std::path::{Path, PathBuf};

/// The quantity a time target refers to.
pub const TIME_TO_DISTANCE: &str = "time_to_distance_s";

/// Where a measured trajectory comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum TrajectoryInput {
    /// A CSV file ([`read_trajectory`]).
    File(PathBuf),
    /// Samples given as they are.
    Samples(Trajectory),
}

impl TrajectoryInput {
    /// The samples, read or checked: as many of each, finite, times
    /// increasing.
    fn samples(&self) -> Result<Trajectory, CommandError> {
        let tr = match self {
            TrajectoryInput::File(file) => return read_trajectory(file),
            TrajectoryInput::Samples(tr) => tr,
        };
        let m = tr.time_s.len();
        let why = if tr.x_m.len() != m || tr.y_m.len() != m {
            format!(
                "t, x and y must have as many samples ({m}, {}, {})",
                tr.x_m.len(),
                tr.y_m.len()
            )
        } else if m == 0 {
            String::from("holds no samples")
        } else if let Some(k) = (0..m).find(|&k| {
            !(tr.time_s[k].is_finite() && tr.x_m[k].is_finite() && tr.y_m[k].is_finite())
        }) {
            format!("sample {k} is not finite")
        } else if let Some(k) = (1..m).find(|&k| tr.time_s[k] <= tr.time_s[k - 1]) {
            format!("time {} at sample {k} does not increase", tr.time_s[k])
        } else {
            return Ok(tr.clone());
        };
        Err(CommandError::argument("trajectory", &tr.label, why))
    }
}

/// What a transient calibration fits, and how.
#[derive(Debug, Clone, PartialEq)]
pub struct CalibrateTransientRequest {
    /// `time_to_distance_s` with `target_s`; `None` with `trajectory`.
    pub quantity: Option<String>,
    /// The measured time [s].
    pub target_s: Option<f64>,
    /// Where the target comes from (for the labels); default "measured".
    pub target_source: Option<String>,
    /// Samples t [s], x [m], y [m] of the tracked point: a CSV file, or
    /// given as they are (Python's arrays).
    pub trajectory: Option<TrajectoryInput>,
    /// The parameters (JSON paths or short names), optional bounds [SI].
    pub params: Vec<ParameterSpec>,
    /// `SPRING:CONTACT`: the spring's preload follows the ON-state balance
    /// that keeps the contact's force.
    pub balance: Option<String>,
    /// Stop a time fit within this of the target [s]; default 1e-5 × target.
    pub tolerance_s: Option<f64>,
    /// Most experiments (2 to 10000).
    pub max_evaluations: usize,
    /// The experiment: fixed step [s], end time [s], distance [m],
    /// direction, tracked point.
    pub step: f64,
    pub end_time: f64,
    pub distance: f64,
    pub direction: [f64; 2],
    pub point: Option<PointSpec>,
}

impl Default for CalibrateTransientRequest {
    fn default() -> Self {
        let s = SwitchOffSettings::default();
        CalibrateTransientRequest {
            quantity: None,
            target_s: None,
            target_source: None,
            trajectory: None,
            params: Vec::new(),
            balance: None,
            tolerance_s: None,
            max_evaluations: 60,
            step: s.step,
            end_time: s.end_time,
            distance: s.distance,
            direction: s.direction,
            point: None,
        }
    }
}

/// The run: the fit and its document.
#[derive(Debug)]
pub struct CalibrateTransientRun {
    pub result: TransientCalibration,
    pub document: Run<TransientCalibrationOutput>,
}

/// Reads a trajectory: lines `t,x,y` [s, m, m], further columns ignored
/// (so `switch-off --csv` output reads as it is); a first line that is not
/// numbers is a header; blank lines and `#` lines are skipped.
pub fn read_trajectory(file: &Path) -> Result<Trajectory, CommandError> {
    let text = std::fs::read_to_string(file).map_err(|io| CommandError::ReadFile {
        file: file.to_path_buf(),
        io,
    })?;
    let bad = |line: usize, why: String| {
        CommandError::argument("trajectory", format!("{}:{line}", file.display()), why)
    };
    let mut tr = Trajectory {
        label: file.display().to_string(),
        time_s: Vec::new(),
        x_m: Vec::new(),
        y_m: Vec::new(),
    };
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let numbers: Option<Vec<f64>> = cells
            .iter()
            .take(3)
            .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect();
        match (numbers, tr.time_s.is_empty() && k == 0) {
            (Some(v), _) if v.len() == 3 => {
                if tr.time_s.last().is_some_and(|&t| v[0] <= t) {
                    return Err(bad(k + 1, format!("time {} does not increase", v[0])));
                }
                tr.time_s.push(v[0]);
                tr.x_m.push(v[1]);
                tr.y_m.push(v[2]);
            }
            (None, true) => {}
            _ => {
                return Err(bad(
                    k + 1,
                    format!(
                    "`{line}`: each line must start with three finite numbers t [s], x [m], y [m]"
                ),
                ))
            }
        }
    }
    if tr.time_s.is_empty() {
        return Err(bad(0, String::from("holds no samples")));
    }
    Ok(tr)
}

/// Runs the transient calibration on `input`.
pub fn run(
    input: &ModelInput,
    request: &CalibrateTransientRequest,
) -> Result<CalibrateTransientRun, CommandError> {
    super::checks::time_span(request.end_time, request.step)?;
    super::checks::positive("distance", request.distance)?;
    if !(2..=10_000).contains(&request.max_evaluations) {
        return Err(CommandError::argument(
            "max_evaluations",
            request.max_evaluations,
            "must be a whole number from 2 to 10000",
        ));
    }
    let target = match (&request.quantity, request.target_s, &request.trajectory) {
        (Some(q), Some(t), None) if q == TIME_TO_DISTANCE => TransientTarget::TimeToDistance {
            seconds: t,
            source: request
                .target_source
                .clone()
                .unwrap_or_else(|| String::from("measured")),
        },
        (Some(q), _, None) if q != TIME_TO_DISTANCE => {
            return Err(CommandError::argument(
                "quantity",
                q,
                format!("the transient quantity is `{TIME_TO_DISTANCE}`"),
            ))
        }
        (Some(_), None, None) => {
            return Err(CommandError::argument(
                "target",
                "none",
                "a time fit needs the measured time [s]",
            ))
        }
        (None, _, Some(tr)) => TransientTarget::Trajectory(tr.samples()?),
        _ => {
            return Err(CommandError::argument(
                "trajectory",
                "with quantity",
                "fit either a quantity's target or a trajectory, not both",
            ))
        }
    };
    let balance = match &request.balance {
        None => None,
        Some(b) => match b.split_once(':') {
            Some((spring, contact)) if !spring.is_empty() && !contact.is_empty() => Some(Balance {
                spring: spring.to_string(),
                contact: contact.to_string(),
            }),
            _ => {
                return Err(CommandError::argument(
                    "balance",
                    b,
                    "must be SPRING:CONTACT (a spring id and a point_line contact id)",
                ))
            }
        },
    };
    if request.params.is_empty() {
        return Err(CommandError::argument(
            "params",
            "none",
            "name the parameters to fit (a JSON path or a short name)",
        ));
    }
    let tolerance_s = match (request.tolerance_s, &target) {
        (Some(t), _) if !(t.is_finite() && t > 0.0) => {
            return Err(CommandError::argument(
                "tolerance",
                t,
                "must be a number > 0",
            ))
        }
        (Some(t), _) => t,
        (None, TransientTarget::TimeToDistance { seconds, .. }) => 1e-5 * seconds.abs(),
        (None, _) => 0.0,
    };
    let fit = TransientFit {
        parameters: request
            .params
            .iter()
            .map(|p| TransientParameter {
                name: p.name.clone(),
                bounds: p.bounds,
            })
            .collect(),
        target,
        balance,
        experiment: SwitchOffSettings {
            step: request.step,
            end_time: request.end_time,
            distance: request.distance,
            direction: request.direction,
            point: request.point.clone(),
            ..SwitchOffSettings::default()
        },
        tolerance_s,
        max_evaluations: request.max_evaluations,
    };
    let result = calibrate_transient(&input.model, &fit).map_err(|source| {
        CommandError::TransientCalibration {
            model: input.label(),
            source: Box::new(source),
        }
    })?;
    let output = TransientCalibrationOutput {
        model: input.model.name.clone(),
        result: result.clone(),
    };
    Ok(CalibrateTransientRun {
        result,
        document: Run::of(input, output),
    })
}

impl CalibrateTransientRun {
    /// The command line's report: what was fitted, to what, how well.
    pub fn text(&self) -> String {
        let r = &self.result;
        let mut out = format!(
            "model {}: calibration to a transient ({}, {:?}; every run at a fixed step of {:e} s)\n",
            self.document.output.model, r.quantity, r.algorithm, r.step_s
        );
        out += "  parameter                              initial           fitted   std. error\n";
        for (p, c) in r.parameters.iter().zip(&r.calibrated) {
            let se = c
                .standard_error
                .map_or_else(|| String::from("—"), |s| format!("{s:.3e}"));
            out += &format!(
                "  {:<34} {:>12.6e} {:>16.9e}   {se}\n",
                p.name, p.initial, p.fitted
            );
        }
        for c in &r.calibrated {
            out += &format!(
                "calibrated: {} to {}; achieved {}\n",
                c.name, c.target, c.achieved
            );
        }
        if let Some(b) = &r.balance {
            out += &format!(
                "the preload of {} follows the balance that keeps {} at {:.4} N: {:.4} N → {:.4} N\n",
                b.spring, b.contact, b.contact_force_n, b.initial_preload_n, b.fitted_preload_n
            );
        }
        let ms = |t: Option<f64>| {
            t.map_or_else(
                || String::from("not reached"),
                |t| format!("{:.6} ms", t * 1e3),
            )
        };
        out += &format!(
            "time to distance: {} at the start, {} at the fit\n",
            ms(r.initial_time_s),
            ms(r.achieved_time_s)
        );
        out += &format!("{} experiments\n", r.history.len());
        out
    }

    /// The calibrated model as a model file's text.
    pub fn fitted_json(&self) -> String {
        self.result.fitted_model.to_json() + "\n"
    }
}
