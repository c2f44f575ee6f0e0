//! Text, JSON and CSV of the switch-off experiment. JSON keys follow
//! DESIGN §7: `model`, `distance_m`, `time_to_distance_s` (null when not
//! reached), `node0` {`time_s`, `x_m`, `y_m`} (absolute coordinates),
//! `max_penetration_m`, `energy`, `rigid` (the same for the rigid model, or
//! null), plus the half-step check, the departure time and the paper's
//! values.

use crate::analysis::switch_off::{SwitchOffResult, SwitchOffRun, DEPARTURE_FRACTION};
use serde_json::{json, Value};
use std::fmt::Write;

/// Paper, Fig. 7: ~2 mm at ~1.75 ms.
pub const PAPER_TIME_TO_2MM_S: f64 = 1.75e-3;
/// Paper, Fig. 8: the rigid model departs after ~1.26 ms.
pub const PAPER_RIGID_DEPARTURE_S: f64 = 1.26e-3;

fn run_json(run: &SwitchOffRun) -> Value {
    json!({
        "time_to_distance_s": run.time_to_distance_s,
        "node0": {"time_s": run.time_s, "x_m": run.x_m, "y_m": run.y_m},
        "max_penetration_m": run.max_penetration_m,
        "contacts": run.contacts,
        "energy": run.energy,
        "steps": run.steps,
        "newton_iterations": run.newton_iterations,
        "min_step_s": run.min_step_s,
    })
}

/// The whole result as one JSON document.
pub fn switch_off_json(r: &SwitchOffResult) -> Value {
    let mut doc = run_json(&r.flexible);
    let o = doc.as_object_mut().expect("an object");
    o.insert("model".into(), json!(r.model));
    o.insert("distance_m".into(), json!(r.settings.distance));
    o.insert("direction".into(), json!(r.settings.direction));
    o.insert("step_s".into(), json!(r.settings.step));
    o.insert("end_time_s".into(), json!(r.settings.end_time));
    o.insert("sample_rate_hz".into(), json!(r.settings.sample_rate));
    o.insert(
        "half_step_time_to_distance_s".into(),
        json!(r.half_step_time_s),
    );
    o.insert(
        "rigid".into(),
        r.rigid.as_ref().map_or(Value::Null, run_json),
    );
    o.insert("rigid_departure_s".into(), json!(r.departure_s));
    o.insert(
        "paper".into(),
        json!({"time_to_distance_s": PAPER_TIME_TO_2MM_S, "rigid_departure_s": PAPER_RIGID_DEPARTURE_S}),
    );
    doc
}

fn ms(t: Option<f64>) -> String {
    t.map_or_else(
        || String::from("not reached"),
        |t| format!("{:.4} ms", t * 1e3),
    )
}

/// The report printed by `switch-off`.
pub fn switch_off_table(r: &SwitchOffResult) -> String {
    let mut s = String::new();
    let d = r.settings.distance * 1e3;
    let _ = writeln!(
        s,
        "model {}: switch-off, node 0 travelling {d:.3} mm along ({}, {})",
        r.model, r.settings.direction[0], r.settings.direction[1]
    );
    let _ = writeln!(s, "{:<34}{:>16}", "", "time to distance");
    let _ = writeln!(
        s,
        "{:<34}{:>16}",
        "paper (Fig. 7, 2 mm)",
        ms(Some(PAPER_TIME_TO_2MM_S))
    );
    let _ = writeln!(
        s,
        "{:<34}{:>16}",
        "this tool, flexible",
        ms(r.flexible.time_to_distance_s)
    );
    if let Some(h) = r.half_step_time_s {
        let change = match (h, r.flexible.time_to_distance_s) {
            (a, Some(b)) => format!(" ({:+.2e} relative)", (a - b) / b),
            _ => String::new(),
        };
        let _ = writeln!(
            s,
            "{:<34}{:>16}{change}",
            "this tool, flexible, half step",
            ms(Some(h))
        );
    }
    if let Some(rigid) = &r.rigid {
        let _ = writeln!(
            s,
            "{:<34}{:>16}",
            "this tool, rigid beams",
            ms(rigid.time_to_distance_s)
        );
        let _ = writeln!(
            s,
            "rigid departs from flexible (> {:.0} % of the distance apart): {} (paper: ~{:.2} ms)",
            100.0 * DEPARTURE_FRACTION,
            r.departure_s.map_or_else(
                || String::from("not within the run"),
                |t| format!("{:.4} ms", t * 1e3)
            ),
            PAPER_RIGID_DEPARTURE_S * 1e3
        );
    }
    let e = &r.flexible.energy;
    let _ = writeln!(
        s,
        "energy [J]: kinetic {:.4e} → {:.4e}, beams {:.4e} → {:.4e}, springs+contacts {:.4e} → {:.4e}, gravity {:.4e} → {:.4e}",
        e.initial.kinetic_j, e.end.kinetic_j, e.initial.strain_j, e.end.strain_j,
        e.initial.spring_j, e.end.spring_j, e.initial.gravity_j, e.end.gravity_j
    );
    let _ = writeln!(
        s,
        "load work {:.4e} J, contact dissipation {:.4e} J, balance error {:.3e} J ({:.2e} of the stored {:.4e} J)",
        e.load_work_j,
        e.contact_dissipation_j,
        e.error_j,
        e.error_j.abs() / e.stored_j.max(f64::MIN_POSITIVE),
        e.stored_j
    );
    for c in &r.flexible.contacts {
        let _ = writeln!(
            s,
            "contact {}: max penetration {:.3e} m, max force {:.3} N, {} impacts",
            c.id, c.max_penetration, c.max_force, c.impacts
        );
    }
    let _ = writeln!(
        s,
        "{} steps (shortest {:.2e} s), {:.2} Newton iterations/step",
        r.flexible.steps,
        r.flexible.min_step_s,
        r.flexible.newton_iterations as f64 / r.flexible.steps.max(1) as f64
    );
    s
}

/// Samples as CSV: time, flexible x, y and (if computed) rigid x, y.
pub fn switch_off_csv(r: &SwitchOffResult) -> String {
    let mut s = String::from("time_s,x_m,y_m");
    if r.rigid.is_some() {
        s.push_str(",rigid_x_m,rigid_y_m");
    }
    s.push('\n');
    let f = &r.flexible;
    for k in 0..f.time_s.len() {
        let _ = write!(s, "{:.9e},{:.9e},{:.9e}", f.time_s[k], f.x_m[k], f.y_m[k]);
        if let Some(rigid) = &r.rigid {
            let (x, y) = (rigid.x_m.get(k), rigid.y_m.get(k));
            let _ = write!(
                s,
                ",{},{}",
                x.map_or(String::new(), |v| format!("{v:.9e}")),
                y.map_or(String::new(), |v| format!("{v:.9e}"))
            );
        }
        s.push('\n');
    }
    s
}
