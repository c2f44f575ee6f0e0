//! Serde types of the JSON model file.
//!
//! All values are SI: metres, kilograms, seconds, newtons, pascals. Angles are
//! in degrees only where the key ends in `_deg`. Every struct denies unknown
//! keys, so a misspelt key is an error instead of a silently ignored value.
//! These types are plain input: nothing here is numerical beyond storage, and
//! nothing is mutated after parsing. See [`super::validate`] for the checks.

use serde::{Deserialize, Serialize};

/// A whole assembly as written in a model file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Model {
    /// Short name, used in reports.
    pub name: String,
    /// Free text: the assumptions behind the model.
    #[serde(default)]
    pub description: String,
    /// Gravitational acceleration [SI: m/s²], global frame.
    #[serde(default)]
    pub gravity: [f64; 2],
    #[serde(default)]
    pub beams: Vec<Beam>,
    #[serde(default)]
    pub rigid_bodies: Vec<RigidBody>,
    #[serde(default)]
    pub point_masses: Vec<PointMass>,
    #[serde(default)]
    pub joints: Vec<Joint>,
    #[serde(default)]
    pub springs: Vec<Spring>,
    #[serde(default)]
    pub loads: Vec<Load>,
    #[serde(default)]
    pub sensors: Vec<Sensor>,
    /// Unilateral contacts (see [`super::contact`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contacts: Vec<super::contact::Contact>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<Reference>,
    /// Rayleigh damping C = αM + βK of the whole assembly.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<RayleighDamping>,
    /// What was calibrated to make this model (written by `calibrate`; see
    /// [`super::calibrated`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub calibrated: Vec<super::Calibrated>,
}

/// A straight, stress-free ANCF cable beam in its reference configuration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Beam {
    pub id: String,
    /// Position of node 0 [SI: m].
    pub start: [f64; 2],
    /// Direction of the beam axis from node 0 [deg], counter-clockwise from global x.
    pub angle_deg: f64,
    /// Length [SI: m].
    pub length: f64,
    /// Number of elements of the uniform division.
    pub elements: usize,
    /// Add mesh nodes at every joint, spring, load and sensor point on this beam.
    #[serde(default = "default_true")]
    pub nodes_at_attachments: bool,
    pub section: Section,
    pub material: Material,
    /// Model the beam as one rigid body with its mass, centre and inertia
    /// (the paper's rigid comparison); attachments stay where they are.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rigid: bool,
}

/// Rectangular cross-section.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Section {
    /// Height, in the bending plane [SI: m].
    pub height: f64,
    /// Width, out of plane [SI: m].
    pub width: f64,
}

/// Linear-elastic isotropic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Young's modulus [SI: Pa].
    pub young: f64,
    /// Density [SI: kg/m³].
    pub density: f64,
    /// Poisson's ratio ν [–], for the shear modulus G = E/(2(1 + ν)) of
    /// the beam-theory estimate (0.3 when left out).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub poisson: Option<f64>,
}

/// A planar rigid body; its reference point is its centre of mass.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RigidBody {
    pub id: String,
    /// Mass [SI: kg], > 0.
    pub mass: f64,
    /// Moment of inertia about the centre of mass [SI: kg m²], ≥ 0.
    pub inertia: f64,
    /// Centre of mass [SI: m].
    pub position: [f64; 2],
    /// Orientation of the body frame [deg].
    #[serde(default)]
    pub angle_deg: f64,
}

/// A point mass (no rotational inertia).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointMass {
    pub id: String,
    /// Mass [SI: kg], > 0.
    pub mass: f64,
    /// Position [SI: m].
    pub position: [f64; 2],
}

/// A material point of the assembly, or a fixed point of the ground.
///
/// Exactly one of `beam` (with `s`), `body` (optionally with `local`) or
/// `ground` must be given.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointSpec {
    /// Beam id; the point is at arc length `s` from node 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beam: Option<String>,
    /// Arc length along the beam [SI: m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub s: Option<f64>,
    /// Rigid body or point mass id.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub body: Option<String>,
    /// Point in the body frame [SI: m]; rigid bodies only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub local: Option<[f64; 2]>,
    /// Fixed global point [SI: m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<[f64; 2]>,
}

/// Kind of a joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum JointType {
    /// Revolute joint: the two points coincide (2 equations).
    Pin,
    /// Rigid connection: pin plus constant relative angle (3 equations).
    Weld,
    /// Point `b` stays on the line through `a` along `axis` (1 equation).
    Slider,
}

/// A joint between two points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Joint {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    #[serde(rename = "type")]
    pub kind: JointType,
    pub a: PointSpec,
    pub b: PointSpec,
    /// Torsional spring of a pin [SI: N m/rad].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion_stiffness: Option<f64>,
    /// Torsional damper of a pin [SI: N m s/rad].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub torsion_damping: Option<f64>,
    /// Slider axis, global frame at the initial configuration (any length).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<[f64; 2]>,
    /// A released support (pins and sliders): the joint holds in every
    /// static equilibrium and modal analysis (the ON state); a transient
    /// started from the equilibrium replaces it by its reaction force
    /// there, as a dead load on each of its points falling with this time
    /// function (`until` or `ramp_down`) — a latch that lets go.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub release: Option<TimeFunction>,
}

/// A translational spring-damper along the line of its two points.
/// Give exactly one of `free_length` and `preload`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Spring {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    pub a: PointSpec,
    pub b: PointSpec,
    /// Stiffness [SI: N/m], > 0.
    pub stiffness: f64,
    /// Damping [SI: N s/m], ≥ 0.
    #[serde(default)]
    pub damping: f64,
    /// Unstressed length [SI: m].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_length: Option<f64>,
    /// Tension at the initial length [SI: N]; negative means compression.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub preload: Option<f64>,
}

/// Frame in which a load's force vector is given.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum LoadFrame {
    #[default]
    Global,
    /// x along the beam's initial tangent at the point, y normal to it.
    /// The direction is fixed at the initial configuration (a dead load).
    Beam,
}

/// Time history of a load: F(t) = force · f(t).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TimeFunction {
    /// f = 1.
    #[default]
    Constant,
    /// f = sin(π t / duration) for t ≤ duration, else 0.
    HalfSine { duration: f64 },
    /// f = 0 before `start`, 1 from then on.
    Step { start: f64 },
    /// f = 1 up to t = `until` [SI: s], 0 after: a release. The load acts
    /// in full in a static equilibrium (t = 0) whenever `until` ≥ 0, so
    /// `{"until": 0}` releases it at the start of a transient.
    Until(f64),
    /// f = 1 up to `start`, then falling linearly to 0 over `duration`
    /// [SI: s]: a release that takes time (the paper's pre-stress forces
    /// "rapidly decrease to zero", Eq. 7). Acts in full in statics.
    RampDown { start: f64, duration: f64 },
}

/// A point force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Load {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub id: Option<String>,
    pub at: PointSpec,
    #[serde(default)]
    pub frame: LoadFrame,
    /// Force amplitude [SI: N].
    pub force: [f64; 2],
    #[serde(default)]
    pub time: TimeFunction,
}

/// What a sensor measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum SensorQuantity {
    Displacement,
    Velocity,
    Acceleration,
}

/// Frame of a sensor reading.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum SensorFrame {
    Global,
    /// Best-fit rigid motion of the beam's nodes removed.
    #[default]
    Corotated,
}

/// A measuring point (vibrometer-like).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Sensor {
    pub id: String,
    pub at: PointSpec,
    pub quantity: SensorQuantity,
    #[serde(default)]
    pub frame: SensorFrame,
    /// Measuring direction (any length): global for `global`, the beam's
    /// initial tangent/normal frame for `corotated`.
    pub direction: [f64; 2],
}

/// Rayleigh (proportional) damping C = αM + βK. α acts on absolute
/// coordinates, so it also slows a free assembly's rigid drift.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RayleighDamping {
    /// Mass-proportional factor α [SI: 1/s].
    #[serde(default)]
    pub alpha: f64,
    /// Stiffness-proportional factor β [SI: s].
    #[serde(default)]
    pub beta: f64,
}

impl RayleighDamping {
    /// Damping ratio of an undamped mode of angular frequency ω [rad/s]:
    /// ζ = α/(2ω) + βω/2 (infinite at ω = 0 when α > 0).
    pub fn ratio(&self, omega: f64) -> f64 {
        let a = if self.alpha == 0.0 {
            0.0
        } else {
            self.alpha / (2.0 * omega)
        };
        a + 0.5 * self.beta * omega
    }
}

/// Measured data the model is compared with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Reference {
    /// First bending frequency [SI: Hz].
    pub first_bending_hz: f64,
    #[serde(default)]
    pub source: String,
}

fn default_true() -> bool {
    true
}
