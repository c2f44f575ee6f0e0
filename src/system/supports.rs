//! The assembly as a free body: its ground supports taken away.
//!
//! A support is any member with one end on the ground: a joint to a
//! `{"ground": …}` point (a clamp, a pin, a roller), a spring or torsion
//! spring to the ground, a contact with a ground segment. What stays is the
//! assembly's own structure: its beams, rigid bodies and point masses, the
//! joints and springs between them. The coordinates (and so every anchor)
//! are unchanged; the kept joints keep their order, so the multipliers of a
//! linearization of the supported system carry over by
//! [`FreeBody::kept_rows`].

use super::System;
use crate::mechanics::pair::Pair;

/// What [`System::remove_supports`] removed and kept.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeBody {
    /// Rows of the supported system's C that the free body keeps, in order
    /// (the kept joints' rows): the free body's multipliers are the
    /// supported ones at these rows.
    pub kept_rows: Vec<usize>,
    /// Labels of the removed joints, springs and contacts.
    pub removed: Vec<String>,
}

fn grounded(pair: &Pair) -> bool {
    pair.a.dofs().is_empty() || pair.b.dofs().is_empty()
}

impl System {
    /// Removes every ground support (module doc) in place.
    pub fn remove_supports(&mut self) -> FreeBody {
        let mut kept_rows = Vec::new();
        let mut removed = Vec::new();
        let constraints = std::mem::take(&mut self.constraints);
        let mut kept = Vec::with_capacity(constraints.len());
        for (c, &row) in constraints.into_iter().zip(&self.constraint_rows) {
            if grounded(c.pair()) {
                removed.push(c.label().to_string());
            } else {
                kept_rows.extend(row..row + c.rows());
                kept.push(c);
            }
        }
        self.constraints = kept;
        self.renumber_constraints();
        // Released supports are supports: their indices would be stale.
        self.released.clear();
        let forces = std::mem::take(&mut self.force_elements);
        for f in forces {
            if grounded(f.pair()) {
                removed.push(f.label().to_string());
            } else {
                self.force_elements.push(f);
            }
        }
        let contacts = std::mem::take(&mut self.contacts);
        for c in contacts {
            if grounded(crate::mechanics::spring::ForceElement::pair(&c)) {
                removed.push(c.label.clone());
            } else {
                self.contacts.push(c);
            }
        }
        FreeBody { kept_rows, removed }
    }
}
