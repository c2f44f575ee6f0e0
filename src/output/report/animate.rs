//! Animated mode shapes as plain SVG: no script, animated by SMIL.
//!
//! A mode φ linearized at q moves the assembly through q + a·cos(2πt/T)·φ.
//! The panel holds the undeformed geometry in grey and the deformed one in
//! colour, both from the one linear map of
//! [`crate::output::figures::assembly_motion`] (every drawn point p moved
//! to p + c·(∂p/∂q)·φ: beams, body outlines, point masses, springs, joints
//! and rails), drawn as [`crate::output::plot::scene`] describes. The
//! deformed geometry is given at [`PHASES`] phases t/T = k/PHASES of one
//! period; every element whose attributes differ between frames carries an
//! `<animate>` whose `values` are those frames (the browser interpolates
//! linearly between them and repeats), the ground's symbols stay still.
//! Frame 0 is q + a·φ, frame PHASES/2 is q − a·φ.
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
use crate::output::figures::{assembly_motion, mode_amplitude, ModeShapeSettings};
use crate::output::plot::scene::{self, SymbolPart, JOINT_RADIUS, MARKER_HALF};
use crate::output::plot::{Geometry, JointKind};
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
    let (at, rate) = assembly_motion(system, q, &mode.shape, settings.points_per_element);
    let frames = (0..PHASES)
        .map(|k| {
            at.moved(
                &rate,
                a * (2.0 * std::f64::consts::PI * k as f64 / PHASES as f64).cos(),
            )
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

/// One drawn SVG element: its tag, class, fixed attributes and the
/// attributes that can move between frames (in order).
#[derive(Debug, Clone, PartialEq)]
struct Prim {
    tag: &'static str,
    class: String,
    fixed: Vec<(&'static str, String)>,
    attrs: Vec<(&'static str, String)>,
}

/// The SVG `points` of pixel points.
fn pixel_points(pts: impl Iterator<Item = (f64, f64)>) -> String {
    pts.map(|(x, y)| format!("{},{}", fmt_px(x), fmt_px(y)))
        .collect::<Vec<_>>()
        .join(" ")
}

fn line(class: &str, points: String) -> Prim {
    Prim {
        tag: "polyline",
        class: class.to_string(),
        fixed: Vec::new(),
        attrs: vec![("points", points)],
    }
}

/// A square of half-side `h` px around pixel `c`.
fn square(c: (f64, f64), h: f64) -> String {
    let (x, y) = c;
    pixel_points(
        [
            (x - h, y - h),
            (x + h, y - h),
            (x + h, y + h),
            (x - h, y + h),
        ]
        .into_iter(),
    )
}

/// The elements that draw `g` (see [`crate::output::plot::scene`]), in an
/// order and number that depend only on the assembly, so that frames of
/// one motion pair up element by element.
fn prims(view: &View, g: &Geometry) -> Vec<Prim> {
    let mut v = Vec::new();
    for b in &g.beams {
        v.push(line("beam", points_attr(view, b)));
    }
    for s in &g.springs {
        v.push(line("spring", points_attr(view, s)));
    }
    for j in &g.joints {
        if let Some(rail) = j.rail {
            v.push(line("rail", points_attr(view, &rail)));
        }
    }
    for b in &g.bodies {
        v.push(match b.len() {
            1 => Prim {
                tag: "polygon",
                class: "body".into(),
                fixed: Vec::new(),
                attrs: vec![("points", square(view.px(b[0]), MARKER_HALF))],
            },
            2 => line("body link", points_attr(view, b)),
            _ => Prim {
                tag: "polygon",
                class: "body".into(),
                fixed: Vec::new(),
                attrs: vec![("points", points_attr(view, b))],
            },
        });
    }
    for m in &g.masses {
        v.push(Prim {
            tag: "polygon",
            class: "body mass".into(),
            fixed: Vec::new(),
            attrs: vec![("points", square(view.px(*m), MARKER_HALF))],
        });
    }
    for (i, j) in g.joints.iter().enumerate() {
        let (x, y) = view.px(j.at);
        for sym in scene::symbols(j) {
            let pts = pixel_points(sym.offsets.iter().map(|o| (x + o[0], y + o[1])));
            let class = match sym.part {
                SymbolPart::Hatch => "hatch",
                SymbolPart::Ground => "ground",
            };
            let tag = if sym.closed { "polygon" } else { "polyline" };
            v.push(Prim {
                tag,
                class: class.into(),
                fixed: Vec::new(),
                attrs: vec![("points", pts)],
            });
        }
        let kind = match j.kind {
            JointKind::Pin => "pin",
            JointKind::Weld => "weld",
            JointKind::Slider => "slider",
        };
        let support = if j.ground { " support" } else { "" };
        v.push(Prim {
            tag: "circle",
            class: format!("joint {kind}{support}"),
            fixed: vec![("data-joint", i.to_string()), ("r", fmt_px(JOINT_RADIUS))],
            attrs: vec![("cx", fmt_px(x)), ("cy", fmt_px(y))],
        });
    }
    v
}

/// `<animate>` of `attribute` through `values` (one per phase), repeating.
fn animate(attribute: &str, values: &[&str]) -> String {
    let mut v = values.join(";");
    v.push(';');
    v.push_str(values[0]);
    format!(
        "<animate attributeName=\"{attribute}\" dur=\"{PERIOD_S}s\" repeatCount=\"indefinite\" values=\"{v}\"/>"
    )
}

/// The elements of `frames` (one list per frame, paired by index), each
/// attribute that differs between frames animated through them.
fn write_prims(s: &mut String, frames: &[Vec<Prim>]) {
    for (i, p) in frames[0].iter().enumerate() {
        let _ = write!(s, "<{} class=\"{}\"", p.tag, p.class);
        for (name, value) in &p.fixed {
            let _ = write!(s, " {name}=\"{value}\"");
        }
        let mut moving = String::new();
        for (k, (name, value)) in p.attrs.iter().enumerate() {
            let _ = write!(s, " {name}=\"{value}\"");
            let values: Vec<&str> = frames.iter().map(|f| f[i].attrs[k].1.as_str()).collect();
            if values.iter().any(|v| *v != value) {
                moving.push_str(&animate(name, &values));
            }
        }
        if moving.is_empty() {
            s.push_str("/>");
        } else {
            let _ = write!(s, ">{moving}</{}>", p.tag);
        }
    }
}

/// The geometry `g` drawn with class `class` (static).
pub fn geometry_svg(view: &View, g: &Geometry, class: &str) -> String {
    let mut s = format!("<g class=\"{class}\">");
    write_prims(&mut s, &[prims(view, g)]);
    s.push_str("</g>");
    s
}

/// The animated deformed geometry of `frames` (class `anim`).
pub fn animated_svg(view: &View, frames: &ModeFrames) -> String {
    let mut s = String::from("<g class=\"deformed anim\">");
    let all: Vec<Vec<Prim>> = frames.frames.iter().map(|f| prims(view, f)).collect();
    write_prims(&mut s, &all);
    s.push_str("</g>");
    s
}

/// Every point of `g` [SI: m].
pub fn all_points(g: &Geometry) -> impl Iterator<Item = &[f64; 2]> {
    g.points()
}
