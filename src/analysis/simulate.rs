//! A general time simulation: optionally the static equilibrium first (the
//! loads at t = 0, e.g. a pre-stress released later), then the
//! generalized-α transient with contacts; sensors and tracked points
//! recorded at every step and resampled at a uniform rate, contact
//! statistics, and the energy balance.
//!
//! Energy balance [SI: J]: with T = ½q̇ᵀMq̇, U the strain energy of beams,
//! springs and contacts, V = −f_gᵀq the gravity potential (the generalized
//! gravity force f_g is constant), W = Σ ½(Q₀ + Q₁)ᵀΔq the work of the
//! applied loads over the steps, D the energy the contacts and the
//! model's damping dissipated and D_num the energy the integrator removed
//! (ρ∞ < 1; [`super::transient::ledger`]), the balance error is
//! (T + U + V)(t) − (T + U + V)(0) − W + D + D_num. The terms are the
//! scheme's own discrete work, so for linear forces and joints the error
//! is round-off; what it holds is the quadrature's error on nonlinear
//! forces, the joints' work and the Newton tolerance.

use super::impulse::sensor::SensorProbe;
use super::statics::start::{starting_equilibrium, Start};
use super::statics::Equilibrium;
use super::transient::contacts::ContactStats;
use super::transient::{Integrator, RunStats, State, TransientSettings, RELEASE_LOAD_TIME};
use crate::error::{SimulationError, TransientError};
use crate::linalg::vector::dot;
use crate::mechanics::anchor::Anchor;
use crate::signal::resample::resample_uniform;
use crate::system::System;

/// Settings of a simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct SimulationSettings {
    pub transient: TransientSettings,
    /// Start from the static equilibrium under the loads at t = 0⁻ (the
    /// reference when it balances them) or from the reference at rest
    /// ([`super::statics::start`]).
    pub start: Start,
    /// Output sample rate [SI: Hz]; 0 keeps every step.
    pub sample_rate: f64,
    /// When the integration fails (a Newton failure, a singular iteration
    /// matrix), return what was computed up to the last accepted step with
    /// the failure in [`Simulation::failure`] instead of an error: the
    /// caller decides whether the run served its purpose.
    pub keep_partial: bool,
}

/// Energies at one time [SI: J].
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct Energies {
    /// Kinetic energy [J].
    pub kinetic_j: f64,
    /// Beam strain energy (axial + bending) [J].
    pub strain_j: f64,
    /// Springs, torsion springs and contacts (elastic part) [J].
    pub spring_j: f64,
    /// Potential energy of gravity [J].
    pub gravity_j: f64,
}

impl Energies {
    pub fn total(&self) -> f64 {
        self.kinetic_j + self.strain_j + self.spring_j + self.gravity_j
    }
}

/// The energy balance of a run [SI: J].
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct EnergyBalance {
    pub initial: Energies,
    #[serde(rename = "final")]
    pub end: Energies,
    /// Work of the applied loads.
    pub load_work_j: f64,
    /// Dissipated by the contacts (damping and friction).
    pub contact_dissipation_j: f64,
    /// Dissipated by the model's damping (the springs' dampers and the
    /// Rayleigh damping C q̇), Σ ½(D₀ + D₁)ᵀΔq.
    pub damping_dissipation_j: f64,
    /// Removed by the integrator itself, the numerical damping of a
    /// spectral radius below 1 (0 at 1): Σ ½(a₀ + a₁)ᵀMΔq − ½(v₀ + v₁)ᵀMΔv.
    pub numerical_dissipation_j: f64,
    /// (T + U + V)(end) − (T + U + V)(0) − W + D + D_num.
    pub error_j: f64,
    /// The elastic energy stored at the start, U(0) (beams, springs,
    /// contacts): the scale of the error.
    pub stored_j: f64,
}

impl EnergyBalance {
    /// The energy put into the run [SI: J]: the kinetic, strain and
    /// spring energy at the start, the loads' work (its magnitude) and the
    /// potential energy gravity gave up.
    pub fn put_in_j(&self) -> f64 {
        let (i, e) = (&self.initial, &self.end);
        i.kinetic_j
            + i.strain_j
            + i.spring_j
            + self.load_work_j.abs()
            + (i.gravity_j - e.gravity_j).max(0.0)
    }

    /// The error as a fraction of the energy put in (infinite for an
    /// error where nothing was put in, 0 for none).
    pub fn relative_error(&self) -> f64 {
        if self.error_j == 0.0 {
            0.0
        } else {
            self.error_j.abs() / self.put_in_j()
        }
    }
}

/// A recorded run.
#[derive(Debug, Clone)]
pub struct Simulation {
    /// Sample times [SI: s].
    pub time: Vec<f64>,
    /// Sensor id and its samples [SI: m, m/s or m/s²].
    pub sensors: Vec<(String, Vec<f64>)>,
    /// What each sensor measures.
    pub quantities: Vec<crate::model::SensorQuantity>,
    /// Tracked points: x and y samples [SI: m].
    pub points: Vec<[Vec<f64>; 2]>,
    /// Every step: time and tracked points (for event times).
    pub step_time: Vec<f64>,
    pub step_points: Vec<[Vec<f64>; 2]>,
    /// What each contact saw, with its normal force at the sample times.
    pub contacts: Vec<ContactStats>,
    /// The failure that ended the run early (only with
    /// [`SimulationSettings::keep_partial`]); the samples end at the last
    /// accepted step, `step_time`'s last entry.
    pub failure: Option<TransientError>,
    pub energy: EnergyBalance,
    pub stats: RunStats,
    /// Shortest step taken [SI: s].
    pub min_step: f64,
    /// Whether the run started from a solved static equilibrium (else
    /// from the reference at rest).
    pub from_equilibrium: bool,
    /// Static iterations spent on the initial equilibrium.
    pub static_iterations: usize,
    /// The applied loads of the integrated system (released supports'
    /// reactions among them).
    pub loads: Vec<crate::mechanics::load::PointLoad>,
}

fn energies(sys: &System, gravity: &[f64], st: &State) -> Energies {
    let u = sys.strain_energy(&st.q);
    Energies {
        kinetic_j: 0.5 * sys.mass().quadratic_form(&st.v),
        strain_j: u.axial + u.bending,
        spring_j: u.springs,
        gravity_j: -dot(gravity, &st.q),
    }
}

/// The output sample rate must be zero (every step) or positive and finite.
fn check_sample_rate(settings: &SimulationSettings) -> Result<(), SimulationError> {
    if settings.sample_rate >= 0.0 && settings.sample_rate.is_finite() {
        Ok(())
    } else {
        Err(SimulationError::InvalidSetting {
            setting: crate::error::Setting::SampleRate,
            allowed: "zero (every step) or positive, and finite",
            value: settings.sample_rate,
        })
    }
}

/// The applied loads' work over the steps, Σ ½(Q₀ + Q₁)ᵀΔq [SI: J]:
/// the trapezoidal rule in q, as the integrator's energy books
/// ([`super::transient::ledger`]).
struct LoadWork {
    /// Q_loads and q at the last state observed.
    force: Vec<f64>,
    q: Vec<f64>,
    scratch: Vec<f64>,
    /// The time the first state's loads are taken at: the one its
    /// accelerations were computed with.
    first_load_time: f64,
    observed: bool,
    /// The work so far [SI: J].
    work: f64,
}

impl LoadWork {
    fn new(n: usize, first_load_time: f64) -> Self {
        LoadWork {
            force: vec![0.0; n],
            q: vec![0.0; n],
            scratch: vec![0.0; n],
            first_load_time,
            observed: false,
            work: 0.0,
        }
    }

    fn observe(&mut self, sys: &System, st: &State) {
        let now = &mut self.scratch;
        now.fill(0.0);
        let t = if self.observed {
            st.t
        } else {
            self.first_load_time
        };
        for l in &sys.loads {
            l.add_generalized_force(&st.q, t, 1.0, now);
        }
        if self.observed {
            self.work += now
                .iter()
                .zip(&self.force)
                .zip(st.q.iter().zip(&self.q))
                .map(|((f1, f0), (q1, q0))| 0.5 * (f0 + f1) * (q1 - q0))
                .sum::<f64>();
        }
        self.observed = true;
        std::mem::swap(&mut self.force, &mut self.scratch);
        self.q.copy_from_slice(&st.q);
    }
}

/// Run a simulation of `sys`, tracking the material points `points`
/// (anchors of `sys`). From the equilibrium, released supports
/// ([`System::release_supports`]) let go; without it a model with released
/// supports is refused (there is no hold to release).
pub fn simulate(
    sys: System,
    points: &[Anchor],
    settings: &SimulationSettings,
) -> Result<Simulation, SimulationError> {
    check_sample_rate(settings)?;
    let start = starting_equilibrium(&sys, settings.start)?;
    simulate_from(sys, start, points, settings)
}

/// [`simulate`] from a static equilibrium of `sys` the caller found (e.g.
/// continued from another design,
/// [`super::statics::design_path::on_state_equilibrium`]), or from the
/// reference at rest when `start` is `None`.
pub fn simulate_from(
    sys: System,
    start: Option<Equilibrium>,
    points: &[Anchor],
    settings: &SimulationSettings,
) -> Result<Simulation, SimulationError> {
    check_sample_rate(settings)?;
    let n = sys.ndof();
    let (sys, start) = match start {
        Some(eq) => {
            let released = sys.release_supports(&eq.q, &eq.lambda);
            (released, Some(eq))
        }
        None => match sys.released.first() {
            Some(r) => {
                return Err(SimulationError::ReleaseNeedsEquilibrium {
                    joint: sys.constraints[r.constraint].label().to_string(),
                })
            }
            None => (sys, None),
        },
    };
    let sys = &sys;
    let from_equilibrium = start.is_some();
    let mut integ = Integrator::new(sys, settings.transient)?;
    let (mut state, static_iterations) = match start {
        Some(eq) => (
            integ.state_after_release(eq.q, vec![0.0; n])?,
            eq.iterations,
        ),
        None => (integ.initial_state()?, 0),
    };
    let probes: Vec<SensorProbe> = sys
        .sensors
        .iter()
        .map(|s| SensorProbe::new(sys, s))
        .collect();
    let mut gravity = vec![0.0; n];
    sys.add_gravity(&mut gravity);
    let initial = energies(sys, &gravity, &state);
    let mut step_time = Vec::new();
    let mut readings: Vec<Vec<f64>> = vec![Vec::new(); probes.len()];
    let mut tracks: Vec<[Vec<f64>; 2]> = vec![[Vec::new(), Vec::new()]; points.len()];
    // The first state's loads as its accelerations took them (from an
    // equilibrium, released supports already let go).
    let first_load_time = if from_equilibrium {
        RELEASE_LOAD_TIME
    } else {
        0.0
    };
    let mut work = LoadWork::new(n, first_load_time);
    let mut min_step = f64::INFINITY;
    let mut forces: Vec<Vec<f64>> = vec![Vec::new(); sys.contacts.len()];
    let mut observe = |st: &State, contact_force: &[f64]| {
        work.observe(sys, st);
        step_time.push(st.t);
        for (r, probe) in readings.iter_mut().zip(&probes) {
            r.push(probe.read(st));
        }
        for (track, a) in tracks.iter_mut().zip(points) {
            let r = sys.user_point(a.position(&st.q));
            track[0].push(r.x);
            track[1].push(r.y);
        }
        for (f, &now) in forces.iter_mut().zip(contact_force) {
            f.push(now);
        }
    };
    // The integrator's `run`, with the contact forces observed and a
    // failure kept when the caller asks.
    observe(&state, &integ.contacts.force);
    let t_end = state.t + settings.transient.steps() as f64 * settings.transient.step;
    let mut failure = None;
    while t_end - state.t > 1e-9 * settings.transient.step {
        match integ.advance(&mut state, t_end) {
            Ok(()) => {
                // The step taken (differences of the times t₀ + k·h would
                // show round-off of the times, not of the steps).
                min_step = min_step.min(integ.current_step());
                observe(&state, &integ.contacts.force);
            }
            Err(e) if settings.keep_partial && step_time.len() > 1 => {
                failure = Some(e);
                break;
            }
            Err(e) => return Err(e.into()),
        }
    }
    let stats = integ.stats;
    let end = energies(sys, &gravity, &state);
    let dissipated = (integ.contacts.stats.iter()).fold(0.0, |d, c| d + c.dissipated);
    let energy = EnergyBalance {
        initial,
        end,
        load_work_j: work.work,
        contact_dissipation_j: dissipated,
        damping_dissipation_j: stats.damping_dissipation,
        numerical_dissipation_j: stats.numerical_dissipation,
        error_j: end.total() - initial.total() - work.work
            + dissipated
            + stats.damping_dissipation
            + stats.numerical_dissipation,
        stored_j: initial.strain_j + initial.spring_j,
    };
    // Samples: linear interpolation between the steps at the sample rate,
    // or every step. The step times increase strictly (every step is
    // longer than 0) and the readings are finite (Newton rejects a
    // non-finite iterate), as the resampler requires.
    let sample = |y: &[f64]| -> Vec<f64> {
        if settings.sample_rate > 0.0 && step_time.len() > 1 {
            resample_uniform(&step_time, y, settings.sample_rate)
                .expect("increasing step times and finite readings")
        } else {
            y.to_vec()
        }
    };
    let sensors: Vec<(String, Vec<f64>)> = probes
        .iter()
        .zip(&readings)
        .map(|(p, r)| (p.id().to_string(), sample(r)))
        .collect();
    let sampled: Vec<[Vec<f64>; 2]> = tracks.iter().map(|[x, y]| [sample(x), sample(y)]).collect();
    let mut contacts = integ.contacts.stats.clone();
    for (c, f) in contacts.iter_mut().zip(&forces) {
        c.force_n = sample(f);
    }
    let count = sample(&step_time).len();
    let time: Vec<f64> = if settings.sample_rate > 0.0 && step_time.len() > 1 {
        (0..count)
            .map(|k| k as f64 / settings.sample_rate)
            .collect()
    } else {
        step_time.clone()
    };
    Ok(Simulation {
        time,
        sensors,
        quantities: probes.iter().map(|p| p.point.quantity).collect(),
        points: sampled,
        step_time,
        step_points: tracks,
        contacts,
        failure,
        energy,
        stats,
        min_step,
        from_equilibrium,
        static_iterations,
        loads: sys.loads.clone(),
    })
}

/// The first time the displacement of a tracked point (x, y samples at
/// `time`) along the unit direction `dir` reaches `distance`, by linear
/// interpolation; `None` if it never does.
pub fn time_to_distance(
    time: &[f64],
    [x, y]: &[Vec<f64>; 2],
    dir: [f64; 2],
    distance: f64,
) -> Option<f64> {
    let s: Vec<f64> = x
        .iter()
        .zip(y)
        .map(|(a, b)| (a - x[0]) * dir[0] + (b - y[0]) * dir[1])
        .collect();
    let k = s.iter().position(|&v| v >= distance)?;
    if k == 0 {
        return Some(time[0]);
    }
    let w = (distance - s[k - 1]) / (s[k] - s[k - 1]);
    Some(time[k - 1] + w * (time[k] - time[k - 1]))
}
