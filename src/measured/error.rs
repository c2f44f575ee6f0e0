//! Why a measurement file could not be used.
//!
//! Every variant names the file and, where one exists, the line (1-based)
//! and the column (1-based cell or field number), so that the command line
//! prints one line a user can act on.

use std::path::PathBuf;

/// A problem with a measurement file or with the records it holds.
#[derive(Debug, thiserror::Error)]
pub enum MeasuredError {
    #[error("{}: cannot read the file: {io}", file.display())]
    Read { file: PathBuf, io: std::io::Error },
    #[error("{}: the file holds no data", file.display())]
    Empty { file: PathBuf },
    #[error("{}:{line}: no column `{name}` in the header (columns: {columns})", file.display())]
    MissingColumn {
        file: PathBuf,
        line: usize,
        name: String,
        columns: String,
    },
    #[error("{}:{line}: the columns {columns} all name a force: give the force column (its name or 1-based index)", file.display())]
    AmbiguousForce {
        file: PathBuf,
        line: usize,
        columns: String,
    },
    #[error("{}:{line}: column {index} (`{name}`) cannot be the {role}: {why}", file.display())]
    ColumnMisused {
        file: PathBuf,
        line: usize,
        index: usize,
        name: String,
        role: &'static str,
        why: &'static str,
    },
    #[error("{}:{line}: column {index} does not exist: the header has {count} columns", file.display())]
    ColumnOutOfRange {
        file: PathBuf,
        line: usize,
        index: usize,
        count: usize,
    },
    #[error("{}:{line}: {found} cells, but the header has {expected}", file.display())]
    Ragged {
        file: PathBuf,
        line: usize,
        found: usize,
        expected: usize,
    },
    #[error("{}:{line}:{column}: `{value}` is not a number", file.display())]
    NotNumeric {
        file: PathBuf,
        line: usize,
        column: usize,
        value: String,
    },
    #[error("{}:{line}:{column}: `{value}` is not a finite number", file.display())]
    NotFinite {
        file: PathBuf,
        line: usize,
        column: usize,
        value: String,
    },
    #[error("{}:{line}: time {time:e} s does not increase (the line before has {previous:e} s)", file.display())]
    TimeNotIncreasing {
        file: PathBuf,
        line: usize,
        time: f64,
        previous: f64,
    },
    #[error("{}:{line}: uneven sampling: time {time:e} s is {offset:+.2} steps off the uniform grid of {step:e} s", file.display())]
    UnevenSampling {
        file: PathBuf,
        line: usize,
        time: f64,
        step: f64,
        offset: f64,
    },
    #[error("{}: {count} samples, at least {min} are needed", file.display())]
    TooFewSamples {
        file: PathBuf,
        count: usize,
        min: usize,
    },
    #[error("{}: the force channel `{channel}` is zero throughout", file.display())]
    ZeroForce { file: PathBuf, channel: String },
    #[error("{}:{line}: double impact: the force rises again to {percent:.0} % of its peak after the first impact ended (line {end_line})", file.display())]
    DoubleImpact {
        file: PathBuf,
        line: usize,
        end_line: usize,
        percent: f64,
    },
    /// A double impact in a record given as arrays (no file lines): the
    /// samples are 0-based indices.
    #[error("{}: double impact: the force rises again to {percent:.0} % of its peak at sample {sample}, after the first impact ended at sample {end_sample} (0-based; are force and response swapped?)", file.display())]
    DoubleImpactInSamples {
        file: PathBuf,
        sample: usize,
        end_sample: usize,
        percent: f64,
    },
    #[error("{}: {what} differs from {first}: {value:e} against {expected:e}", file.display())]
    Mismatch {
        file: PathBuf,
        first: PathBuf,
        what: &'static str,
        value: f64,
        expected: f64,
    },
    #[error("{}:{line}: UFF dataset `{kind}` (not used, skipped by its framing): {found} bytes of binary data before {until}, but its header announces {expected}, so the file cannot be split into its datasets", file.display())]
    UffSkippedBinaryLength {
        file: PathBuf,
        line: usize,
        kind: String,
        found: usize,
        until: &'static str,
        expected: usize,
    },
    #[error("{}:{line}: UFF {dataset} field `{field}`: cannot read `{value}`", file.display())]
    UffField {
        file: PathBuf,
        line: usize,
        dataset: u32,
        field: &'static str,
        value: String,
    },
    #[error("{}:{line}: UFF {dataset}: {field} = {value} is not supported ({supported})", file.display())]
    UffUnsupported {
        file: PathBuf,
        line: usize,
        dataset: u32,
        field: &'static str,
        value: String,
        supported: &'static str,
    },
    #[error("{}:{line}: UFF {dataset} record ends early: {found} values where {expected} are announced", file.display())]
    UffTruncated {
        file: PathBuf,
        line: usize,
        dataset: u32,
        found: usize,
        expected: usize,
    },
    #[error("{}:{line}: UFF 58b record {record}: {found} bytes of binary data before {until}, but its header announces {expected}", file.display())]
    UffBinaryLength {
        file: PathBuf,
        line: usize,
        record: usize,
        found: usize,
        until: &'static str,
        expected: usize,
    },
    #[error("{}:{line}: UFF 58b record {record}: its header announces {announced} bytes of binary data, but {points} points × {per_point} values × {size} bytes make {needed}", file.display())]
    UffBinarySize {
        file: PathBuf,
        line: usize,
        record: usize,
        announced: usize,
        points: usize,
        per_point: usize,
        size: usize,
        needed: usize,
    },
    #[error("{}:{line}: UFF block has no closing `    -1` line", file.display())]
    UffUnterminated { file: PathBuf, line: usize },
    #[error("{}: holds an FRF, which cannot be averaged with other files; give it alone", file.display())]
    MixedKinds { file: PathBuf },
    #[error("{}: the fit band starts at {lo_hz} Hz, at or past the data's last line, {} Hz", file.display(), crate::model::number::significant(*last_hz, 6))]
    BandPastData {
        file: PathBuf,
        lo_hz: f64,
        last_hz: f64,
    },
    #[error("{}: {what}", file.display())]
    NoChannel { file: PathBuf, what: &'static str },
    #[error("{}: {source}", file.display())]
    Spectrum {
        file: PathBuf,
        source: crate::signal::spectrum::SpectrumError,
    },
}
