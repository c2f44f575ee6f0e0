//! The assembly as drawn, and its motion along a mode: one linear map.
//!
//! Every drawn point is a point p(q) of the assembly: a beam's centre line
//! r(ξ) = S(ξ)·e, a rigid body's point x + A(θ)ℓ, a point mass's x, a
//! joint's or a spring's anchor, a slider rail's end a ± L·t(θ_a).
//! [`assembly_motion`] gives each such point at the state q and its
//! displacement per unit amplitude of a motion φ, ṗ = (∂p/∂q)·φ, so a mode
//! is drawn at amplitude c as p(q) + c·ṗ ([`Geometry::moved`]). Beams are
//! linear in q already; for a body point ṗ = φ_x + φ_θ ẑ × A(θ)ℓ, not a
//! finite rotation of the scaled angle. A joint's two points move alike
//! since φ satisfies the linearized constraints, so its marker sits on
//! both parts in every frame.
//!
//! Lengths are in metres, drawn where the model sits (the system's origin
//! added, [`System::origin`]).

use crate::mechanics::anchor::{perp, Anchor, Grad};
use crate::mechanics::element::shape;
use crate::output::plot::{Geometry, JointKind, JointMark};
use crate::system::System;
use nalgebra::Vector2;

/// Points of a drawn line [SI: m].
type Polyline = Vec<[f64; 2]>;

/// Zig-zag points of a drawn spring (between its two straight ends).
const SPRING_ZIGS: usize = 8;
/// Spring ends closer than this fraction of the assembly's size are one
/// point (a torsion spring): no zig-zag is drawn.
const COINCIDENT: f64 = 1e-9;
/// A rail's half-length as a fraction of the assembly's size.
const RAIL_HALF_FRACTION: f64 = 0.08;

/// The drawn geometry of `system` at coordinates `q` [SI: m], beams
/// sampled `points_per_element` times per element.
pub fn assembly_geometry(system: &System, q: &[f64], points_per_element: usize) -> Geometry {
    let still = vec![0.0; q.len()];
    assembly_motion(system, q, &still, points_per_element).0
}

/// The drawn geometry at `q` and, in the same structure, each drawn point's
/// displacement for the motion `phi` [SI: m per unit amplitude] (the module
/// docs). `toward` of the joints is the reference's in both.
pub fn assembly_motion(
    system: &System,
    q: &[f64],
    phi: &[f64],
    points_per_element: usize,
) -> (Geometry, Geometry) {
    let per = points_per_element.max(1);
    let (mut at, mut rate) = (Geometry::default(), Geometry::default());
    let shift = system.origin;
    for (line, moving) in system.beams.iter().map(|b| {
        let line = |v: &[f64], shift: Vector2<f64>| {
            let mut pts = Vec::with_capacity(b.elements.len() * per + 1);
            for (k, el) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                for j in usize::from(k > 0)..=per {
                    let s = shape(el.le, j as f64 / per as f64).s;
                    let mut r = [shift.x, shift.y];
                    for (i, si) in s.iter().enumerate() {
                        r[0] += si * v[dofs[2 * i]];
                        r[1] += si * v[dofs[2 * i + 1]];
                    }
                    pts.push(r);
                }
            }
            pts
        };
        (line(q, shift), line(phi, Vector2::zeros()))
    }) {
        at.beams.push(line);
        rate.beams.push(moving);
    }
    let point = |a: &Anchor| {
        let (p, v) = (a.position(q) + shift, a.velocity(q, phi));
        ([p.x, p.y], [v.x, v.y])
    };
    for body in &system.rigid_bodies {
        let d = body.dof0;
        let (outline, moving): (Vec<_>, Vec<_>) = outline(&body_points(system, d))
            .into_iter()
            .map(|local| {
                point(&Anchor::Rigid {
                    dofs: [d, d + 1, d + 2],
                    local,
                })
            })
            .unzip();
        at.bodies.push(outline);
        rate.bodies.push(moving);
    }
    for m in &system.point_masses {
        let (p, v) = point(&Anchor::PointMass {
            dofs: [m.dof0, m.dof0 + 1],
        });
        at.masses.push(p);
        rate.masses.push(v);
    }
    let size = drawn_size(&at);
    for pair in system.force_elements.iter().map(|f| f.pair()) {
        let ((a, va), (b, vb)) = (point(&pair.a), point(&pair.b));
        // A torsion spring's two points coincide (to round-off).
        let length = (b[0] - a[0]).hypot(b[1] - a[1]);
        if length <= COINCIDENT * size {
            continue;
        }
        if let Some((line, moving)) = zigzag(a, b, va, vb) {
            at.springs.push(line);
            rate.springs.push(moving);
        }
    }
    for c in &system.constraints {
        let pair = c.pair();
        let ground = |a: &Anchor| matches!(a, Anchor::Ground { .. });
        // The part's side: b, or a when b is the ground.
        let part = if ground(&pair.b) { &pair.a } else { &pair.b };
        let (p, v) = point(part);
        let kind = if c.line_direction(q).is_some() {
            JointKind::Slider
        } else if c.rigid() {
            JointKind::Weld
        } else {
            JointKind::Pin
        };
        let toward = toward(system, part, q);
        let rails = c.line_direction(q).map(|t| {
            let half = RAIL_HALF_FRACTION * size;
            let (a, va) = point(&pair.a);
            let turn = perp(t) * angle_rate(&pair.a, q, phi) * half;
            let end = |s: f64| {
                (
                    [a[0] + s * half * t.x, a[1] + s * half * t.y],
                    [va[0] + s * turn.x, va[1] + s * turn.y],
                )
            };
            let ((p0, v0), (p1, v1)) = (end(-1.0), end(1.0));
            ([p0, p1], [v0, v1])
        });
        let mark = |at: [f64; 2], rail| JointMark {
            kind,
            at,
            ground: ground(&pair.a) || ground(&pair.b),
            rail,
            toward,
        };
        at.joints.push(mark(p, rails.map(|r| r.0)));
        rate.joints.push(mark(v, rails.map(|r| r.1)));
    }
    (at, rate)
}

/// The larger side of the bounding box of `g` [SI: m]; 0 for no points.
pub(super) fn drawn_size(g: &Geometry) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in g.points() {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if span.is_finite() {
        span
    } else {
        0.0
    }
}

/// The angle's rate θ̇ = (∂θ/∂q)·φ of an anchor (0 for the ground).
fn angle_rate(a: &Anchor, q: &[f64], phi: &[f64]) -> f64 {
    if !a.has_angle() {
        return 0.0;
    }
    let mut grad = Grad::zeros();
    a.angle_derivatives(q, &mut grad, None);
    a.dofs()
        .iter()
        .enumerate()
        .map(|(k, &d)| grad[k] * phi[d])
        .sum()
}

/// Every local point of the rigid body at `dof0` that something is
/// attached to, its centre of mass (0, 0) first.
fn body_points(system: &System, dof0: usize) -> Vec<Vector2<f64>> {
    use crate::mechanics::spring::ForceElement;
    let pairs = system
        .constraints
        .iter()
        .map(|c| c.pair())
        .chain(system.force_elements.iter().map(|f| f.pair()))
        .chain(system.contacts.iter().map(|c| c.pair()));
    let anchors = pairs
        .flat_map(|p| [&p.a, &p.b])
        .chain(system.loads.iter().map(|l| &l.anchor))
        .chain(system.sensors.iter().map(|s| &s.anchor));
    let mut points = vec![Vector2::zeros()];
    for a in anchors {
        if let Anchor::Rigid { dofs, local } = a {
            if dofs[0] == dof0 && points.iter().all(|p| (p - local).norm() > 0.0) {
                points.push(*local);
            }
        }
    }
    points
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone
/// chain); collinear points give the two ends, one point itself.
fn outline(points: &[Vector2<f64>]) -> Vec<Vector2<f64>> {
    let mut p = points.to_vec();
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: Vector2<f64>, a: Vector2<f64>, b: Vector2<f64>| {
        (a - o).x * (b - o).y - (a - o).y * (b - o).x
    };
    let mut hull: Vec<Vector2<f64>> = Vec::with_capacity(2 * p.len());
    for pass in [p.clone(), p.iter().rev().copied().collect()] {
        let start = hull.len();
        for x in pass {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], x) <= 0.0
            {
                hull.pop();
            }
            hull.push(x);
        }
        hull.pop();
    }
    if hull.len() < 2 {
        // All points on one spot or one line: its two ends.
        return vec![p[0], p[p.len() - 1]];
    }
    hull
}

/// Unit direction from `part`'s anchor into its part at `q` [model axes]:
/// toward a beam's middle along its slope, toward a body's centre of mass,
/// else along +x.
fn toward(system: &System, part: &Anchor, q: &[f64]) -> [f64; 2] {
    let p = part.position(q);
    let unit = |v: Vector2<f64>| {
        let n = v.norm();
        (n > 0.0 && n.is_finite()).then(|| [v.x / n, v.y / n])
    };
    let into = match part {
        Anchor::Beam { dofs, .. } => system
            .beams
            .iter()
            .find(|b| (b.dof0..b.dof0 + 4 * b.node_count()).contains(&dofs[0]))
            .and_then(|b| {
                let n = b.node_count();
                let mid = (0..n)
                    .map(|k| Vector2::new(q[b.dof0 + 4 * k], q[b.dof0 + 4 * k + 1]))
                    .sum::<Vector2<f64>>()
                    / n as f64;
                let theta = part.angle(q);
                let t = Vector2::new(theta.cos(), theta.sin());
                let sign = if t.dot(&(mid - p)) < 0.0 { -1.0 } else { 1.0 };
                unit(sign * t)
            }),
        Anchor::Rigid { dofs, .. } => {
            unit(Vector2::new(q[dofs[0]], q[dofs[1]]) - p).or_else(|| {
                let theta = q[dofs[2]];
                Some([theta.cos(), theta.sin()])
            })
        }
        _ => None,
    };
    into.unwrap_or([1.0, 0.0])
}

/// A zig-zag from `a` to `b` [SI: m] and its points' displacements, linear
/// in the ends' (the zig-zag's width keeps its direction); `None` when the
/// ends coincide (a torsion spring).
fn zigzag(a: [f64; 2], b: [f64; 2], va: [f64; 2], vb: [f64; 2]) -> Option<(Polyline, Polyline)> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let length = d[0].hypot(d[1]);
    if length.is_nan() || length <= 0.0 {
        return None;
    }
    let n = [-d[1] / length, d[0] / length];
    let width = 0.06 * length;
    let mut line = vec![a];
    let mut moving = vec![va];
    let lerp =
        |t: f64, x: [f64; 2], y: [f64; 2]| [x[0] + t * (y[0] - x[0]), x[1] + t * (y[1] - x[1])];
    for k in 0..=SPRING_ZIGS + 1 {
        let t = 0.2 + 0.6 * k as f64 / (SPRING_ZIGS + 1) as f64;
        let side = match k {
            0 => 0.0,
            k if k == SPRING_ZIGS + 1 => 0.0,
            k if k % 2 == 1 => 1.0,
            _ => -1.0,
        };
        let c = lerp(t, a, b);
        line.push([c[0] + side * width * n[0], c[1] + side * width * n[1]]);
        moving.push(lerp(t, va, vb));
    }
    line.push(b);
    moving.push(vb);
    Some((line, moving))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_outline_is_the_hull_and_collinear_points_give_a_link() {
        let v = |x, y| Vector2::new(x, y);
        let hull = outline(&[
            v(0.0, 0.0),
            v(1.0, 0.0),
            v(0.5, 0.2),
            v(0.0, 1.0),
            v(1.0, 1.0),
        ]);
        assert_eq!(hull.len(), 4, "{hull:?}");
        assert!(!hull.contains(&v(0.5, 0.2)));
        let link = outline(&[v(0.0, 0.0), v(2.0, 0.0), v(1.0, 0.0)]);
        assert_eq!(link, vec![v(0.0, 0.0), v(2.0, 0.0)]);
        assert_eq!(outline(&[v(3.0, 4.0)]), vec![v(3.0, 4.0)]);
    }
}
