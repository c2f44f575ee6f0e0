//! Datasets 15 (nodes) and 55 (data at nodes: real normal modes).
//!
//! Dataset 15, one line per node, `4I10,3E13.5`: node label, definition and
//! displacement coordinate systems, colour, x, y, z.
//!
//! Dataset 55, normal modes with three translations per node:
//!
//! 1–5. `A80` ID lines.
//! 6. `6I10`: model type (1 structural), analysis type (2 normal mode),
//!    data characteristic (2: 3 DOF translation; 3: 6 DOF), specific data
//!    type (8 displacement), data type (2 real, 5 complex), values per node.
//! 7. `8I10`: number of integer values (2), of real values (4), load case,
//!    mode number.
//! 8. `4E13.5`: frequency [Hz], modal mass, viscous damping ratio,
//!    hysteretic damping ratio.
//! 9–10, per node: `I10` node label; `6E13.5` its values.

use std::fmt::Write;
use std::path::Path;

use super::{
    blocks_bytes, close_block, columns, fmt_e, id_line, open_block, parse_number, source_bytes,
    write_values,
};
use crate::measured::MeasuredError;

/// A node of dataset 15.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeCoordinates {
    pub label: i64,
    pub xyz: [f64; 3],
}

/// A real normal mode of dataset 55 (3 translations per node).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMode {
    /// ID lines 1–5, separated by newlines (missing ones are written as NONE;
    /// the reader keeps the first).
    pub id: String,
    pub mode_number: i64,
    pub frequency_hz: f64,
    pub modal_mass: f64,
    pub damping_ratio: f64,
    /// (node label, [x, y, z] translation).
    pub nodes: Vec<(i64, [f64; 3])>,
}

/// Appends dataset 15 with `nodes`.
pub fn write_nodes(out: &mut String, nodes: &[NodeCoordinates]) {
    open_block(out, 15);
    for n in nodes {
        let _ = write!(out, "{:>10}{:>10}{:>10}{:>10}", n.label, 0, 0, 11);
        for v in n.xyz {
            out.push_str(&fmt_e(v, 13, 5));
        }
        out.push('\n');
    }
    close_block(out);
}

/// Appends one dataset 55 with mode `m`.
pub fn write_mode(out: &mut String, m: &NormalMode) {
    open_block(out, 55);
    let ids: Vec<&str> = m.id.lines().take(5).collect();
    for k in 0..5 {
        id_line(out, ids.get(k).copied().unwrap_or("NONE"));
    }
    let _ = writeln!(
        out,
        "{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
        1, 2, 2, 8, 2, 3
    );
    let _ = writeln!(out, "{:>10}{:>10}{:>10}{:>10}", 2, 4, 1, m.mode_number);
    write_values(
        out,
        &[m.frequency_hz, m.modal_mass, m.damping_ratio, 0.0],
        4,
        13,
        5,
    );
    for (label, v) in &m.nodes {
        let _ = writeln!(out, "{label:>10}");
        write_values(out, v, 6, 13, 5);
    }
    close_block(out);
}

fn field_err(
    file: &Path,
    line: usize,
    dataset: u32,
    field: &'static str,
    value: &str,
) -> MeasuredError {
    MeasuredError::UffField {
        file: file.to_path_buf(),
        line,
        dataset,
        field,
        value: value.trim().to_string(),
    }
}

fn ints(
    file: &Path,
    line: usize,
    text: &str,
    field: &'static str,
) -> Result<Vec<i64>, MeasuredError> {
    text.split_whitespace()
        .map(|t| t.parse().map_err(|_| field_err(file, line, 55, field, t)))
        .collect()
}

fn reals(file: &Path, line: usize, dataset: u32, text: &str) -> Result<Vec<f64>, MeasuredError> {
    text.split_whitespace()
        .map(|t| parse_number(t).ok_or_else(|| field_err(file, line, dataset, "value", t)))
        .collect()
}

/// The nodes (15) and normal modes (55) of a UFF file; other datasets are
/// skipped.
pub fn read_modes(
    file: &Path,
    text: &str,
) -> Result<(Vec<NodeCoordinates>, Vec<NormalMode>), MeasuredError> {
    let mut nodes = Vec::new();
    let mut modes = Vec::new();
    for b in blocks_bytes(file, &source_bytes(file, text))? {
        match b.kind.as_str() {
            "15" => {
                for (k, l) in b.lines.iter().enumerate() {
                    let line = b.first_line + k;
                    let label = columns(l, 0, 10)
                        .parse()
                        .map_err(|_| field_err(file, line, 15, "node label", l))?;
                    let v = reals(file, line, 15, &l.chars().skip(40).collect::<String>())?;
                    if v.len() != 3 {
                        return Err(MeasuredError::UffTruncated {
                            file: file.to_path_buf(),
                            line,
                            dataset: 15,
                            found: v.len(),
                            expected: 3,
                        });
                    }
                    nodes.push(NodeCoordinates {
                        label,
                        xyz: [v[0], v[1], v[2]],
                    });
                }
            }
            "55" => {
                let lines: Vec<&str> = b.lines.iter().map(|l| l.as_ref()).collect();
                modes.push(parse_mode(file, b.first_line, &lines)?);
            }
            _ => {}
        }
    }
    Ok((nodes, modes))
}

fn parse_mode(file: &Path, first: usize, lines: &[&str]) -> Result<NormalMode, MeasuredError> {
    let truncated = |found: usize, expected: usize| MeasuredError::UffTruncated {
        file: file.to_path_buf(),
        line: first + lines.len(),
        dataset: 55,
        found,
        expected,
    };
    if lines.len() < 8 {
        return Err(truncated(lines.len(), 8));
    }
    let r6 = ints(file, first + 5, lines[5], "record 6")?;
    if r6.len() < 6 {
        return Err(field_err(file, first + 5, 55, "record 6", lines[5]));
    }
    if r6[1] != 2 || r6[4] != 2 {
        return Err(MeasuredError::UffUnsupported {
            file: file.to_path_buf(),
            line: first + 5,
            dataset: 55,
            field: "analysis type / data type",
            value: format!("{} / {}", r6[1], r6[4]),
            supported: "2 / 2 (real normal modes)",
        });
    }
    let per_node = usize::try_from(r6[5]).unwrap_or(0);
    let r7 = ints(file, first + 6, lines[6], "record 7")?;
    let mode_number = *r7
        .get(3)
        .ok_or_else(|| field_err(file, first + 6, 55, "mode number", lines[6]))?;
    let r8 = reals(file, first + 7, 55, lines[7])?;
    if r8.len() < 3 {
        return Err(field_err(
            file,
            first + 7,
            55,
            "frequency, modal mass, damping",
            lines[7],
        ));
    }
    let mut nodes = Vec::new();
    let mut k = 8;
    while k < lines.len() {
        let label: i64 = lines[k]
            .trim()
            .parse()
            .map_err(|_| field_err(file, first + k, 55, "node label", lines[k]))?;
        let mut v = Vec::new();
        k += 1;
        while v.len() < per_node && k < lines.len() {
            v.extend(reals(file, first + k, 55, lines[k])?);
            k += 1;
        }
        if v.len() != per_node || per_node < 3 {
            return Err(truncated(v.len(), per_node.max(3)));
        }
        nodes.push((label, [v[0], v[1], v[2]]));
    }
    Ok(NormalMode {
        id: lines[0].trim().to_string(),
        mode_number,
        frequency_hz: r8[0],
        modal_mass: r8[1],
        damping_ratio: r8[2],
        nodes,
    })
}
