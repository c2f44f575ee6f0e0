//! Validation of a parsed model: physical values, ids, points and joint
//! geometry. The first problem found is reported with its JSON path
//! (e.g. `joints[1].b.s`), so a user can go straight to the offending value.

use super::resolved::{
    Resolution, ResolvedJoint, ResolvedJointKind, ResolvedPoint, ResolvedSpring, SpringLength,
    Torsion,
};
use super::types::*;
use crate::error::{Ids, Problem};

/// Two joint points closer than this [SI: m] coincide.
pub const COINCIDENCE_TOLERANCE: f64 = 1e-9;

/// Memory a beam element needs on the sparse path [SI: bytes]: its share of
/// the reduced stiffness and mass triplets, their compressed copies, the
/// factor's fill and the Krylov basis. Measured peak resident memory of
/// `modal --modes 13`: a 2,000-element cantilever 21 MB, welded square
/// grids of 1,000 / 10,000 / 100,000 elements 18 / 139 / 2,287 MB (the fill
/// of a 2-D grid's factor grows faster than the elements).
pub const BYTES_PER_ELEMENT: usize = 24 * 1024;

/// Memory available to this process [SI: bytes], from /proc/meminfo
/// (`MemAvailable`); `None` where that is not readable.
pub fn available_memory() -> Option<usize> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: usize = line.split_whitespace().nth(1)?.parse().ok()?;
    kb.checked_mul(1024)
}

/// A validation failure: the JSON path and what is wrong there.
pub type Failure = (String, Problem);

/// What a point refers to, after its ids are resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PointTarget<'m> {
    Beam {
        beam: &'m Beam,
        index: usize,
        s: f64,
    },
    Rigid {
        body: &'m RigidBody,
        index: usize,
        local: Option<[f64; 2]>,
    },
    PointMass {
        mass: &'m PointMass,
        index: usize,
    },
    Ground {
        position: [f64; 2],
    },
}

impl PointTarget<'_> {
    /// Initial global position, or `None` for `{"body": id}` without `local`
    /// (in a joint that is the partner's point; elsewhere the body's centre).
    pub fn explicit_position(&self) -> Option<[f64; 2]> {
        match *self {
            PointTarget::Beam { beam, s, .. } => Some(beam.point_at(s)),
            PointTarget::Rigid { body, local, .. } => local.map(|l| body.point_at(l)),
            PointTarget::PointMass { mass, .. } => Some(mass.position),
            PointTarget::Ground { position } => Some(position),
        }
    }

    /// Initial global position, taking a rigid body's centre when no `local` is given.
    pub fn position_or_centre(&self) -> [f64; 2] {
        match *self {
            PointTarget::Rigid { body, local, .. } => body.point_at(local.unwrap_or([0.0, 0.0])),
            _ => self
                .explicit_position()
                .expect("only rigid bodies have implicit points"),
        }
    }

    fn has_orientation(&self) -> bool {
        !matches!(self, PointTarget::PointMass { .. })
    }

    fn is_ground(&self) -> bool {
        matches!(self, PointTarget::Ground { .. })
    }
}

impl Beam {
    /// Unit tangent of the straight reference configuration.
    pub fn tangent(&self) -> [f64; 2] {
        let a = self.angle_deg.to_radians();
        [a.cos(), a.sin()]
    }

    /// Reference position of the material point at arc length `s`.
    pub fn point_at(&self, s: f64) -> [f64; 2] {
        let t = self.tangent();
        [self.start[0] + s * t[0], self.start[1] + s * t[1]]
    }
}

impl RigidBody {
    /// Reference position of a body-frame point.
    pub fn point_at(&self, local: [f64; 2]) -> [f64; 2] {
        let (s, c) = self.angle_deg.to_radians().sin_cos();
        [
            self.position[0] + c * local[0] - s * local[1],
            self.position[1] + s * local[0] + c * local[1],
        ]
    }
}

impl Model {
    /// Resolve a point's ids; `path` is its JSON path for messages.
    pub fn resolve<'m>(&'m self, p: &PointSpec, path: &str) -> Result<PointTarget<'m>, Failure> {
        let fail = |key: &str, problem| Err((format!("{path}.{key}"), problem));
        let given: Vec<&'static str> = [
            ("beam", p.beam.is_some()),
            ("body", p.body.is_some()),
            ("ground", p.ground.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, set)| set.then_some(key))
        .collect();
        if given.len() != 1 {
            return Err((path.to_string(), Problem::AmbiguousPoint { given }));
        }
        if let Some(id) = &p.beam {
            if p.local.is_some() {
                return fail(
                    "local",
                    Problem::KeyNotAllowed {
                        key: "local",
                        why: "it belongs to rigid-body points",
                    },
                );
            }
            let (index, beam) = find(&self.beams, id, |b| &b.id).ok_or_else(|| {
                (
                    format!("{path}.beam"),
                    Problem::UnknownId {
                        kind: "beam",
                        id: id.clone(),
                        available: Ids::of(self.beams.iter().map(|b| &b.id)),
                    },
                )
            })?;
            let s =
                p.s.ok_or_else(|| (path.to_string(), Problem::MissingKey { key: "s" }))?;
            check_finite(s, &format!("{path}.s"))?;
            let slack = 1e-12 * beam.length;
            if !(-slack..=beam.length + slack).contains(&s) {
                return fail(
                    "s",
                    Problem::OutOfRange {
                        value: s,
                        min: 0.0,
                        max: beam.length,
                    },
                );
            }
            return Ok(PointTarget::Beam {
                beam,
                index,
                s: s.clamp(0.0, beam.length),
            });
        }
        if p.s.is_some() {
            return fail(
                "s",
                Problem::KeyNotAllowed {
                    key: "s",
                    why: "it belongs to beam points",
                },
            );
        }
        if let Some(position) = p.ground {
            if p.local.is_some() {
                return fail(
                    "local",
                    Problem::KeyNotAllowed {
                        key: "local",
                        why: "it belongs to rigid-body points",
                    },
                );
            }
            check_finite_pair(position, &format!("{path}.ground"))?;
            return Ok(PointTarget::Ground { position });
        }
        let id = p.body.as_ref().expect("exactly one key is set");
        if let Some((index, body)) = find(&self.rigid_bodies, id, |b| &b.id) {
            if let Some(l) = p.local {
                check_finite_pair(l, &format!("{path}.local"))?;
            }
            return Ok(PointTarget::Rigid {
                body,
                index,
                local: p.local,
            });
        }
        if let Some((index, mass)) = find(&self.point_masses, id, |b| &b.id) {
            if p.local.is_some() {
                return fail(
                    "local",
                    Problem::KeyNotAllowed {
                        key: "local",
                        why: "a point mass has no extent",
                    },
                );
            }
            return Ok(PointTarget::PointMass { mass, index });
        }
        fail(
            "body",
            Problem::UnknownId {
                kind: "rigid body or point mass",
                id: id.clone(),
                available: Ids::of(
                    self.rigid_bodies
                        .iter()
                        .map(|b| &b.id)
                        .chain(self.point_masses.iter().map(|p| &p.id)),
                ),
            },
        )
    }

    /// Check everything; the first problem is returned. To keep what the
    /// check found, and to build a [`crate::System`], use
    /// [`Model::validated`].
    pub fn validate(&self) -> Result<(), Failure> {
        self.resolution().map(|_| ())
    }

    /// Check everything and resolve every reference on the way (see
    /// [`super::resolved`]); the first problem is returned.
    pub(crate) fn resolution(&self) -> Result<Resolution, Failure> {
        if self.beams.is_empty() && self.rigid_bodies.is_empty() && self.point_masses.is_empty() {
            return Err((String::from("$"), Problem::NoBodies));
        }
        check_finite_pair(self.gravity, "gravity")?;
        self.validate_ids()?;
        let mut total_elements = 0usize;
        // Read once: a model is validated again after every change
        // (calibration steps, design paths), beam by beam.
        let max_elements = available_memory().unwrap_or(usize::MAX) / BYTES_PER_ELEMENT;
        for (i, b) in self.beams.iter().enumerate() {
            let p = format!("beams[{i}]");
            check_finite_pair(b.start, &format!("{p}.start"))?;
            check_finite(b.angle_deg, &format!("{p}.angle_deg"))?;
            check_positive(b.length, &format!("{p}.length"))?;
            if b.elements == 0 {
                return Err((format!("{p}.elements"), Problem::ZeroCount));
            }
            total_elements = total_elements.saturating_add(b.elements);
            // A model is limited by memory: refuse one that cannot fit
            // rather than abort on a failed allocation.
            let max = max_elements;
            if total_elements > max {
                let problem = Problem::TooManyElements {
                    total: total_elements,
                    max,
                    kib_per_element: BYTES_PER_ELEMENT / 1024,
                };
                return Err((format!("{p}.elements"), problem));
            }
            check_positive(b.section.height, &format!("{p}.section.height"))?;
            check_positive(b.section.width, &format!("{p}.section.width"))?;
            check_positive(b.material.young, &format!("{p}.material.young"))?;
            check_positive(b.material.density, &format!("{p}.material.density"))?;
            if let Some(nu) = b.material.poisson {
                // An isotropic solid has −1 < ν ≤ 0.5.
                if !(nu > -1.0 && nu <= 0.5) {
                    return Err((
                        format!("{p}.material.poisson"),
                        Problem::OutOfRange {
                            value: nu,
                            min: -1.0,
                            max: 0.5,
                        },
                    ));
                }
            }
        }
        for (i, r) in self.rigid_bodies.iter().enumerate() {
            let p = format!("rigid_bodies[{i}]");
            check_positive(r.mass, &format!("{p}.mass"))?;
            check_non_negative(r.inertia, &format!("{p}.inertia"))?;
            check_finite_pair(r.position, &format!("{p}.position"))?;
            check_finite(r.angle_deg, &format!("{p}.angle_deg"))?;
        }
        for (i, m) in self.point_masses.iter().enumerate() {
            let p = format!("point_masses[{i}]");
            check_positive(m.mass, &format!("{p}.mass"))?;
            check_finite_pair(m.position, &format!("{p}.position"))?;
        }
        let mut resolution = Resolution {
            joints: Vec::with_capacity(self.joints.len()),
            springs: Vec::with_capacity(self.springs.len()),
            loads: Vec::with_capacity(self.loads.len()),
            sensors: Vec::with_capacity(self.sensors.len()),
            contacts: Vec::with_capacity(self.contacts.len()),
        };
        for (i, j) in self.joints.iter().enumerate() {
            let joint = self.validate_joint(j, &format!("joints[{i}]"))?;
            resolution.joints.push(joint);
        }
        for (i, s) in self.springs.iter().enumerate() {
            let spring = self.validate_spring(s, &format!("springs[{i}]"))?;
            resolution.springs.push(spring);
        }
        for (i, l) in self.loads.iter().enumerate() {
            let at = self.validate_load(l, &format!("loads[{i}]"))?;
            resolution.loads.push(at);
        }
        for (i, s) in self.sensors.iter().enumerate() {
            let p = format!("sensors[{i}]");
            let at = self.resolve(&s.at, &format!("{p}.at"))?;
            check_direction(s.direction, &format!("{p}.direction"))?;
            if s.frame == SensorFrame::Corotated && !matches!(at, PointTarget::Beam { .. }) {
                let why = "the co-rotated frame is the beam's; use `global` off beams";
                return Err((
                    format!("{p}.frame"),
                    Problem::KeyNotAllowed {
                        key: "corotated",
                        why,
                    },
                ));
            }
            resolution.sensors.push(ResolvedPoint::from(&at));
        }
        for (i, c) in self.contacts.iter().enumerate() {
            let contact = self.validate_contact(c, &format!("contacts[{i}]"))?;
            resolution.contacts.push(contact);
        }
        if let Some(r) = &self.reference {
            check_positive(r.first_bending_hz, "reference.first_bending_hz")?;
        }
        if let Some(d) = &self.damping {
            check_non_negative(d.alpha, "damping.alpha")?;
            check_non_negative(d.beta, "damping.beta")?;
        }
        Ok(resolution)
    }

    fn validate_ids(&self) -> Result<(), Failure> {
        let mut seen = std::collections::HashSet::new();
        let bodies = (self
            .beams
            .iter()
            .enumerate()
            .map(|(i, b)| (format!("beams[{i}].id"), &b.id)))
        .chain(
            self.rigid_bodies
                .iter()
                .enumerate()
                .map(|(i, b)| (format!("rigid_bodies[{i}].id"), &b.id)),
        )
        .chain(
            self.point_masses
                .iter()
                .enumerate()
                .map(|(i, b)| (format!("point_masses[{i}].id"), &b.id)),
        );
        for (path, id) in bodies {
            check_id(id, &path, &mut seen)?;
        }
        let mut contacts = std::collections::HashSet::new();
        for (i, c) in self.contacts.iter().enumerate() {
            check_id(c.id(), &format!("contacts[{i}].id"), &mut contacts)?;
        }
        let mut sensors = std::collections::HashSet::new();
        for (i, s) in self.sensors.iter().enumerate() {
            check_id(&s.id, &format!("sensors[{i}].id"), &mut sensors)?;
        }
        // Optional ids of joints, springs and loads label them in reports
        // (e.g. redundant constraints); each list is its own namespace.
        let optional = [
            (
                "joints",
                self.joints.iter().map(|j| &j.id).collect::<Vec<_>>(),
            ),
            ("springs", self.springs.iter().map(|s| &s.id).collect()),
            ("loads", self.loads.iter().map(|l| &l.id).collect()),
        ];
        for (list, ids) in optional {
            let mut seen = std::collections::HashSet::new();
            for (i, id) in ids.into_iter().enumerate() {
                if let Some(id) = id {
                    check_id(id, &format!("{list}[{i}].id"), &mut seen)?;
                }
            }
        }
        Ok(())
    }

    fn validate_joint(&self, j: &Joint, p: &str) -> Result<ResolvedJoint, Failure> {
        let a = self.resolve(&j.a, &format!("{p}.a"))?;
        let b = self.resolve(&j.b, &format!("{p}.b"))?;
        if a.is_ground() && b.is_ground() {
            return Err((p.to_string(), Problem::GroundToGround));
        }
        let what = match j.kind {
            JointType::Pin => "a torsion spring",
            JointType::Weld => "a weld",
            JointType::Slider => "the slider's axis",
        };
        let needs_a = j.kind == JointType::Weld
            || j.kind == JointType::Slider
            || j.torsion_stiffness.is_some();
        let needs_b = j.kind == JointType::Weld || j.torsion_stiffness.is_some();
        for (side, t, needed) in [("a", &a, needs_a), ("b", &b, needs_b)] {
            if let (true, PointTarget::PointMass { mass, .. }) = (needed, t) {
                return Err((
                    format!("{p}.{side}"),
                    Problem::NoOrientation {
                        id: mass.id.clone(),
                        what,
                    },
                ));
            }
            debug_assert!(!needed || t.has_orientation());
        }
        let not_pin = "only pins carry torsion springs";
        if j.kind != JointType::Pin {
            if j.torsion_stiffness.is_some() {
                return Err((
                    format!("{p}.torsion_stiffness"),
                    Problem::KeyNotAllowed {
                        key: "torsion_stiffness",
                        why: not_pin,
                    },
                ));
            }
            if j.torsion_damping.is_some() {
                return Err((
                    format!("{p}.torsion_damping"),
                    Problem::KeyNotAllowed {
                        key: "torsion_damping",
                        why: not_pin,
                    },
                ));
            }
        }
        if let Some(k) = j.torsion_stiffness {
            check_non_negative(k, &format!("{p}.torsion_stiffness"))?;
        }
        if let Some(c) = j.torsion_damping {
            check_non_negative(c, &format!("{p}.torsion_damping"))?;
            if j.torsion_stiffness.is_none() && !(a.has_orientation() && b.has_orientation()) {
                let id = point_mass_id(&a).or(point_mass_id(&b)).unwrap_or_default();
                return Err((
                    p.to_string(),
                    Problem::NoOrientation {
                        id,
                        what: "a torsion damper",
                    },
                ));
            }
        }
        let kind = match (j.kind, j.axis) {
            (JointType::Slider, None) => {
                return Err((p.to_string(), Problem::MissingKey { key: "axis" }))
            }
            (JointType::Slider, Some(axis)) => {
                check_direction(axis, &format!("{p}.axis"))?;
                ResolvedJointKind::Slider {
                    axis,
                    release: j.release,
                }
            }
            (_, Some(_)) => {
                let why = "only sliders have an axis";
                return Err((
                    format!("{p}.axis"),
                    Problem::KeyNotAllowed { key: "axis", why },
                ));
            }
            (JointType::Pin, None) => ResolvedJointKind::Pin {
                torsion: (j.torsion_stiffness.is_some() || j.torsion_damping.is_some()).then(
                    || Torsion {
                        stiffness: j.torsion_stiffness.unwrap_or(0.0),
                        damping: j.torsion_damping.unwrap_or(0.0),
                    },
                ),
                release: j.release,
            },
            (JointType::Weld, None) => ResolvedJointKind::Weld,
        };
        if let Some(release) = &j.release {
            validate_release(j, release, a.is_ground(), p)?;
        }
        let resolved = ResolvedJoint {
            a: ResolvedPoint::from(&a),
            b: ResolvedPoint::from(&b),
            kind,
        };
        let (pa, pb) = match (a.explicit_position(), b.explicit_position()) {
            (Some(pa), Some(pb)) => (pa, pb),
            (None, None) => return Err((format!("{p}.b"), Problem::MissingKey { key: "local" })),
            _ => return Ok(resolved),
        };
        if let ResolvedJointKind::Slider { axis, .. } = kind {
            let n = [-axis[1], axis[0]];
            let gap = ((pb[0] - pa[0]) * n[0] + (pb[1] - pa[1]) * n[1]) / n[0].hypot(n[1]);
            if gap.abs() > COINCIDENCE_TOLERANCE {
                return Err((p.to_string(), Problem::OffAxis { gap: gap.abs() }));
            }
            return Ok(resolved);
        }
        let gap = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        if gap > COINCIDENCE_TOLERANCE {
            return Err((p.to_string(), Problem::PointsApart { gap, a: pa, b: pb }));
        }
        Ok(resolved)
    }

    fn validate_spring(&self, s: &Spring, p: &str) -> Result<ResolvedSpring, Failure> {
        let a = self.resolve(&s.a, &format!("{p}.a"))?;
        let b = self.resolve(&s.b, &format!("{p}.b"))?;
        if a.is_ground() && b.is_ground() {
            return Err((p.to_string(), Problem::GroundToGround));
        }
        check_positive(s.stiffness, &format!("{p}.stiffness"))?;
        check_non_negative(s.damping, &format!("{p}.damping"))?;
        let (pa, pb) = (a.position_or_centre(), b.position_or_centre());
        let length = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        if length <= COINCIDENCE_TOLERANCE {
            return Err((p.to_string(), Problem::ZeroLength));
        }
        let length = match (s.free_length, s.preload) {
            (Some(l0), None) => {
                check_positive(l0, &format!("{p}.free_length"))?;
                SpringLength::Free(l0)
            }
            (None, Some(f)) => {
                check_finite(f, &format!("{p}.preload"))?;
                let free_length = length - f / s.stiffness;
                if free_length <= 0.0 {
                    let problem = Problem::NonPositiveFreeLength {
                        free_length,
                        preload: f,
                        stiffness: s.stiffness,
                        length,
                    };
                    return Err((format!("{p}.preload"), problem));
                }
                SpringLength::Preload(f)
            }
            (None, None) => {
                return Err((
                    p.to_string(),
                    Problem::MissingKey {
                        key: "free_length` or `preload",
                    },
                ))
            }
            (Some(_), Some(_)) => {
                let why = "give either `free_length` or `preload`";
                return Err((
                    format!("{p}.preload"),
                    Problem::KeyNotAllowed {
                        key: "preload",
                        why,
                    },
                ));
            }
        };
        Ok(ResolvedSpring {
            a: ResolvedPoint::from(&a),
            b: ResolvedPoint::from(&b),
            length,
        })
    }

    fn validate_load(&self, l: &Load, p: &str) -> Result<ResolvedPoint, Failure> {
        let at = self.resolve(&l.at, &format!("{p}.at"))?;
        check_finite_pair(l.force, &format!("{p}.force"))?;
        if l.frame == LoadFrame::Beam && !matches!(at, PointTarget::Beam { .. }) {
            let why = "the `beam` frame needs a beam point";
            return Err((
                format!("{p}.frame"),
                Problem::KeyNotAllowed { key: "beam", why },
            ));
        }
        if at.is_ground() {
            let why = "a load on the ground does nothing";
            return Err((
                format!("{p}.at"),
                Problem::KeyNotAllowed { key: "ground", why },
            ));
        }
        validate_time(&l.time, &format!("{p}.time"))?;
        Ok(ResolvedPoint::from(&at))
    }
}

/// A time function's numbers, `path` naming it (e.g. `loads[0].time`).
fn validate_time(f: &TimeFunction, path: &str) -> Result<(), Failure> {
    match *f {
        TimeFunction::Constant => Ok(()),
        TimeFunction::HalfSine { duration } => {
            check_positive(duration, &format!("{path}.half_sine.duration"))
        }
        TimeFunction::Step { start } => check_non_negative(start, &format!("{path}.step.start")),
        TimeFunction::Until(until) => check_non_negative(until, &format!("{path}.until")),
        TimeFunction::RampDown { start, duration } => {
            check_non_negative(start, &format!("{path}.ramp_down.start"))?;
            check_positive(duration, &format!("{path}.ramp_down.duration"))
        }
    }
}

/// A released support: a pin or a slider (their reaction is a force), no
/// torsion spring or damper, released by `until` or `ramp_down`.
fn validate_release(
    j: &Joint,
    release: &TimeFunction,
    a_on_ground: bool,
    p: &str,
) -> Result<(), Failure> {
    let path = format!("{p}.release");
    let why = match (j.kind, release) {
        (JointType::Weld, _) => {
            Some("a weld's reaction includes a moment; only pins and sliders can be released")
        }
        (JointType::Slider, _) if !a_on_ground => {
            Some("a released slider needs its rail (point `a`) on the ground")
        }
        _ if j.torsion_stiffness.is_some() || j.torsion_damping.is_some() => {
            Some("a released pin cannot carry a torsion spring or damper")
        }
        (_, TimeFunction::Until(_) | TimeFunction::RampDown { .. }) => None,
        _ => Some("a support is released by `until` or `ramp_down` (it holds in full at t = 0)"),
    };
    match why {
        Some(why) => Err((
            path,
            Problem::KeyNotAllowed {
                key: "release",
                why,
            },
        )),
        None => validate_time(release, &path),
    }
}

fn point_mass_id(t: &PointTarget) -> Option<String> {
    match t {
        PointTarget::PointMass { mass, .. } => Some(mass.id.clone()),
        _ => None,
    }
}

fn find<'a, T>(items: &'a [T], id: &str, key: impl Fn(&T) -> &String) -> Option<(usize, &'a T)> {
    items.iter().enumerate().find(|(_, t)| key(t) == id)
}

fn check_id(
    id: &str,
    path: &str,
    seen: &mut std::collections::HashSet<String>,
) -> Result<(), Failure> {
    if id.trim().is_empty() {
        return Err((path.to_string(), Problem::EmptyId));
    }
    if !seen.insert(id.to_string()) {
        return Err((
            path.to_string(),
            Problem::DuplicateId { id: id.to_string() },
        ));
    }
    Ok(())
}

fn check_finite(value: f64, path: &str) -> Result<(), Failure> {
    if value.is_finite() {
        Ok(())
    } else {
        Err((path.to_string(), Problem::NotFinite { value }))
    }
}

pub(super) fn check_finite_pair(v: [f64; 2], path: &str) -> Result<(), Failure> {
    check_finite(v[0], &format!("{path}[0]"))?;
    check_finite(v[1], &format!("{path}[1]"))
}

pub(super) fn check_positive(value: f64, path: &str) -> Result<(), Failure> {
    check_finite(value, path)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err((path.to_string(), Problem::NotPositive { value }))
    }
}

pub(super) fn check_non_negative(value: f64, path: &str) -> Result<(), Failure> {
    check_finite(value, path)?;
    if value >= 0.0 {
        Ok(())
    } else {
        Err((path.to_string(), Problem::Negative { value }))
    }
}

fn check_direction(d: [f64; 2], path: &str) -> Result<(), Failure> {
    check_finite_pair(d, path)?;
    if d[0] == 0.0 && d[1] == 0.0 {
        return Err((path.to_string(), Problem::ZeroDirection));
    }
    Ok(())
}
