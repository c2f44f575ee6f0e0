//! What a panel of a line figure shows, as plain data: named series,
//! guide lines and labelled markers, with their styles and the legend's
//! place. Shared by the panel drawing ([`super::line`]) and the
//! annotations ([`super::annotate`]).

/// A named curve. Non-finite values (and values ≤ 0 on log axes) leave gaps.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend text; an empty name keeps the series out of the legend.
    pub name: String,
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    pub style: SeriesStyle,
    /// Palette index; `None` takes the next colour of the figure.
    pub colour: Option<usize>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    #[default]
    Line,
    Points,
    LinePoints,
    /// Dashed, in the reference colour (e.g. an O(h⁴) slope).
    Reference,
}

/// A labelled straight line across a panel.
#[derive(Debug, Clone, PartialEq)]
pub struct Guide {
    /// Position, SI.
    pub at: f64,
    pub label: String,
    /// Reference lines (e.g. the measured frequency) are dashed in the
    /// reference colour; others are thin and grey.
    pub reference: bool,
}

/// A marker with a text label above it.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMarker {
    pub x: f64,
    pub y: f64,
    pub label: String,
    pub shape: MarkerShape,
    /// Palette index; `None` is the text colour.
    pub colour: Option<usize>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MarkerShape {
    #[default]
    Ring,
    Dot,
    Square,
    Triangle,
    Cross,
    /// Only the label (above the point).
    None,
}

/// Where a panel's legend goes (inside the plotting area).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// The corner that hides the least data.
    #[default]
    Auto,
    None,
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

impl Series {
    pub fn new(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>, style: SeriesStyle) -> Self {
        Series {
            name: name.into(),
            x,
            y,
            style,
            colour: None,
        }
    }
    pub fn line(name: impl Into<String>, x: Vec<f64>, y: Vec<f64>) -> Self {
        Series::new(name, x, y, SeriesStyle::Line)
    }
}

impl Guide {
    pub fn new(at: f64, label: impl Into<String>) -> Self {
        Guide {
            at,
            label: label.into(),
            reference: false,
        }
    }
    pub fn reference(at: f64, label: impl Into<String>) -> Self {
        Guide {
            reference: true,
            ..Guide::new(at, label)
        }
    }
}

impl PointMarker {
    pub fn new(x: f64, y: f64, label: impl Into<String>) -> Self {
        PointMarker {
            x,
            y,
            label: label.into(),
            shape: MarkerShape::Ring,
            colour: None,
        }
    }
}
