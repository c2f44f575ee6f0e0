//! Where a time run starts: the static equilibrium it is released from, or
//! the reference configuration.
//!
//! A model whose reference does not balance its loads (a string tensioned
//! by a constant load, a preloaded spring, gravity on a supported
//! structure) is pre-stressed: struck at the reference, it would first
//! fall into its equilibrium, and the record would hold that motion, not
//! the vibration about the state `modal --prestress` linearizes. A time
//! run (`transient`, `impulse`) therefore starts by default from the static
//! equilibrium under the loads that act just before it, at t = 0⁻:
//! constant loads, preloads, gravity, releases (`until`, `ramp_down`) in
//! full; a half-sine (zero at t = 0) and a step (starting at t = 0 or
//! later) not at all, so a step still excites. A reference that already
//! balances those loads, with no support released, is that equilibrium:
//! the run starts there, exactly as from the reference.

use super::balance::{unbalanced_force, BALANCE_TOLERANCE};
use super::{solve_equilibrium, Equilibrium, StaticSettings};
use crate::error::AnalysisError;
use crate::system::System;

/// The time at which the starting equilibrium's loads are evaluated: the
/// left limit t → 0⁻ (the smallest negative time; the time functions jump
/// at their parameters, so it is their value just before the run).
pub const START_TIME: f64 = -f64::MIN_POSITIVE;

/// The state a time run starts from, at rest.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// The static equilibrium under the loads at t = 0⁻ (module doc); the
    /// reference itself when it balances them and no support is released.
    #[default]
    Equilibrium,
    /// The reference configuration, whatever acts on it.
    Reference,
}

impl Start {
    /// [`Start::Reference`] when `from_reference`, else the default.
    pub fn from_reference(from_reference: bool) -> Start {
        if from_reference {
            Start::Reference
        } else {
            Start::Equilibrium
        }
    }
}

/// The equilibrium a run starting at `start` is released from: `None` to
/// start at the reference (asked for, or balanced there with no released
/// support).
///
/// An assembly that no joint ties to the ground balances any net force in
/// its accelerating frame ([`super::balance`]'s free fall), so its
/// reference "balances" a load pressing it onto a contact as well as
/// gravity on a free body. When loads act at t = 0⁻ on such an assembly the
/// equilibrium is sought, and when there is none (a free body under
/// gravity falls) the run starts at the reference.
pub fn starting_equilibrium(
    system: &System,
    start: Start,
) -> Result<Option<Equilibrium>, AnalysisError> {
    if start == Start::Reference {
        return Ok(None);
    }
    let settings = StaticSettings {
        time: START_TIME,
        ..StaticSettings::default()
    };
    let balance = unbalanced_force(system, &system.q0, None, START_TIME, 1.0);
    if !system.released.is_empty() || !balance.is_balanced(BALANCE_TOLERANCE) {
        return solve_equilibrium(system, &settings).map(Some);
    }
    if balance.free_fall && loads_act_at_start(system) {
        return Ok(solve_equilibrium(system, &settings).ok());
    }
    Ok(None)
}

/// Whether the reference balances the loads at t = 0⁻ and gravity, to the
/// balance check's tolerance ([`super::balance`]), with no support to
/// release: a run from [`Start::Equilibrium`] starts there.
pub fn reference_balances(system: &System) -> bool {
    matches!(starting_equilibrium(system, Start::Equilibrium), Ok(None))
}

/// Whether any applied load or gravity acts at t = 0⁻.
pub fn loads_act_at_start(system: &System) -> bool {
    let mut f = vec![0.0; system.ndof()];
    system.external_force(&system.q0, START_TIME, 1.0, &mut f);
    f.iter().any(|&x| x != 0.0)
}
