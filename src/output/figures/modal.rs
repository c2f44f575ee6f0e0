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
//! * rigid bodies as outlines of their attachment points, point masses,
//!   springs, joints and supports as [`crate::output::plot::scene`]
//!   describes them, every point moved by the one linear map of
//!   [`super::assembly`]: p(q) + a·(∂p/∂q)·φ.
//!
//! A mode shape has no physical amplitude (it is mass-normalized,
//! φᵀMφ = 1). Each mode is scaled on its own so that the largest
//! displacement of any drawn point is [`ModeShapeSettings::amplitude_fraction`]
//! of the assembly's size (the larger side of the bounding box of the grey
//! geometry). The displacement of a drawn point is the linearized one. The sign is fixed so that the largest
//! displacement points along the normal (n = ẑ × t) of the first beam, or
//! along its tangent for a mostly axial motion, making pictures repeatable.

use super::assembly::{assembly_geometry, assembly_motion, drawn_size};
use crate::analysis::{ModalResult, Mode};
use crate::output::plot::{ModeShape, ModeShapeFigure, Scale};
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

/// The signed amplitude a that scales `phi` for drawing at `q` (see the
/// module docs); 0 when no drawn point moves.
pub fn mode_amplitude(
    system: &System,
    q: &[f64],
    phi: &[f64],
    settings: &ModeShapeSettings,
) -> f64 {
    let per = settings.points_per_element.max(1);
    let (at, rate) = assembly_motion(system, q, phi, per);
    let size = drawn_size(&at);
    let largest = rate
        .points()
        .map(|p| Vector2::new(p[0], p[1]))
        .max_by(|a, b| a.norm().total_cmp(&b.norm()));
    let Some(largest) = largest else {
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
    let (at, rate) = assembly_motion(system, q, &mode.shape, settings.points_per_element);
    ModeShape {
        number: mode.index,
        frequency_hz: mode.frequency_hz,
        kind: mode.kind.to_string(),
        deformed: at.moved(&rate, a),
    }
}
