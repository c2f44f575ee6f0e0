//! Universal File Format (UFF / UNV) datasets, ASCII: 15 (nodes), 55 (data
//! at nodes: normal modes) and 58 (function at a nodal DOF: time records,
//! FRFs, coherence), read and written.
//!
//! A file is a sequence of blocks, each opened and closed by a line holding
//! `-1` (right-aligned in six columns), the first line inside naming the
//! dataset type. Records inside are Fortran fixed-format lines; the layouts
//! follow the public UFF description as pyuff (ladisk/pyuff) reads and
//! writes them, field by field in [`d58`] and [`d55`]. Numbers are read by
//! their fixed columns where names may hold blanks (record 6 of dataset 58,
//! the axis labels) and as blank-separated fields elsewhere, which also
//! accepts three-digit exponents (`1.0E+000`) and Fortran `D` exponents.
//!
//! Datasets that describe the test but carry no data this tool uses (151
//! header, 164 units, 18 and 2420 coordinate systems, 82 trace lines, 2411
//! and 2412 mesh) are skipped; any other type is an error naming its line.
//! The binary variant 58b is reported as unsupported.

pub mod d55;
pub mod d58;

use std::fmt::Write;
use std::path::Path;

use super::{Channel, Channels, MeasuredError, MeasuredFrf, Measurement, TimeRecord};

pub use d55::{NodeCoordinates, NormalMode};
pub use d58::{Function, FunctionType, Ordinate, SpecDataType};

/// Dataset types that are skipped when reading.
pub const SKIPPED: [&str; 7] = ["151", "164", "18", "2420", "82", "2411", "2412"];

/// One block of a UFF file.
#[derive(Debug, Clone)]
pub struct Block<'a> {
    /// The dataset type as written (`58`, `58b`, …).
    pub kind: String,
    /// Line number (1-based) of the line after the type line.
    pub first_line: usize,
    /// The lines between the type line and the closing `-1`.
    pub lines: Vec<&'a str>,
}

/// Splits UFF text into blocks.
pub fn blocks<'a>(file: &Path, text: &'a str) -> Result<Vec<Block<'a>>, MeasuredError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim().is_empty() {
            i += 1;
            continue;
        }
        if lines[i].trim() != "-1" {
            return Err(MeasuredError::UffField {
                file: file.to_path_buf(),
                line: i + 1,
                dataset: 0,
                field: "block delimiter (-1)",
                value: lines[i].trim().to_string(),
            });
        }
        let type_line = i + 1;
        let kind = lines
            .get(type_line)
            .and_then(|l| l.split_whitespace().next())
            .ok_or(MeasuredError::UffUnterminated {
                file: file.to_path_buf(),
                line: i + 1,
            })?
            .to_string();
        let end = (type_line + 1..lines.len())
            .find(|&j| lines[j].trim() == "-1")
            .ok_or(MeasuredError::UffUnterminated {
                file: file.to_path_buf(),
                line: type_line + 1,
            })?;
        out.push(Block {
            kind,
            first_line: type_line + 2,
            lines: lines[type_line + 1..end].to_vec(),
        });
        i = end + 1;
    }
    Ok(out)
}

/// Characters `start..start + len` of a line (by character, so that a
/// non-ASCII label does not shift or split the fields), trimmed.
pub fn columns(line: &str, start: usize, len: usize) -> String {
    line.chars()
        .skip(start)
        .take(len)
        .collect::<String>()
        .trim()
        .to_string()
}

/// A number in Fortran notation (`1.5E+00`, `1.5D+00`, `1.5e-005`).
pub fn parse_number(s: &str) -> Option<f64> {
    let s = s.trim();
    s.parse::<f64>()
        .ok()
        .or_else(|| s.replace(['D', 'd'], "E").parse().ok())
}

/// `v` as C's `%W.Pe`: mantissa with P decimals, `e`, sign, at least two
/// exponent digits, right-aligned in W characters.
pub fn fmt_e(v: f64, width: usize, precision: usize) -> String {
    let s = format!("{v:.precision$e}");
    let (mantissa, exp) = s.split_once('e').expect("Rust's {:e} has an exponent");
    let exp: i32 = exp.parse().expect("Rust's exponent is an integer");
    let sign = if exp < 0 { '-' } else { '+' };
    let body = format!("{mantissa}e{sign}{:02}", exp.abs());
    format!("{body:>width$}")
}

/// Writes `values` in lines of `per_line` fields of `%W.Pe`.
pub fn write_values(
    out: &mut String,
    values: &[f64],
    per_line: usize,
    width: usize,
    precision: usize,
) {
    for chunk in values.chunks(per_line) {
        for v in chunk {
            out.push_str(&fmt_e(*v, width, precision));
        }
        out.push('\n');
    }
}

/// An 80-column text line (ID lines), `NONE` when empty.
pub fn id_line(out: &mut String, text: &str) {
    let t: String = text.chars().take(80).collect();
    let t = if t.trim().is_empty() {
        "NONE".to_string()
    } else {
        t
    };
    let _ = writeln!(out, "{t:<80}");
}

/// Opens a block of type `kind`.
pub fn open_block(out: &mut String, kind: u32) {
    let _ = writeln!(out, "{:>6}", -1);
    let _ = writeln!(out, "{kind:>6}");
}

/// Closes a block.
pub fn close_block(out: &mut String) {
    let _ = writeln!(out, "{:>6}", -1);
}

/// Every dataset-58 function of a file (other types checked: skipped or an
/// error).
pub fn read_functions(file: &Path, text: &str) -> Result<Vec<Function>, MeasuredError> {
    let mut out = Vec::new();
    for b in blocks(file, text)? {
        match b.kind.as_str() {
            "58" => out.push(d58::parse(file, &b)?),
            "58b" => {
                return Err(MeasuredError::UffUnsupported {
                    file: file.to_path_buf(),
                    line: b.first_line - 1,
                    dataset: 58,
                    field: "format",
                    value: "58b (binary)".into(),
                    supported: "ASCII dataset 58; export it as ASCII",
                })
            }
            "15" | "55" => {}
            k if SKIPPED.contains(&k) => {}
            k => {
                return Err(MeasuredError::UnknownUffType {
                    file: file.to_path_buf(),
                    line: b.first_line - 1,
                    value: k.to_string(),
                })
            }
        }
    }
    Ok(out)
}

fn matches(f: &Function, index: usize, channel: &Channel) -> bool {
    match channel {
        Channel::Index(i) => *i == index + 1,
        Channel::Name(n) => f.id[0].trim() == n || f.ordinate_label.trim() == n,
    }
}

/// The measurement a UFF file holds: a force and a response time record
/// (function type 1; the force is the record whose ordinate is a force,
/// type 13, unless `--force` picks one), or an FRF (type 4) with its
/// coherence (type 6) if present.
pub fn measurement_from_uff(
    file: &Path,
    text: &str,
    channels: &Channels,
) -> Result<Measurement, MeasuredError> {
    let functions = read_functions(file, text)?;
    if functions.is_empty() {
        return Err(MeasuredError::NoChannel {
            file: file.to_path_buf(),
            what: "the file holds no dataset 58",
        });
    }
    let pick = |ch: &Option<Channel>, default: &dyn Fn(&Function) -> bool| {
        functions
            .iter()
            .enumerate()
            .find(|(i, f)| match ch {
                Some(c) => matches(f, *i, c),
                None => default(f),
            })
            .map(|(_, f)| f)
    };
    let is_frf = |f: &Function| f.function_type == FunctionType::Frf;
    if functions.iter().any(is_frf) && channels.force.is_none() {
        let h = pick(&channels.response, &is_frf).ok_or(MeasuredError::NoChannel {
            file: file.to_path_buf(),
            what: "no FRF record matches --response",
        })?;
        let coherence = functions
            .iter()
            .find(|f| f.function_type == FunctionType::Coherence)
            .map(|c| c.ordinate.real_parts());
        return Ok(Measurement::Frf(MeasuredFrf {
            file: file.to_path_buf(),
            frequency_hz: h.abscissa(),
            h: h.ordinate.complex(),
            coherence,
        }));
    }
    let is_force = |f: &Function| f.ordinate_type == SpecDataType::FORCE;
    let force = pick(&channels.force, &is_force).ok_or(MeasuredError::NoChannel {
        file: file.to_path_buf(),
        what: "no force record (ordinate type 13) in the file; choose one with --force",
    })?;
    let response = pick(&channels.response, &|f: &Function| !std::ptr::eq(f, force)).ok_or(
        MeasuredError::NoChannel {
            file: file.to_path_buf(),
            what: "no response record besides the force; choose one with --response",
        },
    )?;
    if force.ordinate.len() != response.ordinate.len() || force.dx != response.dx {
        return Err(MeasuredError::Mismatch {
            file: file.to_path_buf(),
            first: file.to_path_buf(),
            what: "the response record's sampling (samples × step)",
            value: response.ordinate.len() as f64 * response.dx,
            expected: force.ordinate.len() as f64 * force.dx,
        });
    }
    if force.dx <= 0.0 || !force.even {
        return Err(MeasuredError::UffUnsupported {
            file: file.to_path_buf(),
            line: force.data_line,
            dataset: 58,
            field: "abscissa spacing",
            value: format!("uneven or dx = {:e}", force.dx),
            supported: "even spacing with dx > 0",
        });
    }
    let lines = force.lines.clone();
    Ok(Measurement::Time(TimeRecord {
        file: file.to_path_buf(),
        sample_rate_hz: 1.0 / force.dx,
        force: force.ordinate.real_parts(),
        response: response.ordinate.real_parts(),
        force_label: force.id[0].trim().to_string(),
        response_label: response.id[0].trim().to_string(),
        lines,
    }))
}
