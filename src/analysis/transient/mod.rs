//! Implicit time integration of the constrained equations of motion
//! (index-3 DAE) with the generalized-α method.
//!
//! M q̈ + C_qᵀλ = Q_ext(q, t) − Q_int(q) − D(q, q̇),  C(q) = 0.
//!
//! Scheme (Chung & Hulbert 1993, in the index-3 form of Arnold & Brüls
//! 2007): with the pseudo-acceleration ā,
//! q₁ = q₀ + h v₀ + h²(½ − β) ā₀ + h²β ā₁,  v₁ = v₀ + h(1 − γ) ā₀ + hγ ā₁,
//! (1 − α_m) ā₁ + α_m ā₀ = (1 − α_f) a₁ + α_f a₀, and the equations of motion
//! and constraints hold exactly at t₁. Parameters from the spectral radius
//! at infinity ρ∞ (see [`super::dispersion::GenAlpha`]); ρ∞ = 1 is the
//! trapezoidal rule (no numerical damping).
//!
//! Newton's method solves for (q₁, μ = λ₁/β′), β′ = (1 − α_m)/((1 − α_f)βh²),
//! on the scaled iteration matrix [M + (K + γ′C_d + ∂(C_qᵀλ)/∂q)/β′, C_qᵀ; C_q, 0]
//! whose blocks are all of order one in h (constraint scaling). The
//! factorization is reused across steps while the contraction rate θ of the
//! iteration stays small, with the rigid rotation turned since it was
//! factored compensated ([`super::frame`]), so a free assembly that spins
//! keeps converging in one iteration; a step stops when the estimated remaining error
//! θ/(1 − θ)·‖Δq‖ is below the tolerance (Hairer & Wanner's test), so a
//! well-predicted step costs one residual and one back-substitution.
//! The step also requires every joint equation to hold to tolerance × size
//! [SI: m] (or tolerance [rad] for weld angles), checked directly.
//! Norm: max over coordinates of |Δqᵢ|·ℓᵢ/L, L the assembly's size [SI: m],
//! ℓᵢ the displacement a unit change of qᵢ causes (1 for positions, the
//! adjacent element length for slopes, the radius of gyration for rigid
//! angles). The rate estimate θ/(1 − θ) carries over from step to step
//! (floored at 1e-3).
//!
//! With the model's Rayleigh damping (`TransientSettings::damping`), the
//! force C q̇, C = αM + βK, joins D in the residual and γ′C joins the
//! iteration matrix ([`rayleigh`]: K is the reference stiffness turned with
//! the assembly's rigid rotation, so rigid motion feels no β damping).
//! Without it the integrator runs exactly as before.
//!
//! The iteration matrix is factored by faer ([`solver`]): densely for small
//! models, by a sparse LU with a fixed pattern for large ones
//! ([`LinearSolver`], [`SPARSE_THRESHOLD`]). The rotating-frame
//! compensation acts on the right-hand side and the correction only, so it
//! serves both paths alike.

pub mod contacts;
pub mod dispersion;
pub mod frame;
pub mod ledger;
mod predictor;
pub mod rayleigh;
mod scaling;
mod settings;
pub mod solver;

pub use settings::{LinearSolver, RunStats, State, TransientSettings, SPARSE_THRESHOLD};

use crate::error::TransientError;
use crate::linalg::vector::largest_weighted;
use crate::linalg::Scatter;
use crate::system::{Linearization, System};
use contacts::{add_contact_dissipation, ContactTracker};
use dispersion::GenAlpha;
use frame::RotatingFrame;
use ledger::StepLedger;
use rayleigh::RayleighForce;
use solver::{DenseLu, FactorFailure, Factorization, Placed, Positions, Product, SparseLu};

/// Contraction rate θ above which a factorization that has served at least
/// as many steps as it has unknowns is renewed (any factorization is renewed
/// above θ = 0.3). Measured on the built-in assembly (h = 1 µs, 100 ms):
/// 0.3 → 1.34 Newton iterations per step, 0.01 → 1.06 at one renewal per
/// ~100 steps. The minimum service keeps large models from refactoring often.
const REFRESH_RATE: f64 = 0.01;

/// The generalized-α integrator for one system.
pub struct Integrator<'s> {
    sys: &'s System,
    settings: TransientSettings,
    coef: GenAlpha,
    /// β′ = (1 − α_m)/((1 − α_f) β h²) and γ′ = γ/(βh).
    beta_p: f64,
    gamma_p: f64,
    /// 1/sᵢ of the correction norm.
    weights: Vec<f64>,
    /// The same for the constraint equations, and which of them are angles.
    row_weights: Vec<f64>,
    row_is_angle: Vec<bool>,
    lu: Factorization,
    /// Rigid rotation since `lu` was factored (see [`frame`]).
    frame: RotatingFrame,
    rhs: Vec<f64>,
    work: Vec<f64>,
    force: Vec<f64>,
    next: State,
    /// Convergence-rate estimate θ/(1 − θ) carried between steps.
    eta: f64,
    /// Renew the factorization at the start of the next Newton iteration.
    stale: bool,
    /// Steps taken since the last factorization.
    since_factor: usize,
    /// The current step [SI: s]: the settings' step, shortened at contact
    /// onsets and while impacts last.
    h: f64,
    /// Times on a run of whole steps are t₀ + k·h, not sums of h (whose
    /// round-off once left a last step of 2.6e-15 s, and an energy error
    /// 69 times the energy put in): the run's start t₀ and its k.
    grid: (f64, u64),
    /// The time the step being taken ends at [SI: s].
    t_next: f64,
    /// Contact states, impact speeds and statistics.
    pub contacts: ContactTracker,
    /// The model's Rayleigh damping, if any.
    rayleigh: Option<RayleighForce>,
    /// Scratch for each step's energy terms ([`ledger`]).
    ledger: StepLedger,
    /// Whether the steps' energy terms are booked into `stats`
    /// ([`Integrator::without_energy_books`]).
    books: bool,
    /// The state before a step that contact step control may repeat.
    saved: State,
    pub stats: RunStats,
}

/// The time the loads of a state started by
/// [`Integrator::state_after_release`] are evaluated at: the smallest
/// positive time, the time functions' right limit at 0.
pub const RELEASE_LOAD_TIME: f64 = f64::MIN_POSITIVE;

/// Shortest step the contact control may take, as a fraction of the
/// settings' step.
const MIN_STEP_FRACTION: f64 = 1.0 / 4096.0;

impl<'s> Integrator<'s> {
    pub fn new(sys: &'s System, settings: TransientSettings) -> Result<Self, TransientError> {
        settings.validate()?;
        let coef = GenAlpha::from_spectral_radius(settings.spectral_radius).map_err(|_| {
            TransientError::InvalidSpectralRadius {
                value: settings.spectral_radius,
            }
        })?;
        let h = settings.step;
        let (n, m) = (sys.ndof(), sys.constraint_count());
        let rayleigh = RayleighForce::new(sys, settings.damping);
        let beta_p = (1.0 - coef.alpha_m) / ((1.0 - coef.alpha_f) * coef.beta * h * h);
        let gamma_p = coef.gamma / (coef.beta * h);
        let sparse = match settings.solver {
            LinearSolver::Auto => n + m > SPARSE_THRESHOLD,
            LinearSolver::Dense => false,
            LinearSolver::Sparse => true,
        };
        let lu = if sparse {
            // The pattern: every position the assembly writes, zeros
            // included (at the reference, with multipliers and velocities
            // zero, so that the constraint Hessians and dampers are visited).
            let mut positions = Positions::default();
            let (lambda, v) = (vec![0.0; m], vec![0.0; n]);
            let at = Linearization {
                q: &sys.q0,
                lambda: Some(&lambda),
                time: 0.0,
                load_scale: 1.0,
            };
            let mut scratch = vec![0.0; n];
            add_iteration_matrix(sys, &at, &v, beta_p, gamma_p, &mut scratch, &mut positions);
            if let Some(r) = &rayleigh {
                r.add_matrix(sys, &at, gamma_p / beta_p, &mut positions);
            }
            let lu = SparseLu::new(n + m, &positions.0).map_err(|f| factor_error(sys, f, 0.0))?;
            Factorization::Sparse(Box::new(lu))
        } else {
            Factorization::Dense(Box::new(DenseLu::new(n + m)))
        };
        let size = characteristic_length(sys);
        let row_is_angle: Vec<bool> = sys
            .constraints
            .iter()
            .flat_map(|c| (0..c.rows()).map(|r| c.row_is_angle(r)))
            .collect();
        let mut row_weights = Vec::with_capacity(m);
        for c in &sys.constraints {
            row_weights
                .extend((0..c.rows()).map(|r| if c.row_is_angle(r) { 1.0 } else { 1.0 / size }));
        }
        let weights = (0..n).map(|i| length_scale(sys, i, size) / size).collect();
        let empty = State {
            t: 0.0,
            q: vec![0.0; n],
            v: vec![0.0; n],
            a: vec![0.0; n],
            abar: vec![0.0; n],
            lambda: vec![0.0; m],
        };
        Ok(Integrator {
            sys,
            settings,
            beta_p,
            gamma_p,
            coef,
            weights,
            row_weights,
            row_is_angle,
            lu,
            frame: RotatingFrame::new(sys),
            rhs: vec![0.0; n + m],
            work: vec![0.0; n + m],
            force: vec![0.0; n],
            saved: empty.clone(),
            next: empty,
            eta: 1.0,
            stale: true,
            since_factor: 0,
            h,
            grid: (f64::NAN, 0),
            t_next: 0.0,
            contacts: ContactTracker::new(sys, &sys.q0),
            rayleigh,
            ledger: StepLedger::new(n),
            books: true,
            stats: RunStats::default(),
        })
    }

    /// Change the step to h: new Newton scalings, refactor at the next
    /// iteration.
    fn set_step(&mut self, h: f64) {
        if h == self.h {
            return;
        }
        self.h = h;
        self.beta_p =
            (1.0 - self.coef.alpha_m) / ((1.0 - self.coef.alpha_f) * self.coef.beta * h * h);
        self.gamma_p = self.coef.gamma / (self.coef.beta * h);
        self.stale = true;
    }

    /// Book no energy terms: `stats.numerical_dissipation` and
    /// `stats.damping_dissipation` stay 0, for a run that reports no
    /// energy balance (the impulse experiment). The books cost the mass
    /// matrix's product with Δq and Δv at every step, and the damping
    /// force at its end: 15 % of the bare blade's impulse run. The state
    /// and every other statistic are the same to the last bit.
    pub fn without_energy_books(mut self) -> Self {
        self.books = false;
        self
    }

    /// The step the integrator takes next [SI: s].
    pub fn current_step(&self) -> f64 {
        self.h
    }

    pub fn settings(&self) -> &TransientSettings {
        &self.settings
    }

    /// Whether the iteration matrix is factored by the sparse LU.
    pub fn is_sparse(&self) -> bool {
        self.lu.is_sparse()
    }

    /// The state at rest in the reference configuration at t = 0, with
    /// consistent accelerations and multipliers: [M C_qᵀ; C_q 0][a; λ] = [Q; 0].
    pub fn initial_state(&mut self) -> Result<State, TransientError> {
        let n = self.sys.ndof();
        self.state_at(self.sys.q0.clone(), vec![0.0; n])
    }

    /// A state at t = 0 with the given coordinates and velocities (which must
    /// satisfy the constraints), with consistent accelerations and
    /// multipliers: [M C_qᵀ; C_q 0][a; λ] = [Q_ext − Q_int − D; −(C_q q̇)_q q̇].
    /// The velocity term is evaluated by central differences of C_q along q̇.
    pub fn state_at(&mut self, q: Vec<f64>, v: Vec<f64>) -> Result<State, TransientError> {
        self.consistent_state(q, v, 0.0)
    }

    /// [`Integrator::state_at`] with the loads' right limit t → 0⁺: a load
    /// released at t = 0 (`{"until": 0}`) is already gone, so the state
    /// starts with the released system's accelerations (a held equilibrium
    /// would start at a = 0 and lag the release by about half a step).
    /// The time functions are piecewise with their jumps at their
    /// parameters, so the smallest positive time is their right limit at 0.
    pub fn state_after_release(
        &mut self,
        q: Vec<f64>,
        v: Vec<f64>,
    ) -> Result<State, TransientError> {
        self.consistent_state(q, v, RELEASE_LOAD_TIME)
    }

    /// The state at t = 0 with the applied loads evaluated at `load_time`.
    fn consistent_state(
        &mut self,
        q: Vec<f64>,
        v: Vec<f64>,
        load_time: f64,
    ) -> Result<State, TransientError> {
        let (n, m) = (self.sys.ndof(), self.sys.constraint_count());
        // [M C_qᵀ; C_q 0] in the iteration matrix's storage (its pattern
        // covers these blocks); the next step refactors.
        self.stale = true;
        self.lu.clear();
        self.sys.mass().add_into(&mut self.lu);
        self.sys
            .add_constraint_jacobian(&q, &mut Placed::mirrored(&mut self.lu, n));
        self.lu
            .factor()
            .map_err(|f| factor_error(self.sys, f, 0.0))?;
        let mut rhs = vec![0.0; n + m];
        self.sys.external_force(&q, load_time, 1.0, &mut rhs[..n]);
        self.sys.internal_force(&q, &mut self.force);
        let mut damping = vec![0.0; n];
        self.sys
            .add_damping(&q, &v, &mut damping, None::<&mut Positions>);
        if let Some(r) = &mut self.rayleigh {
            r.add_force(self.sys, &q, &v, &mut damping);
        }
        for ((r, f), d) in rhs.iter_mut().zip(&self.force).zip(&damping) {
            *r -= f + d;
        }
        let speed = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if speed > 0.0 && m > 0 {
            // −(C_q q̇)_q q̇ ≈ −[C_q(q + εq̇) − C_q(q − εq̇)] q̇ / (2ε), as
            // products over the Jacobians' entries (no C_q stored).
            let eps = 1e-7 * characteristic_length(self.sys) / speed;
            for sign in [1.0, -1.0] {
                let shifted: Vec<f64> = q.iter().zip(&v).map(|(a, b)| a + sign * eps * b).collect();
                let mut product = Product {
                    x: &v,
                    y: &mut rhs[n..],
                    scale: -sign / (2.0 * eps),
                };
                self.sys.add_constraint_jacobian(&shifted, &mut product);
            }
        }
        self.lu.solve_in_place(&mut rhs);
        if let Some(i) = rhs.iter().position(|x| !x.is_finite()) {
            return Err(TransientError::Singular {
                time: 0.0,
                dof: self.dof_name(i),
            });
        }
        let a = rhs[..n].to_vec();
        self.contacts = ContactTracker::new(self.sys, &q);
        Ok(State {
            t: 0.0,
            q,
            v,
            abar: a.clone(),
            a,
            lambda: rhs[n..].to_vec(),
        })
    }

    fn dof_name(&self, column: usize) -> String {
        dof_name(self.sys, column)
    }

    /// rhs = −[(M a + Q_int + D − Q_ext + C_qᵀλ)/β′; C(q)] at `next`.
    fn residual(&mut self, t: f64) {
        let n = self.sys.ndof();
        let st = &self.next;
        let (dyn_part, con_part) = self.rhs.split_at_mut(n);
        self.sys.inertial_and_internal_force(&st.q, &st.a, dyn_part);
        self.sys.external_force(&st.q, t, 1.0, &mut self.force);
        for (r, f) in dyn_part.iter_mut().zip(&self.force) {
            *r -= f;
        }
        self.sys
            .add_damping(&st.q, &st.v, dyn_part, None::<&mut Positions>);
        if let Some(r) = &mut self.rayleigh {
            r.add_force(self.sys, &st.q, &st.v, dyn_part);
        }
        add_contact_dissipation(
            self.sys,
            &st.q,
            &st.v,
            &self.contacts.impact,
            dyn_part,
            None::<(f64, f64, &mut Positions)>,
        );
        self.sys.add_constraint_forces(&st.q, &st.lambda, dyn_part);
        let s = -1.0 / self.beta_p;
        dyn_part.iter_mut().for_each(|r| *r *= s);
        self.sys.constraint_residual(&st.q, con_part);
        con_part.iter_mut().for_each(|c| *c = -*c);
    }

    /// Factor the scaled iteration matrix at `next`.
    fn refactor(&mut self, t: f64) -> Result<(), TransientError> {
        let n = self.sys.ndof();
        let st = &self.next;
        let at = Linearization {
            q: &st.q,
            lambda: Some(&st.lambda),
            time: t,
            load_scale: 1.0,
        };
        self.lu.clear();
        let scratch = &mut self.work[..n];
        add_iteration_matrix(
            self.sys,
            &at,
            &st.v,
            self.beta_p,
            self.gamma_p,
            scratch,
            &mut self.lu,
        );
        if let Some(r) = &self.rayleigh {
            r.add_matrix(self.sys, &at, self.gamma_p / self.beta_p, &mut self.lu);
        }
        add_contact_dissipation(
            self.sys,
            &st.q,
            &st.v,
            &self.contacts.impact,
            scratch,
            Some((1.0 / self.beta_p, self.gamma_p / self.beta_p, &mut self.lu)),
        );
        self.lu.factor().map_err(|f| factor_error(self.sys, f, t))?;
        self.frame.anchor(&self.next.q);
        self.stats.factorizations += 1;
        self.since_factor = 0;
        self.stale = false;
        Ok(())
    }

    /// Whether |Cᵢ(q)|·sᵢ ≤ tolerance at `next` (sᵢ = 1/size for lengths,
    /// 1 for angles), so that joints hold to ~tolerance × size [SI: m].
    fn constraints_satisfied(&mut self) -> bool {
        let m = self.sys.constraint_count();
        let c = &mut self.work[..m];
        self.sys.constraint_residual(&self.next.q, c);
        c.iter()
            .zip(&self.row_weights)
            .all(|(c, w)| (c * w).abs() <= self.settings.tolerance)
    }

    /// Constant-acceleration predictor (a₁ = a₀); measured: linear
    /// extrapolation of a does not reduce the iterations, because a carries
    /// the Newton error of q amplified by 1/(βh²).
    fn predict(&mut self, from: &State) {
        let h = self.h;
        let GenAlpha {
            alpha_m,
            beta,
            gamma,
            ..
        } = self.coef;
        let nx = &mut self.next;
        nx.t = self.t_next;
        let n = from.q.len();
        predictor::predict(
            predictor::Coefficients {
                h,
                alpha_m,
                beta,
                gamma,
            },
            predictor::From {
                q: &from.q[..n],
                v: &from.v[..n],
                a: &from.a[..n],
                abar: &from.abar[..n],
            },
            predictor::Into {
                q: &mut nx.q[..n],
                v: &mut nx.v[..n],
                abar: &mut nx.abar[..n],
            },
        );
        nx.a.copy_from_slice(&from.a);
        nx.lambda.copy_from_slice(&from.lambda);
    }

    /// Advance `state` by one step.
    pub fn step(&mut self, state: &mut State) -> Result<(), TransientError> {
        let n = self.sys.ndof();
        let h = self.h;
        let t1 = self.t_next;
        let inv_bh2 = 1.0 / (self.coef.beta * h * h);
        let mut restarted = false;
        self.predict(state);
        self.frame.update(&self.next.q);
        let mut previous = f64::INFINITY;
        let mut k = 0;
        loop {
            if self.stale {
                self.refactor(t1)?;
            }
            self.residual(t1);
            let residual_norm = largest_weighted(&self.rhs, None);
            self.frame.to_reference(&mut self.rhs);
            self.lu.solve_in_place(&mut self.rhs);
            self.frame.from_reference(&mut self.rhs);
            let nx = &mut self.next;
            let (gamma_p, beta_p) = (self.gamma_p, self.beta_p);
            let (dq, w) = (&self.rhs[..n], &self.weights[..n]);
            let (q, v) = (&mut nx.q[..n], &mut nx.v[..n]);
            let (a, abar) = (&mut nx.a[..n], &mut nx.abar[..n]);
            for i in 0..n {
                let d = dq[i];
                q[i] += d;
                v[i] += gamma_p * d;
                a[i] += beta_p * d;
                abar[i] += inv_bh2 * d;
            }
            let norm = largest_weighted(dq, Some(w));
            for (l, d) in nx.lambda.iter_mut().zip(&self.rhs[n..]) {
                *l += self.beta_p * d;
            }
            k += 1;
            self.stats.newton_iterations += 1;
            if !norm.is_finite() {
                return Err(TransientError::NewtonFailure {
                    time: t1,
                    residual: residual_norm,
                    iterations: k,
                });
            }
            if k > 1 {
                let theta = norm / previous;
                if theta >= 1.0 || k > self.settings.max_iterations {
                    if restarted {
                        return Err(TransientError::NewtonFailure {
                            time: t1,
                            residual: residual_norm,
                            iterations: k,
                        });
                    }
                    // Renew the Jacobian at the predictor and start over.
                    restarted = true;
                    self.predict(state);
                    self.stale = true;
                    previous = f64::INFINITY;
                    continue;
                }
                self.eta = theta / (1.0 - theta);
                let served = self.since_factor >= self.lu.size();
                if theta > 0.3 || (theta > REFRESH_RATE && served) {
                    self.stale = true;
                }
            }
            let small = self.eta * norm <= self.settings.tolerance
                || norm <= 1e-3 * self.settings.tolerance;
            if small && self.constraints_satisfied() {
                break;
            }
            previous = norm;
        }
        self.eta = self.eta.max(1e-3);
        std::mem::swap(state, &mut self.next);
        // `next` now holds the state the step left.
        let (sys, left) = (self.sys, &self.next);
        if self.books {
            self.stats.numerical_dissipation += self.ledger.numerical_dissipation(sys, left, state);
            self.stats.damping_dissipation +=
                self.ledger
                    .damping_dissipation(sys, self.rayleigh.as_mut(), left, state);
        }
        self.stats.steps += 1;
        self.since_factor += 1;
        // `work[..m]` still holds C(q) of the accepted iterate, from the
        // stop test (`constraints_satisfied`).
        let m = self.sys.constraint_count();
        for (c, &angle) in self.work[..m].iter().zip(&self.row_is_angle) {
            let worst = if angle {
                &mut self.stats.max_angle_residual
            } else {
                &mut self.stats.max_length_residual
            };
            *worst = worst.max(c.abs());
        }
        Ok(())
    }

    /// Advance `state` by one accepted step of at most the settings' step,
    /// ending at `t_end` at the latest. Without contacts that is
    /// [`Integrator::step`]; with contacts a step in which one closes too
    /// deep, or whose Newton iteration fails, is repeated with a shorter
    /// step (see [`contacts`]), and steps stay short while impacts last.
    pub fn advance(&mut self, state: &mut State, t_end: f64) -> Result<(), TransientError> {
        let nominal = self.settings.step;
        let remaining = t_end - state.t;
        let cap = match self.settings.fixed_step {
            true => nominal,
            false => nominal.min(self.contacts.step_limit),
        };
        // Grow back towards the nominal step by at most 2× per step.
        let mut h = (2.0 * self.h).min(cap).min(remaining);
        // What would be left after this step is joined to it: a sliver
        // step of a thousandth of the step or less is never taken.
        if remaining - h <= SLIVER * nominal {
            h = remaining;
        }
        // A last whole step that round-off makes a hair short is whole.
        if (h - nominal).abs() <= 1e-9 * nominal {
            h = nominal;
        }
        if self.sys.contacts.is_empty() {
            self.set_step(h);
            self.t_next = self.time_after(state.t, h);
            self.step(state)?;
            self.on_grid(h);
            return Ok(());
        }
        let min_step = nominal * MIN_STEP_FRACTION;
        loop {
            self.set_step(h);
            self.t_next = self.time_after(state.t, h);
            self.contacts.begin_step(self.sys, &state.q, &state.v);
            self.saved.clone_from(state);
            let books = (
                self.stats.damping_dissipation,
                self.stats.numerical_dissipation,
            );
            let result = self.step(state);
            let retry = match &result {
                Err(TransientError::NewtonFailure { .. }) => Some(0.5 * h),
                Err(_) => None,
                Ok(()) if self.settings.fixed_step => None,
                Ok(()) => self.contacts.onset_check(self.sys, &state.q, h),
            };
            match retry {
                Some(shorter) if shorter >= min_step => {
                    if result.is_ok() {
                        self.stats.steps -= 1;
                    }
                    (
                        self.stats.damping_dissipation,
                        self.stats.numerical_dissipation,
                    ) = books;
                    state.clone_from(&self.saved);
                    h = shorter;
                }
                _ => {
                    result?;
                    self.on_grid(h);
                    self.contacts
                        .accept(self.sys, (state.t, &state.q, &state.v), h);
                    return Ok(());
                }
            }
        }
    }

    /// The end of a step of `h` from `t`: on a run of whole steps of the
    /// settings' step h₀, t₀ + (k + 1)·h₀ (a new run starts where `t` is
    /// off the current one's times); else t + h.
    fn time_after(&mut self, t: f64, h: f64) -> f64 {
        let nominal = self.settings.step;
        if h != nominal {
            return t + h;
        }
        let (t0, k) = self.grid;
        if t != t0 + k as f64 * nominal {
            self.grid = (t, 0);
        }
        self.grid.0 + (self.grid.1 + 1) as f64 * nominal
    }

    /// Counts an accepted step of `h` on the run of whole steps.
    fn on_grid(&mut self, h: f64) {
        if h == self.settings.step {
            self.grid.1 += 1;
        }
    }

    /// Integrate from `state` to the end time, calling `observe` after every
    /// step (and once for the initial state).
    pub fn run(
        &mut self,
        state: &mut State,
        mut observe: impl FnMut(&State),
    ) -> Result<RunStats, TransientError> {
        observe(state);
        let t_end = state.t + self.settings.steps() as f64 * self.settings.step;
        while t_end - state.t > 1e-9 * self.settings.step {
            self.advance(state, t_end)?;
            observe(state);
        }
        Ok(self.stats)
    }
}

/// Adds the scaled iteration matrix
/// [M + (K + γ′C_d + ∂(C_qᵀλ)/∂q)/β′, C_qᵀ; C_q, 0] at `at` (velocities v)
/// into `out`; `scratch` (length n) receives the damper forces, unused.
fn add_iteration_matrix(
    sys: &System,
    at: &Linearization,
    v: &[f64],
    beta_p: f64,
    gamma_p: f64,
    scratch: &mut [f64],
    out: &mut impl Scatter,
) {
    let n = sys.ndof();
    sys.mass().add_into(out);
    sys.add_tangent_stiffness(at, &mut Placed::scaled(out, 1.0 / beta_p));
    sys.add_damping(
        at.q,
        v,
        scratch,
        Some(&mut Placed::scaled(out, gamma_p / beta_p)),
    );
    sys.add_constraint_jacobian(at.q, &mut Placed::mirrored(out, n));
}

/// A last step this fraction of the step or shorter is joined to the one
/// before it.
const SLIVER: f64 = 1e-3;

/// Name of unknown i of [q; λ].
fn dof_name(sys: &System, i: usize) -> String {
    if i < sys.ndof() {
        sys.dof_label(i)
    } else {
        format!("constraint equation {}", i - sys.ndof())
    }
}

fn factor_error(sys: &System, failure: FactorFailure, time: f64) -> TransientError {
    match failure {
        FactorFailure::Singular { column } => TransientError::Singular {
            time,
            dof: dof_name(sys, column),
        },
        FactorFailure::Memory => TransientError::OutOfMemory {
            size: sys.ndof() + sys.constraint_count(),
        },
    }
}

/// The displacement [SI: m] that a unit change of coordinate i causes:
/// 1 for positions; for a beam slope the mean length of the adjacent
/// elements (δr' moves the centre line by ~δr'·Le); for a rigid body's
/// angle its radius of gyration √(J/m) (the assembly's `size` without
/// inertia). Newton corrections are measured in these units, relative to
/// the assembly's size: no constant of its own, so that the test is the
/// same at every scale.
fn length_scale(sys: &System, i: usize, size: f64) -> f64 {
    for b in &sys.beams {
        if (b.dof0..b.dof0 + 4 * b.node_count()).contains(&i) {
            let k = i - b.dof0;
            if k % 4 < 2 {
                return 1.0;
            }
            let node = k / 4;
            let s = &b.node_s;
            let before = if node > 0 { s[node] - s[node - 1] } else { 0.0 };
            let after = if node + 1 < s.len() {
                s[node + 1] - s[node]
            } else {
                0.0
            };
            let count = (node > 0) as u8 + (node + 1 < s.len()) as u8;
            return (before + after) / f64::from(count.max(1));
        }
    }
    for r in &sys.rigid_bodies {
        if i == r.dof0 + 2 {
            let gyration = (r.inertia / r.mass).sqrt();
            return if gyration > 0.0 { gyration } else { size };
        }
    }
    1.0
}

/// Size of the assembly [SI: m]: the largest beam length or extent of the
/// beam end nodes, body centres and point masses, or contact segment (1 m
/// for a single point without contacts: nothing else sets a length). No floor: joints are held to the same
/// fraction of a MEMS device as of a machine.
fn characteristic_length(sys: &System) -> f64 {
    let q = &sys.q0;
    let mut points: Vec<usize> = Vec::new();
    for b in &sys.beams {
        points.push(b.dof0);
        points.push(b.dof0 + 4 * (b.node_count() - 1));
    }
    points.extend(sys.rigid_bodies.iter().map(|r| r.dof0));
    points.extend(sys.point_masses.iter().map(|p| p.dof0));
    let extent = (0..2)
        .map(|axis| {
            let values = points.iter().map(|&i| q[i + axis]);
            values.clone().fold(f64::NEG_INFINITY, f64::max) - values.fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let longest = sys
        .beams
        .iter()
        .map(|b| b.node_s[b.node_s.len() - 1])
        .chain(sys.contacts.iter().map(|c| c.length()))
        .fold(0.0, f64::max);
    match longest.max(extent) {
        size if size > 0.0 && size.is_finite() => size,
        _ => 1.0,
    }
}
