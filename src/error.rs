//! Typed errors of the library.
//!
//! Model errors carry the file, the JSON path and the problem, so that the
//! command line can print one line a user can act on. Analysis errors carry
//! the quantities that explain them (times, residuals, coordinates).
//!
//! The errors of one analysis that wrap others live with that analysis
//! ([`crate::analysis::impulse::ImpulseError`],
//! [`crate::analysis::calibrate::CalibrationError`]), so that this module
//! depends on nothing else in the crate.

use std::fmt;
use std::path::PathBuf;

/// The ids a model has of one kind (its sensors, beams, bodies …), listed
/// in a message that names an unknown one: `a, b, c`, or `none`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Ids(pub Vec<String>);

impl Ids {
    /// The ids, in the model's order.
    pub fn of<'a>(ids: impl IntoIterator<Item = &'a String>) -> Self {
        Ids(ids.into_iter().cloned().collect())
    }
}

impl fmt::Display for Ids {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            write!(f, "none")
        } else {
            write!(f, "{}", self.0.join(", "))
        }
    }
}

/// Where a model came from, for messages.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source {
    File(PathBuf),
    BuiltIn,
}

impl fmt::Display for Source {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Source::File(p) => write!(f, "{}", p.display()),
            Source::BuiltIn => write!(f, "<built-in model>"),
        }
    }
}

/// A problem with one value of a model, found by validation.
///
/// Values the user wrote are shown with `{:?}`, which switches to exponent
/// notation for very small and very large numbers (`-1e-9`, not
/// `-0.000000001`) and always shows that a number is a float.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Problem {
    #[error("must be a finite number, got {value:?}")]
    NotFinite { value: f64 },
    #[error("must be positive, got {value:?}")]
    NotPositive { value: f64 },
    #[error("must not be negative, got {value:?}")]
    Negative { value: f64 },
    #[error("must be at least 1, got 0")]
    ZeroCount,
    #[error("the beams have {total} elements in all, more than the {max} this machine's available memory holds (about {kib_per_element} kB per element)")]
    TooManyElements {
        total: usize,
        max: usize,
        kib_per_element: usize,
    },
    #[error("{value:?} is outside [{min:?}, {max:?}]")]
    OutOfRange { value: f64, min: f64, max: f64 },
    #[error("must not be empty")]
    EmptyId,
    #[error("id `{id}` is used twice")]
    DuplicateId { id: String },
    #[error("no {kind} with id `{id}` (the model's: {available})")]
    UnknownId {
        kind: &'static str,
        id: String,
        available: Ids,
    },
    #[error(
        "give exactly one of `beam`, `body` or `ground` (this point gives {})",
        given_keys(given)
    )]
    AmbiguousPoint { given: Vec<&'static str> },
    #[error("`{key}` is required here")]
    MissingKey { key: &'static str },
    #[error("`{key}` is not allowed here: {why}")]
    KeyNotAllowed {
        key: &'static str,
        why: &'static str,
    },
    #[error("a direction must have non-zero length")]
    ZeroDirection,
    #[error(
        "the points do not coincide initially: a is at {}, b at {}, a gap of {gap:.3e} m",
        point_text(.a),
        point_text(.b)
    )]
    PointsApart { gap: f64, a: [f64; 2], b: [f64; 2] },
    #[error("point b is {gap:.3e} m off the slider axis through point a")]
    OffAxis { gap: f64 },
    #[error("both points are fixed to the ground: nothing to connect")]
    GroundToGround,
    #[error("`{id}` is a point mass and has no orientation; {what} needs a rigid body, a beam or the ground")]
    NoOrientation { id: String, what: &'static str },
    #[error("both points are the same, the spring has zero length")]
    ZeroLength,
    #[error("the model has no bodies (no beam, rigid body or point mass)")]
    NoBodies,
    #[error("the segment has length {length:.3e} m: its end points coincide")]
    DegenerateSegment { length: f64 },
    #[error("the pin radius {radius:?} m must be below half the slot width {width:?} m (no clearance left)")]
    PinTooLarge { radius: f64, width: f64 },
    #[error("the point starts {distance:.3e} m from the line, within its radius {radius:?} m: give `side` (`left` or `right` of from→to)")]
    SideNeeded { distance: f64, radius: f64 },
    #[error("the spring's free length {free_length:.3e} m is not positive (preload {preload:?} N, stiffness {stiffness:?} N/m, initial length {length:.3e} m)")]
    NonPositiveFreeLength {
        free_length: f64,
        preload: f64,
        stiffness: f64,
        length: f64,
    },
}

/// A model that fails validation: the JSON path of the first offending
/// value (e.g. `joints[1].b.s`) and what is wrong there
/// ([`crate::model::Model::validated`]). A model read from a file reports
/// it as [`ModelError::Invalid`], naming the file too.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{path}: {problem}")]
pub struct InvalidModel {
    pub path: String,
    pub problem: Problem,
}

/// "`beam` and `ground`", or "none of them" for an empty list.
fn given_keys(keys: &[&str]) -> String {
    match keys {
        [] => String::from("none of them"),
        [one] => format!("only `{one}`"),
        [init @ .., last] => {
            let init: Vec<String> = init.iter().map(|k| format!("`{k}`")).collect();
            format!("{} and `{last}`", init.join(", "))
        }
    }
}

/// Why a model could not be read.
#[derive(Debug, thiserror::Error)]
pub enum ModelError {
    #[error("{source_name}: cannot read the file: {io}")]
    Read {
        source_name: Source,
        io: std::io::Error,
    },
    #[error("{source_name}:{line}:{column}: malformed JSON: {message}")]
    Syntax {
        source_name: Source,
        line: usize,
        column: usize,
        message: String,
    },
    /// A number JSON allows but an `f64` cannot hold (e.g. `1e999`).
    /// serde_json reports it as a syntax error; the path locates it better.
    #[error("{source_name}:{line}:{column}: {path}: number out of range: model values must be finite (magnitude below 1.8e308)")]
    NumberOutOfRange {
        source_name: Source,
        line: usize,
        column: usize,
        path: String,
    },
    #[error("{source_name}: {path}: {message}")]
    Schema {
        source_name: Source,
        path: String,
        message: String,
    },
    #[error("{source_name}: {path}: {problem}")]
    Invalid {
        source_name: Source,
        path: String,
        problem: Problem,
    },
}

/// Why an analysis failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AnalysisError {
    /// A mesh of a convergence study
    /// ([`crate::analysis::convergence`]) fails validation.
    #[error("the model at {elements} elements per beam is not valid")]
    InvalidMesh {
        elements: usize,
        source: Box<InvalidModel>,
    },
    #[error("{path}: the mass matrix is singular in the direction of {dof} (a body without inertia in a free direction)")]
    SingularMass { dof: String, path: String },
    #[error("the system has no free coordinates left after the constraints")]
    NoFreedom,
    #[error("the eigen solver did not converge ({size}×{size} problem)")]
    EigenSolver { size: usize },
    /// Statics on a large model: the reduced tangent is singular (a
    /// mechanism), which only the dense path resolves.
    #[error("the static tangent is singular (a mechanism) and the model has {size} free coordinates: free motions are resolved on the dense path only, up to {max}")]
    IndefiniteLargeTangent { size: usize, max: usize },
    /// Statics: the loads push the whole assembly as a rigid body.
    #[error("the assembly cannot carry the load: it has no support, so the loads move it as a rigid body (fix it to the ground with a joint)")]
    NoSupport,
    /// Statics: the reduced tangent is singular in a direction the load pushes.
    #[error("the assembly cannot carry the load: it is a mechanism, free to move without stiffness in a motion that moves {dof} most (add a support or a spring there)")]
    Mechanism { dof: String },
    /// Statics: Newton's method failed even with the smallest load increment.
    #[error("the static equilibrium did not converge: at load factor {load_factor:.6} Newton's method stopped after {iterations} iterations with an unbalanced force of {residual:.3e} N (no equilibrium near the load path, or a limit point)")]
    NotConverged {
        load_factor: f64,
        iterations: usize,
        residual: f64,
    },
    /// Statics: the equilibrium loses stability on the load path.
    #[error("the static equilibrium loses stability at load factor {load_factor:.9} (load path: {path}): the stiffness against a motion that moves {dof} most reaches zero there (buckling or snap-through); past it no stable equilibrium follows the load path")]
    Unstable {
        load_factor: f64,
        dof: String,
        path: LoadPath,
    },
    /// Statics: gravity alone, ramped up, makes the equilibrium unstable.
    #[error("the static equilibrium under gravity alone loses stability at {gravity_factor:.6} × g: the stiffness against a motion that moves {dof} most reaches zero there")]
    UnstableUnderGravity { gravity_factor: f64, dof: String },
    /// Statics: the design's equilibrium found from its own reference has
    /// open the contact whose opening stopped the continuation: it is not
    /// the state that contact holds (e.g. a lever turned over past its stop).
    #[error("the equilibrium found from the design's own reference has contact `{contact}` open ({force:.3e} N): not the state the contact holds")]
    ContactOpenInFallback { contact: String, force: f64 },
    /// Statics: the equilibrium continued from another design of the
    /// assembly was not reached.
    /// `fallback`: why solving the design from its own reference failed
    /// too.
    #[error("continued from the design of `{from}`: {reason}; solved from its own reference instead: {fallback}")]
    FromDesign {
        from: String,
        reason: Box<DesignPathError>,
        fallback: Box<AnalysisError>,
    },
}

/// The order in which a static solve applies gravity and the applied
/// loads from the reference ([`crate::analysis::statics`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, schemars::JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum LoadPath {
    /// Gravity ramped to 1 g, then the loads to their factor.
    GravityFirst,
    /// Gravity and the loads ramped together.
    Together,
    /// The loads ramped to their factor, then gravity.
    LoadsFirst,
    /// The loads alone (the model has no gravity).
    LoadsOnly,
    /// Gravity alone (no load acts at the factor asked).
    GravityOnly,
}

impl std::fmt::Display for LoadPath {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LoadPath::GravityFirst => "gravity first, then the loads",
            LoadPath::Together => "gravity and the loads together",
            LoadPath::LoadsFirst => "the loads first, then gravity",
            LoadPath::LoadsOnly => "the loads alone (no gravity)",
            LoadPath::GravityOnly => "gravity alone (no loads)",
        })
    }
}

/// Why a state of one design cannot be carried to another
/// ([`crate::system::System::transfer_from`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TransferError {
    /// The target has a part the source does not (by kind and id).
    #[error("{kind} `{id}` of the target design has no counterpart in the source design")]
    Missing { kind: &'static str, id: String },
    /// The source vector does not belong to the source system.
    #[error("the source state has {got} coordinates, its system {expected}")]
    Length { got: usize, expected: usize },
}

/// Why a continuation in the design did not reach the design
/// ([`crate::analysis::statics::design_path`]).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DesignPathError {
    #[error("the starting design: {0}")]
    Start(AnalysisError),
    #[error("contact `{contact}` opens at {at:.4} of the way to the design: no equilibrium with it closed")]
    ContactOpens { contact: String, at: f64 },
    /// `last`: why the last, smallest step failed (in the message, not a
    /// `source`: the chain would print it twice).
    #[error("no equilibrium found beyond {at:.4} of the way to the design (steps below {min_step} of it): {last}")]
    Stalled {
        at: f64,
        min_step: f64,
        last: AnalysisError,
    },
    /// A state of one design could not be carried to the next.
    #[error("at {at:.4} of the way to the design: {source}")]
    Transfer { at: f64, source: TransferError },
    /// A design on the way fails validation (e.g. joint points that meet
    /// at both ends of the path but not between); `invalid` is in the
    /// message, not a `source` (as `last` of `Stalled`).
    #[error("the design at {at:.4} of the way is not a valid model: {invalid}")]
    InvalidDesign { at: f64, invalid: Box<InvalidModel> },
    /// The state reached holds more total potential energy than the
    /// design's unloaded reference: a jump to another branch.
    #[error("the state reached holds a total potential energy of {found:.6e} J, above the {reference:.6e} J of the design's reference: a jump to another branch, refused")]
    EnergyAboveReference { found: f64, reference: f64 },
    /// The state reached does not balance the design's own system.
    #[error("the state reached does not balance the design's own system: unbalanced force {unbalanced:.3e} N against {scale:.3e} N, constraint violation {violation:.3e} m")]
    Unbalanced {
        unbalanced: f64,
        scale: f64,
        violation: f64,
    },
}

/// Why a time integration failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TransientError {
    #[error("time step must be positive and finite, got {step} s")]
    InvalidStep { step: f64 },
    #[error("end time {end_time} s must be finite and longer than one step ({step} s)")]
    InvalidEndTime { end_time: f64, step: f64 },
    #[error("spectral radius must be in [0, 1], got {value}")]
    InvalidSpectralRadius { value: f64 },
    #[error("Newton iteration failed at t = {time:.9e} s after {iterations} iterations (residual {residual:.3e})")]
    NewtonFailure {
        time: f64,
        residual: f64,
        iterations: usize,
    },
    #[error("the iteration matrix is singular at t = {time:.9e} s (in the direction of {dof})")]
    Singular { time: f64, dof: String },
    #[error("no memory for the sparse LU factors of the {size}-unknown iteration matrix")]
    OutOfMemory { size: usize },
}

/// A setting of a simulation, named in its errors (the command line maps
/// each to its flag).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Setting {
    Step,
    EndTime,
    Distance,
    Direction,
    SampleRate,
}

impl fmt::Display for Setting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Setting::Step => "time step",
            Setting::EndTime => "end time",
            Setting::Distance => "travel distance",
            Setting::Direction => "length of the travel direction",
            Setting::SampleRate => "sample rate",
        })
    }
}

/// Why a simulation (`transient`, `switch-off`) failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulationError {
    #[error("the initial static equilibrium")]
    Equilibrium(#[from] AnalysisError),
    #[error("time integration")]
    Transient(#[from] TransientError),
    #[error("the {setting} must be {allowed}, got {value:?}")]
    InvalidSetting {
        setting: Setting,
        allowed: &'static str,
        value: f64,
    },
    #[error("the tracked point: {why}")]
    InvalidPoint { why: String },
    /// The model with every beam rigid (the rigid comparison) fails
    /// validation.
    #[error("the model with every beam rigid")]
    RigidModel(#[source] Box<InvalidModel>),
    #[error("the time integration diverged before the tracked point reached its distance: run again up to {time_s:e} s, its energy balance misses by {fraction:.3e} times the energy put in (a sound run: below 1e-2)")]
    Unsound { time_s: f64, fraction: f64 },
    #[error("joint `{joint}` is a released support: it lets go of the static equilibrium's hold, so the run must start from the static equilibrium")]
    ReleaseNeedsEquilibrium { joint: String },
}

/// An error and its causes on one line, `a: b: c` (each error names its
/// own context once and leaves its cause to [`std::error::Error::source`]).
pub fn chain_text(e: &dyn std::error::Error) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        line.push_str(": ");
        line.push_str(&c.to_string());
        cause = c.source();
    }
    line
}

/// A point [SI: m] as `[x, y]` to the picometre (the round-off of a
/// rotated offset, 4.9e-18 m, is not a coordinate the user typed).
fn point_text(p: &[f64; 2]) -> String {
    let r = |x: f64| {
        let v = (x * 1e12).round() / 1e12;
        if v == 0.0 {
            0.0
        } else {
            v
        }
    };
    format!("[{:?}, {:?}]", r(p[0]), r(p[1]))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_point_is_written_to_the_picometre() {
        // A 90° rotation of (0.08, 0) and 0.025 + 0.05 as computed.
        let p = [4.898587196589413e-18, -0.07500000000000001];
        assert_eq!(super::point_text(&p), "[0.0, -0.075]");
        assert_eq!(super::point_text(&[1.5e-6, -2.0]), "[1.5e-6, -2.0]");
    }
}
