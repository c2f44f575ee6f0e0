//! Applied point forces and their time functions.
//!
//! A load is a dead force F(t) = F₀ f(t) [SI: N] at an anchor, fixed in
//! direction (a `beam`-frame load is turned into the global frame once, at the
//! initial configuration). Its generalized force is `Q = (∂r/∂q)ᵀ F`
//! (paper Eq. 7); on a rigid-body point off the centre, `∂Q/∂q ≠ 0`.

use crate::mechanics::anchor::{Anchor, Hess, PosJac};
use crate::model::TimeFunction;
use nalgebra::Vector2;

impl TimeFunction {
    /// f(t) [–].
    pub fn value(&self, t: f64) -> f64 {
        match *self {
            TimeFunction::Constant => 1.0,
            TimeFunction::HalfSine { duration } => {
                if (0.0..=duration).contains(&t) {
                    (std::f64::consts::PI * t / duration).sin()
                } else {
                    0.0
                }
            }
            TimeFunction::Step { start } => {
                if t >= start {
                    1.0
                } else {
                    0.0
                }
            }
            TimeFunction::RampDown { start, duration } => {
                if t <= start {
                    1.0
                } else if t >= start + duration {
                    0.0
                } else {
                    1.0 - (t - start) / duration
                }
            }
            TimeFunction::Until(until) => {
                if t <= until {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// A point force on the assembly.
#[derive(Debug, Clone)]
pub struct PointLoad {
    pub label: String,
    pub anchor: Anchor,
    /// Amplitude in the global frame [SI: N].
    pub force: Vector2<f64>,
    pub time: TimeFunction,
}

impl PointLoad {
    /// Force at time t [SI: N].
    pub fn force_at(&self, t: f64) -> Vector2<f64> {
        self.force * self.time.value(t)
    }

    /// Adds the generalized force at (q, t), scaled by `scale`, into `out` (global).
    pub fn add_generalized_force(&self, q: &[f64], t: f64, scale: f64, out: &mut [f64]) {
        self.add_force_of(q, self.force_at(t) * scale, out);
    }

    /// Adds the generalized force of the amplitude F₀ (its time function
    /// at 1) at q into `out`: where and how the load pushes.
    pub fn add_amplitude_force(&self, q: &[f64], out: &mut [f64]) {
        self.add_force_of(q, self.force, out);
    }

    /// Adds Jᵀf, the generalized force of `f` [SI: N] at the anchor, at q.
    fn add_force_of(&self, q: &[f64], f: Vector2<f64>, out: &mut [f64]) {
        if f == Vector2::zeros() {
            return;
        }
        let mut jac = PosJac::zeros();
        self.anchor.position_jacobian(q, &mut jac);
        for (k, &d) in self.anchor.dofs().iter().enumerate() {
            out[d] += jac.column(k).dot(&f);
        }
    }

    /// ∂Q/∂q (local to the anchor) at (q, t), scaled; zero except on rigid bodies.
    pub fn load_stiffness(&self, q: &[f64], t: f64, scale: f64, out: &mut Hess) {
        out.fill(0.0);
        self.anchor
            .position_hessian_dot(q, self.force_at(t) * scale, out);
    }
}

/// The force magnitude |F₀|·f(t) [SI: N] at the times `time` of every
/// time-varying load (released loads and supports among them), by label.
pub fn load_magnitudes<'a>(loads: &'a [PointLoad], time: &[f64]) -> Vec<(&'a str, Vec<f64>)> {
    loads
        .iter()
        .filter(|l| !matches!(l.time, TimeFunction::Constant))
        .map(|l| {
            let f0 = l.force.norm();
            let v = time.iter().map(|&t| f0 * l.time.value(t)).collect();
            (l.label.as_str(), v)
        })
        .collect()
}
