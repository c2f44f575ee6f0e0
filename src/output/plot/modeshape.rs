//! Mode-shape figures: one subplot per mode, undeformed geometry in grey
//! under the deformed geometry in colour, x and y at one length scale.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::annotate::draw_title;
use super::error::PlotError;
use super::frame::{self, AxisFrame, AxisMap, Coord, FrameSizes, PanelLayout};
use super::geom::{Extent, Pt};
use super::scene::{self, Geometry, JointKind, SymbolPart, JOINT_RADIUS, MARKER_HALF};
use super::size::PlotSize;
use super::style::{self, palette, Scale, TextSizes, BACKGROUND, INK, UNDEFORMED};
use super::ticks::nice_step;

/// One mode: its number, frequency, a short kind ("bending", "axial", …;
/// empty for none) and the deformed geometry (amplitude scaled by the caller).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModeShape {
    pub number: usize,
    pub frequency_hz: f64,
    pub kind: String,
    pub deformed: Geometry,
}

impl ModeShape {
    /// "Mode 1: 4577.3 Hz (bending)".
    pub fn title(&self) -> String {
        let mut t = format!("Mode {}: {:.1} Hz", self.number, self.frequency_hz);
        if !self.kind.is_empty() {
            t.push_str(&format!(" ({})", self.kind));
        }
        t
    }
}

/// A grid of mode shapes sharing one undeformed geometry.
#[derive(Debug, Clone)]
pub struct ModeShapeFigure {
    /// Figure title above the grid; may be empty.
    pub title: String,
    /// How lengths are shown on both axes (default millimetres).
    pub length_scale: Scale,
    /// Grid columns; `None` picks the count that draws the modes largest.
    pub columns: Option<usize>,
    pub undeformed: Geometry,
    pub modes: Vec<ModeShape>,
}

impl Default for ModeShapeFigure {
    fn default() -> Self {
        ModeShapeFigure {
            title: String::new(),
            length_scale: Scale::mm(),
            columns: None,
            undeformed: Geometry::default(),
            modes: Vec::new(),
        }
    }
}

/// Label areas of one subplot, from the text sizes.
struct Cell {
    title_h: u32,
    top: u32,
    right: u32,
    bottom: u32,
    x_area: u32,
}

impl Cell {
    fn new(sizes: &TextSizes) -> Self {
        Cell {
            title_h: (sizes.label * 1.8) as u32,
            top: (sizes.tick * 0.6) as u32,
            right: (sizes.tick * 1.5) as u32,
            bottom: frame::bottom_margin(sizes),
            x_area: frame::x_label_area(sizes),
        }
    }
}

impl ModeShapeFigure {
    fn map(&self) -> AxisMap {
        AxisMap {
            factor: self.length_scale.factor,
            log: false,
        }
    }

    /// Extent of undeformed and deformed geometry of `modes`, in display units.
    fn extent<'a>(&'a self, modes: impl Iterator<Item = &'a ModeShape>) -> (Extent, Extent) {
        let (mut ex, mut ey) = (Extent::default(), Extent::default());
        let m = self.map();
        let geometries = std::iter::once(&self.undeformed).chain(modes.map(|m| &m.deformed));
        for p in geometries.flat_map(Geometry::points) {
            if let (Some(x), Some(y)) = (m.coord(p[0]), m.coord(p[1])) {
                ex.add(x);
                ey.add(y);
            }
        }
        (ex, ey)
    }

    fn columns(&self, width: u32, height: u32, sizes: &TextSizes) -> usize {
        if let Some(c) = self.columns {
            return c.clamp(1, self.modes.len());
        }
        let (ex, ey) = self.extent(self.modes.iter());
        let Some((_, (sx, sy))) = padded_box(ex, ey) else {
            return 1;
        };
        let cell = Cell::new(sizes);
        let n = self.modes.len();
        let scale = |cols: usize| {
            let rows = n.div_ceil(cols);
            let w = width as f64 / cols as f64 - 80.0 - cell.right as f64;
            let h = height as f64 / rows as f64
                - (cell.title_h + cell.top + cell.x_area + cell.bottom) as f64;
            (w / sx).min(h / sy)
        };
        // The largest drawing; fewer columns unless more are clearly better.
        let mut best = (1, scale(1));
        for cols in 2..=n {
            let s = scale(cols);
            if s > best.1 * 1.02 {
                best = (cols, s);
            }
        }
        best.0
    }

    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        if self.modes.is_empty() {
            return Err(PlotError::EmptyData {
                what: "mode-shape figure has no mode".into(),
            });
        }
        let sizes = TextSizes::for_size(size);
        let title_h = draw_title(root, &self.title, &sizes)?;
        let body = root.split_vertically(title_h).1;
        let (w, h) = body.dim_in_pixel();
        let cols = self.columns(w, h, &sizes);
        let rows = self.modes.len().div_ceil(cols);
        let cells = body.split_evenly((rows, cols));
        // One frame for all subplots, so that shapes compare at a glance.
        let extent = self.extent(self.modes.iter());
        let mut layouts = Vec::new();
        for (mode, cell) in self.modes.iter().zip(&cells) {
            layouts.push(self.draw_mode(root, cell, mode, extent, &sizes)?);
        }
        Ok(layouts)
    }

    fn draw_mode<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        cell_area: &DrawingArea<DB, Shift>,
        mode: &ModeShape,
        extent: (Extent, Extent),
        sizes: &TextSizes,
    ) -> Result<PanelLayout, PlotError> {
        let cell = Cell::new(sizes);
        let (cw, _) = cell_area.dim_in_pixel();
        let title = style::text(sizes.label, INK, HPos::Center, VPos::Center);
        cell_area.draw(&Text::new(
            mode.title(),
            (cw as i32 / 2, cell.title_h as i32 / 2 + 4),
            title,
        ))?;
        let area = cell_area.split_vertically(cell.title_h).1;

        let (ex, ey) = extent;
        let empty = || PlotError::EmptyData {
            what: format!("mode {} has no geometry", mode.number),
        };
        let ((cx, cy), (sx, sy)) = padded_box(ex, ey).ok_or_else(empty)?;

        // Equal aspect: one length per pixel on both axes. The y label area
        // depends on the tick labels, which depend on the range: iterate.
        let (aw, ah) = area.dim_in_pixel();
        let map = self.map();
        let x_desc = self.length_scale.label("x");
        let y_desc = self.length_scale.label("y");
        let mut y_area = (sizes.tick * 3.0 + sizes.label * 1.7) as u32;
        let mut frames = None;
        for _ in 0..3 {
            let pw = aw
                .saturating_sub(frame::left_margin(sizes) + y_area + cell.right)
                .max(20) as f64
                - 1.0;
            let ph = ah
                .saturating_sub(cell.top + cell.x_area + cell.bottom)
                .max(20) as f64
                - 1.0;
            let per_px = (sx / pw).max(sy / ph);
            let (hx, hy) = (per_px * pw / 2.0, per_px * ph / 2.0);
            // A tick about every 90 px, the same step on both axes unless y
            // would get fewer than two labels.
            let step = nice_step(per_px * 90.0);
            let xf = AxisFrame::with_step(map, cx - hx, cx + hx, step, x_desc.clone());
            let mut y_step = step;
            let mut yf = AxisFrame::with_step(map, cy - hy, cy + hy, y_step, y_desc.clone());
            for _ in 0..3 {
                if yf.ticks.major.len() >= 2 {
                    break;
                }
                y_step = nice_step(y_step / 2.2);
                yf = AxisFrame::with_step(map, cy - hy, cy + hy, y_step, y_desc.clone());
            }
            let needed = frame::y_label_area(root, &yf, sizes)?;
            let done = needed <= y_area;
            y_area = y_area.max(needed);
            frames = Some((xf, yf));
            if done {
                break;
            }
        }
        let (xf, yf) = frames.expect("loop runs at least once");
        let fs = FrameSizes {
            top: cell.top,
            left: frame::left_margin(sizes),
            right: cell.right,
            bottom: cell.bottom,
            x_label_area: cell.x_area,
            y_label_area: y_area,
        };
        let mut chart = frame::build_chart(&area, &xf, &yf, fs)?;
        frame::draw_mesh(&mut chart, &xf, &yf, sizes, true)?;
        let grey = Look {
            line: UNDEFORMED.stroke_width(2),
            body: UNDEFORMED.stroke_width(2),
            joint: UNDEFORMED.stroke_width(2),
        };
        draw_geometry(&mut chart, &self.undeformed, map, &grey)?;
        let colour = Look {
            line: palette(0).stroke_width(3),
            body: palette(1).filled(),
            joint: palette(0).stroke_width(2),
        };
        draw_geometry(&mut chart, &mode.deformed, map, &colour)?;
        Ok(frame::layout_of(&chart, &xf, &yf))
    }
}

/// Centre and size of the shown box around the extents: 6 % of the larger
/// span added on every side.
fn padded_box(ex: Extent, ey: Extent) -> Option<(Pt, Pt)> {
    let (x0, x1) = ex.padded(0.0, 0.0, 1.0)?;
    let (y0, y1) = ey.padded(0.0, 0.0, 1.0)?;
    let pad = 0.06 * (x1 - x0).max(y1 - y0);
    let centre = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    Some((centre, (x1 - x0 + 2.0 * pad, y1 - y0 + 2.0 * pad)))
}

struct Look {
    line: ShapeStyle,
    body: ShapeStyle,
    joint: ShapeStyle,
}

fn draw_geometry<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Coord>,
    g: &Geometry,
    map: AxisMap,
    look: &Look,
) -> Result<(), PlotError> {
    let to = |p: &[f64; 2]| -> Option<Pt> { Some((map.coord(p[0])?, map.coord(p[1])?)) };
    let thin = ShapeStyle {
        stroke_width: 1,
        ..look.joint
    };
    let ground = UNDEFORMED.stroke_width(1);
    for beam in &g.beams {
        let pts: Vec<Pt> = beam.iter().filter_map(to).collect();
        let pts = thin_to_pixels(chart, &pts, MIN_SEGMENT_PX);
        chart.draw_series(LineSeries::new(pts, look.line))?;
    }
    for spring in &g.springs {
        chart.draw_series(LineSeries::new(spring.iter().filter_map(to), thin))?;
    }
    for rail in g.joints.iter().filter_map(|j| j.rail) {
        chart.draw_series(LineSeries::new(rail.iter().filter_map(to), look.joint))?;
    }
    let h = MARKER_HALF as i32;
    let square = |p: Pt| EmptyElement::at(p) + Rectangle::new([(-h, -h), (h, h)], look.body);
    for body in &g.bodies {
        let pts: Vec<Pt> = body.iter().filter_map(to).collect();
        match pts.len() {
            0 => {}
            1 => {
                chart.draw_series(pts.into_iter().map(square))?;
            }
            2 => {
                let link = ShapeStyle {
                    stroke_width: look.line.stroke_width + 3,
                    ..look.body
                };
                chart.draw_series(LineSeries::new(pts, link))?;
            }
            _ => {
                chart.draw_series(std::iter::once(Polygon::new(pts.clone(), look.body)))?;
            }
        }
    }
    chart.draw_series(g.masses.iter().filter_map(to).map(square))?;
    let r = JOINT_RADIUS.round() as i32;
    for j in &g.joints {
        let Some(p) = to(&j.at) else { continue };
        for sym in scene::symbols(j) {
            let px: Vec<(i32, i32)> = sym
                .offsets
                .iter()
                .map(|o| (o[0].round() as i32, o[1].round() as i32))
                .collect();
            let style = if sym.part == SymbolPart::Hatch {
                ground
            } else {
                thin
            };
            let mut path = px.clone();
            if sym.closed {
                path.push(px[0]);
            }
            chart.draw_series(std::iter::once(
                EmptyElement::at(p) + PathElement::new(path, style),
            ))?;
        }
        let fill = if j.kind == JointKind::Weld {
            look.joint.color.filled()
        } else {
            BACKGROUND.filled()
        };
        chart.draw_series(std::iter::once(
            EmptyElement::at(p)
                + Circle::new((0, 0), r as u32, fill)
                + Circle::new((0, 0), r as u32, look.joint),
        ))?;
    }
    Ok(())
}

/// Shortest drawn segment of a beam centre line [px].
const MIN_SEGMENT_PX: i32 = 6;

/// The points of `pts` at least `min_px` pixels apart (the first and last
/// always). plotters outlines a thick polyline segment by segment from
/// integer pixels, so densely sampled curves (1–2 px segments) come out
/// jagged; chords of a few pixels stay within a fraction of a pixel of the
/// curve.
fn thin_to_pixels<DB: DrawingBackend>(
    chart: &ChartContext<'_, DB, Coord>,
    pts: &[Pt],
    min_px: i32,
) -> Vec<Pt> {
    let far = |a: &Pt, b: &Pt| {
        let (p, q) = (chart.backend_coord(a), chart.backend_coord(b));
        (p.0 - q.0).pow(2) + (p.1 - q.1).pow(2) >= min_px * min_px
    };
    let mut kept: Vec<Pt> = Vec::with_capacity(pts.len());
    for (i, p) in pts.iter().enumerate() {
        let last = i + 1 == pts.len();
        match kept.last() {
            None => kept.push(*p),
            Some(q) if far(q, p) => kept.push(*p),
            // The end point replaces a kept point too close to it.
            Some(_) if last && kept.len() > 1 => {
                kept.pop();
                kept.push(*p);
            }
            Some(_) if last => kept.push(*p),
            Some(_) => {}
        }
    }
    kept
}
