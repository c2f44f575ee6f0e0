//! Released supports: a joint with `release` (a latch) holds in the
//! static equilibrium — the ON state of a pre-stressed mechanism — and lets
//! go in the transient that starts there.
//!
//! At the equilibrium (q*, λ*) the joint exerts the force R = −∂C/∂r_b ᵀλ*
//! [SI: N] on its point b and −R on its point a (a pin: R = −(λ₀, λ₁); a
//! slider on a ground rail: R = −λ n). The released system drops the
//! joint's equations and applies R f(t) at b and −R f(t) at a as dead loads
//! (fixed direction), f the joint's `release` time function (1 at t = 0).
//! At t = 0 the loads equal the reactions, so q* is an equilibrium of the
//! released system too and the transient starts at rest without a jump;
//! then the hold fades as f does. The coordinates (and so every anchor)
//! are those of the holding system: only constraints and loads change.

use super::System;
use crate::mechanics::joint::{Pin, Slider};
use crate::mechanics::load::PointLoad;
use crate::mechanics::pair::Pair;
use crate::model::TimeFunction;
use nalgebra::Vector2;

/// A joint that holds until a transient releases it.
#[derive(Debug, Clone)]
pub struct ReleasedSupport {
    /// Index of its constraint in [`System::constraints`].
    pub constraint: usize,
    /// How its hold falls after t = 0.
    pub time: TimeFunction,
    /// The joint (the constraint's own copy): one whose whole reaction is
    /// a force on its points, so the loads that replace it are forces.
    pub joint: ReleasedJoint,
}

/// The kinds of joint a model may release (validation refuses a released
/// weld: its reaction includes a moment).
#[derive(Debug, Clone)]
pub enum ReleasedJoint {
    Pin(Pin),
    Slider(Slider),
}

impl ReleasedJoint {
    /// The force the joint exerts on its point b [SI: N] at (q, λ), λ its
    /// own multipliers.
    pub fn point_reaction(&self, q: &[f64], lambda: &[f64]) -> Vector2<f64> {
        match self {
            ReleasedJoint::Pin(p) => p.point_reaction(lambda),
            ReleasedJoint::Slider(s) => s.point_reaction(q, lambda),
        }
    }

    pub fn label(&self) -> &str {
        match self {
            ReleasedJoint::Pin(p) => &p.label,
            ReleasedJoint::Slider(s) => &s.label,
        }
    }

    pub fn pair(&self) -> &Pair {
        match self {
            ReleasedJoint::Pin(p) => &p.pair,
            ReleasedJoint::Slider(s) => &s.pair,
        }
    }
}

impl System {
    /// The system after the release of every released support, given the
    /// equilibrium `q` and multipliers `lambda` of this (holding) system;
    /// `self` unchanged when it has none.
    pub fn release_supports(mut self, q: &[f64], lambda: &[f64]) -> System {
        let released = std::mem::take(&mut self.released);
        for r in released.iter().rev() {
            let c = self.constraints.remove(r.constraint);
            let row = self.constraint_rows[r.constraint];
            let force = r.joint.point_reaction(q, &lambda[row..row + c.rows()]);
            let pair = r.joint.pair();
            for (side, anchor, f) in [("b", &pair.b, force), ("a", &pair.a, -force)] {
                if anchor.dofs().is_empty() {
                    continue;
                }
                self.loads.push(PointLoad {
                    label: format!("{} (released, on {side})", r.joint.label()),
                    anchor: anchor.clone(),
                    force: f,
                    time: r.time,
                });
            }
        }
        self.renumber_constraints();
        self
    }
}
