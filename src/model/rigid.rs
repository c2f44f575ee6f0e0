//! Rigid beams: a beam with `"rigid": true` becomes one rigid body with the
//! beam's mass m = ρ h w L [SI: kg], centre at mid-length and moment of
//! inertia m L²/12 [SI: kg m²] about it (the cable element's consistent
//! mass: it has no rotary inertia of the section, so the flexible beam has
//! exactly these three values), its body frame along the beam axis. Every
//! attachment at arc length s becomes the body point (s − L/2, 0); loads in
//! the `beam` frame and co-rotated sensors turn into the global frame at the
//! reference (a rigid body has no deformation to co-rotate with).
//!
//! The transformation is done on the model, before assembly, so every
//! analysis sees an ordinary rigid body (the paper's rigid comparison model).

use super::types::{Beam, LoadFrame, Model, PointSpec, RigidBody, SensorFrame};

impl Beam {
    /// The rigid body with this beam's mass, centre and inertia.
    pub fn as_rigid_body(&self) -> RigidBody {
        let mass = self.mass();
        RigidBody {
            id: self.id.clone(),
            mass,
            inertia: mass * self.length * self.length / 12.0,
            position: self.point_at(0.5 * self.length),
            angle_deg: self.angle_deg,
        }
    }
}

impl Beam {
    /// The point at arc length `s` in the body frame of the beam's rigid
    /// stand-in: (s − L/2, 0) [SI: m].
    pub fn rigid_local(&self, s: f64) -> [f64; 2] {
        [s - 0.5 * self.length, 0.0]
    }
}

fn rotate(angle_deg: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = angle_deg.to_radians().sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

impl Model {
    /// The point on the rigid stand-in of a rigid beam (unchanged elsewhere).
    pub fn rigid_point(&self, p: &PointSpec) -> PointSpec {
        let Some(beam) = p.beam.as_deref().and_then(|id| self.beam(id)) else {
            return p.clone();
        };
        if !beam.rigid {
            return p.clone();
        }
        PointSpec {
            body: Some(beam.id.clone()),
            local: Some(beam.rigid_local(p.s.unwrap_or(0.0))),
            ..PointSpec::default()
        }
    }

    /// The same model with every beam marked `rigid` replaced by its rigid
    /// body (see the module doc).
    pub fn with_rigid_beams(&self) -> Model {
        let mut m = self.clone();
        let beam_of = |p: &PointSpec| {
            p.beam
                .as_deref()
                .and_then(|id| self.beam(id))
                .filter(|b| b.rigid)
        };
        for l in &mut m.loads {
            if let (LoadFrame::Beam, Some(b)) = (l.frame, beam_of(&l.at)) {
                l.force = rotate(b.angle_deg, l.force);
                l.frame = LoadFrame::Global;
            }
            l.at = self.rigid_point(&l.at);
        }
        for s in &mut m.sensors {
            if let (SensorFrame::Corotated, Some(b)) = (s.frame, beam_of(&s.at)) {
                s.direction = rotate(b.angle_deg, s.direction);
                s.frame = SensorFrame::Global;
            }
            s.at = self.rigid_point(&s.at);
        }
        for j in &mut m.joints {
            j.a = self.rigid_point(&j.a);
            j.b = self.rigid_point(&j.b);
        }
        for s in &mut m.springs {
            s.a = self.rigid_point(&s.a);
            s.b = self.rigid_point(&s.b);
        }
        for c in &mut m.contacts {
            let p = self.rigid_point(c.point());
            *c.point_mut() = p;
        }
        let rigid: Vec<RigidBody> = self
            .beams
            .iter()
            .filter(|b| b.rigid)
            .map(Beam::as_rigid_body)
            .collect();
        m.beams.retain(|b| !b.rigid);
        m.rigid_bodies.extend(rigid);
        m
    }

    /// The same model with every beam rigid (`--rigid-beams`).
    pub fn all_beams_rigid(&self) -> Model {
        let mut m = self.clone();
        for b in &mut m.beams {
            b.rigid = true;
        }
        m
    }
}
