//! Straight paths between two designs of one assembly.
//!
//! Two models are *designs of one assembly* when their JSON forms differ
//! only in real numbers: the same bodies, beams (with the same element
//! counts), joints, springs, contacts and loads, in the same order, with
//! the same ids and kinds; the name and the description may differ. The
//! path between them, τ ∈ [0, 1], moves every number that differs on the
//! straight line a + τ(b − a) in its own unit (a stiffness in N/m, a
//! point's coordinate in m, a force in N), so every model on it has the
//! coordinates of both. The statics use it to reach the equilibrium of a
//! changed design from that of a known one
//! ([`crate::analysis::statics::design_path`]).
//!
//! A design between two valid ones need not be valid (the joint points of
//! a turned beam and a moved body meet at both ends but not between, a
//! preload's free length crosses zero): each is validated, and an invalid
//! one is the validation error.

use super::{Model, ValidModel};
use crate::error::{InvalidModel, Problem};
use serde_json::Value;

/// The straight path from one design to another (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignPath {
    from: Value,
    to: Value,
    to_model: ValidModel,
}

/// Top-level keys whose text may differ between designs of one assembly.
const FREE_TEXT: [&str; 2] = ["name", "description"];

impl Model {
    /// The path from `self` to `to`, or `None` when the two are not
    /// designs of one assembly (they differ in more than real numbers).
    pub fn path_to(&self, to: &ValidModel) -> Option<DesignPath> {
        let mut from = serde_json::to_value(self).expect("models serialize");
        let mut to_json = serde_json::to_value(&**to).expect("models serialize");
        for key in FREE_TEXT {
            if let (Some(slot), Some(v)) = (from.get_mut(key), to_json.get(key)) {
                slot.clone_from(v);
            }
        }
        // What was calibrated is a record about a design, not a number of
        // it: the designs along the path carry none.
        for json in [&mut from, &mut to_json] {
            if let Some(o) = json.as_object_mut() {
                o.remove("calibrated");
            }
        }
        same_structure(&from, &to_json).then(|| DesignPath {
            from,
            to: to_json,
            to_model: to.clone(),
        })
    }
}

impl DesignPath {
    /// The design a fraction `tau` of the way (the end design itself at
    /// τ = 1, exactly), validated: the first problem of an invalid one
    /// (module doc), or a number the straight line takes beyond f64 (two
    /// values of opposite sign near the largest).
    pub fn at(&self, tau: f64) -> Result<ValidModel, InvalidModel> {
        if tau == 1.0 {
            return Ok(self.to_model.clone());
        }
        let json = lerp(&self.from, &self.to, tau).map_err(|(mut keys, value)| {
            keys.reverse();
            let path = keys.concat();
            InvalidModel {
                path: path.strip_prefix('.').unwrap_or(&path).to_string(),
                problem: Problem::NotFinite { value },
            }
        })?;
        // Every number is finite and of its end designs' kind (floats
        // between floats, the integers equal), in their structure: the
        // value is a model's JSON form.
        let model: Model = serde_json::from_value(json)
            .expect("a design between two designs of one assembly deserializes");
        model.validated()
    }
}

/// Whether `a` and `b` differ only in real numbers (integers, such as
/// element counts, must agree).
fn same_structure(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) => {
            let whole = |n: &serde_json::Number| n.is_i64() || n.is_u64();
            x == y || !(whole(x) || whole(y))
        }
        (Value::Array(x), Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(p, q)| same_structure(p, q))
        }
        (Value::Object(x), Value::Object(y)) => {
            x.len() == y.len()
                && x.iter()
                    .all(|(k, v)| y.get(k).is_some_and(|w| same_structure(v, w)))
        }
        _ => a == b,
    }
}

/// `a + τ(b − a)` in every real number (`a` and `b` of the same
/// structure); a number that is not finite there is an error with the keys
/// of its JSON path, innermost first (`.height`, `[0]` …).
fn lerp(a: &Value, b: &Value, tau: f64) -> Result<Value, (Vec<String>, f64)> {
    let within = |key: String| {
        move |(mut keys, value): (Vec<String>, f64)| {
            keys.push(key);
            (keys, value)
        }
    };
    match (a, b) {
        (Value::Number(x), Value::Number(y)) if x != y => {
            let (x, y) = (x.as_f64().unwrap_or(0.0), y.as_f64().unwrap_or(0.0));
            let v = x + tau * (y - x);
            serde_json::Number::from_f64(v)
                .map(Value::Number)
                .ok_or((Vec::new(), v))
        }
        (Value::Array(x), Value::Array(y)) => x
            .iter()
            .zip(y)
            .enumerate()
            .map(|(i, (p, q))| lerp(p, q, tau).map_err(within(format!("[{i}]"))))
            .collect::<Result<_, _>>()
            .map(Value::Array),
        (Value::Object(x), Value::Object(y)) => x
            .iter()
            .map(|(k, v)| {
                let w = y.get(k).unwrap_or(v);
                let v = lerp(v, w, tau).map_err(within(format!(".{k}")))?;
                Ok((k.clone(), v))
            })
            .collect::<Result<_, _>>()
            .map(Value::Object),
        _ => Ok(a.clone()),
    }
}

#[cfg(test)]
mod tests {
    use crate::error::{InvalidModel, Problem};
    use crate::Model;

    #[test]
    fn the_path_runs_from_one_design_to_the_other_in_every_number() {
        let a = Model::switch_off_builtin();
        let mut b = a.to_model();
        b.name = String::from("changed");
        b.joints[0].torsion_stiffness = Some(1000.0);
        b.gravity[1] = 0.0;
        let b = b.validated().expect("a valid design");
        let path = a.path_to(&b).expect("designs of one assembly");
        let c0 = a.joints[0].torsion_stiffness.unwrap();
        for tau in [0.0, 0.25, 0.5] {
            let m = path.at(tau).expect("a valid design");
            let ct = m.joints[0].torsion_stiffness.unwrap();
            assert!((ct - (c0 + tau * (1000.0 - c0))).abs() <= 1e-12 * 1000.0);
            assert!((m.gravity[1] - a.gravity[1] * (1.0 - tau)).abs() <= 1e-15);
            assert_eq!(m.beams, a.beams);
        }
        assert_eq!(path.at(0.0).unwrap().joints, a.joints);
        assert_eq!(path.at(1.0).unwrap(), b);
    }

    #[test]
    fn other_assemblies_have_no_path() {
        let a = Model::switch_off_builtin();
        let valid = |m: Model| m.validated().expect("a valid model");
        let mut more_elements = a.to_model();
        more_elements.beams[0].elements += 1;
        assert!(a.path_to(&valid(more_elements)).is_none());
        let mut renamed = a.to_model();
        renamed.joints[0].id = Some(String::from("other"));
        assert!(a.path_to(&valid(renamed)).is_none());
        let mut fewer = a.to_model();
        fewer.springs.clear();
        assert!(a.path_to(&valid(fewer)).is_none());
        assert!(a.path_to(&Model::builtin()).is_none());
    }

    /// Designs between two valid ones are validated: one with a number
    /// beyond f64 on the way is the validation error at its path.
    #[test]
    fn an_invalid_design_on_the_way_is_the_validation_error() {
        let a = Model::switch_off_builtin();
        let mut far = a.to_model();
        far.gravity = [-1e308, 0.0];
        let far = far.validated().expect("a valid design");
        let mut other = a.to_model();
        other.gravity = [1e308, 0.0];
        let other = other.validated().expect("a valid design");
        let path = far.path_to(&other).expect("designs of one assembly");
        assert_eq!(
            path.at(0.5),
            Err(InvalidModel {
                path: String::from("gravity[0]"),
                problem: Problem::NotFinite {
                    value: f64::INFINITY
                },
            })
        );
    }
}
