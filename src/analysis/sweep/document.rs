//! The JSON document of a sweep (design section 8), the result of a run
//! ([`SweepRun`]) and the joining of shards ([`merge`]).
//!
//! A complete run's document has, per point, its parameter values, the
//! quantity (`result`, `null` where the point failed, with `error`) and for
//! tracked quantities the frequencies of all tracked modes and their MAC
//! with the previous point. A shard's document (`"shard": {"index",
//! "count"}`) has instead the computed elastic modes with their shapes
//! (`modes`), which tracking needs; [`merge`] joins shards back into a run
//! and tracks it, so the merged document is the one a single run prints.

use super::error::SweepError;
use super::grid::{coordinates, Shard};
use super::quantity::{Evaluation, Quantity, RawMode, Trace};
use super::tracking::{track, TrackedMode};
use serde::{Deserialize, Serialize};

/// A sweep as a JSON document.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SweepDocument {
    /// The model's name.
    pub model: String,
    /// The quantity's name (`first_bending_hz`, `frequency:K`).
    pub quantity: String,
    /// Fingerprint of the model, the parameters and the settings.
    pub sweep_id: String,
    /// Points of the whole grid.
    pub total_points: usize,
    /// The varied parameters and their values.
    pub parameters: Vec<ParameterValues>,
    /// Linearized at the static equilibrium under the loads.
    pub prestress: bool,
    /// Elastic modes tracked (tracked quantities).
    #[serde(default)]
    pub tracked_modes: Option<usize>,
    /// Points of this document that failed.
    pub failed_points: usize,
    /// Which shard this is (shard documents only).
    #[serde(default)]
    pub shard: Option<ShardInfo>,
    /// Provenance (set by the command line): this build's version and the
    /// SHA-256 of the model file (or of the built-in model's text).
    #[serde(default)]
    pub tool_version: Option<String>,
    /// SHA-256 (hex) of the model's bytes (set by the command line).
    #[serde(default)]
    pub model_sha256: Option<String>,
    /// The run's warnings (set by the command line): the model's unit
    /// warnings and those of the points.
    #[serde(default)]
    pub warnings: Vec<String>,
    /// The points of this document, by index.
    pub points: Vec<PointRecord>,
}

/// One parameter's name and values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ParameterValues {
    /// As given (`height`, `beams[blade].section.height`, `load_scale:F`).
    pub name: String,
    /// Canonical form (`beams[0].section.height`).
    pub target: String,
    /// SI, as in the model file.
    pub values: Vec<f64>,
    /// Spaced logarithmically (`:log`).
    pub log: bool,
}

/// `K/N` of a shard.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ShardInfo {
    /// K, 1-based [–].
    pub index: usize,
    /// N, the number of shards [–].
    pub count: usize,
}

/// One point of a sweep document.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PointRecord {
    /// Row-major index in the grid.
    pub index: usize,
    /// Parameter values, in `--param` order.
    pub values: Vec<f64>,
    /// The quantity; `null` for a failed point (and in a shard, for a
    /// tracked quantity).
    pub result: Option<f64>,
    /// Why the point failed; null when it did not.
    #[serde(default)]
    pub error: Option<String>,
    /// Frequencies of the tracked modes [Hz] (tracked quantities).
    #[serde(default)]
    pub frequencies_hz: Option<Vec<Option<f64>>>,
    /// MAC of each tracked mode with the same mode at the point it was
    /// tracked from (`null` where tracking starts).
    #[serde(default)]
    pub mac: Option<Vec<Option<f64>>>,
    /// Computed elastic modes (shard documents of tracked quantities).
    #[serde(default)]
    pub modes: Option<Vec<RawMode>>,
    /// The switch-off's tracked point (`time_to_distance_s` over one
    /// parameter).
    #[serde(default)]
    pub node0: Option<Trace>,
    /// Unit-sanity warnings of the model at this point
    /// ([`crate::model::UnitWarning`]), as text.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// What every point of a sweep shares.
#[derive(Debug, Clone, PartialEq)]
pub struct Header {
    pub model: String,
    pub quantity: Quantity,
    pub sweep_id: String,
    pub parameters: Vec<ParameterValues>,
    pub prestress: bool,
    /// Elastic modes tracked (tracked quantities).
    pub tracked_modes: Option<usize>,
}

impl Header {
    /// Values per parameter.
    pub fn shape(&self) -> Vec<usize> {
        self.parameters.iter().map(|p| p.values.len()).collect()
    }

    pub fn total_points(&self) -> usize {
        self.shape().iter().product()
    }

    /// Parameter values of point `index`.
    pub fn values(&self, index: usize) -> Vec<f64> {
        coordinates(&self.shape(), index)
            .iter()
            .zip(&self.parameters)
            .map(|(&i, p)| p.values[i])
            .collect()
    }
}

/// One computed point.
#[derive(Debug, Clone, PartialEq)]
pub struct RawPoint {
    pub index: usize,
    pub values: Vec<f64>,
    /// The evaluation, or the error message.
    pub outcome: Result<Evaluation, String>,
    /// Unit-sanity warnings of the model at this point, as text.
    pub warnings: Vec<String>,
}

/// The points a run computed (all, or one shard's).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRun {
    pub header: Header,
    pub shard: Option<Shard>,
    /// In index order.
    pub points: Vec<RawPoint>,
}

impl SweepRun {
    /// Points that failed.
    pub fn failed(&self) -> usize {
        self.points.iter().filter(|p| p.outcome.is_err()).count()
    }

    /// The document: tracked if complete, with the modes if a shard.
    pub fn document(&self) -> SweepDocument {
        let h = &self.header;
        let points = match self.shard {
            Some(_) => self.points.iter().map(shard_record).collect(),
            None => self.tracked_records(),
        };
        SweepDocument {
            model: h.model.clone(),
            quantity: h.quantity.to_string(),
            sweep_id: h.sweep_id.clone(),
            total_points: h.total_points(),
            parameters: h.parameters.clone(),
            prestress: h.prestress,
            tracked_modes: h.tracked_modes,
            failed_points: self.failed(),
            shard: self.shard.map(|s| ShardInfo {
                index: s.index,
                count: s.count,
            }),
            tool_version: None,
            model_sha256: None,
            warnings: Vec::new(),
            points,
        }
    }

    /// Records of a complete run (tracking applied).
    fn tracked_records(&self) -> Vec<PointRecord> {
        let h = &self.header;
        let (Some(k), Some(n)) = (h.quantity.tracked_mode(), h.tracked_modes) else {
            return self.points.iter().map(|p| record(p, None)).collect();
        };
        let modes: Vec<Option<&[RawMode]>> = self
            .points
            .iter()
            .map(|p| p.outcome.as_ref().ok().map(|e| e.modes.as_slice()))
            .collect();
        let tracked = track(&h.shape(), &modes, n);
        self.points
            .iter()
            .zip(tracked)
            .map(|(p, t)| {
                let mut r = record(p, t.as_deref());
                if let Some(t) = t {
                    r.result = t.get(k - 1).copied().flatten().map(|m| m.frequency_hz);
                }
                r
            })
            .collect()
    }
}

fn record(p: &RawPoint, tracked: Option<&[Option<TrackedMode>]>) -> PointRecord {
    let freq = |t: &[Option<TrackedMode>]| t.iter().map(|m| m.map(|m| m.frequency_hz)).collect();
    let mac = |t: &[Option<TrackedMode>]| t.iter().map(|m| m.and_then(|m| m.mac)).collect();
    PointRecord {
        index: p.index,
        values: p.values.clone(),
        result: p.outcome.as_ref().ok().and_then(|e| e.value),
        error: p.outcome.as_ref().err().cloned(),
        frequencies_hz: tracked.map(freq),
        mac: tracked.map(mac),
        modes: None,
        node0: p.outcome.as_ref().ok().and_then(|e| e.trace.clone()),
        warnings: p.warnings.clone(),
    }
}

fn shard_record(p: &RawPoint) -> PointRecord {
    let modes = p
        .outcome
        .as_ref()
        .ok()
        .filter(|e| !e.modes.is_empty())
        .map(|e| e.modes.clone());
    PointRecord {
        modes,
        ..record(p, None)
    }
}

/// Joins shard documents (each with the name of its file, for messages)
/// into the complete run. Refuses documents that are not shards, shards of
/// different sweeps or shard counts, points that do not belong where they
/// are, duplicate and missing points.
pub fn merge(shards: &[(String, SweepDocument)]) -> Result<SweepRun, SweepError> {
    let (first_file, first) = shards.first().ok_or(SweepError::NothingToMerge)?;
    let info = |file: &str, d: &SweepDocument| {
        d.shard.ok_or_else(|| SweepError::NotAShard {
            file: file.to_string(),
        })
    };
    let count = info(first_file, first)?.count;
    let header = Header {
        model: first.model.clone(),
        quantity: Quantity::parse(&first.quantity).map_err(|e| SweepError::NotADocument {
            file: first_file.clone(),
            message: e.to_string(),
        })?,
        sweep_id: first.sweep_id.clone(),
        parameters: first.parameters.clone(),
        prestress: first.prestress,
        tracked_modes: first.tracked_modes,
    };
    let total = header.total_points();
    let mut slots: Vec<Option<(RawPoint, &str)>> = vec![None; total];
    for (file, d) in shards {
        let s = info(file, d)?;
        let same = d.sweep_id == first.sweep_id
            && s.count == count
            && d.parameters == first.parameters
            && d.quantity == first.quantity;
        if !same {
            return Err(SweepError::DifferentSweep {
                file: file.clone(),
                found: format!("{} (shard {}/{})", d.sweep_id, s.index, s.count),
                expected: format!("{} (shard count {count})", first.sweep_id),
                first: first_file.clone(),
            });
        }
        for r in &d.points {
            let bad = |why: String| SweepError::InconsistentPoint {
                file: file.clone(),
                index: r.index,
                why,
            };
            if r.index >= total {
                return Err(bad(format!("the grid has {total} points")));
            }
            if Shard::of(r.index, count) != s.index {
                return Err(bad(format!(
                    "it belongs to shard {}/{count}",
                    Shard::of(r.index, count)
                )));
            }
            if r.values != header.values(r.index) {
                return Err(bad(format!(
                    "values {:?}, the grid has {:?}",
                    r.values,
                    header.values(r.index)
                )));
            }
            if let Some((_, other)) = &slots[r.index] {
                return Err(SweepError::DuplicatePoint {
                    index: r.index,
                    first: other.to_string(),
                    second: file.clone(),
                });
            }
            let outcome = match &r.error {
                Some(e) => Err(e.clone()),
                None => Ok(Evaluation {
                    value: r.result,
                    modes: r.modes.clone().unwrap_or_default(),
                    trace: r.node0.clone(),
                }),
            };
            let point = RawPoint {
                index: r.index,
                values: r.values.clone(),
                outcome,
                warnings: r.warnings.clone(),
            };
            slots[r.index] = Some((point, file.as_str()));
        }
    }
    let missing: Vec<usize> = (0..total).filter(|&i| slots[i].is_none()).collect();
    if !missing.is_empty() {
        let mut missing_shards: Vec<usize> = missing.iter().map(|&i| Shard::of(i, count)).collect();
        missing_shards.sort_unstable();
        missing_shards.dedup();
        return Err(SweepError::MissingPoints {
            count: missing.len(),
            total,
            first_missing: missing.iter().copied().take(5).collect(),
            missing_shards,
            shards: count,
        });
    }
    Ok(SweepRun {
        header,
        shard: None,
        points: slots.into_iter().flatten().map(|(p, _)| p).collect(),
    })
}
