//! Linearized modal analysis of the constrained system.
//!
//! At a state (q, λ): K = ∂(Q_int − Q_ext)/∂q + ∂(C_qᵀλ)/∂q, M constant.
//! With N an orthonormal basis of null(C_q): K_r = NᵀKN, M_r = NᵀMN, and
//! K_r x = ω² M_r x is solved by Cholesky reduction. f = √max(ω², 0)/2π [Hz].
//!
//! For a large reduced problem (> [`LANCZOS_MIN_SIZE`] coordinates, at most a
//! quarter of them wanted) only the requested modes are computed, by
//! shift-invert Lanczos ([`super::lanczos`]); max|ω²| below is then the
//! estimate maxᵢ (K_r)ᵢᵢ/(M_r)ᵢᵢ. On free beams of 128 and 500 elements the
//! rigid count (3) is unchanged by that estimate, and frequencies agree with
//! the dense path to 1e-14 (tests/large_modal.rs).
//!
//! Zero-frequency (rigid-body or mechanism) modes are those with
//! |ω²| ≤ tol, tol = [`ModalSettings::rigid_tolerance`] · ε · max|ω²|, either
//! as the solver returns it or after the Rayleigh refinement below.
//! Measured on free beams of 8–500 elements, the solver's zero eigenvalues
//! scatter at 0.02–0.12 · ε · max|ω²| while the first bending mode sits at
//! ≥ 1e4 · ε · max|ω²| (500 elements; 6e10 at 8). On the paper's assembly
//! with 2 uniform elements (a rigid body and a point mass on the blade) one
//! zero eigenvalue came out at 43 (faer) to 69 (in-house) · ε · max|ω²|, so the
//! solver's value alone is not a safe test; the refined quotient of a rigid
//! motion is zero up to the square of the solver's error, which separates
//! the two kinds by many orders of magnitude. Default factor: 64.
//!
//! Each elastic mode's ω² is then refined by its Rayleigh quotient
//! 2U(φ)/φᵀMφ, with U evaluated from strain variations: the dense solver's ω²
//! is only accurate to ~ε·max|ω²| absolutely, which a short element (e.g. an
//! attachment node 0.19 mm from a mesh node) makes 2e-7 of the first
//! bending ω². Each elastic mode is classified by where its strain energy
//! ½φᵀKφ sits: beam axial, beam bending, or springs.

use super::eigen::{solve_generalized, EigenFailure};
use super::lanczos::{lowest_modes, max_eigenvalue_estimate};
use super::reduce::NullSpace;
use crate::error::AnalysisError;
use crate::system::{EnergyBreakdown, Linearization, System};
use faer::Mat;
use serde::Serialize;

/// Settings of a modal analysis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModalSettings {
    /// Number of modes to report, rigid ones included (`None` = all).
    pub modes: Option<usize>,
    /// Multiple of ε·max|ω²| below which ω² counts as zero.
    pub rigid_tolerance: f64,
    /// Eigensolver choice.
    pub method: EigenMethod,
}

/// Which eigensolver a modal analysis uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EigenMethod {
    /// Lanczos when the reduced size exceeds [`LANCZOS_MIN_SIZE`] and at most
    /// a quarter of the modes are wanted; dense otherwise. A Lanczos failure
    /// falls back to the dense solver.
    #[default]
    Auto,
    /// Dense Cholesky reduction: all eigenvalues, vectors for the
    /// requested modes ([`super::eigen::solve_generalized`]).
    Dense,
    /// Shift-invert Lanczos ([`super::lanczos`]) for the requested modes only.
    Lanczos,
}

/// Reduced size above which [`EigenMethod::Auto`] may choose Lanczos.
pub const LANCZOS_MIN_SIZE: usize = 300;

impl Default for ModalSettings {
    fn default() -> Self {
        ModalSettings {
            modes: None,
            rigid_tolerance: 64.0,
            method: EigenMethod::Auto,
        }
    }
}

/// What a mode mostly does.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ModeKind {
    /// Zero frequency: rigid-body motion or a free mechanism.
    Rigid,
    Bending,
    Axial,
    /// Energy mostly in springs (e.g. a body rocking on a torsion spring).
    Spring,
}

impl std::fmt::Display for ModeKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = match self {
            ModeKind::Rigid => "rigid",
            ModeKind::Bending => "bending",
            ModeKind::Axial => "axial",
            ModeKind::Spring => "spring",
        };
        f.write_str(s)
    }
}

/// Fractions of a mode's strain energy.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyFractions {
    pub axial: f64,
    pub bending: f64,
    pub springs: f64,
}

/// One mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Mode {
    /// Mode number, 1-based, in ascending frequency.
    pub index: usize,
    /// Natural frequency [SI: Hz]; 0 for rigid modes.
    pub frequency_hz: f64,
    /// Eigenvalue ω² [SI: rad²/s²] (negative = unstable direction).
    pub eigenvalue: f64,
    pub kind: ModeKind,
    /// Strain-energy split (all zero for rigid modes).
    pub energy: EnergyFractions,
    /// Mass-normalized shape in the global coordinates (φᵀMφ = 1).
    #[serde(skip)]
    pub shape: Vec<f64>,
}

/// Result of a modal analysis.
#[derive(Debug, Clone, Serialize)]
pub struct ModalResult {
    /// Number of coordinates.
    pub dofs: usize,
    /// Number of constraint equations.
    pub constraints: usize,
    /// Labels of joints with redundant equations.
    pub redundant_constraints: Vec<String>,
    /// Dimension of the reduced problem.
    pub reduced_dofs: usize,
    /// Number of zero-frequency modes.
    pub rigid_modes: usize,
    pub modes: Vec<Mode>,
}

impl ModalResult {
    /// Elastic modes of a kind, ascending.
    pub fn of_kind(&self, kind: ModeKind) -> impl Iterator<Item = &Mode> {
        self.modes.iter().filter(move |m| m.kind == kind)
    }

    /// The first bending mode, if any was computed.
    pub fn first_bending(&self) -> Option<&Mode> {
        self.of_kind(ModeKind::Bending).next()
    }
}

/// Modal analysis at the system's reference configuration (unloaded, λ = 0).
pub fn modal_at_reference(
    system: &System,
    settings: &ModalSettings,
) -> Result<ModalResult, AnalysisError> {
    modal(system, &system.reference(), settings)
}

/// The problem linearized at a state and reduced to the free coordinates:
/// N, an orthonormal basis of null(C_q); K_r = NᵀKN and M_r = NᵀMN (units
/// of K and M per pair of reduced coordinates).
#[derive(Debug, Clone)]
pub struct ReducedProblem {
    pub null_space: NullSpace,
    pub stiffness: Mat<f64>,
    pub mass: Mat<f64>,
}

impl ReducedProblem {
    /// Tangent stiffness and constraint Jacobian at `at`, their null space,
    /// the projections; fails if the constraints leave no free coordinate.
    pub fn new(system: &System, at: &Linearization) -> Result<Self, AnalysisError> {
        let n = system.ndof();
        let mut k = Mat::zeros(n, n);
        system.tangent_stiffness(at, &mut k);
        let mut cq = Mat::zeros(system.constraint_count(), n);
        system.constraint_jacobian(at.q, &mut cq);
        let null_space = NullSpace::new(&cq);
        if null_space.dim() == 0 {
            return Err(AnalysisError::NoFreedom);
        }
        Ok(ReducedProblem {
            stiffness: null_space.project(&k),
            mass: null_space.project(system.mass().dense()),
            null_space,
        })
    }
}

/// Modal analysis linearized at `at`.
pub fn modal(
    system: &System,
    at: &Linearization,
    settings: &ModalSettings,
) -> Result<ModalResult, AnalysisError> {
    let n = system.ndof();
    let mass = system.mass();
    let ReducedProblem {
        null_space: ns,
        stiffness: kr,
        mass: mr,
    } = ReducedProblem::new(system, at)?;
    let eigen_error = |e: EigenFailure| match e {
        EigenFailure::SingularMass { direction } => {
            let full = ns.expand(&direction, n);
            let i = (0..n)
                .max_by(|&a, &b| full[a].abs().total_cmp(&full[b].abs()))
                .unwrap_or(0);
            AnalysisError::SingularMass {
                dof: system.dof_label(i),
                path: system.dof_model_path(i),
            }
        }
        EigenFailure::NoConvergence => AnalysisError::EigenSolver { size: ns.dim() },
    };
    let dim = ns.dim();
    let count = settings.modes.map_or(dim, |c| c.min(dim));
    let lanczos = match settings.method {
        EigenMethod::Dense => false,
        EigenMethod::Lanczos => count < dim,
        EigenMethod::Auto => dim > LANCZOS_MIN_SIZE && 4 * count <= dim,
    };
    let partial = if lanczos {
        match lowest_modes(&kr, &mr, count) {
            Ok(e) => Some(e),
            Err(e) if settings.method == EigenMethod::Lanczos => return Err(eigen_error(e)),
            Err(_) => None,
        }
    } else {
        None
    };
    // With a partial spectrum, max|ω²| is estimated by maxᵢ (K_r)ᵢᵢ/(M_r)ᵢᵢ
    // (a Rayleigh quotient: ≤ max|ω²|, within a modest factor of it).
    let (eig, lmax) = match partial {
        Some(e) => (e, max_eigenvalue_estimate(&kr, &mr)),
        None => {
            let e = solve_generalized(&kr, &mr, count).map_err(eigen_error)?;
            let lmax = e.spectrum.max_abs().unwrap_or(0.0);
            (e, lmax)
        }
    };
    let tol = settings.rigid_tolerance * f64::EPSILON * lmax;
    // Zero eigenvalues of the whole spectrum, also beyond the modes asked for.
    let mut rigid_modes = eig
        .count_within(tol)
        .unwrap_or_else(|| eig.values.iter().filter(|v| v.abs() <= tol).count());
    let shapes: Vec<Vec<f64>> = (0..count)
        .map(|i| ns.expand(eig.vectors.col_as_slice(i), n))
        .collect();
    // Rayleigh quotients with the cancellation-free energy form, for the
    // modes above the solver's noise bound: the dense solver's ω² carries an
    // absolute error ~ε·max|ω²|.
    let elastic: Vec<usize> = (0..count).filter(|&i| eig.values[i].abs() > tol).collect();
    let phis: Vec<&[f64]> = elastic.iter().map(|&i| shapes[i].as_slice()).collect();
    let mut energies = vec![EnergyBreakdown::default(); elastic.len()];
    system.stiffness_quadratic_forms(at, &phis, &mut energies);
    let mut energy_of = elastic.iter().zip(&energies).peekable();
    let mut modes = Vec::with_capacity(count);
    for (i, shape) in shapes.into_iter().enumerate() {
        let zero = EnergyFractions {
            axial: 0.0,
            bending: 0.0,
            springs: 0.0,
        };
        let (kind, energy, value) = match energy_of.next_if(|(&j, _)| j == i) {
            None => (ModeKind::Rigid, zero, eig.values[i]),
            Some((_, energy)) => {
                let refined = 2.0 * energy.total() / mass.quadratic_form(&shape);
                if refined.abs() <= tol {
                    // Above the solver's noise bound, but it strains nothing.
                    rigid_modes += 1;
                    (ModeKind::Rigid, zero, refined)
                } else {
                    let (kind, fractions) = classify(*energy);
                    (kind, fractions, refined)
                }
            }
        };
        let frequency_hz = if kind == ModeKind::Rigid {
            0.0
        } else {
            value.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
        };
        modes.push(Mode {
            index: i + 1,
            frequency_hz,
            eigenvalue: value,
            kind,
            energy,
            shape,
        });
    }
    let redundant_constraints = redundant_labels(system, &ns.redundant_rows);
    Ok(ModalResult {
        dofs: n,
        constraints: system.constraint_count(),
        redundant_constraints,
        reduced_dofs: ns.dim(),
        rigid_modes,
        modes,
    })
}

fn classify(e: EnergyBreakdown) -> (ModeKind, EnergyFractions) {
    let total = e.axial.abs() + e.bending.abs() + e.springs.abs();
    let frac = |x: f64| if total > 0.0 { x.abs() / total } else { 0.0 };
    let fr = EnergyFractions {
        axial: frac(e.axial),
        bending: frac(e.bending),
        springs: frac(e.springs),
    };
    let kind = if fr.springs > fr.axial && fr.springs > fr.bending {
        ModeKind::Spring
    } else if fr.axial > fr.bending {
        ModeKind::Axial
    } else {
        ModeKind::Bending
    };
    (kind, fr)
}

fn redundant_labels(system: &System, rows: &[usize]) -> Vec<String> {
    let mut labels: Vec<String> = Vec::new();
    for &r in rows {
        let idx = system.constraint_rows.partition_point(|&start| start <= r) - 1;
        let label = system.constraints[idx].label().to_string();
        if !labels.contains(&label) {
            labels.push(label);
        }
    }
    labels
}
