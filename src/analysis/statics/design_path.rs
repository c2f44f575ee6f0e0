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
//! **A design is solved as itself.** Two designs along the path can have
//! different coordinate layouts (a moved attachment moves its mesh node,
//! and the node count changes when it crosses a node): every step carries
//! the last state to the next design through material positions
//! ([`System::transfer_from`]), never by index. The end state is verified
//! on the end design's own system (force balance and constraints,
//! [`verify`]), and a state whose total potential energy
//! ([`System::potential_energy`]) exceeds the end design's reference is
//! refused as a jump to another branch.
//!
//! [`on_state_equilibrium`] is what the switch-off uses: the path is the
//! straight line between two designs of one assembly
//! ([`Model::path_to`]), from a known design (the built-in model, or the
//! swept one) to the wanted one. When the continuation cannot reach the
//! design it solves the design from its own reference and says so in
//! [`Equilibrium::branch`].

use super::{
    continue_equilibrium, solve_equilibrium, Branch, Equilibrium, LoadPath, StaticSettings,
};
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
    let mut prev = build(0.0);
    let mut eq = solve_equilibrium(&prev, settings).map_err(DesignPathError::Start)?;
    let closed: Vec<usize> = (0..prev.contacts.len())
        .filter(|&i| prev.contacts[i].elastic_force(&eq.q) > 0.0)
        .collect();
    let initial: Vec<f64> = closed
        .iter()
        .map(|&i| prev.contacts[i].elastic_force(&eq.q))
        .collect();
    let (mut tau, mut step, mut steps) = (0.0f64, FIRST_STEP, 0usize);
    while tau < 1.0 {
        let next = (tau + step).min(1.0);
        let sys = build(next);
        let q = sys
            .transfer_from(&prev, &eq.q)
            .map_err(|source| DesignPathError::Transfer { at: next, source })?;
        let start = Equilibrium {
            q,
            lambda: vec![0.0; sys.constraint_count()],
            ..eq.clone()
        };
        let step_result = continue_equilibrium(&sys, &start, eq.load_scale, settings)
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
                prev = sys;
                tau = next;
                steps += 1;
                step = (2.0 * step).min(1.0);
            }
            Err(source) => {
                step *= 0.25;
                if step < MIN_STEP {
                    // Stalled where a contact had almost let go: the
                    // design lies beyond where it opens.
                    let fading = closed
                        .iter()
                        .zip(&initial)
                        .find(|&(&i, &f0)| prev.contacts[i].elastic_force(&eq.q) < FADED * f0);
                    return Err(match fading {
                        Some((&i, _)) => DesignPathError::ContactOpens {
                            contact: prev.contacts[i].label.clone(),
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
    verify(&prev, &eq)?;
    Ok((eq, steps))
}

/// The ON-state equilibrium of `model` (its systems built by `system`,
/// e.g. with its beams made rigid): continued along the straight path
/// ([`Model::path_to`]) from `base` when `model` is a design of base's
/// assembly, so that the contacts closed in base's equilibrium stay
/// closed; solved from the reference (load-factor continuation) when it is
/// not a design of base's assembly, when base's own equilibrium is not
/// found, or when the continuation does not reach the design (then
/// [`Equilibrium::branch`] says why). An error only when no way finds it.
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
        Ok((eq, steps)) => Ok(Equilibrium {
            branch: Branch::continued(&base.name, steps),
            ..eq
        }),
        Err(DesignPathError::Start(_)) => solve_equilibrium(&system(model), settings),
        Err(reason) => {
            let sys = system(model);
            match solve_equilibrium(&sys, settings) {
                Ok(eq) => {
                    let path = eq.branch.path.unwrap_or(LoadPath::GravityFirst);
                    Ok(Equilibrium {
                        branch: Branch::after_continuation(&base.name, reason.to_string(), path),
                        ..eq
                    })
                }
                Err(fallback) => Err(AnalysisError::FromDesign {
                    from: base.name.clone(),
                    reason: Box::new(reason),
                    fallback: Box::new(fallback),
                }),
            }
        }
    }
}

/// Relative unbalanced force accepted by [`balanced`] and [`verify`].
const BALANCE_TOLERANCE: f64 = 1e-6;
/// Constraint violation accepted by [`verify`], relative to the
/// assembly's size.
const CONSTRAINT_TOLERANCE: f64 = 1e-9;

/// `found` if it balances: ‖Q_int − Q_ext + C_qᵀλ‖∞ at most
/// [`BALANCE_TOLERANCE`] of the larger of the applied forces and the
/// multipliers: every step of the path is checked on its own balance, not
/// on the continuation's word.
fn balanced(sys: &System, found: Equilibrium) -> Result<Equilibrium, AnalysisError> {
    let (unbalanced, scale) = unbalanced_force(sys, &found);
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

/// ‖Q_int − Q_ext + C_qᵀλ‖∞ at the equilibrium's state and multipliers,
/// and the force scale it is judged against: the largest applied,
/// internal or joint force, and at least [`resolution_force`] over
/// [`BALANCE_TOLERANCE`] (so that an unbalance the solver cannot resolve is
/// not taken for a wrong state) [SI: N].
fn unbalanced_force(sys: &System, eq: &Equilibrium) -> (f64, f64) {
    let n = sys.ndof();
    let (mut int, mut ext) = (vec![0.0; n], vec![0.0; n]);
    sys.internal_force(&eq.q, &mut int);
    sys.external_force(&eq.q, eq.time, eq.load_scale, &mut ext);
    let mut r = int.clone();
    sys.add_constraint_forces(&eq.q, &eq.lambda, &mut r);
    let max = |v: &[f64]| v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let unbalanced = r
        .iter()
        .zip(&ext)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let scale = max(&ext).max(max(&eq.lambda)).max(max(&int));
    (
        unbalanced,
        scale.max(resolution_force(sys) / BALANCE_TOLERANCE),
    )
}

/// The force below which an unbalance is not resolved [SI: N]: what a
/// displacement of [`STEP_RESOLUTION`] × the assembly's size makes in the
/// stiffest element, EA/Le (the statics' Newton iteration stops on a step
/// that small), and at least the round-off of the stiffest beam's elastic
/// force, 256 ε EA.
fn resolution_force(sys: &System) -> f64 {
    let length = sys.length_scale();
    sys.beams
        .iter()
        .flat_map(|b| {
            b.elements.iter().map(move |e| {
                let ea = b.section.ea;
                (ea / e.le * STEP_RESOLUTION * length).max(256.0 * f64::EPSILON * ea)
            })
        })
        .fold(0.0, f64::max)
}

/// The statics' smallest resolved step, relative to the assembly's size
/// (its Newton iteration stops on a step below it).
const STEP_RESOLUTION: f64 = 1e-10;

/// Checks an equilibrium on the design's own system: its coordinates fit
/// the system, it balances (see [`balanced`]), it meets the constraints to
/// [`CONSTRAINT_TOLERANCE`] × the assembly's size, and its total potential
/// energy is not above the reference's (else it jumped to another branch).
pub fn verify(sys: &System, eq: &Equilibrium) -> Result<(), DesignPathError> {
    if eq.q.len() != sys.ndof() || eq.lambda.len() != sys.constraint_count() {
        return Err(DesignPathError::Transfer {
            at: 1.0,
            source: crate::error::TransferError::Length {
                got: eq.q.len(),
                expected: sys.ndof(),
            },
        });
    }
    let (unbalanced, scale) = unbalanced_force(sys, eq);
    let mut c = vec![0.0; sys.constraint_count()];
    sys.constraint_residual(&eq.q, &mut c);
    let violation = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if unbalanced > BALANCE_TOLERANCE * scale
        || violation > CONSTRAINT_TOLERANCE * sys.length_scale()
    {
        return Err(DesignPathError::Unbalanced {
            unbalanced,
            scale,
            violation,
        });
    }
    let found = sys.potential_energy(&eq.q, eq.time, eq.load_scale);
    let reference = sys.potential_energy(&sys.q0, eq.time, eq.load_scale);
    // Round-off of the energies: relative to the larger, and at least the
    // energy of a strain of 256 ε in the stiffest beam, (256 ε)² EA L.
    let stiffest = sys.beams.iter().map(|b| b.section.ea).fold(0.0, f64::max);
    let floor = (256.0 * f64::EPSILON).powi(2) * stiffest * sys.length_scale();
    let slack = (1e-9 * found.abs().max(reference.abs())).max(floor) + f64::MIN_POSITIVE;
    if found > reference + slack {
        return Err(DesignPathError::EnergyAboveReference { found, reference });
    }
    Ok(())
}
