//! The bundled font.
//!
//! Plotters is built with its `ab_glyph` text renderer, which knows no system
//! fonts: every family name used in a figure must be registered first. We
//! embed DejaVu Sans (see `assets/fonts/LICENSE`) and register it once, under
//! [`FAMILY`], for every style (bold and italic fall back to the regular face).

use ab_glyph::FontRef;
use plotters::style::{register_font, FontStyle};
use std::sync::OnceLock;

use super::error::PlotError;

/// The family name every text element uses. SVG output names it too, so an
/// SVG viewer substitutes its own sans-serif face.
pub(super) const FAMILY: &str = "sans-serif";

/// DejaVu Sans, embedded. The path goes through `CARGO_MANIFEST_DIR` so this
/// module can live at any depth of the crate's module tree.
static DEJAVU_SANS: &[u8] = include_bytes!(concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/assets/fonts/DejaVuSans.ttf"
));

static REGISTERED: OnceLock<bool> = OnceLock::new();

/// Registers the bundled font (idempotent, thread-safe).
pub(super) fn ensure_registered() -> Result<(), PlotError> {
    let ok =
        *REGISTERED.get_or_init(|| register_font(FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok());
    if ok {
        Ok(())
    } else {
        Err(PlotError::Font)
    }
}

static FACE: OnceLock<Option<FontRef<'static>>> = OnceLock::new();

/// The bundled face, for rasterising PNG text ourselves (see `pngtext`).
pub(super) fn face() -> Option<&'static FontRef<'static>> {
    FACE.get_or_init(|| FontRef::try_from_slice(DEJAVU_SANS).ok())
        .as_ref()
}
