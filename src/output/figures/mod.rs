//! Figures of analysis results: the maps from results to the plain data of
//! [`super::plot`], and writing them to SVG or PNG files.
//!
//! * [`modal`] — mode shapes of a modal analysis: the undeformed assembly
//!   in grey and each mode's deformed shape q₀ + a·φ in colour, beams drawn
//!   as their curved ANCF centre lines r(ξ) = S(ξ)·e.
//! * [`convergence`] — a mesh-convergence study
//!   ([`crate::analysis::convergence`]: the first bending frequencies
//!   against the number of elements, their relative errors against an
//!   analytic (Euler–Bernoulli) or finest-mesh reference) as the log-log
//!   error figure with the O(h⁴) slope of Hermite cubics.
//! * [`impulse`] — the impulse experiment: sensor signal over the force
//!   pulse against time, and the amplitude spectrum with identified peaks,
//!   eigenfrequency guides and the measured reference frequency.
//!
//! All data are SI (m, Hz); figures show lengths in millimetres.

pub mod convergence;
pub mod impulse;
pub mod modal;

pub use convergence::convergence_figure;
pub use impulse::{response_figure, response_path, spectrum_figure, write_impulse_figures};
pub use modal::{
    assembly_geometry, mode_amplitude, mode_shape_figure, mode_shape_figure_with, ModeShapeSettings,
};

use super::plot::{render, write_atomic, Figure, Format, PlotError, PlotSize};
use crate::analysis::ModalResult;
use crate::system::System;
use std::path::Path;

/// Renders `figure` in the format named by `path`'s extension (`.svg`,
/// `.png`) and writes it atomically. An unknown extension is
/// [`PlotError::UnknownExtension`] and nothing is drawn; a failed write
/// leaves no file behind.
pub fn write_figure(figure: &Figure, path: &Path, size: PlotSize) -> Result<(), PlotError> {
    let format = Format::from_path(path)?;
    let bytes = render(figure, format, size)?;
    write_atomic(path, &bytes)
}

/// Writes the first six elastic mode shapes of `result`, linearized at `q`
/// (`system.q0` at the reference state), to `path` (`.svg` or `.png`).
pub fn write_mode_shapes(
    system: &System,
    q: &[f64],
    result: &ModalResult,
    path: &Path,
) -> Result<(), PlotError> {
    let format = Format::from_path(path)?;
    let figure = mode_shape_figure_with(system, q, result, &ModeShapeSettings::default());
    if figure.modes.is_empty() {
        return Err(PlotError::EmptyData {
            what: format!(
                "the {} computed modes include no elastic one ({} rigid modes in all)",
                result.modes.len(),
                result.rigid_modes
            ),
        });
    }
    let bytes = render(&figure.into(), format, PlotSize::default())?;
    write_atomic(path, &bytes)
}
