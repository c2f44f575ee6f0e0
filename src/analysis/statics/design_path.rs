//! Continuation in a design parameter: the equilibrium of a changed design
//! found from the equilibrium of a known one.
//!
//! A pre-stressed assembly held by a contact (the switch-off's ON state:
//! the spring's preload against F_x², the pad against the fixed contact)
//! has no equilibrium with part of its pre-stress, so the load-factor
//! continuation of [`super::solve_equilibrium`] can fail for a design far
//! from the one it was made for. Here the designs form a path τ ∈ [0, 1]
//! (the caller builds the system at each τ, e.g. a parameter interpolated
//! from the known design at τ = 0 to the wanted one at τ = 1); the
//! equilibrium at τ = 0 is solved as usual, then each step starts Newton's
//! method ([`super::continue_equilibrium`] at the full load factor) from
//! the last converged state. Step control: the step doubles after a step
//! that converged, is quartered after one that did not, and the path gives
//! up below [`MIN_STEP`]. After every step the contacts that were closed at
//! τ = 0 must still be, and the result must balance (checked
//! independently): a contact that opens, or whose force has faded below
//! [`FADED`] of its start where the path stalls, means that the design has
//! no equilibrium with it closed (the answer, not a failure of the method).
//!
//! [`on_state_equilibrium`] is what the switch-off uses: the path is the
//! straight line between two designs of one assembly
//! ([`Model::path_to`]), from a known design (the built-in model, or the
//! swept one) to the wanted one.

use super::{continue_equilibrium, solve_equilibrium, Equilibrium, StaticSettings};
use crate::error::AnalysisError;
pub use crate::error::DesignPathError;
use crate::mechanics::spring::ForceElement;
use crate::model::Model;
use crate::system::System;

/// Smallest step in τ before the path gives up.
pub const MIN_STEP: f64 = 1.0 / 4096.0;
/// A contact closed at the start whose force has fallen below this
/// fraction of its starting force where the path stalls is taken to open
/// there (its stiffness vanishes with its force, so Newton's method cannot
/// follow it through).
const FADED: f64 = 0.05;
/// First step in τ.
const FIRST_STEP: f64 = 0.25;

/// The equilibrium at τ = 1 of the systems `build(τ)`, by continuation from
/// τ = 0 (see the module doc); also the number of path steps taken.
pub fn equilibrium_along(
    build: impl Fn(f64) -> System,
    settings: &StaticSettings,
) -> Result<(Equilibrium, usize), DesignPathError> {
    let start = build(0.0);
    let mut eq = solve_equilibrium(&start, settings).map_err(DesignPathError::Start)?;
    let closed: Vec<usize> = (0..start.contacts.len())
        .filter(|&i| start.contacts[i].elastic_force(&eq.q) > 0.0)
        .collect();
    let initial: Vec<f64> = closed
        .iter()
        .map(|&i| start.contacts[i].elastic_force(&eq.q))
        .collect();
    let (mut tau, mut step, mut steps) = (0.0f64, FIRST_STEP, 0usize);
    while tau < 1.0 {
        let next = (tau + step).min(1.0);
        let sys = build(next);
        let step_result = continue_equilibrium(&sys, &eq, eq.load_scale, settings)
            .and_then(|found| balanced(&sys, found));
        match step_result {
            Ok(found) => {
                if let Some(&i) = closed
                    .iter()
                    .find(|&&i| sys.contacts[i].elastic_force(&found.q) <= 0.0)
                {
                    return Err(DesignPathError::ContactOpens {
                        contact: sys.contacts[i].label.clone(),
                        at: next,
                    });
                }
                eq = found;
                tau = next;
                steps += 1;
                step = (2.0 * step).min(1.0);
            }
            Err(source) => {
                step *= 0.25;
                if step < MIN_STEP {
                    // Stalled where a contact had almost let go: the
                    // design lies beyond where it opens.
                    let sys = build(tau);
                    let fading = closed
                        .iter()
                        .zip(&initial)
                        .find(|&(&i, &f0)| sys.contacts[i].elastic_force(&eq.q) < FADED * f0);
                    return Err(match fading {
                        Some((&i, _)) => DesignPathError::ContactOpens {
                            contact: sys.contacts[i].label.clone(),
                            at: tau,
                        },
                        None => DesignPathError::Stalled {
                            at: tau,
                            min_step: MIN_STEP,
                            last: source,
                        },
                    });
                }
            }
        }
    }
    Ok((eq, steps))
}

/// The ON-state equilibrium of `model` (its systems built by `system`,
/// e.g. with its beams made rigid): continued along the straight path
/// ([`Model::path_to`]) from `base` when `model` is a design of base's
/// assembly, so that the contacts closed in base's equilibrium stay
/// closed or the answer says where one opens; solved from the reference
/// (load-factor continuation) when it is not, or when base's own
/// equilibrium is not found.
pub fn on_state_equilibrium(
    model: &Model,
    base: &Model,
    system: impl Fn(&Model) -> System,
    settings: &StaticSettings,
) -> Result<Equilibrium, AnalysisError> {
    let Some(path) = base.path_to(model) else {
        return solve_equilibrium(&system(model), settings);
    };
    match equilibrium_along(|tau| system(&path.at(tau)), settings) {
        Ok((eq, _)) => Ok(eq),
        Err(DesignPathError::Start(_)) => solve_equilibrium(&system(model), settings),
        Err(reason) => Err(AnalysisError::FromDesign {
            from: base.name.clone(),
            reason: Box::new(reason),
        }),
    }
}

/// Relative unbalanced force accepted by [`balanced`].
const BALANCE_TOLERANCE: f64 = 1e-6;

/// `found` if it balances: ‖Q_int − Q_ext + C_qᵀλ‖∞ at most
/// [`BALANCE_TOLERANCE`] of the larger of the applied forces and the
/// multipliers: every step of the path is checked on its own balance, not
/// on the continuation's word.
fn balanced(sys: &System, found: Equilibrium) -> Result<Equilibrium, AnalysisError> {
    let n = sys.ndof();
    let (mut r, mut ext) = (vec![0.0; n], vec![0.0; n]);
    sys.internal_force(&found.q, &mut r);
    sys.external_force(&found.q, found.time, found.load_scale, &mut ext);
    sys.add_constraint_forces(&found.q, &found.lambda, &mut r);
    let max = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let unbalanced = r
        .iter()
        .zip(&ext)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let scale = max(&ext).max(max(&found.lambda));
    if unbalanced <= BALANCE_TOLERANCE * scale {
        Ok(found)
    } else {
        Err(AnalysisError::NotConverged {
            load_factor: found.load_scale,
            iterations: found.iterations,
            residual: unbalanced,
        })
    }
}
