//! What validation finds out about a model's references, kept as owned,
//! index-based data: the body each point is on, each joint's kind with what
//! only that kind has (a slider's axis, a pin's torsion spring, the release
//! of the joints that can be released), each spring's free length or
//! preload, each contact's segment owner and clearance.
//!
//! [`super::Model::validate`] produces it while it checks the model, so the
//! assembly ([`crate::System::new`]) reads the answers instead of looking
//! the ids up again: nothing there can be missing.

use super::contact::{SegmentOwner, Side};
use super::types::{Model, TimeFunction};
use super::validate::PointTarget;

/// A point after its ids are resolved: which body of the model it is on
/// (by index into the model's list of that kind) and where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ResolvedPoint {
    /// On `beams[index]` at arc length `s` [SI: m], within [0, L].
    Beam { index: usize, s: f64 },
    /// On `rigid_bodies[index]` at the body-frame point `local` [SI: m];
    /// `None`: the body's centre, or in a joint the partner's point.
    Rigid {
        index: usize,
        local: Option<[f64; 2]>,
    },
    /// At `point_masses[index]`.
    PointMass { index: usize },
    /// Fixed in space at `position` [SI: m].
    Ground { position: [f64; 2] },
}

impl From<&PointTarget<'_>> for ResolvedPoint {
    fn from(t: &PointTarget<'_>) -> Self {
        match *t {
            PointTarget::Beam { index, s, .. } => ResolvedPoint::Beam { index, s },
            PointTarget::Rigid { index, local, .. } => ResolvedPoint::Rigid { index, local },
            PointTarget::PointMass { index, .. } => ResolvedPoint::PointMass { index },
            PointTarget::Ground { position } => ResolvedPoint::Ground { position },
        }
    }
}

impl ResolvedPoint {
    /// Initial global position in `model` (the model the point was
    /// resolved in: its indices are that model's), or `None` for a
    /// rigid-body point without `local` (see
    /// [`PointTarget::explicit_position`]). Crate-only: the assembly calls
    /// it with its own model.
    pub(crate) fn explicit_position(&self, model: &Model) -> Option<[f64; 2]> {
        match *self {
            ResolvedPoint::Beam { index, s } => Some(model.beams[index].point_at(s)),
            ResolvedPoint::Rigid { index, local } => {
                local.map(|l| model.rigid_bodies[index].point_at(l))
            }
            ResolvedPoint::PointMass { index } => Some(model.point_masses[index].position),
            ResolvedPoint::Ground { position } => Some(position),
        }
    }
}

/// A pin's torsion spring and damper (either may be left out: 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Torsion {
    /// [SI: N m/rad]
    pub stiffness: f64,
    /// [SI: N m s/rad]
    pub damping: f64,
}

/// A joint's kind with what only that kind has.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ResolvedJointKind {
    /// `release`: `until` or `ramp_down` (a released pin has no torsion).
    Pin {
        torsion: Option<Torsion>,
        release: Option<TimeFunction>,
    },
    Weld,
    /// `axis`: non-zero, global frame; `release` only with point a on the
    /// ground.
    Slider {
        axis: [f64; 2],
        release: Option<TimeFunction>,
    },
}

/// A joint's points and kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ResolvedJoint {
    pub a: ResolvedPoint,
    pub b: ResolvedPoint,
    pub kind: ResolvedJointKind,
}

/// How a spring's unstressed length is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum SpringLength {
    /// The free length [SI: m], > 0.
    Free(f64),
    /// The tension at the initial length [SI: N]; the free length follows
    /// from the assembled positions (positive there).
    Preload(f64),
}

/// A spring's points and length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ResolvedSpring {
    pub a: ResolvedPoint,
    pub b: ResolvedPoint,
    pub length: SpringLength,
}

/// What distinguishes the two contact kinds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum ResolvedContactKind {
    /// Clearance width/2 − pin radius [SI: m], > 0.
    PinSlot { clearance: f64 },
    /// `side`: `None` when the point starts off the line by more than
    /// `radius`, on the side it starts on.
    PointLine { radius: f64, side: Option<Side> },
}

/// A contact's segment owner, point and kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ResolvedContact {
    pub owner: SegmentOwner,
    pub point: ResolvedPoint,
    pub kind: ResolvedContactKind,
}

/// Everything of one model, in the model's order: `joints[i]` is the
/// model's `joints[i]`, and so on.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Resolution {
    pub joints: Vec<ResolvedJoint>,
    pub springs: Vec<ResolvedSpring>,
    /// Where each load acts.
    pub loads: Vec<ResolvedPoint>,
    /// Where each sensor is.
    pub sensors: Vec<ResolvedPoint>,
    pub contacts: Vec<ResolvedContact>,
}
