//! Line figures stacked top to bottom in one image, each with its own x
//! axis and title (e.g. a whole record over a zoom on its first
//! milliseconds). The height is shared in proportion to the parts' panel
//! counts; the text keeps the whole image's sizes.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::error::PlotError;
use super::frame::PanelLayout;
use super::line::LineFigure;
use super::size::PlotSize;
use super::style::TextSizes;

/// Line figures drawn one below the other.
#[derive(Debug, Clone, Default)]
pub struct StackedFigure {
    /// Top to bottom.
    pub parts: Vec<LineFigure>,
}

impl StackedFigure {
    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        size: PlotSize,
    ) -> Result<Vec<PanelLayout>, PlotError> {
        if self.parts.is_empty() {
            return Err(PlotError::EmptyData {
                what: "stacked figure has no part".into(),
            });
        }
        let sizes = TextSizes::for_size(size);
        let weights: Vec<u32> = self
            .parts
            .iter()
            .map(|p| p.panels.len().max(1) as u32)
            .collect();
        let total: u32 = weights.iter().sum();
        let mut heights: Vec<u32> = weights.iter().map(|w| size.height * w / total).collect();
        let used: u32 = heights.iter().sum();
        if let Some(last) = heights.last_mut() {
            *last += size.height - used;
        }
        let mut breaks = Vec::with_capacity(heights.len());
        let mut y = 0i32;
        for h in &heights[..heights.len() - 1] {
            y += *h as i32;
            breaks.push(y);
        }
        let areas = root.split_by_breakpoints::<i32, i32, _, _>([], breaks);
        let mut layouts = Vec::new();
        for ((part, area), h) in self.parts.iter().zip(&areas).zip(&heights) {
            let part_size = PlotSize {
                width: size.width,
                height: *h,
            };
            layouts.extend(part.draw_sized(area, part_size, sizes)?);
        }
        Ok(layouts)
    }
}
