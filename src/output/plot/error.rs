//! The plot module's error type.

use std::path::PathBuf;

use plotters::drawing::DrawingAreaErrorKind;

use crate::output::files::WriteError;

/// Why a figure could not be made or written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    #[error("{path}: unknown plot format (use a .svg or .png file name)", path = path.display())]
    UnknownExtension { path: PathBuf },
    #[error("{path}: cannot write the plot: {io}", path = path.display())]
    Io { path: PathBuf, io: std::io::Error },
    /// The drawing library failed; its message.
    #[error("drawing failed: {0}")]
    Backend(String),
    #[error("PNG encoding failed: {0}")]
    PngEncode(String),
    #[error("nothing to plot: {what}")]
    EmptyData { what: String },
    #[error("series `{series}` has {x_len} x values but {y_len} y values")]
    LengthMismatch {
        series: String,
        x_len: usize,
        y_len: usize,
    },
    #[error("plot size {width}×{height} is outside 100…16384 pixels")]
    InvalidSize { width: u32, height: u32 },
    #[error("the embedded font could not be loaded")]
    Font,
}

impl From<WriteError> for PlotError {
    fn from(WriteError { path, io }: WriteError) -> Self {
        PlotError::Io { path, io }
    }
}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for PlotError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        PlotError::Backend(e.to_string())
    }
}
