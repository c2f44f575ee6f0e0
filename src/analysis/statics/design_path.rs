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
//! the secant predictor: the line through the last two converged states,
//! extended to the next τ (from the first state alone on the first step).
//! A design change that moves a stiff contact's seat (a slot's end cap
//! 1 mm along the path, the contact closed by 1 µm) opens or crushes the
//! contact when the last state is taken as it is, and Newton's method
//! starts from the contact's whole force out of balance whatever the step;
//! the secant moves the parts with the seat, and leaves an error of the
//! order of the step squared. A step whose secant start fails (Newton's
//! method stalls, the state does not balance or is unstable, or a closed
//! contact opens) is tried again, the same step, from the last state as it
//! is, before the step is cut.
//!
//! **Folds.** A path can fold back: the branch it follows ends at a limit
//! point in τ (the path from the calibrated switch-off design to the
//! uncalibrated one with its spring housing moved 0.1 mm folds near
//! τ = 0.61) and the design beyond is held only on another branch. The
//! secant follows the branch into the fold, where every step, from either
//! start, stalls with a residual that shrinks with the step, and the path
//! stops below [`MIN_STEP`]. Started from the last state alone, the path
//! reaches the fold with longer steps and one of them lands on the other
//! branch (it jumps the fold). So when the secant path does not reach the
//! design, for any reason, the whole path is run again with the last state
//! as each step's start ([`Predictor::LastState`]), and that outcome is the
//! answer: the path never ends worse than it did without the secant
//! (tests/design_path_fold.rs checks that on the fold's design, and that
//! where both paths reach a design they reach the same equilibrium).
//!
//! **Step control.** The step doubles after a step that converged, is
//! quartered after one that did not, and the path gives up below
//! [`MIN_STEP`]. After every step the contacts that were closed at
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

use super::balance::{unbalanced_force, BALANCE_TOLERANCE};
use super::{
    continue_equilibrium, solve_equilibrium, Branch, Equilibrium, LoadPath, StaticSettings,
};
pub use crate::error::DesignPathError;
use crate::error::{AnalysisError, InvalidModel};
use crate::mechanics::spring::ForceElement;
use crate::model::ValidModel;
use crate::system::System;
use std::cell::OnceCell;

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
/// τ = 0 (see the module doc); also the number of path steps taken. A
/// design `build` refuses (an invalid model) ends the path there.
pub fn equilibrium_along(
    build: impl Fn(f64) -> Result<System, InvalidModel>,
    settings: &StaticSettings,
) -> Result<(Equilibrium, usize), DesignPathError> {
    equilibrium_along_from(build, &PathStart::new(), settings)
}

/// The equilibrium of a path's first design, `build(0)`, once solved
/// (load stepping from its reference): several paths from one design,
/// built by one system builder, solve it once.
pub type PathStart = OnceCell<Result<Equilibrium, AnalysisError>>;

/// [`equilibrium_along`], with the equilibrium at τ = 0 taken from `start`
/// when it was solved before, and kept there when it is solved here.
/// `start` must belong to the same first design and system builder.
pub fn equilibrium_along_from(
    build: impl Fn(f64) -> Result<System, InvalidModel>,
    start: &PathStart,
    settings: &StaticSettings,
) -> Result<(Equilibrium, usize), DesignPathError> {
    match equilibrium_along_with(&build, start, settings, Predictor::Secant) {
        // A fold (module doc): the path as it was without the secant.
        Err(e) if !matches!(e, DesignPathError::Start(_)) => {
            equilibrium_along_with(build, start, settings, Predictor::LastState)
        }
        found => found,
    }
}

/// Where each step of a design path starts Newton's method (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Predictor {
    /// The secant through the last two equilibria (carried to the next
    /// design), then, when that step fails, the last equilibrium.
    Secant,
    /// The last equilibrium as it is.
    LastState,
}

/// [`equilibrium_along_from`] with one predictor throughout, no second
/// path when it does not reach the design.
pub fn equilibrium_along_with(
    build: impl Fn(f64) -> Result<System, InvalidModel>,
    start: &PathStart,
    settings: &StaticSettings,
    predictor: Predictor,
) -> Result<(Equilibrium, usize), DesignPathError> {
    let invalid = |at: f64| {
        move |invalid| DesignPathError::InvalidDesign {
            at,
            invalid: Box::new(invalid),
        }
    };
    let mut prev = build(0.0).map_err(invalid(0.0))?;
    let mut eq = start
        .get_or_init(|| solve_equilibrium(&prev, settings))
        .clone()
        .map_err(DesignPathError::Start)?;
    let closed: Vec<usize> = (0..prev.contacts.len())
        .filter(|&i| prev.contacts[i].elastic_force(&eq.q) > 0.0)
        .collect();
    let initial: Vec<f64> = closed
        .iter()
        .map(|&i| prev.contacts[i].elastic_force(&eq.q))
        .collect();
    let (mut tau, mut step, mut steps) = (0.0f64, FIRST_STEP, 0usize);
    // The converged state before the last one, its system and τ.
    let mut before: Option<(System, Vec<f64>, f64)> = None;
    while tau < 1.0 {
        let next = (tau + step).min(1.0);
        let sys = build(next).map_err(invalid(next))?;
        let transfer = |from: &System, q: &[f64]| {
            sys.transfer_from(from, q)
                .map_err(|source| DesignPathError::Transfer { at: next, source })
        };
        let last = transfer(&prev, &eq.q)?;
        // The predictors in turn (module doc): the secant, then the last
        // state as it is; the first step that converges with the closed
        // contacts closed is taken, the last predictor's outcome decides.
        let secant = match (&before, predictor) {
            (Some((older, q_older, tau_older)), Predictor::Secant) => {
                let q_older = transfer(older, q_older)?;
                let ratio = (next - tau) / (tau - tau_older);
                let mut q = last.clone();
                q.iter_mut()
                    .zip(&q_older)
                    .for_each(|(a, b)| *a += ratio * (*a - b));
                Some(q)
            }
            _ => None,
        };
        let mut step_result = Err(Rejected::Failed(AnalysisError::NotConverged {
            load_factor: eq.load_scale,
            iterations: 0,
            residual: f64::INFINITY,
        }));
        for q in secant.into_iter().chain(std::iter::once(last)) {
            let start = Equilibrium {
                q,
                lambda: vec![0.0; sys.constraint_count()],
                ..eq.clone()
            };
            step_result = continue_equilibrium(&sys, &start, eq.load_scale, settings)
                .and_then(|found| balanced(&sys, found))
                .map_err(Rejected::Failed)
                .and_then(|found| {
                    match closed
                        .iter()
                        .find(|&&i| sys.contacts[i].elastic_force(&found.q) <= 0.0)
                    {
                        Some(&i) => Err(Rejected::Opens(i)),
                        None => Ok(found),
                    }
                });
            if step_result.is_ok() {
                break;
            }
        }
        match step_result {
            Err(Rejected::Opens(i)) => {
                return Err(DesignPathError::ContactOpens {
                    contact: sys.contacts[i].label.clone(),
                    at: next,
                });
            }
            Ok(found) => {
                before = Some((
                    std::mem::replace(&mut prev, sys),
                    std::mem::replace(&mut eq, found).q,
                    tau,
                ));
                tau = next;
                steps += 1;
                step = (2.0 * step).min(1.0);
            }
            Err(Rejected::Failed(source)) => {
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
    model: &ValidModel,
    base: &ValidModel,
    system: impl Fn(&ValidModel) -> System,
    settings: &StaticSettings,
) -> Result<Equilibrium, AnalysisError> {
    on_state_equilibrium_from(model, base, &PathStart::new(), system, settings)
}

/// [`on_state_equilibrium`], with base's own equilibrium (where a path
/// from it starts) kept in `start` for the next design continued from the
/// same base with the same `system` ([`equilibrium_along_from`]).
pub fn on_state_equilibrium_from(
    model: &ValidModel,
    base: &ValidModel,
    start: &PathStart,
    system: impl Fn(&ValidModel) -> System,
    settings: &StaticSettings,
) -> Result<Equilibrium, AnalysisError> {
    let Some(path) = base.path_to(model) else {
        return solve_equilibrium(&system(model), settings);
    };
    match equilibrium_along_from(|tau| path.at(tau).map(|m| system(&m)), start, settings) {
        Ok((eq, steps)) => Ok(Equilibrium {
            branch: Branch::continued(&base.name, steps),
            ..eq
        }),
        Err(DesignPathError::Start(_)) => solve_equilibrium(&system(model), settings),
        Err(reason) => {
            let sys = system(model);
            let fallback = solve_equilibrium(&sys, settings).and_then(|eq| {
                // The contact whose opening stopped the path must hold in
                // the state found instead, or it is another state.
                let opened = match &reason {
                    DesignPathError::ContactOpens { contact, .. } => {
                        sys.contacts.iter().find(|c| &c.label == contact)
                    }
                    _ => None,
                };
                match opened.map(|c| (c, c.elastic_force(&eq.q))) {
                    Some((c, force)) if force <= 0.0 => Err(AnalysisError::ContactOpenInFallback {
                        contact: c.label.clone(),
                        force,
                    }),
                    _ => Ok(eq),
                }
            });
            match fallback {
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

/// `found` if it balances its system ([`unbalanced_force`] with
/// its own multipliers, to [`BALANCE_TOLERANCE`]): every step of the path
/// is checked on its own balance, not on the continuation's word.
fn balanced(sys: &System, found: Equilibrium) -> Result<Equilibrium, AnalysisError> {
    let b = unbalanced_force(
        sys,
        &found.q,
        Some(&found.lambda),
        found.time,
        found.load_scale,
    );
    if b.is_balanced(BALANCE_TOLERANCE) {
        Ok(found)
    } else {
        Err(AnalysisError::NotConverged {
            load_factor: found.load_scale,
            iterations: found.iterations,
            residual: b.unbalanced,
        })
    }
}

/// Checks an equilibrium on the design's own system: its coordinates fit
/// the system, it balances and meets the constraints
/// ([`unbalanced_force`] to [`BALANCE_TOLERANCE`]), and its total
/// potential energy is not above the reference's (else it jumped to
/// another branch).
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
    let b = unbalanced_force(sys, &eq.q, Some(&eq.lambda), eq.time, eq.load_scale);
    if !b.is_balanced(BALANCE_TOLERANCE) {
        return Err(DesignPathError::Unbalanced {
            unbalanced: b.unbalanced,
            scale: b.scale,
            violation: b.constraint_violation,
        });
    }
    let found = sys.potential_energy(&eq.q, eq.time, eq.load_scale);
    let reference = sys.potential_energy(&sys.q0, eq.time, eq.load_scale);
    // Round-off of the energies: relative to the larger, and at least the
    // energy of a strain of 256 ε in the stiffest beam, (256 ε)² EA L.
    let floor = (256.0 * f64::EPSILON).powi(2) * sys.stiffest_ea() * sys.length_scale();
    let slack = (1e-9 * found.abs().max(reference.abs())).max(floor) + f64::MIN_POSITIVE;
    if found > reference + slack {
        return Err(DesignPathError::EnergyAboveReference { found, reference });
    }
    Ok(())
}

/// Why a path step from one predictor was not taken.
enum Rejected {
    /// Newton's method did not find a balanced state.
    Failed(AnalysisError),
    /// The state found has this contact, closed at the start, open.
    Opens(usize),
}
