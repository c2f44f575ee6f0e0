//! Modal results as a table, a JSON document and CSV.

use crate::analysis::ModalResult;
use crate::model::{Model, UnitWarning};
use std::fmt::Write;

/// Readable table: index, frequency [Hz], kind, energy split.
pub fn modal_table(model: &Model, r: &ModalResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: {} coordinates, {} constraint equations, {} free",
        model.name, r.dofs, r.constraints, r.reduced_dofs
    );
    if !r.redundant_constraints.is_empty() {
        let _ = writeln!(
            s,
            "redundant constraints: {}",
            r.redundant_constraints.join(", ")
        );
    }
    let _ = writeln!(
        s,
        "{} zero-frequency modes: {} rigid, {} mechanism",
        r.rigid_modes,
        r.rigid_modes - r.mechanism_modes,
        r.mechanism_modes
    );
    let _ = writeln!(
        s,
        "{:>5}  {:>14}  {:<8}  {:>7}  {:>7}  {:>7}  {:>11}  {:>7}",
        "mode", "frequency [Hz]", "kind", "bend %", "axial %", "sprg %", "error bound", "shear %"
    );
    for m in &r.modes {
        if m.kind.is_zero() {
            let _ = writeln!(s, "{:>5}  {:>14}  {:<8}", m.index, "0", m.kind);
        } else {
            let bound = m
                .error_bound
                .map_or(String::from("-"), |b| format!("{b:.1e}"));
            let shear = m
                .shear_estimate
                .map_or(String::from("-"), |e| format!("{:+.2}", 100.0 * e));
            let _ = writeln!(
                s,
                "{:>5}  {:>14.3}  {:<8}  {:>7.2}  {:>7.2}  {:>7.2}  {:>11}  {:>7}",
                m.index,
                m.frequency_hz,
                m.kind,
                100.0 * m.energy.bending,
                100.0 * m.energy.axial,
                100.0 * m.energy.springs,
                bound,
                shear
            );
        }
    }
    if let Some(worst) = r.accuracy_warning() {
        let _ = writeln!(
            s,
            "warning: {}",
            accuracy_warning_text(worst, &model.size_warnings())
        );
    }
    s
}

/// The warning of a modal result whose lowest frequencies the eigen-solve
/// certifies only to `worst` (relative), above
/// [`crate::analysis::modal::ACCURACY_WARNING`], with its cause: the parts
/// of `sizes` ([`Model::size_warnings`]) when the model has parts whose
/// sizes disagree by orders of magnitude (their matrices then span many
/// more orders than a consistent model's), else the round-off of a very
/// fine mesh.
pub fn accuracy_warning_text(worst: f64, sizes: &[UnitWarning]) -> String {
    let head = format!(
        "the eigen-solve certifies the lowest frequencies only to {worst:.1e} (relative), \
         more than the {:.0e} a useful mesh reaches; ",
        crate::analysis::modal::ACCURACY_WARNING
    );
    let parts: Vec<&str> = sizes
        .iter()
        .filter_map(|w| match w {
            UnitWarning::Size { part, .. } | UnitWarning::LeverArm { part, .. } => {
                Some(part.as_str())
            }
            _ => None,
        })
        .collect();
    if parts.is_empty() {
        format!(
            "{head}the round-off of a very fine mesh limits them \
             (fewer elements give a tighter bound)"
        )
    } else {
        format!(
            "{head}parts whose sizes disagree by orders of magnitude limit them: {} \
             (over {} times the size or lever arm of a part joined to {}; is a length in other \
             units than metres?)",
            parts.join(", "),
            crate::model::sanity::MAX_SIZE_RATIO,
            if parts.len() == 1 { "it" } else { "them" }
        )
    }
}

/// CSV: one row per mode.
pub fn modal_csv(r: &ModalResult) -> String {
    let mut s = String::from("mode,frequency_hz,eigenvalue_rad2_s2,kind,bending_fraction,axial_fraction,spring_fraction,error_bound\n");
    for m in &r.modes {
        let _ = writeln!(
            s,
            "{},{:.10e},{:.10e},{},{:.6},{:.6},{:.6},{}",
            m.index,
            m.frequency_hz,
            m.eigenvalue,
            m.kind,
            m.energy.bending,
            m.energy.axial,
            m.energy.springs,
            m.error_bound.map_or(String::new(), |b| format!("{b:.3e}"))
        );
    }
    s
}
