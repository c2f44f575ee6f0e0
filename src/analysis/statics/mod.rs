//! Static equilibrium of the constrained assembly.
//!
//! Solves, for the coordinates q [SI: m, –, rad] and the constraint
//! multipliers λ,
//!
//! ```text
//! Q_int(q) − Q_ext(q) + C_qᵀ(q) λ = 0,     C(q) = 0,
//! ```
//!
//! i.e. the equations of motion with q̈ = 0: beam elastic forces and spring
//! forces (preloaded springs and torsion springs included) against constant
//! loads and gravity, the joints (supports to the ground among them)
//! carrying the rest.
//!
//! **Which loads.** A load enters with its value at `time` (default 0):
//! `constant` loads in full, a `step` starting at 0 in full, a `half_sine`
//! (zero at t = 0) and a step starting later not at all. Applied loads are
//! multiplied by the load factor `load_scale`; gravity is not.
//!
//! **Method.** Newton's method on the full equations in null-space form:
//! each step restores the constraints to first order with the minimum-norm
//! correction Δq_p = −A⁺C (A: the independent rows of C_q), then solves the
//! reduced tangent problem NᵀK N Δz = −Nᵀ(r + K Δq_p) on an orthonormal
//! basis N of null(C_q), where K = ∂(Q_int − Q_ext)/∂q + ∂(C_qᵀλ)/∂q is the
//! full tangent at the current multipliers. The multipliers are the
//! least-squares ones at every iterate, λ = −(AAᵀ)⁻¹A(Q_int − Q_ext), so the
//! residual r = Q_int − Q_ext + C_qᵀλ is the unbalanced force that no joint
//! can carry. A backtracking line search on ‖r‖ (plus the constraint
//! violation) damps the steps; load stepping (continuation) with adaptive
//! increments carries large deflections.
//!
//! **Load paths.** The equilibrium does not depend on the order in which
//! conservative loads are applied, but whether stepping reaches it does: a
//! slack string hangs far under gravity before its tension comes, an
//! assembly that only its loads hold (a pre-stressed mechanism, e.g. the
//! switch-off's ON state) has no equilibrium under gravity alone. The solve
//! ramps gravity first, then the applied loads up to their factor
//! ([`LoadPath::GravityFirst`]); when that fails it tries gravity and the
//! loads together, then the loads first, and reports the first error only
//! when every path failed. [`Equilibrium::branch`] says which path found it.
//!
//! **Contacts** act as nonlinear springs (their elastic law). Their
//! tangent nKδⁿ⁻¹ vanishes at δ = 0 and an open contact has none, so a
//! body resting on a contact, or a small gap away from it, would make the
//! Newton matrix singular: the Newton matrix (never the residual) gets a
//! regularizing stiffness for each contact whose own tangent is below it
//! ([`crate::mechanics::contact::ContactElement::regularization`]), so the iteration
//! closes the gap and converges to the exact equilibrium, where the
//! regularization has dropped out of any loaded contact stiffer than it.
//!
//! **Failures.** A reduced tangent that is singular in a direction the load
//! pushes means the assembly cannot carry the load: the error names the free
//! motion (the whole assembly unsupported, or the coordinate a mechanism
//! moves most). After each converged load step the reduced tangent must be
//! positive (semi)definite. An indefinite tangent after a large step may be
//! Newton's jump to another branch, not a loss of stability: the step is
//! cut until it is at most [`CONFIRM_STEP`] of the ramp. Only an indefinite
//! tangent at a converged state that close to a stable one is a loss of
//! stability (buckling, a limit point): the critical load factor is then
//! located by regula falsi on the lowest eigenvalue ω² of (NᵀKN, NᵀMN)
//! and reported, with the load path it was on, instead of an unstable or
//! wrong equilibrium.
//! The reduced-tangent machinery (factoring, corrections, zero modes,
//! stability) lives in the sibling module `reduced_tangent`.

pub mod balance;
mod branch;
mod continuation;
pub mod design_path;
mod newton;
pub mod prestress;
mod reduced_tangent;
pub mod start;

use crate::error::AnalysisError;
pub use crate::error::LoadPath;
use crate::linalg::null_space::{symmetrize, NullSpace, Projected};
use crate::linalg::sparse::mul_vec;
pub(crate) use crate::linalg::vector::{argmax_abs, dot, norm2, norm_inf};
use crate::linalg::{Scatter, Triplets};
use crate::mechanics::contact::Regularize;
use crate::system::{Linearization, System};
pub use branch::{Branch, BranchKind};
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;
use faer::{Mat, Side};
use reduced_tangent::{definite_factor, Factor, TangentSolver};

/// Settings of a static solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticSettings {
    /// Factor on the applied loads (not on gravity).
    pub load_scale: f64,
    /// Time at which the loads' time functions are evaluated [SI: s].
    pub time: f64,
    /// Relative force-residual tolerance (against the largest force).
    pub tolerance: f64,
    /// Newton iterations allowed per load step.
    pub max_iterations: usize,
    /// First load increment, as a fraction of each ramp.
    pub initial_increment: f64,
    /// Smallest load increment before giving up, as a fraction of each ramp.
    pub min_increment: f64,
    /// Most load steps (accepted and rejected) in all.
    pub max_steps: usize,
    /// Check that every converged load step is stable, and stop with
    /// [`AnalysisError::Unstable`] at the first that is not.
    pub check_stability: bool,
}

impl Default for StaticSettings {
    fn default() -> Self {
        StaticSettings {
            load_scale: 1.0,
            time: 0.0,
            tolerance: 1e-10,
            max_iterations: 25,
            initial_increment: 1.0,
            min_increment: 1e-4,
            max_steps: 400,
            check_stability: true,
        }
    }
}

/// A converged static equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct Equilibrium {
    /// Coordinates at equilibrium.
    pub q: Vec<f64>,
    /// Constraint multipliers (C_qᵀλ is the generalized joint force on q,
    /// with the sign of an internal force).
    pub lambda: Vec<f64>,
    /// The applied-load factor the equilibrium is at.
    pub load_scale: f64,
    /// Time at which the loads were evaluated [SI: s].
    pub time: f64,
    /// Accepted load steps.
    pub steps: usize,
    /// Newton iterations over all steps.
    pub iterations: usize,
    /// Final unbalanced force ‖Q_int − Q_ext + C_qᵀλ‖∞ [SI: N, N m].
    pub residual: f64,
    /// Final constraint violation ‖C‖∞ [SI: m, rad].
    pub constraint_violation: f64,
    /// How it was found (the load path from the reference, or a
    /// continuation from another design).
    pub branch: Branch,
}

impl Equilibrium {
    /// The linearization at this equilibrium (multipliers included).
    pub fn linearization(&self) -> Linearization<'_> {
        Linearization {
            q: &self.q,
            lambda: Some(&self.lambda),
            time: self.time,
            load_scale: self.load_scale,
        }
    }
}

/// Static equilibrium under the model's loads × `settings.load_scale`
/// and gravity, from the reference configuration.
pub fn solve_equilibrium(
    system: &System,
    settings: &StaticSettings,
) -> Result<Equilibrium, AnalysisError> {
    let solver = Solver::new(system, settings);
    let both = solver.has_gravity && settings.load_scale != 0.0;
    let paths: &[LoadPath] = if both {
        &[
            LoadPath::GravityFirst,
            LoadPath::Together,
            LoadPath::LoadsFirst,
        ]
    } else if solver.has_gravity {
        &[LoadPath::GravityOnly]
    } else {
        &[LoadPath::LoadsOnly]
    };
    let mut first_error = None;
    for &path in paths {
        let mut state = solver.reference_state();
        match solver.follow(&mut state, path) {
            Ok(()) => return Ok(solver.finish(state, Branch::reference(path))),
            // A fault of the model, not of the path: no other path helps.
            Err(e @ (AnalysisError::SingularMass { .. } | AnalysisError::EigenSolver { .. })) => {
                return Err(e)
            }
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    Err(first_error.unwrap_or(AnalysisError::NoFreedom))
}

/// Static equilibrium as [`solve_equilibrium`], along the one load path
/// `path` (no other is tried): e.g. to check that the equilibrium does not
/// depend on the order of the loads.
pub fn solve_equilibrium_along(
    system: &System,
    settings: &StaticSettings,
    path: LoadPath,
) -> Result<Equilibrium, AnalysisError> {
    let solver = Solver::new(system, settings);
    let mut state = solver.reference_state();
    solver.follow(&mut state, path)?;
    Ok(solver.finish(state, Branch::reference(path)))
}

/// Continue an equilibrium to another applied-load factor (same time and
/// gravity), e.g. for a load sweep.
pub fn continue_equilibrium(
    system: &System,
    from: &Equilibrium,
    load_scale: f64,
    settings: &StaticSettings,
) -> Result<Equilibrium, AnalysisError> {
    let settings = StaticSettings {
        load_scale,
        time: from.time,
        ..*settings
    };
    let solver = Solver::new(system, &settings);
    let mut state = State {
        q: from.q.clone(),
        lambda: from.lambda.clone(),
        gravity: 1.0,
        loads: from.load_scale,
        steps: from.steps,
        iterations: from.iterations,
        residual: from.residual,
        violation: from.constraint_violation,
    };
    solver.ramp(&mut state, Ramp::Loads, load_scale, LoadPath::GravityFirst)?;
    Ok(solver.finish(state, from.branch.clone()))
}

/// Where the continuation is.
#[derive(Debug, Clone)]
pub(crate) struct State {
    pub(crate) q: Vec<f64>,
    pub(crate) lambda: Vec<f64>,
    /// Fraction of gravity applied.
    pub(crate) gravity: f64,
    /// Applied-load factor.
    pub(crate) loads: f64,
    pub(crate) steps: usize,
    pub(crate) iterations: usize,
    pub(crate) residual: f64,
    pub(crate) violation: f64,
}

/// How Newton steps are damped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Damping {
    Full,
    LineSearch,
}

/// What a ramp steps: gravity's fraction, the loads' factor, or both at
/// once (gravity's fraction t with the loads at t × `loads`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Ramp {
    Gravity,
    Loads,
    Both { loads: f64 },
}

impl Ramp {
    /// The ramped parameter of a state.
    pub(crate) fn param(self, s: &State) -> f64 {
        match self {
            Ramp::Gravity | Ramp::Both { .. } => s.gravity,
            Ramp::Loads => s.loads,
        }
    }

    /// Sets the ramped parameter of a state.
    pub(crate) fn set(self, s: &mut State, v: f64) {
        match self {
            Ramp::Gravity => s.gravity = v,
            Ramp::Loads => s.loads = v,
            Ramp::Both { loads } => {
                s.gravity = v;
                s.loads = v * loads;
            }
        }
    }

    /// The load factor at parameter value v (for messages).
    pub(crate) fn load_factor(self, v: f64) -> f64 {
        match self {
            Ramp::Gravity => 0.0,
            Ramp::Loads => v,
            Ramp::Both { loads } => v * loads,
        }
    }
}

/// Largest step, as a fraction of a ramp, after which an indefinite
/// tangent is taken as a loss of stability rather than a jump to another
/// branch.
pub const CONFIRM_STEP: f64 = 1.0 / 1024.0;

/// Why one Newton solve at a fixed load failed.
pub(crate) enum NewtonFailure {
    /// Out of iterations or no descent: retry with a smaller increment.
    /// `repeats`: every iterate's Newton matrix would have been the same
    /// with the other contact regularization the solve was asked about, so
    /// a solve with it would repeat this one step by step.
    Stalled {
        iterations: usize,
        residual: f64,
        repeats: bool,
    },
    /// A definite answer (no support, mechanism).
    Fatal(AnalysisError),
}

/// What the residual looks like at one q.
pub(crate) struct Snapshot {
    /// r = Q_int − Q_ext + C_qᵀλ.
    pub(crate) r: Vec<f64>,
    pub(crate) lambda: Vec<f64>,
    pub(crate) c: Vec<f64>,
    /// A: the independent rows of C_q (sparse, |rows| × n).
    pub(crate) cq: SparseColMat<usize, f64>,
    pub(crate) ns: NullSpace,
    /// Independent constraint rows.
    pub(crate) rows: Vec<usize>,
    /// Sparse Cholesky factor of A Aᵀ.
    pub(crate) gram: Option<faer::sparse::linalg::solvers::Llt<usize, f64>>,
    pub(crate) merit: f64,
}

pub(crate) struct Solver<'a> {
    pub(crate) system: &'a System,
    pub(crate) settings: StaticSettings,
    pub(crate) has_gravity: bool,
    pub(crate) gravity_force: Vec<f64>,
    /// M's diagonal (kinetic shares of coordinates).
    pub(crate) mass_diagonal: Vec<f64>,
    /// Scale of each coordinate for step sizes: a length for positions, 1
    /// for slopes and angles.
    pub(crate) scales: Vec<f64>,
    /// Characteristic length of the assembly [SI: m].
    pub(crate) length: f64,
    /// Force below which residuals are round-off of the stiffest element [SI: N].
    pub(crate) noise: f64,
}

impl<'a> Solver<'a> {
    pub(crate) fn new(system: &'a System, settings: &StaticSettings) -> Self {
        let n = system.ndof();
        let mut gravity_force = vec![0.0; n];
        system.add_gravity(&mut gravity_force);
        let has_gravity = gravity_force.iter().any(|&g| g != 0.0);
        let length = system.length_scale();
        let mut scales = vec![length; n];
        for b in &system.beams {
            for k in 0..b.node_count() {
                scales[b.dof0 + 4 * k + 2] = 1.0;
                scales[b.dof0 + 4 * k + 3] = 1.0;
            }
        }
        for r in &system.rigid_bodies {
            scales[r.dof0 + 2] = 1.0;
        }
        let stiff = system.stiffest_ea();
        Solver {
            system,
            settings: *settings,
            has_gravity,
            gravity_force,
            mass_diagonal: system.mass().diagonal(),
            scales,
            length,
            noise: 256.0 * f64::EPSILON * stiff,
        }
    }

    fn reference_state(&self) -> State {
        State {
            q: self.system.q0.clone(),
            lambda: vec![0.0; self.system.constraint_count()],
            gravity: 0.0,
            loads: 0.0,
            steps: 0,
            iterations: 0,
            residual: 0.0,
            violation: 0.0,
        }
    }

    /// Gravity and the applied loads from the state (the reference) to
    /// their full values along `path`.
    fn follow(&self, state: &mut State, path: LoadPath) -> Result<(), AnalysisError> {
        let loads = self.settings.load_scale;
        match path {
            LoadPath::GravityFirst | LoadPath::GravityOnly | LoadPath::LoadsOnly => {
                if self.has_gravity {
                    self.ramp(state, Ramp::Gravity, 1.0, path)?;
                }
                self.ramp(state, Ramp::Loads, loads, path)
            }
            LoadPath::Together => self.ramp(state, Ramp::Both { loads }, 1.0, path),
            LoadPath::LoadsFirst => {
                self.ramp(state, Ramp::Loads, loads, path)?;
                self.ramp(state, Ramp::Gravity, 1.0, path)
            }
        }
    }

    fn finish(&self, s: State, branch: Branch) -> Equilibrium {
        Equilibrium {
            q: s.q,
            lambda: s.lambda,
            load_scale: s.loads,
            time: self.settings.time,
            steps: s.steps,
            iterations: s.iterations,
            residual: s.residual,
            constraint_violation: s.violation,
            branch,
        }
    }

    /// Q_int − Q_ext at the given gravity fraction and load factor.
    fn unbalanced(&self, q: &[f64], gravity: f64, loads: f64, out: &mut [f64]) {
        let n = q.len();
        let mut ext = vec![0.0; n];
        self.system
            .external_force(q, self.settings.time, loads, &mut ext);
        self.system.internal_force(q, out);
        for i in 0..n {
            out[i] -= ext[i] - (1.0 - gravity) * self.gravity_force[i];
        }
    }

    /// Force scale of a load level: the largest applied, internal or joint force.
    fn force_reference(&self, snap: &Snapshot, q: &[f64], gravity: f64, loads: f64) -> f64 {
        let n = q.len();
        let mut ext = vec![0.0; n];
        self.system
            .external_force(q, self.settings.time, loads, &mut ext);
        let mut int = vec![0.0; n];
        self.system.internal_force(q, &mut int);
        let g = self.gravity_force.iter().map(|x| x.abs() * gravity);
        let f = ext
            .iter()
            .chain(&int)
            .map(|x| x.abs())
            .chain(g)
            .fold(0.0, f64::max);
        let li: Vec<f64> = snap.rows.iter().map(|&i| snap.lambda[i]).collect();
        let mut forces = vec![0.0; n];
        mul_transpose(&snap.cq, &li, &mut forces);
        f.max(norm_inf(&forces))
    }

    pub(crate) fn snapshot(&self, q: &[f64], gravity: f64, loads: f64) -> Snapshot {
        let sys = self.system;
        let (n, m) = (sys.ndof(), sys.constraint_count());
        let mut f = vec![0.0; n];
        self.unbalanced(q, gravity, loads, &mut f);
        let mut c = vec![0.0; m];
        sys.constraint_residual(q, &mut c);
        let mut all = Triplets::new(m, n);
        sys.add_constraint_jacobian(q, &mut all);
        let ns = NullSpace::new(m, n, all.entries());
        let rows: Vec<usize> = (0..m).filter(|i| !ns.redundant_rows.contains(i)).collect();
        let mi = rows.len();
        // A (independent rows, renumbered) and A Aᵀ, both sparse.
        let mut index = vec![usize::MAX; m];
        for (a, &i) in rows.iter().enumerate() {
            index[i] = a;
        }
        let mut a_rows = Triplets::new(mi, n);
        for (i, j, v) in all.entries() {
            if index[i] != usize::MAX {
                a_rows.add(index[i], j, v);
            }
        }
        let cq = a_rows.to_sparse();
        let gram = (mi > 0)
            .then(|| gram_matrix(&cq).sp_cholesky(Side::Lower).ok())
            .flatten();
        let mut lambda = vec![0.0; m];
        let mut r = f.clone();
        if let Some(g) = &gram {
            let mut af = vec![0.0; mi];
            mul_vec(&cq, &f, &mut af);
            let li = g.solve(Mat::from_fn(mi, 1, |a, _| -af[a]));
            let li: Vec<f64> = (0..mi).map(|a| li[(a, 0)]).collect();
            for (a, &i) in rows.iter().enumerate() {
                lambda[i] = li[a];
            }
            let mut forces = vec![0.0; n];
            mul_transpose(&cq, &li, &mut forces);
            r.iter_mut().zip(&forces).for_each(|(rj, fj)| *rj += fj);
        }
        let merit = norm2(&r) + norm2(&c) / self.length;
        Snapshot {
            r,
            lambda,
            c,
            cq,
            ns,
            rows,
            gram,
            merit,
        }
    }
}

/// y = Aᵀ x for a compressed-column A.
pub(crate) fn mul_transpose(a: &SparseColMat<usize, f64>, x: &[f64], y: &mut [f64]) {
    let a = a.as_ref();
    for (j, yj) in y.iter_mut().enumerate().take(a.ncols()) {
        *yj = a
            .row_idx_of_col(j)
            .zip(a.val_of_col(j))
            .map(|(i, v)| v * x[i])
            .sum();
    }
}

/// A Aᵀ for a compressed-column A (rows of a few joints share columns).
fn gram_matrix(a: &SparseColMat<usize, f64>) -> SparseColMat<usize, f64> {
    let ar = a.as_ref();
    let mut g = Triplets::new(ar.nrows(), ar.nrows());
    for j in 0..ar.ncols() {
        let entries: Vec<(usize, f64)> = ar
            .row_idx_of_col(j)
            .zip(ar.val_of_col(j))
            .map(|(i, v)| (i, *v))
            .collect();
        for &(r, u) in &entries {
            for &(c, v) in &entries {
                g.add(r, c, u * v);
            }
        }
    }
    g.to_sparse()
}
