//! Universal File Format (UFF / UNV) datasets 15 (nodes), 55 (data at
//! nodes: normal modes) and 58 (function at a nodal DOF: time records, FRFs,
//! coherence): ASCII read and written, binary 58b read.
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
//! Dataset 58b, the binary variant of 58 that acquisition software writes,
//! is read as well ([`d58b`] has its layout): its block holds arbitrary
//! bytes (newlines among them), so files are split into blocks as bytes,
//! the binary part taken by the byte count its type line announces.
//!
//! Every other dataset is skipped by its framing alone, whatever its type:
//! an ASCII block ends at its closing `-1` line, a binary one (a type
//! written `NNb`, as 58b) after the byte count its type line announces.
//! Real exports hold many the tool has no use for: Simcenter Testlab writes
//! a 1858 (qualifiers) beside each 58, results hold 2414, and headers,
//! units, coordinate systems, trace lines and meshes (151, 164, 18, 2420,
//! 82, 2411, 2412) describe the test. A reader lists what it skipped
//! ([`Skipped`], [`skipped_note`]) so that the user sees it; a dataset it
//! uses but cannot parse is an error naming its line.

pub mod d55;
pub mod d58;
pub mod d58b;

use std::borrow::Cow;
use std::fmt::Write;
use std::path::Path;

use super::{
    Channel, Channels, MeasuredError, MeasuredFrf, Measurement, ResponseQuantity, TimeRecord,
};

pub use d55::{NodeCoordinates, NormalMode};
pub use d58::{Function, FunctionType, Ordinate, SpecDataType};
pub use d58b::Binary;

/// One block of a UFF file.
#[derive(Debug, Clone)]
pub struct Block<'a> {
    /// The dataset type as written (`58`, `58b`, …; `58B` is read as `58b`).
    pub kind: String,
    /// Line number (1-based) of the line after the type line.
    pub first_line: usize,
    /// The text lines between the type line and the closing `-1` (for
    /// 58b, the ASCII lines before the binary data), decoded as UTF-8 with
    /// invalid bytes replaced.
    pub lines: Vec<Cow<'a, str>>,
    /// Dataset 58b: the binary data after the ASCII lines.
    pub binary: Option<Binary<'a>>,
}

/// A dataset a reader skipped: its type as written (`1858`, `2414b`) and
/// the line (1-based) of its type line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Skipped {
    pub kind: String,
    pub line: usize,
}

/// The note that lists the datasets of `file` a reader skipped, by type in
/// the order met, with their count and first line: `a.uff: 3 UFF datasets
/// this tool does not use were skipped: 151 (line 1), 1858 ×2 (first at
/// line 40)`; `None` when none was.
pub fn skipped_note(file: &Path, skipped: &[Skipped]) -> Option<String> {
    let mut kinds: Vec<(&str, usize, usize)> = Vec::new();
    for s in skipped {
        match kinds.iter_mut().find(|(k, _, _)| *k == s.kind) {
            Some(k) => k.1 += 1,
            None => kinds.push((&s.kind, 1, s.line)),
        }
    }
    let list: Vec<String> = kinds
        .iter()
        .map(|(kind, n, line)| match n {
            1 => format!("{kind} (line {line})"),
            n => format!("{kind} ×{n} (first at line {line})"),
        })
        .collect();
    match skipped.len() {
        0 => None,
        n => Some(format!(
            "{}: {n} UFF dataset{} this tool does not use {} skipped: {}",
            file.display(),
            if n == 1 { "" } else { "s" },
            if n == 1 { "was" } else { "were" },
            list.join(", ")
        )),
    }
}

/// Whether a dataset type is binary: digits and a `b` (`58b`, `2414B`).
fn is_binary_kind(kind: &str) -> bool {
    kind.strip_suffix(['b', 'B'])
        .is_some_and(|n| !n.is_empty() && n.bytes().all(|c| c.is_ascii_digit()))
}

/// Splits UFF text into blocks (as [`blocks_bytes`]; binary 58b data must
/// be intact in `text`, see [`source_bytes`]).
pub fn blocks<'a>(file: &Path, text: &'a str) -> Result<Vec<Block<'a>>, MeasuredError> {
    blocks_bytes(file, text.as_bytes())
}

/// A read position in a file's bytes, with the 1-based number of the line
/// it stands on (lines counted at every `\n`, inside binary data too).
struct Cursor<'a> {
    data: &'a [u8],
    pos: usize,
    line: usize,
}

impl<'a> Cursor<'a> {
    /// The next line without its `\n` or `\r\n`, and its number.
    fn next_line(&mut self) -> Option<(usize, &'a [u8])> {
        if self.pos >= self.data.len() {
            return None;
        }
        let rest = &self.data[self.pos..];
        let (line, advance) = match rest.iter().position(|&c| c == b'\n') {
            Some(k) => (&rest[..k], k + 1),
            None => (rest, rest.len()),
        };
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        let no = self.line;
        self.pos += advance;
        self.line += 1;
        Some((no, line))
    }

    /// Skips `n` raw bytes (at most to the end), counting their newlines.
    fn skip(&mut self, n: usize) -> &'a [u8] {
        let end = self.pos.saturating_add(n).min(self.data.len());
        let bytes = &self.data[self.pos..end];
        self.line += bytes.iter().filter(|&&c| c == b'\n').count();
        self.pos = end;
        bytes
    }
}

fn is_delimiter(line: &[u8]) -> bool {
    line.trim_ascii() == b"-1"
}

/// Splits the bytes of a UFF file into blocks. ASCII blocks end at the
/// first `-1` line; a binary block (58b, or any type `NNb`) holds, after
/// its type line, the number of ASCII lines and then exactly the number of
/// binary bytes its type line announces (whatever bytes they are, newlines
/// included), followed by the closing `-1` (after at most one line end,
/// which some writers add). Only a 58b keeps its binary part
/// ([`Block::binary`]); another binary type is framed to be skipped.
pub fn blocks_bytes<'a>(file: &Path, data: &'a [u8]) -> Result<Vec<Block<'a>>, MeasuredError> {
    let mut cur = Cursor {
        data,
        pos: 0,
        line: 1,
    };
    let mut out = Vec::new();
    let mut records = 0;
    while let Some((open, line)) = cur.next_line() {
        if line.trim_ascii().is_empty() {
            continue;
        }
        if !is_delimiter(line) {
            return Err(MeasuredError::UffField {
                file: file.to_path_buf(),
                line: open,
                dataset: 0,
                field: "block delimiter (-1)",
                value: String::from_utf8_lossy(line.trim_ascii()).into_owned(),
            });
        }
        let unterminated = |line| MeasuredError::UffUnterminated {
            file: file.to_path_buf(),
            line,
        };
        let (type_no, type_line) = cur.next_line().ok_or_else(|| unterminated(open))?;
        let type_text = String::from_utf8_lossy(type_line);
        let mut kind = type_text
            .split_whitespace()
            .next()
            .ok_or_else(|| unterminated(open))?
            .to_string();
        let is_58b = kind.eq_ignore_ascii_case("58b");
        if kind == "58" || is_58b {
            records += 1;
        }
        if !is_binary_kind(&kind) {
            let mut lines = Vec::new();
            loop {
                let (_, l) = cur.next_line().ok_or_else(|| unterminated(type_no))?;
                if is_delimiter(l) {
                    break;
                }
                lines.push(String::from_utf8_lossy(l));
            }
            out.push(Block {
                kind,
                first_line: type_no + 1,
                lines,
                binary: None,
            });
            continue;
        }
        // A binary block: its ASCII lines, then exactly its announced
        // bytes, then the closing `-1`. A 58b's header is read in full; of
        // another binary type only the framing (a dataset skipped).
        let (header, ascii_lines, byte_count) = if is_58b {
            kind = "58b".into();
            let h = d58b::BinaryHeader::parse(file, type_no, &type_text)?;
            (Some(h), h.ascii_lines, h.bytes)
        } else {
            let (a, b) = d58b::framing(file, type_no, &type_text, &kind)?;
            (None, a, b)
        };
        let mut lines = Vec::with_capacity(ascii_lines.min(64));
        for k in 0..ascii_lines {
            let (_, l) = cur.next_line().ok_or_else(|| MeasuredError::UffTruncated {
                file: file.to_path_buf(),
                line: cur.line,
                dataset: dataset_number(&kind),
                found: k,
                expected: ascii_lines,
            })?;
            lines.push(String::from_utf8_lossy(l));
        }
        let start = cur.pos;
        let bytes = cur.skip(byte_count);
        let closed = bytes.len() == byte_count
            && match cur.next_line() {
                // One line end after the data, then the `-1`.
                Some((_, [])) => cur.next_line().is_some_and(|(_, l)| is_delimiter(l)),
                Some((_, l)) => is_delimiter(l),
                None => false,
            };
        if !closed {
            let (found, until) = d58b::binary_extent(&data[start..]);
            return Err(match header {
                Some(_) => MeasuredError::UffBinaryLength {
                    file: file.to_path_buf(),
                    line: type_no,
                    record: records,
                    found,
                    until,
                    expected: byte_count,
                },
                None => MeasuredError::UffSkippedBinaryLength {
                    file: file.to_path_buf(),
                    line: type_no,
                    kind,
                    found,
                    until,
                    expected: byte_count,
                },
            });
        }
        out.push(Block {
            kind,
            first_line: type_no + 1,
            lines,
            binary: header.map(|header| Binary {
                header,
                bytes,
                line: type_no,
                record: records,
            }),
        });
    }
    Ok(out)
}

/// The number of a dataset type (`2414b` → 2414) for messages; 0 when it
/// has none.
fn dataset_number(kind: &str) -> u32 {
    kind.trim_end_matches(['b', 'B']).parse().unwrap_or(0)
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

/// The bytes to split for `text` read from `file`. Callers that read a
/// file as text decode it lossily (`String::from_utf8_lossy`), which turns
/// the invalid UTF-8 of binary 58b data into U+FFFD and changes its byte
/// count. When `text` holds U+FFFD and `file` still holds the bytes it was
/// decoded from, those bytes are returned; otherwise `text` itself.
pub fn source_bytes<'t>(file: &Path, text: &'t str) -> Cow<'t, [u8]> {
    if text.contains(char::REPLACEMENT_CHARACTER) {
        if let Ok(bytes) = std::fs::read(file) {
            if String::from_utf8_lossy(&bytes) == text {
                return Cow::Owned(bytes);
            }
        }
    }
    Cow::Borrowed(text.as_bytes())
}

/// Every dataset-58 function (ASCII 58 and binary 58b) of a file, other
/// types checked: skipped or an error. `text` is the file read as text; a
/// file with binary 58b records is read again as bytes (see
/// [`source_bytes`]).
pub fn read_functions(file: &Path, text: &str) -> Result<Vec<Function>, MeasuredError> {
    read_functions_bytes(file, &source_bytes(file, text))
}

/// Every dataset-58 function (ASCII 58 and binary 58b) in the bytes of a
/// UFF file; the datasets skipped are not reported ([`read_functions_noted`]
/// does).
pub fn read_functions_bytes(file: &Path, data: &[u8]) -> Result<Vec<Function>, MeasuredError> {
    Ok(read_functions_noted(file, data)?.0)
}

/// Every dataset-58 function (ASCII 58 and binary 58b) in the bytes of a
/// UFF file, and every other dataset, skipped by its framing (module doc).
pub fn read_functions_noted(
    file: &Path,
    data: &[u8],
) -> Result<(Vec<Function>, Vec<Skipped>), MeasuredError> {
    let mut out = Vec::new();
    let mut skipped = Vec::new();
    for b in blocks_bytes(file, data)? {
        match (b.kind.as_str(), &b.binary) {
            (_, Some(bin)) => out.push(d58b::parse(file, &b, bin)?),
            ("58", None) => out.push(d58::parse(file, &b)?),
            (kind, None) => skipped.push(Skipped {
                kind: kind.to_string(),
                line: b.first_line - 1,
            }),
        }
    }
    Ok((out, skipped))
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
/// coherence (type 6) if present; with the note of the datasets skipped
/// ([`skipped_note`]).
pub fn measurement_from_uff(
    file: &Path,
    bytes: &[u8],
    channels: &Channels,
) -> Result<(Measurement, Option<String>), MeasuredError> {
    let (functions, skipped) = read_functions_noted(file, bytes)?;
    let note = skipped_note(file, &skipped);
    measurement_of(file, &functions, channels).map(|m| (m, note))
}

/// The measurement [`measurement_from_uff`] picks from `functions`.
fn measurement_of(
    file: &Path,
    functions: &[Function],
    channels: &Channels,
) -> Result<Measurement, MeasuredError> {
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
            what: "no FRF record matches the response channel",
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
            quantity: ResponseQuantity::ALL
                .into_iter()
                .find(|q| q.uff_type() == h.ordinate_type),
        }));
    }
    let is_force = |f: &Function| f.ordinate_type == SpecDataType::FORCE;
    let force = pick(&channels.force, &is_force).ok_or(MeasuredError::NoChannel {
        file: file.to_path_buf(),
        what: "no force record (ordinate type 13) in the file; name the force channel",
    })?;
    let response = pick(&channels.response, &|f: &Function| !std::ptr::eq(f, force)).ok_or(
        MeasuredError::NoChannel {
            file: file.to_path_buf(),
            what: "no response record besides the force; name the response channel",
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
        response_label: labelled(response),
        lines,
    }))
}

/// A response record's name, with what it measures when its ordinate type
/// says and its name does not: `tip (velocity)`.
fn labelled(response: &Function) -> String {
    let id = response.id[0].trim();
    let typed = ResponseQuantity::ALL
        .into_iter()
        .find(|q| q.uff_type() == response.ordinate_type);
    match typed {
        Some(q) if ResponseQuantity::named(id) != Some(q) => format!("{id} ({})", q.name()),
        _ => id.to_string(),
    }
}
