//! The ON-state balance of moments about a ground pivot, at the reference
//! geometry: how the switch-off model sets a spring's preload from the
//! measured pre-stress forces (the paper's Table 4: F_x² and F_c).
//!
//! The moving assembly turns about the ground pin of its one `pin_slot`
//! contact; the pin–slot force acts along the line through the pin's
//! centre, so it has no moment about it. The moments [SI: N m] about that
//! centre of everything else that holds the assembly must vanish:
//!
//! M_loads + M_gravity + M_springs + F_c · a_c = 0,
//!
//! with the loads acting at t = 0⁻ (in full: a released load acts in the ON
//! state), gravity on every body at its centre of mass, every spring's
//! force at its reference length (the preload, or k(l − l₀)) on its
//! non-ground end, and the contact force F_c [SI: N] on the point of a
//! `point_line` contact along the line's normal towards the point's side,
//! a_c its arm [SI: m]. Internal forces (joints, torsion springs) have no
//! net moment. The equation is linear in the one spring's preload P:
//! M = M₀ + P·a_s, so it gives P for a measured F_c
//! ([`balanced_preload`]) or F_c for a given P ([`balance_contact_force`]).
//! At the reference geometry, not the deformed ON state: the ON state
//! found by the statics differs by the deformation (0.1 % of F_c on the
//! built-in model).

use crate::model::{Contact, Side};
use crate::model::{PointSpec, ValidModel};

/// Why a moment balance cannot be formed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BalanceError {
    #[error("the moment balance needs exactly one pin_slot contact with a ground pin as its pivot; the model has {found}")]
    Pivot { found: usize },
    #[error("no spring with id `{id}` (springs: {available})")]
    UnknownSpring { id: String, available: String },
    #[error("spring `{id}` has no preload to set (it gives its free_length)")]
    NoPreload { id: String },
    #[error("spring `{id}` must join the assembly to the ground (one end on the ground)")]
    NotGrounded { id: String },
    #[error("no point_line contact with id `{id}` (point_line contacts: {available})")]
    UnknownContact { id: String, available: String },
    #[error("contact `{id}` needs a ground line and a side for the balance")]
    ContactNotGrounded { id: String },
    #[error("joint `{id}` holds the assembly to the ground: a moment balance about the pivot alone does not apply")]
    GroundJoint { id: String },
    #[error("spring `{id}` has no arm about the pivot (its line passes through it)")]
    NoArm { id: String },
    #[error("a point of the balance cannot be placed: {why}")]
    Point { why: String },
}

/// The pieces of the balance: M₀ (everything but the spring's preload and
/// the contact) [SI: N m], the spring's arm a_s and the contact's a_c [SI: m].
struct Balance {
    rest: f64,
    spring_arm: f64,
    contact_arm: f64,
}

fn cross(r: [f64; 2], f: [f64; 2]) -> f64 {
    r[0] * f[1] - r[1] * f[0]
}

fn position(model: &ValidModel, p: &PointSpec) -> Result<[f64; 2], BalanceError> {
    if let Some(g) = p.ground {
        return Ok(g);
    }
    let resolved = model
        .resolve_point(p, "point")
        .map_err(|e| BalanceError::Point { why: e.to_string() })?;
    match resolved.explicit_position(model) {
        Some(x) => Ok(x),
        None => model
            .rigid_bodies
            .iter()
            .find(|b| Some(&b.id) == p.body.as_ref())
            .map(|b| b.position)
            .ok_or_else(|| BalanceError::Point {
                why: format!("{p:?}"),
            }),
    }
}

/// A spring's reference points a, b and the unit vector a → b [SI: m, –].
type Line = ([f64; 2], [f64; 2], [f64; 2]);

/// The reference points of a spring (a, b) and the unit vector a → b.
fn spring_line(model: &ValidModel, k: usize) -> Result<Line, BalanceError> {
    let s = &model.springs[k];
    let (a, b) = (position(model, &s.a)?, position(model, &s.b)?);
    let l = (b[0] - a[0]).hypot(b[1] - a[1]);
    Ok((a, b, [(b[0] - a[0]) / l, (b[1] - a[1]) / l]))
}

fn form(model: &ValidModel, spring: &str, contact: &str) -> Result<Balance, BalanceError> {
    let pivots: Vec<[f64; 2]> = model
        .contacts
        .iter()
        .filter_map(|c| match c {
            Contact::PinSlot { pin, .. } => pin.ground,
            Contact::PointLine { .. } => None,
        })
        .collect();
    let [pivot] = pivots[..] else {
        return Err(BalanceError::Pivot {
            found: pivots.len(),
        });
    };
    if let Some(j) = model
        .joints
        .iter()
        .find(|j| j.a.ground.is_some() || j.b.ground.is_some())
    {
        return Err(BalanceError::GroundJoint {
            id: j.id.clone().unwrap_or_default(),
        });
    }
    let arm = |x: [f64; 2], f: [f64; 2]| cross([x[0] - pivot[0], x[1] - pivot[1]], f);
    let mut rest = 0.0;
    for load in &model.loads {
        use crate::model::TimeFunction as F;
        let acts = match load.time {
            F::Constant | F::RampDown { .. } => true,
            F::Until(until) => until >= 0.0,
            F::Step { start } => start <= 0.0,
            F::HalfSine { .. } => false,
        };
        if !acts {
            continue;
        }
        let x = position(model, &load.at)?;
        let f = match load.frame {
            crate::model::LoadFrame::Global => load.force,
            crate::model::LoadFrame::Beam => {
                let beam = model
                    .beams
                    .iter()
                    .find(|b| Some(&b.id) == load.at.beam.as_ref())
                    .ok_or_else(|| BalanceError::Point {
                        why: String::from("a beam-frame load off a beam"),
                    })?;
                let t = beam.tangent();
                [
                    t[0] * load.force[0] - t[1] * load.force[1],
                    t[1] * load.force[0] + t[0] * load.force[1],
                ]
            }
        };
        rest += arm(x, f);
    }
    let g = model.gravity;
    let weight = |m: f64, x: [f64; 2]| arm(x, [m * g[0], m * g[1]]);
    for b in &model.beams {
        let m = b.material.density * b.section.area() * b.length;
        rest += weight(m, b.point_at(0.5 * b.length));
    }
    rest += model
        .rigid_bodies
        .iter()
        .map(|b| weight(b.mass, b.position))
        .sum::<f64>();
    rest += model
        .point_masses
        .iter()
        .map(|p| weight(p.mass, p.position))
        .sum::<f64>();
    let ids: Vec<String> = model.springs.iter().filter_map(|s| s.id.clone()).collect();
    let chosen = model
        .springs
        .iter()
        .position(|s| s.id.as_deref() == Some(spring))
        .ok_or_else(|| BalanceError::UnknownSpring {
            id: spring.to_string(),
            available: ids.join(", "),
        })?;
    let mut spring_arm = 0.0;
    for (k, s) in model.springs.iter().enumerate() {
        let (a, b, e) = spring_line(model, k)?;
        // Tension T pulls b towards a and a towards b; only the end off
        // the ground acts on the assembly.
        let unit_moment = match (s.a.ground.is_some(), s.b.ground.is_some()) {
            (true, false) => arm(b, [-e[0], -e[1]]),
            (false, true) => arm(a, e),
            (false, false) => 0.0,
            (true, true) => continue,
        };
        let id = || s.id.clone().unwrap_or_else(|| format!("springs[{k}]"));
        if k == chosen {
            if s.preload.is_none() {
                return Err(BalanceError::NoPreload { id: id() });
            }
            if s.a.ground.is_some() == s.b.ground.is_some() {
                return Err(BalanceError::NotGrounded { id: id() });
            }
            if unit_moment.abs() <= 1e-12 * model_size(a, b) {
                return Err(BalanceError::NoArm { id: id() });
            }
            spring_arm = unit_moment;
        } else {
            let tension = match (s.preload, s.free_length) {
                (Some(p), _) => p,
                (None, Some(l0)) => s.stiffness * ((b[0] - a[0]).hypot(b[1] - a[1]) - l0),
                (None, None) => 0.0,
            };
            rest += tension * unit_moment;
        }
    }
    let point_lines: Vec<&Contact> = model
        .contacts
        .iter()
        .filter(|c| matches!(c, Contact::PointLine { .. }))
        .collect();
    let Some(Contact::PointLine {
        point, line, side, ..
    }) = point_lines.iter().find(|c| c.id() == contact).copied()
    else {
        return Err(BalanceError::UnknownContact {
            id: contact.to_string(),
            available: point_lines
                .iter()
                .map(|c| c.id().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        });
    };
    let (Some(true), Some(side)) = (line.ground, side) else {
        return Err(BalanceError::ContactNotGrounded {
            id: contact.to_string(),
        });
    };
    let d = [line.to[0] - line.from[0], line.to[1] - line.from[1]];
    let l = d[0].hypot(d[1]);
    // The normal towards the point's side of from → to.
    let n = match side {
        Side::Left => [-d[1] / l, d[0] / l],
        Side::Right => [d[1] / l, -d[0] / l],
    };
    let contact_arm = arm(position(model, point)?, n);
    Ok(Balance {
        rest,
        spring_arm,
        contact_arm,
    })
}

fn model_size(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1]).max(f64::MIN_POSITIVE)
}

/// The preload [SI: N, tension positive] of spring `spring` that balances,
/// about the pivot, the loads, gravity, the other springs and a force
/// `contact_force_n` [SI: N] on the point of contact `contact` (module doc).
pub fn balanced_preload(
    model: &ValidModel,
    spring: &str,
    contact: &str,
    contact_force_n: f64,
) -> Result<f64, BalanceError> {
    let b = form(model, spring, contact)?;
    Ok(-(b.rest + contact_force_n * b.contact_arm) / b.spring_arm)
}

/// The force [SI: N] on contact `contact` that the balance about the pivot
/// leaves with spring `spring` at its model preload (module doc).
pub fn balance_contact_force(
    model: &ValidModel,
    spring: &str,
    contact: &str,
) -> Result<f64, BalanceError> {
    let b = form(model, spring, contact)?;
    let k = model
        .springs
        .iter()
        .position(|s| s.id.as_deref() == Some(spring))
        .expect("form found the spring");
    let p = model.springs[k].preload.expect("form checked the preload");
    if b.contact_arm == 0.0 {
        return Err(BalanceError::Point {
            why: format!("contact `{contact}`'s force has no arm about the pivot"),
        });
    }
    Ok(-(b.rest + p * b.spring_arm) / b.contact_arm)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;

    /// The built-in model's preload (11.06 N compression) was set from this
    /// balance with the measured F_c = 2.92 N (its description), and so was
    /// its uncalibrated companion's (36.47 N, F_x² at the tip).
    #[test]
    fn builtin_preload_is_the_balance_with_the_measured_contact_force() {
        for (m, preload) in [
            (Model::switch_off_builtin(), -11.06),
            (Model::switch_off_uncalibrated_builtin(), -36.47),
        ] {
            let p = balanced_preload(&m, "helical_spring", "fixed_contact", 2.92).unwrap();
            let f = balance_contact_force(&m, "helical_spring", "fixed_contact").unwrap();
            assert!(
                (p - preload).abs() < 0.005,
                "{}: preload {p}, contact force {f}",
                m.name
            );
            assert!((f - 2.92).abs() < 1e-3, "{}: contact force {f}", m.name);
        }
    }
}
