//! Modal results as a table, a JSON document and CSV.
//!
//! A negative eigenvalue ω² < 0 is printed as its imaginary frequency
//! √|ω²|/2π followed by `i` (`190.623i`), never as 0 Hz; its kind says
//! whether the state is an unstable equilibrium (`unstable`) or no
//! equilibrium at all (`negative`). A state that is not an equilibrium is
//! said above the table, with the unbalanced force and where it acts.

use crate::analysis::modal::EquilibriumCheck;
use crate::analysis::prestress::PrestressedModal;
use crate::analysis::{ModalResult, Mode};
use crate::model::{Model, UnitWarning};
use std::fmt::Write;

/// A mode's frequency cell: `0` for zero modes, `f` to 3 decimals, or the
/// imaginary frequency `√|ω²|/2π` with an `i` for a negative eigenvalue.
pub fn frequency_cell(m: &Mode) -> String {
    // Below 1 Hz three decimals would print a slow elastic mode (a
    // 2.99e-6 Hz bending mode of a beam typed 1000× too long) as `0.000`
    // beside "0 zero-frequency modes": four significant digits instead.
    let cell = |f: f64| {
        if f >= 1.0 {
            format!("{f:.3}")
        } else {
            format!("{f:.3e}")
        }
    };
    if m.kind.is_zero() {
        String::from("0")
    } else if m.frequency_hz < 0.0 {
        format!("{}i", cell(-m.frequency_hz))
    } else {
        cell(m.frequency_hz)
    }
}

/// The lines that say whether the state is an equilibrium (nothing when it
/// is one and nothing is unstable) and what the `i` frequencies mean.
fn equilibrium_lines(s: &mut String, state: &str, e: &EquilibriumCheck, r: &ModalResult) {
    if let Some(w) = e.warning(state) {
        let _ = writeln!(s, "{w}");
    }
    if r.unstable_modes > 0 {
        let _ = writeln!(
            s,
            "{state} is an unstable equilibrium: {} mode(s) with negative eigenvalue (kind `unstable`)",
            r.unstable_modes
        );
    }
    if r.unstable_modes + r.negative_modes > 0 {
        let _ = writeln!(
            s,
            "i: imaginary frequency √|ω²|/2π of a negative eigenvalue ω² (a motion growing as e^(√|ω²| t), not a vibration)"
        );
    }
}

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
    equilibrium_lines(&mut s, "the reference configuration", &r.equilibrium, r);
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
                "{:>5}  {:>14}  {:<8}  {:>7.2}  {:>7.2}  {:>7.2}  {:>11}  {:>7}",
                m.index,
                frequency_cell(m),
                m.kind,
                100.0 * m.energy.bending,
                100.0 * m.energy.axial,
                100.0 * m.energy.springs,
                bound,
                shear
            );
        }
    }
    s
}

/// The warning of a modal result whose lowest frequencies the eigen-solve
/// certifies only to `worst` (relative), above
/// [`crate::analysis::modal::ACCURACY_WARNING`], with its cause, from the
/// model's unit warnings ([`Model::unit_warnings`]): the parts whose sizes
/// disagree by orders of magnitude (their matrices then span many more
/// orders than a consistent model's), else the values that look like
/// other units, else the round-off of the stiffest entries (a very fine
/// mesh, or stiff parts on soft springs).
pub fn accuracy_warning_text(worst: f64, units: &[UnitWarning]) -> String {
    let head = format!(
        "the eigen-solve certifies the lowest frequencies only to {worst:.1e} (relative), \
         more than the {:.0e} a useful mesh reaches; ",
        crate::analysis::modal::ACCURACY_WARNING
    );
    let parts: Vec<&str> = units
        .iter()
        .filter_map(|w| match w {
            UnitWarning::Size { part, .. } | UnitWarning::LeverArm { part, .. } => {
                Some(part.as_str())
            }
            UnitWarning::SpringLength { path, .. } => Some(path.as_str()),
            _ => None,
        })
        .collect();
    let values: Vec<&str> = units
        .iter()
        .filter_map(|w| match w {
            UnitWarning::Slender { path, .. }
            | UnitWarning::Young { path, .. }
            | UnitWarning::Density { path, .. }
            | UnitWarning::WaveSpeed { path, .. } => Some(path.as_str()),
            _ => None,
        })
        .collect();
    if !parts.is_empty() {
        format!(
            "{head}parts whose sizes disagree by orders of magnitude limit them: {} \
             (over {} times the size or lever arm of a part joined to {}; is a length in other \
             units than metres?)",
            parts.join(", "),
            crate::model::sanity::MAX_SIZE_RATIO,
            if parts.len() == 1 { "it" } else { "them" }
        )
    } else if !values.is_empty() {
        format!(
            "{head}values that look like other units than SI limit them: {} (see the unit \
             warning{})",
            values.join(", "),
            if values.len() == 1 { "" } else { "s" }
        )
    } else {
        format!(
            "{head}the round-off of the stiffest entries limits them: a very fine mesh, or a \
             stiff part on soft springs, makes the stiffness span many orders (fewer elements \
             give a tighter bound)"
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

/// Frequencies at the equilibrium beside the unstressed mode of the same
/// shape: its number, the mass-weighted MAC and the shift (module doc of
/// [`crate::analysis::prestress`]); a mode without a partner says so.
pub fn prestress_table(model_name: &str, r: &PrestressedModal) -> String {
    let mut s = String::new();
    let eq = &r.equilibrium;
    let _ = writeln!(
        s,
        "model {model_name}: modes at the static equilibrium (load factor {}, {} load steps, {} Newton iterations, unbalanced force {:.2e} N)",
        eq.load_scale, eq.steps, eq.iterations, eq.residual
    );
    let _ = writeln!(s, "found: {}", eq.branch);
    let _ = writeln!(
        s,
        "{} zero-frequency modes at the equilibrium, {} at the reference",
        r.prestressed.rigid_modes, r.reference.rigid_modes
    );
    let p = &r.prestressed;
    equilibrium_lines(&mut s, "the static equilibrium", &p.equilibrium, p);
    if let Some(w) = r
        .reference
        .equilibrium
        .warning("the reference configuration (the unstressed modes' state)")
    {
        let _ = writeln!(s, "{w}");
    }
    let _ = writeln!(
        s,
        "unstressed: the reference mode of the same shape (mass-weighted MAC ≥ {}), not of the same rank",
        crate::analysis::prestress::PAIR_MAC
    );
    let _ = writeln!(
        s,
        "{:>5}  {:>17}  {:<9}  {:>16}  {:>5}  {:>6}  {:>9}",
        "mode", "pre-stressed [Hz]", "kind", "unstressed [Hz]", "(no.)", "MAC", "shift [%]"
    );
    for (i, m) in p.modes.iter().enumerate() {
        let best = r.matches.get(i).copied().flatten();
        let (f0, no) = match r.partner(i) {
            Some(u) => (frequency_cell(u), format!("({})", u.index)),
            None => (String::from("unpaired"), String::from("-")),
        };
        let mac = best.map_or_else(|| "-".to_string(), |b| format!("{:.3}", b.mac));
        let shift = r
            .shift_percent(i)
            .map_or_else(|| "-".to_string(), |v| format!("{v:+.4}"));
        let _ = writeln!(
            s,
            "{:>5}  {:>17}  {:<9}  {:>16}  {:>5}  {:>6}  {:>9}",
            i + 1,
            frequency_cell(m),
            m.kind.to_string(),
            f0,
            no,
            mac,
            shift
        );
    }
    s
}
