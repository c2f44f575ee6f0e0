//! Mode-shape figures of a modal analysis.
//!
//! A mode shape φ is a direction in the global coordinates q: beam node
//! positions and slopes [m, –], rigid-body positions and angles [m, rad],
//! point-mass positions [m]. The figure shows the assembly at the state q
//! it was linearized at (grey) and at q + a·φ (colour):
//!
//! * beams as their centre lines r(ξ) = S(ξ)·e with the Hermite shape
//!   functions of [`crate::mechanics::element::shape`], sampled at
//!   [`ModeShapeSettings::points_per_element`] points per element, so that
//!   a bending mode is drawn curved as the element interpolates it, not as
//!   straight lines between nodes;
//! * rigid bodies and point masses as markers at their positions;
//! * joints as small circles at their anchor positions (point a of each
//!   joint; both points coincide in the linearized motion).
//!
//! A mode shape has no physical amplitude (it is mass-normalized,
//! φᵀMφ = 1). Each mode is scaled on its own so that the largest
//! displacement of any drawn point is [`ModeShapeSettings::amplitude_fraction`]
//! of the assembly's size (the larger side of the bounding box of the grey
//! geometry). The displacement of a drawn point is the linearized one: beam
//! points and body positions are linear in q, a joint anchor on a rotating
//! body moves by (∂r/∂q)·φ. The sign is fixed so that the largest
//! displacement points along the normal (n = ẑ × t) of the first beam, or
//! along its tangent for a mostly axial motion, making pictures repeatable.

use crate::analysis::{ModalResult, Mode};
use crate::mechanics::element::shape;
use crate::output::plot::{Geometry, ModeShape, ModeShapeFigure, Scale};
use crate::system::System;
use nalgebra::Vector2;

/// What a mode-shape figure shows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeShapeSettings {
    /// Most modes drawn (the first ones of the result, in order).
    pub modes: usize,
    /// Draw zero-frequency (rigid-body or mechanism) modes too.
    pub include_rigid: bool,
    /// Largest displacement of a drawn point as a fraction of the
    /// assembly's size.
    pub amplitude_fraction: f64,
    /// Centre-line samples per beam element (≥ 1; 1 draws chords).
    pub points_per_element: usize,
}

impl Default for ModeShapeSettings {
    fn default() -> Self {
        ModeShapeSettings {
            modes: 6,
            include_rigid: false,
            amplitude_fraction: 0.15,
            points_per_element: 16,
        }
    }
}

/// The drawn geometry of `system` at coordinates `q` [SI: m]: beam centre
/// lines sampled `points_per_element` times per element from the shape
/// functions, rigid-body and point-mass positions, joint anchors; drawn
/// where the model sits (the system's origin added, see
/// [`System::origin`]).
pub fn assembly_geometry(system: &System, q: &[f64], points_per_element: usize) -> Geometry {
    geometry(system, q, points_per_element, system.origin)
}

/// The geometry of `q` moved by `shift` (zero for a motion φ).
fn geometry(
    system: &System,
    q: &[f64],
    points_per_element: usize,
    shift: Vector2<f64>,
) -> Geometry {
    let per = points_per_element.max(1);
    let beams = system
        .beams
        .iter()
        .map(|b| {
            let mut line = Vec::with_capacity(b.elements.len() * per + 1);
            for (k, el) in b.elements.iter().enumerate() {
                let dofs = b.element_dofs(k);
                let first = if k == 0 { 0 } else { 1 };
                for j in first..=per {
                    let s = shape(el.le, j as f64 / per as f64).s;
                    let mut r = [shift.x, shift.y];
                    for (i, si) in s.iter().enumerate() {
                        r[0] += si * q[dofs[2 * i]];
                        r[1] += si * q[dofs[2 * i + 1]];
                    }
                    line.push(r);
                }
            }
            line
        })
        .collect();
    let rigid = system.rigid_bodies.iter().map(|r| r.dof0);
    let masses = system.point_masses.iter().map(|p| p.dof0);
    let bodies = rigid
        .chain(masses)
        .map(|d| [q[d] + shift.x, q[d + 1] + shift.y])
        .collect();
    let joints = system
        .constraints
        .iter()
        .map(|c| {
            let p = c.pair().a.position(q) + shift;
            [p.x, p.y]
        })
        .collect();
    Geometry {
        beams,
        bodies,
        joints,
    }
}

/// Linearized displacement of every drawn point for the motion `phi` at
/// `q`, in the order of [`Geometry`]'s points: beams, bodies, joints.
fn displacements(system: &System, q: &[f64], phi: &[f64], per: usize) -> Vec<Vector2<f64>> {
    // Beam points and body positions are linear in q: their displacement is
    // the geometry of φ itself (positions and slopes alike).
    let g = geometry(system, phi, per, Vector2::zeros());
    let mut d: Vec<Vector2<f64>> = g
        .beams
        .iter()
        .flatten()
        .chain(&g.bodies)
        .map(|p| Vector2::new(p[0], p[1]))
        .collect();
    d.extend(
        system
            .constraints
            .iter()
            .map(|c| c.pair().a.velocity(q, phi)),
    );
    d
}

/// The larger side of the bounding box of `g` [SI: m]; 0 for no points.
fn size_of(g: &Geometry) -> f64 {
    let pts = g.beams.iter().flatten().chain(&g.bodies).chain(&g.joints);
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pts {
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

/// The signed amplitude a that scales `phi` for drawing at `q` (see the
/// module docs); 0 when no drawn point moves.
pub fn mode_amplitude(
    system: &System,
    q: &[f64],
    phi: &[f64],
    settings: &ModeShapeSettings,
) -> f64 {
    let per = settings.points_per_element.max(1);
    let size = size_of(&assembly_geometry(system, q, per));
    let d = displacements(system, q, phi, per);
    let Some(largest) = d.iter().max_by(|a, b| a.norm().total_cmp(&b.norm())) else {
        return 0.0;
    };
    let max = largest.norm();
    if max == 0.0 || !max.is_finite() {
        return 0.0;
    }
    let t = system
        .beams
        .first()
        .map_or(Vector2::new(1.0, 0.0), |b| b.tangent);
    let n = Vector2::new(-t.y, t.x);
    let along = if largest.dot(&n).abs() >= 0.1 * max {
        largest.dot(&n)
    } else {
        largest.dot(&t)
    };
    let sign = if along < 0.0 { -1.0 } else { 1.0 };
    sign * settings.amplitude_fraction * size / max
}

/// Mode shapes of `result` at the system's reference state `system.q0`:
/// the first `modes` elastic modes (rigid ones skipped), amplitudes and
/// sampling as in [`ModeShapeSettings::default`].
pub fn mode_shape_figure(system: &System, result: &ModalResult, modes: usize) -> ModeShapeFigure {
    let settings = ModeShapeSettings {
        modes,
        ..ModeShapeSettings::default()
    };
    mode_shape_figure_with(system, &system.q0, result, &settings)
}

/// Mode shapes of `result` linearized at `q` (e.g. a pre-stressed
/// equilibrium; `system.q0` for the reference state).
pub fn mode_shape_figure_with(
    system: &System,
    q: &[f64],
    result: &ModalResult,
    settings: &ModeShapeSettings,
) -> ModeShapeFigure {
    let per = settings.points_per_element.max(1);
    let shown = result
        .modes
        .iter()
        .filter(|m| settings.include_rigid || !m.kind.is_zero())
        .take(settings.modes);
    let modes = shown.map(|m| mode_shape(system, q, m, settings)).collect();
    ModeShapeFigure {
        title: format!(
            "Mode shapes of {} (largest displacement {:.0} % of the assembly size)",
            system.name,
            100.0 * settings.amplitude_fraction
        ),
        length_scale: Scale::mm(),
        columns: None,
        undeformed: assembly_geometry(system, q, per),
        modes,
    }
}

fn mode_shape(system: &System, q: &[f64], mode: &Mode, settings: &ModeShapeSettings) -> ModeShape {
    let a = mode_amplitude(system, q, &mode.shape, settings);
    let deformed: Vec<f64> = q.iter().zip(&mode.shape).map(|(q, p)| q + a * p).collect();
    ModeShape {
        number: mode.index,
        frequency_hz: mode.frequency_hz,
        kind: mode.kind.to_string(),
        deformed: assembly_geometry(system, &deformed, settings.points_per_element),
    }
}
