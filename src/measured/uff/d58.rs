//! Dataset 58: a function at a nodal degree of freedom (time record, FRF,
//! coherence, …).
//!
//! Layout (line: Fortran format, fields):
//!
//! 1–5. `A80` ID lines 1–5 (name, description, date, …; `NONE` if empty).
//! 6. `I5,I10,I5,I10,1X,A10,I10,I4,1X,A10,I10,I4`: function type (1 time
//!    response, 4 FRF, 6 coherence, …), function id, version, load case,
//!    response entity name, node, direction, reference entity name, node,
//!    direction.
//! 7. `3I10,3E13.5`: ordinate data type (2 real single, 4 real double,
//!    5 complex single, 6 complex double), number of points, abscissa
//!    spacing (1 even, 0 uneven), abscissa minimum, increment, z value.
//! 8–11. `I10,3I5,1X,A20,1X,A20`: specific data type, length, force and
//!    temperature unit exponents, axis label, units label; for the abscissa,
//!    the ordinate numerator, the ordinate denominator and the z axis.
//!    Specific data types used here: 0 unknown, 8 displacement, 11 velocity,
//!    12 acceleration, 13 excitation force, 17 time, 18 frequency.
//! 12. Data: even spacing, ordinates only (real single `6E13.5`, real
//!    double `4E20.12`, complex single `6E13.5` as re, im pairs, complex
//!    double `4E20.12`); uneven spacing, abscissa and ordinate together.
//!
//! Dataset 58b holds records 1–11 as here and record 12 in binary: see
//! [`super::d58b`], which reads records 1–11 with [`parse_header`].
//!
//! This writer writes doubles (`%20.11e`, four to a line) with an even
//! abscissa, as pyuff's `_write58` does.

use std::fmt::Write;
use std::path::Path;

use realfft::num_complex::Complex64;

use super::{close_block, columns, fmt_e, id_line, open_block, parse_number, write_values, Block};
use crate::measured::MeasuredError;

/// Function type of record 6.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FunctionType {
    Time,
    Frf,
    Coherence,
    /// Any other UFF function type (kept as read).
    Other(i64),
}

impl FunctionType {
    pub fn code(self) -> i64 {
        match self {
            FunctionType::Time => 1,
            FunctionType::Frf => 4,
            FunctionType::Coherence => 6,
            FunctionType::Other(c) => c,
        }
    }
    pub fn from_code(c: i64) -> Self {
        match c {
            1 => FunctionType::Time,
            4 => FunctionType::Frf,
            6 => FunctionType::Coherence,
            c => FunctionType::Other(c),
        }
    }
}

/// UFF specific data types (records 8–11).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SpecDataType(pub i64);

impl SpecDataType {
    pub const UNKNOWN: SpecDataType = SpecDataType(0);
    pub const DISPLACEMENT: SpecDataType = SpecDataType(8);
    pub const VELOCITY: SpecDataType = SpecDataType(11);
    pub const ACCELERATION: SpecDataType = SpecDataType(12);
    pub const FORCE: SpecDataType = SpecDataType(13);
    pub const TIME: SpecDataType = SpecDataType(17);
    pub const FREQUENCY: SpecDataType = SpecDataType(18);
}

/// The ordinate values.
#[derive(Debug, Clone, PartialEq)]
pub enum Ordinate {
    Real(Vec<f64>),
    Complex(Vec<Complex64>),
}

impl Ordinate {
    pub fn len(&self) -> usize {
        match self {
            Ordinate::Real(v) => v.len(),
            Ordinate::Complex(v) => v.len(),
        }
    }
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Real parts (the values of a real ordinate).
    pub fn real_parts(&self) -> Vec<f64> {
        match self {
            Ordinate::Real(v) => v.clone(),
            Ordinate::Complex(v) => v.iter().map(|c| c.re).collect(),
        }
    }
    /// Complex values (a real ordinate with zero imaginary parts).
    pub fn complex(&self) -> Vec<Complex64> {
        match self {
            Ordinate::Real(v) => v.iter().map(|r| Complex64::new(*r, 0.0)).collect(),
            Ordinate::Complex(v) => v.clone(),
        }
    }
}

/// One dataset 58.
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    pub id: [String; 5],
    pub function_type: FunctionType,
    pub response_entity: String,
    pub response_node: i64,
    pub response_direction: i64,
    pub reference_entity: String,
    pub reference_node: i64,
    pub reference_direction: i64,
    /// Even abscissa: x_i = x_min + i·dx; otherwise `x` holds them.
    pub even: bool,
    pub x_min: f64,
    pub dx: f64,
    pub x: Vec<f64>,
    pub abscissa_type: SpecDataType,
    pub abscissa_label: String,
    pub abscissa_units: String,
    pub ordinate_type: SpecDataType,
    pub ordinate_label: String,
    pub ordinate_units: String,
    pub denominator_type: SpecDataType,
    pub denominator_label: String,
    pub denominator_units: String,
    pub ordinate: Ordinate,
    /// Line (1-based) of the first data line, for messages.
    pub data_line: usize,
    /// Line (1-based) of each point's data, for messages (empty for a
    /// function not read from a file; for 58b, the record's type line).
    pub lines: Vec<usize>,
}

impl Function {
    /// The abscissa values.
    pub fn abscissa(&self) -> Vec<f64> {
        if self.even {
            (0..self.ordinate.len())
                .map(|i| self.x_min + i as f64 * self.dx)
                .collect()
        } else {
            self.x.clone()
        }
    }
}

fn int_field(
    file: &Path,
    line: usize,
    text: &str,
    field: &'static str,
) -> Result<i64, MeasuredError> {
    let t = text.trim();
    if t.is_empty() {
        return Ok(0);
    }
    t.parse().map_err(|_| MeasuredError::UffField {
        file: file.to_path_buf(),
        line,
        dataset: 58,
        field,
        value: t.to_string(),
    })
}

/// How the data of a dataset 58 are laid out (record 7).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// Number of points.
    pub points: usize,
    /// Complex ordinate (re, im pairs).
    pub complex: bool,
    /// Double precision (ordinate data types 4 and 6); single otherwise.
    pub double: bool,
    /// Even abscissa; an uneven one stores each point's abscissa first.
    pub even: bool,
    /// Line (1-based) of record 7, for messages.
    pub line: usize,
}

impl Layout {
    /// Values stored per point: abscissa (uneven only), re, im (complex).
    pub fn per_point(&self) -> usize {
        usize::from(self.complex) + 1 + usize::from(!self.even)
    }

    /// Puts `values` (`points × per_point`, in stored order) into `f`,
    /// `lines` holding the line of each value.
    pub fn fill(&self, f: &mut Function, values: &[f64], lines: &[usize]) {
        let per_point = self.per_point();
        let pts = values.chunks(per_point);
        if !self.even {
            f.x = pts.clone().map(|p| p[0]).collect();
        }
        let o = usize::from(!self.even);
        f.ordinate = if self.complex {
            Ordinate::Complex(pts.map(|p| Complex64::new(p[o], p[o + 1])).collect())
        } else {
            Ordinate::Real(pts.map(|p| p[o]).collect())
        };
        f.lines = lines.iter().copied().step_by(per_point).collect();
    }
}

/// Parses the lines of one (ASCII) dataset-58 block.
pub fn parse(file: &Path, b: &Block) -> Result<Function, MeasuredError> {
    let (mut f, layout) = parse_header(file, b)?;
    let line_no = |k: usize| b.first_line + k;
    let n = layout.points * layout.per_point();
    let mut values = Vec::with_capacity(n);
    let mut value_lines = Vec::with_capacity(n);
    for (k, l) in b.lines[11..].iter().enumerate() {
        for tok in l.split_whitespace() {
            value_lines.push(line_no(11 + k));
            let v = parse_number(tok).ok_or(MeasuredError::UffField {
                file: file.to_path_buf(),
                line: line_no(11 + k),
                dataset: 58,
                field: "data value",
                value: tok.to_string(),
            })?;
            values.push(v);
        }
    }
    if values.len() != n {
        return Err(MeasuredError::UffTruncated {
            file: file.to_path_buf(),
            line: line_no(b.lines.len()),
            dataset: 58,
            found: values.len(),
            expected: n,
        });
    }
    layout.fill(&mut f, &values, &value_lines);
    Ok(f)
}

/// Parses records 1–11 of a dataset 58 or 58b: the function without its
/// data (empty ordinate) and the layout of the data.
pub fn parse_header(file: &Path, b: &Block) -> Result<(Function, Layout), MeasuredError> {
    let line_no = |k: usize| b.first_line + k;
    if b.lines.len() < 11 {
        return Err(MeasuredError::UffTruncated {
            file: file.to_path_buf(),
            line: line_no(b.lines.len()),
            dataset: 58,
            found: b.lines.len(),
            expected: 11,
        });
    }
    let id: [String; 5] = std::array::from_fn(|k| b.lines[k].trim_end().to_string());
    let r6: &str = &b.lines[5];
    let l6 = line_no(5);
    let function_type =
        FunctionType::from_code(int_field(file, l6, &columns(r6, 0, 5), "function type")?);
    let response_node = int_field(file, l6, &columns(r6, 41, 10), "response node")?;
    let response_direction = int_field(file, l6, &columns(r6, 51, 4), "response direction")?;
    let reference_node = int_field(file, l6, &columns(r6, 66, 10), "reference node")?;
    let reference_direction = int_field(file, l6, &columns(r6, 76, 4), "reference direction")?;
    let l7 = line_no(6);
    let r7: Vec<&str> = b.lines[6].split_whitespace().collect();
    let field7 = |k: usize, name: &'static str| -> Result<&str, MeasuredError> {
        r7.get(k).copied().ok_or(MeasuredError::UffField {
            file: file.to_path_buf(),
            line: l7,
            dataset: 58,
            field: name,
            value: b.lines[6].trim().to_string(),
        })
    };
    let ord_type = int_field(
        file,
        l7,
        field7(0, "ordinate data type")?,
        "ordinate data type",
    )?;
    let num_pts = int_field(file, l7, field7(1, "number of points")?, "number of points")?;
    let spacing = int_field(file, l7, field7(2, "abscissa spacing")?, "abscissa spacing")?;
    let real7 = |k: usize, name: &'static str| -> Result<f64, MeasuredError> {
        let s = field7(k, name)?;
        parse_number(s).ok_or(MeasuredError::UffField {
            file: file.to_path_buf(),
            line: l7,
            dataset: 58,
            field: name,
            value: s.to_string(),
        })
    };
    let x_min = real7(3, "abscissa minimum")?;
    let dx = real7(4, "abscissa increment")?;
    let complex = match ord_type {
        2 | 4 => false,
        5 | 6 => true,
        other => {
            return Err(MeasuredError::UffUnsupported {
                file: file.to_path_buf(),
                line: l7,
                dataset: 58,
                field: "ordinate data type",
                value: other.to_string(),
                supported: "2, 4 (real), 5, 6 (complex)",
            })
        }
    };
    let even = spacing == 1;
    let axis = |k: usize| -> Result<(SpecDataType, String, String), MeasuredError> {
        let l: &str = &b.lines[7 + k];
        let t = int_field(
            file,
            line_no(7 + k),
            &columns(l, 0, 10),
            "specific data type",
        )?;
        Ok((SpecDataType(t), columns(l, 26, 20), columns(l, 47, 20)))
    };
    let (abscissa_type, abscissa_label, abscissa_units) = axis(0)?;
    let (ordinate_type, ordinate_label, ordinate_units) = axis(1)?;
    let (denominator_type, denominator_label, denominator_units) = axis(2)?;
    let layout = Layout {
        points: usize::try_from(num_pts).unwrap_or(0),
        complex,
        double: matches!(ord_type, 4 | 6),
        even,
        line: l7,
    };
    let f = Function {
        id,
        function_type,
        response_entity: columns(r6, 31, 10),
        response_node,
        response_direction,
        reference_entity: columns(r6, 56, 10),
        reference_node,
        reference_direction,
        even,
        x_min,
        dx,
        x: Vec::new(),
        abscissa_type,
        abscissa_label,
        abscissa_units,
        ordinate_type,
        ordinate_label,
        ordinate_units,
        denominator_type,
        denominator_label,
        denominator_units,
        ordinate: Ordinate::Real(Vec::new()),
        data_line: line_no(11),
        lines: Vec::new(),
    };
    Ok((f, layout))
}

/// Appends `f` as an ASCII dataset 58 (even abscissa, doubles). An uneven
/// `f` is written with x_min and dx of its first two abscissae.
pub fn write(out: &mut String, f: &Function) {
    open_block(out, 58);
    for id in &f.id {
        id_line(out, id);
    }
    let name = |s: &str| -> String {
        let s: String = s.chars().take(10).collect();
        if s.trim().is_empty() {
            "NONE".into()
        } else {
            s
        }
    };
    let _ = writeln!(
        out,
        "{:>5}{:>10}{:>5}{:>10} {:<10}{:>10}{:>4} {:<10}{:>10}{:>4}",
        f.function_type.code(),
        0,
        0,
        0,
        name(&f.response_entity),
        f.response_node,
        f.response_direction,
        name(&f.reference_entity),
        f.reference_node,
        f.reference_direction
    );
    let (ord_code, values): (u32, Vec<f64>) = match &f.ordinate {
        Ordinate::Real(v) => (4, v.clone()),
        Ordinate::Complex(v) => (6, v.iter().flat_map(|c| [c.re, c.im]).collect()),
    };
    let _ = writeln!(
        out,
        "{:>10}{:>10}{:>10}{}{}{}",
        ord_code,
        f.ordinate.len(),
        1,
        fmt_e(f.x_min, 13, 5),
        // Seven significant digits (the field's 13 columns with its
        // leading blank, dx being positive): 1/51,200 s and 1/10,240 s are
        // written exactly, so a record read back has its rate.
        fmt_e(f.dx, 13, 6),
        fmt_e(0.0, 13, 5)
    );
    let axis = |out: &mut String, t: SpecDataType, label: &str, units: &str| {
        let label = if label.is_empty() { "NONE" } else { label };
        let units = if units.is_empty() { "NONE" } else { units };
        let label: String = label.chars().take(20).collect();
        let units: String = units.chars().take(20).collect();
        let _ = writeln!(
            out,
            "{:>10}{:>5}{:>5}{:>5} {label:<20} {units:<20}",
            t.0, 0, 0, 0
        );
    };
    axis(out, f.abscissa_type, &f.abscissa_label, &f.abscissa_units);
    axis(out, f.ordinate_type, &f.ordinate_label, &f.ordinate_units);
    axis(
        out,
        f.denominator_type,
        &f.denominator_label,
        &f.denominator_units,
    );
    axis(out, SpecDataType::UNKNOWN, "NONE", "NONE");
    write_values(out, &values, 4, 20, 11);
    close_block(out);
}
