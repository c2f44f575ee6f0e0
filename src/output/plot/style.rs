//! Colours, text sizes and display scales shared by every figure kind.

use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, IntoFont, RGBAColor, RGBColor, TextStyle};

use super::font::FAMILY;
use super::size::PlotSize;

/// The Okabe–Ito colour-blind-safe palette, in the order series get them.
/// Reddish purple is kept out of it: it marks reference lines.
pub const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),  // blue
    RGBColor(213, 94, 0),   // vermillion
    RGBColor(0, 158, 115),  // bluish green
    RGBColor(230, 159, 0),  // orange
    RGBColor(86, 180, 233), // sky blue
    RGBColor(0, 0, 0),      // black
    RGBColor(240, 228, 66), // yellow (last: weak on white)
];

/// Reference lines (e.g. the measured 4600 Hz, a target, an O(hᵖ) slope):
/// Okabe–Ito reddish purple, always dashed.
pub const REFERENCE: RGBColor = RGBColor(204, 121, 167);
/// Undeformed geometry.
pub const UNDEFORMED: RGBColor = RGBColor(160, 160, 160);
/// Plain marker lines (e.g. computed eigenfrequencies).
pub const GUIDE: RGBColor = RGBColor(100, 100, 100);
/// Text, axes and unlabelled markers.
pub const INK: RGBColor = RGBColor(25, 25, 25);
/// Background of every figure.
pub const BACKGROUND: RGBColor = RGBColor(255, 255, 255);

/// The colour of palette entry `index` (wraps around).
pub fn palette(index: usize) -> RGBColor {
    PALETTE[index % PALETTE.len()]
}

pub(super) fn grid_bold() -> RGBAColor {
    INK.mix(0.16)
}

pub(super) fn grid_light() -> RGBAColor {
    INK.mix(0.06)
}

/// How values given in SI units are shown on an axis: `shown = value ×
/// factor`, with `unit` written into the axis label as `Label [unit]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Scale {
    pub factor: f64,
    pub unit: String,
}

impl Scale {
    pub fn new(factor: f64, unit: impl Into<String>) -> Self {
        Scale {
            factor,
            unit: unit.into(),
        }
    }
    /// Values shown as they are, in `unit`.
    pub fn unit(unit: impl Into<String>) -> Self {
        Scale::new(1.0, unit)
    }
    /// Dimensionless: no unit in the label.
    pub fn none() -> Self {
        Scale::new(1.0, "")
    }
    /// Seconds shown in milliseconds.
    pub fn ms() -> Self {
        Scale::new(1e3, "ms")
    }
    /// Hertz shown in kilohertz.
    pub fn khz() -> Self {
        Scale::new(1e-3, "kHz")
    }
    /// Hertz shown as hertz.
    pub fn hz() -> Self {
        Scale::unit("Hz")
    }
    /// Metres shown in millimetres.
    pub fn mm() -> Self {
        Scale::new(1e3, "mm")
    }
    /// The SI prefix (p … G, in steps of 10³) that shows `max_abs` (in
    /// `base_unit`) as a number in [1, 1000). `si("s", 0.004)` gives ms,
    /// `si("Hz", 12e3)` kHz. Zero or non-finite `max_abs` gives no prefix.
    pub fn si(base_unit: &str, max_abs: f64) -> Self {
        const PREFIXES: [(i32, &str); 8] = [
            (-12, "p"),
            (-9, "n"),
            (-6, "µ"),
            (-3, "m"),
            (0, ""),
            (3, "k"),
            (6, "M"),
            (9, "G"),
        ];
        let m = max_abs.abs();
        if !m.is_finite() || m == 0.0 {
            return Scale::unit(base_unit);
        }
        // Tiny tolerance so 1000 is shown as 1 k, not 1000.
        let exp = ((m.log10() + 1e-9).floor() as i32).div_euclid(3) * 3;
        let exp = exp.clamp(-12, 9);
        let prefix = PREFIXES.iter().find(|p| p.0 == exp).map_or("", |p| p.1);
        Scale::new(10f64.powi(-exp), format!("{prefix}{base_unit}"))
    }
    /// `value` in display units.
    pub fn apply(&self, value: f64) -> f64 {
        value * self.factor
    }
    /// `"name [unit]"`, or just `name` when there is no unit.
    pub fn label(&self, name: &str) -> String {
        if self.unit.is_empty() {
            name.to_string()
        } else {
            format!("{name} [{}]", self.unit)
        }
    }
}

impl Default for Scale {
    fn default() -> Self {
        Scale::none()
    }
}

/// Text sizes in pixels for a figure of a given size: 1200×800 is the
/// reference, larger or smaller figures scale the text with the square root
/// of the area (clamped so small figures stay readable).
#[derive(Debug, Clone, Copy)]
pub(super) struct TextSizes {
    pub title: f64,
    pub label: f64,
    pub tick: f64,
    pub legend: f64,
    pub note: f64,
}

impl TextSizes {
    pub fn for_size(size: PlotSize) -> Self {
        let k = ((size.width as f64 * size.height as f64) / (1200.0 * 800.0))
            .sqrt()
            .clamp(0.75, 3.0);
        TextSizes {
            title: 30.0 * k,
            label: 22.0 * k,
            tick: 18.0 * k,
            legend: 18.0 * k,
            note: 16.0 * k,
        }
    }
}

/// A text style with the bundled font.
pub(super) fn text(size: f64, colour: RGBColor, h: HPos, v: VPos) -> TextStyle<'static> {
    (FAMILY, size)
        .into_font()
        .color(&colour)
        .pos(Pos::new(h, v))
}

/// `v` with `sig` significant digits, trailing zeros removed.
pub fn format_sig(v: f64, sig: usize) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            format!("{v}")
        };
    }
    let mag = v.abs().log10().floor() as i32;
    if !(-4..6).contains(&mag) {
        return super::ticks::pretty_sci(v, sig);
    }
    let decimals = (sig as i32 - 1 - mag).max(0) as usize;
    super::ticks::trim_zeros(format!("{v:.decimals$}"))
}
