//! The MAC = (φᵀψ)²/(φᵀφ ψᵀψ) [–] of this model's elastic modes (rows)
//! against another mode set (columns), on the translations [m] at the
//! export nodes (beam nodes, body points): the other set is a model file
//! (its modes computed with the same settings) or UFF 55 modes matched by
//! node number.

use super::CommandError;
use crate::analysis::{modal_at_reference, ModalResult, ModalSettings, Mode};
use crate::measured::uff::d55::read_modes;
use crate::model::Model;
use crate::output::modal_uff::{export_nodes, translations};
use crate::results::modal::MacTable;
use crate::signal::mac::mac;
use crate::System;
use std::path::Path;

fn elastic(r: &ModalResult) -> Vec<&Mode> {
    r.modes.iter().filter(|m| !m.kind.is_zero()).collect()
}

/// The elastic modes' frequencies [Hz] and translations at `system`'s
/// export nodes.
fn elastic_translations(system: &System, r: &ModalResult) -> (Vec<f64>, Vec<Vec<f64>>) {
    let nodes = export_nodes(system);
    let e = elastic(r);
    (
        e.iter().map(|m| m.frequency_hz).collect(),
        e.iter().map(|m| translations(&nodes, &m.shape)).collect(),
    )
}

/// The MAC of `a`'s elastic modes (rows, of `sa`) against `b`'s (columns,
/// of `sb`); `other` names `b`'s source in the error when the two have
/// different export nodes.
pub fn mac_of(
    (sa, a): (&System, &ModalResult),
    (sb, b): (&System, &ModalResult),
    other: &Path,
) -> Result<MacTable, CommandError> {
    let (na, nb) = (export_nodes(sa).len(), export_nodes(sb).len());
    if na != nb {
        return Err(CommandError::OtherModes {
            other: other.to_path_buf(),
            why: format!("{nb} export nodes, this model has {na}: the MAC needs the same nodes"),
        });
    }
    let (rows, mine) = elastic_translations(sa, a);
    let (cols, theirs) = elastic_translations(sb, b);
    Ok(table(rows, cols, &mac(&mine, &theirs)))
}

fn table(rows_hz: Vec<f64>, columns_hz: Vec<f64>, m: &nalgebra::DMatrix<f64>) -> MacTable {
    MacTable {
        rows_hz,
        columns_hz,
        matrix: m
            .row_iter()
            .map(|r| r.iter().copied().collect::<Vec<f64>>())
            .collect(),
    }
}

/// The MAC of `result`'s elastic modes (of `system`) against the mode set
/// in `other`: a model file (`.json`, its modes computed with `settings`)
/// or a UFF file with datasets 55.
pub fn mac_against(
    system: &System,
    result: &ModalResult,
    other: &Path,
    settings: &ModalSettings,
) -> Result<MacTable, CommandError> {
    let is_json = other
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"));
    if is_json {
        let model = Model::from_file(other)?;
        let sys = System::new(&model);
        let r = modal_at_reference(&sys, settings)
            .map_err(|e| CommandError::analysis(other.display().to_string(), e))?;
        return mac_of((system, result), (&sys, &r), other);
    }
    let nodes = export_nodes(system);
    let (rows, mine) = elastic_translations(system, result);
    // Bytes, decoded leniently: a file may also hold binary 58b records.
    let bytes = std::fs::read(other).map_err(|io| CommandError::OtherModes {
        other: other.to_path_buf(),
        why: format!("cannot read the file: {io}"),
    })?;
    let text = String::from_utf8_lossy(&bytes);
    let (_, modes) = read_modes(other, &text)?;
    if modes.is_empty() {
        return Err(CommandError::OtherModes {
            other: other.to_path_buf(),
            why: String::from("no UFF dataset 55 (normal modes) in the file"),
        });
    }
    let mut shapes = Vec::new();
    for m in &modes {
        let mut v = Vec::with_capacity(2 * nodes.len());
        for n in &nodes {
            let (_, t) = m.nodes.iter().find(|(l, _)| *l == n.label).ok_or_else(|| {
                CommandError::OtherModes {
                    other: other.to_path_buf(),
                    why: format!(
                        "mode {} has no node {} ({})",
                        m.mode_number, n.label, n.name
                    ),
                }
            })?;
            v.extend([t[0], t[1]]);
        }
        shapes.push(v);
    }
    let cols = modes.iter().map(|m| m.frequency_hz).collect();
    Ok(table(rows, cols, &mac(&mine, &shapes)))
}

/// The MAC as the command line's table.
pub fn mac_table(t: &MacTable) -> String {
    use std::fmt::Write;
    let mut s = String::from("MAC (rows: this model, columns: the other set) [Hz]\n");
    let _ = write!(s, "{:>10}", "");
    for c in &t.columns_hz {
        let _ = write!(s, " {c:>9.1}");
    }
    s.push('\n');
    for (r, row) in t.rows_hz.iter().zip(&t.matrix) {
        let _ = write!(s, "{r:>10.1}");
        for v in row {
            let _ = write!(s, " {v:>9.3}");
        }
        s.push('\n');
    }
    s
}
