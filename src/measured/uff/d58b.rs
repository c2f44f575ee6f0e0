//! Dataset 58b: dataset 58 with its data in binary (UC-SDRL's "Binary 58",
//! written by Siemens Testlab, B&K, LMS and others).
//!
//! Layout, as pyuff (ladisk/pyuff) documents and reads it:
//!
//! ```text
//!     -1
//!     58b     1     2          11        2000     0     0           0           0
//! (11 ASCII lines: records 1–11 of dataset 58, as in the ASCII dataset)
//! (2000 binary bytes: record 12)
//!     -1
//! ```
//!
//! The type line is `I6,A1,I6,I6,I12,I12,I6,I6,I12,I12`: 58, `b`, byte
//! ordering (1 little endian, 2 big endian), floating-point format (2 IEEE
//! 754; 1 DEC VMS and 3 IBM 370 are not read), number of ASCII lines that
//! follow (11), number of binary bytes after them, four unused fields.
//!
//! The binary bytes start right after the line end of the 11th ASCII line
//! and hold the values of record 12 in the ASCII order (uneven abscissa:
//! x, then the ordinate; complex: re, im), each of the precision of the
//! ordinate data type of record 7: 4-byte floats for types 2 (real) and 5
//! (complex), 8-byte doubles for 4 and 6, in the declared byte order. The
//! byte count must be exactly points × values per point × value size. The
//! closing `-1` follows the last byte; one line end before it is accepted
//! (pyuff's `fix_58b` repairs files that have one).
//!
//! Binary values have no line of their own: messages about a point name the
//! line of its record's `58b` type line.

use std::path::Path;

use super::{d58, Block};
use crate::measured::MeasuredError;

/// The byte order a 58b type line declares.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ByteOrder {
    Little,
    Big,
}

/// The binary fields of a 58b type line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BinaryHeader {
    pub order: ByteOrder,
    /// Number of ASCII lines between the type line and the binary data.
    pub ascii_lines: usize,
    /// Number of binary bytes after the ASCII lines.
    pub bytes: usize,
}

/// The binary part of a 58b block.
#[derive(Debug, Clone)]
pub struct Binary<'a> {
    pub header: BinaryHeader,
    /// The binary data (exactly `header.bytes` bytes).
    pub bytes: &'a [u8],
    /// Line (1-based) of the `58b` type line.
    pub line: usize,
    /// Number (1-based) of this record among the file's dataset-58
    /// records (ASCII and binary), as `--force N` / `--response N` count.
    pub record: usize,
}

impl BinaryHeader {
    /// Reads the fields after `58b` in the type line `text` (line `line`).
    pub fn parse(file: &Path, line: usize, text: &str) -> Result<BinaryHeader, MeasuredError> {
        let tokens: Vec<&str> = text.split_whitespace().collect();
        let field = |k: usize, name: &'static str| -> Result<i64, MeasuredError> {
            tokens
                .get(k)
                .and_then(|t| t.parse().ok())
                .ok_or(MeasuredError::UffField {
                    file: file.to_path_buf(),
                    line,
                    dataset: 58,
                    field: name,
                    value: text.trim().to_string(),
                })
        };
        let unsupported = |field: &'static str, value: i64, supported: &'static str| {
            MeasuredError::UffUnsupported {
                file: file.to_path_buf(),
                line,
                dataset: 58,
                field,
                value: value.to_string(),
                supported,
            }
        };
        let order = match field(1, "58b byte ordering")? {
            1 => ByteOrder::Little,
            2 => ByteOrder::Big,
            v => {
                return Err(unsupported(
                    "58b byte ordering",
                    v,
                    "1 little, 2 big endian",
                ))
            }
        };
        let fp = field(2, "58b floating-point format")?;
        if fp != 2 {
            return Err(unsupported("58b floating-point format", fp, "2, IEEE 754"));
        }
        let ascii_lines = field(3, "58b number of ASCII lines")?;
        if ascii_lines != 11 {
            return Err(unsupported(
                "58b number of ASCII lines",
                ascii_lines,
                "11, records 1-11 of dataset 58",
            ));
        }
        let bytes = field(4, "58b number of bytes")?;
        let bytes = usize::try_from(bytes).map_err(|_| MeasuredError::UffField {
            file: file.to_path_buf(),
            line,
            dataset: 58,
            field: "58b number of bytes",
            value: bytes.to_string(),
        })?;
        Ok(BinaryHeader {
            order,
            ascii_lines: 11,
            bytes,
        })
    }
}

/// The framing of a binary dataset of another type than 58b (`kind`, read
/// only to be skipped): the number of ASCII lines after its type line and
/// of binary bytes after them, fields 4 and 5 of the type line as in 58b.
pub fn framing(
    file: &Path,
    line: usize,
    text: &str,
    kind: &str,
) -> Result<(usize, usize), MeasuredError> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    let field = |k: usize, name: &'static str| {
        tokens
            .get(k)
            .and_then(|t| t.parse::<usize>().ok())
            .ok_or(MeasuredError::UffField {
                file: file.to_path_buf(),
                line,
                dataset: kind.trim_end_matches(['b', 'B']).parse().unwrap_or(0),
                field: name,
                value: text.trim().to_string(),
            })
    };
    Ok((
        field(3, "binary dataset's number of ASCII lines")?,
        field(4, "binary dataset's number of bytes")?,
    ))
}

/// For a binary block that is not closed where its header says: the number
/// of bytes from the block's start `rest` to the next `    -1` line (one
/// line end before it not counted) and a name for that end, or all of
/// `rest` and "the end of the file".
pub fn binary_extent(rest: &[u8]) -> (usize, &'static str) {
    const MARK: &[u8] = b"    -1";
    let closing = (0..rest.len().saturating_sub(MARK.len() - 1)).find(|&k| {
        rest[k..].starts_with(MARK)
            && matches!(rest.get(k + MARK.len()), None | Some(b'\r' | b'\n'))
    });
    match closing {
        Some(k) => {
            let body = &rest[..k];
            let body = body.strip_suffix(b"\n").unwrap_or(body);
            let body = body.strip_suffix(b"\r").unwrap_or(body);
            (body.len(), "the closing `    -1`")
        }
        None => (rest.len(), "the end of the file"),
    }
}

/// Decodes `bytes` as IEEE 754 values of `size` bytes (4 or 8) in `order`.
pub fn decode(bytes: &[u8], size: usize, order: ByteOrder) -> Vec<f64> {
    bytes
        .chunks_exact(size)
        .map(|c| match (size, order) {
            (4, ByteOrder::Little) => f64::from(f32::from_le_bytes([c[0], c[1], c[2], c[3]])),
            (4, ByteOrder::Big) => f64::from(f32::from_be_bytes([c[0], c[1], c[2], c[3]])),
            (_, ByteOrder::Little) => f64::from_le_bytes(eight(c)),
            (_, ByteOrder::Big) => f64::from_be_bytes(eight(c)),
        })
        .collect()
}

fn eight(c: &[u8]) -> [u8; 8] {
    let mut a = [0; 8];
    a.copy_from_slice(c);
    a
}

/// Parses a 58b block: records 1–11 as dataset 58, then the binary data.
pub fn parse(file: &Path, b: &Block, bin: &Binary) -> Result<d58::Function, MeasuredError> {
    let (mut f, layout) = d58::parse_header(file, b)?;
    let size = if layout.double { 8 } else { 4 };
    let per_point = layout.per_point();
    let needed = layout.points * per_point * size;
    if bin.bytes.len() != needed {
        return Err(MeasuredError::UffBinarySize {
            file: file.to_path_buf(),
            line: bin.line,
            record: bin.record,
            announced: bin.bytes.len(),
            points: layout.points,
            per_point,
            size,
            needed,
        });
    }
    let values = decode(bin.bytes, size, bin.header.order);
    layout.fill(&mut f, &values, &vec![bin.line; values.len()]);
    Ok(f)
}
