//! What a drawing of the assembly holds: parts in model coordinates
//! [SI: m], and the pixel-sized symbols drawn at joints and supports.
//!
//! A [`Geometry`] is plain data. The figures' builder
//! ([`crate::output::figures::assembly_motion`]) fills it twice for a mode:
//! the assembly at the state q, and the displacement of every drawn point
//! per unit amplitude of the mode, so that a frame at amplitude c is
//! [`Geometry::moved`]: every point p + c·ṗ. The mode-shape figures
//! (plotters) and the report's SVG panels and animations draw the same
//! geometry with the same [`symbols`].
//!
//! - Beams: centre lines as their elements interpolate them.
//! - Rigid bodies: the outline of their centre of mass and every point
//!   something is attached to (joints, springs, contacts, loads, sensors);
//!   two points draw a link, one a square marker.
//! - Point masses: square markers.
//! - Springs: zig-zags between their two points.
//! - Joints: a pin is an open circle, a weld a filled one, a slider a
//!   roller (an open circle) at its point b on a rail through its point a.
//!   A joint to the ground is a support: a pin gets a triangle on hatched
//!   ground, a weld (a clamp) a hatched wall across the part, a slider its
//!   rail hatched.

/// A joint's kind, as drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Points a and b held together, rotation free.
    Pin,
    /// Points a and b held together, rotation locked.
    Weld,
    /// Point b held on a line through point a (turning with part a).
    Slider,
}

/// A joint where it is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct JointMark {
    pub kind: JointKind,
    /// The joint's point on its parts [SI: m]: both points of a pin or a
    /// weld (they coincide), point b of a slider.
    pub at: [f64; 2],
    /// One side is the ground: a support.
    pub ground: bool,
    /// A slider's rail: two points of its line [SI: m].
    pub rail: Option<[[f64; 2]; 2]>,
    /// Unit direction from the joint into the part it holds, at the
    /// reference (a clamp's wall stands across it); not scaled by a motion.
    pub toward: [f64; 2],
}

/// Planar geometry of an assembly [SI: m].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Geometry {
    /// Beam centre lines, one polyline each.
    pub beams: Vec<Vec<[f64; 2]>>,
    /// Rigid-body outlines (closed when three or more points).
    pub bodies: Vec<Vec<[f64; 2]>>,
    /// Point masses.
    pub masses: Vec<[f64; 2]>,
    /// Springs and dampers as zig-zag polylines.
    pub springs: Vec<Vec<[f64; 2]>>,
    /// Joints and supports.
    pub joints: Vec<JointMark>,
}

impl Geometry {
    /// Every point of the drawing [SI: m].
    pub fn points(&self) -> impl Iterator<Item = &[f64; 2]> {
        self.beams
            .iter()
            .flatten()
            .chain(self.bodies.iter().flatten())
            .chain(&self.masses)
            .chain(self.springs.iter().flatten())
            .chain(
                self.joints.iter().flat_map(|j| {
                    std::iter::once(&j.at).chain(j.rail.iter().flat_map(|r| r.iter()))
                }),
            )
    }

    /// This geometry with every point p moved to p + c·ṗ, ṗ the point's
    /// counterpart in `rate` (a geometry of the same structure).
    pub fn moved(&self, rate: &Geometry, c: f64) -> Geometry {
        let p = |a: &[f64; 2], v: &[f64; 2]| [a[0] + c * v[0], a[1] + c * v[1]];
        let line = |a: &Vec<[f64; 2]>, v: &Vec<[f64; 2]>| -> Vec<[f64; 2]> {
            a.iter().zip(v).map(|(a, v)| p(a, v)).collect()
        };
        let lines = |a: &[Vec<[f64; 2]>], v: &[Vec<[f64; 2]>]| -> Vec<Vec<[f64; 2]>> {
            a.iter().zip(v).map(|(a, v)| line(a, v)).collect()
        };
        Geometry {
            beams: lines(&self.beams, &rate.beams),
            bodies: lines(&self.bodies, &rate.bodies),
            masses: line(&self.masses, &rate.masses),
            springs: lines(&self.springs, &rate.springs),
            joints: self
                .joints
                .iter()
                .zip(&rate.joints)
                .map(|(j, v)| JointMark {
                    at: p(&j.at, &v.at),
                    rail: j
                        .rail
                        .zip(v.rail)
                        .map(|(r, w)| [p(&r[0], &w[0]), p(&r[1], &w[1])]),
                    ..j.clone()
                })
                .collect(),
        }
    }
}

/// What a symbol's stroke is for (the SVG class and the figures' style).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SymbolPart {
    /// Ground: a support's triangle, wall or track.
    Ground,
    /// Hatching on the ground side.
    Hatch,
}

/// A pixel-sized piece of a symbol: a polyline (closed when `closed`) at
/// offsets [px] from the symbol's point, x right and y down.
#[derive(Debug, Clone, PartialEq)]
pub struct SymbolPath {
    pub part: SymbolPart,
    pub closed: bool,
    pub offsets: Vec<[f64; 2]>,
}

/// Radius of a joint's circle [px].
pub const JOINT_RADIUS: f64 = 3.5;
/// Half the side of a point mass's or a one-point body's square [px].
pub const MARKER_HALF: f64 = 4.0;

/// The symbol pieces of `joint` besides its circle (which the renderers
/// draw as a circle of [`JOINT_RADIUS`], filled for a weld): a ground pin's
/// triangle and hatched ground, a clamp's hatched wall, a ground rail's
/// hatching. Offsets are in pixels, y down.
pub fn symbols(joint: &JointMark) -> Vec<SymbolPath> {
    if !joint.ground {
        return Vec::new();
    }
    match joint.kind {
        JointKind::Pin => pin_support(),
        JointKind::Weld => clamp(joint.toward),
        JointKind::Slider => Vec::new(),
    }
}

/// The hatching of a ground line from `a` to `b` [px offsets], strokes
/// of `length` px going to `side` (a unit pixel direction).
fn hatch(a: [f64; 2], b: [f64; 2], side: [f64; 2], length: f64) -> Vec<SymbolPath> {
    let n = 4;
    (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
            // Strokes lean along the line, as drawn by hand.
            let u = [(b[0] - a[0]) / n as f64, (b[1] - a[1]) / n as f64];
            let q = [
                p[0] + length * side[0] - 0.5 * u[0],
                p[1] + length * side[1] - 0.5 * u[1],
            ];
            SymbolPath {
                part: SymbolPart::Hatch,
                closed: false,
                offsets: vec![p, q],
            }
        })
        .collect()
}

/// A triangle under the pin on a hatched ground line.
fn pin_support() -> Vec<SymbolPath> {
    let (h, w) = (10.0, 7.0);
    let r = JOINT_RADIUS;
    let mut v = vec![
        SymbolPath {
            part: SymbolPart::Ground,
            closed: true,
            offsets: vec![[0.0, r], [-w, r + h], [w, r + h]],
        },
        SymbolPath {
            part: SymbolPart::Ground,
            closed: false,
            offsets: vec![[-w - 4.0, r + h], [w + 4.0, r + h]],
        },
    ];
    v.extend(hatch([-w - 4.0, r + h], [w + 4.0, r + h], [0.0, 1.0], 5.0));
    v
}

/// A wall across the part at the joint, hatched on the side away from it.
/// `toward` is in model axes (y up).
fn clamp(toward: [f64; 2]) -> Vec<SymbolPath> {
    // Pixel axes have y down.
    let t = [toward[0], -toward[1]];
    let n = [-t[1], t[0]];
    let half = 10.0;
    let a = [-half * n[0], -half * n[1]];
    let b = [half * n[0], half * n[1]];
    let mut v = vec![SymbolPath {
        part: SymbolPart::Ground,
        closed: false,
        offsets: vec![a, b],
    }];
    v.extend(hatch(a, b, [-t[0], -t[1]], 6.0));
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_clamp_is_hatched_on_the_side_away_from_its_part() {
        // A part going right (+x): the hatching goes left (−x in pixels).
        let v = clamp([1.0, 0.0]);
        let strokes: Vec<_> = v.iter().filter(|p| p.part == SymbolPart::Hatch).collect();
        assert!(!strokes.is_empty());
        for s in strokes {
            assert!(s.offsets[1][0] < s.offsets[0][0], "{s:?}");
        }
        // A part going up (+y in the model, −y in pixels): hatching down.
        for s in clamp([0.0, 1.0])
            .iter()
            .filter(|p| p.part == SymbolPart::Hatch)
        {
            assert!(s.offsets[1][1] > s.offsets[0][1], "{s:?}");
        }
    }
}
