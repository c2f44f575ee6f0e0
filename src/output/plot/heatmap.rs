//! Heat maps: a value over a 2-D grid of (x, y) as coloured cells, with a
//! colour bar. For sweeps over two parameters.
//!
//! Cells are centred on the grid values and reach halfway to their
//! neighbours (in log10 on a log axis); missing values (non-finite, e.g. a
//! failed point) are drawn in light grey. Colours run through a
//! perceptually uniform, colour-blind-safe map (viridis, dark blue → yellow)
//! from the smallest to the largest value. A [`LabelledHeatMap`] also
//! writes a text in every cell (e.g. the MAC values), dark on the light
//! end of the map and white on the dark end.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::annotate::draw_title;
use super::error::PlotError;
use super::frame::{self, AxisFrame, AxisMap, FrameSizes, PanelLayout};
use super::geom::Extent;
use super::size::PlotSize;
use super::style::{self, Scale, TextSizes, INK};
use plotters::style::text_anchor::{HPos, VPos};

/// A value over a grid.
#[derive(Debug, Clone, Default)]
pub struct HeatMap {
    pub title: String,
    pub x_label: String,
    pub x_scale: Scale,
    pub x_log: bool,
    pub y_label: String,
    pub y_scale: Scale,
    pub y_log: bool,
    /// Grid values along x and y (SI), ascending or descending.
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// `z[j][i]` at `(x[i], y[j])`, SI; non-finite = missing.
    pub z: Vec<Vec<f64>>,
    /// The colour bar's quantity (e.g. "Frequency") and display scale.
    pub z_label: String,
    pub z_scale: Scale,
}

/// Viridis at eight stops.
const VIRIDIS: [(u8, u8, u8); 8] = [
    (68, 1, 84),
    (70, 50, 127),
    (54, 92, 141),
    (39, 127, 142),
    (31, 161, 135),
    (74, 194, 109),
    (159, 218, 58),
    (253, 231, 37),
];

/// Missing cells.
const MISSING: RGBColor = RGBColor(225, 225, 225);

/// The colour at `t` ∈ [0, 1].
pub fn colour_map(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (VIRIDIS.len() - 1) as f64;
    let i = (s.floor() as usize).min(VIRIDIS.len() - 2);
    let f = s - i as f64;
    let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
    let mix = |p: u8, q: u8| (p as f64 + f * (q as f64 - p as f64)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Cell edges (coordinates) around each of `centres`.
fn edges(centres: &[f64]) -> Vec<(f64, f64)> {
    let n = centres.len();
    (0..n)
        .map(|i| {
            let half = |j: usize| (centres[j] - centres[i]) / 2.0;
            let (lo, hi) = match n {
                1 => (-0.5, 0.5),
                _ if i == 0 => (-half(1), half(1)),
                _ if i + 1 == n => (half(i - 1), -half(i - 1)),
                _ => (half(i - 1), half(i + 1)),
            };
            let (a, b) = (centres[i] + lo, centres[i] + hi);
            (a.min(b), a.max(b))
        })
        .collect()
}

impl HeatMap {
    fn coords(values: &[f64], map: AxisMap, what: &str) -> Result<Vec<f64>, PlotError> {
        values
            .iter()
            .map(|&v| map.coord(v))
            .collect::<Option<Vec<f64>>>()
            .filter(|c| !c.is_empty())
            .ok_or_else(|| PlotError::EmptyData {
                what: format!(
                    "the {what} values cannot be shown (non-finite, or ≤ 0 on a log axis)"
                ),
            })
    }

    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        self.draw_labelled(root, size, None)
    }

    /// Draws the map, and `labels[j][i]` centred in cell (i, j) if given.
    fn draw_labelled<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
        labels: Option<&[Vec<String>]>,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        let rows_ok =
            self.z.len() == self.y.len() && self.z.iter().all(|r| r.len() == self.x.len());
        if !rows_ok {
            return Err(PlotError::LengthMismatch {
                series: self.title.clone(),
                x_len: self.x.len() * self.y.len(),
                y_len: self.z.iter().map(Vec::len).sum(),
            });
        }
        let sizes = TextSizes::for_size(size);
        let title_h = draw_title(root, &self.title, &sizes)?;
        let xm = AxisMap {
            factor: self.x_scale.factor,
            log: self.x_log,
        };
        let ym = AxisMap {
            factor: self.y_scale.factor,
            log: self.y_log,
        };
        let xc = HeatMap::coords(&self.x, xm, "x")?;
        let yc = HeatMap::coords(&self.y, ym, "y")?;
        let (xe, ye) = (edges(&xc), edges(&yc));
        let span = |e: &[(f64, f64)]| {
            let lo = e.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let hi = e.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
            (lo, hi)
        };
        let (x0, x1) = span(&xe);
        let (y0, y1) = span(&ye);
        let mut ze = Extent::default();
        self.z.iter().flatten().for_each(|&v| ze.add(v));
        let (z0, z1) = ze
            .padded(0.0, 0.0, 1.0)
            .ok_or_else(|| PlotError::EmptyData {
                what: format!("heat map `{}` has no value to show", self.title),
            })?;
        let target = |px: u32, per: f64| (px as f64 / per).round().clamp(3.0, 10.0) as usize;
        // A labelled map over integers (mode numbers) ticks every integer.
        let integers = |v: &[f64]| v.iter().all(|x| x.fract() == 0.0);
        let axis = |map: AxisMap, lo: f64, hi: f64, desc: String, n: usize, grid: &[f64]| {
            if labels.is_some() && !map.log && integers(grid) {
                AxisFrame::with_step(map, lo, hi, map.factor.abs(), desc)
            } else {
                AxisFrame::new(map, lo, hi, desc, n)
            }
        };
        let x = axis(
            xm,
            x0,
            x1,
            self.x_scale.label(&self.x_label),
            target(size.width, 140.0),
            &self.x,
        );
        let y = axis(
            ym,
            y0,
            y1,
            self.y_scale.label(&self.y_label),
            target(size.height, 70.0),
            &self.y,
        );
        let zm = AxisMap {
            factor: self.z_scale.factor,
            log: false,
        };
        let z = AxisFrame::new(
            zm,
            zm.coord(z0).unwrap_or(0.0),
            zm.coord(z1).unwrap_or(1.0),
            self.z_scale.label(&self.z_label),
            target(size.height, 70.0),
        );
        let (w, h) = root.dim_in_pixel();
        let area = root.margin(title_h, 0, 0, 0);
        let bar_w = (w / 6).max(120);
        let (main, bar) = area.split_horizontally(w.saturating_sub(bar_w));
        let plot_h =
            h.saturating_sub(title_h + frame::x_label_area(&sizes) + frame::bottom_margin(&sizes));
        if plot_h < 40 || w < 300 {
            return Err(PlotError::InvalidSize {
                width: w,
                height: h,
            });
        }
        let fs = FrameSizes {
            top: (sizes.tick * 0.8) as u32,
            left: frame::left_margin(&sizes),
            right: (sizes.tick * 2.0) as u32,
            bottom: frame::bottom_margin(&sizes),
            x_label_area: frame::x_label_area(&sizes),
            y_label_area: frame::y_label_area(root, &y, &sizes)?,
        };
        let mut chart = frame::build_chart(&main, &x, &y, fs)?;
        // Mesh first: the cells cover the grid lines.
        frame::draw_mesh(&mut chart, &x, &y, &sizes, true)?;
        let span_z = (z.hi - z.lo).max(f64::MIN_POSITIVE);
        let mut cells = Vec::with_capacity(xc.len() * yc.len());
        for (j, row) in self.z.iter().enumerate() {
            for (i, &v) in row.iter().enumerate() {
                let colour = match zm.coord(v) {
                    Some(c) => colour_map((c - z.lo) / span_z),
                    None => MISSING,
                };
                cells.push(Rectangle::new(
                    [(xe[i].0, ye[j].0), (xe[i].1, ye[j].1)],
                    colour.filled(),
                ));
            }
        }
        chart.draw_series(cells)?;
        if let Some(labels) = labels {
            let mut texts = Vec::new();
            for (j, (row, values)) in labels.iter().zip(&self.z).enumerate() {
                for (i, (text, &v)) in row.iter().zip(values).enumerate() {
                    let t = zm.coord(v).map_or(0.0, |c| (c - z.lo) / span_z);
                    let colour = if t > 0.55 {
                        INK
                    } else {
                        RGBColor(255, 255, 255)
                    };
                    let centre = (0.5 * (xe[i].0 + xe[i].1), 0.5 * (ye[j].0 + ye[j].1));
                    texts.push(Text::new(
                        text.clone(),
                        centre,
                        style::text(sizes.tick, colour, HPos::Center, VPos::Center),
                    ));
                }
            }
            chart.draw_series(texts)?;
        }
        let layout = frame::layout_of(&chart, &x, &y);

        // The colour bar: a one-column chart over the value range.
        let strip = AxisFrame::with_step(
            AxisMap {
                factor: 1.0,
                log: false,
            },
            0.0,
            1.0,
            10.0,
            String::new(),
        );
        let bar_fs = FrameSizes {
            left: 4,
            right: bar_w.saturating_sub(40 + frame::y_label_area(root, &z, &sizes)?),
            y_label_area: frame::y_label_area(root, &z, &sizes)?,
            ..fs
        };
        let mut bar_chart = frame::build_chart(&bar, &strip, &z, bar_fs)?;
        frame::draw_mesh(&mut bar_chart, &strip, &z, &sizes, false)?;
        let steps = 128;
        bar_chart.draw_series((0..steps).map(|k| {
            let (a, b) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
            let colour = colour_map((a + b) / 2.0);
            Rectangle::new(
                [
                    (0.0, z.lo + a * (z.hi - z.lo)),
                    (1.0, z.lo + b * (z.hi - z.lo)),
                ],
                colour.filled(),
            )
        }))?;
        Ok(vec![layout])
    }
}

/// A heat map with a text in every cell.
#[derive(Debug, Clone, Default)]
pub struct LabelledHeatMap {
    pub map: HeatMap,
    /// `labels[j][i]` in the cell at `(x[i], y[j])`.
    pub labels: Vec<Vec<String>>,
}

impl LabelledHeatMap {
    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        let m = &self.map;
        let fits =
            self.labels.len() == m.y.len() && self.labels.iter().all(|r| r.len() == m.x.len());
        if !fits {
            return Err(PlotError::LengthMismatch {
                series: format!("{} (cell labels)", m.title),
                x_len: m.x.len() * m.y.len(),
                y_len: self.labels.iter().map(Vec::len).sum(),
            });
        }
        m.draw_labelled(root, size, Some(&self.labels))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_meet_halfway() {
        let e = edges(&[0.0, 1.0, 3.0]);
        assert_eq!(e, vec![(-0.5, 0.5), (0.5, 2.0), (2.0, 4.0)]);
        assert_eq!(edges(&[2.0]), vec![(1.5, 2.5)]);
    }

    #[test]
    fn colour_map_runs_from_dark_to_light() {
        let lum = |c: RGBColor| 0.2126 * c.0 as f64 + 0.7152 * c.1 as f64 + 0.0722 * c.2 as f64;
        let l: Vec<f64> = (0..=10).map(|k| lum(colour_map(k as f64 / 10.0))).collect();
        assert!(l.windows(2).all(|w| w[1] > w[0]), "{l:?}");
    }
}
