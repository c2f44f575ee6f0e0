//! The reduced flexible body as a document: what `reduce` writes to its
//! output file and the Python package's `ReducedBody` holds.
//!
//! Units: positions [SI: m]; the basis Ψ over the model's coordinates in
//! their units per unit modal coordinate (beam positions [m], slopes [–],
//! rigid-body angles [rad], point-mass positions [m]); the reduced mass
//! ΨᵀMΨ [SI: kg m² per unit² of modal coordinate: Ψ is M-normalized, so
//! the identity]; the reduced stiffness ΨᵀKΨ [SI: rad²/s², diag(ω²)];
//! the 3D form's mass [SI: kg] and stiffness [SI: N/m] over 3
//! translations per node, its basis [SI: m per unit modal coordinate].

use crate::analysis::reduce::{NodeKind, ReductionCheck, ReductionMethod};
use schemars::JsonSchema;
use serde::Serialize;

/// One interface point.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct InterfacePoint {
    /// The beam's id.
    pub beam: String,
    /// Arc length of the point along the beam [SI: m] (a mesh node).
    pub s: f64,
    /// Its four coordinates [rx, ry, r'x, r'y] in q (0-based).
    pub coordinates: [usize; 4],
    /// Its node and its virtual node in the 3D form (0-based).
    pub nodes: [usize; 2],
}

/// The body's 3D form (see [`crate::analysis::reduce::NodeForm`]).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct NodeFormDoc {
    /// Node positions in the model's frame at the linearization state,
    /// z = 0 [SI: m], N × 3.
    pub positions: Vec<[f64; 3]>,
    /// What each node stands for.
    pub kinds: Vec<NodeKind>,
    /// M₃ (3N × 3N) nonzeros as [row, column, value] [SI: kg].
    pub mass: Vec<(usize, usize, f64)>,
    /// K₃ (3N × 3N) nonzeros as [row, column, value] [SI: N/m, in the
    /// plane; z rows and columns are zero].
    pub stiffness: Vec<(usize, usize, f64)>,
    /// Ψ₃ (3N × m), rows x, y, z per node [SI: m].
    pub basis: Vec<Vec<f64>>,
}

/// The reduced body.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ReducedBody {
    /// The model's name.
    pub model: String,
    pub method: ReductionMethod,
    /// Component modes asked for.
    pub modes: usize,
    /// Reduced at the static equilibrium (the stiffening kept, the preload
    /// forces not).
    pub prestress: bool,
    /// Factor on the applied loads at that equilibrium [–] (1 without
    /// `prestress`: no equilibrium was sought).
    pub load_scale: f64,
    /// Ground supports kept in the body.
    pub keep_supports: bool,
    /// The supports (joints, springs, contacts to the ground) removed.
    pub removed_supports: Vec<String>,
    pub interface: Vec<InterfacePoint>,
    /// Number of coordinates of q.
    pub coordinates: usize,
    /// The linearization state q (positions in the system's frame, about
    /// the model's centre of mass; add `origin` for the model's frame).
    pub q: Vec<f64>,
    /// The model's centre of mass in its own frame [SI: m].
    pub origin: [f64; 2],
    /// Total mass [SI: kg].
    pub total_mass_kg: f64,
    /// Moment of inertia about the centre of mass, z axis [SI: kg m²].
    pub inertia_kg_m2: f64,
    /// The component modes' frequencies [SI: Hz]: fixed-interface
    /// (Craig–Bampton) or free (free-interface).
    pub component_hz: Vec<f64>,
    /// The flexible basis's own frequencies √(ΨᵀKΨ)ᵢᵢ/2π [SI: Hz].
    pub basis_hz: Vec<f64>,
    /// Reduced mass ΨᵀMΨ (m × m).
    pub mass: Vec<Vec<f64>>,
    /// Reduced stiffness ΨᵀKΨ (m × m) [SI: rad²/s²].
    pub stiffness: Vec<Vec<f64>>,
    /// Ψ over the model's coordinates (n × m).
    pub basis: Vec<Vec<f64>>,
    /// The rigid motions the frame carries (n × r), M-orthonormal.
    pub rigid: Vec<Vec<f64>>,
    /// The 3D form.
    pub nodes: NodeFormDoc,
    /// The reduced body against the full model.
    pub check: ReductionCheck,
}

/// The rows of a faer matrix.
pub fn rows(m: &faer::Mat<f64>) -> Vec<Vec<f64>> {
    (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)]).collect())
        .collect()
}
