//! Where a model sits: its centre of mass and rigid placements of the
//! whole model.
//!
//! The physics of an assembly does not depend on where it sits or how it
//! is turned. Two things here serve that:
//! - [`Model::centre_of_mass`] [SI: m]: the system is assembled relative
//!   to it ([`crate::System::origin`]), so a model placed 1 km from the
//!   origin keeps its positions O(its own size) inside, and no lever arm,
//!   rigid-motion field or tolerance loses the digits an offset of 1 km
//!   would cost (ε·1 km ≈ 2e-13 m against elements of millimetres).
//! - [`Model::placed`]: the same model turned by an angle about the
//!   global origin and moved by an offset, with every global-frame vector
//!   turned along (gravity, global loads and sensor directions, slider
//!   axes, ground points and ground segments); body-frame and beam-frame
//!   quantities stay as they are. The placement property tests use it, and
//!   a user can use it to put a sub-assembly where it belongs.

use super::types::{JointType, LoadFrame, Model, PointSpec, SensorFrame};

/// A rigid placement of the plane: turn by `angle_deg` about the origin,
/// then move by `offset` [SI: m].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Rotation [deg], counter-clockwise.
    pub angle_deg: f64,
    /// Translation after the rotation [SI: m].
    pub offset: [f64; 2],
}

impl Placement {
    /// A pure translation (exact: no rotation arithmetic touches a value).
    pub fn translation(offset: [f64; 2]) -> Placement {
        Placement {
            angle_deg: 0.0,
            offset,
        }
    }

    /// A free vector turned by the rotation.
    pub fn turn(&self, v: [f64; 2]) -> [f64; 2] {
        if self.angle_deg == 0.0 {
            return v;
        }
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }

    /// A point turned and moved.
    pub fn point(&self, p: [f64; 2]) -> [f64; 2] {
        let r = self.turn(p);
        [r[0] + self.offset[0], r[1] + self.offset[1]]
    }

    fn point_spec(&self, p: &mut PointSpec) {
        if let Some(g) = p.ground.as_mut() {
            *g = self.point(*g);
        }
    }
}

impl Model {
    /// The centre of mass of the reference configuration [SI: m]: beams
    /// at their mid-length with ρ h w L, rigid bodies and point masses at
    /// their positions. The origin when the model has no mass.
    pub fn centre_of_mass(&self) -> [f64; 2] {
        let mut total = 0.0;
        let mut moment = [0.0; 2];
        let mut add = |m: f64, p: [f64; 2]| {
            if m.is_finite() && m > 0.0 && p.iter().all(|x| x.is_finite()) {
                total += m;
                moment[0] += m * p[0];
                moment[1] += m * p[1];
            }
        };
        for b in &self.beams {
            add(b.mass(), b.point_at(0.5 * b.length));
        }
        for r in &self.rigid_bodies {
            add(r.mass, r.position);
        }
        for p in &self.point_masses {
            add(p.mass, p.position);
        }
        if total > 0.0 {
            [moment[0] / total, moment[1] / total]
        } else {
            [0.0; 2]
        }
    }

    /// The same model placed rigidly (see the module doc).
    pub fn placed(&self, placement: &Placement) -> Model {
        let mut m = self.clone();
        let p = placement;
        m.gravity = p.turn(m.gravity);
        for b in &mut m.beams {
            b.start = p.point(b.start);
            b.angle_deg += p.angle_deg;
        }
        for r in &mut m.rigid_bodies {
            r.position = p.point(r.position);
            r.angle_deg += p.angle_deg;
        }
        for pm in &mut m.point_masses {
            pm.position = p.point(pm.position);
        }
        for j in &mut m.joints {
            p.point_spec(&mut j.a);
            p.point_spec(&mut j.b);
            if j.kind == JointType::Slider {
                j.axis = j.axis.map(|a| p.turn(a));
            }
        }
        for s in &mut m.springs {
            p.point_spec(&mut s.a);
            p.point_spec(&mut s.b);
        }
        for l in &mut m.loads {
            p.point_spec(&mut l.at);
            if l.frame == LoadFrame::Global {
                l.force = p.turn(l.force);
            }
        }
        for s in &mut m.sensors {
            p.point_spec(&mut s.at);
            if s.frame == SensorFrame::Global {
                s.direction = p.turn(s.direction);
            }
        }
        for c in &mut m.contacts {
            p.point_spec(c.point_mut());
            let seg = c.segment_mut();
            if seg.ground == Some(true) {
                seg.from = p.point(seg.from);
                seg.to = p.point(seg.to);
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_quarter_turn_maps_the_axes_and_a_translation_is_exact() {
        let p = Placement {
            angle_deg: 90.0,
            offset: [1.0, 2.0],
        };
        let x = p.point([1.0, 0.0]);
        assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 3.0).abs() < 1e-15);
        let t = Placement::translation([1e3, -1e3]);
        assert_eq!(t.point([0.1, 0.2]), [1e3 + 0.1, -1e3 + 0.2]);
    }
}
