//! A drawing backend that passes everything to the wrapped (bitmap) backend
//! except text, which it rasterises itself.
//!
//! Plotters' `ab_glyph` renderer drops each glyph's left side bearing and
//! snaps glyphs to truncated whole pixels, so PNG text comes out unevenly
//! spaced ("45 81 Hz"). Here glyphs are laid out with kerning at sub-pixel
//! positions, and the anchor box is plotters' own (advance width × size/1.24),
//! so layout computed by plotters still fits. SVG text is left to the viewer.

use ab_glyph::{point, Font, PxScale, ScaleFont};
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingBackend, DrawingErrorKind,
};

use super::font;

/// Wraps a backend; see the module documentation.
pub(super) struct TextFix<B>(pub B);

type Res<B> = Result<(), DrawingErrorKind<<B as DrawingBackend>::ErrorType>>;

impl<B: DrawingBackend> DrawingBackend for TextFix<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> Res<B> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> Res<B> {
        self.0.present()
    }
    fn draw_pixel(&mut self, point: BackendCoord, color: BackendColor) -> Res<B> {
        self.0.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Res<B> {
        self.0.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Res<B> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Res<B> {
        self.0.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Res<B> {
        self.0.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Res<B> {
        self.0.fill_polygon(vert, style)
    }
    fn blit_bitmap(&mut self, pos: BackendCoord, size: (u32, u32), src: &[u8]) -> Res<B> {
        self.0.blit_bitmap(pos, size, src)
    }
    fn estimate_text_size<S: BackendTextStyle>(
        &self,
        text: &str,
        style: &S,
    ) -> Result<(u32, u32), DrawingErrorKind<Self::ErrorType>> {
        self.0.estimate_text_size(text, style)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Res<B> {
        let color = style.color();
        let Some(face) = font::face() else {
            return self.0.draw_text(text, style, pos);
        };
        if color.alpha == 0.0 || text.is_empty() {
            return Ok(());
        }
        let size = style.size() as f32;
        let scale = PxScale::from(size);
        let scaled = face.as_scaled(scale);

        // Advance widths with kerning, as plotters measures the text.
        let mut ids = Vec::with_capacity(text.len());
        let mut caret = Vec::with_capacity(text.len());
        let mut x = 0f32;
        for c in text.chars() {
            let id = scaled.glyph_id(c);
            if let Some(&prev) = ids.last() {
                x += scaled.kern(prev, id);
            }
            ids.push(id);
            caret.push(x);
            x += scaled.h_advance(id);
        }
        let width = x;
        // Plotters' text box is size/1.24 high; centre the capitals in it.
        let box_h = size / 1.24;
        let cap = face
            .outline_glyph(scaled.scaled_glyph('H'))
            .map_or(0.63 * size, |g| g.px_bounds().height());
        let left = match style.anchor().h_pos {
            HPos::Left => 0.0,
            HPos::Center => -width / 2.0,
            HPos::Right => -width,
        };
        let top = match style.anchor().v_pos {
            VPos::Top => 0.0,
            VPos::Center => -box_h / 2.0,
            VPos::Bottom => -box_h,
        };
        let baseline = top + box_h / 2.0 + cap / 2.0;
        let transform = style.transform();
        for (id, cx) in ids.into_iter().zip(caret) {
            let glyph = id.with_scale_and_position(scale, point(left + cx, baseline));
            let Some(outline) = face.outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            let mut pixels = Vec::new();
            outline.draw(|gx, gy, coverage| {
                if coverage > 0.004 {
                    let (dx, dy) = (b.min.x as i32 + gx as i32, b.min.y as i32 + gy as i32);
                    pixels.push((transform.transform(dx, dy), coverage));
                }
            });
            for ((dx, dy), coverage) in pixels {
                let c = BackendColor {
                    alpha: color.alpha * f64::from(coverage.min(1.0)),
                    rgb: color.rgb,
                };
                self.0.draw_pixel((pos.0 + dx, pos.1 + dy), c)?;
            }
        }
        Ok(())
    }
}
