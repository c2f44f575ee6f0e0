//! Reports of the statics and the pre-stressed modal analysis: the
//! equilibrium (node positions, joint reactions, spring forces) as a table,
//! JSON and a figure; frequencies at the equilibrium beside the unstressed
//! ones. (Load sweeps, `modal --sweep-load`, are parameter studies:
//! [`crate::analysis::sweep`].)
//!
//! Units: SI throughout (m, N, N m, Hz); tables show millimetres and degrees
//! where the header says so.
//!
//! Joint reactions are the forces the joint exerts on its point `b` (the
//! model's second point): −(λ₀, λ₁) for a pin or weld, −λ n for a slider
//! (n the current axis normal), and for a weld also the moment −λ₂ on b
//! (conjugate to b's angle). The joint exerts the opposite on `a`.

use crate::analysis::prestress::PrestressedModal;
use crate::analysis::statics::Equilibrium;
use crate::model::{JointType, Model};
use crate::output::figures::assembly_geometry;
use crate::output::plot::{LineFigure, Panel, Scale, Series, SeriesStyle};
use crate::system::System;
use nalgebra::Vector2;
use serde::Serialize;
use std::fmt::Write;

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
        nodes,
        bodies,
        reactions,
        springs,
    }
}

/// Readable tables of the equilibrium (lengths in mm).
pub fn static_table(r: &StaticReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: static equilibrium at load factor {}: {} load steps, {} Newton iterations, unbalanced force {:.2e} N, constraint violation {:.2e}",
        r.model, r.load_scale, r.load_steps, r.iterations, r.residual, r.constraint_violation
    );
    // A model without beams has no nodes: no empty table.
    if !r.nodes.is_empty() {
        let _ = writeln!(s, "\nnodes");
        let _ = writeln!(
            s,
            "{:<10} {:>4} {:>8} {:>10} {:>10} {:>11} {:>11} {:>9} {:>11}",
            "beam",
            "node",
            "s [mm]",
            "x [mm]",
            "y [mm]",
            "ux [mm]",
            "uy [mm]",
            "slope [°]",
            "strain"
        );
        for n in &r.nodes {
            let _ = writeln!(
                s,
                "{:<10} {:>4} {:>8.3} {:>10.4} {:>10.4} {:>11.4e} {:>11.4e} {:>9.3} {:>11.3e}",
                n.beam,
                n.node,
                1e3 * n.s,
                1e3 * n.position[0],
                1e3 * n.position[1],
                1e3 * n.displacement[0],
                1e3 * n.displacement[1],
                n.slope_deg,
                n.strain
            );
        }
    }
    if !r.bodies.is_empty() {
        let _ = writeln!(s, "\nbodies");
        let _ = writeln!(
            s,
            "{:<12} {:>10} {:>10} {:>11} {:>11} {:>12}",
            "body", "x [mm]", "y [mm]", "ux [mm]", "uy [mm]", "rotation [°]"
        );
        for b in &r.bodies {
            let rot = b
                .rotation_deg
                .map_or_else(|| "-".to_string(), |v| format!("{v:.4e}"));
            let _ = writeln!(
                s,
                "{:<12} {:>10.4} {:>10.4} {:>11.4e} {:>11.4e} {:>12}",
                b.id,
                1e3 * b.position[0],
                1e3 * b.position[1],
                1e3 * b.displacement[0],
                1e3 * b.displacement[1],
                rot
            );
        }
    }
    if !r.reactions.is_empty() {
        let _ = writeln!(s, "\njoint reactions (force of the joint on its point b)");
        let _ = writeln!(
            s,
            "{:<16} {:<7} {:>11} {:>11} {:>12}",
            "joint", "type", "Fx [N]", "Fy [N]", "M [N m]"
        );
        for j in &r.reactions {
            let m = j
                .moment
                .map_or_else(|| "-".to_string(), |v| format!("{v:.4e}"));
            let kind = format!("{:?}", j.kind).to_lowercase();
            let _ = writeln!(
                s,
                "{:<16} {:<7} {:>11.4} {:>11.4} {:>12}",
                j.joint, kind, j.force[0], j.force[1], m
            );
        }
    }
    if !r.springs.is_empty() {
        let _ = writeln!(s, "\nsprings (tension +)");
        let _ = writeln!(
            s,
            "{:<20} {:>14} {:>12}",
            "spring", "force [N, N m]", "length [mm]"
        );
        for sp in &r.springs {
            let len = sp
                .length
                .map_or_else(|| "-".to_string(), |v| format!("{:.4}", 1e3 * v));
            let _ = writeln!(s, "{:<20} {:>14.4} {:>12}", sp.spring, sp.force, len);
        }
    }
    s
}

/// The reference and the equilibrium shape, displacements magnified so the
/// largest shows as 5 % of the assembly when they are smaller than that.
pub fn equilibrium_figure(system: &System, eq: &Equilibrium) -> LineFigure {
    let (q0, q) = (&system.q0, &eq.q);
    let reference = assembly_geometry(system, q0, 16);
    let extent = reference
        .beams
        .iter()
        .flatten()
        .chain(&reference.bodies)
        .fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |e, p| {
            (e.0.min(p[0]), e.1.max(p[0]), e.2.min(p[1]), e.3.max(p[1]))
        });
    let size = (extent.1 - extent.0).max(extent.3 - extent.2).max(1e-9);
    let mut umax: f64 = 0.0;
    let positions = system
        .beams
        .iter()
        .flat_map(|b| (0..b.node_count()).map(move |k| b.dof0 + 4 * k))
        .chain(system.rigid_bodies.iter().map(|r| r.dof0))
        .chain(system.point_masses.iter().map(|p| p.dof0));
    for i in positions {
        umax = umax.max((q[i] - q0[i]).hypot(q[i + 1] - q0[i + 1]));
    }
    let factor = if umax > 0.0 && umax < 0.05 * size {
        (0.05 * size / umax).round().max(1.0)
    } else {
        1.0
    };
    let shown: Vec<f64> = q0
        .iter()
        .zip(q)
        .map(|(a, b)| a + factor * (b - a))
        .collect();
    let deformed = assembly_geometry(system, &shown, 16);
    let label = if factor > 1.0 {
        format!("equilibrium (displacements × {factor})")
    } else {
        "equilibrium".to_string()
    };
    let mut panel = Panel::new("y", Scale::mm());
    let poly = |name: String, pts: &[[f64; 2]], colour: usize, style| Series {
        name,
        x: pts.iter().map(|p| p[0]).collect(),
        y: pts.iter().map(|p| p[1]).collect(),
        style,
        colour: Some(colour),
    };
    for (i, (r, d)) in reference.beams.iter().zip(&deformed.beams).enumerate() {
        let named = |s: &str| if i == 0 { s.to_string() } else { String::new() };
        panel
            .series
            .push(poly(named("reference"), r, 0, SeriesStyle::Reference));
        panel
            .series
            .push(poly(named(&label), d, 0, SeriesStyle::Line));
    }
    if !deformed.bodies.is_empty() {
        panel.series.push(poly(
            "bodies".to_string(),
            &deformed.bodies,
            1,
            SeriesStyle::Points,
        ));
    }
    // Equal spans on both axes keep the shape's proportions.
    let (cx, cy) = (0.5 * (extent.0 + extent.1), 0.5 * (extent.2 + extent.3));
    let half = 0.6 * size;
    panel.y_range = Some((cy - half, cy + half));
    let mut fig = LineFigure::new(
        format!(
            "{}: static equilibrium at load factor {}",
            system.name, eq.load_scale
        ),
        "x",
        Scale::mm(),
    );
    fig.x_range = Some((cx - half, cx + half));
    fig.panels.push(panel);
    fig
}

/// Frequencies at the equilibrium beside the unstressed ones.
pub fn prestress_table(model_name: &str, r: &PrestressedModal) -> String {
    let mut s = String::new();
    let eq = &r.equilibrium;
    let _ = writeln!(
        s,
        "model {model_name}: modes at the static equilibrium (load factor {}, {} load steps, {} Newton iterations, unbalanced force {:.2e} N)",
        eq.load_scale, eq.steps, eq.iterations, eq.residual
    );
    let _ = writeln!(
        s,
        "{} zero-frequency modes at the equilibrium, {} at the reference",
        r.prestressed.rigid_modes, r.reference.rigid_modes
    );
    let _ = writeln!(
        s,
        "{:>5}  {:>16}  {:>16}  {:>9}  {:<8}",
        "mode", "unstressed [Hz]", "pre-stressed [Hz]", "shift [%]", "kind"
    );
    for (i, m) in r.prestressed.modes.iter().enumerate() {
        let f0 = r.reference.modes.get(i).map(|m| m.frequency_hz);
        let shift = r
            .shift_percent(i)
            .map_or_else(|| "-".to_string(), |v| format!("{v:+.4}"));
        let f0 = f0.map_or_else(|| "-".to_string(), |v| format!("{v:.3}"));
        let _ = writeln!(
            s,
            "{:>5}  {:>16}  {:>16.3}  {:>9}  {:<8}",
            i + 1,
            f0,
            m.frequency_hz,
            shift,
            m.kind
        );
    }
    s
}
