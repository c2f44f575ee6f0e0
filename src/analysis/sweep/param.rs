//! Parameters of a sweep: which numbers of the model a value changes.
//!
//! A parameter is named in one of three ways:
//!
//! * a JSON path to a number of the model file or a short name of
//!   `calibrate --param` (`height`, `blade.young`, `slot.mass`, …), both
//!   resolved by [`crate::model::path`] into the number's canonical path
//!   (`beams[0].section.height`);
//! * `load_scale:ID[,ID…]` — the value multiplies the force of each named
//!   load (an id, or `loads[i]` for a load without one) and the preload of
//!   each named spring (by its id; the whole pre-stress of the switch-off
//!   scales with `load_scale:F_x2,F_c,helical_spring`): the paper's
//!   "pre-stress" factor. It only acts through a static equilibrium, so a
//!   sweep with it linearizes there.
//!
//! A load's force, a spring's preload and gravity act through the static
//! equilibrium as `load_scale:` does, so a sweep over one of them
//! linearizes there too.
//!
//! `NAME+=…` adds the values to the model's number instead (an offset).
//!
//! Values are SI, like the model file. Each point gets its own copy of the
//! model with the values written in; the copy is then parsed and validated
//! like a model file, so a value the model cannot take (a negative height)
//! fails that point with the validation message, not the sweep.

use super::error::{PointError, SweepError};
use super::grid::Axis;
use crate::error::InvalidModel;
use crate::model::path::{NumberPath, PathError, Step};
use crate::model::{Model, ValidModel};
use serde_json::{Number, Value};

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
    path: NumberPath,
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
    /// Whether it changes what pre-stresses the model: `load_scale:`, a
    /// load's force, a spring's preload or gravity ([`pre_stresses`]).
    pub scales_loads: bool,
    edits: Vec<Edit>,
}

impl Parameter {
    /// Resolves `NAME=LO:HI:N[:log]` or `NAME=V1,V2,…` against `model`
    /// (JSON form `json`); `NAME+=…` adds the values to the model's number (an offset,
    /// e.g. a point moved by 0 → −1 mm).
    pub fn parse(model: &Model, json: &Value, given: &str) -> Result<Parameter, SweepError> {
        let syntax = || SweepError::ParamSyntax {
            given: given.to_string(),
        };
        let (name, range) = given.split_once('=').ok_or_else(syntax)?;
        let bare = name.trim();
        if bare.strip_suffix('+').unwrap_or(bare).trim().is_empty() {
            return Err(syntax());
        }
        let axis = Axis::parse(range, given)?;
        Parameter::resolve(model, json, name, axis).map_err(|e| match e {
            SweepError::ParamSyntax { .. } => syntax(),
            e => e,
        })
    }

    /// Resolves `NAME` (or `NAME+`, an offset) with the values of `axis`.
    pub fn resolve(
        model: &Model,
        json: &Value,
        name: &str,
        axis: Axis,
    ) -> Result<Parameter, SweepError> {
        let (name, offset) = match name.trim().strip_suffix('+') {
            Some(n) => (n.trim(), true),
            None => (name.trim(), false),
        };
        let syntax = || SweepError::ParamSyntax {
            given: format!("{name}{}", if offset { "+" } else { "" }),
        };
        if name.is_empty() {
            return Err(syntax());
        }
        let (target, edits, scales_loads) = match name.strip_prefix("load_scale:") {
            Some(_) if offset => return Err(syntax()),
            Some(ids) => {
                let (t, e) = load_scale(model, json, name, ids)?;
                (t, e, true)
            }
            None => {
                let path = NumberPath::resolve(model, json, name).map_err(unknown_or_path)?;
                let current = path.get(json);
                let integer = current.is_some_and(|v| v.is_i64() || v.is_u64());
                let (op, lowest) = match (offset, current.and_then(Value::as_f64)) {
                    (false, _) => (Op::Set, axis.first()),
                    (true, Some(base)) => (Op::Shift { base }, base + axis.first()),
                    (true, None) => {
                        return Err(SweepError::NoValueToOffset {
                            name: name.to_string(),
                            path: path.to_string(),
                        })
                    }
                };
                let mut target = path.to_string();
                if offset {
                    target.push_str(" offset");
                }
                path.check_settable(json, name, number(lowest, integer))
                    .map_err(|e| match e {
                        // The message names the offset as the target does.
                        PathError::NotSettable { name, message, .. } => PathError::NotSettable {
                            name,
                            path: target.clone(),
                            message,
                        },
                        e => e,
                    })?;
                let stresses = pre_stresses(&path.to_string());
                (target, vec![Edit { path, op, integer }], stresses)
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

    /// Resolves `NAME` (or `NAME+`) at the one value `value`.
    pub fn at(
        model: &Model,
        json: &Value,
        name: &str,
        value: f64,
    ) -> Result<Parameter, SweepError> {
        if !value.is_finite() {
            return Err(SweepError::NotANumber {
                given: name.to_string(),
                what: "the value",
                text: format!("{value:?}"),
            });
        }
        let axis = Axis::Range {
            lo: value,
            hi: value,
            count: 1,
            log: false,
        };
        Parameter::resolve(model, json, name, axis)
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
            e.path.set(json, number(v, e.integer));
        }
    }
}

/// Adds `p` to `parameters`, refusing a second name of a number one of
/// them changes.
pub fn add_distinct(parameters: &mut Vec<Parameter>, p: Parameter) -> Result<(), SweepError> {
    if let Some(other) = parameters.iter().find(|o| o.overlaps(&p)) {
        return Err(SweepError::DuplicateParameter {
            name: p.name.clone(),
            other: other.name.clone(),
            target: p.target.clone(),
        });
    }
    parameters.push(p);
    Ok(())
}

/// The parameters of one point, each `NAME` (or `NAME+`) at its value:
/// what `apply` needs to write them into `json` (the model's JSON form);
/// Python's `Model.with_params`.
pub fn at_values(
    model: &Model,
    json: &Value,
    named: &[(String, f64)],
) -> Result<Vec<Parameter>, SweepError> {
    let mut parameters = Vec::with_capacity(named.len());
    for (name, value) in named {
        add_distinct(&mut parameters, Parameter::at(model, json, name, *value)?)?;
    }
    Ok(parameters)
}

/// The model with each parameter at its value: written into a copy of the
/// JSON form `base`, then parsed and validated as a model file is.
pub fn apply(base: &Value, params: &[Parameter], values: &[f64]) -> Result<ValidModel, PointError> {
    let mut json = base.clone();
    for (p, &v) in params.iter().zip(values) {
        p.write(&mut json, v);
    }
    let model: Model = serde_json::from_value(json).map_err(|e| PointError::Schema {
        message: e.to_string(),
    })?;
    model
        .validated()
        .map_err(|InvalidModel { path, problem }| PointError::Invalid { path, problem })
}

/// A JSON number; whole values where the model holds an integer.
fn number(v: f64, integer: bool) -> Value {
    if integer && v.fract() == 0.0 && v.abs() < 9.0e15 {
        return Value::from(v as i64);
    }
    Number::from_f64(v).map_or(Value::Null, Value::Number)
}

/// A name that is neither a short name nor a path: the sweep's message
/// (which also offers `load_scale:`); other path errors as they are.
fn unknown_or_path(e: PathError) -> SweepError {
    match e {
        PathError::Unknown { name, short_names } => {
            SweepError::UnknownParameter { name, short_names }
        }
        e => SweepError::Path(e),
    }
}

/// Whether the number at the canonical JSON `path` is one of what
/// pre-stresses a model: a load's force (`loads[i].force[j]`), a spring's
/// preload (`springs[i].preload`) or gravity (`gravity[j]`).
pub fn pre_stresses(path: &str) -> bool {
    (path.starts_with("loads[") && path.contains("].force"))
        || (path.starts_with("springs[") && path.ends_with("].preload"))
        || path.starts_with("gravity")
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
            let path = NumberPath::new(vec![
                Step::Key("loads".into()),
                Step::Index(i),
                Step::Key("force".into()),
                Step::Index(c),
            ]);
            let base = path.number(json).unwrap_or(0.0);
            edits.push(Edit {
                path,
                op: Op::Scale { base },
                integer: false,
            });
        }
    }
    for &k in &springs {
        let path = NumberPath::new(vec![
            Step::Key("springs".into()),
            Step::Index(k),
            Step::Key("preload".into()),
        ]);
        let base = path.number(json).unwrap_or(0.0);
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
        assert!(resolve("gravity[1]").unwrap().scales_loads);
        assert!(resolve("loads[0].force[1]").unwrap().scales_loads);
        assert!(!resolve("height").unwrap().scales_loads);
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
            Err(SweepError::Path(PathError::Ambiguous { .. }))
        ));
        assert!(matches!(
            resolve("beams[wing].section.height"),
            Err(SweepError::Path(PathError::NotFound { .. }))
        ));
        assert!(matches!(
            resolve("beams[0].section"),
            Err(SweepError::Path(PathError::NotNumeric { .. }))
        ));
        assert!(matches!(
            resolve("beams[0].id"),
            Err(SweepError::Path(PathError::NotNumeric { .. }))
        ));
        assert!(matches!(
            resolve("beams[0].colour"),
            Err(SweepError::Path(PathError::NotSettable { .. }))
        ));
        assert!(matches!(
            resolve("beams[0.height"),
            Err(SweepError::Path(PathError::Syntax { .. }))
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

    #[test]
    fn one_value_per_name_is_a_one_point_sweep() {
        let m = Model::builtin();
        let json = serde_json::to_value(&m).unwrap();
        let named = [
            (String::from("young"), 1.1e11),
            (String::from("beams[0].section.width+"), 1e-4),
        ];
        let at = at_values(&m, &json, &named).unwrap();
        let swept: Vec<Parameter> = [
            "young=1.1e11:1.1e11:1",
            "beams[0].section.width+=1e-4:1e-4:1",
        ]
        .iter()
        .map(|g| Parameter::parse(&m, &json, g).unwrap())
        .collect();
        assert_eq!(at, swept);
        let out = apply(&json, &at, &[1.1e11, 1e-4]).unwrap();
        assert_eq!(out.beams[0].material.young, 1.1e11);
        assert_eq!(out.beams[0].section.width, m.beams[0].section.width + 1e-4);
        let twice = [
            (String::from("height"), 1e-3),
            (String::from("beams[0].section.height"), 2e-3),
        ];
        assert!(matches!(
            at_values(&m, &json, &twice),
            Err(SweepError::DuplicateParameter { .. })
        ));
        assert!(matches!(
            at_values(&m, &json, &[(String::from("height"), f64::NAN)]),
            Err(SweepError::NotANumber { .. })
        ));
    }
}
