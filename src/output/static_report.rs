//! Reports of the statics and the pre-stressed modal analysis: the
//! equilibrium (node positions, joint reactions, spring forces; the typed
//! result is [`crate::results::statics`]) as a table and a figure; frequencies at the equilibrium beside the unstressed
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

use crate::analysis::statics::Equilibrium;
use crate::output::figures::assembly_geometry;
use crate::output::plot::{LineFigure, Panel, Scale, Series, SeriesStyle};
use crate::system::System;
use std::fmt::Write;

pub use crate::results::statics::{
    static_report, BodyState, NodeState, Reaction, SpringState, StaticReport,
};

/// Readable tables of the equilibrium (lengths in mm).
pub fn static_table(r: &StaticReport) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "model {}: static equilibrium at load factor {}: {} load steps, {} Newton iterations, unbalanced force {:.2e} N, constraint violation {:.2e}",
        r.model, r.load_scale, r.load_steps, r.iterations, r.residual, r.constraint_violation
    );
    let _ = writeln!(s, "found: {}", r.branch);
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
        .chain(reference.bodies.iter().flatten())
        .chain(&reference.masses)
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
    let bodies: Vec<[f64; 2]> = deformed
        .bodies
        .iter()
        .flatten()
        .chain(&deformed.masses)
        .copied()
        .collect();
    if !bodies.is_empty() {
        panel
            .series
            .push(poly("bodies".to_string(), &bodies, 1, SeriesStyle::Points));
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

/// Frequencies at the equilibrium beside the unstressed ones (it lives
/// with the other modal tables).
pub use super::modal_report::prestress_table;
