//! Axes and plot frames shared by the figure kinds: the data-to-coordinate
//! transform (scale, log10), the chart with explicit ticks, the mesh, the
//! published [`PanelLayout`], and a small placer that keeps labels apart.

use std::fmt;
use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::error::PlotError;
use super::style::{self, TextSizes, INK};
use super::ticks::{self, AxisTicks};

/// The coordinate system of every chart: display units (or their log10) on
/// both axes, ticks given explicitly.
pub(super) type Coord = Cartesian2d<TickAxis, TickAxis>;

/// A linear plotters axis whose tick positions are given (bold: labelled
/// ticks and grid lines; light: minor grid lines). Plotters' own
/// `WithKeyPoints` does the same but is not `Clone`.
#[derive(Clone)]
pub(super) struct TickAxis {
    inner: RangedCoordf64,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl Ranged for TickAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.inner.range()
    }
}

/// SI value → chart coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct AxisMap {
    pub factor: f64,
    pub log: bool,
}

impl AxisMap {
    /// The chart coordinate of an SI value; `None` for non-finite values and,
    /// on a log axis, for values ≤ 0.
    pub fn coord(&self, v: f64) -> Option<f64> {
        let d = v * self.factor;
        match (d.is_finite(), self.log) {
            (false, _) => None,
            (true, false) => Some(d),
            (true, true) => (d > 0.0).then(|| d.log10()),
        }
    }

    /// The SI value of a chart coordinate.
    pub fn value(&self, c: f64) -> f64 {
        let d = if self.log { 10f64.powf(c) } else { c };
        d / self.factor
    }
}

/// One axis as drawn: coordinate range, ticks and description.
#[derive(Debug, Clone)]
pub(super) struct AxisFrame {
    pub map: AxisMap,
    pub lo: f64,
    pub hi: f64,
    pub ticks: AxisTicks,
    pub desc: String,
}

impl AxisFrame {
    /// Ticks chosen for about `target` labels over `[lo, hi]` (coordinates).
    pub fn new(map: AxisMap, lo: f64, hi: f64, desc: String, target: usize) -> Self {
        AxisFrame::build(map, lo, hi, desc, target)
    }

    /// Like [`AxisFrame::new`], but an end within 2 % of the span from a
    /// tick (a decade on log axes) is moved onto it: 0.005…19.995 becomes
    /// 0…20.
    pub fn snapped(map: AxisMap, lo: f64, hi: f64, desc: String, target: usize) -> Self {
        let step = if map.log {
            1.0
        } else {
            ticks::nice_step((hi - lo) / target.max(1) as f64)
        };
        let tol = 0.02 * (hi - lo);
        let down = (lo / step).floor() * step;
        let up = (hi / step).ceil() * step;
        let lo = if lo - down < tol { down } else { lo };
        let hi = if up - hi < tol { up } else { hi };
        AxisFrame::build(map, lo, hi, desc, target)
    }

    fn build(map: AxisMap, lo: f64, hi: f64, desc: String, target: usize) -> Self {
        let ticks = if map.log {
            ticks::log(10f64.powf(lo), 10f64.powf(hi))
        } else {
            ticks::linear(lo, hi, target)
        };
        AxisFrame {
            map,
            lo,
            hi,
            ticks,
            desc,
        }
    }

    /// Linear ticks at multiples of `step` (coordinates).
    pub fn with_step(map: AxisMap, lo: f64, hi: f64, step: f64, desc: String) -> Self {
        AxisFrame {
            map,
            lo,
            hi,
            ticks: ticks::linear_with_step(lo, hi, step),
            desc,
        }
    }

    fn ranged(&self) -> TickAxis {
        TickAxis {
            inner: (self.lo..self.hi).into(),
            major: self.ticks.major.clone(),
            minor: self.ticks.minor.clone(),
        }
    }
}

/// Where one panel or subplot of a rendered figure is, and how data map to
/// its pixels.
#[derive(Clone)]
pub struct PanelLayout {
    /// Pixel columns of the x range's start and end (left, right).
    pub x_pixels: (i32, i32),
    /// Pixel rows of the y range's start and end (bottom, top).
    pub y_pixels: (i32, i32),
    /// Shown x range, SI units.
    pub x_range: (f64, f64),
    /// Shown y range, SI units.
    pub y_range: (f64, f64),
    pub x_log: bool,
    pub y_log: bool,
    x_map: AxisMap,
    y_map: AxisMap,
    coord: Coord,
}

impl fmt::Debug for PanelLayout {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("PanelLayout")
            .field("x_pixels", &self.x_pixels)
            .field("y_pixels", &self.y_pixels)
            .field("x_range", &self.x_range)
            .field("y_range", &self.y_range)
            .field("x_log", &self.x_log)
            .field("y_log", &self.y_log)
            .finish()
    }
}

impl PanelLayout {
    /// The pixel at which the renderer draws the SI data point `(x, y)`
    /// (plotters' own mapping); `None` if a coordinate cannot be shown
    /// (not finite, or ≤ 0 on a log axis).
    pub fn to_pixel(&self, x: f64, y: f64) -> Option<(i32, i32)> {
        let cx = self.x_map.coord(x)?;
        let cy = self.y_map.coord(y)?;
        Some(self.coord.translate(&(cx, cy)))
    }
}

/// Pixel sizes around the plotting area of one chart.
#[derive(Debug, Clone, Copy)]
pub(super) struct FrameSizes {
    pub top: u32,
    /// Left of the y label area, so the rotated y description keeps clear
    /// of the figure edge.
    pub left: u32,
    pub right: u32,
    /// Below the x label area: room for descenders of the x description.
    pub bottom: u32,
    pub x_label_area: u32,
    pub y_label_area: u32,
}

pub(super) fn build_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    x: &AxisFrame,
    y: &AxisFrame,
    f: FrameSizes,
) -> Result<ChartContext<'a, DB, Coord>, PlotError> {
    Ok(ChartBuilder::on(area)
        .margin_top(f.top)
        .margin_left(f.left)
        .margin_bottom(f.bottom)
        .margin_right(f.right)
        .x_label_area_size(f.x_label_area)
        .y_label_area_size(f.y_label_area)
        .build_cartesian_2d(x.ranged(), y.ranged())?)
}

/// Draws grid, axes, tick labels and axis descriptions.
pub(super) fn draw_mesh<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Coord>,
    x: &AxisFrame,
    y: &AxisFrame,
    sizes: &TextSizes,
    show_x: bool,
) -> Result<(), PlotError> {
    let xf = |v: &f64| {
        if show_x {
            x.ticks.label(*v)
        } else {
            String::new()
        }
    };
    let yf = |v: &f64| y.ticks.label(*v);
    let x_desc = if show_x { x.desc.as_str() } else { "" };
    chart
        .configure_mesh()
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .x_desc(x_desc)
        .y_desc(y.desc.as_str())
        .label_style(style::text(sizes.tick, INK, HPos::Center, VPos::Center))
        .axis_desc_style(style::text(sizes.label, INK, HPos::Center, VPos::Center))
        .bold_line_style(style::grid_bold())
        .light_line_style(style::grid_light())
        .axis_style(INK.mix(0.8))
        .set_all_tick_mark_size(6)
        .draw()?;
    Ok(())
}

/// The published layout of a chart.
pub(super) fn layout_of<DB: DrawingBackend>(
    chart: &ChartContext<'_, DB, Coord>,
    x: &AxisFrame,
    y: &AxisFrame,
) -> PanelLayout {
    let (px, py) = chart.plotting_area().get_pixel_range();
    PanelLayout {
        x_pixels: (px.start, px.end - 1),
        y_pixels: (py.end - 1, py.start),
        x_range: (x.map.value(x.lo), x.map.value(x.hi)),
        y_range: (y.map.value(y.lo), y.map.value(y.hi)),
        x_log: x.map.log,
        y_log: y.map.log,
        x_map: x.map,
        y_map: y.map,
        coord: chart.as_coord_spec().clone(),
    }
}

/// Bottom margin of a chart that shows its x description.
pub(super) fn bottom_margin(sizes: &TextSizes) -> u32 {
    (sizes.label * 0.3) as u32 + 2
}

/// Left margin of a chart (see [`FrameSizes::left`]).
pub(super) fn left_margin(sizes: &TextSizes) -> u32 {
    (sizes.label * 0.2) as u32 + 2
}

/// Width of the left label area: widest tick label, tick marks, and the
/// rotated axis description.
pub(super) fn y_label_area<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    y: &AxisFrame,
    sizes: &TextSizes,
) -> Result<u32, PlotError> {
    let style = style::text(sizes.tick, INK, HPos::Left, VPos::Top);
    let mut widest = 0;
    for label in y.ticks.labels() {
        widest = widest.max(area.estimate_text_size(label, &style)?.0);
    }
    Ok(widest + 14 + (sizes.label * 1.5) as u32)
}

/// Height of the bottom label area with tick labels and description.
pub(super) fn x_label_area(sizes: &TextSizes) -> u32 {
    (sizes.tick * 1.3 + sizes.label * 1.4 + 8.0) as u32
}

/// Pixel rectangle `(x0, y0, x1, y1)`.
pub(super) type Rect = (i32, i32, i32, i32);

/// Keeps text labels from overlapping each other, markers and the legend:
/// each label takes the first free candidate place inside the bounds.
#[derive(Debug, Default)]
pub(super) struct Placer {
    taken: Vec<Rect>,
}

impl Placer {
    /// Reserves a rectangle no label may overlap (a marker, the legend).
    pub fn block(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// Takes the first candidate that lies inside `bounds` and overlaps
    /// nothing taken; failing that, the first such candidate after moving it
    /// horizontally into `bounds`; failing that, the first candidate moved.
    pub fn place(&mut self, candidates: impl IntoIterator<Item = Rect>, bounds: Rect) -> Rect {
        let candidates: Vec<Rect> = candidates.into_iter().collect();
        let shifted = candidates.iter().map(|&r| {
            let dx = if r.0 < bounds.0 {
                bounds.0 - r.0
            } else if r.2 > bounds.2 {
                bounds.2 - r.2
            } else {
                0
            };
            (r.0 + dx, r.1, r.2 + dx, r.3)
        });
        let fits = |r: &Rect| {
            let inside = r.0 >= bounds.0 && r.2 <= bounds.2 && r.1 >= bounds.1 && r.3 <= bounds.3;
            inside && !self.taken.iter().any(|t| overlaps(*t, *r))
        };
        let chosen = candidates
            .iter()
            .copied()
            .find(fits)
            .or_else(|| shifted.clone().find(fits))
            .or_else(|| shifted.clone().next())
            .unwrap_or_default();
        self.taken.push(chosen);
        chosen
    }
}

/// `r`, then `r` moved by `step`, `2 step`, … (`n` rectangles in all).
pub(super) fn stack(r: Rect, step: i32, n: i32) -> impl Iterator<Item = Rect> {
    (0..n).map(move |k| (r.0, r.1 + k * step, r.2, r.3 + k * step))
}

fn overlaps(a: Rect, b: Rect) -> bool {
    a.0 < b.2 && b.0 < a.2 && a.1 < b.3 && b.1 < a.3
}
