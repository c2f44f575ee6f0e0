//! The linear-algebra layer: every matrix algorithm of the crate, on faer.
//!
//! Analyses state problems (a stiffness, a mass, a constraint Jacobian) and
//! call in here; nothing in this module knows about beams or joints.
//!
//! - [`sparse`]: assembly targets ([`Scatter`]: a dense matrix or a triplet
//!   list), compressed-column matrices and their products;
//! - [`null_space`]: an orthonormal, sparse basis of null(C_q), built per
//!   group of coupled constraint rows, with redundant rows named;
//! - [`dense`]: the generalized symmetric-definite eigenproblem by faer's
//!   Cholesky and self-adjoint eigensolver (the QR path);
//! - [`krylov`]: the lowest modes of a large sparse pencil by shift-invert
//!   Lanczos in the M inner product (our own: it deflates the known zero
//!   modes and works in the M inner product) on faer's sparse Cholesky/LU
//!   factors, certified complete by [`inertia`];
//! - [`inertia`]: the count of eigenvalues below a shift (Sylvester's law
//!   on faer's sparse LDLᵀ);
//! - [`subspace`]: Rayleigh–Ritz on a few (possibly dependent) columns:
//!   the reduced models of component-mode synthesis;
//! - [`vector`]: the few vector helpers (dot, norms, axpy) everyone shares.

pub mod dense;
pub mod inertia;
pub mod krylov;
pub mod null_space;
pub mod sparse;
pub mod subspace;
pub mod vector;

pub use sparse::{Scatter, Triplets};

/// Why a generalized eigenproblem K x = λ M x could not be solved.
#[derive(Debug, Clone, PartialEq)]
pub enum EigenFailure {
    /// M is not positive definite; the vector spans (approximately) its
    /// null direction, in the coordinates of the problem.
    SingularMass { direction: Vec<f64> },
    /// The eigensolver did not converge.
    NoConvergence,
    /// A sparse factorization failed (out of memory or structurally singular).
    Factorization,
}
