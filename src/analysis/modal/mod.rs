//! Linearized modal analysis of the constrained system.
//!
//! At a state (q, λ): K = ∂(Q_int − Q_ext)/∂q + ∂(C_qᵀλ)/∂q, M constant.
//! With N an orthonormal basis of null(C_q) ([`crate::linalg::null_space`]):
//! K_r = NᵀKN, M_r = NᵀMN, assembled directly in the reduced coordinates
//! (no full-size matrix is formed), and K_r x = ω² M_r x is solved.
//! f = √max(ω², 0)/2π [Hz].
//!
//! 1. Zero-frequency (rigid-body or mechanism) modes are counted from the
//!    kinematics ([`super::zero_modes`]), not from a threshold on the
//!    spectrum, and deflated: the eigensolver sees only the elastic
//!    spectrum, so nothing elastic is ever called rigid.
//! 2. Elastic modes: up to [`DENSE_MAX`] reduced coordinates, the dense
//!    path ([`crate::linalg::dense`]) with the zero modes moved below the
//!    spectrum by an exact rank-k shift; above it, K_r and M_r stay sparse
//!    and the lowest modes come from shift-invert Lanczos
//!    ([`crate::linalg::krylov`]) M-orthogonal to the zero modes, with
//!    memory proportional to the nonzeros. A dense solve whose lowest
//!    modes' bounds exceed [`ACCURACY_WARNING`] is repeated by shift-invert
//!    ([`EigenMethod::Auto`]).
//! 3. Each elastic ω² is refined by its Rayleigh quotient 2U(φ)/φᵀMφ, U
//!    from strain variations (cancellation-free): a solver's ω² carries an
//!    absolute error ~ε·max|ω²|, which a fine mesh or a short element makes
//!    larger than the lowest ω².
//! 4. Each elastic mode reports `error_bound`, a bound on the relative
//!    frequency error that the eigen-solve and round-off leave (not the
//!    discretization error): with the M_r-normalized residual
//!    ‖r‖ = ‖K_r x − ω² M_r x‖_{M_r⁻¹} and the gap δ to the nearest other
//!    computed ω² outside its cluster of repeated values (within 1e-6),
//!    |Δω²| ≤ min(‖r‖, ‖r‖²/δ) (Krylov–Bogoliubov and the
//!    quadratic residual bound of a Rayleigh quotient), so
//!    |Δf|/f ≤ ½ min(‖r‖, ‖r‖²/δ)/ω² + √dim·ε (the round-off of the
//!    refined quotient's sums) + ½ R/U (R the energy form's own round-off
//!    estimate, U = ½φᵀKφ: the rounding of the stiff terms a soft mode's
//!    strain cancels).
//! 5. Each elastic mode is classified by where its strain energy ½φᵀKφ
//!    sits: beam axial, beam bending, or springs.
//! 6. The state is checked for equilibrium ([`super::statics::balance`]:
//!    force balance with the given or least-squares multipliers, and the
//!    constraints, to [`super::statics::balance::BALANCE_TOLERANCE`]). Only
//!    at an equilibrium is the linearization a vibration (ω² > 0) or an
//!    instability (ω² < 0). A mode whose refined ω² is negative beyond its
//!    error bound (a bound below ½, so the sign is certain) is
//!    [`ModeKind::Unstable`] at an equilibrium (it grows as e^{√|ω²| t})
//!    and [`ModeKind::Negative`] at a state that is none (the unloaded
//!    reference of a preloaded model: a direction of negative stiffness of
//!    a linearization that describes no motion about that state). Its
//!    frequency is reported as −√|ω²|/2π [Hz]: the magnitude of the
//!    imaginary frequency with a minus sign, never 0.

use super::statics::balance::unbalanced_force;
use super::zero_modes::zero_modes;
use crate::error::AnalysisError;
use crate::linalg::dense::{solve_generalized, MassFactor};
use crate::linalg::krylov::{lowest_modes_refined, KrylovSettings};
use crate::linalg::null_space::{symmetrize, NullSpace, Projected};
use crate::linalg::sparse::mul_vec;
use crate::linalg::sparse::on_common_pattern;
use crate::linalg::vector::{argmax_abs, dot};
use crate::linalg::{EigenFailure, Triplets};
use crate::system::{EnergyBreakdown, Linearization, System};
use faer::linalg::solvers::Solve;
use faer::sparse::SparseColMat;
use faer::{Mat, Side};
use rayon::prelude::*;

mod result;
pub use result::{EnergyFractions, EquilibriumCheck, ModalResult, Mode, ModeKind, RefusedMode};

/// Settings of a modal analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ModalSettings {
    /// Number of modes to report, rigid ones included (`None` = all, dense
    /// path only).
    pub modes: Option<usize>,
    /// Eigensolver choice.
    pub method: EigenMethod,
}

/// Which eigensolver a modal analysis uses for the elastic modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EigenMethod {
    /// Dense up to [`DENSE_MAX`] reduced coordinates or when all modes are
    /// wanted, sparse shift-invert otherwise; a dense solve whose lowest
    /// modes' error bounds exceed [`ACCURACY_WARNING`] is repeated by
    /// shift-invert and the better result kept.
    #[default]
    Auto,
    /// Dense Cholesky reduction and the QR algorithm ([`crate::linalg::dense`]).
    Dense,
    /// Sparse shift-invert Lanczos ([`crate::linalg::krylov`]).
    Sparse,
}

/// Reduced size above which [`EigenMethod::Auto`] chooses the sparse path.
pub const DENSE_MAX: usize = 300;

/// Relative frequency error bound above which the solve, not the mesh,
/// limits a reported frequency (a Hermite mesh with 8 elements per half
/// wave is ~1e-5 off, so a finer bound is below any useful mesh).
pub const ACCURACY_WARNING: f64 = 1e-7;

/// Relative frequency error bound above which a mode is refused: not
/// reported as a frequency (the issue-37 criterion: a frequency printed
/// is right to 1e-5).
pub const REFUSE_BOUND: f64 = 1e-5;

/// Total beam elements from which the round-off of the stiffness, not the
/// model, is what limits a mode's accuracy (a cantilever's bound reaches
/// 1e-7 near 2,000 elements).
const FINE_MESH_ELEMENTS: f64 = 1000.0;

/// Modal analysis at the system's reference configuration (unloaded, λ = 0).
pub fn modal_at_reference(
    system: &System,
    settings: &ModalSettings,
) -> Result<ModalResult, AnalysisError> {
    modal(system, &system.reference(), settings)
}

/// The elastic modes from one eigensolver path.
struct Elastic {
    sparse: bool,
    certified: bool,
    shapes: Vec<Vec<f64>>,
    energies: Vec<EnergyBreakdown>,
    refined: Vec<f64>,
    bounds: Vec<f64>,
}

impl Elastic {
    /// Largest error bound of the lowest three modes.
    fn worst(&self) -> f64 {
        self.bounds.iter().take(3).fold(0.0, |a: f64, &b| a.max(b))
    }
}

/// The reduced pencil in one of two storages.
enum Pencil {
    Dense {
        k: Mat<f64>,
        m: Mat<f64>,
    },
    Sparse {
        k: SparseColMat<usize, f64>,
        m: SparseColMat<usize, f64>,
    },
}

/// Modal analysis linearized at `at`.
pub fn modal(
    system: &System,
    at: &Linearization,
    settings: &ModalSettings,
) -> Result<ModalResult, AnalysisError> {
    let n = system.ndof();
    let mut cq = Triplets::new(system.constraint_count(), n);
    system.add_constraint_jacobian(at.q, &mut cq);
    // Positions in units of the model's size, so that the basis weighs
    // them like slopes and angles whatever the model's units or scale.
    let mut d = vec![1.0; n];
    let size = system.length_scale();
    for i in system.point_coordinates() {
        d[i] = size;
        d[i + 1] = size;
    }
    let ns = NullSpace::scaled(cq.nrows(), n, cq.entries(), &d);
    let dim = ns.dim();
    if dim == 0 {
        return Err(AnalysisError::NoFreedom);
    }
    let singular = |direction: &[f64], reduced: bool| {
        let full = if reduced {
            ns.expand(direction)
        } else {
            direction.to_vec()
        };
        let i = argmax_abs(&full);
        AnalysisError::SingularMass {
            dof: system.dof_label(i),
            path: system.dof_model_path(i),
        }
    };
    let eigen_error = |e: EigenFailure, reduced: bool| match e {
        EigenFailure::SingularMass { direction } => singular(&direction, reduced),
        EigenFailure::NoConvergence | EigenFailure::Factorization => {
            AnalysisError::EigenSolver { size: dim }
        }
    };
    let zero = zero_modes(system, at, &cq).map_err(|e| eigen_error(e, false))?;
    let k0 = zero.shapes.len();
    let count = settings.modes.map_or(dim, |c| c.min(dim));
    let elastic_wanted = count.saturating_sub(k0).min(dim - k0);
    let sparse = match settings.method {
        EigenMethod::Dense => false,
        EigenMethod::Sparse => true,
        EigenMethod::Auto => dim > DENSE_MAX && settings.modes.is_some(),
    };
    let z_reduced: Vec<Vec<f64>> = zero.shapes.iter().map(|s| ns.restrict(s)).collect();
    let solve = |sparse: bool| -> Result<Elastic, AnalysisError> {
        let pencil = if sparse {
            // One triplet list at a time, dropped once compressed (the
            // lists take three times the compressed matrices' memory).
            let k = {
                let mut k = Triplets::new(dim, dim);
                system.add_tangent_stiffness(at, &mut Projected::new(&ns, &mut k));
                k.to_sparse()
            };
            let m = {
                let mut m = Triplets::new(dim, dim);
                system.mass().add_into(&mut Projected::new(&ns, &mut m));
                m.to_sparse()
            };
            // One pattern for both, the originals dropped.
            let [k, m] = on_common_pattern(&k, &m);
            Pencil::Sparse { k, m }
        } else {
            let (mut k, mut m) = (Mat::zeros(dim, dim), Mat::zeros(dim, dim));
            system.add_tangent_stiffness(at, &mut Projected::new(&ns, &mut k));
            system.mass().add_into(&mut Projected::new(&ns, &mut m));
            symmetrize(&mut k);
            symmetrize(&mut m);
            Pencil::Dense { k, m }
        };
        let mut precise = None;
        let (values, vectors, factor) = match &pencil {
            Pencil::Dense { k, m } => {
                let (v, x, f) = dense_elastic(k, m, &z_reduced, elastic_wanted)
                    .map_err(|e| eigen_error(e, true))?;
                (v, x, Some(f))
            }
            Pencil::Sparse { k, m } => {
                // K_r x from strain variations: (DN)ᵀ K (DN x), the
                // columns shared among the pool's threads (the same
                // operations per column, so the same bits however shared;
                // the element states are formed once per share).
                let share = rayon::current_num_threads().max(1);
                let products = |xs: &[&[f64]], out: &mut [&mut [f64]]| {
                    let chunk = xs.len().div_ceil(share).max(1);
                    xs.par_chunks(chunk)
                        .zip(out.par_chunks_mut(chunk))
                        .for_each(|(x, o)| system.stiffness_products(at, &ns, x, o));
                };
                let r = lowest_modes_refined(
                    k,
                    m,
                    &z_reduced,
                    &KrylovSettings::new(elastic_wanted),
                    &products,
                )
                .map_err(|e| eigen_error(e, true))?;
                if !r.residuals.is_empty() {
                    precise = Some((r.residuals, r.guard_values, r.certified));
                }
                (r.values, r.vectors, None)
            }
        };
        let shapes: Vec<Vec<f64>> = (0..values.len())
            .map(|i| ns.expand(vectors.col_as_slice(i)))
            .collect();
        // Rayleigh quotients from the cancellation-free energy form.
        let phis: Vec<&[f64]> = shapes.iter().map(Vec::as_slice).collect();
        let mut energies = vec![EnergyBreakdown::default(); phis.len()];
        // Shapes shared among the pool's threads (each shape's sums are
        // the same however they are shared).
        let share = phis
            .len()
            .div_ceil(rayon::current_num_threads().max(1))
            .max(1);
        phis.par_chunks(share)
            .zip(energies.par_chunks_mut(share))
            .for_each(|(p, e)| system.stiffness_quadratic_forms(at, p, e));
        let mass = system.mass();
        let refined: Vec<f64> = shapes
            .par_iter()
            .zip(&energies)
            .map(|(s, e)| 2.0 * e.total() / mass.quadratic_form(s))
            .collect();
        // Plus the round-off of the energy form itself (R relative to U is
        // the relative error of ω², half of it of the frequency): a soft
        // mode among stiff elements carries the rounding of their terms.
        let raw = match &precise {
            Some((bounds, _, _)) => precise_bounds(bounds, &refined, dim),
            None => error_bounds(&pencil, factor.as_ref(), &vectors, &refined),
        };
        let bounds = raw
            .into_iter()
            .zip(&energies)
            .map(|(b, e)| b + 0.5 * e.roundoff / e.total().abs().max(f64::MIN_POSITIVE))
            .collect();
        Ok(Elastic {
            sparse,
            certified: precise.as_ref().is_none_or(|p| p.2),
            shapes,
            energies,
            refined,
            bounds,
        })
    };
    let mut result = solve(sparse)?;
    // Auto: a dense solve that cannot certify its lowest modes (a very
    // slender or finely meshed model, whose ω² span more than the dense
    // solver's ε·max|ω²| resolves) is repeated by shift-invert, which
    // resolves the lowest modes relative to themselves; the better one stays.
    if settings.method == EigenMethod::Auto && !sparse && result.worst() > ACCURACY_WARNING {
        if let Ok(other) = solve(true) {
            if other.worst() < result.worst() {
                result = other;
            }
        }
    }
    let Elastic {
        sparse,
        certified,
        shapes,
        energies,
        refined,
        bounds,
    } = result;
    let mut modes = Vec::with_capacity(count);
    let zero_fractions = EnergyFractions {
        axial: 0.0,
        bending: 0.0,
        springs: 0.0,
    };
    for (k, shape) in zero.shapes.iter().enumerate().take(count) {
        modes.push(Mode {
            index: modes.len() + 1,
            frequency_hz: 0.0,
            eigenvalue: 0.0,
            kind: if k < zero.rigid {
                ModeKind::Rigid
            } else {
                ModeKind::Mechanism
            },
            energy: zero_fractions,
            error_bound: None,
            shear_estimate: None,
            shape: shape.clone(),
        });
    }
    let mut elastic: Vec<usize> = (0..shapes.len()).collect();
    elastic.sort_by(|&a, &b| refined[a].total_cmp(&refined[b]));
    let balance = unbalanced_force(system, at.q, at.lambda, at.time, at.load_scale);
    let equilibrium = EquilibriumCheck::new(system, &balance);
    let elements: usize = system.beams.iter().map(|b| b.elements.len()).sum();
    let mut refused_modes = Vec::new();
    for i in elastic {
        if bounds[i].is_nan() || bounds[i] > REFUSE_BOUND {
            // Not a frequency: the arithmetic did not resolve it.
            // A hint only where the mesh is what limits it: thousands of
            // elements (fewer resolve every mode the elements can carry).
            let n = elements as f64 * (REFUSE_BOUND / bounds[i]).powf(1.0 / 7.0);
            let hint = (sparse && n >= FINE_MESH_ELEMENTS && bounds[i].is_finite()).then(|| {
                let digits = 10f64.powi(n.log10().floor() as i32 - 1);
                ((n / digits).floor() * digits) as usize
            });
            refused_modes.push(RefusedMode {
                index: modes.len() + refused_modes.len() + 1,
                error_bound: bounds[i],
                elements_hint: hint,
            });
            continue;
        }
        let (mut kind, energy) = classify(energies[i]);
        // Negative beyond the bound: a bound below ½ certifies the sign.
        if refined[i] < 0.0 && bounds[i] < 0.5 {
            kind = if equilibrium.balanced {
                ModeKind::Unstable
            } else {
                ModeKind::Negative
            };
        }
        modes.push(Mode {
            index: modes.len() + refused_modes.len() + 1,
            frequency_hz: refined[i].signum() * refined[i].abs().sqrt()
                / (2.0 * std::f64::consts::PI),
            eigenvalue: refined[i],
            kind,
            energy,
            error_bound: Some(bounds[i]),
            shear_estimate: None,
            shape: shapes[i].clone(),
        });
    }
    let redundant_constraints = redundant_labels(system, &ns.redundant_rows);
    Ok(ModalResult {
        dofs: n,
        constraints: system.constraint_count(),
        redundant_constraints,
        reduced_dofs: dim,
        rigid_modes: k0,
        mechanism_modes: k0 - zero.rigid,
        solver: if sparse {
            "sparse shift-invert Lanczos"
        } else {
            "dense"
        },
        unstable_modes: modes
            .iter()
            .filter(|m| m.kind == ModeKind::Unstable)
            .count(),
        negative_modes: modes
            .iter()
            .filter(|m| m.kind == ModeKind::Negative)
            .count(),
        modes,
        equilibrium,
        refused_modes,
        mode_count_certified: certified,
    })
}

/// The lowest `wanted` eigenpairs of (K_r, M_r) that are M_r-orthogonal to
/// the zero modes Z (M_r-orthonormal). The zero modes are moved out of the
/// way exactly: with Y = M_r Z, K' = K_r + s Y Yᵀ has K'Z = s M_r Z and
/// acts on the M_r-orthogonal complement as K_r does. With s below every
/// eigenvalue (s = −2 maxᵢ Σⱼ|K_ij|/M_ii, twice a Gershgorin-type bound
/// on |ω²|), the first k of
/// the pencil (K', M_r) are the deflated zero modes, the rest the elastic
/// ones; nothing is labelled by the size of an eigenvalue.
fn dense_elastic(
    k: &Mat<f64>,
    m: &Mat<f64>,
    z: &[Vec<f64>],
    wanted: usize,
) -> Result<(Vec<f64>, Mat<f64>, MassFactor), EigenFailure> {
    let dim = k.nrows();
    if z.is_empty() {
        let e = solve_generalized(k, m, wanted)?;
        return Ok((e.values, e.vectors, e.mass));
    }
    let bound: f64 = (0..dim)
        .map(|i| {
            let row: f64 = k.col_as_slice(i).iter().map(|v| v.abs()).sum();
            row / m[(i, i)].abs().max(f64::MIN_POSITIVE)
        })
        .fold(0.0, f64::max);
    let shift = -2.0 * bound;
    let z = Mat::from_fn(dim, z.len(), |r, c| z[c][r]);
    let y = m * &z;
    let shifted = k + shift * (&y * y.transpose());
    let e = solve_generalized(&shifted, m, z.ncols() + wanted)?;
    let skip = z.ncols();
    Ok((
        e.values[skip..].to_vec(),
        e.vectors.subcols(skip, e.vectors.ncols() - skip).to_owned(),
        e.mass,
    ))
}

/// Applies M_r⁻¹ to the columns of a matrix in place.
type MassSolve<'a> = Box<dyn Fn(&mut Mat<f64>) + 'a>;

/// ½ min(‖r‖, ‖r‖²/δ)/ω² per mode (module doc, item 4).
fn error_bounds(
    pencil: &Pencil,
    factor: Option<&MassFactor>,
    vectors: &Mat<f64>,
    values: &[f64],
) -> Vec<f64> {
    let count = values.len();
    let dim = vectors.nrows();
    let mut residuals = Mat::zeros(dim, count);
    let m_solver: Option<MassSolve<'_>> = match pencil {
        Pencil::Dense { k, m } => {
            let (kx, mx) = (k * vectors, m * vectors);
            for (j, &lambda) in values.iter().enumerate() {
                for i in 0..dim {
                    residuals[(i, j)] = kx[(i, j)] - lambda * mx[(i, j)];
                }
            }
            factor.map(|f| Box::new(move |r: &mut Mat<f64>| f.solve_in_place(r)) as _)
        }
        Pencil::Sparse { k, m } => {
            let (kc, mc) = (k, m);
            let (mut kx, mut mx) = (vec![0.0; dim], vec![0.0; dim]);
            for (j, &lambda) in values.iter().enumerate() {
                let x = vectors.col_as_slice(j);
                mul_vec(kc, x, &mut kx);
                mul_vec(mc, x, &mut mx);
                for i in 0..dim {
                    residuals[(i, j)] = kx[i] - lambda * mx[i];
                }
            }
            mc.sp_cholesky(Side::Lower)
                .ok()
                .map(|l| Box::new(move |r: &mut Mat<f64>| l.solve_in_place(r.as_mut())) as _)
        }
    };
    let mut solved = residuals.clone();
    let Some(solve) = m_solver else {
        return vec![f64::INFINITY; count];
    };
    solve(&mut solved);
    (0..count)
        .map(|j| {
            let r = dot(residuals.col_as_slice(j), solved.col_as_slice(j))
                .max(0.0)
                .sqrt();
            // The gap to the nearest value outside this mode's cluster
            // (values within 1e-6 of each other: a repeated frequency of a
            // symmetric structure, whose subspace is what is determined).
            let gap = (0..count)
                .map(|i| (values[i] - values[j]).abs())
                .filter(|&d| d > 1e-6 * values[j].abs())
                .fold(f64::INFINITY, f64::min);
            let dl = r.min(r * r / gap);
            // Plus the round-off of the refined quotient itself, whose
            // sums run over all coordinates (√dim ε, typical accumulation).
            0.5 * dl / values[j].abs() + (dim as f64).sqrt() * f64::EPSILON
        })
        .collect()
}

/// The relative frequency error bound per mode from the refined solve's
/// bounds on |θ − ω²| (½ of it relative to ω², plus the √dim ε of the
/// refined quotient's sums as in [`error_bounds`]).
fn precise_bounds(value_bounds: &[f64], values: &[f64], dim: usize) -> Vec<f64> {
    (0..values.len())
        .map(|j| {
            let b = value_bounds.get(j).copied().unwrap_or(f64::INFINITY);
            0.5 * b / values[j].abs() + (dim as f64).sqrt() * f64::EPSILON
        })
        .collect()
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
