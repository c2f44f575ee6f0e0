//! Rigid-rotation compensation of a reused Newton iteration matrix.
//!
//! The planar equations of motion are objective: if every plane vector of
//! the state turns by a rotation R (positions, beam slopes r', joint
//! separations, their multipliers) and every angle shifts by the same φ,
//! the elastic, spring and constraint forces turn with them, and the scaled
//! iteration matrix obeys J(Rq) = 𝐑 J(q) 𝐑ᵀ, where 𝐑 applies R to each
//! (x, y) pair of the unknowns [q; λ] and leaves scalars (rigid-body angles,
//! weld angles, slider distances) alone. The mass matrix is unchanged
//! (it weighs x and y alike, and rigid bodies are referred to their centre
//! of mass). Applied loads fixed in space and dampers break this only in
//! the load-stiffness and damping parts.
//!
//! A free-flying assembly turns through several radians while the
//! integrator reuses one factorization, so a plain reuse converges at a
//! rate θ that grows with the angle turned. Solving with 𝐑 J_f⁻¹ 𝐑ᵀ instead
//! (J_f factored at q_f, R the best-fit rotation from q_f to the current
//! state) removes the rigid rotation from the Jacobian's error; what is
//! left is the change of the elastic deformation, orders of magnitude
//! smaller. The Newton residual is always exact, so the result does not
//! depend on this approximation, only the iteration count does.
//!
//! R is the least-squares (Procrustes) rotation of the system's material
//! points (beam nodes, body centres, point masses) about their centroid:
//! φ = atan2(Σ pᶠᵢ × pᵢ, Σ pᶠᵢ · pᵢ) with centred positions p.

use crate::system::System;

/// Tracks the rigid rotation of a system since its iteration matrix was
/// factored, and turns vectors between the current and that frame.
#[derive(Debug, Clone)]
pub struct RotatingFrame {
    /// (x, y) index pairs of [q; λ] that turn as plane vectors.
    pairs: Vec<(usize, usize)>,
    /// How many of the first pairs are (0, 1), (2, 3), …: the beams' nodes
    /// when the beams come first in q, turned by one sweep over x.
    leading: usize,
    /// Coordinates (x index; y follows) of the points the fit uses.
    points: Vec<usize>,
    /// Centred point positions when the matrix was factored [SI: m].
    reference: Vec<[f64; 2]>,
    /// cos φ and sin φ of the rotation from that frame to the current one.
    cos: f64,
    sin: f64,
}

impl RotatingFrame {
    /// The frame of a system's unknowns [q; λ] (λ after the n coordinates).
    pub fn new(sys: &System) -> Self {
        let n = sys.ndof();
        let mut pairs = Vec::new();
        let mut points = Vec::new();
        for b in &sys.beams {
            for node in 0..b.node_count() {
                let d = b.dof0 + 4 * node;
                pairs.push((d, d + 1));
                pairs.push((d + 2, d + 3));
                points.push(d);
            }
        }
        for r in &sys.rigid_bodies {
            pairs.push((r.dof0, r.dof0 + 1));
            points.push(r.dof0);
        }
        for p in &sys.point_masses {
            pairs.push((p.dof0, p.dof0 + 1));
            points.push(p.dof0);
        }
        for (c, &row) in sys.constraints.iter().zip(&sys.constraint_rows) {
            if let Some(first) = c.vector_rows() {
                pairs.push((n + row + first, n + row + first + 1));
            }
        }
        let leading = pairs
            .iter()
            .enumerate()
            .take_while(|&(k, &(i, j))| i == 2 * k && j == 2 * k + 1)
            .count();
        RotatingFrame {
            leading,
            pairs,
            reference: vec![[0.0; 2]; points.len()],
            points,
            cos: 1.0,
            sin: 0.0,
        }
    }

    /// Take the configuration q (at which the matrix is being factored) as
    /// the reference: no rotation.
    pub fn anchor(&mut self, q: &[f64]) {
        let c = self.centroid(q);
        for (r, &i) in self.reference.iter_mut().zip(&self.points) {
            *r = [q[i] - c[0], q[i + 1] - c[1]];
        }
        self.cos = 1.0;
        self.sin = 0.0;
    }

    /// Best-fit rotation from the reference configuration to q.
    pub fn update(&mut self, q: &[f64]) {
        let c = self.centroid(q);
        let (mut dot, mut cross) = (0.0, 0.0);
        for (r, &i) in self.reference.iter().zip(&self.points) {
            let p = [q[i] - c[0], q[i + 1] - c[1]];
            dot += r[0] * p[0] + r[1] * p[1];
            cross += r[0] * p[1] - r[1] * p[0];
        }
        let norm = dot.hypot(cross);
        if norm > 0.0 {
            (self.cos, self.sin) = (dot / norm, cross / norm);
        } else {
            (self.cos, self.sin) = (1.0, 0.0);
        }
    }

    /// The angle φ turned since the reference [rad].
    pub fn angle(&self) -> f64 {
        self.sin.atan2(self.cos)
    }

    /// x ← 𝐑ᵀ x: a vector of the current frame seen in the reference frame.
    pub fn to_reference(&self, x: &mut [f64]) {
        self.turn(x, -self.sin);
    }

    /// x ← 𝐑 x: a vector of the reference frame seen in the current frame.
    pub fn from_reference(&self, x: &mut [f64]) {
        self.turn(x, self.sin);
    }

    fn turn(&self, x: &mut [f64], sin: f64) {
        if sin == 0.0 {
            return;
        }
        let cos = self.cos;
        for p in x[..2 * self.leading].chunks_exact_mut(2) {
            let (a, b) = (p[0], p[1]);
            p[0] = cos * a - sin * b;
            p[1] = sin * a + cos * b;
        }
        for &(i, j) in &self.pairs[self.leading..] {
            let (a, b) = (x[i], x[j]);
            x[i] = cos * a - sin * b;
            x[j] = sin * a + cos * b;
        }
    }

    fn centroid(&self, q: &[f64]) -> [f64; 2] {
        let mut c = [0.0; 2];
        for &i in &self.points {
            c[0] += q[i];
            c[1] += q[i + 1];
        }
        let k = self.points.len().max(1) as f64;
        [c[0] / k, c[1] / k]
    }
}
