//! Text, JSON, CSV and figure of a general `transient` run
//! ([`crate::analysis::simulate`]). JSON keys (DESIGN §7): `model`,
//! `step_s`, `end_time_s`, `steps`, `time_s`, `sensors` {id: samples},
//! `contacts` [{`id`, `max_penetration_m`, `max_force_n`, `impacts`,
//! `dissipated_j`, `force_n` (the normal force at the sample times [SI: N])}],
//! `energy`. The CSV has a column `load_<label>_force_n` per time-varying
//! load (its magnitude [SI: N], the force `frf` reads back) and
//! `contact_<id>_force_n` per contact.

use crate::analysis::simulate::{Simulation, SimulationSettings};
use crate::mechanics::load::load_magnitudes;
use crate::model::SensorQuantity;
use crate::output::plot::{Legend, LineFigure, Panel, Scale, Series};
use crate::output::records_uff::{records_uff, Record, RecordKind};

use std::fmt::Write;

/// Where the run started, as the table's header says it.
fn start_words(settings: &SimulationSettings, sim: &Simulation) -> &'static str {
    use crate::analysis::statics::start::Start;
    match (sim.from_equilibrium, settings.start) {
        (true, _) => ", from the static equilibrium under the loads at t = 0",
        (false, Start::Equilibrium) => ", from the reference (it balances the loads at t = 0)",
        (false, Start::Reference) => ", from the reference (as asked)",
    }
}

pub fn transient_table(model: &str, settings: &SimulationSettings, sim: &Simulation) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {model}: {} steps to {:.4e} s (step {:.2e} s, shortest {:.2e} s), {:.2} Newton iterations/step{}",
        sim.stats.steps,
        sim.step_time.last().copied().unwrap_or(0.0),
        settings.transient.step,
        sim.min_step,
        sim.stats.newton_iterations as f64 / sim.stats.steps.max(1) as f64,
        start_words(settings, sim)
    );
    if let Some(e) = &sim.failure {
        let _ = writeln!(
            s,
            "stopped early at the last accepted step, t = {:.6e} s: {}",
            sim.step_time.last().copied().unwrap_or(0.0),
            crate::error::chain_text(e)
        );
    }
    for (id, v) in &sim.sensors {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let last = v.last().copied().unwrap_or(f64::NAN);
        let _ = writeln!(
            s,
            "sensor {id}: min {lo:.6e}, max {hi:.6e}, final {last:.6e}"
        );
    }
    for c in &sim.contacts {
        let _ = writeln!(
            s,
            "contact {}: max penetration {:.3e} m, max force {:.4} N, {} impacts, dissipated {:.3e} J",
            c.id, c.max_penetration, c.max_force, c.impacts, c.dissipated
        );
    }
    let e = &sim.energy;
    let _ = writeln!(
        s,
        "energy balance: error {:.3e} J, {:.2e} of the {:.4e} J put in (at the start {:.4e} J, load work {:.4e} J)",
        e.error_j,
        e.relative_error(),
        e.put_in_j(),
        e.initial.kinetic_j + e.initial.strain_j + e.initial.spring_j,
        e.load_work_j,
    );
    let _ = writeln!(
        s,
        "dissipated: integrator (spectral radius {}) {:.4e} J, damping {:.4e} J, contacts {:.4e} J",
        crate::model::number::significant(settings.transient.spectral_radius, 4),
        e.numerical_dissipation_j,
        e.damping_dissipation_j,
        e.contact_dissipation_j
    );
    s
}

/// UFF 58 time data of a run sampled at a uniform rate: the force
/// magnitude |F₀|·f(t) of every time-varying load (at the sample times),
/// then every sensor (see [`super::records_uff`]).
pub fn transient_uff(sim: &Simulation, provenance: &[String; 2]) -> String {
    let forces = load_magnitudes(&sim.loads, &sim.time);
    let mut records: Vec<Record> = forces
        .iter()
        .map(|(name, v)| Record {
            name,
            kind: RecordKind::Force,
            values: v,
        })
        .collect();
    records.extend(
        sim.sensors
            .iter()
            .zip(&sim.quantities)
            .map(|((id, v), q)| Record {
                name: id,
                kind: RecordKind::Sensor(*q),
                values: v,
            }),
    );
    records_uff(&sim.time, &records, provenance)
}

pub fn transient_csv(sim: &Simulation) -> String {
    let mut s = String::from("time_s");
    for (id, _) in &sim.sensors {
        let _ = write!(s, ",{id}");
    }
    let loads = load_magnitudes(&sim.loads, &sim.time);
    for (label, _) in &loads {
        let _ = write!(s, ",load_{label}_force_n");
    }
    for c in &sim.contacts {
        let _ = write!(s, ",contact_{}_force_n", c.id);
    }
    s.push('\n');
    for (k, t) in sim.time.iter().enumerate() {
        let _ = write!(s, "{t:.9e}");
        for (_, v) in &sim.sensors {
            let _ = write!(s, ",{:.9e}", v[k]);
        }
        for (_, v) in &loads {
            let _ = write!(s, ",{:.9e}", v[k]);
        }
        for c in &sim.contacts {
            let _ = write!(s, ",{:.9e}", c.force_n[k]);
        }
        s.push('\n');
    }
    s
}

/// One panel per sensor against time in ms.
pub fn transient_figure(model: &str, sim: &Simulation) -> LineFigure {
    let mut fig = LineFigure::new(format!("Transient: {model}"), "Time", Scale::ms());
    for ((id, v), q) in sim.sensors.iter().zip(&sim.quantities) {
        let max = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let unit = match q {
            SensorQuantity::Displacement => "m",
            SensorQuantity::Velocity => "m/s",
            SensorQuantity::Acceleration => "m/s²",
        };
        let mut p = Panel::new(id.clone(), Scale::si(unit, max));
        p.series
            .push(Series::line(id.clone(), sim.time.clone(), v.clone()));
        p.legend = Legend::None;
        fig.panels.push(p);
    }
    fig
}
