//! Time records from CSV files.
//!
//! Layout: one header row of column names, then one row per sample; the
//! first column is time, strictly increasing on a uniform grid, in seconds
//! unless its name gives milliseconds or microseconds ([`time_scale`]:
//! `time_ms`, `t [ms]`, `time (us)`, `t_µs`, …; a 51.2 kHz record whose
//! `time_ms` column was read as seconds would be a 51.2 Hz one).
//! The force and response columns are chosen by header name or 1-based
//! index. By default the force is the one column whose name holds `force`
//! (any case; as in what `impulse --csv` writes: `time_s`, the sensor,
//! `force_n`), else column 2 (several such columns are an error); the
//! response is the first column after time that is not the force. Header
//! names may be quoted. The time column, or one column for both, is
//! refused as a channel. Cells are separated by commas,
//! semicolons or tabs (whichever the header uses), or by blanks; lines
//! starting with `#` and blank lines are skipped.
//!
//! Checks, each reported with the file and line: every row has as many
//! cells as the header; every cell is a finite number; time increases; every
//! time lies within 2 % of a step of the uniform grid t₀ + i·Δt, with
//! Δt = (t_last − t₀)/(n − 1) (printed times carry rounding, a dropped or
//! repeated sample does not pass).

use std::path::Path;

use super::{Channel, MeasuredError, TimeRecord, MIN_SAMPLES};

/// Largest allowed distance of a time stamp from the uniform grid, in steps.
pub const GRID_TOLERANCE: f64 = 0.02;
/// Largest allowed deviation of one step from the median step (printed
/// times with few digits jitter; a missing sample doubles a step).
pub const STEP_TOLERANCE: f64 = 0.5;

fn split(line: &str, sep: Option<char>) -> Vec<&str> {
    match sep {
        Some(c) => line.split(c).map(str::trim).collect(),
        None => line.split_whitespace().collect(),
    }
}

/// A header cell without the quotes a spreadsheet or R's `write.csv` puts
/// around it.
fn unquote(name: &str) -> &str {
    let t = name.trim();
    t.strip_prefix('"')
        .and_then(|u| u.strip_suffix('"'))
        .unwrap_or(t)
}

fn separator(header: &str) -> Option<char> {
    [',', ';', '\t'].into_iter().find(|c| header.contains(*c))
}

/// The 0-based column of `channel` (or of `default`, 1-based).
fn column(
    file: &Path,
    line: usize,
    names: &[&str],
    channel: Option<&Channel>,
    default: usize,
) -> Result<usize, MeasuredError> {
    let index = match channel {
        Some(Channel::Name(n)) => {
            return names
                .iter()
                .position(|h| h == n)
                .ok_or_else(|| MeasuredError::MissingColumn {
                    file: file.to_path_buf(),
                    line,
                    name: n.clone(),
                    columns: names.join(", "),
                })
        }
        Some(Channel::Index(i)) => *i,
        None => default,
    };
    if index == 0 || index > names.len() {
        return Err(MeasuredError::ColumnOutOfRange {
            file: file.to_path_buf(),
            line,
            index,
            count: names.len(),
        });
    }
    Ok(index - 1)
}

/// The default force column, 1-based: the one column after time whose name
/// holds `force` (any case) and is not a contact's (`contact_…`: a
/// reaction the structure makes, as `transient --csv` names it, not the
/// excitation), else 2; several such columns are an error.
fn default_force(file: &Path, line: usize, names: &[&str]) -> Result<usize, MeasuredError> {
    let named: Vec<usize> = names
        .iter()
        .enumerate()
        .skip(1)
        .filter(|(_, h)| {
            let h = h.to_lowercase();
            h.contains("force") && !h.starts_with("contact_")
        })
        .map(|(i, _)| i + 1)
        .collect();
    match named.as_slice() {
        [] => Ok(2),
        [one] => Ok(*one),
        _ => Err(MeasuredError::AmbiguousForce {
            file: file.to_path_buf(),
            line,
            columns: named
                .iter()
                .map(|i| format!("`{}`", names[i - 1]))
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}

/// Refuses the time column as a channel, and one column as both.
fn check_roles(
    file: &Path,
    line: usize,
    names: &[&str],
    (fi, ri): (usize, usize),
) -> Result<(), MeasuredError> {
    let misuse = |index: usize, role, why| MeasuredError::ColumnMisused {
        file: file.to_path_buf(),
        line,
        index: index + 1,
        name: names[index].to_string(),
        role,
        why,
    };
    if fi == 0 {
        return Err(misuse(fi, "force", "the first column is time"));
    }
    if ri == 0 {
        return Err(misuse(ri, "response", "the first column is time"));
    }
    if fi == ri {
        return Err(misuse(ri, "response", "it is the force column too"));
    }
    Ok(())
}

/// Seconds per unit of the time column named `name`: 1e-3 when its name
/// ends in a millisecond unit (`ms`, after `_`, ` `, `[`, `(` or `/`, a
/// closing bracket allowed), 1e-6 for microseconds (`us`, `µs`, `μs`), else
/// 1 (seconds, with or without `_s`).
pub fn time_scale(name: &str) -> f64 {
    let lower = name.trim().to_lowercase();
    let unit = lower.trim_end_matches([']', ')']);
    let ends = |u: &str| {
        unit.strip_suffix(u).is_some_and(|head| {
            head.ends_with(['_', ' ', '[', '(', '/', '-']) || head.ends_with("in ")
        })
    };
    if ends("ms") {
        1e-3
    } else if ends("us") || ends("µs") || ends("μs") {
        1e-6
    } else {
        1.0
    }
}

/// Parses CSV text (see the module doc) into a time record.
pub fn parse_csv(
    file: &Path,
    text: &str,
    channels: &super::Channels,
) -> Result<TimeRecord, MeasuredError> {
    let mut rows = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = rows.next().ok_or_else(|| MeasuredError::Empty {
        file: file.to_path_buf(),
    })?;
    let sep = separator(header);
    let names: Vec<&str> = split(header, sep).into_iter().map(unquote).collect();
    let default = match channels.force {
        Some(_) => 2,
        None => default_force(file, header_line, &names)?,
    };
    let fi = column(file, header_line, &names, channels.force.as_ref(), default)?;
    let ri = column(
        file,
        header_line,
        &names,
        channels.response.as_ref(),
        if fi == 1 { 3 } else { 2 },
    )?;
    check_roles(file, header_line, &names, (fi, ri))?;
    let seconds = time_scale(names[0]);
    let (mut t, mut force, mut response, mut lines) = (vec![], vec![], vec![], vec![]);
    for (line, row) in rows {
        let cells = split(row, sep);
        if cells.len() != names.len() {
            return Err(MeasuredError::Ragged {
                file: file.to_path_buf(),
                line,
                found: cells.len(),
                expected: names.len(),
            });
        }
        let cell = |c: usize| -> Result<f64, MeasuredError> {
            let value = cells[c];
            let v: f64 = value.parse().map_err(|_| MeasuredError::NotNumeric {
                file: file.to_path_buf(),
                line,
                column: c + 1,
                value: value.to_string(),
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(MeasuredError::NotFinite {
                    file: file.to_path_buf(),
                    line,
                    column: c + 1,
                    value: value.to_string(),
                })
            }
        };
        // Every cell must be a number, used or not: a stray text cell means
        // the columns are not what the header says.
        for c in 0..cells.len() {
            cell(c)?;
        }
        t.push(cell(0)? * seconds);
        force.push(cell(fi)?);
        response.push(cell(ri)?);
        lines.push(line);
    }
    if t.len() < MIN_SAMPLES {
        return Err(MeasuredError::TooFewSamples {
            file: file.to_path_buf(),
            count: t.len(),
            min: MIN_SAMPLES,
        });
    }
    let sample_rate_hz = uniform_rate(file, &t, &lines)?;
    Ok(TimeRecord {
        file: file.to_path_buf(),
        sample_rate_hz,
        force,
        response,
        force_label: names[fi].to_string(),
        response_label: names[ri].to_string(),
        lines,
    })
}

/// The sample rate of strictly increasing, uniformly spaced times.
pub fn uniform_rate(file: &Path, t: &[f64], lines: &[usize]) -> Result<f64, MeasuredError> {
    for i in 1..t.len() {
        if t[i] <= t[i - 1] {
            return Err(MeasuredError::TimeNotIncreasing {
                file: file.to_path_buf(),
                line: lines[i],
                time: t[i],
                previous: t[i - 1],
            });
        }
    }
    let n = t.len();
    // A dropped or repeated sample: one step far from the typical one.
    let mut steps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    steps.sort_by(f64::total_cmp);
    let typical = steps[steps.len() / 2];
    for i in 1..n {
        let offset = (t[i] - t[i - 1]) / typical - 1.0;
        if offset.abs() > STEP_TOLERANCE {
            return Err(MeasuredError::UnevenSampling {
                file: file.to_path_buf(),
                line: lines[i],
                time: t[i],
                step: typical,
                offset,
            });
        }
    }
    // A slow drift: the grid from the first and last times.
    let step = (t[n - 1] - t[0]) / (n - 1) as f64;
    for i in 1..n {
        let offset = (t[i] - t[0]) / step - i as f64;
        if offset.abs() > GRID_TOLERANCE {
            return Err(MeasuredError::UnevenSampling {
                file: file.to_path_buf(),
                line: lines[i],
                time: t[i],
                step,
                offset,
            });
        }
    }
    Ok(1.0 / step)
}
