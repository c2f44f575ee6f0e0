//! The static equilibrium as a typed result (`static --json`): node and
//! body positions and displacements where the model sits [SI: m, rad],
//! joint reactions on each joint's point `b` [SI: N, N m] (−(λ₀, λ₁) for a
//! pin or weld, −λ n for a slider, and for a weld the moment −λ₂), and
//! spring forces [SI: N or N m]. The tables and the figure are in
//! [`crate::output::static_report`].

use crate::analysis::statics::{Branch, Equilibrium};
use crate::model::{JointType, Model};
use crate::system::System;
use nalgebra::Vector2;
use serde::Serialize;

/// A beam node at equilibrium.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct NodeState {
    /// The beam's id.
    pub beam: String,
    /// Node number along the beam, 0-based [–].
    pub node: usize,
    /// Reference arc length [SI: m].
    pub s: f64,
    /// Position [SI: m].
    pub position: [f64; 2],
    /// Displacement from the reference [SI: m].
    pub displacement: [f64; 2],
    /// Slope angle atan2(r'y, r'x) [deg].
    pub slope_deg: f64,
    /// Axial strain |r'| − 1 [–].
    pub strain: f64,
}

/// A rigid body or point mass at equilibrium.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct BodyState {
    /// The body's id.
    pub id: String,
    /// Position of its reference point [SI: m].
    pub position: [f64; 2],
    /// Displacement from the reference [SI: m].
    pub displacement: [f64; 2],
    /// Rotation from the reference [deg]; `None` for a point mass.
    pub rotation_deg: Option<f64>,
}

/// The force (and moment) a joint exerts on its point b.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct Reaction {
    /// The joint's label.
    pub joint: String,
    pub kind: JointType,
    /// Force [SI: N], global frame.
    pub force: [f64; 2],
    /// Moment [SI: N m]; welds only.
    pub moment: Option<f64>,
}

/// A spring's force at equilibrium.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct SpringState {
    /// The spring's id.
    pub spring: String,
    /// Tension (+) or compression (−) [SI: N]; a torsion spring's moment [SI: N m].
    pub force: f64,
    /// Current length [SI: m]; `None` for a torsion spring.
    pub length: Option<f64>,
}

/// Everything `ancf-modal static` reports.
#[derive(Debug, Clone, Serialize, schemars::JsonSchema)]
pub struct StaticReport {
    /// Model name.
    pub model: String,
    /// Factor on the applied loads (gravity is not scaled) [–].
    pub load_scale: f64,
    /// Load increments taken [–].
    pub load_steps: usize,
    /// Newton iterations in all [–].
    pub iterations: usize,
    /// Unbalanced force at the solution [SI: N].
    pub residual: f64,
    /// Constraint violation at the solution [SI: m, rad].
    pub constraint_violation: f64,
    /// How the equilibrium was found (the load path from the reference).
    pub branch: Branch,
    /// Every beam node.
    pub nodes: Vec<NodeState>,
    /// Every rigid body and point mass.
    pub bodies: Vec<BodyState>,
    /// Every joint's reaction.
    pub reactions: Vec<Reaction>,
    /// Every spring's force.
    pub springs: Vec<SpringState>,
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// The report of an equilibrium of `system`, built from `model`.
pub fn static_report(model: &Model, system: &System, eq: &Equilibrium) -> StaticReport {
    let (q, q0) = (&eq.q, &system.q0);
    // Positions where the model sits (the system works about its centre).
    let at = |i: usize| [q[i] + system.origin.x, q[i + 1] + system.origin.y];
    let mut nodes = Vec::new();
    for b in &system.beams {
        for (k, &s) in b.node_s.iter().enumerate() {
            let i = b.dof0 + 4 * k;
            let position = at(i);
            nodes.push(NodeState {
                beam: b.id.clone(),
                node: k,
                s,
                position,
                displacement: sub([q[i], q[i + 1]], [q0[i], q0[i + 1]]),
                slope_deg: q[i + 3].atan2(q[i + 2]).to_degrees(),
                strain: q[i + 2].hypot(q[i + 3]) - 1.0,
            });
        }
    }
    let mut bodies = Vec::new();
    for r in &system.rigid_bodies {
        let i = r.dof0;
        bodies.push(BodyState {
            id: r.id.clone(),
            position: at(i),
            displacement: sub([q[i], q[i + 1]], [q0[i], q0[i + 1]]),
            rotation_deg: Some((q[i + 2] - q0[i + 2]).to_degrees()),
        });
    }
    for p in &system.point_masses {
        let i = p.dof0;
        bodies.push(BodyState {
            id: p.id.clone(),
            position: at(i),
            displacement: sub([q[i], q[i + 1]], [q0[i], q0[i + 1]]),
            rotation_deg: None,
        });
    }
    let mut reactions = Vec::new();
    for ((c, &row), joint) in system
        .constraints
        .iter()
        .zip(&system.constraint_rows)
        .zip(&model.joints)
    {
        let l = &eq.lambda[row..row + c.rows()];
        let (force, moment) = match joint.kind {
            JointType::Pin => ([-l[0], -l[1]], None),
            JointType::Weld => ([-l[0], -l[1]], Some(-l[2])),
            JointType::Slider => {
                let axis = joint.axis.unwrap_or([1.0, 0.0]);
                let a = Vector2::new(axis[0], axis[1]).normalize();
                let turn = if c.pair().a.has_angle() {
                    c.pair().a.angle(q) - c.pair().a.angle(q0)
                } else {
                    0.0
                };
                let (sn, cs) = turn.sin_cos();
                let n0 = Vector2::new(-a.y, a.x);
                let n = Vector2::new(cs * n0.x - sn * n0.y, sn * n0.x + cs * n0.y);
                ([-l[0] * n.x, -l[0] * n.y], None)
            }
        };
        reactions.push(Reaction {
            joint: c.label().to_string(),
            kind: joint.kind,
            force,
            moment,
        });
    }
    // Torsion springs come first (built with the joints), then the springs.
    let torsion = system.force_elements.len() - model.springs.len();
    let springs = system
        .force_elements
        .iter()
        .enumerate()
        .map(|(i, f)| SpringState {
            spring: f.label().to_string(),
            force: f.elastic_force(q),
            length: (i >= torsion).then(|| f.pair().separation(q).norm()),
        })
        .collect();
    StaticReport {
        model: model.name.clone(),
        load_scale: eq.load_scale,
        load_steps: eq.steps,
        iterations: eq.iterations,
        residual: eq.residual,
        constraint_violation: eq.constraint_violation,
        branch: eq.branch.clone(),
        nodes,
        bodies,
        reactions,
        springs,
    }
}
