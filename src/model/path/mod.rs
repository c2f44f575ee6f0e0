//! Names of the model's numbers: one parser, one resolver, one reader and
//! writer, used by calibration, sweeps and the Python package.
//!
//! A parameter is named in one of two ways:
//!
//! * a **JSON path** to a number of the model file (section 4 of the
//!   design), keys joined by dots and array elements as `[INDEX]` or `[ID]`
//!   (the element whose `"id"` is ID): `beams[blade].section.height`,
//!   `springs[0].stiffness`, `springs[main].b.ground[1]`, `gravity[1]`. An
//!   optional key the file leaves out (a pin's `torsion_stiffness`) may be
//!   named too: it is added when a value is written.
//! * a **short name** `[ID.][GROUP.]PROPERTY` ([`short`]: `height`,
//!   `blade.young`, `slot.mass`), which stands for its JSON path.
//!
//! Either resolves to a [`NumberPath`], its canonical form with indices
//! (`beams[0].section.height`); two names of one number resolve to the same
//! path. Values are SI, as in the model file (m, kg, s, N, Pa; see the
//! short-name table for each property's unit). A path reads and writes the
//! model's JSON form through serde_json's JSON pointers; a short name's
//! [`Target`] also reads and writes the typed [`Model`] directly, and both
//! give the same number.

pub mod error;
pub mod short;

pub use error::PathError;
pub use short::{available_names, resolve_short, Property, Target, PROPERTIES};

use crate::model::Model;
use serde_json::Value;
use std::fmt;

/// One step of a resolved path.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Step {
    Key(String),
    Index(usize),
}

/// A resolved path to a number of the model file: keys and indices.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct NumberPath(Vec<Step>);

impl NumberPath {
    pub fn new(steps: Vec<Step>) -> Self {
        NumberPath(steps)
    }

    pub fn steps(&self) -> &[Step] {
        &self.0
    }

    /// Resolves a short name or a JSON path against the model (`json` is
    /// its JSON form). A name without `[` is first tried as a short name;
    /// the path must end at a number, or at a key its object leaves out.
    pub fn resolve(model: &Model, json: &Value, name: &str) -> Result<NumberPath, PathError> {
        if !name.contains('[') {
            match resolve_short(model, name) {
                Ok((_, target)) => return Ok(target.path()),
                Err(e @ PathError::Ambiguous { .. }) => return Err(e),
                Err(_) => {}
            }
        }
        // A first key the model file does not have: not meant as a path.
        let first = name.split(['.', '[']).next().unwrap_or_default().trim();
        if json.get(first).is_none() {
            return Err(PathError::Unknown {
                name: name.to_string(),
                short_names: available_names(model),
            });
        }
        Self::resolve_json(json, name)
    }

    /// Resolves a JSON path (`beams[blade].section.height`) against the
    /// model's JSON form: ids become indices.
    pub fn resolve_json(json: &Value, name: &str) -> Result<NumberPath, PathError> {
        let written = split(name)?;
        let mut path = NumberPath(Vec::with_capacity(written.len()));
        let mut at = Some(json);
        let count = written.len();
        for (n, w) in written.into_iter().enumerate() {
            let here = path.to_string();
            let not_found = |what: String, available: Vec<String>| PathError::NotFound {
                name: name.to_string(),
                path: format!("{here}{what}"),
                available,
            };
            let current = at.ok_or_else(|| not_found(String::new(), vec![]))?;
            match w {
                Written::Key(k) => {
                    let Value::Object(map) = current else {
                        return Err(not_found(format!(".{k}"), vec![]));
                    };
                    let sep = if path.0.is_empty() { "" } else { "." };
                    at = match map.get(k) {
                        Some(v) => Some(v),
                        // An optional key the file left out: only at the end.
                        None if n + 1 == count => None,
                        None => {
                            let keys = map.keys().cloned().collect();
                            return Err(not_found(format!("{sep}{k}"), keys));
                        }
                    };
                    path.0.push(Step::Key(k.to_string()));
                }
                Written::Element(token) => {
                    let Value::Array(items) = current else {
                        return Err(not_found(format!("[{token}]"), vec![]));
                    };
                    let Some(index) = element(items, token) else {
                        return Err(not_found(format!("[{token}]"), labels(items)));
                    };
                    at = items.get(index);
                    path.0.push(Step::Index(index));
                }
            }
        }
        let kind = match at {
            None | Some(Value::Null) | Some(Value::Number(_)) => return Ok(path),
            Some(Value::Bool(_)) => "a true/false value",
            Some(Value::String(_)) => "a text",
            Some(Value::Array(_)) => "a list (name one element, e.g. [0])",
            Some(Value::Object(_)) => "a group of values (name one of its keys)",
        };
        Err(PathError::NotNumeric {
            name: name.to_string(),
            path: path.to_string(),
            kind,
        })
    }

    /// The JSON pointer (RFC 6901): `/beams/0/section/height`.
    pub fn pointer(&self) -> String {
        pointer(&self.0)
    }

    /// The value at the path in `json` (`None` for a key left out).
    pub fn get<'a>(&self, json: &'a Value) -> Option<&'a Value> {
        json.pointer(&self.pointer())
    }

    /// The number at the path in `json`.
    pub fn number(&self, json: &Value) -> Option<f64> {
        self.get(json).and_then(Value::as_f64)
    }

    /// Writes `value` at the path, adding a missing last key; `false` when
    /// the path's parent is not in `json`.
    pub fn set(&self, json: &mut Value, value: Value) -> bool {
        let Some((last, head)) = self.0.split_last() else {
            return false;
        };
        let Some(parent) = json.pointer_mut(&pointer(head)) else {
            return false;
        };
        let slot = match (last, parent) {
            (Step::Key(k), Value::Object(map)) => map.entry(k.clone()).or_insert(Value::Null),
            (Step::Index(i), Value::Array(items)) => match items.get_mut(*i) {
                Some(v) => v,
                None => return false,
            },
            _ => return false,
        };
        *slot = value;
        true
    }

    /// Refuses a path the model file cannot hold `value` at (e.g. an
    /// unknown key added at the end, a fraction for a count): the model's
    /// JSON form `json` with the value written in must parse as a model.
    /// `name` is the parameter as given, for the error.
    pub fn check_settable(&self, json: &Value, name: &str, value: Value) -> Result<(), PathError> {
        let mut trial = json.clone();
        self.set(&mut trial, value);
        serde_json::from_value::<Model>(trial)
            .map(drop)
            .map_err(|e| PathError::NotSettable {
                name: name.to_string(),
                path: self.to_string(),
                message: e.to_string(),
            })
    }
}

/// `beams[0].section.height`.
impl fmt::Display for NumberPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (n, step) in self.0.iter().enumerate() {
            match step {
                Step::Key(k) if n == 0 => f.write_str(k)?,
                Step::Key(k) => write!(f, ".{k}")?,
                Step::Index(i) => write!(f, "[{i}]")?,
            }
        }
        Ok(())
    }
}

fn pointer(steps: &[Step]) -> String {
    let mut s = String::new();
    for step in steps {
        s.push('/');
        match step {
            Step::Key(k) => s.push_str(&k.replace('~', "~0").replace('/', "~1")),
            Step::Index(i) => s.push_str(&i.to_string()),
        }
    }
    s
}

/// The index of element `token` (`[INDEX]` or `[ID]`) of `items`.
fn element(items: &[Value], token: &str) -> Option<usize> {
    match token.parse::<usize>() {
        Ok(i) => (i < items.len()).then_some(i),
        Err(_) => items
            .iter()
            .position(|v| v.get("id") == Some(&Value::from(token))),
    }
}

/// The elements of a list as a path names them: `[ID]`, or `[INDEX]`.
fn labels(items: &[Value]) -> Vec<String> {
    items
        .iter()
        .enumerate()
        .map(|(i, v)| match v.get("id").and_then(Value::as_str) {
            Some(id) => format!("[{id}]"),
            None => format!("[{i}]"),
        })
        .collect()
}

/// A key or an `[ID]`/`[INDEX]` element of a path as written.
enum Written<'a> {
    Key(&'a str),
    Element(&'a str),
}

/// Splits `a.b[c][2].d` into its steps.
fn split(text: &str) -> Result<Vec<Written<'_>>, PathError> {
    let err = |at: &str| PathError::Syntax {
        name: text.to_string(),
        at: at.to_string(),
    };
    let mut steps = Vec::new();
    for segment in text.split('.') {
        let (key, mut rest) = match segment.find('[') {
            Some(i) => segment.split_at(i),
            None => (segment, ""),
        };
        if key.is_empty() || key.contains(']') {
            return Err(err(segment));
        }
        steps.push(Written::Key(key.trim()));
        while !rest.is_empty() {
            let inner = rest.strip_prefix('[').ok_or_else(|| err(rest))?;
            let close = inner.find(']').ok_or_else(|| err(rest))?;
            let token = inner[..close].trim();
            if token.is_empty() || token.contains('[') {
                return Err(err(rest));
            }
            steps.push(Written::Element(token));
            rest = &inner[close + 1..];
        }
    }
    Ok(steps)
}

#[cfg(test)]
mod tests;
