//! The modal assurance criterion between two mode sets.
//!
//!   MAC(a, b) = |aᵀ b|² / ((aᵀ a)(bᵀ b))
//!
//! for real shapes sampled at the same degrees of freedom: 1 for parallel
//! shapes (any scale, either sign), 0 for orthogonal ones. With a mass
//! matrix M the mass-weighted form |aᵀ M b|² / ((aᵀ M a)(bᵀ M b)) is the
//! identity between the mass-orthogonal modes of one model.

use nalgebra::DMatrix;

/// MAC(aᵢ, bⱼ) for each pair, `rows = a.len()`, `cols = b.len()`. Shapes of
/// one pair must have equal length; a zero shape gives 0.
pub fn mac(a: &[Vec<f64>], b: &[Vec<f64>]) -> DMatrix<f64> {
    DMatrix::from_fn(a.len(), b.len(), |i, j| pair(&a[i], &b[j], dot))
}

/// Mass-weighted MAC; `m_times(y)` returns M·y for the symmetric mass
/// matrix M of the shapes' coordinates.
pub fn mac_weighted(
    a: &[Vec<f64>],
    b: &[Vec<f64>],
    m_times: impl Fn(&[f64]) -> Vec<f64>,
) -> DMatrix<f64> {
    let w = |x: &[f64], y: &[f64]| dot(x, &m_times(y));
    DMatrix::from_fn(a.len(), b.len(), |i, j| pair(&a[i], &b[j], w))
}

/// MAC(a, b) of one pair; 0 when the lengths differ or a shape is zero.
pub fn mac_pair(a: &[f64], b: &[f64]) -> f64 {
    if a.len() != b.len() {
        return 0.0;
    }
    pair(a, b, dot)
}

fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

fn pair(x: &[f64], y: &[f64], inner: impl Fn(&[f64], &[f64]) -> f64) -> f64 {
    let xy = inner(x, y);
    let xx = inner(x, x);
    let yy = inner(y, y);
    if xx <= 0.0 || yy <= 0.0 {
        0.0
    } else {
        xy * xy / (xx * yy)
    }
}
