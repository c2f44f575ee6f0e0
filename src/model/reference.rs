//! The paper's reference values (Skrinjar, Slavič, Boltežar, Tables 1–4),
//! embedded from `reference/paper_tables.json`.

use serde_json::Value;

/// Paper, Fig. 7: node 0 travels ~2 mm in ~1.75 ms at switch-off [SI: s].
pub const PAPER_TIME_TO_2MM_S: f64 = 1.75e-3;
/// Paper, Fig. 8: the rigid model departs from the measurement after
/// ~1.26 ms [SI: s].
pub const PAPER_RIGID_DEPARTURE_S: f64 = 1.26e-3;

/// The reference file's text.
pub const PAPER_TABLES_JSON: &str = include_str!("../../reference/paper_tables.json");

/// Table 3: first bending frequency of the free-free assembly [SI: Hz].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Table3 {
    pub experiment_hz: f64,
    pub ancf_hz: f64,
    pub ansys_hz: f64,
}

fn tables() -> Value {
    serde_json::from_str(PAPER_TABLES_JSON).expect("the embedded reference file is valid JSON")
}

/// The paper's Table 3.
pub fn table3() -> Table3 {
    let t = &tables()["table3_first_bending_free_free"];
    let get = |k: &str| t[k].as_f64().expect("Table 3 entries are numbers");
    Table3 {
        experiment_hz: get("experiment_hz"),
        ancf_hz: get("ancf_hz"),
        ansys_hz: get("ansys_beam188_hz"),
    }
}

/// The source citation of the reference file.
pub fn source() -> String {
    tables()["source"].as_str().unwrap_or_default().to_string()
}

/// The two error conventions of a model frequency against an experiment.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct Errors {
    /// (model − experiment)/experiment × 100 [%].
    pub error_percent: f64,
    /// (experiment − model)/model × 100 [%], the paper's convention.
    pub paper_error_percent: f64,
}

impl Errors {
    pub fn new(model_hz: f64, experiment_hz: f64) -> Errors {
        Errors {
            error_percent: 100.0 * (model_hz - experiment_hz) / experiment_hz,
            paper_error_percent: 100.0 * (experiment_hz - model_hz) / model_hz,
        }
    }
}
