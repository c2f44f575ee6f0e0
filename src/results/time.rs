//! The documents of the time-domain commands: `impulse` (the paper's
//! hammer test, its spectrum and first bending peak), `transient` (sensors,
//! contacts, energy balance) and `switch-off` (the tracked point's travel
//! after the release, flexible and rigid).

use crate::analysis::impulse::{Excitation, ImpulseResult};
use crate::analysis::simulate::{EnergyBalance, Simulation, SimulationSettings};
use crate::analysis::statics::start::Start;
use crate::analysis::statics::Branch;
use crate::analysis::switch_off::{Calibrated, SwitchOffResult, SwitchOffRun, Uncalibrated};
use crate::analysis::switch_off_study::SwitchOffStudy;
use crate::analysis::transient::contacts::ContactStats;
use crate::model::reference::Errors;
use schemars::JsonSchema;
use serde::Serialize;
use std::collections::BTreeMap;

/// The first bending mode's damping, identified from the records against
/// the model's.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct DampingSummary {
    /// ζ fitted from the sensor record [–].
    pub identified_ratio: f64,
    /// Frequency of the fitted mode [Hz].
    pub identified_hz: f64,
    /// The model's own ζ of that mode (Rayleigh or complex mode) [–].
    pub modal_ratio: f64,
    /// ζ the integrator's numerical damping adds [–].
    pub numerical_ratio: f64,
    /// modal + numerical ζ, what the fit should find [–].
    pub expected_ratio: f64,
    /// (identified − expected)/expected [–]; null when nothing is expected.
    pub relative_error: Option<f64>,
}

/// A spectrum peak.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PeakSummary {
    /// Interpolated peak frequency [Hz].
    pub frequency_hz: f64,
    /// Interpolated amplitude [sensor unit × s].
    pub magnitude: f64,
}

/// `impulse --json` (also `identify`'s `impulse`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ImpulseOutput {
    /// Model name.
    pub model: String,
    /// Which loads excite the run (`half_sine`: the hammer, or `step`).
    pub excitation: Excitation,
    /// Ids of the exciting loads.
    pub excitation_loads: Vec<String>,
    /// The start asked for: `equilibrium` (the static equilibrium under
    /// the loads at t = 0⁻, the reference when it balances them) or
    /// `reference`.
    pub start: Start,
    /// Whether the blow struck a solved static equilibrium (its modes are
    /// the pre-stressed ones, as `modal --prestress`), else the reference.
    pub from_equilibrium: bool,
    /// First bending frequency from the FFT peak, the integrator's period
    /// error removed [Hz]; null when no peak is near the mode.
    pub first_bending_hz: Option<f64>,
    /// The same peak as the FFT shows it [Hz].
    pub first_bending_raw_hz: Option<f64>,
    /// The sensor's reading of the first bending mode over the mode's
    /// largest motion [–] (below 1e-3 the sensor does not see it, and no
    /// first bending frequency is identified); null without a bending mode.
    pub first_bending_sight: Option<f64>,
    /// The hammer's work on the first bending mode over its force times
    /// the mode's largest motion [–] (below 1e-3 the hammer does not
    /// excite it, and no first bending frequency is identified); null
    /// without a bending mode.
    pub first_bending_reach: Option<f64>,
    /// Where the first bending mode moves most, when the sensor does not
    /// see it or the hammer does not excite it (a sensor or a blow there
    /// would); else null.
    pub first_bending_seen_at: Option<String>,
    /// The eigenvalue analysis's first bending frequency at the state
    /// struck [Hz].
    pub eigen_first_bending_hz: Option<f64>,
    /// (raw − eigen)/eigen [–].
    pub raw_vs_eigen: Option<f64>,
    /// (corrected − eigen)/eigen [–].
    pub corrected_vs_eigen: Option<f64>,
    /// The first bending mode's damping from the record; null without a
    /// fit.
    pub damping: Option<DampingSummary>,
    /// Spectrum peaks, ascending in frequency.
    pub peaks: Vec<PeakSummary>,
    /// The experiment's first bending frequency [Hz]; null without one.
    pub reference_hz: Option<f64>,
    /// (model − experiment)/experiment [%] of `first_bending_hz`.
    pub error_percent: Option<f64>,
    /// (experiment − model)/model [%], the paper's convention.
    pub paper_error_percent: Option<f64>,
    /// Time steps taken [–].
    pub steps: usize,
    /// Time step [s].
    pub step_s: f64,
    /// End time [s].
    pub end_time_s: f64,
    /// Spectral radius at infinity of generalized-α [–].
    pub spectral_radius: f64,
    /// Newton iterations in all [–].
    pub newton_iterations: usize,
    /// Factorizations of the iteration matrix [–].
    pub factorizations: usize,
    /// Largest joint position residual over the run [m].
    pub max_joint_residual_m: f64,
    /// Largest joint angle residual over the run [rad].
    pub max_joint_residual_rad: f64,
    /// Sensor id.
    pub sensor: String,
    /// Sensor sampling rate [Hz].
    pub sample_rate_hz: f64,
    /// Number of sensor samples [–].
    pub samples: usize,
}

impl ImpulseOutput {
    /// The document of `r` on `model_name`, against the experiment's
    /// `reference_hz`.
    pub fn new(model_name: &str, r: &ImpulseResult, reference_hz: Option<f64>) -> Self {
        let fb = r.first_bending;
        let errors = fb
            .zip(reference_hz)
            .map(|(f, e)| Errors::new(f.corrected_hz, e));
        ImpulseOutput {
            model: model_name.to_string(),
            excitation: r.excitation,
            excitation_loads: r.excitation_loads.clone(),
            start: r.settings.start,
            from_equilibrium: r.equilibrium_iterations.is_some(),
            first_bending_hz: fb.map(|f| f.corrected_hz),
            first_bending_raw_hz: fb.map(|f| f.raw_hz),
            first_bending_sight: r.sight.as_ref().map(|s| s.ratio),
            first_bending_reach: r.sight.as_ref().map(|s| s.reach),
            first_bending_seen_at: r
                .sight
                .as_ref()
                .filter(|s| s.blind())
                .map(|s| s.best_point.clone()),
            eigen_first_bending_hz: r.modal.first_bending().map(|m| m.frequency_hz),
            raw_vs_eigen: fb.map(|f| f.raw_error()),
            corrected_vs_eigen: fb.map(|f| f.corrected_error()),
            damping: r.damping.map(|d| DampingSummary {
                identified_ratio: d.identified_ratio,
                identified_hz: d.identified_hz,
                modal_ratio: d.modal_ratio,
                numerical_ratio: d.numerical_ratio,
                expected_ratio: d.expected_ratio(),
                relative_error: d.relative_error(),
            }),
            peaks: r
                .peaks
                .iter()
                .map(|p| PeakSummary {
                    frequency_hz: p.frequency_hz,
                    magnitude: p.magnitude,
                })
                .collect(),
            reference_hz,
            error_percent: errors.map(|e| e.error_percent),
            paper_error_percent: errors.map(|e| e.paper_error_percent),
            steps: r.stats.steps,
            step_s: r.settings.transient.step,
            end_time_s: r.settings.transient.end_time,
            spectral_radius: r.settings.transient.spectral_radius,
            newton_iterations: r.stats.newton_iterations,
            factorizations: r.stats.factorizations,
            max_joint_residual_m: r.stats.max_length_residual,
            max_joint_residual_rad: r.stats.max_angle_residual,
            sensor: r.sensor.clone(),
            sample_rate_hz: r.sample_rate_hz,
            samples: r.signal.len(),
        }
    }
}

/// `transient --json`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct TransientOutput {
    /// Model name.
    pub model: String,
    /// Time step [s].
    pub step_s: f64,
    /// End time [s].
    pub end_time_s: f64,
    /// The start asked for: `equilibrium` (the static equilibrium under
    /// the loads at t = 0⁻, the reference when it balances them) or
    /// `reference`.
    pub start: Start,
    /// Whether the run started from a solved static equilibrium (else from
    /// the reference at rest).
    pub from_equilibrium: bool,
    /// Output sample rate [Hz]; 0 keeps every step.
    pub sample_rate_hz: f64,
    /// Time steps taken [–].
    pub steps: usize,
    /// Newton iterations in all [–].
    pub newton_iterations: usize,
    /// Shortest step taken [s].
    pub min_step_s: f64,
    /// Time of the last accepted step when the run stopped before its end
    /// time (a Newton failure, a singular iteration matrix) [s]; null when
    /// it reached it.
    pub ended_at_s: Option<f64>,
    /// Why it stopped early, one line; null when it did not.
    pub failure: Option<String>,
    /// Sample times [s].
    pub time_s: Vec<f64>,
    /// Each sensor's samples by id [m, m/s or m/s², by the sensor's quantity].
    pub sensors: BTreeMap<String, Vec<f64>>,
    /// What each contact saw.
    pub contacts: Vec<ContactStats>,
    /// The energy balance [J].
    pub energy: EnergyBalance,
}

impl TransientOutput {
    /// The document of `sim`, run with `settings` on `model_name`.
    pub fn new(model_name: &str, settings: &SimulationSettings, sim: &Simulation) -> Self {
        TransientOutput {
            model: model_name.to_string(),
            step_s: settings.transient.step,
            end_time_s: settings.transient.end_time,
            start: settings.start,
            from_equilibrium: sim.from_equilibrium,
            sample_rate_hz: settings.sample_rate,
            steps: sim.stats.steps,
            newton_iterations: sim.stats.newton_iterations,
            min_step_s: sim.min_step,
            ended_at_s: sim.failure.as_ref().and(sim.step_time.last().copied()),
            failure: sim.failure.as_ref().map(|e| crate::error::chain_text(e)),
            time_s: sim.time.clone(),
            sensors: sim.sensors.iter().cloned().collect(),
            contacts: sim.contacts.clone(),
            energy: sim.energy,
        }
    }
}

/// The tracked point's samples.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PointSamples {
    /// Sample times [s].
    pub time_s: Vec<f64>,
    /// Absolute x coordinate [m].
    pub x_m: Vec<f64>,
    /// Absolute y coordinate [m].
    pub y_m: Vec<f64>,
}

/// One run of the switch-off: the flexible model's (at the top level of
/// [`SwitchOffOutput`]) or the rigid one's.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct RunOutput {
    /// How the ON state was found (its branch: continued from another
    /// design, or solved from the reference and along which load path).
    pub on_state: Branch,
    /// When the tracked point has travelled the distance [s]; null when
    /// not reached.
    pub time_to_distance_s: Option<f64>,
    /// The tracked point's samples.
    pub node0: PointSamples,
    /// Largest contact penetration [m].
    pub max_penetration_m: f64,
    /// What each contact saw.
    pub contacts: Vec<ContactStats>,
    /// The released loads' forces at the sample times, by label [N].
    pub released_loads: BTreeMap<String, Vec<f64>>,
    /// When a run that failed after reaching the distance ended [s]; else null.
    pub ended_at_s: Option<f64>,
    /// The energy balance [J].
    pub energy: EnergyBalance,
    /// Time steps taken [–].
    pub steps: usize,
    /// Newton iterations in all [–].
    pub newton_iterations: usize,
    /// Shortest step taken [s].
    pub min_step_s: f64,
}

impl RunOutput {
    fn new(run: &SwitchOffRun) -> Self {
        RunOutput {
            on_state: run.on_state.clone(),
            time_to_distance_s: run.time_to_distance_s,
            node0: PointSamples {
                time_s: run.time_s.clone(),
                x_m: run.x_m.clone(),
                y_m: run.y_m.clone(),
            },
            max_penetration_m: run.max_penetration_m,
            contacts: run.contacts.clone(),
            released_loads: run.released_loads.iter().cloned().collect(),
            ended_at_s: run.ended_at_s,
            energy: run.energy,
            steps: run.steps,
            newton_iterations: run.newton_iterations,
            min_step_s: run.min_step_s,
        }
    }
}

/// The rigid model's run with its departure time.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct RigidRun {
    /// The run (its keys sit beside `departure_s`).
    #[serde(flatten)]
    pub run: RunOutput,
    /// When the point departs (moves a small fraction of the distance) [s];
    /// null if it does not.
    pub departure_s: Option<f64>,
    /// When their y displacements alone are that far apart [s] (the
    /// paper's Fig. 8 quantity); null if they are not.
    pub departure_y_s: Option<f64>,
}

/// The paper's switch-off values (Figs. 7–8).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct PaperSwitchOff {
    /// Time to 2 mm of travel, Fig. 7 [s].
    pub time_to_distance_s: f64,
    /// The paper's rigid model departs from the measurement in y, Fig. 8
    /// [s] (compare `rigid.departure_y_s`).
    pub rigid_departure_s: f64,
}

/// `switch-off --json`: the flexible run's values at the top level.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SwitchOffOutput {
    /// Model name.
    pub model: String,
    /// The tracked point's name (`BEAM:S` or a body).
    pub tracked_point: String,
    /// Parameters calibrated in the model (empty: a prediction).
    pub calibrated: Vec<Calibrated>,
    /// The built-in model's uncalibrated companion (F_x² at the blade tip)
    /// and its time, a prediction beside the fit; null for other models.
    pub uncalibrated: Option<Uncalibrated>,
    /// The analysis's warnings (the provenance block's list starts with them).
    pub warnings: Vec<String>,
    /// Travel distance of the tracked point [m].
    pub distance_m: f64,
    /// Travel direction (global, unit) [–].
    pub direction: [f64; 2],
    /// Time step [s].
    pub step_s: f64,
    /// End time [s].
    pub end_time_s: f64,
    /// Output sample rate [Hz].
    pub sample_rate_hz: f64,
    /// Time to the distance of the check run at half the step [s]; null
    /// without it or when not reached.
    pub half_step_time_to_distance_s: Option<f64>,
    /// The flexible model's run (its keys sit at the top level).
    #[serde(flatten)]
    pub flexible: RunOutput,
    /// The same for the model with every beam rigid (`--compare-rigid`),
    /// else null.
    pub rigid: Option<RigidRun>,
    /// The paper's values; null unless the model is the built-in one.
    pub paper: Option<PaperSwitchOff>,
    /// The paper's Fig. 10 study (`fig10`: the pre-stress doubled, c_t
    /// lowered, the spring's attachment −1 mm, alone and together; every
    /// time a prediction, `calibrated` says of what model); else null.
    pub fig10: Option<SwitchOffStudy>,
}

impl SwitchOffOutput {
    /// The document of `r`.
    pub fn new(r: &SwitchOffResult) -> Self {
        use crate::model::reference::{PAPER_RIGID_DEPARTURE_S, PAPER_TIME_TO_2MM_S};
        SwitchOffOutput {
            model: r.model.clone(),
            tracked_point: r.point_label.clone(),
            calibrated: r.calibrated.clone(),
            uncalibrated: r.uncalibrated.clone(),
            warnings: r.warnings.clone(),
            distance_m: r.settings.distance,
            direction: r.settings.direction,
            step_s: r.settings.step,
            end_time_s: r.settings.end_time,
            sample_rate_hz: r.settings.sample_rate,
            half_step_time_to_distance_s: r.half_step_time_s,
            flexible: RunOutput::new(&r.flexible),
            rigid: r.rigid.as_ref().map(|run| RigidRun {
                run: RunOutput::new(run),
                departure_s: r.departure_s,
                departure_y_s: r.departure_y_s,
            }),
            paper: r.builtin.then_some(PaperSwitchOff {
                time_to_distance_s: PAPER_TIME_TO_2MM_S,
                rigid_departure_s: PAPER_RIGID_DEPARTURE_S,
            }),
            fig10: None,
        }
    }
}
