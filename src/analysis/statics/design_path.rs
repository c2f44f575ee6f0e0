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
//! τ = 0 must still be: a contact that opens means that the design has no
//! equilibrium with it closed (the answer, not a failure of the method).

use super::{continue_equilibrium, solve_equilibrium, Equilibrium, StaticSettings};
use crate::error::AnalysisError;
use crate::spring::ForceElement;
use crate::system::System;

/// Smallest step in τ before the path gives up.
pub const MIN_STEP: f64 = 1.0 / 4096.0;
/// First step in τ.
const FIRST_STEP: f64 = 0.25;

/// Why the path did not reach τ = 1.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignPathError {
    #[error("the starting design: {0}")]
    Start(AnalysisError),
    #[error("contact `{contact}` opens at {at:.4} of the way to the design: no equilibrium with it closed")]
    ContactOpens { contact: String, at: f64 },
    #[error("no equilibrium found beyond {at:.4} of the way to the design (steps below {MIN_STEP} of it): {source}")]
    Stalled { at: f64, source: AnalysisError },
}

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
    let (mut tau, mut step, mut steps) = (0.0f64, FIRST_STEP, 0usize);
    while tau < 1.0 {
        let next = (tau + step).min(1.0);
        let sys = build(next);
        match continue_equilibrium(&sys, &eq, eq.load_scale, settings) {
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
                    return Err(DesignPathError::Stalled { at: tau, source });
                }
            }
        }
    }
    Ok((eq, steps))
}
