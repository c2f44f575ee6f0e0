//! The reduced tangent of the statics: its factorization and Newton
//! corrections, and the diagnosis when it is not positive definite.
//!
//! On an orthonormal basis N of null(C_q), the reduced tangent NᵀKN [SI: N/m,
//! N, N m/rad by coordinate] is factored by Cholesky when it is clearly
//! positive definite, else decomposed into the modes of (NᵀKN, NᵀMN) — the
//! generalized eigenproblem of [`super::modal`], whose mass scaling makes
//! "zero stiffness" independent of units (|ω²| ≤ 64 ε max|ω²|). A load
//! component on a zero mode is a load nothing carries: the whole assembly
//! unsupported (a rigid motion while no joint holds it to the ground), else
//! a mechanism, named by the coordinate with the largest kinetic share
//! √M_ii |φ_i|. After a converged load step, a negative lowest ω² means a
//! loss of stability, located by regula falsi (Illinois) on ω²₁ between the
//! last stable load and this one.

use super::{
    argmax_abs, dot, norm2, norm_inf, Damping, LoadPath, NewtonFailure, Ramp, Snapshot, Solver,
    State,
};
use crate::error::AnalysisError;
use crate::linalg::dense::{generalized_eigenvalues, solve_generalized};
use crate::linalg::krylov::{lowest_modes, KrylovSettings};
use crate::linalg::null_space::{symmetrize, NullSpace, Projected};
use crate::linalg::sparse::mul_vec;
use crate::linalg::EigenFailure;
use crate::linalg::Triplets;
use crate::mechanics::anchor::Anchor;
use crate::mechanics::contact::Regularize;
use crate::system::{Linearization, System};
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;
use faer::{Mat, Side};

impl Solver<'_> {
    /// Modes of the reduced pair (K_r, M_r) and the zero threshold.
    pub(crate) fn reduced_modes(
        &self,
        kr: &Mat<f64>,
        ns: &NullSpace,
    ) -> Result<ReducedModes, AnalysisError> {
        let mr = self.reduced_mass(ns);
        let eig = solve_generalized(kr, &mr, kr.nrows()).map_err(|e| match e {
            EigenFailure::SingularMass { direction } => {
                let full = ns.expand(&direction);
                let i = argmax_abs(&full);
                AnalysisError::SingularMass {
                    dof: self.system.dof_label(i),
                    path: self.system.dof_model_path(i),
                }
            }
            EigenFailure::NoConvergence | EigenFailure::Factorization => {
                AnalysisError::EigenSolver { size: kr.nrows() }
            }
        })?;
        // A Newton step's zero-stiffness test: |ω²| within the dense
        // solver's round-off, 64 ε max|ω²|.
        let lmax = eig.values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let zero = 64.0 * f64::EPSILON * lmax;
        Ok(ReducedModes {
            values: eig.values,
            vectors: eig.vectors,
            zero,
        })
    }

    /// The LU factor of an indefinite reduced tangent K_r when no mode of
    /// (K_r, M_r) is a zero-stiffness one, else `None` (the caller then
    /// decomposes it into modes). The modes' correction Σ φφᵀb/ω² is K_r⁻¹b
    /// when no ω² is dropped as zero, so LU gives it without the vectors:
    /// only the eigenvalues are computed, and the threshold is the modes'
    /// own (64 ε max|ω²|) with a margin of 16 for the two computations'
    /// round-off.
    pub(crate) fn nonsingular_lu(
        &self,
        kr: &Mat<f64>,
        ns: &NullSpace,
    ) -> Option<faer::linalg::solvers::PartialPivLu<f64>> {
        let mr = self.reduced_mass(ns);
        let values = generalized_eigenvalues(kr, &mr).ok()?;
        let lmax = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let zero = 64.0 * f64::EPSILON * lmax;
        let clear = values.iter().all(|v| v.abs() > 16.0 * zero);
        clear.then(|| kr.partial_piv_lu())
    }

    /// NᵀMN, dense (small problems).
    pub(crate) fn reduced_mass(&self, ns: &NullSpace) -> Mat<f64> {
        let d = ns.dim();
        let mut mr = Mat::zeros(d, d);
        self.system
            .mass()
            .add_into(&mut Projected::new(ns, &mut mr));
        symmetrize(&mut mr);
        mr
    }

    /// The error for a load that drives a zero-stiffness motion.
    pub(crate) fn free_motion_error(&self, motion: &[f64]) -> AnalysisError {
        let grounded = self.system.constraints.iter().any(|c| {
            matches!(c.pair().a, Anchor::Ground { .. })
                || matches!(c.pair().b, Anchor::Ground { .. })
        });
        if !grounded && is_rigid_motion(self.system, &self.system.q0, motion) {
            AnalysisError::NoSupport
        } else {
            AnalysisError::Mechanism {
                dof: self.system.dof_label(self.kinetic_argmax(motion)),
            }
        }
    }

    /// Coordinate with the largest kinetic-energy share √M_ii |φ_i|.
    pub(crate) fn kinetic_argmax(&self, phi: &[f64]) -> usize {
        let w: Vec<f64> = phi
            .iter()
            .enumerate()
            .map(|(i, p)| p * self.mass_diagonal[i].max(0.0).sqrt())
            .collect();
        argmax_abs(&w)
    }

    /// Lowest eigenvalue ω² of the reduced tangent at a converged state,
    /// its expanded mode and the zero threshold; `None` for a system without
    /// free coordinates. Unless `exact`, a small model's clearly definite tangent returns
    /// ω² = +∞ without solving the eigenproblem.
    pub(crate) fn lowest_mode(
        &self,
        state: &State,
        exact: bool,
    ) -> Result<Option<LowestMode>, AnalysisError> {
        let sys = self.system;
        let n = sys.ndof();
        let at = Linearization {
            q: &state.q,
            lambda: Some(&state.lambda),
            time: self.settings.time,
            load_scale: state.loads,
        };
        let mut cq = Triplets::new(sys.constraint_count(), n);
        sys.add_constraint_jacobian(&state.q, &mut cq);
        let ns = NullSpace::new(cq.nrows(), n, cq.entries());
        let d = ns.dim();
        if d == 0 {
            return Ok(None);
        }
        let definite = || LowestMode {
            value: f64::INFINITY,
            shape: Vec::new(),
            zero: 0.0,
        };
        if d > crate::analysis::modal::DENSE_MAX {
            // Large: the lowest mode by shift-invert, always. A sparse
            // Cholesky's success proves nothing where its round-off (ε
            // times the stiffest element's EA/Le) exceeds the lowest ω²:
            // a 2,000-element hanger in compression factored up to 1.11 ×
            // its Euler load and was reported buckling there.
            let (mut kr, mut mr) = (Triplets::new(d, d), Triplets::new(d, d));
            sys.add_tangent_stiffness(&at, &mut Projected::new(&ns, &mut kr));
            sys.mass().add_into(&mut Projected::new(&ns, &mut mr));
            let modes = lowest_modes(&kr, &mr, &[], &KrylovSettings::new(1))
                .map_err(|_| AnalysisError::EigenSolver { size: d })?;
            let lmax = crate::linalg::sparse::diagonal(&kr.to_sparse())
                .iter()
                .zip(crate::linalg::sparse::diagonal(&mr.to_sparse()))
                .fold(0.0f64, |a, (k, m)| a.max((k / m).abs()));
            let shape = ns.expand(modes.vectors.col_as_slice(0));
            let (value, zero) = self.rayleigh(&at, &shape, true);
            let zero = zero.min(64.0 * f64::EPSILON * lmax);
            return Ok(Some(LowestMode { value, shape, zero }));
        }
        let mut kr = Mat::zeros(d, d);
        sys.add_tangent_stiffness(&at, &mut Projected::new(&ns, &mut kr));
        symmetrize(&mut kr);
        if !exact && definite_factor(&kr).is_some() {
            return Ok(Some(definite()));
        }
        let modes = self.reduced_modes(&kr, &ns)?;
        let xr: Vec<f64> = (0..d).map(|r| modes.vectors[(r, 0)]).collect();
        let shape = ns.expand(&xr);
        let (value, zero) = self.rayleigh(&at, &shape, false);
        Ok(Some(LowestMode {
            value,
            shape,
            zero: zero.min(modes.zero),
        }))
    }

    /// The Rayleigh quotient φᵀKφ / φᵀMφ of a mode expanded to all
    /// coordinates and its rounding. The eigen-solver's own round-off is
    /// ε max|ω²|, set by the stiffest motion (a string's axial modes): on a
    /// string compressed 0.05 % past buckling, ω²₁ = −0.086 1/s² was under
    /// that threshold (0.20 1/s²) and passed as definite; the quotient of an
    /// eigenvector accurate to δ is accurate to δ².
    ///
    /// Small models (`precise` false): K summed element by element at `at`,
    /// rounding 64 ε |φ|ᵀ|K||φ| / φᵀMφ; a bending mode touches the axial
    /// stiffness only through its own (second-order) stretch. Large ones:
    /// φᵀKφ from the beams' strain variations
    /// ([`System::stiffness_quadratic_form`]), rounding 64 times the
    /// form's own estimate: on a fine mesh the assembled entries cancel
    /// terms of order EI/Le³ and EA/Le whose rounding exceeds a buckling
    /// mode's ω² (a 2,000-element hanger).
    fn rayleigh(&self, at: &Linearization, shape: &[f64], precise: bool) -> (f64, f64) {
        let n = self.system.ndof();
        let (energy, rounding) = if precise {
            let form = self.system.stiffness_quadratic_form(at, shape);
            (2.0 * form.total(), 64.0 * 2.0 * form.roundoff)
        } else {
            let mut k = Triplets::new(n, n);
            self.system.add_tangent_stiffness(at, &mut k);
            let (mut energy, mut rounding) = (0.0, 0.0);
            for (i, j, v) in k.entries() {
                energy += shape[i] * v * shape[j];
                rounding += (shape[i] * v * shape[j]).abs();
            }
            (energy, 64.0 * f64::EPSILON * rounding)
        };
        let mut m_phi = vec![0.0; n];
        self.system.mass().mul_vec(shape, &mut m_phi);
        let modal_mass = dot(shape, &m_phi);
        (energy / modal_mass, rounding / modal_mass)
    }

    /// The lowest mode of the reduced tangent at a converged state when it
    /// is negative beyond round-off (the tangent is indefinite), else `None`.
    pub(crate) fn indefinite(&self, state: &State) -> Result<Option<LowestMode>, AnalysisError> {
        Ok(self
            .lowest_mode(state, false)?
            .filter(|low| low.value < -low.zero))
    }

    /// The loss of stability between the stable `prev` and the converged
    /// but indefinite `next` (lowest mode `low`), located by regula falsi
    /// (Illinois) on ω²₁, as the error to report.
    pub(crate) fn locate_instability(
        &self,
        prev: &State,
        next: &State,
        low: LowestMode,
        which: Ramp,
        path: LoadPath,
    ) -> AnalysisError {
        match self.regula_falsi(prev, next, low, which) {
            Ok((critical, dof)) => match which {
                Ramp::Gravity => AnalysisError::UnstableUnderGravity {
                    gravity_factor: critical,
                    dof,
                },
                _ => AnalysisError::Unstable {
                    load_factor: which.load_factor(critical),
                    dof,
                    path,
                },
            },
            Err(e) => e,
        }
    }

    /// The critical parameter of ramp `which` between `prev` and `next`,
    /// and the coordinate its buckling mode moves most.
    fn regula_falsi(
        &self,
        prev: &State,
        next: &State,
        low: LowestMode,
        which: Ramp,
    ) -> Result<(f64, String), AnalysisError> {
        let mut dof = self.system.dof_label(self.kinetic_argmax(&low.shape));
        let mut a = prev.clone();
        let (mut sa, mut fa) = (which.param(prev), 0.0);
        if let Some(m) = self.lowest_mode(prev, true)? {
            fa = m.value;
        }
        let (mut sb, mut fb) = (which.param(next), low.value);
        let scale = fa.abs().max(fb.abs());
        let mut critical = sb;
        let mut side = 0i8;
        for _ in 0..40 {
            let sc = if fa > 0.0 && fb.is_finite() {
                sa - fa * (sb - sa) / (fb - fa)
            } else {
                0.5 * (sa + sb)
            };
            critical = sc;
            if (sb - sa).abs() <= 1e-9 * sa.abs().max(sb.abs()) {
                break;
            }
            let mut c = a.clone();
            which.set(&mut c, sc);
            if self
                .newton(&mut c, Damping::Full, Regularize::OpenAndBarelyClosed, None)
                .is_err()
            {
                // No equilibrium near the stable one at sc (past a limit
                // point): the loss lies below it. Bisect from here on
                // (before, sc itself was returned: a string past buckling
                // got the bracket's midpoint, 0.991699 for 0.991168).
                (sb, fb) = (sc, f64::NAN);
                side = 0;
                continue;
            }
            let Some(m) = self.lowest_mode(&c, true)? else {
                break;
            };
            if m.value.abs() <= 1e-10 * scale {
                break;
            }
            if m.value < 0.0 {
                (sb, fb) = (sc, m.value);
                dof = self.system.dof_label(self.kinetic_argmax(&m.shape));
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            } else {
                (sa, fa) = (sc, m.value);
                a = c;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
        }
        Ok((critical, dof))
    }
}

/// Factorization of the reduced tangent.
pub(crate) enum Factor {
    Empty,
    Cholesky(faer::linalg::solvers::Llt<f64>),
    /// A small indefinite tangent with no zero-stiffness mode (see
    /// [`Solver::nonsingular_lu`]): the same correction as its modes give.
    Lu(faer::linalg::solvers::PartialPivLu<f64>),
    /// The reduced tangent of a large model, sparse and definite.
    Sparse(faer::sparse::linalg::solvers::Llt<usize, f64>),
    /// The reduced tangent of a large model, sparse and indefinite.
    SparseLu(Box<faer::sparse::linalg::solvers::Lu<usize, f64>>),
    Modes(ReducedModes),
}

/// The tangent of one Newton iteration, ready to compute corrections.
pub(crate) struct TangentSolver {
    /// The full tangent K (n × n, sparse).
    pub(crate) k: SparseColMat<usize, f64>,
    pub(crate) ns: NullSpace,
    pub(crate) factor: Factor,
}

impl TangentSolver {
    /// Newton correction for the residuals of `snap` (its r and C, the
    /// constraint rows of its own C_q): Δq = Δq_p + N Δz with
    /// Δq_p = −Aᵀ(AAᵀ)⁻¹C and NᵀKN Δz = −Nᵀ(r + K Δq_p). With `check`, a
    /// residual on a zero-stiffness mode is an error (the load is not carried);
    /// otherwise that part is dropped.
    pub(crate) fn correction(
        &self,
        snap: &Snapshot,
        f_ref: f64,
        check: bool,
        solver: &Solver,
    ) -> Result<Vec<f64>, NewtonFailure> {
        let n = self.k.nrows();
        let mut kdq = vec![0.0; n];
        let mut dq = vec![0.0; n];
        if let Some(g) = &snap.gram {
            let mi = snap.rows.len();
            let y = g.solve(Mat::from_fn(mi, 1, |a, _| -snap.c[snap.rows[a]]));
            let y: Vec<f64> = (0..mi).map(|a| y[(a, 0)]).collect();
            super::mul_transpose(&snap.cq, &y, &mut dq);
        }
        mul_vec(&self.k, &dq, &mut kdq);
        let b: Vec<f64> = (0..n).map(|i| -(snap.r[i] + kdq[i])).collect();
        let br = self.ns.restrict(&b);
        let d = br.len();
        let dz: Vec<f64> = match &self.factor {
            Factor::Empty => Vec::new(),
            Factor::Cholesky(llt) => {
                let x = llt.solve(Mat::from_fn(d, 1, |i, _| br[i]));
                (0..d).map(|i| x[(i, 0)]).collect()
            }
            Factor::Lu(lu) => {
                let x = lu.solve(Mat::from_fn(d, 1, |i, _| br[i]));
                (0..d).map(|i| x[(i, 0)]).collect()
            }
            Factor::Sparse(llt) => {
                let x = llt.solve(Mat::from_fn(d, 1, |i, _| br[i]));
                (0..d).map(|i| x[(i, 0)]).collect()
            }
            Factor::SparseLu(lu) => {
                let x = lu.solve(Mat::from_fn(d, 1, |i, _| br[i]));
                (0..d).map(|i| x[(i, 0)]).collect()
            }
            Factor::Modes(modes) => {
                let mut x = vec![0.0; d];
                let mut driven = vec![0.0; d];
                for (i, &mu) in modes.values.iter().enumerate() {
                    let s: f64 = (0..d).map(|r| modes.vectors[(r, i)] * br[r]).sum();
                    let target = if mu.abs() <= modes.zero {
                        &mut driven
                    } else {
                        &mut x
                    };
                    let w = if mu.abs() <= modes.zero { s } else { s / mu };
                    for (r, t) in target.iter_mut().enumerate() {
                        *t += modes.vectors[(r, i)] * w;
                    }
                }
                if check {
                    // The force this free motion would have to take: M_r φ s.
                    let mr = solver.reduced_mass(&self.ns);
                    let force: Vec<f64> = (0..d)
                        .map(|r| (0..d).map(|c| mr[(r, c)] * driven[c]).sum())
                        .collect();
                    if norm_inf(&force) > (1e-8 * f_ref).max(solver.noise) {
                        let motion = self.ns.expand(&driven);
                        return Err(NewtonFailure::Fatal(solver.free_motion_error(&motion)));
                    }
                }
                x
            }
        };
        for (d, e) in dq.iter_mut().zip(self.ns.expand(&dz)) {
            *d += e;
        }
        Ok(dq)
    }
}

/// The lowest mode of a reduced tangent.
pub(crate) struct LowestMode {
    pub(crate) value: f64,
    pub(crate) shape: Vec<f64>,
    pub(crate) zero: f64,
}

/// Eigen-decomposition of a reduced pencil with its zero threshold.
pub(crate) struct ReducedModes {
    pub values: Vec<f64>,
    pub vectors: Mat<f64>,
    pub zero: f64,
}

/// Cholesky factor of a clearly positive definite matrix: every pivot keeps
/// at least 1e-10 of its diagonal entry (a scale-free test: it is the same
/// for any units of the coordinates).
pub(crate) fn definite_factor(a: &Mat<f64>) -> Option<faer::linalg::solvers::Llt<f64>> {
    let llt = a.llt(Side::Lower).ok()?;
    let l = llt.L();
    let ok = (0..a.nrows()).all(|i| {
        let d = a[(i, i)];
        d > 0.0 && l[(i, i)] * l[(i, i)] > 1e-10 * d
    });
    ok.then_some(llt)
}

/// Whether `phi` is (to 1e-6) a rigid motion of the whole assembly at q.
pub(crate) fn is_rigid_motion(system: &System, q: &[f64], phi: &[f64]) -> bool {
    let n = system.ndof();
    let norm = norm2(phi);
    if norm == 0.0 {
        return false;
    }
    // Translation x, y and rotation about the origin, as coordinate fields.
    let mut fields = vec![vec![0.0; n], vec![0.0; n], vec![0.0; n]];
    for b in &system.beams {
        for k in 0..b.node_count() {
            let i = b.dof0 + 4 * k;
            fields[0][i] = 1.0;
            fields[1][i + 1] = 1.0;
            fields[2][i] = -q[i + 1];
            fields[2][i + 1] = q[i];
            fields[2][i + 2] = -q[i + 3];
            fields[2][i + 3] = q[i + 2];
        }
    }
    for r in &system.rigid_bodies {
        let i = r.dof0;
        fields[0][i] = 1.0;
        fields[1][i + 1] = 1.0;
        fields[2][i] = -q[i + 1];
        fields[2][i + 1] = q[i];
        fields[2][i + 2] = 1.0;
    }
    for p in &system.point_masses {
        let i = p.dof0;
        fields[0][i] = 1.0;
        fields[1][i + 1] = 1.0;
        fields[2][i] = -q[i + 1];
        fields[2][i + 1] = q[i];
    }
    // Least-squares fit of phi by the three fields (Gram–Schmidt).
    let mut residual = phi.to_vec();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    for mut f in fields {
        for b in &basis {
            let p = dot(&f, b);
            f.iter_mut().zip(b).for_each(|(x, y)| *x -= p * y);
        }
        let nf = norm2(&f);
        if nf > 1e-12 {
            f.iter_mut().for_each(|x| *x /= nf);
            let p = dot(&residual, &f);
            residual.iter_mut().zip(&f).for_each(|(x, y)| *x -= p * y);
            basis.push(f);
        }
    }
    norm2(&residual) <= 1e-6 * norm
}
