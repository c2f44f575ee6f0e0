//! Modal results as a table, a JSON document and CSV.

use crate::analysis::ModalResult;
use std::fmt::Write;

/// Readable table: index, frequency [Hz], kind, energy split.
pub fn modal_table(model_name: &str, r: &ModalResult) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {model_name}: {} coordinates, {} constraint equations, {} free",
        r.dofs, r.constraints, r.reduced_dofs
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
            "warning: the eigen-solve certifies the lowest frequencies only to {worst:.1e} (relative), \
             more than the {:.0e} a useful mesh reaches; the round-off of a very fine mesh limits them \
             (fewer elements give a tighter bound)",
            crate::analysis::modal::ACCURACY_WARNING
        );
    }
    s
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
