//! Model modes for experimental-modal-analysis tools: UFF 15 (nodes) and
//! UFF 55 (normal modes), and the node-wise translation vectors the MAC
//! compares.
//!
//! Nodes, numbered from 1 in this order: every beam's mesh nodes (node 0 to
//! the tip), then the rigid bodies' reference points (centres of mass), then
//! the point masses. Each carries its x, y translation (z = 0, planar).
//! Shapes are the modal result's mass-normalised ones (φᵀMφ = 1, so the
//! modal mass written is 1 kg); rigid modes are left out.

use crate::analysis::ModalResult;
use crate::measured::uff::d55::{write_mode, write_nodes, NodeCoordinates, NormalMode};
use crate::system::System;

/// A node of the export: label, name and the indices of its x and y in q.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportNode {
    pub label: i64,
    pub name: String,
    pub dofs: [usize; 2],
}

/// The export's nodes (module doc).
pub fn export_nodes(system: &System) -> Vec<ExportNode> {
    let mut out = Vec::new();
    let mut push = |name: String, dof0: usize| {
        let label = out.len() as i64 + 1;
        out.push(ExportNode {
            label,
            name,
            dofs: [dof0, dof0 + 1],
        });
    };
    for b in &system.beams {
        for k in 0..b.node_count() {
            push(format!("{} node {k}", b.id), b.dof0 + 4 * k);
        }
    }
    for r in &system.rigid_bodies {
        push(r.id.clone(), r.dof0);
    }
    for p in &system.point_masses {
        push(p.id.clone(), p.dof0);
    }
    out
}

/// Node-wise translations [x₁, y₁, x₂, y₂, …] of a global shape.
pub fn translations(nodes: &[ExportNode], shape: &[f64]) -> Vec<f64> {
    nodes
        .iter()
        .flat_map(|n| [shape[n.dofs[0]], shape[n.dofs[1]]])
        .collect()
}

/// UFF 15 and 55 text of the elastic modes; `provenance` goes into each
/// mode's ID lines 2 and 3.
pub fn modal_uff(system: &System, result: &ModalResult, provenance: &[String; 2]) -> String {
    let nodes = export_nodes(system);
    let mut s = String::new();
    let coords: Vec<NodeCoordinates> = nodes
        .iter()
        .map(|n| NodeCoordinates {
            label: n.label,
            xyz: [
                system.q0[n.dofs[0]] + system.origin.x,
                system.q0[n.dofs[1]] + system.origin.y,
                0.0,
            ],
        })
        .collect();
    write_nodes(&mut s, &coords);
    for m in result.modes.iter().filter(|m| !m.kind.is_zero()) {
        let t = translations(&nodes, &m.shape);
        write_mode(
            &mut s,
            &NormalMode {
                id: format!(
                    "mode {} ({})\n{}\n{}",
                    m.index, m.kind, provenance[0], provenance[1]
                ),
                mode_number: m.index as i64,
                frequency_hz: m.frequency_hz,
                modal_mass: 1.0,
                damping_ratio: 0.0,
                nodes: nodes
                    .iter()
                    .zip(t.chunks(2))
                    .map(|(n, v)| (n.label, [v[0], v[1], 0.0]))
                    .collect(),
            },
        );
    }
    s
}
