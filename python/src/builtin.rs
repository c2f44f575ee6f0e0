//! The shipped model files (`models/*.json`), by file stem.

/// (file stem, JSON text) of every file in `models/`; the Python suite
/// checks that the list is complete.
pub const MODELS: [(&str, &str); 6] = [
    ("rcbo_free_free", ancf::model::DEFAULT_MODEL_JSON),
    ("rcbo_switch_off", ancf::model::SWITCH_OFF_MODEL_JSON),
    (
        "rcbo_switch_off_uncalibrated",
        ancf::model::SWITCH_OFF_UNCALIBRATED_MODEL_JSON,
    ),
    (
        "rcbo_prestressed",
        include_str!("../../models/rcbo_prestressed.json"),
    ),
    (
        "beam_free_free",
        include_str!("../../models/beam_free_free.json"),
    ),
    ("cantilever", include_str!("../../models/cantilever.json")),
];

/// The JSON text of the shipped model `name`.
pub fn text(name: &str) -> Option<&'static str> {
    MODELS.iter().find(|(n, _)| *n == name).map(|(_, t)| *t)
}

/// The names, for a message.
pub fn names() -> String {
    MODELS
        .iter()
        .map(|(n, _)| *n)
        .collect::<Vec<_>>()
        .join(", ")
}
