//! What a sweep computes at each point, and the one function that computes
//! it on a model ([`evaluate`]).
//!
//! * `first_bending_hz` — the lowest mode whose strain energy is mostly
//!   bending ([`crate::analysis::ModeKind::Bending`]) [Hz];
//! * `frequency:K` — the K-th elastic mode [Hz] (zero-frequency rigid-body
//!   or mechanism modes not counted), *tracked*: K is the mode's place at
//!   the sweep's first point, and at every other point the mode is the one
//!   whose shape matches (MAC, [`super::tracking`]), so a mode keeps its
//!   identity where it crosses another.
//!
//! * `time_to_distance_s` — the switch-off ([`crate::analysis::switch_off`]
//!   with its defaults: equilibrium, release, node 0 of the first beam
//!   travelling 2 mm along x) [s]; each point's ON state is continued from
//!   the swept model's (the contacts that hold it stay closed, or the
//!   point reports where one lets go);
//! * `peak:SENSOR` — the largest |reading| of a sensor over a `transient`
//!   run (from the static equilibrium when the sweep is pre-stressed) [SI
//!   unit of the sensor].
//!
//! Modes are computed at the reference configuration, or at the static
//! equilibrium under the model's constant loads and gravity when the sweep
//! is pre-stressed (the linearization of `modal --prestress`).
//!
//! New quantities are new variants of [`Quantity`], parsed in
//! [`Quantity::parse`] and computed in [`evaluate`].

use super::error::{PointError, SweepError};
use crate::analysis::modal::{modal, ModalResult, ModalSettings};
use crate::analysis::simulate::{simulate, SimulationSettings};
use crate::analysis::statics::start::Start;
use crate::analysis::statics::{solve_equilibrium, StaticSettings};
use crate::analysis::switch_off::{run_switch_off_from, SwitchOffSettings};
use crate::analysis::transient::TransientSettings;
use crate::analysis::EigenMethod;
use crate::model::ValidModel;
use crate::system::System;
use serde::{Deserialize, Serialize};

/// A quantity a sweep computes at each point.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Quantity {
    /// First bending frequency [Hz].
    FirstBendingHz,
    /// The tracked K-th elastic mode's frequency [Hz] (K ≥ 1).
    Frequency { mode: usize },
    /// Switch-off time to the travel distance [SI: s].
    TimeToDistance,
    /// Largest |reading| of a sensor over a transient run.
    Peak { sensor: String },
}

/// The quantity names [`Quantity::parse`] accepts.
pub const AVAILABLE: [&str; 4] = [
    "first_bending_hz",
    "frequency:K",
    "time_to_distance_s",
    "peak:SENSOR",
];

impl Quantity {
    /// Parses a name of [`AVAILABLE`].
    pub fn parse(text: &str) -> Result<Quantity, SweepError> {
        let unknown = || SweepError::UnknownQuantity {
            given: text.to_string(),
            available: AVAILABLE.to_vec(),
        };
        let t = text.trim();
        if t == "first_bending_hz" {
            return Ok(Quantity::FirstBendingHz);
        }
        if t == "time_to_distance_s" {
            return Ok(Quantity::TimeToDistance);
        }
        if let Some(id) = t.strip_prefix("peak:") {
            let id = id.trim();
            if id.is_empty() {
                return Err(unknown());
            }
            return Ok(Quantity::Peak {
                sensor: id.to_string(),
            });
        }
        if let Some(k) = t.strip_prefix("frequency:") {
            let mode = k.trim().parse::<usize>().ok().filter(|&k| k >= 1);
            return mode
                .map(|mode| Quantity::Frequency { mode })
                .ok_or_else(unknown);
        }
        Err(unknown())
    }

    /// The mode number a tracked quantity follows.
    pub fn tracked_mode(&self) -> Option<usize> {
        match self {
            Quantity::Frequency { mode } => Some(*mode),
            _ => None,
        }
    }

    /// Label for plots and tables.
    pub fn label(&self) -> String {
        match self {
            Quantity::FirstBendingHz => "First bending frequency".into(),
            Quantity::Frequency { mode } => format!("Frequency of mode {mode}"),
            Quantity::TimeToDistance => "Time to distance".into(),
            Quantity::Peak { sensor } => format!("Peak of sensor {sensor}"),
        }
    }

    /// SI unit of the value ("" for a sensor peak: the sensor's unit).
    pub fn unit(&self) -> &'static str {
        match self {
            Quantity::FirstBendingHz | Quantity::Frequency { .. } => "Hz",
            Quantity::TimeToDistance => "s",
            Quantity::Peak { .. } => "",
        }
    }
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Quantity::FirstBendingHz => f.write_str("first_bending_hz"),
            Quantity::Frequency { mode } => write!(f, "frequency:{mode}"),
            Quantity::TimeToDistance => f.write_str("time_to_distance_s"),
            Quantity::Peak { sensor } => write!(f, "peak:{sensor}"),
        }
    }
}

/// An elastic mode of one point, as tracking needs it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct RawMode {
    /// [SI: Hz]
    pub frequency_hz: f64,
    /// Mass-normalized shape in the global coordinates.
    pub shape: Vec<f64>,
}

/// What [`evaluate`] gives for one point.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// The quantity, when it does not need the other points (`None` for a
    /// tracked quantity, which [`super::tracking`] assigns).
    pub value: Option<f64>,
    /// Elastic modes, ascending (tracked quantities only).
    pub modes: Vec<RawMode>,
    /// The switch-off's tracked point over time (`time_to_distance_s`,
    /// when [`EvalSettings::keep_trace`]).
    pub trace: Option<Trace>,
}

/// The tracked point of a switch-off run (node 0 by default): absolute
/// coordinates at the output samples, as `switch-off --json`'s `node0`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Trace {
    /// [SI: s]
    pub time_s: Vec<f64>,
    /// [SI: m]
    pub x_m: Vec<f64>,
    /// [SI: m]
    pub y_m: Vec<f64>,
}

/// How the points are computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EvalSettings {
    /// Linearize at the static equilibrium instead of the reference.
    pub prestress: bool,
    pub method: EigenMethod,
    /// Elastic modes computed for tracking.
    pub modes: usize,
    /// Step and end time of transient quantities [SI: s] (`None`: the
    /// switch-off's 1 µs and 3 ms).
    pub step: Option<f64>,
    pub end_time: Option<f64>,
    /// Keep each switch-off's trace (a one-parameter sweep draws them).
    pub keep_trace: bool,
}

/// Computes `quantity` on `model`, a point of a sweep of `base` (the
/// switch-off's ON state is continued from base's,
/// [`crate::analysis::switch_off::run_switch_off_from`]).
pub fn evaluate(
    quantity: &Quantity,
    model: &ValidModel,
    base: &ValidModel,
    settings: &EvalSettings,
) -> Result<Evaluation, PointError> {
    let system = System::new(model);
    match quantity {
        Quantity::FirstBendingHz => {
            let r = elastic_modes(&system, settings, 6, |r| r.first_bending().is_some())?;
            let computed = r.modes.len() - r.rigid_modes.min(r.modes.len());
            let f = r
                .first_bending()
                .ok_or(PointError::NoBendingMode { computed })?;
            Ok(Evaluation {
                value: Some(f.frequency_hz),
                modes: Vec::new(),
                trace: None,
            })
        }
        Quantity::Frequency { mode } => {
            let wanted = settings.modes.max(*mode);
            let r = elastic_modes(&system, settings, wanted, |_| true)?;
            let modes: Vec<RawMode> = r
                .modes
                .into_iter()
                .filter(|m| !m.kind.is_zero())
                .map(|m| RawMode {
                    frequency_hz: m.frequency_hz,
                    shape: m.shape,
                })
                .collect();
            if modes.len() < *mode {
                return Err(PointError::TooFewModes {
                    wanted: *mode,
                    available: modes.len(),
                });
            }
            Ok(Evaluation {
                value: None,
                modes,
                trace: None,
            })
        }
        Quantity::TimeToDistance => {
            let defaults = SwitchOffSettings::default();
            let so = SwitchOffSettings {
                step: settings.step.unwrap_or(defaults.step),
                end_time: settings.end_time.unwrap_or(defaults.end_time),
                ..defaults
            };
            let r = run_switch_off_from(model, base, &so)?;
            let t = r
                .flexible
                .time_to_distance_s
                .ok_or(PointError::NotReached {
                    distance: so.distance,
                    end_time: so.end_time,
                })?;
            let run = r.flexible;
            Ok(Evaluation {
                value: Some(t),
                modes: Vec::new(),
                trace: settings.keep_trace.then_some(Trace {
                    time_s: run.time_s,
                    x_m: run.x_m,
                    y_m: run.y_m,
                }),
            })
        }
        Quantity::Peak { sensor } => {
            let index = system
                .sensors
                .iter()
                .position(|s| &s.id == sensor)
                .ok_or_else(|| PointError::UnknownSensor {
                    id: sensor.clone(),
                    available: crate::error::Ids::of(system.sensors.iter().map(|s| &s.id)),
                })?;
            let defaults = SwitchOffSettings::default();
            let sim = simulate(
                System::new(model),
                &[],
                &SimulationSettings {
                    transient: TransientSettings {
                        step: settings.step.unwrap_or(defaults.step),
                        end_time: settings.end_time.unwrap_or(defaults.end_time),
                        damping: model.damping,
                        ..TransientSettings::default()
                    },
                    start: Start::Equilibrium,
                    sample_rate: 0.0,
                    keep_partial: false,
                },
            )?;
            let peak = sim.sensors[index]
                .1
                .iter()
                .fold(0.0f64, |m, x| m.max(x.abs()));
            Ok(Evaluation {
                value: Some(peak),
                modes: Vec::new(),
                trace: None,
            })
        }
    }
}

/// At least `wanted` elastic modes (fewer if the model has fewer); when
/// `enough` rejects them, all modes.
fn elastic_modes(
    system: &System,
    settings: &EvalSettings,
    wanted: usize,
    enough: impl Fn(&ModalResult) -> bool,
) -> Result<ModalResult, PointError> {
    let equilibrium = if settings.prestress {
        Some(solve_equilibrium(system, &StaticSettings::default())?)
    } else {
        None
    };
    let reference = system.reference();
    let at = equilibrium
        .as_ref()
        .map_or(reference, |e| e.linearization());
    let run = |count: usize| {
        modal(
            system,
            &at,
            &ModalSettings {
                modes: Some(count),
                method: settings.method,
            },
        )
    };
    // Three rigid modes of a free planar assembly, then the elastic ones.
    let r = run(wanted + 3)?;
    let elastic = r.modes.len() - r.rigid_modes.min(r.modes.len());
    let more = r.reduced_dofs > r.modes.len();
    if more && (elastic < wanted || !enough(&r)) {
        let count = if elastic < wanted {
            wanted + r.rigid_modes
        } else {
            r.reduced_dofs
        };
        return Ok(run(count)?);
    }
    Ok(r)
}
