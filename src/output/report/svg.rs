//! Inline SVG for the report: the one mapping from model coordinates
//! [SI: m] to panel pixels (equal scale on x and y, y up), and the
//! assembly drawn to scale.

use crate::output::plot::Geometry;
use crate::system::System;
use nalgebra::Vector2;
use std::fmt::Write;

/// Model-to-pixel mapping of a panel: x → margin + (x − x₀)·k,
/// y → height − margin − (y − y₀)·k, one k for both axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub width: f64,
    pub height: f64,
    x0: f64,
    y0: f64,
    /// Pixels per metre.
    pub scale: f64,
    margin: f64,
}

impl View {
    /// The mapping that fits `points` [SI: m] into a panel `width` pixels
    /// wide (its height follows the points' aspect ratio, within
    /// [0.35, 1.2]·width), leaving `margin` pixels on every side.
    pub fn fit<'a>(points: impl Iterator<Item = &'a [f64; 2]>, width: f64, margin: f64) -> View {
        let (lo, hi) = bounds(points).unwrap_or(([0.0; 2], [1.0; 2]));
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let inner = width - 2.0 * margin;
        let height = (inner * span[1] / span[0] + 2.0 * margin).clamp(0.35 * width, 1.2 * width);
        let scale = (inner / span[0]).min((height - 2.0 * margin) / span[1]);
        // Centre the drawing in the panel.
        let x0 = lo[0] - (inner / scale - span[0]) / 2.0;
        let y0 = lo[1] - ((height - 2.0 * margin) / scale - span[1]) / 2.0;
        View {
            width,
            height,
            x0,
            y0,
            scale,
            margin,
        }
    }

    /// The mapping that draws `points` [SI: m] as large as fits in
    /// `max_width` × `max_height` pixels with `margin` pixels on every
    /// side, the panel cut to the drawing (no empty band beside it), at
    /// least `min_height` pixels high so that symbols fit around a flat
    /// assembly, with a band of [`SCALE_BAR_BAND`] pixels below it.
    pub fn fit_box(
        points: &[[f64; 2]],
        (max_width, max_height): (f64, f64),
        min_height: f64,
        margin: f64,
    ) -> View {
        let Some((lo, hi)) = bounds(points.iter()) else {
            return View::fit(points.iter(), max_width, margin);
        };
        let span = [(hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12)];
        let (iw, ih) = (max_width - 2.0 * margin, max_height - 2.0 * margin);
        let scale = (iw / span[0]).min(ih / span[1]);
        let width = span[0] * scale + 2.0 * margin;
        let height = (span[1] * scale + 2.0 * margin).max(min_height);
        // The band for the scale bar under the drawing.
        View {
            width,
            height: height + SCALE_BAR_BAND,
            x0: lo[0],
            y0: lo[1] - ((height - 2.0 * margin) / scale - span[1]) / 2.0 - SCALE_BAR_BAND / scale,
            scale,
            margin,
        }
    }

    /// The pixel of model point `p` [SI: m].
    pub fn px(&self, p: [f64; 2]) -> (f64, f64) {
        (
            self.margin + (p[0] - self.x0) * self.scale,
            self.height - self.margin - (p[1] - self.y0) * self.scale,
        )
    }

    /// The opening tag of an SVG element of this size.
    pub fn open(&self, class: &str, label: &str) -> String {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"{class}\" viewBox=\"0 0 {w} {h}\" width=\"{w}\" height=\"{h}\" role=\"img\" aria-label=\"{}\">",
            escape(label),
            w = fmt_px(self.width),
            h = fmt_px(self.height),
        )
    }
}

/// The lower-left and upper-right corners of `points` [SI: m]; `None`
/// for no finite point.
fn bounds<'a>(points: impl Iterator<Item = &'a [f64; 2]>) -> Option<([f64; 2], [f64; 2])> {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in points {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    (lo[0].is_finite() && hi[0].is_finite()).then_some((lo, hi))
}

/// A pixel coordinate with two decimals (trailing zeros dropped).
pub fn fmt_px(v: f64) -> String {
    let s = format!("{v:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        String::from("0")
    } else {
        s.to_string()
    }
}

/// `text` with the five XML special characters escaped.
pub fn escape(text: &str) -> String {
    let mut s = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => s.push_str("&amp;"),
            '<' => s.push_str("&lt;"),
            '>' => s.push_str("&gt;"),
            '"' => s.push_str("&quot;"),
            '\'' => s.push_str("&#39;"),
            c => s.push(c),
        }
    }
    s
}

/// A point of the system drawn where the model sits [SI: m].
fn at(system: &System, p: Vector2<f64>) -> [f64; 2] {
    let p = p + system.origin;
    [p.x, p.y]
}

/// Height of the band under a [`View::fit_box`] drawing that holds its
/// scale bar [px].
pub const SCALE_BAR_BAND: f64 = 22.0;

/// Tallest drawing of the assembly [px].
const ASSEMBLY_MAX_HEIGHT: f64 = 520.0;

/// The assembly at `q`, to scale, as large as fits `width` pixels wide and
/// [`ASSEMBLY_MAX_HEIGHT`] high: beams, bodies, springs, joints and
/// supports as the mode panels draw them,
/// contacts as diamonds at their moving point, loads as arrows (length
/// proportional to the force, the largest a tenth of the drawing) and
/// sensors as rings; a scale bar of a round length in mm.
pub fn assembly_svg(system: &System, q: &[f64], geometry: &Geometry, width: f64) -> String {
    let points: Vec<[f64; 2]> = super::animate::all_points(geometry).copied().collect();
    let view = View::fit_box(&points, (width, ASSEMBLY_MAX_HEIGHT), 120.0, 30.0);
    let mut s = view.open("assembly", &format!("the assembly {}", system.name));
    s.push_str(&super::animate::geometry_svg(&view, geometry, "undeformed"));
    for c in &system.contacts {
        let (x, y) = view.px(at(
            system,
            crate::mechanics::spring::ForceElement::pair(c)
                .b
                .position(q),
        ));
        let _ = write!(
            s,
            "<polygon class=\"contact\" points=\"{},{} {},{} {},{} {},{}\"><title>{}</title></polygon>",
            fmt_px(x),
            fmt_px(y - 5.0),
            fmt_px(x + 5.0),
            fmt_px(y),
            fmt_px(x),
            fmt_px(y + 5.0),
            fmt_px(x - 5.0),
            fmt_px(y),
            escape(&c.label)
        );
    }
    let largest = system
        .loads
        .iter()
        .map(|l| l.force.norm())
        .fold(0.0f64, f64::max);
    for l in &system.loads {
        if largest == 0.0 {
            break;
        }
        let (x, y) = view.px(at(system, l.anchor.position(q)));
        let length = 0.1 * view.width * l.force.norm() / largest;
        let d = l.force / l.force.norm().max(f64::MIN_POSITIVE);
        let tail = (x - d.x * length, y + d.y * length);
        let _ = write!(
            s,
            "<line class=\"load\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" marker-end=\"url(#arrow)\"><title>{}</title></line>",
            fmt_px(tail.0),
            fmt_px(tail.1),
            fmt_px(x),
            fmt_px(y),
            escape(&l.label)
        );
    }
    for sensor in &system.sensors {
        let (x, y) = view.px(at(system, sensor.anchor.position(q)));
        let _ = write!(
            s,
            "<circle class=\"sensor\" cx=\"{}\" cy=\"{}\" r=\"6\"><title>{}</title></circle>",
            fmt_px(x),
            fmt_px(y),
            escape(&sensor.id)
        );
    }
    s.push_str(&scale_bar(&view));
    s.push_str("<defs><marker id=\"arrow\" viewBox=\"0 0 10 10\" refX=\"10\" refY=\"5\" markerWidth=\"8\" markerHeight=\"8\" orient=\"auto\"><path d=\"M0,0 L10,5 L0,10 z\"/></marker></defs></svg>");
    s
}

/// A bar of a round length (1, 2 or 5 × 10ⁿ mm) about a fifth of the panel.
fn scale_bar(view: &View) -> String {
    let target_m = 0.2 * view.width / view.scale;
    let decade = 10f64.powf(target_m.log10().floor());
    let length = [5.0, 2.0, 1.0]
        .iter()
        .map(|f| f * decade)
        .find(|l| *l <= target_m)
        .unwrap_or(decade);
    let px = length * view.scale;
    let (x, y) = (10.0, view.height - 10.0);
    format!(
        "<g class=\"scalebar\"><line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/><text x=\"{}\" y=\"{}\">{} mm</text></g>",
        fmt_px(x),
        fmt_px(y),
        fmt_px(x + px),
        fmt_px(y),
        fmt_px(x),
        fmt_px(y - 4.0),
        crate::output::plot::format_sig(length * 1e3, 3)
    )
}
