//! What a model file says was calibrated to make it: the records
//! `calibrate` writes into the model it fits (`calibrated` in the file),
//! so that every output that runs the model can say which of its numbers
//! is a fit and to what, and never present a fitted result as agreement.
//!
//! A record holds while the model still has the fitted value at the
//! record's path (to 1e-12 relative) and, when the record carries one, the
//! same numbers as when it was fitted (`design_sha256`, the SHA-256 of the
//! model's JSON with its name, description and records left out): a model
//! edited after its calibration, at the fitted number or anywhere else, no
//! longer is the calibrated one, and a record that does not hold is
//! reported ([`super::UnitWarning::StaleCalibration`]) and left out of the
//! outputs ([`Model::calibrations`]).

use serde::{Deserialize, Serialize};

use super::path::NumberPath;
use super::Model;

/// One model quantity set so that a result hits a target: a fit, never
/// agreement.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Calibrated {
    /// Its JSON path in the model (`loads[0].at.s`).
    pub name: String,
    /// Its value [SI, as in the model file].
    pub value: f64,
    /// What it was set to reproduce ("time_to_distance_s = 1.75e-3 s (the
    /// paper's Fig. 7)", "the trajectory of FILE, 120 samples").
    pub target: String,
    /// What the fitted model gives for it ("time_to_distance_s =
    /// 1.7500e-3 s", "rms residual 1.2e-6 m").
    pub achieved: String,
    /// Standard error of the value [SI, as `value`] from the least-squares
    /// Jacobian and residual (a fit to several samples); `None` for a fit
    /// that meets one target exactly (no residual to estimate it from).
    #[serde(default)]
    pub standard_error: Option<f64>,
    /// [`Model::design_sha256`] of the fitted model (module doc); records
    /// without it hold on the value alone.
    #[serde(default)]
    pub design_sha256: Option<String>,
}

/// Relative agreement of a record's value with the model's number.
const HOLDS: f64 = 1e-12;

impl Model {
    /// The model's number at a record's path, `None` when the path does not
    /// resolve to a number.
    fn calibrated_number(&self, json: &serde_json::Value, record: &Calibrated) -> Option<f64> {
        NumberPath::resolve(self, json, &record.name)
            .ok()
            .and_then(|p| p.number(json))
    }

    /// The SHA-256 (hex) of the model's numbers and structure: its JSON
    /// with the name, the description and the calibration records left
    /// out.
    pub fn design_sha256(&self) -> String {
        use sha2::{Digest, Sha256};
        let mut json = serde_json::to_value(self).expect("models serialize");
        if let Some(o) = json.as_object_mut() {
            for key in ["name", "description", "calibrated"] {
                o.remove(key);
            }
        }
        let text = serde_json::to_string(&json).expect("JSON serializes");
        Sha256::digest(text.as_bytes())
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect()
    }

    /// Whether the model still has the record's value (and its design).
    fn holds(&self, json: &serde_json::Value, record: &Calibrated) -> bool {
        let value = self
            .calibrated_number(json, record)
            .is_some_and(|v| (v - record.value).abs() <= HOLDS * record.value.abs().max(1e-300));
        value
            && record
                .design_sha256
                .as_ref()
                .is_none_or(|h| *h == self.design_sha256())
    }

    /// The calibration records that hold (module doc), in file order.
    pub fn calibrations(&self) -> Vec<Calibrated> {
        if self.calibrated.is_empty() {
            return Vec::new();
        }
        let json = serde_json::to_value(self).expect("models serialize");
        self.calibrated
            .iter()
            .filter(|r| self.holds(&json, r))
            .cloned()
            .collect()
    }

    /// Each record that does not hold: its index, name, value and the
    /// model's number there (`None`: the path names no number).
    pub fn stale_calibrations(&self) -> Vec<(usize, Calibrated, Option<f64>)> {
        if self.calibrated.is_empty() {
            return Vec::new();
        }
        let json = serde_json::to_value(self).expect("models serialize");
        self.calibrated
            .iter()
            .enumerate()
            .filter(|(_, r)| !self.holds(&json, r))
            .map(|(k, r)| (k, r.clone(), self.calibrated_number(&json, r)))
            .collect()
    }

    /// The model with `records` added to what it says was calibrated,
    /// each stamped with the model's design (an earlier record of the same
    /// quantity is replaced; the others are stamped anew, as they still
    /// describe this design).
    pub fn with_calibrations(mut self, records: &[Calibrated]) -> Model {
        self.calibrated
            .retain(|old| records.iter().all(|r| r.name != old.name));
        self.calibrated.extend(records.iter().cloned());
        let design = self.design_sha256();
        for r in &mut self.calibrated {
            r.design_sha256 = Some(design.clone());
        }
        self
    }
}
