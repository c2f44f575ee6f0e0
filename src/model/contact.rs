//! Contacts in the model file (`contacts`): unilateral, compliant contacts
//! between a point with a radius and a segment of a rigid body or of the
//! ground, and their validation.
//!
//! - `pin_slot`: a pin of radius r [SI: m] in a stadium-shaped slot: the
//!   segment `from`–`to` (body frame) swept by a circle of radius
//!   width/2. Clearance c = width/2 − r; penetration δ = dist(pin centre,
//!   segment) − c [SI: m] (flat sides and end caps, as in DyS's pin–slot
//!   clearance joint).
//! - `point_line`: a point of radius r against one side of a segment;
//!   δ = r − (signed distance to the line on that side), only while the
//!   point lies over the segment.
//!
//! Contact laws (`law.model`), δ̇ the penetration rate [SI: m/s]:
//! `linear` F = kδ + dδ̇; `hertz` F = Kδⁿ; `lankarani_nikravesh`,
//! `hunt_crossley`, `flores`: F = Kδⁿ(1 + ξ δ̇/δ̇⁻) with ξ = 3(1 − c_r²)/4,
//! 3(1 − c_r)/2 and 8(1 − c_r)/(5 c_r), δ̇⁻ = max(the approach speed at the
//! start of the impact, `min_impact_velocity`). F is never negative.
//! Optional `friction` μ: regularized Coulomb force μF v_t/√(v_t² + v_s²),
//! v_s = `friction_velocity` [SI: m/s].

use super::resolved::{ResolvedContact, ResolvedContactKind, ResolvedPoint};
use super::types::PointSpec;
use super::validate::{
    check_finite_pair, check_non_negative, check_positive, Failure, PointTarget,
};
use super::Model;
use crate::error::Problem;
use serde::{Deserialize, Serialize};

/// Default δ̇⁻ floor [SI: m/s] (DESIGN §7).
pub const DEFAULT_MIN_IMPACT_VELOCITY: f64 = 1e-3;
/// Default friction regularization speed [SI: m/s].
pub const DEFAULT_FRICTION_VELOCITY: f64 = 1e-4;

/// A contact between a point and a segment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum Contact {
    /// A pin in a slot with clearance.
    PinSlot {
        id: String,
        slot: Segment,
        /// The pin's centre.
        pin: PointSpec,
        /// [SI: m], below width/2.
        pin_radius: f64,
        law: ContactLaw,
        /// Coulomb coefficient μ [–].
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction: Option<f64>,
        /// Regularization speed of the friction law [SI: m/s].
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction_velocity: Option<f64>,
    },
    /// A rounded point against one side of a segment.
    PointLine {
        id: String,
        point: PointSpec,
        /// [SI: m], ≥ 0.
        radius: f64,
        line: Segment,
        /// The side of the direction `from`→`to` the point stays on;
        /// default: the side it starts on.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        side: Option<Side>,
        law: ContactLaw,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction: Option<f64>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        friction_velocity: Option<f64>,
    },
}

/// A segment fixed in a rigid body (`body`) or in space (`ground: true`),
/// its end points in the body frame (global for the ground) [SI: m].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Segment {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<bool>,
    pub from: [f64; 2],
    pub to: [f64; 2],
    /// Slot width [SI: m]; `pin_slot` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<f64>,
}

/// Side of a directed line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    Left,
    Right,
}

/// The normal-force law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LawModel {
    Linear,
    Hertz,
    LankaraniNikravesh,
    HuntCrossley,
    Flores,
}

/// Parameters of a contact law; which apply depends on `model`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ContactLaw {
    pub model: LawModel,
    /// k [SI: N/m] for `linear`, K [SI: N/mⁿ] otherwise.
    pub stiffness: f64,
    /// d [SI: N s/m]; `linear` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<f64>,
    /// n [–]; default 1.5; not for `linear`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exponent: Option<f64>,
    /// Coefficient of restitution c_r in (0, 1]; the dissipative laws.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// δ̇⁻ floor [SI: m/s]; default 1e-3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_impact_velocity: Option<f64>,
}

impl ContactLaw {
    /// Whether the law has a hysteresis-damping factor ξ.
    pub fn is_dissipative(&self) -> bool {
        matches!(
            self.model,
            LawModel::LankaraniNikravesh | LawModel::HuntCrossley | LawModel::Flores
        )
    }

    /// The exponent n (1 for `linear`).
    pub fn exponent(&self) -> f64 {
        match self.model {
            LawModel::Linear => 1.0,
            _ => self.exponent.unwrap_or(1.5),
        }
    }

    /// The hysteresis factor ξ [–] (0 for `linear` and `hertz`).
    pub fn xi(&self) -> f64 {
        let c = self.restitution.unwrap_or(1.0);
        match self.model {
            LawModel::Linear | LawModel::Hertz => 0.0,
            LawModel::LankaraniNikravesh => 3.0 * (1.0 - c * c) / 4.0,
            LawModel::HuntCrossley => 3.0 * (1.0 - c) / 2.0,
            LawModel::Flores => 8.0 * (1.0 - c) / (5.0 * c),
        }
    }
}

impl Contact {
    pub fn id(&self) -> &str {
        match self {
            Contact::PinSlot { id, .. } | Contact::PointLine { id, .. } => id,
        }
    }

    pub fn law(&self) -> &ContactLaw {
        match self {
            Contact::PinSlot { law, .. } | Contact::PointLine { law, .. } => law,
        }
    }

    /// The moving point (pin centre or rounded point).
    pub fn point(&self) -> &PointSpec {
        match self {
            Contact::PinSlot { pin, .. } => pin,
            Contact::PointLine { point, .. } => point,
        }
    }

    pub fn point_mut(&mut self) -> &mut PointSpec {
        match self {
            Contact::PinSlot { pin, .. } => pin,
            Contact::PointLine { point, .. } => point,
        }
    }

    pub fn segment(&self) -> &Segment {
        match self {
            Contact::PinSlot { slot, .. } => slot,
            Contact::PointLine { line, .. } => line,
        }
    }

    pub fn segment_mut(&mut self) -> &mut Segment {
        match self {
            Contact::PinSlot { slot, .. } => slot,
            Contact::PointLine { line, .. } => line,
        }
    }

    /// (μ, regularization speed) when the contact has friction.
    pub fn friction(&self) -> Option<(f64, f64)> {
        let (mu, v) = match self {
            Contact::PinSlot {
                friction,
                friction_velocity,
                ..
            }
            | Contact::PointLine {
                friction,
                friction_velocity,
                ..
            } => (friction, friction_velocity),
        };
        mu.map(|mu| (mu, v.unwrap_or(DEFAULT_FRICTION_VELOCITY)))
    }
}

/// Where a segment lives, after its id is resolved.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SegmentOwner {
    Ground,
    /// Index into `rigid_bodies`.
    Body(usize),
}

impl Model {
    /// The owner of a contact's segment; `path` is the segment's JSON path.
    pub fn segment_owner(&self, s: &Segment, path: &str) -> Result<SegmentOwner, Failure> {
        match (&s.body, s.ground) {
            (Some(id), None) => self
                .rigid_bodies
                .iter()
                .position(|b| &b.id == id)
                .map(SegmentOwner::Body)
                .ok_or_else(|| {
                    (
                        format!("{path}.body"),
                        Problem::UnknownId {
                            kind: "rigid body",
                            id: id.clone(),
                            available: crate::error::Ids::of(
                                self.rigid_bodies.iter().map(|b| &b.id),
                            ),
                        },
                    )
                }),
            (None, Some(true)) => Ok(SegmentOwner::Ground),
            (None, Some(false)) => Err((
                format!("{path}.ground"),
                Problem::KeyNotAllowed {
                    key: "ground",
                    why: "give `\"ground\": true` or a `body`",
                },
            )),
            (Some(_), Some(_)) => Err((
                path.to_string(),
                Problem::AmbiguousPoint {
                    given: vec!["body", "ground"],
                },
            )),
            (None, None) => Err((
                path.to_string(),
                Problem::MissingKey {
                    key: "body` or `ground",
                },
            )),
        }
    }

    /// The segment's end points in the global frame at the reference.
    pub fn segment_global(&self, s: &Segment, owner: SegmentOwner) -> ([f64; 2], [f64; 2]) {
        match owner {
            SegmentOwner::Ground => (s.from, s.to),
            SegmentOwner::Body(i) => {
                let b = &self.rigid_bodies[i];
                (b.point_at(s.from), b.point_at(s.to))
            }
        }
    }

    pub(super) fn validate_contact(
        &self,
        c: &Contact,
        p: &str,
    ) -> Result<ResolvedContact, Failure> {
        let seg = c.segment();
        let seg_path = match c {
            Contact::PinSlot { .. } => format!("{p}.slot"),
            Contact::PointLine { .. } => format!("{p}.line"),
        };
        let owner = self.segment_owner(seg, &seg_path)?;
        check_finite_pair(seg.from, &format!("{seg_path}.from"))?;
        check_finite_pair(seg.to, &format!("{seg_path}.to"))?;
        let length = (seg.to[0] - seg.from[0]).hypot(seg.to[1] - seg.from[1]);
        if length <= super::validate::COINCIDENCE_TOLERANCE {
            return Err((seg_path, Problem::DegenerateSegment { length }));
        }
        let point_path = match c {
            Contact::PinSlot { .. } => format!("{p}.pin"),
            Contact::PointLine { .. } => format!("{p}.point"),
        };
        let target = self.resolve(c.point(), &point_path)?;
        if let (PointTarget::Ground { .. }, SegmentOwner::Ground) = (&target, owner) {
            return Err((p.to_string(), Problem::GroundToGround));
        }
        if let (PointTarget::Rigid { index, .. }, SegmentOwner::Body(b)) = (&target, owner) {
            if *index == b {
                return Err((
                    point_path,
                    Problem::KeyNotAllowed {
                        key: "body",
                        why: "the point and the segment belong to the same body",
                    },
                ));
            }
        }
        let kind = match c {
            Contact::PinSlot {
                pin_radius, slot, ..
            } => {
                check_positive(*pin_radius, &format!("{p}.pin_radius"))?;
                let width = slot
                    .width
                    .ok_or_else(|| (format!("{p}.slot"), Problem::MissingKey { key: "width" }))?;
                check_positive(width, &format!("{p}.slot.width"))?;
                if *pin_radius >= 0.5 * width {
                    return Err((
                        format!("{p}.pin_radius"),
                        Problem::PinTooLarge {
                            radius: *pin_radius,
                            width,
                        },
                    ));
                }
                ResolvedContactKind::PinSlot {
                    clearance: 0.5 * width - pin_radius,
                }
            }
            Contact::PointLine {
                radius, line, side, ..
            } => {
                check_non_negative(*radius, &format!("{p}.radius"))?;
                if line.width.is_some() {
                    return Err((
                        format!("{p}.line.width"),
                        Problem::KeyNotAllowed {
                            key: "width",
                            why: "only slots have a width",
                        },
                    ));
                }
                if side.is_none() {
                    let (a, b) = self.segment_global(line, owner);
                    let pos = target.position_or_centre();
                    let (tx, ty) = ((b[0] - a[0]) / length, (b[1] - a[1]) / length);
                    let h = -ty * (pos[0] - a[0]) + tx * (pos[1] - a[1]);
                    if h.abs() <= *radius {
                        return Err((
                            format!("{p}.side"),
                            Problem::SideNeeded {
                                distance: h.abs(),
                                radius: *radius,
                            },
                        ));
                    }
                }
                ResolvedContactKind::PointLine {
                    radius: *radius,
                    side: *side,
                }
            }
        };
        if let Some((mu, v)) = c.friction() {
            check_non_negative(mu, &format!("{p}.friction"))?;
            check_positive(v, &format!("{p}.friction_velocity"))?;
        }
        self.validate_law(c.law(), &format!("{p}.law"))?;
        Ok(ResolvedContact {
            owner,
            point: ResolvedPoint::from(&target),
            kind,
        })
    }

    fn validate_law(&self, law: &ContactLaw, p: &str) -> Result<(), Failure> {
        check_positive(law.stiffness, &format!("{p}.stiffness"))?;
        let not = |key: &'static str, why: &'static str| {
            Err((format!("{p}.{key}"), Problem::KeyNotAllowed { key, why }))
        };
        let linear = law.model == LawModel::Linear;
        match law.damping {
            Some(_) if !linear => {
                return not("damping", "only the `linear` law has a damping coefficient")
            }
            Some(d) => check_non_negative(d, &format!("{p}.damping"))?,
            None => {}
        }
        if let Some(n) = law.exponent {
            if linear {
                return not("exponent", "the `linear` law has exponent 1");
            }
            check_positive(n, &format!("{p}.exponent"))?;
        }
        match (law.is_dissipative(), law.restitution) {
            (true, None) => {
                return Err((p.to_string(), Problem::MissingKey { key: "restitution" }))
            }
            (true, Some(c)) if !(c > 0.0 && c <= 1.0) => {
                return Err((
                    format!("{p}.restitution"),
                    Problem::OutOfRange {
                        value: c,
                        min: 0.0,
                        max: 1.0,
                    },
                ))
            }
            (false, Some(_)) => {
                return not(
                    "restitution",
                    "only lankarani_nikravesh, hunt_crossley and flores use a restitution",
                )
            }
            _ => {}
        }
        if let Some(v) = law.min_impact_velocity {
            check_positive(v, &format!("{p}.min_impact_velocity"))?;
        }
        Ok(())
    }
}
