//! Parameter studies (`ancf-modal sweep`): a quantity computed over a grid
//! of model parameters.
//!
//! A sweep varies one or more numbers of the model ([`param`]: a JSON path,
//! a calibration short name, or a load factor) over axes `LO:HI:N[:log]`
//! ([`grid`]); several parameters make the full grid, its points in
//! row-major order of the parameters. At each point the model file's values
//! are changed in a copy of the model, which is then validated and
//! assembled afresh, and the [`quantity`] is computed; points are
//! independent and run in parallel (rayon). A point that fails (a value the
//! model refuses, a buckled equilibrium) is recorded with its error message
//! and the sweep goes on.
//!
//! Frequencies of a tracked quantity follow their modes across the grid by
//! MAC ([`tracking`]), which needs every point: a shard (`--shard K/N`,
//! every N-th point) keeps the computed mode shapes, and
//! [`document::merge`] joins shards and tracks them, giving exactly the
//! document of a single run.
//!
//! Units are SI throughout, as in the model file; frequencies in Hz.

pub mod document;
pub mod error;
pub mod grid;
pub mod param;
pub mod quantity;
pub mod tracking;

pub use document::{
    merge, Header, ParameterValues, PointRecord, RawPoint, SweepDocument, SweepRun,
};
pub use error::{PointError, SweepError};
pub use grid::{Axis, Grid, Shard};
pub use param::Parameter;
pub use quantity::{evaluate, EvalSettings, Evaluation, Quantity, RawMode, Trace};

use crate::analysis::EigenMethod;
use crate::model::{Model, ValidModel};
use rayon::prelude::*;

/// How a sweep is computed.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSettings {
    pub quantity: Quantity,
    /// Step and end time of transient quantities [SI: s] (`None`: the
    /// switch-off's defaults).
    pub step: Option<f64>,
    pub end_time: Option<f64>,
    /// Elastic modes tracked for a tracked quantity (at least its K).
    pub tracked_modes: usize,
    /// Linearize at the static equilibrium under the model's loads (implied
    /// by a `load_scale:` parameter).
    pub prestress: bool,
    pub method: EigenMethod,
}

impl SweepSettings {
    pub fn new(quantity: Quantity) -> Self {
        SweepSettings {
            quantity,
            step: None,
            end_time: None,
            tracked_modes: DEFAULT_TRACKED_MODES,
            prestress: false,
            method: EigenMethod::Auto,
        }
    }
}

/// Elastic modes tracked unless asked otherwise.
pub const DEFAULT_TRACKED_MODES: usize = 6;

/// Computed modes beyond the tracked ones, so that a mode entering from
/// above can be matched.
fn margin(tracked: usize) -> usize {
    (tracked / 2).max(2)
}

/// A resolved sweep, ready to run.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// The model's JSON form, into which each point writes its values.
    base: serde_json::Value,
    /// The swept model itself.
    model: ValidModel,
    pub parameters: Vec<Parameter>,
    pub grid: Grid,
    pub settings: SweepSettings,
    pub header: Header,
}

/// Points computed in parallel (rayon's pool) or one after another.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Execution {
    Parallel,
    Serial,
}

impl Sweep {
    /// Resolves the `NAME=LO:HI:N[:log]` specifications against `model`.
    pub fn new(
        model: &ValidModel,
        specs: &[String],
        settings: SweepSettings,
    ) -> Result<Sweep, SweepError> {
        if specs.is_empty() {
            return Err(SweepError::NoParameters);
        }
        let base = serde_json::to_value(&**model).expect("models serialize");
        let mut parameters: Vec<Parameter> = Vec::with_capacity(specs.len());
        for spec in specs {
            param::add_distinct(&mut parameters, Parameter::parse(model, &base, spec)?)?;
        }
        let mut settings = settings;
        if settings.tracked_modes == 0 {
            return Err(SweepError::NoTrackedModes);
        }
        if let Some(k) = settings.quantity.tracked_mode() {
            settings.tracked_modes = settings.tracked_modes.max(k);
        }
        settings.prestress |= parameters.iter().any(|p| p.scales_loads);
        let grid = Grid::new(parameters.iter().map(|p| p.axis.values()).collect())?;
        let header = Header {
            model: model.name.clone(),
            quantity: settings.quantity.clone(),
            sweep_id: fingerprint(model, &parameters, &settings),
            parameters: parameters
                .iter()
                .zip(&grid.axes)
                .map(|(p, v)| ParameterValues {
                    name: p.name.clone(),
                    target: p.target.clone(),
                    values: v.clone(),
                    log: p.axis.is_log(),
                })
                .collect(),
            prestress: settings.prestress,
            tracked_modes: settings
                .quantity
                .tracked_mode()
                .map(|_| settings.tracked_modes),
        };
        Ok(Sweep {
            base,
            model: model.clone(),
            parameters,
            grid,
            settings,
            header,
        })
    }

    /// Number of points of the whole grid.
    pub fn total_points(&self) -> usize {
        self.grid.len()
    }

    /// The indices of the points a run computes.
    pub fn indices(&self, shard: Option<Shard>) -> Vec<usize> {
        (0..self.total_points())
            .filter(|&i| shard.is_none_or(|s| s.contains(i)))
            .collect()
    }

    /// The model at parameter values `values` (validated).
    pub fn model_at(&self, values: &[f64]) -> Result<ValidModel, PointError> {
        param::apply(&self.base, &self.parameters, values)
    }

    /// Computes point `index`.
    pub fn point(&self, index: usize) -> RawPoint {
        let values = self.grid.values(index);
        let eval = EvalSettings {
            prestress: self.settings.prestress,
            method: self.settings.method,
            modes: self.settings.tracked_modes + margin(self.settings.tracked_modes),
            step: self.settings.step,
            end_time: self.settings.end_time,
            keep_trace: self.grid.shape().len() == 1,
        };
        let mut warnings = Vec::new();
        let outcome = self
            .model_at(&values)
            .and_then(|m| {
                // A point says only what its values add to the model's own
                // unit warnings (the run gives those once).
                let base: Vec<String> = self
                    .model
                    .unit_warnings()
                    .iter()
                    .map(|w| w.to_string())
                    .collect();
                warnings = m
                    .unit_warnings()
                    .iter()
                    .map(|w| w.to_string())
                    .filter(|w| !base.contains(w))
                    .collect();
                evaluate(&self.settings.quantity, &m, &self.model, &eval)
            })
            .map_err(|e| crate::error::chain_text(&e));
        RawPoint {
            index,
            values,
            outcome,
            warnings,
        }
    }

    /// Computes the points of `shard` (all when `None`); `progress` is
    /// called after each point (from the worker threads).
    pub fn run(
        &self,
        shard: Option<Shard>,
        execution: Execution,
        progress: &(dyn Fn() + Sync),
    ) -> SweepRun {
        let indices = self.indices(shard);
        let one = |&i: &usize| {
            let p = self.point(i);
            progress();
            p
        };
        let points = match execution {
            Execution::Parallel => indices.par_iter().map(one).collect(),
            Execution::Serial => indices.iter().map(one).collect(),
        };
        SweepRun {
            header: self.header.clone(),
            shard,
            points,
        }
    }
}

/// `sweep_id`: FNV-1a (64 bit) of the model, the parameters' targets and
/// axes, the quantity and the settings, as 16 hex digits.
fn fingerprint(model: &Model, parameters: &[Parameter], settings: &SweepSettings) -> String {
    let mut text = serde_json::to_string(model).expect("models serialize");
    for p in parameters {
        text.push_str(&format!("\n{}={}", p.target, p.axis));
    }
    text.push_str(&format!(
        "\n{}\n{}\n{}\n{:?}\n{:?}\n{:?}",
        settings.quantity,
        settings.tracked_modes,
        settings.prestress,
        settings.method,
        settings.step,
        settings.end_time
    ));
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}
