//! What a modal analysis returns: the modes with their kind, energy
//! split and error bound [SI: Hz, rad²/s²], the modes refused, and the
//! check of the state's equilibrium that decides whether a negative ω² is
//! an instability.

use super::{ACCURACY_WARNING, REFUSE_BOUND};
use crate::analysis::statics::balance::{Balance, BALANCE_TOLERANCE};
use crate::system::System;
use serde::Serialize;

/// A mode the eigen-solve could not resolve to [`REFUSE_BOUND`]: it is not
/// reported as a frequency.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct RefusedMode {
    /// The mode's number among the modes, 1-based, had it been reported.
    pub index: usize,
    /// Its bound on the relative frequency error [–].
    pub error_bound: f64,
    /// Total beam elements at which the arithmetic is expected to resolve
    /// it: the round-off of a factor of K grows as the elements to the 7th
    /// power on ω² (measured on a cantilever, 2,000 to 20,000 elements).
    pub elements_hint: Option<usize>,
}

/// What a mode mostly does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ModeKind {
    /// Zero frequency: a rigid motion of the whole assembly.
    Rigid,
    /// Zero frequency: a motion the joints leave free while the assembly
    /// as a whole does not move rigidly (a lever free to turn on its pin).
    Mechanism,
    Bending,
    Axial,
    /// Energy mostly in springs (e.g. a body rocking on a torsion spring).
    Spring,
    /// Negative ω² at a verified equilibrium: the equilibrium is unstable,
    /// the mode grows as e^{√|ω²| t} (frequency reported as −√|ω²|/2π).
    Unstable,
    /// Negative ω² at a state that is not an equilibrium: a direction of
    /// negative stiffness of the linearization, neither a vibration nor a
    /// statement about stability (frequency reported as −√|ω²|/2π).
    Negative,
}

impl ModeKind {
    /// A zero-frequency mode (rigid or mechanism).
    pub fn is_zero(self) -> bool {
        matches!(self, ModeKind::Rigid | ModeKind::Mechanism)
    }

    /// A mode with negative ω² (unstable, or negative at a non-equilibrium).
    pub fn is_negative(self) -> bool {
        matches!(self, ModeKind::Unstable | ModeKind::Negative)
    }
}

impl std::fmt::Display for ModeKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = match self {
            ModeKind::Rigid => "rigid",
            ModeKind::Mechanism => "mechanism",
            ModeKind::Bending => "bending",
            ModeKind::Axial => "axial",
            ModeKind::Spring => "spring",
            ModeKind::Unstable => "unstable",
            ModeKind::Negative => "negative",
        };
        f.write_str(s)
    }
}

/// Fractions of a mode's strain energy.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, schemars::JsonSchema)]
pub struct EnergyFractions {
    /// Fraction in beam stretching [–].
    pub axial: f64,
    /// Fraction in beam bending [–].
    pub bending: f64,
    /// Fraction in springs and torsion springs [–].
    pub springs: f64,
}

/// One mode.
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct Mode {
    /// Mode number, 1-based, in ascending frequency.
    pub index: usize,
    /// Natural frequency [SI: Hz]; 0 for rigid modes; −√|ω²|/2π for a
    /// negative eigenvalue (the imaginary frequency's magnitude, negated).
    pub frequency_hz: f64,
    /// Eigenvalue ω² [SI: rad²/s²] (negative = unstable direction).
    pub eigenvalue: f64,
    /// What the mode mostly does (by where its strain energy sits).
    pub kind: ModeKind,
    /// Strain-energy split [–] (all zero for rigid modes).
    pub energy: EnergyFractions,
    /// Bound on the relative frequency error the eigen-solve and round-off
    /// leave [–]; `None` for rigid modes.
    pub error_bound: Option<f64>,
    /// Estimated relative frequency change from Euler–Bernoulli to
    /// Timoshenko theory (bending modes; set by [`crate::analysis::shear::annotate`]).
    pub shear_estimate: Option<f64>,
    /// Mass-normalized shape in the global coordinates (φᵀMφ = 1).
    #[serde(skip)]
    pub shape: Vec<f64>,
}

/// Result of a modal analysis.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct ModalResult {
    /// Number of coordinates.
    pub dofs: usize,
    /// Number of constraint equations.
    pub constraints: usize,
    /// Labels of joints with redundant equations.
    pub redundant_constraints: Vec<String>,
    /// Dimension of the reduced problem.
    pub reduced_dofs: usize,
    /// Number of zero-frequency modes (all of them, also beyond `modes`):
    /// rigid motions of the whole assembly and mechanisms.
    pub rigid_modes: usize,
    /// How many of the zero-frequency modes are mechanisms of the joints.
    pub mechanism_modes: usize,
    /// Which eigensolver ran.
    pub solver: &'static str,
    pub modes: Vec<Mode>,
    /// Whether the state is an equilibrium (module doc, item 6).
    pub equilibrium: EquilibriumCheck,
    /// Reported modes of kind [`ModeKind::Unstable`].
    pub unstable_modes: usize,
    /// Reported modes of kind [`ModeKind::Negative`].
    pub negative_modes: usize,
    /// Modes whose error bound exceeds [`REFUSE_BOUND`]: not in `modes`.
    pub refused_modes: Vec<RefusedMode>,
    /// Whether Sylvester's inertia confirmed that no mode below the
    /// highest reported one was skipped.
    pub mode_count_certified: bool,
}

/// Whether the state a modal analysis is linearized at is an equilibrium
/// ([`crate::analysis::statics::balance`]).
#[derive(Debug, Clone, PartialEq, Serialize, schemars::JsonSchema)]
pub struct EquilibriumCheck {
    /// Force balance and constraints hold to `tolerance` [–].
    pub balanced: bool,
    /// Largest unbalanced generalized force, with the multipliers of the
    /// state or least-squares ones; moments divided by the model's size [N].
    pub unbalanced_n: f64,
    /// Largest internal, applied or joint force it is compared with [N].
    pub force_scale_n: f64,
    /// Relative tolerance of the check [–].
    pub tolerance: f64,
    /// The unbalanced force the arithmetic may leave at a balanced state
    /// (the rounding of the elastic forces, of the stored reference and of
    /// the statics' smallest step) [N]: balanced when `unbalanced_n` ≤
    /// `tolerance` × `force_scale_n` + `rounding_n`.
    pub rounding_n: f64,
    /// The coordinate the largest unbalanced force acts on.
    pub at: String,
    /// Largest constraint residual ‖C(q)‖∞ [m, –].
    pub constraint_violation: f64,
    /// Whether a uniform acceleration of the whole (unsupported) assembly
    /// was allowed: a free assembly falling under gravity is in
    /// equilibrium in its falling frame.
    pub free_fall: bool,
}

impl EquilibriumCheck {
    /// The check of `b` at [`BALANCE_TOLERANCE`].
    pub fn new(system: &System, b: &Balance) -> Self {
        EquilibriumCheck {
            balanced: b.is_balanced(BALANCE_TOLERANCE),
            unbalanced_n: b.unbalanced,
            force_scale_n: b.scale,
            tolerance: BALANCE_TOLERANCE,
            rounding_n: b.noise,
            at: system.dof_label(b.worst_dof),
            constraint_violation: b.constraint_violation,
            free_fall: b.free_fall,
        }
    }

    /// One sentence for a state called `state` ("the reference") that is
    /// not an equilibrium, `None` when it is one.
    pub fn warning(&self, state: &str) -> Option<String> {
        (!self.balanced).then(|| {
            format!(
                "{state} is not an equilibrium: unbalanced force {:.3e} N on {} ({:.1e} of the largest force {:.3e} N; constraints violated by {:.1e}); \
                 its modes are the linearization at a state that does not stay put, not a vibration",
                self.unbalanced_n,
                self.at,
                self.unbalanced_n / self.force_scale_n.max(f64::MIN_POSITIVE),
                self.force_scale_n,
                self.constraint_violation
            )
        })
    }
}

impl ModalResult {
    /// Elastic modes of a kind, ascending.
    pub fn of_kind(&self, kind: ModeKind) -> impl Iterator<Item = &Mode> {
        self.modes.iter().filter(move |m| m.kind == kind)
    }

    /// The first bending mode, if any was computed.
    pub fn first_bending(&self) -> Option<&Mode> {
        self.of_kind(ModeKind::Bending).next()
    }

    /// Largest error bound among the lowest three elastic modes, when it
    /// exceeds [`ACCURACY_WARNING`].
    pub fn accuracy_warning(&self) -> Option<f64> {
        let worst = self
            .modes
            .iter()
            .filter_map(|m| m.error_bound)
            .take(3)
            .fold(0.0f64, f64::max);
        (worst > ACCURACY_WARNING).then_some(worst)
    }

    /// The warnings of this result at a state called `state` ("the
    /// reference"): not an equilibrium, or an unstable equilibrium.
    pub fn warnings(&self, state: &str) -> Vec<String> {
        let mut w: Vec<String> = self.equilibrium.warning(state).into_iter().collect();
        if self.unstable_modes > 0 {
            let list: Vec<String> = self
                .modes
                .iter()
                .filter(|m| m.kind == ModeKind::Unstable)
                .map(|m| {
                    format!(
                        "mode {} (ω² = {:.4e} rad²/s², grows as e^(t/{:.3e} s))",
                        m.index,
                        m.eigenvalue,
                        1.0 / m.eigenvalue.abs().sqrt()
                    )
                })
                .collect();
            w.push(format!(
                "{state} is an unstable equilibrium: {} mode(s) with negative eigenvalue: {}",
                self.unstable_modes,
                list.join(", ")
            ));
        }
        for r in &self.refused_modes {
            let hint = r.elements_hint.map_or(String::new(), |n| {
                format!("; about {n} beam elements in all resolve it")
            });
            let why = if self.solver == "dense" {
                "the dense solve's round-off limits it (the sparse solver refines it)".to_string()
            } else if r.elements_hint.is_some() {
                format!("the round-off of a very fine mesh's stiffness limits it{hint}")
            } else {
                "the eigen-solve's round-off limits it".to_string()
            };
            w.push(format!(
                "mode {} is not reported as a frequency: the eigen-solve resolves it only to {:.1e} (relative), more than {REFUSE_BOUND:.0e}; {why}",
                r.index, r.error_bound
            ));
        }
        if !self.mode_count_certified {
            w.push(
                "the eigen-solve could not confirm by Sylvester's inertia that no mode below the highest reported one was skipped (the factorization's round-off on this mesh exceeds the gap it counts in)"
                    .to_string(),
            );
        }
        w
    }
}
