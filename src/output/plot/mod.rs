//! Figures of modal and impulse-response results, rendered to SVG or PNG.
//!
//! The module depends on nothing else in the crate but the atomic write of
//! [`super::files`]: callers fill plain data structs, in SI units, and
//! [`render`] turns a [`Figure`] into the bytes of an SVG or PNG file;
//! [`write_atomic`] puts them on disk. Rendering needs no system library and
//! no installed font: text uses DejaVu Sans, embedded.
//!
//! # Figures
//!
//! * [`LineFigure`] — a title and one or more panels stacked vertically that
//!   share the x axis (e.g. the sensor signal over the force pulse). Each
//!   panel has named [`Series`] (lines, points, or dashed reference lines), a
//!   legend, vertical and horizontal [`Guide`] lines with labels (e.g.
//!   computed eigenfrequencies, and the 4600 Hz experiment as a *reference*
//!   guide, drawn dashed in the reference colour) and labelled
//!   [`PointMarker`]s (e.g. identified peaks at (f, dB)). Axes may be
//!   logarithmic.
//! * [`ModeShapeFigure`] — a grid with one subplot per mode: the undeformed
//!   geometry in grey (beams, body outlines, point masses, springs, joints
//!   and supports as [`scene`] describes them), the deformed geometry in
//!   colour, and
//!   a title such as "Mode 1: 4577.3 Hz (bending)". x and y use one length
//!   scale (equal aspect ratio). The caller scales the mode amplitude.
//! * [`HeatMap`] — a value over a 2-D grid as coloured cells (viridis) with
//!   a colour bar; missing values in light grey (e.g. a parameter study).
//! * [`calibration_figure`] and [`convergence_figure`] build line figures
//!   for a calibration (frequency against a parameter, target line, fitted
//!   point, numbered iterates) and a log-log convergence study (relative
//!   error against the number of elements, with an O(hᵖ) slope).
//!
//! # Units
//!
//! All data are SI (s, Hz, m, N, …; dB where a series is in decibels). Each
//! axis has a [`Scale`] that says how it is *shown*: `Scale::ms()` shows
//! seconds as milliseconds, `Scale::khz()` hertz as kilohertz,
//! `Scale::mm()` metres as millimetres, and `Scale::si(unit, max)` picks the
//! SI prefix. The unit is written into the axis label: `Time [ms]`.
//!
//! # Style
//!
//! Series take colours from one colour-blind-safe palette (Okabe–Ito,
//! [`PALETTE`]) in order, across all panels of a figure; undeformed geometry
//! is grey; reference lines are dashed in [`REFERENCE`] (reddish purple),
//! plain guides are thin dark grey. Text scales with the figure size.
//!
//! Tick labels get as many decimals as their step needs; log axes use
//! decades (or 1-2-5 steps over short ranges) and write powers of ten as
//! 10⁻⁶. Labels of guides and markers are placed so that they do not
//! overlap each other, markers or the legend; the legend goes to the corner
//! that hides the least data unless a corner is chosen. Long series are
//! thinned to four points per pixel column (first, min, max, last), which
//! draws the same. Values outside a fixed range are clipped.
//!
//! Layout facts (pixel positions of data points, plot areas) are available
//! through [`Figure::layout`] and [`Figure::pixel_of`], for tests and for
//! callers that annotate.
//!
//! PNG text is rasterised by this module from the embedded font (plotters'
//! own glyph placement spaces letters unevenly); SVG text is `<text>` in the
//! `sans-serif` family, drawn by the viewer.

mod annotate;
mod error;
mod font;
mod frame;
mod geom;
mod heatmap;
mod line;
mod modeshape;
mod pngtext;
mod presets;
pub mod scene;
mod series;
mod size;
mod stack;
mod style;
mod ticks;

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::files;

pub use error::PlotError;
pub use frame::PanelLayout;
pub use heatmap::{colour_map, HeatMap, LabelledHeatMap};
pub use line::{LineFigure, Panel};
pub use modeshape::{ModeShape, ModeShapeFigure};
pub use presets::{calibration_figure, convergence_figure, Calibration, Convergence};
pub use scene::{Geometry, JointKind, JointMark};
pub use series::{Guide, Legend, MarkerShape, PointMarker, Series, SeriesStyle};
pub use size::PlotSize;
pub use stack::StackedFigure;
pub use style::{
    format_sig, palette, Scale, BACKGROUND, GUIDE, INK, PALETTE, REFERENCE, UNDEFORMED,
};
pub use ticks::superscript;

/// Output file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Svg,
    Png,
}

impl Format {
    /// The format named by the file extension (`.svg`, `.png`, any case).
    pub fn from_path(path: &Path) -> Result<Format, PlotError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            _ => Err(PlotError::UnknownExtension {
                path: path.to_path_buf(),
            }),
        }
    }
}

/// Any figure this module draws.
#[derive(Debug, Clone)]
pub enum Figure {
    Line(LineFigure),
    ModeShapes(ModeShapeFigure),
    Heat(HeatMap),
    Stack(StackedFigure),
    LabelledHeat(LabelledHeatMap),
}

impl From<LabelledHeatMap> for Figure {
    fn from(f: LabelledHeatMap) -> Self {
        Figure::LabelledHeat(f)
    }
}

impl From<StackedFigure> for Figure {
    fn from(f: StackedFigure) -> Self {
        Figure::Stack(f)
    }
}

impl From<HeatMap> for Figure {
    fn from(f: HeatMap) -> Self {
        Figure::Heat(f)
    }
}

impl From<LineFigure> for Figure {
    fn from(f: LineFigure) -> Self {
        Figure::Line(f)
    }
}

impl From<ModeShapeFigure> for Figure {
    fn from(f: ModeShapeFigure) -> Self {
        Figure::ModeShapes(f)
    }
}

impl Figure {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        root.fill(&BACKGROUND)?;
        match self {
            Figure::Line(f) => f.draw(root, size),
            Figure::ModeShapes(f) => f.draw(root, size),
            Figure::Heat(f) => f.draw(root, size),
            Figure::Stack(f) => f.draw(root, size),
            Figure::LabelledHeat(f) => f.draw(root, size),
        }
    }

    /// Where each panel (line figure) or subplot (mode shapes) lands at
    /// `size`, with the data-to-pixel mapping the renderer uses.
    pub fn layout(&self, size: PlotSize) -> Result<Vec<PanelLayout>, PlotError> {
        size.check()?;
        font::ensure_registered()?;
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, (size.width, size.height)).into_drawing_area();
        self.draw(&root, size)
    }

    /// The pixel at which SI data point `(x, y)` of panel (or subplot)
    /// `panel` is drawn at `size`; `None` if there is no such panel or the
    /// point cannot be shown (non-finite, or ≤ 0 on a log axis).
    pub fn pixel_of(
        &self,
        size: PlotSize,
        panel: usize,
        x: f64,
        y: f64,
    ) -> Result<Option<(i32, i32)>, PlotError> {
        Ok(self.layout(size)?.get(panel).and_then(|p| p.to_pixel(x, y)))
    }
}

/// Renders `figure` as the bytes of an SVG or PNG file.
pub fn render(figure: &Figure, format: Format, size: PlotSize) -> Result<Vec<u8>, PlotError> {
    size.check()?;
    font::ensure_registered()?;
    let (w, h) = (size.width, size.height);
    match format {
        Format::Svg => {
            let mut svg = String::new();
            {
                let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
                figure.draw(&root, size)?;
                root.present()?;
            }
            Ok(svg.into_bytes())
        }
        Format::Png => {
            let mut rgb = vec![0u8; w as usize * h as usize * 3];
            {
                let backend = pngtext::TextFix(BitMapBackend::with_buffer(&mut rgb, (w, h)));
                let root = backend.into_drawing_area();
                figure.draw(&root, size)?;
                root.present()?;
            }
            encode_png(&rgb, w, h)
        }
    }
}

fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, PlotError> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    // Plots are flat colour: per-row adaptive filtering shrinks them ~2×.
    encoder.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
    // Best compression took half of `identify`'s run time (0.55 → 0.36 s CPU
    // with Default) for files no smaller (the four figures: 452 kB vs 457 kB).
    encoder.set_compression(png::Compression::Default);
    let err = |e: png::EncodingError| PlotError::PngEncode(e.to_string());
    let mut writer = encoder.write_header().map_err(err)?;
    writer.write_image_data(rgb).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(out)
}

/// Writes `bytes` to `path` atomically ([`files::write_atomic`]: a
/// temporary file in the same directory, renamed over `path`); a failure is
/// [`PlotError::Io`] and leaves `path` untouched.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), PlotError> {
    Ok(files::write_atomic(path, bytes)?)
}
