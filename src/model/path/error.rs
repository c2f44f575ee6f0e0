//! Why a parameter name does not name a number of the model.

/// A parameter name that does not resolve, with the name as given and
/// what the model allows there. Messages are one line and name quantities,
/// never the flags or arguments they came from.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PathError {
    /// A short name (`[ID.][GROUP.]PROPERTY`) the model does not have.
    #[error("unknown parameter `{name}`; this model has: {}", available.join(", "))]
    UnknownShortName {
        name: String,
        /// The model's short names, canonical form.
        available: Vec<String>,
    },
    /// Neither a short name nor a path whose first key the model file has.
    #[error("unknown parameter `{name}`: give a JSON path to a number of the model (e.g. `beams[0].section.height`, `springs[ID].stiffness`) or a short name: {}", short_names.join(", "))]
    Unknown {
        name: String,
        short_names: Vec<String>,
    },
    /// A short name without an id that more than one element has.
    #[error("parameter `{name}` is ambiguous; name one of: {}", candidates.join(", "))]
    Ambiguous {
        name: String,
        candidates: Vec<String>,
    },
    #[error("`{name}`: malformed JSON path at `{at}` (write keys with dots and elements as [INDEX] or [ID], e.g. `beams[blade].section.height`)")]
    Syntax { name: String, at: String },
    /// A key or element the model does not have; `available` lists what is
    /// there (keys, or elements as `[ID]`/`[INDEX]`).
    #[error("`{name}`: the model has no `{path}`{}", hint_list(available))]
    NotFound {
        name: String,
        path: String,
        available: Vec<String>,
    },
    #[error("`{name}`: `{path}` is {kind}, not a number")]
    NotNumeric {
        name: String,
        path: String,
        kind: &'static str,
    },
    /// The model file cannot hold a number there (`message`: why, from the
    /// model's schema, naming the value).
    #[error("`{name}`: `{path}` cannot take a number: {message}")]
    NotSettable {
        name: String,
        path: String,
        message: String,
    },
}

fn hint_list(available: &[String]) -> String {
    if available.is_empty() {
        String::new()
    } else {
        format!(" (there: {})", available.join(", "))
    }
}
