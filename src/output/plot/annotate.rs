//! Annotations drawn in pixel coordinates on top of charts: the figure
//! title, markers, boxed labels and the legend.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::error::PlotError;
use super::frame::Rect;
use super::geom::{self, Bounds};
use super::series::{Legend, MarkerShape, SeriesStyle};
use super::style::{self, TextSizes, BACKGROUND, INK};

/// Draws the figure title centred in a band at the top; returns the band's
/// height (small when there is no title).
pub(super) fn draw_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    sizes: &TextSizes,
) -> Result<u32, PlotError> {
    if title.is_empty() {
        return Ok((sizes.title * 0.5) as u32);
    }
    let h = (sizes.title * 1.8) as u32;
    let (w, _) = root.dim_in_pixel();
    let style = style::text(sizes.title, INK, HPos::Center, VPos::Center);
    root.draw(&Text::new(
        title.to_string(),
        (w as i32 / 2, h as i32 / 2 + 2),
        style,
    ))?;
    Ok(h)
}

pub(super) struct LegendEntry {
    pub name: String,
    pub style: SeriesStyle,
    pub colour: RGBColor,
}

pub(super) fn draw_marker<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    p: (i32, i32),
    shape: MarkerShape,
    colour: RGBColor,
) -> Result<(), PlotError> {
    match shape {
        MarkerShape::Ring => root.draw(&Circle::new(p, 7, colour.stroke_width(2)))?,
        MarkerShape::Dot => root.draw(&Circle::new(p, 5, colour.filled()))?,
        MarkerShape::Square => root.draw(&Rectangle::new(
            [(p.0 - 6, p.1 - 6), (p.0 + 6, p.1 + 6)],
            colour.filled(),
        ))?,
        MarkerShape::Triangle => root.draw(&TriangleMarker::new(p, 7, colour.filled()))?,
        MarkerShape::Cross => root.draw(&Cross::new(p, 6, colour.stroke_width(2)))?,
        MarkerShape::None => {}
    }
    Ok(())
}

pub(super) fn text_size<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    style: &TextStyle<'_>,
) -> Result<(i32, i32), PlotError> {
    let (w, h) = root.estimate_text_size(text, style)?;
    Ok((w as i32, h as i32 + 2))
}

/// Text on a faint white box, so it stays readable over curves.
pub(super) fn draw_label<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    text: &str,
    r: Rect,
    style: TextStyle<'_>,
) -> Result<(), PlotError> {
    if text.is_empty() {
        return Ok(());
    }
    root.draw(&Rectangle::new(
        [(r.0 - 2, r.1 - 1), (r.2 + 2, r.3 + 1)],
        BACKGROUND.mix(0.75).filled(),
    ))?;
    root.draw(&Text::new(text.to_string(), (r.0, r.1 + 1), style))?;
    Ok(())
}

const GLYPH_W: i32 = 36;

/// The legend's rectangle at `pos` inside `plot`; for [`Legend::Auto`] the
/// corner where the fewest `drawn` segments and points would be hidden.
pub(super) fn legend_rect<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    pos: Legend,
    plot: Rect,
    drawn: &[Vec<(i32, i32)>],
    sizes: &TextSizes,
) -> Result<Option<Rect>, PlotError> {
    if entries.is_empty() || pos == Legend::None {
        return Ok(None);
    }
    let style = style::text(sizes.legend, INK, HPos::Left, VPos::Center);
    let mut text_w = 0;
    for e in entries {
        text_w = text_w.max(text_size(root, &e.name, &style)?.0);
    }
    let row = (sizes.legend * 1.5) as i32;
    let (w, h) = (
        12 + GLYPH_W + 10 + text_w + 14,
        8 + row * entries.len() as i32 + 8,
    );
    let inset = 12;
    let at = |pos: Legend| {
        let x0 = match pos {
            Legend::UpperLeft | Legend::LowerLeft => plot.0 + inset,
            _ => plot.2 - inset - w,
        };
        let y0 = match pos {
            Legend::UpperLeft | Legend::UpperRight | Legend::Auto => plot.1 + inset,
            _ => plot.3 - inset - h,
        };
        (x0, y0, x0 + w, y0 + h)
    };
    if pos != Legend::Auto {
        return Ok(Some(at(pos)));
    }
    let corners = [
        Legend::UpperRight,
        Legend::UpperLeft,
        Legend::LowerRight,
        Legend::LowerLeft,
    ];
    let best = corners
        .iter()
        .map(|&c| at(c))
        .min_by_key(|&r| hidden(r, drawn))
        .unwrap_or_else(|| at(Legend::UpperRight));
    Ok(Some(best))
}

/// How much of the drawn data `r` would cover: segments crossing it, and
/// single points in it (weighted up: they are markers).
fn hidden(r: Rect, drawn: &[Vec<(i32, i32)>]) -> usize {
    let b = Bounds {
        x0: f64::from(r.0 - 4),
        x1: f64::from(r.2 + 4),
        y0: f64::from(r.1 - 4),
        y1: f64::from(r.3 + 4),
    };
    let pt = |p: (i32, i32)| (f64::from(p.0), f64::from(p.1));
    drawn
        .iter()
        .map(|line| match line.as_slice() {
            [p] => 5 * usize::from(b.contains(pt(*p))),
            _ => line
                .windows(2)
                .filter(|w| geom::segment_meets(pt(w[0]), pt(w[1]), b))
                .count(),
        })
        .sum()
}

pub(super) fn draw_legend<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    r: Rect,
    sizes: &TextSizes,
) -> Result<(), PlotError> {
    root.draw(&Rectangle::new(
        [(r.0, r.1), (r.2, r.3)],
        BACKGROUND.mix(0.9).filled(),
    ))?;
    root.draw(&Rectangle::new(
        [(r.0, r.1), (r.2, r.3)],
        INK.mix(0.3).stroke_width(1),
    ))?;
    let row = (sizes.legend * 1.5) as i32;
    let style = style::text(sizes.legend, INK, HPos::Left, VPos::Center);
    for (i, e) in entries.iter().enumerate() {
        let yc = r.1 + 8 + row * i as i32 + row / 2;
        let (g0, g1) = (r.0 + 12, r.0 + 12 + GLYPH_W);
        let line = e.colour.stroke_width(2);
        match e.style {
            SeriesStyle::Line | SeriesStyle::LinePoints => {
                root.draw(&PathElement::new(vec![(g0, yc), (g1, yc)], line))?;
            }
            SeriesStyle::Reference => {
                for k in 0..3 {
                    let s = g0 + k * 14;
                    root.draw(&PathElement::new(
                        vec![(s, yc), ((s + 9).min(g1), yc)],
                        line,
                    ))?;
                }
            }
            SeriesStyle::Points => {}
        }
        if matches!(e.style, SeriesStyle::Points | SeriesStyle::LinePoints) {
            root.draw(&Circle::new(((g0 + g1) / 2, yc), 5, e.colour.filled()))?;
        }
        root.draw(&Text::new(e.name.clone(), (g1 + 10, yc), style.clone()))?;
    }
    Ok(())
}
