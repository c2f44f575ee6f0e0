//! Writing figures to SVG or PNG files.

use super::modal::{mode_shape_figure_with, ModeShapeSettings};
use crate::analysis::ModalResult;
use crate::output::plot::{render, write_atomic, Figure, Format, PlotError, PlotSize};
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
                "the {} computed modes include no elastic one ({} zero-frequency modes in all)",
                result.modes.len(),
                result.rigid_modes
            ),
        });
    }
    let bytes = render(&figure.into(), format, PlotSize::default())?;
    write_atomic(path, &bytes)
}
