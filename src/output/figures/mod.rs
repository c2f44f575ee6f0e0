//! Figures of analysis results: the maps from results to the plain data of
//! [`super::plot`], and writing them to SVG or PNG files.
//!
//! * [`modal`] — mode shapes of a modal analysis: the undeformed assembly
//!   in grey and each mode's deformed shape q₀ + a·φ in colour, beams drawn
//!   as their curved ANCF centre lines r(ξ) = S(ξ)·e.
//! * [`convergence`] — a mesh-convergence study
//!   ([`crate::analysis::convergence`]: the first bending frequencies
//!   against the number of elements, their relative errors against an
//!   analytic (Euler–Bernoulli) or finest-mesh reference) as the log-log
//!   error figure with the O(h⁴) slope of Hermite cubics.
//! * [`impulse`] — the impulse experiment: sensor signal over the force
//!   pulse against time, and the amplitude spectrum with identified peaks,
//!   eigenfrequency guides and the measured reference frequency.
//!
//! * [`mac`] — the MAC matrix between two mode sets as a labelled heat map.
//! * [`sweep`] — a parameter study: tracked frequencies (Campbell style) or
//!   the quantity against one parameter, a heat map over two.
//!
//! All data are SI (m, Hz); figures show lengths in millimetres.

pub mod assembly;
pub mod convergence;
pub mod impulse;
pub mod mac;
pub mod modal;
pub mod sweep;
pub mod switch_off;
mod write;

pub use assembly::{assembly_geometry, assembly_motion};
pub use convergence::convergence_figure;
pub use impulse::{response_figure, response_path, spectrum_figure, write_impulse_figures};
pub use mac::mac_figure;
pub use modal::{mode_amplitude, mode_shape_figure, mode_shape_figure_with, ModeShapeSettings};
pub use write::{write_figure, write_mode_shapes};
