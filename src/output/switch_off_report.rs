//! Text, JSON and CSV of the switch-off experiment. JSON keys follow
//! DESIGN §7: `model`, `tracked_point` (its name), `distance_m`,
//! `time_to_distance_s` (null when not reached), `ended_at_s` (null unless
//! the run failed after the distance), `node0` {`time_s`, `x_m`, `y_m`}
//! (the tracked point's absolute coordinates [SI: m]), `max_penetration_m`,
//! `contacts` [{…, `force_n`}] and `released_loads` {label: [N]} at the
//! sample times, `energy`, `rigid` (the same for the rigid model with its
//! `departure_s` and `departure_y_s`, or null), `calibrated` [{`name`, `value`, `target`, `achieved`, `standard_error`}]
//! (empty: a prediction), `warnings`, the half-step check, `paper`
//! (the paper's values; null unless the model is the built-in one) and
//! `fig10` (the paper's Fig. 10 study, [`study_table`] in text; null unless
//! asked for).

use crate::analysis::switch_off::{SwitchOffResult, DEPARTURE_FRACTION};
use crate::analysis::switch_off_study::SwitchOffStudy;

use std::fmt::Write;

pub use crate::model::reference::{PAPER_RIGID_DEPARTURE_S, PAPER_TIME_TO_2MM_S};

fn ms(t: Option<f64>) -> String {
    t.map_or_else(
        || String::from("not reached"),
        |t| format!("{:.4} ms", t * 1e3),
    )
}

/// Why the flexible run reports no time: how far the tracked point got
/// along the direction within the run.
fn short_of_distance(r: &SwitchOffResult) -> String {
    let run = &r.flexible;
    let end = run.time_s.last().copied().unwrap_or(0.0);
    format!(
        "  not reached: the tracked point travels at most {:.6} mm of the {:.6} mm along the direction in the run's {:.4} ms",
        run.max_travel_m(r.settings.direction) * 1e3,
        r.settings.distance * 1e3,
        end * 1e3
    )
}

/// The report printed by `switch-off`.
pub fn switch_off_table(r: &SwitchOffResult) -> String {
    let mut s = String::new();
    let d = r.settings.distance * 1e3;
    let _ = writeln!(
        s,
        "model {}: switch-off, {} travelling {d:.3} mm along ({}, {})",
        r.model, r.point_label, r.settings.direction[0], r.settings.direction[1]
    );
    if r.calibrated.is_empty() {
        let _ = writeln!(
            s,
            "calibrated: nothing; every time below is a prediction of the model"
        );
    }
    let _ = writeln!(s, "ON state: {}", r.flexible.on_state);
    for c in &r.calibrated {
        let _ = writeln!(
            s,
            "CALIBRATED: {} = {} to reproduce {} (a fit, not agreement)",
            c.name, c.value, c.target
        );
    }
    for w in &r.warnings {
        let _ = writeln!(s, "warning: {w}");
    }
    let _ = writeln!(s, "{:<34}{:>16}", "", "time to distance");
    if r.builtin {
        let _ = writeln!(
            s,
            "{:<34}{:>16}",
            "paper (Fig. 7, 2 mm, measured)",
            ms(Some(PAPER_TIME_TO_2MM_S))
        );
    }
    let flexible = r.flexible.time_to_distance_s;
    let fitted = r
        .calibrated
        .iter()
        .any(|c| c.target.starts_with("time_to_distance_s"));
    let label = if fitted {
        "this tool, flexible (calibrated)"
    } else {
        "this tool, flexible"
    };
    let _ = writeln!(s, "{label:<34}{:>16}", ms(flexible));
    if flexible.is_none() {
        let _ = writeln!(s, "{}", short_of_distance(r));
    }
    if let Some(h) = r.half_step_time_s {
        let change = match (h, flexible) {
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
    if let Some(u) = &r.uncalibrated {
        let _ = writeln!(
            s,
            "{:<34}{:>16} (a prediction: model {}, F_x² at the blade tip)",
            "this tool, uncalibrated",
            ms(u.time_to_distance_s),
            u.model
        );
    }
    if let Some(rigid) = &r.rigid {
        let against = match (rigid.time_to_distance_s, flexible) {
            (Some(a), Some(b)) => {
                format!(" (rigid {:+.1} % against flexible)", 100.0 * (a - b) / b)
            }
            _ => String::new(),
        };
        let _ = writeln!(
            s,
            "{:<34}{:>16}{against}",
            "this tool, rigid beams",
            ms(rigid.time_to_distance_s)
        );
        let at = |t: Option<f64>| {
            t.map_or_else(
                || String::from("not within the run"),
                |t| format!("{:.4} ms", t * 1e3),
            )
        };
        let limit = DEPARTURE_FRACTION * r.settings.distance * 1e3;
        let _ = writeln!(
            s,
            "rigid departs from flexible (> {limit:.3} mm apart): {} in the plane, {} in y",
            at(r.departure_s),
            at(r.departure_y_s),
        );
        if r.builtin {
            let _ = writeln!(
                s,
                "paper (Fig. 8): its rigid model departs from the measurement in y at ~{:.2} ms; the comparable quantity here is the y departure, with the flexible model in the measurement's place (a prediction)",
                PAPER_RIGID_DEPARTURE_S * 1e3
            );
        }
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
        "load work {:.4e} J, dissipated by the contacts {:.4e} J, the damping {:.4e} J and the integrator {:.4e} J, balance error {:.3e} J ({} the stored {:.4e} J)",
        e.load_work_j,
        e.contact_dissipation_j,
        e.damping_dissipation_j,
        e.numerical_dissipation_j,
        e.error_j,
        stored_share(e.error_j, e.stored_j),
        e.stored_j
    );
    let t = &r.flexible.time_s;
    for c in &r.flexible.contacts {
        let start = c.force_n.first().copied().unwrap_or(0.0);
        let opens = (start > 0.0)
            .then(|| c.force_n.iter().position(|&f| f == 0.0))
            .flatten()
            .map_or(String::new(), |k| {
                format!(", opens by {:.1} µs", t[k] * 1e6)
            });
        let _ = writeln!(
            s,
            "contact {}: ON force {start:.4} N{opens}, max penetration {:.3e} m, max force {:.3} N, {} impacts",
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

/// The balance error as a share of the energy stored at the start, in
/// words ("3.33e-4 of"; "with nothing stored, against" when none is).
fn stored_share(error: f64, stored: f64) -> String {
    if stored > 0.0 {
        format!("{:.2e} of", error.abs() / stored)
    } else {
        String::from("with nothing stored at the start, against")
    }
}

/// What a study's times are: predictions, of a model that calibrated
/// what it lists.
pub fn study_label(study: &SwitchOffStudy) -> String {
    if study.calibrated.is_empty() {
        String::from("every time a prediction; nothing calibrated")
    } else {
        let names: Vec<&str> = study.calibrated.iter().map(|c| c.name.as_str()).collect();
        format!(
            "the reference's model has {} CALIBRATED; every change is a prediction",
            names.join(", ")
        )
    }
}

/// The paper's Fig. 10 study printed after `switch-off`'s report.
pub fn study_table(study: &SwitchOffStudy, r: &SwitchOffResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "Fig. 10 study ({}): time for {} to travel {:.3} mm",
        study_label(study),
        r.point_label,
        r.settings.distance * 1e3
    );
    let _ = writeln!(
        s,
        "  {:<48}{:>12}{:>8}  the paper's text",
        "change", "time", "ratio"
    );
    for row in &study.rows {
        let ratio = row
            .ratio_to_reference
            .map_or_else(|| String::from("–"), |q| format!("{q:.3}"));
        let _ = writeln!(
            s,
            "  {:<48}{:>12}{ratio:>8}  {}",
            row.change,
            ms(row.time_to_distance_s),
            row.paper
        );
        if let Some(e) = &row.error {
            let _ = writeln!(s, "    failed: {e}");
        }
    }
    if let Some(q) = study.combined_ratio {
        let _ = writeln!(
            s,
            "all three together / reference = {q:.3} (a prediction), beside the paper's ≈ 1/3 ({:.3}; 2 mm in ≈ {:.1} ms)",
            study.paper_combined_ratio,
            study.paper_combined_time_s * 1e3
        );
    }
    s
}

/// Samples as CSV: time, flexible x, y, (if computed) rigid x, y, then the
/// flexible run's contact forces and released loads [SI: N].
pub fn switch_off_csv(r: &SwitchOffResult) -> String {
    let mut s = String::from("time_s,x_m,y_m");
    if r.rigid.is_some() {
        s.push_str(",rigid_x_m,rigid_y_m");
    }
    let f = &r.flexible;
    for c in &f.contacts {
        let _ = write!(s, ",contact_{}_force_n", c.id);
    }
    for (label, _) in &f.released_loads {
        let _ = write!(s, ",\"{label} force_n\"");
    }
    s.push('\n');
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
        let forces = f.contacts.iter().map(|c| &c.force_n);
        for v in forces.chain(f.released_loads.iter().map(|(_, v)| v)) {
            let _ = write!(s, ",{:.9e}", v[k]);
        }
        s.push('\n');
    }
    s
}
