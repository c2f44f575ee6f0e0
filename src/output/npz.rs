//! NumPy's `.npz` archive: a ZIP of `.npy` arrays, written without
//! compression, for numpy's `np.load` (and any ZIP reader).
//!
//! - **`.npy` (format 1.0):** the magic `\x93NUMPY`, the version 1.0, a
//!   little-endian u16 header length, then a Python-literal header
//!   `{'descr': '<f8', 'fortran_order': False, 'shape': (r, c), }` padded
//!   with spaces and a newline so that the data starts on a multiple of
//!   64 bytes, then the values in C (row-major) order, little-endian:
//!   `<f8` (IEEE double), `<i8` (signed 64-bit integer), `|b1` (a byte
//!   0 or 1) or `<Uk` (text of at most k characters, each as a UTF-32
//!   code unit, padded with zeros).
//! - **ZIP (stored):** one local header, name and data per array, then
//!   the central directory and its end record (PKWARE APPNOTE 4.3). No
//!   ZIP64: an archive of 4 GiB or more is refused.
//!
//! The values keep their units; the caller documents them.

use thiserror::Error;

/// One array of the archive: its name (without `.npy`), shape and values.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    pub name: String,
    pub shape: Vec<usize>,
    pub data: NpyData,
}

/// The values, row-major.
#[derive(Debug, Clone, PartialEq)]
pub enum NpyData {
    F64(Vec<f64>),
    I64(Vec<i64>),
    Bool(Vec<bool>),
    Text(Vec<String>),
}

impl NpyArray {
    /// A float array of `shape` (row-major values).
    pub fn f64(name: &str, shape: &[usize], values: Vec<f64>) -> NpyArray {
        NpyArray {
            name: name.to_string(),
            shape: shape.to_vec(),
            data: NpyData::F64(values),
        }
    }

    /// A rows × columns float array from its rows (all of one length).
    pub fn rows(name: &str, rows: &[Vec<f64>], columns: usize) -> NpyArray {
        NpyArray::f64(name, &[rows.len(), columns], rows.concat())
    }

    /// An integer array of `shape` (row-major values).
    pub fn i64(name: &str, shape: &[usize], values: Vec<i64>) -> NpyArray {
        NpyArray {
            name: name.to_string(),
            shape: shape.to_vec(),
            data: NpyData::I64(values),
        }
    }

    /// A boolean array of `shape`.
    pub fn bool(name: &str, shape: &[usize], values: Vec<bool>) -> NpyArray {
        NpyArray {
            name: name.to_string(),
            shape: shape.to_vec(),
            data: NpyData::Bool(values),
        }
    }

    /// A text array of `shape` (row-major values).
    pub fn text(name: &str, shape: &[usize], values: Vec<String>) -> NpyArray {
        NpyArray {
            name: name.to_string(),
            shape: shape.to_vec(),
            data: NpyData::Text(values),
        }
    }

    fn len(&self) -> usize {
        match &self.data {
            NpyData::F64(v) => v.len(),
            NpyData::I64(v) => v.len(),
            NpyData::Bool(v) => v.len(),
            NpyData::Text(v) => v.len(),
        }
    }

    /// The `.npy` file's bytes.
    fn npy(&self) -> Vec<u8> {
        // Text: as wide as the longest value (at least 1 character).
        let width = match &self.data {
            NpyData::Text(v) => v
                .iter()
                .map(|t| t.chars().count())
                .max()
                .unwrap_or(0)
                .max(1),
            _ => 0,
        };
        let descr = match self.data {
            NpyData::F64(_) => "<f8".to_string(),
            NpyData::I64(_) => "<i8".to_string(),
            NpyData::Bool(_) => "|b1".to_string(),
            NpyData::Text(_) => format!("<U{width}"),
        };
        let shape = match self.shape.as_slice() {
            [n] => format!("({n},)"),
            dims => {
                let d: Vec<String> = dims.iter().map(usize::to_string).collect();
                format!("({})", d.join(", "))
            }
        };
        let mut header =
            format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
        // magic 6 + version 2 + length 2 + header + '\n' ≡ 0 (mod 64)
        let pad = (64 - (10 + header.len() + 1) % 64) % 64;
        header.push_str(&" ".repeat(pad));
        header.push('\n');
        let mut out = Vec::with_capacity(10 + header.len() + 8 * self.len());
        out.extend_from_slice(b"\x93NUMPY\x01\x00");
        out.extend_from_slice(&(header.len() as u16).to_le_bytes());
        out.extend_from_slice(header.as_bytes());
        match &self.data {
            NpyData::F64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            NpyData::I64(v) => v
                .iter()
                .for_each(|x| out.extend_from_slice(&x.to_le_bytes())),
            NpyData::Bool(v) => out.extend(v.iter().map(|&b| u8::from(b))),
            NpyData::Text(v) => {
                for t in v {
                    let mut units: Vec<u32> = t.chars().map(u32::from).collect();
                    units.resize(width, 0);
                    units
                        .iter()
                        .for_each(|u| out.extend_from_slice(&u.to_le_bytes()));
                }
            }
        }
        out
    }
}

/// Why an archive cannot be made.
#[derive(Debug, Error, PartialEq)]
pub enum NpzError {
    #[error("array `{name}`: shape {shape:?} holds {expected} values, not {actual}")]
    Shape {
        name: String,
        shape: Vec<usize>,
        expected: usize,
        actual: usize,
    },
    #[error("the archive would be {bytes} bytes; .npz without ZIP64 holds less than 4 GiB")]
    TooLarge { bytes: usize },
}

/// The `.npz` archive's bytes.
pub fn npz(arrays: &[NpyArray]) -> Result<Vec<u8>, NpzError> {
    const DOS_DATE_1980_01_01: u16 = (1 << 5) | 1;
    let mut out = Vec::new();
    let mut central = Vec::new();
    for a in arrays {
        let expected: usize = a.shape.iter().product();
        if expected != a.len() {
            return Err(NpzError::Shape {
                name: a.name.clone(),
                shape: a.shape.clone(),
                expected,
                actual: a.len(),
            });
        }
        let data = a.npy();
        let name = format!("{}.npy", a.name);
        let (offset, size) = (u32_of(out.len())?, u32_of(data.len())?);
        let crc = crc32fast::hash(&data);
        // Shared by the local header (after its signature and version) and
        // the central one (after signature, made-by and version).
        let mut common = Vec::new();
        for v in [0u16, 0, 0, DOS_DATE_1980_01_01] {
            common.extend_from_slice(&v.to_le_bytes()); // flags, method, time, date
        }
        for v in [crc, size, size] {
            common.extend_from_slice(&v.to_le_bytes());
        }
        common.extend_from_slice(&(name.len() as u16).to_le_bytes());
        common.extend_from_slice(&0u16.to_le_bytes()); // extra field length
        out.extend_from_slice(&0x0403_4b50u32.to_le_bytes());
        out.extend_from_slice(&20u16.to_le_bytes());
        out.extend_from_slice(&common);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&data);
        central.extend_from_slice(&0x0201_4b50u32.to_le_bytes());
        central.extend_from_slice(&20u16.to_le_bytes()); // made by
        central.extend_from_slice(&20u16.to_le_bytes()); // needed
        central.extend_from_slice(&common);
        for v in [0u16, 0, 0] {
            central.extend_from_slice(&v.to_le_bytes()); // comment, disk, internal
        }
        central.extend_from_slice(&0u32.to_le_bytes()); // external attributes
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let (start, size) = (u32_of(out.len())?, u32_of(central.len())?);
    out.extend_from_slice(&central);
    let count = arrays.len() as u16;
    out.extend_from_slice(&0x0605_4b50u32.to_le_bytes());
    for v in [0u16, 0, count, count] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&size.to_le_bytes());
    out.extend_from_slice(&start.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes()); // comment length
    u32_of(out.len())?;
    Ok(out)
}

fn u32_of(n: usize) -> Result<u32, NpzError> {
    u32::try_from(n).map_err(|_| NpzError::TooLarge { bytes: n })
}
