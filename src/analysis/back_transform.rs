//! Back-transformation Y ← Q Y by the Householder reflectors of a
//! tridiagonalization (Q = H₀H₁⋯H_{m−1}, Hₖ = I − βₖvₖvₖᵀ acting on rows
//! k+1…), for the eigenvectors of T to become eigenvectors of C. In the modal
//! analysis Y holds mode shapes in the tridiagonal basis (dimensionless,
//! unit norm).
//!
//! Reflectors are applied four at a time in the compact WY form
//! (Schreiber & Van Loan, SIAM J. Sci. Stat. Comput. 10 (1989) 53–57;
//! LAPACK dlarft/dlarfb): H_k H_{k+1} H_{k+2} H_{k+3} = I − V T Vᵀ with
//! V = [v_k … v_{k+3}] and T upper triangular, so that one pass over the
//! rows forms S = Vᵀ Y and a second applies Y ← Y − V (T S). The columns of
//! Y go through in tiles of four whose S stays in registers. That is a
//! quarter of the passes of reflector-by-reflector application, and the
//! passes are fused multiply-adds where the CPU has them (AVX2 and FMA,
//! chosen at run time; the plain kernel evaluates the same sums unfused).
//! Both are backward stable like the single reflectors: the result differs
//! from theirs by rounding only (a few ε‖Y‖).

use super::fused::{self, madd};

/// Reflectors per block.
const BLOCK: usize = 4;

/// Columns of Y per tile.
const TILE: usize = 4;

/// The stored reflectors: column k of the column-major `vectors` (column
/// stride `ld` ≥ n), rows k+1…n−1, holds vₖ (first entry 1); `beta[k]` = βₖ
/// (0 = identity).
pub(crate) struct Reflectors<'a> {
    pub n: usize,
    pub ld: usize,
    pub vectors: &'a [f64],
    pub beta: &'a [f64],
}

impl Reflectors<'_> {
    /// Column k of the storage from row `from` on (vₖ itself for from > k).
    fn v(&self, k: usize, from: usize) -> &[f64] {
        &self.vectors[k * self.ld + from..k * self.ld + self.n]
    }

    /// T of H_{k0} ⋯ H_{k0+3} = I − V T Vᵀ (forward, columnwise, dlarft):
    /// T[j][j] = βⱼ, T[0..j][j] = −βⱼ T[0..j][0..j] (V[:, 0..j]ᵀ vⱼ).
    fn block_t(&self, k0: usize) -> [[f64; BLOCK]; BLOCK] {
        let mut t = [[0.0; BLOCK]; BLOCK];
        for j in 0..BLOCK {
            let bj = self.beta[k0 + j];
            t[j][j] = bj;
            // vₗ·vⱼ over vⱼ's rows (vₗ starts earlier).
            let vj = self.v(k0 + j, k0 + j + 1);
            let g: [f64; BLOCK] = std::array::from_fn(|l| {
                if l < j {
                    super::small_eigen::dot(self.v(k0 + l, k0 + j + 1), vj)
                } else {
                    0.0
                }
            });
            for (i, row) in t.iter_mut().enumerate().take(j) {
                let s: f64 = (i..j).map(|l| row[l] * g[l]).sum();
                row[j] = -bj * s;
            }
        }
        t
    }
}

/// Y ← Q Y for the row-major n × w block `y`.
pub(crate) fn apply_q(r: &Reflectors, y: &mut [f64], w: usize) {
    let m = r.n.saturating_sub(1);
    let ts: Vec<[[f64; BLOCK]; BLOCK]> = (0..m / BLOCK).map(|b| r.block_t(BLOCK * b)).collect();
    #[cfg(target_arch = "x86_64")]
    if fused::available() {
        // SAFETY: the CPU has the features the function is compiled for.
        unsafe { apply_q_fma(r, &ts, y, w) };
        return;
    }
    apply_q_tiles::<false>(r, &ts, y, w);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn apply_q_fma(r: &Reflectors, ts: &[[[f64; BLOCK]; BLOCK]], y: &mut [f64], w: usize) {
    apply_q_tiles::<true>(r, ts, y, w);
}

/// Every column tile through every reflector: the trailing ones (beyond the
/// last whole block) one by one, then the blocks, last first.
#[inline(always)]
fn apply_q_tiles<const FMA: bool>(
    r: &Reflectors,
    ts: &[[[f64; BLOCK]; BLOCK]],
    y: &mut [f64],
    w: usize,
) {
    let mut c0 = 0;
    while c0 < w {
        match (w - c0).min(TILE) {
            4 => tile_through::<4, FMA>(r, ts, y, w, c0),
            3 => tile_through::<3, FMA>(r, ts, y, w, c0),
            2 => tile_through::<2, FMA>(r, ts, y, w, c0),
            _ => tile_through::<1, FMA>(r, ts, y, w, c0),
        }
        c0 += TILE;
    }
}

/// Columns c0…c0+TW−1 of y through the reflectors beyond the last whole
/// block (n−2 down) one by one, then through the blocks, last first.
#[inline(always)]
fn tile_through<const TW: usize, const FMA: bool>(
    r: &Reflectors,
    ts: &[[[f64; BLOCK]; BLOCK]],
    y: &mut [f64],
    w: usize,
    c0: usize,
) {
    for k in (BLOCK * ts.len()..r.n.saturating_sub(1)).rev() {
        single::<TW, FMA>(r, k, y, w, c0);
    }
    for (b, t) in ts.iter().enumerate().rev() {
        block::<TW, FMA>(r, BLOCK * b, t, y, w, c0);
    }
}

/// One reflector k on the tile.
#[inline(always)]
fn single<const TW: usize, const FMA: bool>(
    r: &Reflectors,
    k: usize,
    y: &mut [f64],
    w: usize,
    c0: usize,
) {
    let b = r.beta[k];
    if b == 0.0 {
        return;
    }
    let v = r.v(k, k + 1);
    let mut s = [0.0; TW];
    for (i, &vi) in v.iter().enumerate() {
        let row = &y[(k + 1 + i) * w + c0..][..TW];
        for c in 0..TW {
            s[c] = madd::<FMA>(vi, row[c], s[c]);
        }
    }
    s.iter_mut().for_each(|x| *x *= b);
    for (i, &vi) in v.iter().enumerate() {
        let row = &mut y[(k + 1 + i) * w + c0..][..TW];
        for c in 0..TW {
            row[c] = madd::<FMA>(-vi, s[c], row[c]);
        }
    }
}

/// The block of reflectors k0…k0+3 (compact WY form, T = `t`) on the tile.
/// vⱼ is nonzero from row k0+1+j, so the first three rows see fewer terms.
#[inline(always)]
fn block<const TW: usize, const FMA: bool>(
    r: &Reflectors,
    k0: usize,
    t: &[[f64; BLOCK]; BLOCK],
    y: &mut [f64],
    w: usize,
    c0: usize,
) {
    let n = r.n;
    // Whole columns, indexed by row.
    let v: [&[f64]; BLOCK] = std::array::from_fn(|j| r.v(k0 + j, 0));
    // S = Vᵀ Y; the first three rows (k0+1…k0+3) meet 1, 2, 3 reflectors.
    let mut s = [[0.0; TW]; BLOCK];
    for row in k0 + 1..(k0 + BLOCK).min(n) {
        let yr = &y[row * w + c0..][..TW];
        for (j, sj) in s.iter_mut().enumerate().take(row - k0) {
            for c in 0..TW {
                sj[c] = madd::<FMA>(v[j][row], yr[c], sj[c]);
            }
        }
    }
    for row in k0 + BLOCK..n {
        let yr = &y[row * w + c0..][..TW];
        let a = [v[0][row], v[1][row], v[2][row], v[3][row]];
        for c in 0..TW {
            let x = yr[c];
            for j in 0..BLOCK {
                s[j][c] = madd::<FMA>(a[j], x, s[j][c]);
            }
        }
    }
    // U = T S (T upper triangular).
    let mut u = [[0.0; TW]; BLOCK];
    for i in 0..BLOCK {
        for c in 0..TW {
            let mut acc = 0.0;
            for j in i..BLOCK {
                acc = madd::<FMA>(t[i][j], s[j][c], acc);
            }
            u[i][c] = acc;
        }
    }
    // Y ← Y − V U.
    for row in k0 + 1..(k0 + BLOCK).min(n) {
        let yr = &mut y[row * w + c0..][..TW];
        for (j, uj) in u.iter().enumerate().take(row - k0) {
            for c in 0..TW {
                yr[c] = madd::<FMA>(-v[j][row], uj[c], yr[c]);
            }
        }
    }
    for row in k0 + BLOCK..n {
        let yr = &mut y[row * w + c0..][..TW];
        let a = [v[0][row], v[1][row], v[2][row], v[3][row]];
        for c in 0..TW {
            let mut x = yr[c];
            for j in 0..BLOCK {
                x = madd::<FMA>(-a[j], u[j][c], x);
            }
            yr[c] = x;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::householder::reflector;

    /// Reflectors of a pseudo-random n × n matrix's columns, stored as the
    /// tridiagonalization stores them (one column with v₀ = 1 per step).
    /// Column 1 is zero below row 2, so H₁ = I (β₁ = 0) when n ≥ 4.
    fn reflectors(n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut a: Vec<f64> = (0..n * n)
            .map(|i| ((i * 7919 % 1009) as f64 / 1009.0) - 0.5)
            .collect();
        if n >= 4 {
            a[n + 3..2 * n].fill(0.0);
        }
        let mut beta = vec![0.0; n.saturating_sub(1)];
        for k in 0..n.saturating_sub(1) {
            beta[k] = reflector(&mut a[k * n + k + 1..(k + 1) * n]).1;
        }
        (a, beta)
    }

    /// The definition: H_{m−1} first, then … H₀, one reflector at a time.
    fn one_by_one(r: &Reflectors, y: &mut [f64], w: usize) {
        for k in (0..r.n.saturating_sub(1)).rev() {
            let v = r.v(k, k + 1);
            for c in 0..w {
                let s: f64 = v
                    .iter()
                    .enumerate()
                    .map(|(i, vi)| vi * y[(k + 1 + i) * w + c])
                    .sum();
                for (i, vi) in v.iter().enumerate() {
                    y[(k + 1 + i) * w + c] -= r.beta[k] * s * vi;
                }
            }
        }
    }

    /// Blocked application (plain and fused kernels) equals the reflectors
    /// applied one by one, to rounding, for sizes with and without a partial
    /// block and a partial column tile; an orthogonal Q keeps column norms.
    #[test]
    fn blocked_application_equals_the_single_reflectors() {
        for n in [1, 2, 3, 5, 8, 9, 40] {
            let (vectors, beta) = reflectors(n);
            assert!(n < 4 || beta[1] == 0.0, "n = {n}: H₁ is the identity");
            let r = Reflectors {
                n,
                ld: n,
                vectors: &vectors,
                beta: &beta,
            };
            let ts: Vec<_> = (0..n.saturating_sub(1) / BLOCK)
                .map(|b| r.block_t(BLOCK * b))
                .collect();
            for w in [1, 3, 4, 5, 12, 13] {
                let y0: Vec<f64> = (0..n * w)
                    .map(|i| ((i * 104_729 % 997) as f64 / 997.0) - 0.5)
                    .collect();
                let mut expected = y0.clone();
                one_by_one(&r, &mut expected, w);
                let mut kernels = vec![("plain", y0.clone())];
                apply_q_tiles::<false>(&r, &ts, &mut kernels[0].1, w);
                #[cfg(target_arch = "x86_64")]
                if fused::available() {
                    let mut y = y0.clone();
                    // SAFETY: the CPU has the features.
                    unsafe { apply_q_fma(&r, &ts, &mut y, w) };
                    kernels.push(("fma", y));
                }
                for (name, got) in kernels {
                    let err = got
                        .iter()
                        .zip(&expected)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max);
                    assert!(
                        err <= 10.0 * n as f64 * f64::EPSILON,
                        "{name}, n = {n}, w = {w}: max difference {err:e}"
                    );
                    for c in 0..w {
                        let norm =
                            |y: &[f64]| (0..n).map(|i| y[i * w + c].powi(2)).sum::<f64>().sqrt();
                        let (before, after) = (norm(&y0), norm(&got));
                        assert!(
                            (after - before).abs() <= 10.0 * n as f64 * f64::EPSILON * before,
                            "{name}, n = {n}: norm {before} -> {after}"
                        );
                    }
                }
            }
        }
    }
}
