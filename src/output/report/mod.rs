//! The one-file HTML report: every result of a run in a page a designer
//! can mail to a colleague.
//!
//! The page is self-contained: inline SVG and CSS, a few lines of plain
//! JavaScript (mode picker, amplitude slider, play/pause), no external URL
//! of any kind, and a content security policy that forbids loading
//! anything, so a stray reference fails loudly in the browser's console.
//! Without JavaScript every section still shows and the modes still move
//! (SMIL, [`animate`]); readers who ask for reduced motion, and the print
//! stylesheet, get one still frame per mode.
//!
//! What the page shows comes from the caller as typed pieces
//! ([`ReportInput`]): the system and the state it was linearized at, the
//! modal result, and sections of figures (rendered by the same figure code
//! as `--plot`, [`crate::output::plot::render`] to an SVG string), tables
//! and notes. Full-precision frequencies sit in `data-` attributes of the
//! modes table, for checks and scripts.
//!
//! Units: lengths on the drawings in mm (a scale bar), frequencies in Hz.

pub mod animate;
mod page;
pub mod sections;
pub mod svg;

use crate::analysis::ModalResult;
use crate::output::figures::{assembly_geometry, ModeShapeSettings};
use crate::output::plot::{render, Figure, Format, PlotError, PlotSize};
use crate::system::System;
use animate::{all_points, animated_svg, geometry_svg, mode_frames};
use std::fmt::Write;
use svg::{escape, View};

/// Where a report came from (shown at its top).
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    pub tool_version: String,
    pub model_name: String,
    pub model_sha256: String,
    pub command_line: String,
    /// When the report was written (the caller's clock; ISO 8601).
    pub date: String,
}

/// A table: a header row and body rows of text cells.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    pub caption: String,
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

/// A section beyond the assembly and the modes.
#[derive(Debug, Clone)]
pub struct Section {
    /// Unique in the page (letters, digits, `-`).
    pub id: String,
    pub title: String,
    /// Paragraphs of plain text.
    pub notes: Vec<String>,
    pub tables: Vec<Table>,
    /// Text tables as the command line prints them (monospaced).
    pub preformatted: Vec<String>,
    pub figures: Vec<(Figure, PlotSize)>,
}

/// Modes linearized at a state of a system.
#[derive(Debug, Clone)]
pub struct ModeSet<'a> {
    /// Heading of the modes' section, e.g. "Modes at the reference".
    pub title: &'a str,
    pub system: &'a System,
    /// The state the modes were linearized at.
    pub q: &'a [f64],
    pub modal: &'a ModalResult,
    /// Each mode's damping ratio ζ [–] (null for zero-frequency modes);
    /// empty when not computed.
    pub damping_ratio: Vec<Option<f64>>,
}

/// Everything a report shows.
#[derive(Debug, Clone)]
pub struct ReportInput<'a> {
    pub provenance: Provenance,
    /// Free text of the model (its assumptions).
    pub description: &'a str,
    /// The modes (the first set draws the assembly too).
    pub mode_sets: Vec<ModeSet<'a>>,
    pub sections: Vec<Section>,
    /// The run's warnings (about the model, the analyses and the
    /// records), one sentence each: shown first, before any number.
    pub warnings: &'a [String],
}

/// Largest displacement of an animated mode, as a fraction of the
/// diagonal of the assembly's bounding box.
pub const AMPLITUDE_OF_DIAGONAL: f64 = 0.15;
/// Width of the mode drawings [px].
const WIDTH: f64 = 560.0;
/// Widest drawing of the assembly [px]: the page's text width.
const ASSEMBLY_WIDTH: f64 = 1140.0;
/// Margin of the mode panels [px]: room for the pixel-sized symbols of
/// supports around the drawing.
const SYMBOL_MARGIN: f64 = 22.0;
/// Beam samples per element in the animations.
const POINTS_PER_ELEMENT: usize = 8;

/// The report as one HTML document.
pub fn report_html(input: &ReportInput) -> Result<String, PlotError> {
    let mut body = String::new();
    let mut nav = Vec::new();
    if !input.warnings.is_empty() {
        nav.push(("warnings".to_string(), "Warnings".to_string()));
        body.push_str("<section id=\"warnings\" class=\"warnings\"><h2>Warnings</h2><ul>");
        for w in input.warnings {
            let _ = write!(body, "<li>{}</li>", escape(w));
        }
        body.push_str("</ul></section>");
    }
    if let Some(first) = input.mode_sets.first() {
        let g = assembly_geometry(first.system, first.q, POINTS_PER_ELEMENT);
        nav.push(("assembly".to_string(), "Assembly".to_string()));
        let _ = write!(
            body,
            "<section id=\"assembly\"><h2>Assembly</h2>{}<p class=\"note\">{}</p></section>",
            svg::assembly_svg(first.system, first.q, &g, ASSEMBLY_WIDTH),
            escape(input.description)
        );
    }
    for (k, set) in input.mode_sets.iter().enumerate() {
        let id = format!("modes-{}", k + 1);
        nav.push((id.clone(), set.title.to_string()));
        body.push_str(&modes_section(&id, set));
    }
    for s in &input.sections {
        nav.push((s.id.clone(), s.title.clone()));
        body.push_str(&section_html(s)?);
    }
    let mut modes: Vec<usize> = input
        .mode_sets
        .iter()
        .flat_map(|set| set.modal.modes.iter())
        .filter(|m| !m.kind.is_zero())
        .map(|m| m.index)
        .collect();
    modes.sort_unstable();
    modes.dedup();
    Ok(page::document(&input.provenance, &nav, &modes, &body))
}

/// The modes table and one animated panel per elastic mode.
fn modes_section(id: &str, set: &ModeSet) -> String {
    let r = set.modal;
    let mut s = format!(
        "<section id=\"{id}\" class=\"modes\"><h2>{}</h2><p>{} coordinates, {} constraint equations, {} free; {} zero-frequency modes ({} rigid, {} mechanism); solver: {}.</p>",
        escape(set.title),
        r.dofs,
        r.constraints,
        r.reduced_dofs,
        r.rigid_modes,
        r.rigid_modes - r.mechanism_modes.min(r.rigid_modes),
        r.mechanism_modes,
        escape(r.solver),
    );
    // An undamped model has no damping column (a column of "0.000 %"
    // reads as a measured zero).
    let damped = set.damping_ratio.iter().flatten().any(|z| *z != 0.0);
    let _ = write!(
        s,
        "<table class=\"modes-table\"><thead><tr><th>mode</th><th>frequency [Hz]</th><th>kind</th><th>bending %</th><th>axial %</th><th>spring %</th><th>error bound</th>{}</tr></thead><tbody>",
        if damped { "<th>damping ζ</th>" } else { "" }
    );
    for (k, m) in r.modes.iter().enumerate() {
        let bound = m.error_bound.map_or(String::new(), |b| format!("{b:.1e}"));
        let zeta = set
            .damping_ratio
            .get(k)
            .copied()
            .flatten()
            .map_or(String::new(), |z| format!("{:.3} %", 100.0 * z));
        let zeta = if damped {
            format!("<td class=\"num\">{zeta}</td>")
        } else {
            String::new()
        };
        let _ = write!(
            s,
            "<tr data-mode=\"{}\" data-frequency-hz=\"{:?}\" data-kind=\"{}\"><td>{}</td><td class=\"num\">{:.3}</td><td>{}</td><td class=\"num\">{:.2}</td><td class=\"num\">{:.2}</td><td class=\"num\">{:.2}</td><td class=\"num\">{bound}</td>{zeta}</tr>",
            m.index,
            m.frequency_hz,
            m.kind,
            m.index,
            m.frequency_hz,
            m.kind,
            100.0 * m.energy.bending,
            100.0 * m.energy.axial,
            100.0 * m.energy.springs,
        );
    }
    s.push_str("</tbody></table>");
    let undeformed = assembly_geometry(set.system, set.q, POINTS_PER_ELEMENT);
    let settings = ModeShapeSettings {
        amplitude_fraction: AMPLITUDE_OF_DIAGONAL * diagonal_over_side(&undeformed),
        points_per_element: POINTS_PER_ELEMENT,
        ..ModeShapeSettings::default()
    };
    let elastic: Vec<_> = r.modes.iter().filter(|m| !m.kind.is_zero()).collect();
    let frames: Vec<_> = elastic
        .iter()
        .map(|m| mode_frames(set.system, set.q, m, &settings))
        .collect();
    // One view for every panel of the set, so they compare at one scale.
    let points = all_points(&undeformed).chain(
        frames
            .iter()
            .flat_map(|f| f.frames.iter().flat_map(all_points)),
    );
    // The margin holds the supports' symbols (a ground pin's triangle and
    // hatching reach 19 px below its point).
    let view = View::fit(points, WIDTH / 2.0, SYMBOL_MARGIN);
    s.push_str("<div class=\"mode-grid\">");
    for (m, f) in elastic.iter().zip(&frames) {
        let _ = write!(
            s,
            "<figure class=\"mode\" data-mode=\"{}\">{}{}{}{}</svg><figcaption>Mode {}: {:.1} Hz ({})</figcaption></figure>",
            m.index,
            view.open("mode-shape", &format!("mode {} shape", m.index)),
            geometry_svg(&view, &undeformed, "undeformed"),
            animated_svg(&view, f),
            geometry_svg(&view, &f.frames[0], "deformed still"),
            m.index,
            m.frequency_hz,
            m.kind
        );
    }
    s.push_str("</div></section>");
    s
}

/// The bounding box's diagonal over its larger side (the figures' size).
fn diagonal_over_side(g: &crate::output::plot::Geometry) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in all_points(g) {
        for i in 0..2 {
            lo[i] = lo[i].min(p[i]);
            hi[i] = hi[i].max(p[i]);
        }
    }
    let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
    let side = w.max(h);
    if side > 0.0 && side.is_finite() {
        w.hypot(h) / side
    } else {
        1.0
    }
}

fn section_html(s: &Section) -> Result<String, PlotError> {
    let mut out = format!(
        "<section id=\"{}\"><h2>{}</h2>",
        escape(&s.id),
        escape(&s.title)
    );
    for n in &s.notes {
        let _ = write!(out, "<p>{}</p>", escape(n));
    }
    for t in &s.tables {
        out.push_str(&table_html(t));
    }
    for p in &s.preformatted {
        let _ = write!(out, "<pre>{}</pre>", escape(p));
    }
    for (figure, size) in &s.figures {
        let svg = String::from_utf8(render(figure, Format::Svg, *size)?)
            .expect("the SVG renderer writes UTF-8");
        let start = svg.find("<svg").unwrap_or(0);
        let _ = write!(out, "<figure class=\"plot\">{}</figure>", &svg[start..]);
    }
    out.push_str("</section>");
    Ok(out)
}

fn table_html(t: &Table) -> String {
    let mut s = String::from("<table>");
    if !t.caption.is_empty() {
        let _ = write!(s, "<caption>{}</caption>", escape(&t.caption));
    }
    s.push_str("<thead><tr>");
    for h in &t.header {
        let _ = write!(s, "<th>{}</th>", escape(h));
    }
    s.push_str("</tr></thead><tbody>");
    for row in &t.rows {
        s.push_str("<tr>");
        for c in row {
            let _ = write!(s, "<td>{}</td>", escape(c));
        }
        s.push_str("</tr>");
    }
    s.push_str("</tbody></table>");
    s
}
