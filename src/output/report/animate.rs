//! Animated mode shapes as plain SVG: no script, animated by SMIL.
//!
//! A mode φ linearized at q moves the assembly through q + a·cos(2πt/T)·φ.
//! The panel holds the undeformed geometry in grey and the deformed one in
//! colour, each drawn element sampled as the mode-shape figures sample it
//! ([`crate::output::figures::assembly_geometry`]: beam centre lines from
//! the shape functions, bodies and point masses at their positions, joints
//! at their anchors). The deformed geometry is given at [`PHASES`] phases
//! t/T = k/PHASES of one period, and every polyline, body marker and joint
//! circle carries an `<animate>` whose `values` are those frames (the
//! browser interpolates linearly between them and repeats). Frame 0 is
//! q + a·φ, frame PHASES/2 is q − a·φ.
//!
//! Each panel also holds frame 0 as a still picture (class `still`),
//! which the stylesheet shows instead of the animation in print and for
//! readers who ask for reduced motion.
//!
//! The amplitude a makes the largest displacement of a drawn point
//! [`ModeShapeSettings::amplitude_fraction`] of the assembly's size, as
//! the figures do ([`mode_amplitude`]); the report passes a fraction of
//! the bounding box's diagonal.

use super::svg::{fmt_px, View};
use crate::analysis::Mode;
use crate::output::figures::{assembly_geometry, mode_amplitude, ModeShapeSettings};
use crate::output::plot::Geometry;
use crate::system::System;
use std::fmt::Write;

/// Phases per period of an animation.
pub const PHASES: usize = 24;
/// Seconds one period of the animation lasts on screen.
pub const PERIOD_S: f64 = 2.0;

/// One mode's frames: the geometry at q + a·cos(2πk/PHASES)·φ, k = 0…PHASES−1.
#[derive(Debug, Clone)]
pub struct ModeFrames {
    pub amplitude: f64,
    pub frames: Vec<Geometry>,
}

/// The frames of `mode` linearized at `q` (see the module doc).
pub fn mode_frames(
    system: &System,
    q: &[f64],
    mode: &Mode,
    settings: &ModeShapeSettings,
) -> ModeFrames {
    let a = mode_amplitude(system, q, &mode.shape, settings);
    let frames = (0..PHASES)
        .map(|k| {
            let c = a * (2.0 * std::f64::consts::PI * k as f64 / PHASES as f64).cos();
            let deformed: Vec<f64> = q.iter().zip(&mode.shape).map(|(q, p)| q + c * p).collect();
            assembly_geometry(system, &deformed, settings.points_per_element)
        })
        .collect();
    ModeFrames {
        amplitude: a,
        frames,
    }
}

/// The SVG `points` of a polyline.
pub fn points_attr(view: &View, line: &[[f64; 2]]) -> String {
    let mut s = String::with_capacity(line.len() * 14);
    for (i, p) in line.iter().enumerate() {
        let (x, y) = view.px(*p);
        if i > 0 {
            s.push(' ');
        }
        let _ = write!(s, "{},{}", fmt_px(x), fmt_px(y));
    }
    s
}

/// Half the side of a body marker [px].
const BODY: f64 = 4.0;
/// Radius of a joint circle [px].
const JOINT: f64 = 3.0;

fn square(view: &View, p: [f64; 2]) -> String {
    let (x, y) = view.px(p);
    let c = [
        (x - BODY, y - BODY),
        (x + BODY, y - BODY),
        (x + BODY, y + BODY),
        (x - BODY, y + BODY),
    ];
    c.iter()
        .map(|(x, y)| format!("{},{}", fmt_px(*x), fmt_px(*y)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// `<animate>` of `attribute` through `values` (one per phase), repeating.
fn animate(attribute: &str, values: &[String]) -> String {
    let mut v = values.join(";");
    v.push(';');
    v.push_str(&values[0]);
    format!(
        "<animate attributeName=\"{attribute}\" dur=\"{PERIOD_S}s\" repeatCount=\"indefinite\" values=\"{v}\"/>"
    )
}

/// The geometry `g` drawn with class `class` (static).
pub fn geometry_svg(view: &View, g: &Geometry, class: &str) -> String {
    let mut s = format!("<g class=\"{class}\">");
    for line in &g.beams {
        let _ = write!(s, "<polyline points=\"{}\"/>", points_attr(view, line));
    }
    for b in &g.bodies {
        let _ = write!(
            s,
            "<polygon class=\"body\" points=\"{}\"/>",
            square(view, *b)
        );
    }
    for j in &g.joints {
        let (x, y) = view.px(*j);
        let _ = write!(
            s,
            "<circle class=\"joint\" cx=\"{}\" cy=\"{}\" r=\"{JOINT}\"/>",
            fmt_px(x),
            fmt_px(y)
        );
    }
    s.push_str("</g>");
    s
}

/// The animated deformed geometry of `frames` (class `anim`).
pub fn animated_svg(view: &View, frames: &ModeFrames) -> String {
    let first = &frames.frames[0];
    let mut s = String::from("<g class=\"deformed anim\">");
    for (i, line) in first.beams.iter().enumerate() {
        let values: Vec<String> = frames
            .frames
            .iter()
            .map(|f| points_attr(view, &f.beams[i]))
            .collect();
        let _ = write!(
            s,
            "<polyline points=\"{}\">{}</polyline>",
            points_attr(view, line),
            animate("points", &values)
        );
    }
    for (i, b) in first.bodies.iter().enumerate() {
        let values: Vec<String> = frames
            .frames
            .iter()
            .map(|f| square(view, f.bodies[i]))
            .collect();
        let _ = write!(
            s,
            "<polygon class=\"body\" points=\"{}\">{}</polygon>",
            square(view, *b),
            animate("points", &values)
        );
    }
    for (i, j) in first.joints.iter().enumerate() {
        let (x, y) = view.px(*j);
        let px: Vec<(f64, f64)> = frames.frames.iter().map(|f| view.px(f.joints[i])).collect();
        let cx: Vec<String> = px.iter().map(|p| fmt_px(p.0)).collect();
        let cy: Vec<String> = px.iter().map(|p| fmt_px(p.1)).collect();
        let _ = write!(
            s,
            "<circle class=\"joint\" cx=\"{}\" cy=\"{}\" r=\"{JOINT}\">{}{}</circle>",
            fmt_px(x),
            fmt_px(y),
            animate("cx", &cx),
            animate("cy", &cy)
        );
    }
    s.push_str("</g>");
    s
}

/// Every point of `g` [SI: m].
pub fn all_points(g: &Geometry) -> impl Iterator<Item = &[f64; 2]> {
    g.beams.iter().flatten().chain(&g.bodies).chain(&g.joints)
}
