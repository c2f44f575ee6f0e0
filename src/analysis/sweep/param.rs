//! Parameters of a sweep: which numbers of the model a value changes.
//!
//! A parameter is named in one of three ways:
//!
//! * a JSON path to a number of the model file (section 4 of the design),
//!   keys joined by dots and array elements as `[INDEX]` or `[ID]` (the
//!   element whose `"id"` is ID): `beams[blade].section.height`,
//!   `springs[0].stiffness`, `springs[main].b.ground[1]`, `gravity[1]`.
//!   An optional key the file leaves out (a pin's `torsion_stiffness`) may
//!   be named too; it is added with the value.
//! * a short name of `calibrate --param` (`height`, `blade.young`,
//!   `slot.mass`, …), resolved by [`crate::analysis::calibrate::params`]
//!   and then treated as its JSON path;
//! * `load_scale:ID[,ID…]` — the value multiplies the force of each named
//!   load (an id, or `loads[i]` for a load without one) and the preload of
//!   each named spring (by its id; the whole pre-stress of the switch-off
//!   scales with `load_scale:F_x2,F_c,helical_spring`): the paper's
//!   "pre-stress" factor. It only acts through a static equilibrium, so a
//!   sweep with it linearizes there.
//!
//! Values are SI, like the model file. Each point gets its own copy of the
//! model with the values written in; the copy is then parsed and validated
//! like a model file, so a value the model cannot take (a negative height)
//! fails that point with the validation message, not the sweep.

use super::error::{PointError, SweepError};
use super::grid::Axis;
use crate::analysis::calibrate::params::{available_names, resolve_name};
use crate::analysis::calibrate::CalibrationError;
use crate::model::Model;
use serde_json::{Map, Number, Value};

/// One step of a resolved path.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Step {
    Key(String),
    Index(usize),
}

/// What a value does to one number of the model.
#[derive(Debug, Clone, PartialEq)]
enum Op {
    /// The value replaces the number.
    Set,
    /// The value multiplies the model's number `base`.
    Scale { base: f64 },
    /// The value is added to the model's number `base` (`NAME+=…`).
    Shift { base: f64 },
}

/// One number a parameter changes.
#[derive(Debug, Clone, PartialEq)]
struct Edit {
    path: Vec<Step>,
    op: Op,
    /// The model holds a whole number here (e.g. `elements`): whole values
    /// are written as integers.
    integer: bool,
}

/// A resolved parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    /// As the user wrote it (before `=`).
    pub name: String,
    /// Canonical form: the JSON path with indices, or
    /// `load_scale:loads[i],…`; two names of the same number agree here.
    pub target: String,
    pub axis: Axis,
    /// Whether this is a `load_scale:` (pre-stress) parameter.
    pub scales_loads: bool,
    edits: Vec<Edit>,
}

impl Parameter {
    /// Resolves `NAME=LO:HI:N[:log]` against `model` (JSON form `json`);
    /// `NAME+=LO:HI:N` adds the values to the model's number (an offset,
    /// e.g. a point moved by 0 → −1 mm).
    pub fn parse(model: &Model, json: &Value, given: &str) -> Result<Parameter, SweepError> {
        let (name, range) = given
            .split_once('=')
            .ok_or_else(|| SweepError::ParamSyntax {
                given: given.to_string(),
            })?;
        let (name, offset) = match name.trim().strip_suffix('+') {
            Some(n) => (n.trim(), true),
            None => (name.trim(), false),
        };
        if name.is_empty() {
            return Err(SweepError::ParamSyntax {
                given: given.to_string(),
            });
        }
        let axis = Axis::parse(range, given)?;
        let (target, edits, scales_loads) = match name.strip_prefix("load_scale:") {
            Some(_) if offset => {
                return Err(SweepError::ParamSyntax {
                    given: given.to_string(),
                })
            }
            Some(ids) => {
                let (t, e) = load_scale(model, json, name, ids)?;
                (t, e, true)
            }
            None => {
                let path = resolve_number(model, json, name)?;
                let mut target = display(&path);
                let current = get(json, &path);
                let integer = current.is_some_and(|v| v.is_i64() || v.is_u64());
                let op = match (offset, current.and_then(Value::as_f64)) {
                    (false, _) => Op::Set,
                    (true, Some(base)) => Op::Shift { base },
                    (true, None) => {
                        return Err(SweepError::NoValueToOffset {
                            name: name.to_string(),
                            path: target,
                        })
                    }
                };
                let lowest = match op {
                    Op::Shift { base } => base + axis.lo,
                    _ => axis.lo,
                };
                if offset {
                    target.push_str(" offset");
                }
                let edit = Edit { path, op, integer };
                check_settable(json, name, &target, &edit, lowest)?;
                (target, vec![edit], false)
            }
        };
        Ok(Parameter {
            name: if offset {
                format!("{name}+")
            } else {
                name.to_string()
            },
            target,
            axis,
            scales_loads,
            edits,
        })
    }

    /// Whether `self` and `other` change a common number.
    pub fn overlaps(&self, other: &Parameter) -> bool {
        self.edits
            .iter()
            .any(|a| other.edits.iter().any(|b| a.path == b.path))
    }

    /// Writes `value` into the JSON form of a model.
    fn write(&self, json: &mut Value, value: f64) {
        for e in &self.edits {
            let v = match e.op {
                Op::Set => value,
                Op::Scale { base } => base * value,
                Op::Shift { base } => base + value,
            };
            if let Some(slot) = slot_mut(json, &e.path) {
                *slot = number(v, e.integer);
            }
        }
    }
}

/// The model with each parameter at its value: written into a copy of the
/// JSON form `base`, then parsed and validated as a model file is.
pub fn apply(base: &Value, params: &[Parameter], values: &[f64]) -> Result<Model, PointError> {
    let mut json = base.clone();
    for (p, &v) in params.iter().zip(values) {
        p.write(&mut json, v);
    }
    let model: Model = serde_json::from_value(json).map_err(|e| PointError::Schema {
        message: e.to_string(),
    })?;
    model
        .validate()
        .map_err(|(path, problem)| PointError::Invalid { path, problem })?;
    Ok(model)
}

/// A JSON number; whole values where the model holds an integer.
fn number(v: f64, integer: bool) -> Value {
    if integer && v.fract() == 0.0 && v.abs() < 9.0e15 {
        return Value::from(v as i64);
    }
    Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// The path of a number named by a JSON path or a short name.
fn resolve_number(model: &Model, json: &Value, name: &str) -> Result<Vec<Step>, SweepError> {
    let looks_like_path = name.contains('[');
    if !looks_like_path {
        match resolve_name(model, name) {
            Ok((_, target)) => return resolve_path(json, name, &target.json_path()),
            Err(CalibrationError::AmbiguousParameter { candidates, .. }) => {
                return Err(SweepError::AmbiguousParameter {
                    name: name.to_string(),
                    candidates,
                })
            }
            Err(_) => {}
        }
    }
    // A first key the model file does not have: not meant as a path.
    let first = name.split(['.', '[']).next().unwrap_or_default().trim();
    if json.get(first).is_none() {
        return Err(SweepError::UnknownParameter {
            name: name.to_string(),
            short_names: available_names(model),
        });
    }
    resolve_path(json, name, name)
}

/// `[ID]`/`[INDEX]` element or key of a path as written.
enum Written<'a> {
    Key(&'a str),
    Element(&'a str),
}

/// Splits `a.b[c][2].d` into its steps.
fn split_path<'a>(name: &str, text: &'a str) -> Result<Vec<Written<'a>>, SweepError> {
    let err = |at: &str| SweepError::PathSyntax {
        name: name.to_string(),
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

/// Resolves a written path against the model's JSON: ids become indices.
/// The end must be a number, or a key the object leaves out.
fn resolve_path(json: &Value, name: &str, text: &str) -> Result<Vec<Step>, SweepError> {
    let written = split_path(name, text)?;
    let mut path = Vec::with_capacity(written.len());
    let mut at = Some(json);
    let count = written.len();
    for (n, w) in written.into_iter().enumerate() {
        let last = n + 1 == count;
        let here = display(&path);
        let not_found = |what: String, available: Vec<String>| SweepError::PathNotFound {
            name: name.to_string(),
            path: if here.is_empty() {
                what
            } else {
                format!("{here}{what}")
            },
            available,
        };
        let current = at.ok_or_else(|| not_found(String::new(), vec![]))?;
        match w {
            Written::Key(k) => {
                let Value::Object(map) = current else {
                    return Err(not_found(format!(".{k}"), vec![]));
                };
                let sep = if path.is_empty() { "" } else { "." };
                match map.get(k) {
                    Some(v) => at = Some(v),
                    // An optional key the file left out: only at the end.
                    None if last => at = None,
                    None => {
                        return Err(not_found(
                            format!("{sep}{k}"),
                            map.keys().cloned().collect(),
                        ))
                    }
                }
                path.push(Step::Key(k.to_string()));
            }
            Written::Element(token) => {
                let Value::Array(items) = current else {
                    return Err(not_found(format!("[{token}]"), vec![]));
                };
                let index = match token.parse::<usize>() {
                    Ok(i) if i < items.len() => Some(i),
                    Ok(_) => None,
                    Err(_) => items
                        .iter()
                        .position(|v| v.get("id") == Some(&Value::from(token))),
                };
                let Some(index) = index else {
                    let ids: Vec<String> = items
                        .iter()
                        .enumerate()
                        .map(|(i, v)| match v.get("id").and_then(Value::as_str) {
                            Some(id) => format!("[{id}]"),
                            None => format!("[{i}]"),
                        })
                        .collect();
                    return Err(not_found(format!("[{token}]"), ids));
                };
                at = items.get(index);
                path.push(Step::Index(index));
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
    Err(SweepError::NotNumeric {
        name: name.to_string(),
        path: display(&path),
        kind,
    })
}

/// Refuses a path the model file cannot hold a number at (e.g. an unknown
/// key added at the end): the model with `value` written in must parse.
fn check_settable(
    json: &Value,
    name: &str,
    target: &str,
    edit: &Edit,
    value: f64,
) -> Result<(), SweepError> {
    let mut trial = json.clone();
    if let Some(slot) = slot_mut(&mut trial, &edit.path) {
        *slot = number(value, edit.integer);
    }
    serde_json::from_value::<Model>(trial)
        .map(drop)
        .map_err(|e| SweepError::NotSettable {
            name: name.to_string(),
            path: target.to_string(),
            message: e.to_string(),
        })
}

/// The names `load_scale:` accepts for the model's loads: the id, or
/// `loads[i]` for a load without one.
pub fn load_labels(model: &Model) -> Vec<String> {
    model
        .loads
        .iter()
        .enumerate()
        .map(|(i, l)| l.id.clone().unwrap_or_else(|| format!("loads[{i}]")))
        .collect()
}

/// The edits of `load_scale:ID[,ID…]`.
fn load_scale(
    model: &Model,
    json: &Value,
    name: &str,
    ids: &str,
) -> Result<(String, Vec<Edit>), SweepError> {
    let labels = load_labels(model);
    let mut indices = Vec::new();
    // Springs with a preload, by id: the pre-stress they carry scales too.
    let mut springs = Vec::new();
    for id in ids.split(',').map(str::trim) {
        let spring = model
            .springs
            .iter()
            .position(|s| s.id.as_deref() == Some(id) && s.preload.is_some());
        if let Some(k) = spring {
            if !springs.contains(&k) {
                springs.push(k);
            }
            continue;
        }
        let i = labels
            .iter()
            .position(|l| l == id)
            .or_else(|| {
                let inner = id.strip_prefix("loads[")?.strip_suffix(']')?;
                inner.parse::<usize>().ok().filter(|&i| i < labels.len())
            })
            .ok_or_else(|| SweepError::UnknownLoad {
                name: name.to_string(),
                id: id.to_string(),
                available: labels.clone(),
            })?;
        if !indices.contains(&i) {
            indices.push(i);
        }
    }
    indices.sort_unstable();
    springs.sort_unstable();
    let mut edits = Vec::new();
    for &i in &indices {
        for c in 0..2 {
            let path = vec![
                Step::Key("loads".into()),
                Step::Index(i),
                Step::Key("force".into()),
                Step::Index(c),
            ];
            let base = get(json, &path).and_then(Value::as_f64).unwrap_or(0.0);
            edits.push(Edit {
                path,
                op: Op::Scale { base },
                integer: false,
            });
        }
    }
    for &k in &springs {
        let path = vec![
            Step::Key("springs".into()),
            Step::Index(k),
            Step::Key("preload".into()),
        ];
        let base = get(json, &path).and_then(Value::as_f64).unwrap_or(0.0);
        edits.push(Edit {
            path,
            op: Op::Scale { base },
            integer: false,
        });
    }
    let target: Vec<String> = indices
        .iter()
        .map(|i| format!("loads[{i}]"))
        .chain(springs.iter().map(|k| format!("springs[{k}]")))
        .collect();
    Ok((format!("load_scale:{}", target.join(",")), edits))
}

fn get<'a>(json: &'a Value, path: &[Step]) -> Option<&'a Value> {
    path.iter().try_fold(json, |v, s| match s {
        Step::Key(k) => v.get(k.as_str()),
        Step::Index(i) => v.get(*i),
    })
}

/// The value at `path`, creating a missing last key.
fn slot_mut<'a>(json: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    let (last, head) = path.split_last()?;
    let parent = head.iter().try_fold(json, |v, s| match s {
        Step::Key(k) => v.get_mut(k.as_str()),
        Step::Index(i) => v.get_mut(*i),
    })?;
    match last {
        Step::Key(k) => match parent {
            Value::Object(map) => Some(map_entry(map, k)),
            _ => None,
        },
        Step::Index(i) => parent.get_mut(*i),
    }
}

fn map_entry<'a>(map: &'a mut Map<String, Value>, key: &str) -> &'a mut Value {
    map.entry(key.to_string()).or_insert(Value::Null)
}

/// `beams[0].section.height`.
fn display(path: &[Step]) -> String {
    let mut s = String::new();
    for step in path {
        match step {
            Step::Key(k) if s.is_empty() => s.push_str(k),
            Step::Key(k) => {
                s.push('.');
                s.push_str(k);
            }
            Step::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn resolve(name: &str) -> Result<Parameter, SweepError> {
        let m = Model::builtin();
        let json = serde_json::to_value(&m).unwrap();
        Parameter::parse(&m, &json, &format!("{name}=1:2:3"))
    }

    #[test]
    fn all_spellings_of_one_number_agree() {
        for name in [
            "height",
            "blade.height",
            "blade.section.height",
            "beams[blade].section.height",
            "beams[0].section.height",
        ] {
            assert_eq!(
                resolve(name).unwrap().target,
                "beams[0].section.height",
                "{name}"
            );
        }
        assert_eq!(resolve("gravity[1]").unwrap().target, "gravity[1]");
        assert_eq!(
            resolve("load_scale:loads[0]").unwrap().target,
            "load_scale:loads[0]"
        );
    }

    #[test]
    fn bad_names_say_why() {
        assert!(matches!(
            resolve("colour"),
            Err(SweepError::UnknownParameter { .. })
        ));
        assert!(matches!(
            resolve("mass"),
            Err(SweepError::AmbiguousParameter { .. })
        ));
        assert!(matches!(
            resolve("beams[wing].section.height"),
            Err(SweepError::PathNotFound { .. })
        ));
        assert!(matches!(
            resolve("beams[0].section"),
            Err(SweepError::NotNumeric { .. })
        ));
        assert!(matches!(
            resolve("beams[0].id"),
            Err(SweepError::NotNumeric { .. })
        ));
        assert!(matches!(
            resolve("beams[0].colour"),
            Err(SweepError::NotSettable { .. })
        ));
        assert!(matches!(
            resolve("beams[0.height"),
            Err(SweepError::PathSyntax { .. })
        ));
        assert!(matches!(
            resolve("load_scale:nope"),
            Err(SweepError::UnknownLoad { .. })
        ));
    }

    #[test]
    fn an_offset_adds_to_the_models_number() {
        let m = Model::builtin();
        let json = serde_json::to_value(&m).unwrap();
        let base = m.beams[0].section.height;
        let p = Parameter::parse(&m, &json, "beams[0].section.height+=-1e-4:1e-4:3").unwrap();
        assert_eq!(p.name, "beams[0].section.height+");
        assert_ne!(
            p.target, "beams[0].section.height",
            "an offset is its own target"
        );
        for v in [-1e-4, 0.0, 1e-4] {
            let out = apply(&json, std::slice::from_ref(&p), &[v]).unwrap();
            assert_eq!(out.beams[0].section.height, base + v);
        }
        assert!(matches!(
            Parameter::parse(&m, &json, "load_scale:loads[0]+=0:1:2"),
            Err(SweepError::ParamSyntax { .. })
        ));
    }

    #[test]
    fn apply_writes_values_and_validates() {
        let m = Model::builtin();
        let json = serde_json::to_value(&m).unwrap();
        let p = Parameter::parse(&m, &json, "beams[0].elements=2:6:3").unwrap();
        let q = Parameter::parse(&m, &json, "load_scale:loads[0]=0:2:3").unwrap();
        let out = apply(&json, &[p.clone(), q], &[4.0, 2.0]).unwrap();
        assert_eq!(out.beams[0].elements, 4);
        assert_eq!(out.loads[0].force[1], 2.0 * m.loads[0].force[1]);
        assert!(matches!(
            apply(&json, std::slice::from_ref(&p), &[4.5]),
            Err(PointError::Schema { .. })
        ));
        let h = Parameter::parse(&m, &json, "height=1:2:3").unwrap();
        assert!(matches!(
            apply(&json, &[h], &[-1e-3]),
            Err(PointError::Invalid { .. })
        ));
    }
}
