//! Sensor readings: displacement, velocity or acceleration of a material
//! point along a measuring direction, in the global frame or co-rotated with
//! the beam.
//!
//! Co-rotated frame (vibrometer on a flying part): the best-fit rigid motion
//! of the beam's nodes (2-D Procrustes: centroid c(t) and angle φ(t)
//! minimizing Σ|pᵢ − c − R(φ)(Pᵢ − C)|²) is removed. With w = r − c the
//! sensor point relative to the centroid, the co-rotated displacement is
//! u = R(φ)ᵀw − (r₀ − C), and its rates follow from differentiating that
//! exactly (φ̇, φ̈ from the node velocities and accelerations), so the rigid
//! drift and spin of a free-free part do not leak into the spectrum.
//! Units: [SI: m], [SI: m/s], [SI: m/s²].

use crate::analysis::transient::State;
use crate::model::{SensorFrame, SensorQuantity};
use crate::system::{SensorPoint, System};
use nalgebra::{Matrix2, Vector2};

/// A sensor with the reference data its frame needs.
#[derive(Debug, Clone)]
pub struct SensorProbe {
    pub point: SensorPoint,
    /// For the co-rotated frame: the beam's node position indices and their
    /// reference positions relative to the reference centroid.
    nodes: Vec<usize>,
    reference: Vec<Vector2<f64>>,
    /// Sensor point relative to the reference centroid.
    offset0: Vector2<f64>,
    /// Measuring direction in the global frame at the reference.
    direction: Vector2<f64>,
}

/// Centroid and rotation of the best fit, with first and second rates:
/// the rotation as R(φ)ᵀ, and φ̇, φ̈.
struct Fit {
    c: [Vector2<f64>; 3],
    rt: Matrix2<f64>,
    phi_rates: [f64; 2],
}

/// R(φ)ᵀ for φ = atan2(s, c), c² + s² = `den`: (cos φ, sin φ) = (c, s)/√den,
/// no angle formed (atan2 and sin_cos were a tenth of an impulse run).
fn rot_t(c: f64, s: f64, den: f64) -> Matrix2<f64> {
    if den > 0.0 {
        let r = den.sqrt();
        let (c, s) = (c / r, s / r);
        Matrix2::new(c, s, -s, c)
    } else {
        Matrix2::identity()
    }
}

/// J with Rᵀ' = Rᵀ J (d/dφ of Rᵀ(φ)).
fn jm() -> Matrix2<f64> {
    Matrix2::new(0.0, 1.0, -1.0, 0.0)
}

impl SensorProbe {
    pub fn new(system: &System, point: &SensorPoint) -> SensorProbe {
        let q0 = &system.q0;
        let r0 = point.anchor.position(q0);
        let (nodes, reference, offset0, direction) = match (point.frame, point.beam) {
            (SensorFrame::Corotated, Some(b)) => {
                let beam = &system.beams[b];
                let nodes: Vec<usize> = (0..beam.node_count()).map(|k| beam.dof0 + 4 * k).collect();
                let pts: Vec<Vector2<f64>> = nodes
                    .iter()
                    .map(|&i| Vector2::new(q0[i], q0[i + 1]))
                    .collect();
                let c = pts.iter().sum::<Vector2<f64>>() / pts.len() as f64;
                let t = beam.tangent;
                let dir = t * point.direction.x + Vector2::new(-t.y, t.x) * point.direction.y;
                (nodes, pts.iter().map(|p| p - c).collect(), r0 - c, dir)
            }
            _ => (Vec::new(), Vec::new(), r0, point.direction),
        };
        SensorProbe {
            point: point.clone(),
            nodes,
            reference,
            offset0,
            direction,
        }
    }

    pub fn id(&self) -> &str {
        &self.point.id
    }

    /// Best fit of the beam's nodes and its rates up to the `ORDER`-th
    /// (1 or 2; the second rates are 0 when not asked for). A constant, so
    /// that the loops over the rates unroll (the impulse reads a velocity
    /// at every step).
    fn fit<const ORDER: usize>(&self, st: &State) -> Fit {
        let n = self.nodes.len() as f64;
        let node = |x: &[f64], i: usize| Vector2::new(x[i], x[i + 1]);
        let x = [&st.q, &st.v, &st.a];
        let mut c = [Vector2::zeros(); 3];
        for &i in &self.nodes {
            for o in 0..=ORDER {
                c[o] += node(x[o], i);
            }
        }
        c.iter_mut().for_each(|x| *x /= n);
        // S = Σ P̃ × p̃, C = Σ P̃ · p̃ and their rates.
        let (mut s, mut cc) = ([0.0; 3], [0.0; 3]);
        for (k, &i) in self.nodes.iter().enumerate() {
            let p = self.reference[k];
            for o in 0..=ORDER {
                let d = node(x[o], i) - c[o];
                s[o] += p.x * d.y - p.y * d.x;
                cc[o] += p.dot(&d);
            }
        }
        let den = cc[0] * cc[0] + s[0] * s[0];
        let num = cc[0] * s[1] - s[0] * cc[1];
        let phi_d = num / den;
        let phi_dd = if ORDER == 2 {
            let num_d = cc[0] * s[2] - s[0] * cc[2];
            let den_d = 2.0 * (cc[0] * cc[1] + s[0] * s[1]);
            (num_d * den - num * den_d) / (den * den)
        } else {
            0.0
        };
        Fit {
            c,
            rt: rot_t(cc[0], s[0], den),
            phi_rates: [phi_d, phi_dd],
        }
    }

    /// The reading at a state, in the sensor's quantity and frame.
    pub fn read(&self, st: &State) -> f64 {
        self.read_as(st, self.point.quantity)
    }

    /// The reading of another quantity at the same point and frame (e.g. the
    /// velocity of a displacement sensor, for interpolation).
    pub fn read_as(&self, st: &State, quantity: SensorQuantity) -> f64 {
        let anchor = &self.point.anchor;
        let r = anchor.position(&st.q);
        if self.nodes.is_empty() {
            let value = match quantity {
                SensorQuantity::Displacement => r - self.offset0,
                SensorQuantity::Velocity => anchor.velocity(&st.q, &st.v),
                SensorQuantity::Acceleration => anchor.acceleration(&st.q, &st.v, &st.a),
            };
            return value.dot(&self.direction);
        }
        // The acceleration's fit only for an acceleration (the impulse
        // reads a velocity at every step).
        let fit = if quantity == SensorQuantity::Acceleration {
            self.fit::<2>(st)
        } else {
            self.fit::<1>(st)
        };
        let rt = fit.rt;
        let j = jm();
        let w = r - fit.c[0];
        let value = match quantity {
            SensorQuantity::Displacement => rt * w - self.offset0,
            SensorQuantity::Velocity => {
                let wd = anchor.velocity(&st.q, &st.v) - fit.c[1];
                rt * (wd + j * w * fit.phi_rates[0])
            }
            SensorQuantity::Acceleration => {
                let wd = anchor.velocity(&st.q, &st.v) - fit.c[1];
                let wdd = anchor.acceleration(&st.q, &st.v, &st.a) - fit.c[2];
                let (pd, pdd) = (fit.phi_rates[0], fit.phi_rates[1]);
                rt * (wdd + j * wd * (2.0 * pd) + j * w * pdd - w * (pd * pd))
            }
        };
        value.dot(&self.direction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// R(φ)ᵀ from (c, s)/√(c² + s²) is the one from φ = atan2(s, c),
        /// sin φ and cos φ, to round-off (both are within an ulp or two of
        /// the true rotation), at every angle and scale.
        #[test]
        fn rotation_without_the_angle_is_the_angles_rotation(
            phi in -std::f64::consts::PI..std::f64::consts::PI,
            scale in prop_oneof![Just(1.0), 1e-12..1e6f64],
        ) {
            let (c, s) = (scale * phi.cos(), scale * phi.sin());
            let (sin, cos) = s.atan2(c).sin_cos();
            let expected = Matrix2::new(cos, sin, -sin, cos);
            let got = rot_t(c, s, c * c + s * s);
            prop_assert!((got - expected).amax() <= 4.0 * f64::EPSILON, "{got} vs {expected}");
        }
    }

    #[test]
    fn no_rotation_without_a_fit() {
        assert_eq!(rot_t(0.0, 0.0, 0.0), Matrix2::identity());
    }
}
