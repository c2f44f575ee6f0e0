//! Why a parameter study could not be set up, merged, or why one of its
//! points failed.
//!
//! [`SweepError`] stops a sweep before any point runs (a bad `--param`, an
//! unknown quantity, a bad shard) or refuses a merge; [`PointError`] is the
//! failure of one point, which the sweep records and goes on.

use crate::error::{AnalysisError, Problem};
use crate::model::path::PathError;

/// A problem with the set-up of a sweep or with joining its shards.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SweepError {
    #[error("no parameter to vary")]
    NoParameters,
    #[error("`{given}` is not NAME=LO:HI:N[:log], NAME=V1,V2,… or NAME+= either (an offset; not for load_scale:)")]
    ParamSyntax { given: String },
    #[error("`{name}+=`: the model has no value at `{path}` to offset (give it in the model file, or set it with `{name}=`)")]
    NoValueToOffset { name: String, path: String },
    #[error("`{given}`: {what} `{text}` is not a finite number")]
    NotANumber {
        given: String,
        what: &'static str,
        text: String,
    },
    #[error(
        "`{given}`: the number of values must be a whole number from 1 to {max}, got `{text}`"
    )]
    BadCount {
        given: String,
        text: String,
        max: usize,
    },
    #[error("`{given}`: `{text}` is not `log` (the only spacing option)")]
    BadSpacing { given: String, text: String },
    #[error("`{given}`: a logarithmic range needs 0 < LO and 0 < HI, got {lo:?} and {hi:?}")]
    LogNotPositive { given: String, lo: f64, hi: f64 },
    #[error("the grid has {total} points, more than the {max} a sweep runs")]
    TooManyPoints { total: u128, max: usize },
    #[error("unknown parameter `{name}`: give a JSON path to a number of the model (e.g. `beams[0].section.height`, `springs[ID].stiffness`), `load_scale:ID[,ID…]`, or a short name: {}", short_names.join(", "))]
    UnknownParameter {
        name: String,
        short_names: Vec<String>,
    },
    /// A name that does not resolve to a number of the model.
    #[error(transparent)]
    Path(#[from] PathError),
    #[error("`{name}`: the model has no load `{id}`; its loads are: {}", if available.is_empty() { String::from("none") } else { available.join(", ") })]
    UnknownLoad {
        name: String,
        id: String,
        available: Vec<String>,
    },
    #[error("`{name}` and `{other}` both change {target}")]
    DuplicateParameter {
        name: String,
        other: String,
        target: String,
    },
    #[error("unknown quantity `{given}`; available: {}", available.join(", "))]
    UnknownQuantity {
        given: String,
        available: Vec<&'static str>,
    },
    #[error("`{given}`: the shard must be K/N with 1 ≤ K ≤ N (1-based), e.g. 2/8")]
    BadShard { given: String },
    #[error("the number of tracked modes must be at least 1")]
    NoTrackedModes,
    #[error("nothing to merge (give the shard documents)")]
    NothingToMerge,
    #[error("{file}: not a sweep document: {message}")]
    NotADocument { file: String, message: String },
    #[error("{file}: a complete sweep, not a shard (only shards are merged)")]
    NotAShard { file: String },
    #[error(
        "{file} belongs to a different sweep (sweep_id {found}, expected {expected} from {first})"
    )]
    DifferentSweep {
        file: String,
        found: String,
        expected: String,
        first: String,
    },
    #[error("{file}: point {index} is not the point the sweep defines there: {why}")]
    InconsistentPoint {
        file: String,
        index: usize,
        why: String,
    },
    #[error("point {index} is in {first} and again in {second}")]
    DuplicatePoint {
        index: usize,
        first: String,
        second: String,
    },
    #[error("{count} of the {total} points are missing (first: {}); they belong to shards {} of {shards}", first_missing.iter().map(usize::to_string).collect::<Vec<_>>().join(", "), missing_shards.iter().map(usize::to_string).collect::<Vec<_>>().join(", "))]
    MissingPoints {
        count: usize,
        total: usize,
        first_missing: Vec<usize>,
        missing_shards: Vec<usize>,
        shards: usize,
    },
}

/// Why one point of a sweep failed; recorded with the point.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PointError {
    /// The changed model does not deserialize (e.g. a fraction for a count).
    #[error("the model does not accept the value: {message}")]
    Schema { message: String },
    /// The changed model fails validation (e.g. a negative height).
    #[error("{path}: {problem}")]
    Invalid { path: String, problem: Problem },
    #[error(transparent)]
    Analysis(#[from] AnalysisError),
    #[error("no bending mode among the {computed} elastic modes computed")]
    NoBendingMode { computed: usize },
    #[error("elastic mode {wanted} asked for, but the model has only {available}")]
    TooFewModes { wanted: usize, available: usize },
    #[error("the tracked point does not travel {distance:e} m within {end_time:e} s")]
    NotReached { distance: f64, end_time: f64 },
    #[error("no sensor `{id}` in the model (its sensors: {available})")]
    UnknownSensor {
        id: String,
        available: crate::error::Ids,
    },
    #[error(transparent)]
    Simulation(#[from] crate::error::SimulationError),
}
