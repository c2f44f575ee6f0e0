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

use super::Model;
use serde_json::Value;

/// The straight path from one design to another (see the module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct DesignPath {
    from: Value,
    to: Value,
    to_model: Model,
}

/// Top-level keys whose text may differ between designs of one assembly.
const FREE_TEXT: [&str; 2] = ["name", "description"];

impl Model {
    /// The path from `self` to `to`, or `None` when the two are not
    /// designs of one assembly (they differ in more than real numbers).
    pub fn path_to(&self, to: &Model) -> Option<DesignPath> {
        let mut from = serde_json::to_value(self).expect("models serialize");
        let to_json = serde_json::to_value(to).expect("models serialize");
        for key in FREE_TEXT {
            if let (Some(slot), Some(v)) = (from.get_mut(key), to_json.get(key)) {
                slot.clone_from(v);
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
    /// τ = 1, exactly).
    pub fn at(&self, tau: f64) -> Model {
        if tau == 1.0 {
            return self.to_model.clone();
        }
        serde_json::from_value(lerp(&self.from, &self.to, tau))
            .expect("a design between two designs of one assembly deserializes")
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

/// `a + τ(b − a)` in every real number (`a` and `b` of the same structure).
fn lerp(a: &Value, b: &Value, tau: f64) -> Value {
    match (a, b) {
        (Value::Number(x), Value::Number(y)) if x != y => {
            let (x, y) = (x.as_f64().unwrap_or(0.0), y.as_f64().unwrap_or(0.0));
            serde_json::Number::from_f64(x + tau * (y - x)).map_or(Value::Null, Value::Number)
        }
        (Value::Array(x), Value::Array(y)) => {
            Value::Array(x.iter().zip(y).map(|(p, q)| lerp(p, q, tau)).collect())
        }
        (Value::Object(x), Value::Object(y)) => Value::Object(
            x.iter()
                .map(|(k, v)| (k.clone(), lerp(v, &y[k], tau)))
                .collect(),
        ),
        _ => a.clone(),
    }
}

#[cfg(test)]
mod tests {
    use crate::Model;

    #[test]
    fn the_path_runs_from_one_design_to_the_other_in_every_number() {
        let a = Model::switch_off_builtin();
        let mut b = a.clone();
        b.name = String::from("changed");
        b.joints[0].torsion_stiffness = Some(1000.0);
        b.gravity[1] = 0.0;
        let path = a.path_to(&b).expect("designs of one assembly");
        let c0 = a.joints[0].torsion_stiffness.unwrap();
        for tau in [0.0, 0.25, 0.5] {
            let m = path.at(tau);
            let ct = m.joints[0].torsion_stiffness.unwrap();
            assert!((ct - (c0 + tau * (1000.0 - c0))).abs() <= 1e-12 * 1000.0);
            assert!((m.gravity[1] - a.gravity[1] * (1.0 - tau)).abs() <= 1e-15);
            assert_eq!(m.beams, a.beams);
        }
        assert_eq!(path.at(0.0).joints, a.joints);
        assert_eq!(path.at(1.0), b);
    }

    #[test]
    fn other_assemblies_have_no_path() {
        let a = Model::switch_off_builtin();
        let mut more_elements = a.clone();
        more_elements.beams[0].elements += 1;
        assert!(a.path_to(&more_elements).is_none());
        let mut renamed = a.clone();
        renamed.joints[0].id = Some(String::from("other"));
        assert!(a.path_to(&renamed).is_none());
        let mut fewer = a.clone();
        fewer.springs.clear();
        assert!(a.path_to(&fewer).is_none());
        assert!(a.path_to(&Model::builtin()).is_none());
    }
}
