//! The size of a figure.

use super::error::PlotError;

/// Figure size in pixels (SVG user units).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlotSize {
    pub width: u32,
    pub height: u32,
}

impl Default for PlotSize {
    fn default() -> Self {
        PlotSize {
            width: 1200,
            height: 800,
        }
    }
}

impl PlotSize {
    pub(super) fn check(self) -> Result<(), PlotError> {
        let ok = |v: u32| (100..=16384).contains(&v);
        if ok(self.width) && ok(self.height) {
            Ok(())
        } else {
            Err(PlotError::InvalidSize {
                width: self.width,
                height: self.height,
            })
        }
    }
}
