//! Zero-frequency modes counted from the kinematics of the assembly.
//!
//! A zero mode moves without straining anything. Such a motion is rigid on
//! every body, so it lies in the span V of the bodies' rigid motions
//! ([`crate::System::rigid_motions`], weld clusters merged) that satisfy the
//! linearized constraints, C_q V a = 0. Among those, the ones with zero
//! stiffness are the null space of the small pencil (VᵀK_tV, VᵀMV), K_t
//! the full tangent at the linearization state: at an unloaded reference
//! only springs stiffen a rigid motion; under pre-stress gravity, preloads
//! and the constraint forces do too, so a pendulum under gravity keeps its
//! frequency.
//!
//! VᵀK_tV is formed from the cancellation-free energy form
//! ([`crate::System::stiffness_quadratic_forms`], by polarization), which
//! also estimates its own round-off R
//! ([`crate::system::EnergyBreakdown::roundoff`]): strain variations that
//! cancel nodal terms of size s carry ε·s, so a rigid motion's form is
//! ~ε²·(the energy of those sizes), and stress terms (tension, curvature,
//! preloads, constraint forces) carry ε of their size. A stiffness μ = ω²
//! of a candidate counts as zero when |μ| ≤ 64 R/m, m its mass. A pendulum
//! under gravity sits at ~1/(64 ε) times its threshold (its stiffness is a
//! stress term), a rigid motion of a free 2,000-element beam at ≤ R/m.
//!
//! The rank of C_q V is decided on unit-norm columns and rows (the
//! coefficient space of V mixes translations and rotations) by the same
//! grouped Gram–Schmidt/QR as the constraint null space.

use crate::linalg::dense::solve_generalized_small;
use crate::linalg::null_space::NullSpace;
use crate::linalg::vector::dot;
use crate::linalg::{EigenFailure, Triplets};
use crate::system::{EnergyBreakdown, Linearization, System};

/// Zero modes of a linearization.
#[derive(Debug, Clone, Default)]
pub struct ZeroModes {
    /// Mass-normalized shapes in the global coordinates (φᵀMφ = 1).
    pub shapes: Vec<Vec<f64>>,
    /// Rigid clusters of bodies (bodies joined by welds count as one).
    pub clusters: usize,
    /// Rigid motions that satisfy the constraints (the candidates).
    pub candidates: usize,
}

/// Round-off factor of the zero test.
const ZERO_FACTOR: f64 = 64.0;

/// The zero modes of the system linearized at `at`; `cq` holds C_q there.
pub fn zero_modes(
    system: &System,
    at: &Linearization,
    cq: &Triplets,
) -> Result<ZeroModes, EigenFailure> {
    let n = system.ndof();
    let motions = system.rigid_motions(at.q);
    let c = motions.fields.len();
    // B = C_q V (m × c), its columns scaled by the size of their terms.
    let mut by_coord: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for (f, field) in motions.fields.iter().enumerate() {
        for &(i, v) in field {
            by_coord[i].push((f, v));
        }
    }
    let mut b: Vec<(usize, usize, f64)> = Vec::new();
    for (i, j, v) in cq.entries() {
        for &(f, w) in &by_coord[j] {
            b.push((i, f, v * w));
        }
    }
    // Column scale: the size of each column's terms before they cancel
    // (a rigid motion of a cluster satisfies its own welds, so its column
    // of B is round-off; scaling by that would blow the motion up).
    let mut col_size = vec![0.0; c];
    {
        // |B| summed per (row, column), then squared per column.
        let mut sums: Vec<(usize, usize, f64)> =
            b.iter().map(|&(i, f, v)| (i, f, v.abs())).collect();
        sums.sort_unstable_by_key(|e| (e.1, e.0));
        let mut k = 0;
        while k < sums.len() {
            let (i, f, mut v) = sums[k];
            k += 1;
            while k < sums.len() && sums[k].0 == i && sums[k].1 == f {
                v += sums[k].2;
                k += 1;
            }
            col_size[f] += v * v;
        }
    }
    let col_norm: Vec<f64> = col_size
        .iter()
        .map(|&s: &f64| if s > 0.0 { s.sqrt() } else { 1.0 })
        .collect();
    let kernel = NullSpace::new(
        cq.nrows(),
        c,
        b.iter().map(|&(i, f, v)| (i, f, v / col_norm[f])),
    );
    let r = kernel.dim();
    // Candidate motions u_k = V a_k in the global coordinates.
    let mut u: Vec<Vec<f64>> = Vec::with_capacity(r);
    for k in 0..r {
        let mut e = vec![0.0; r];
        e[k] = 1.0;
        let a = kernel.expand(&e);
        let mut uk = vec![0.0; n];
        for (f, &af) in a.iter().enumerate() {
            if af != 0.0 {
                for &(i, v) in &motions.fields[f] {
                    uk[i] += af / col_norm[f] * v;
                }
            }
        }
        u.push(uk);
    }
    // Unit mass for every candidate, so the forms below are ω²-sized.
    let mass = system.mass();
    let mut scratch = vec![0.0; n];
    for uk in &mut u {
        mass.mul_vec(uk, &mut scratch);
        let m = dot(uk, &scratch);
        if m > 0.0 {
            let inv = 1.0 / m.sqrt();
            uk.iter_mut().for_each(|x| *x *= inv);
        }
    }
    let out = |shapes| ZeroModes {
        shapes,
        clusters: motions.clusters,
        candidates: r,
    };
    if r == 0 {
        return Ok(out(Vec::new()));
    }
    // Mass and stiffness of the candidates.
    let mu: Vec<Vec<f64>> = u
        .iter()
        .map(|x| {
            let mut y = vec![0.0; n];
            mass.mul_vec(x, &mut y);
            y
        })
        .collect();
    let mv = faer::Mat::from_fn(r, r, |i, j| 0.5 * (dot(&u[i], &mu[j]) + dot(&u[j], &mu[i])));
    let mut shapes: Vec<Vec<f64>> = u.clone();
    let mut pairs = Vec::new();
    for i in 0..r {
        for j in i + 1..r {
            shapes.push(u[i].iter().zip(&u[j]).map(|(a, b)| a + b).collect());
            pairs.push((i, j));
        }
    }
    let refs: Vec<&[f64]> = shapes.iter().map(Vec::as_slice).collect();
    let mut energies = vec![EnergyBreakdown::default(); refs.len()];
    system.stiffness_quadratic_forms(at, &refs, &mut energies);
    let form = |e: &EnergyBreakdown| 2.0 * e.total();
    let field_noise = field_roundoff(system, at, &u);
    let mut kv = faer::Mat::zeros(r, r);
    let mut noise = field_noise;
    for i in 0..r {
        kv[(i, i)] = form(&energies[i]);
        noise = noise.max(2.0 * energies[i].roundoff / mv[(i, i)]);
    }
    for (p, &(i, j)) in pairs.iter().enumerate() {
        let e = &energies[r + p];
        let v = 0.5 * (form(e) - kv[(i, i)] - kv[(j, j)]);
        kv[(i, j)] = v;
        kv[(j, i)] = v;
        noise = noise.max(2.0 * e.roundoff / (mv[(i, i)] + mv[(j, j)]));
    }
    let (values, vectors) = solve_generalized_small(&kv, &mv).map_err(|e| match e {
        // A massless free motion: report it in the global coordinates.
        EigenFailure::SingularMass { direction } => {
            let mut full = vec![0.0; n];
            for (a, ui) in direction.iter().zip(&u) {
                full.iter_mut().zip(ui).for_each(|(s, x)| *s += a * x);
            }
            EigenFailure::SingularMass { direction: full }
        }
        other => other,
    })?;
    let zero = ZERO_FACTOR * noise;
    let mut result = Vec::new();
    for (k, &value) in values.iter().enumerate() {
        if value.abs() <= zero {
            let mut shape = vec![0.0; n];
            for (i, ui) in u.iter().enumerate() {
                let a = vectors[(i, k)];
                shape.iter_mut().zip(ui).for_each(|(s, x)| *s += a * x);
            }
            result.push(shape);
        }
    }
    Ok(out(result))
}

/// Row sums of |A| of what is assembled into it.
struct RowAbsSum(Vec<f64>);

impl crate::linalg::Scatter for RowAbsSum {
    fn add(&mut self, i: usize, _j: usize, v: f64) {
        self.0[i] += v.abs();
    }
}

/// The stiffness [SI: rad²/s²] a candidate's rounding gives it: a
/// rotation field ẑ × (r − c) is formed with an error ε|r| per position
/// (an assembly far from the origin loses digits in r − c), so a unit-mass
/// candidate turning at rate θ (its largest slope or angle entry) carries an
/// error vector e with eᵢ = ε|qᵢ|θ on positions, whose energy is at most
/// λ_G Σᵢ Mᵢᵢeᵢ², λ_G = maxᵢ Σⱼ|Kᵢⱼ|/Mᵢᵢ (Gershgorin).
fn field_roundoff(system: &System, at: &Linearization, u: &[Vec<f64>]) -> f64 {
    let n = system.ndof();
    // Only an assembly far from the origin (|q| well beyond its own size)
    // loses digits there; near it the field's rounding is that of the
    // variation itself, which the energy form's estimate already holds.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    let mut far = 0.0f64;
    for i in system.point_coordinates() {
        for axis in 0..2 {
            let x = at.q[i + axis];
            lo[axis] = lo[axis].min(x);
            hi[axis] = hi[axis].max(x);
            far = far.max(x.abs());
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    if far <= 4.0 * size {
        return 0.0;
    }
    let mut rows = RowAbsSum(vec![0.0; n]);
    system.add_tangent_stiffness(at, &mut rows);
    let md = system.mass().diagonal();
    let lambda_g = rows
        .0
        .iter()
        .zip(&md)
        .filter(|(_, m)| **m > 0.0)
        .fold(0.0f64, |a, (k, m)| a.max(k / m));
    let mut position = vec![false; n];
    for i in system.point_coordinates() {
        position[i] = true;
        position[i + 1] = true;
    }
    let mut orientation = vec![false; n];
    for b in &system.beams {
        for k in 0..b.node_count() {
            orientation[b.dof0 + 4 * k + 2] = true;
            orientation[b.dof0 + 4 * k + 3] = true;
        }
    }
    for rb in &system.rigid_bodies {
        orientation[rb.dof0 + 2] = true;
    }
    u.iter()
        .map(|uk| {
            let theta = (0..n)
                .filter(|&i| orientation[i])
                .fold(0.0f64, |a, i| a.max(uk[i].abs()));
            let e2: f64 = (0..n)
                .filter(|&i| position[i])
                .map(|i| md[i] * (f64::EPSILON * at.q[i].abs() * theta).powi(2))
                .sum();
            lambda_g * e2
        })
        .fold(0.0, f64::max)
}
