//! The figure of a mesh-convergence study
//! ([`crate::analysis::convergence`]): the relative errors of the first
//! bending frequencies against the number of elements per beam on log-log
//! axes, with the n⁻⁴ = O(h⁴) reference slope of Hermite cubic elements.
//! With the finest mesh as reference its own (zero) error is left out.

use crate::analysis::convergence::{ConvergenceData, ReferenceKind};
use crate::output::plot::{convergence_figure as preset_figure, Convergence, LineFigure};

/// Relative error against elements per beam, log-log, one series per
/// bending mode (named with its reference frequency) and the O(h⁴) slope.
pub fn convergence_figure(data: &ConvergenceData) -> LineFigure {
    let against = match data.reference_kind {
        ReferenceKind::Exact => String::from("exact frequencies"),
        ReferenceKind::FinestMesh => format!(
            "the {}-element mesh",
            data.elements.last().copied().unwrap_or_default()
        ),
    };
    let errors = data
        .errors
        .iter()
        .zip(&data.reference_hz)
        .enumerate()
        .map(|(k, (e, f))| (format!("bending {}: {:.1} Hz", k + 1, f), e.clone()))
        .collect();
    preset_figure(&Convergence {
        title: format!("Mesh convergence of {} (reference: {against})", data.model),
        elements: data.elements.iter().map(|&n| n as f64).collect(),
        errors,
        order: 4,
    })
}
