//! `transient`: a general time integration of the model by generalized-α
//! (spectral radius ρ∞ [–]) over `end_time` [s] in steps of `step` [s],
//! shortened at contact onsets; from rest at the static equilibrium under
//! the loads at t = 0⁻ (released supports let go; the reference when it
//! balances them) or at the reference configuration. The sensors [m, m/s
//! or m/s²] are resampled at `sample_rate` [Hz]; the contacts' forces [N]
//! and the energy balance [J] come with them
//! ([`crate::analysis::simulate`]). A run that fails keeps what it computed
//! up to its last accepted step, and says so.

use super::{CommandError, ModelInput, Run};
use crate::analysis::impulse::ACQUISITION_RATE_HZ;
use crate::analysis::simulate::{simulate, EnergyBalance, Simulation, SimulationSettings};
use crate::analysis::statics::start::Start;
use crate::analysis::transient::TransientSettings;
use crate::output::figures::write_figure;
use crate::output::plot::PlotSize;
use crate::output::transient_report::{
    transient_csv, transient_figure, transient_table, transient_uff,
};
use crate::results::TransientOutput;
use crate::System;
use std::path::Path;

/// What `transient` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientRequest {
    /// End time [s] (> 0, longer than one step).
    pub end_time: f64,
    /// Time step [s] (> 0; shortened at contact onsets).
    pub step: f64,
    /// Spectral radius at infinity of generalized-α [–] (0 to 1).
    pub spectral_radius: f64,
    /// The state the run starts from at rest: the static equilibrium
    /// under the loads at t = 0⁻ (the default; the reference when it
    /// balances them) or the reference ([`Start`]).
    pub start: Start,
    /// Output sample rate [Hz] (≥ 0); 0 keeps every step.
    pub sample_rate: f64,
    /// Model every beam as a rigid body.
    pub rigid_beams: bool,
}

impl Default for TransientRequest {
    fn default() -> Self {
        let t = TransientSettings::default();
        TransientRequest {
            end_time: 0.01,
            step: t.step,
            spectral_radius: t.spectral_radius,
            start: Start::default(),
            sample_rate: ACQUISITION_RATE_HZ,
            rigid_beams: false,
        }
    }
}

/// `transient`'s output: the recorded run and the document.
#[derive(Debug)]
pub struct TransientRun {
    /// The integrated model's name (its beams rigid with `rigid_beams`).
    pub model_name: String,
    /// The settings it ran with.
    pub settings: SimulationSettings,
    /// The sensors' records, the contacts and the energy balance.
    pub simulation: Simulation,
    /// The document with the run's warnings.
    pub document: Run<TransientOutput>,
}

/// Runs `transient` on `input`.
pub fn run(input: &ModelInput, request: &TransientRequest) -> Result<TransientRun, CommandError> {
    super::checks::time_span(request.end_time, request.step)?;
    super::checks::spectral_radius(request.spectral_radius)?;
    super::checks::sample_rate(request.sample_rate)?;
    let model = match request.rigid_beams {
        true => input
            .model
            .all_beams_rigid()
            .validated()
            .map_err(|source| CommandError::RigidBeams {
                model: input.label(),
                source,
            })?,
        false => (*input.model).clone(),
    };
    let settings = SimulationSettings {
        transient: TransientSettings {
            step: request.step,
            end_time: request.end_time,
            spectral_radius: request.spectral_radius,
            damping: model.damping,
            ..TransientSettings::default()
        },
        start: request.start,
        sample_rate: request.sample_rate,
        keep_partial: true,
    };
    settings.transient.validate()?;
    let simulation = simulate(System::new(&model), &[], &settings)
        .map_err(|e| CommandError::simulation(input.label(), e))?;
    let output = TransientOutput::new(&model.name, &settings, &simulation);
    let mut own: Vec<String> = stopped_warning(&simulation).into_iter().collect();
    own.extend(energy_warning(&simulation.energy, request.spectral_radius));
    Ok(TransientRun {
        model_name: model.name.clone(),
        settings,
        simulation,
        document: Run::of(input, output).warn(input, own),
    })
}

/// The warning of a run that stopped before its end time: what failed,
/// and where the samples end.
fn stopped_warning(sim: &Simulation) -> Option<String> {
    let failure = sim.failure.as_ref()?;
    let last = sim.step_time.last().copied().unwrap_or(0.0);
    Some(format!(
        "the run stopped early: {}; the records end at the last accepted step, t = {last:.6e} s",
        crate::error::chain_text(failure)
    ))
}

/// An energy error above this fraction of the energy put in is a warning.
pub const ENERGY_WARNING_FRACTION: f64 = 1e-3;

/// The warning of a run whose energy balance misses by more than
/// [`ENERGY_WARNING_FRACTION`] of the energy put in, with what helps.
pub fn energy_warning(e: &EnergyBalance, spectral_radius: f64) -> Option<String> {
    let fraction = e.relative_error();
    if fraction <= ENERGY_WARNING_FRACTION {
        return None;
    }
    let (verb, help) = if e.error_j > 0.0 && spectral_radius >= 1.0 {
        (
            "gains",
            "generalized-α at a spectral radius of 1 dissipates nothing numerically, and with joints its energy can drift: a spectral radius below 1 (0.9) or a smaller step helps",
        )
    } else if e.error_j > 0.0 {
        ("gains", "a run at half the step tells whether it converges")
    } else {
        ("loses", "the integrator's own dissipation is booked apart, so a coarse step or the joints take it: a run at half the step tells whether it converges")
    };
    Some(format!(
        "energy balance: the run {verb} {:.3e} J unaccounted for, {} the {:.4e} J put in (energy at the start, load work, gravity): {help}",
        e.error_j.abs(),
        share(fraction),
        e.put_in_j(),
    ))
}

/// A fraction of what was put in, in words: "1.5 % of", "14630 times".
fn share(fraction: f64) -> String {
    let sig = |v: f64| crate::model::number::significant(v, 4);
    if !fraction.is_finite() {
        String::from("with nothing put in, against")
    } else if fraction < 1.0 {
        format!("{} % of", sig(100.0 * fraction))
    } else {
        format!("{} times", sig(fraction))
    }
}

impl TransientRun {
    /// The command line's report.
    pub fn text(&self) -> String {
        transient_table(&self.model_name, &self.settings, &self.simulation)
    }

    /// The samples as CSV (`--csv`): time [s], each sensor, each contact's
    /// force [N].
    pub fn csv(&self) -> String {
        transient_csv(&self.simulation)
    }

    /// The loads' and sensors' records as UFF 58 (`--uff`), stamped with
    /// the model's hash; UFF 58 time data are evenly sampled, so the run
    /// needs a sample rate above 0.
    pub fn uff(&self) -> Result<String, CommandError> {
        if self.settings.sample_rate <= 0.0 {
            return Err(CommandError::argument(
                "sample_rate",
                self.settings.sample_rate,
                "must be above 0 for UFF 58 (evenly sampled time data)",
            ));
        }
        let sha = self.document.model_sha256.as_deref().unwrap_or_default();
        let provenance = crate::results::provenance::header_lines(sha);
        Ok(transient_uff(&self.simulation, &provenance))
    }

    /// Draws each sensor against time to `path` (.svg or .png), as
    /// `--plot`.
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        let figure = transient_figure(&self.model_name, &self.simulation);
        write_figure(&figure.into(), path, PlotSize::default())?;
        Ok(())
    }
}
