//! Line figures: one or more panels stacked vertically, sharing the x axis.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::annotate::{
    draw_label, draw_legend, draw_marker, draw_title, legend_rect, text_size, LegendEntry,
};
use super::error::PlotError;
use super::frame::{self, stack, AxisFrame, AxisMap, Coord, FrameSizes, PanelLayout, Placer, Rect};
use super::geom::{self, Bounds, Extent, Pt};
use super::series::{Guide, Legend, MarkerShape, PointMarker, Series, SeriesStyle};
use super::size::PlotSize;
use super::style::{self, palette, Scale, TextSizes, GUIDE, INK, REFERENCE};

/// A figure of curves over a shared x axis. Data are SI; `x_scale` says how
/// x is shown (and gives the unit in the label).
#[derive(Debug, Clone, Default)]
pub struct LineFigure {
    pub title: String,
    /// The quantity on the x axis, without unit (e.g. "Frequency").
    pub x_label: String,
    pub x_scale: Scale,
    pub x_log: bool,
    /// Shown x range (SI); `None` fits the data of all panels.
    pub x_range: Option<(f64, f64)>,
    /// Top to bottom; the bottom panel carries the x tick labels.
    pub panels: Vec<Panel>,
}

/// One panel of a [`LineFigure`].
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// The quantity on the y axis, without unit (e.g. "Acceleration").
    pub y_label: String,
    pub y_scale: Scale,
    pub y_log: bool,
    /// Shown y range (SI); `None` fits this panel's data.
    pub y_range: Option<(f64, f64)>,
    pub series: Vec<Series>,
    /// Vertical lines at x values (e.g. eigenfrequencies).
    pub vlines: Vec<Guide>,
    /// Horizontal lines at y values (e.g. a calibration target).
    pub hlines: Vec<Guide>,
    /// Labelled markers (e.g. identified peaks).
    pub points: Vec<PointMarker>,
    pub legend: Legend,
}

impl Panel {
    pub fn new(y_label: impl Into<String>, y_scale: Scale) -> Self {
        Panel {
            y_label: y_label.into(),
            y_scale,
            ..Panel::default()
        }
    }

    fn y_map(&self) -> AxisMap {
        AxisMap {
            factor: self.y_scale.factor,
            log: self.y_log,
        }
    }

    /// x values drawn as markers (which must not be cut by the frame).
    fn marker_xs(&self) -> impl Iterator<Item = f64> + '_ {
        let series = self
            .series
            .iter()
            .filter(|s| matches!(s.style, SeriesStyle::Points | SeriesStyle::LinePoints))
            .flat_map(|s| s.x.iter().copied());
        self.points.iter().map(|p| p.x).chain(series)
    }

    /// The y axis of this panel, over data whose x is shown.
    fn y_frame(&self, index: usize, x: &AxisFrame, plot_h: u32) -> Result<AxisFrame, PlotError> {
        let m = self.y_map();
        let mut e = Extent::default();
        if let Some((lo, hi)) = self.y_range {
            e.add(m.coord(lo).unwrap_or(f64::NAN));
            e.add(m.coord(hi).unwrap_or(f64::NAN));
        } else {
            let shown = |xv: f64| x.map.coord(xv).is_some_and(|c| c >= x.lo && c <= x.hi);
            for s in &self.series {
                for (&xv, &yv) in s.x.iter().zip(&s.y) {
                    if shown(xv) {
                        e.add(m.coord(yv).unwrap_or(f64::NAN));
                    }
                }
            }
            for g in &self.hlines {
                e.add(m.coord(g.at).unwrap_or(f64::NAN));
            }
            for p in &self.points {
                e.add(m.coord(p.y).unwrap_or(f64::NAN));
            }
        }
        let (below, above) = match (self.y_range.is_some(), self.points.is_empty()) {
            (true, _) => (0.0, 0.0),
            (false, true) => (0.05, 0.05),
            (false, false) => (0.05, 0.15),
        };
        let (lo, hi) = e
            .padded(below, above, 1.0)
            .ok_or_else(|| PlotError::EmptyData {
                what: format!(
                    "panel {} (`{}`) has no value to show",
                    index + 1,
                    self.y_label
                ),
            })?;
        let target = (plot_h as f64 / 70.0).round().clamp(2.0, 10.0) as usize;
        let frame = if self.y_range.is_some() {
            AxisFrame::new
        } else {
            AxisFrame::snapped
        };
        Ok(frame(m, lo, hi, self.y_scale.label(&self.y_label), target))
    }
}

impl LineFigure {
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, x_scale: Scale) -> Self {
        LineFigure {
            title: title.into(),
            x_label: x_label.into(),
            x_scale,
            ..LineFigure::default()
        }
    }

    fn validate(&self) -> Result<(), PlotError> {
        if self.panels.is_empty() {
            return Err(PlotError::EmptyData {
                what: format!("line figure `{}` has no panel", self.title),
            });
        }
        for s in self.panels.iter().flat_map(|p| &p.series) {
            if s.x.len() != s.y.len() {
                return Err(PlotError::LengthMismatch {
                    series: s.name.clone(),
                    x_len: s.x.len(),
                    y_len: s.y.len(),
                });
            }
        }
        Ok(())
    }

    fn x_frame(&self, width: u32) -> Result<AxisFrame, PlotError> {
        let m = AxisMap {
            factor: self.x_scale.factor,
            log: self.x_log,
        };
        let mut e = Extent::default();
        let mut add = |v: f64| e.add(m.coord(v).unwrap_or(f64::NAN));
        if let Some((lo, hi)) = self.x_range {
            add(lo);
            add(hi);
        } else {
            for p in &self.panels {
                p.series.iter().flat_map(|s| &s.x).for_each(|&v| add(v));
                p.vlines.iter().for_each(|g| add(g.at));
                p.points.iter().for_each(|q| add(q.x));
            }
        }
        // Pad only when a marker sits near an edge of the data.
        let near_edge = e.padded(0.0, 0.0, 1.0).is_some_and(|(lo, hi)| {
            let margin = 0.03 * (hi - lo);
            let xs = self.panels.iter().flat_map(Panel::marker_xs);
            xs.filter_map(|v| m.coord(v))
                .any(|c| c < lo + margin || c > hi - margin)
        });
        let pad = if self.x_range.is_none() && near_edge {
            0.04
        } else {
            0.0
        };
        let (lo, hi) = e
            .padded(pad, pad, 1.0)
            .ok_or_else(|| PlotError::EmptyData {
                what: format!("line figure `{}` has no x value to show", self.title),
            })?;
        let target = (width as f64 / 140.0).round().clamp(3.0, 12.0) as usize;
        let frame = if self.x_range.is_some() {
            AxisFrame::new
        } else {
            AxisFrame::snapped
        };
        Ok(frame(m, lo, hi, self.x_scale.label(&self.x_label), target))
    }

    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        self.draw_sized(root, size, TextSizes::for_size(size))
    }

    /// Draws into `root` of `size` pixels with the given text sizes (a part
    /// of a [`super::StackedFigure`] keeps the whole figure's text).
    pub(super) fn draw_sized<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
        sizes: TextSizes,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        self.validate()?;
        let title_h = draw_title(root, &self.title, &sizes)?;
        let x = self.x_frame(size.width)?;

        let n = self.panels.len() as u32;
        let top = (sizes.tick * 0.8) as u32;
        let gap = 10u32;
        let bottom = frame::x_label_area(&sizes);
        let pad = frame::bottom_margin(&sizes);
        let fixed = title_h + bottom + pad + n * top + (n - 1) * gap;
        let plot_h = size.height.saturating_sub(fixed) / n;
        if plot_h < 20 {
            return Err(PlotError::InvalidSize {
                width: size.width,
                height: size.height,
            });
        }
        let frames = self
            .panels
            .iter()
            .enumerate()
            .map(|(i, p)| p.y_frame(i, &x, plot_h))
            .collect::<Result<Vec<_>, _>>()?;
        let mut y_area = 0;
        for f in &frames {
            y_area = y_area.max(frame::y_label_area(root, f, &sizes)?);
        }

        let mut breaks = vec![title_h as i32];
        for _ in 1..n {
            let last = *breaks.last().expect("not empty");
            breaks.push(last + (top + plot_h + gap) as i32);
        }
        let areas = root.split_by_breakpoints::<i32, i32, _, _>([], breaks);
        let mut next_colour = 0;
        let mut layouts = Vec::new();
        for (i, (panel, y)) in self.panels.iter().zip(&frames).enumerate() {
            let last = i + 1 == self.panels.len();
            let fs = FrameSizes {
                top,
                left: frame::left_margin(&sizes),
                right: (sizes.tick * 2.0) as u32,
                bottom: if last { pad } else { 0 },
                x_label_area: if last { bottom } else { gap },
                y_label_area: y_area,
            };
            let mut chart = frame::build_chart(&areas[i + 1], &x, y, fs)?;
            frame::draw_mesh(&mut chart, &x, y, &sizes, last)?;
            panel.draw_content(root, &mut chart, &x, y, &sizes, &mut next_colour)?;
            layouts.push(frame::layout_of(&chart, &x, y));
        }
        Ok(layouts)
    }
}

impl Panel {
    fn draw_content<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &mut ChartContext<'_, DB, Coord>,
        x: &AxisFrame,
        y: &AxisFrame,
        sizes: &TextSizes,
        next_colour: &mut usize,
    ) -> Result<(), PlotError> {
        let b = Bounds {
            x0: x.lo,
            x1: x.hi,
            y0: y.lo,
            y1: y.hi,
        };
        let (px, py) = chart.plotting_area().get_pixel_range();
        let plot: Rect = (px.start, py.start, px.end, py.end);
        let columns = (px.end - px.start).max(1) as usize;

        // Guides under the data.
        for g in &self.vlines {
            if let Some(c) = x.map.coord(g.at).filter(|c| (x.lo..=x.hi).contains(c)) {
                draw_guide(chart, [(c, y.lo), (c, y.hi)], g.reference)?;
            }
        }
        for g in &self.hlines {
            if let Some(c) = y.map.coord(g.at).filter(|c| (y.lo..=y.hi).contains(c)) {
                draw_guide(chart, [(x.lo, c), (x.hi, c)], g.reference)?;
            }
        }

        let mut legend = Vec::new();
        // Drawn data in pixels (polylines; single points), for the legend.
        let mut drawn: Vec<Vec<(i32, i32)>> = Vec::new();
        for s in &self.series {
            let colour = if s.style == SeriesStyle::Reference {
                REFERENCE
            } else {
                let index = s.colour.unwrap_or_else(|| {
                    *next_colour += 1;
                    *next_colour - 1
                });
                palette(index)
            };
            let points =
                s.x.iter()
                    .zip(&s.y)
                    .map(|(&a, &c)| Some((x.map.coord(a)?, y.map.coord(c)?)));
            let runs = geom::runs(points);
            if s.style != SeriesStyle::Points {
                for run in &runs {
                    for part in geom::clip_polyline(run, b) {
                        let part = geom::decimate(&part, x.lo, x.hi, columns);
                        drawn.push(part.iter().map(|p| chart.backend_coord(p)).collect());
                        if s.style == SeriesStyle::Reference {
                            chart.draw_series(DashedLineSeries::new(
                                part,
                                12,
                                7,
                                colour.stroke_width(2),
                            ))?;
                        } else {
                            // A dense curve (more points than pixel columns,
                            // e.g. a decimated oscillation) turns sharply at
                            // every point; mitred 2-px joins of the bitmap
                            // backend then shoot spikes out of the panel.
                            let width = if part.len() > columns { 1 } else { 2 };
                            chart.draw_series(LineSeries::new(part, colour.stroke_width(width)))?;
                        }
                    }
                }
            }
            if matches!(s.style, SeriesStyle::Points | SeriesStyle::LinePoints) {
                let inside: Vec<Pt> = runs
                    .iter()
                    .flatten()
                    .copied()
                    .filter(|p| b.contains(*p))
                    .collect();
                drawn.extend(inside.iter().map(|p| vec![chart.backend_coord(p)]));
                chart.draw_series(
                    inside
                        .into_iter()
                        .map(|p| Circle::new(p, 5, colour.filled())),
                )?;
            }
            if !s.name.is_empty() {
                legend.push(LegendEntry {
                    name: s.name.clone(),
                    style: s.style,
                    colour,
                });
            }
        }

        // Markers, then every label placed so that none overlaps another,
        // a marker or the legend.
        let mut placer = Placer::default();
        for m in &self.points {
            if let Some(c) = x.map.coord(m.x).zip(y.map.coord(m.y)) {
                drawn.push(vec![chart.backend_coord(&c)]);
            }
        }
        let legend_box = legend_rect(root, &legend, self.legend, plot, &drawn, sizes)?;
        if let Some(r) = legend_box {
            placer.block(r);
        }
        let mut marker_px = Vec::new();
        for m in &self.points {
            let Some(c) = x
                .map
                .coord(m.x)
                .zip(y.map.coord(m.y))
                .filter(|c| b.contains(*c))
            else {
                continue;
            };
            let p = chart.backend_coord(&c);
            let colour = m.colour.map_or(INK, palette);
            draw_marker(root, p, m.shape, colour)?;
            if m.shape != MarkerShape::None {
                placer.block((p.0 - 7, p.1 - 7, p.0 + 7, p.1 + 7));
            }
            marker_px.push((p, m));
        }
        let note = |colour| style::text(sizes.note, colour, HPos::Left, VPos::Top);
        for (p, m) in marker_px {
            let (w, h) = text_size(root, &m.label, &note(INK))?;
            let (up, side) = (10 + h, 12);
            let above = (p.0 - w / 2, p.1 - up, p.0 - w / 2 + w, p.1 - up + h);
            let right = (p.0 + side, p.1 - h / 2, p.0 + side + w, p.1 - h / 2 + h);
            let left = (p.0 - side - w, p.1 - h / 2, p.0 - side, p.1 - h / 2 + h);
            let below = (above.0, p.1 + 10, above.2, p.1 + 10 + h);
            let candidates = [above, right, left]
                .into_iter()
                .chain(stack(above, -(h + 2), 6).skip(1))
                .chain(stack(right, -(h + 2), 4).skip(1))
                .chain(stack(left, -(h + 2), 4).skip(1))
                .chain(stack(below, h + 2, 4));
            let r = placer.place(candidates, plot);
            draw_label(root, &m.label, r, note(INK))?;
        }
        for g in &self.vlines {
            if let Some(c) = x.map.coord(g.at).filter(|c| (x.lo..=x.hi).contains(c)) {
                let p = chart.backend_coord(&(c, y.hi));
                let colour = if g.reference { REFERENCE } else { GUIDE };
                let (w, h) = text_size(root, &g.label, &note(colour))?;
                let right = (p.0 + 5, p.1 + 4, p.0 + 5 + w, p.1 + 4 + h);
                let left = (p.0 - 5 - w, p.1 + 4, p.0 - 5, p.1 + 4 + h);
                let candidates = stack(right, h + 2, 12).chain(stack(left, h + 2, 12));
                let r = placer.place(candidates, plot);
                draw_label(root, &g.label, r, note(colour))?;
            }
        }
        for g in &self.hlines {
            if let Some(c) = y.map.coord(g.at).filter(|c| (y.lo..=y.hi).contains(c)) {
                let p = chart.backend_coord(&(x.hi, c));
                let colour = if g.reference { REFERENCE } else { GUIDE };
                let (w, h) = text_size(root, &g.label, &note(colour))?;
                let above = (p.0 - 8 - w, p.1 - 4 - h, p.0 - 8, p.1 - 4);
                let below = (p.0 - 8 - w, p.1 + 4, p.0 - 8, p.1 + 4 + h);
                let candidates = stack(above, -(h + 2), 6).chain(stack(below, h + 2, 6));
                let r = placer.place(candidates, plot);
                draw_label(root, &g.label, r, note(colour))?;
            }
        }
        if let Some(r) = legend_box {
            draw_legend(root, &legend, r, sizes)?;
        }
        Ok(())
    }
}

fn draw_guide<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Coord>,
    ends: [Pt; 2],
    reference: bool,
) -> Result<(), PlotError> {
    if reference {
        chart.draw_series(DashedLineSeries::new(
            ends,
            12,
            7,
            REFERENCE.stroke_width(2),
        ))?;
    } else {
        chart.draw_series(LineSeries::new(ends, GUIDE.mix(0.7).stroke_width(1)))?;
    }
    Ok(())
}
