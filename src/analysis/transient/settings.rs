//! Settings, state and counters of a transient run [SI units on each
//! field], apart from the integrator that uses them.

use crate::error::TransientError;
use crate::model::RayleighDamping;

/// Order n + m of the iteration matrix above which [`LinearSolver::Auto`]
/// takes the sparse path. Measured with `cargo bench --bench
/// transient_solver` (the cantilever of `models/cantilever.json` with more
/// elements, 2000 steps of 1 µs, whole run): dense/sparse 3.0/4.0 ms at 39
/// unknowns, 8.7/9.2 at 103, 11.3/11.9 at 119, 12.7/13.5 at 135,
/// 17.2/15.0 at 167, 46/34 at 263, 105/51 at 391. The paths cross between
/// 135 and 167 unknowns and differ by under 10 % around there; above, the
/// dense cost grows like (n + m)² per solve and (n + m)³ per
/// factorization, and its memory like (n + m)².
pub const SPARSE_THRESHOLD: usize = 150;

/// How the iteration matrix is factored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum LinearSolver {
    /// Dense up to [`SPARSE_THRESHOLD`] unknowns (coordinates plus
    /// constraint equations), sparse above.
    #[default]
    Auto,
    /// faer's dense LU with partial pivoting: memory (n + m)².
    Dense,
    /// faer's sparse LU, symbolic factorization reused: memory proportional
    /// to the nonzeros.
    Sparse,
}

/// Settings of a transient run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransientSettings {
    /// Time step h [SI: s].
    pub step: f64,
    /// End time [SI: s].
    pub end_time: f64,
    /// Spectral radius at infinity ρ∞ ∈ [0, 1].
    pub spectral_radius: f64,
    /// Newton tolerance on the scaled correction norm [–]; joints are held
    /// to tolerance × the assembly's size [SI: m] and weld angles to the
    /// tolerance [rad]. The default 1e-10 puts the Newton error of the
    /// built-in assembly's first bending frequency at 1.5e-8 (2e-6 at 1e-9:
    /// the residual a joint keeps is proportional to the vibration, so it
    /// acts as a compliance; measured against a 1e-12 run).
    pub tolerance: f64,
    /// Newton iterations per step before the factorization is renewed.
    pub max_iterations: usize,
    /// Dense or sparse factorization of the iteration matrix.
    pub solver: LinearSolver,
    /// The model's Rayleigh damping C = αM + βK (`None`: none).
    pub damping: Option<RayleighDamping>,
    /// Every step is the settings' step: no shorter step at contact onset
    /// (a step whose Newton iteration fails is still halved). The results
    /// are then smooth functions of the model's parameters, as a
    /// calibration needs; the onset control's accuracy is given up.
    pub fixed_step: bool,
}

impl Default for TransientSettings {
    fn default() -> Self {
        TransientSettings {
            step: 1e-6,
            end_time: 0.1,
            spectral_radius: 0.9,
            tolerance: 1e-10,
            max_iterations: 8,
            solver: LinearSolver::Auto,
            damping: None,
            fixed_step: false,
        }
    }
}

impl TransientSettings {
    /// Check the settings against each other.
    pub fn validate(&self) -> Result<(), TransientError> {
        if !(self.step > 0.0 && self.step.is_finite()) {
            return Err(TransientError::InvalidStep { step: self.step });
        }
        if !(self.end_time > self.step && self.end_time.is_finite()) {
            return Err(TransientError::InvalidEndTime {
                end_time: self.end_time,
                step: self.step,
            });
        }
        if !(0.0..=1.0).contains(&self.spectral_radius) {
            return Err(TransientError::InvalidSpectralRadius {
                value: self.spectral_radius,
            });
        }
        Ok(())
    }

    /// Number of steps to reach the end time.
    pub fn steps(&self) -> usize {
        (self.end_time / self.step - 1e-9).ceil() as usize
    }
}

/// The state of the system at one time.
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time [SI: s].
    pub t: f64,
    pub q: Vec<f64>,
    /// Velocities q̇.
    pub v: Vec<f64>,
    /// Accelerations q̈.
    pub a: Vec<f64>,
    /// Generalized-α pseudo-accelerations ā.
    pub abar: Vec<f64>,
    /// Constraint multipliers λ [SI: N, N m].
    pub lambda: Vec<f64>,
}

/// Counters of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunStats {
    pub steps: usize,
    pub newton_iterations: usize,
    pub factorizations: usize,
    /// Largest |C(q)| of positional constraint equations over all steps [SI: m].
    pub max_length_residual: f64,
    /// Largest |C(q)| of angular constraint equations (welds) [rad].
    pub max_angle_residual: f64,
    /// Energy the model's damping absorbed (the springs' dampers and the
    /// Rayleigh damping), Σ ½(D₀ + D₁)ᵀΔq over the steps [SI: J]; 0
    /// without damping, or when the run keeps no energy books
    /// ([`super::Integrator::without_energy_books`]: the impulse experiment).
    pub damping_dissipation: f64,
    /// Energy the integrator itself removed, Σ ½(a₀ + a₁)ᵀMΔq −
    /// ½(v₀ + v₁)ᵀMΔv over the steps [SI: J]: 0 at a spectral radius of 1,
    /// positive below ([`super::ledger`]); 0 when the run keeps no energy
    /// books (the impulse experiment).
    pub numerical_dissipation: f64,
}
