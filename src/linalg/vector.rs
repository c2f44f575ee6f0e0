//! Vector helpers shared by the whole crate (plain slices, f64).

/// aᵀb.
#[inline]
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// aᵀb summed in eight interleaved partial sums, then pairwise: the
/// sums vectorize (a plain left-to-right sum waits on every addition),
/// and the round-off grows more slowly with the length. For the long
/// vectors of the iterative eigensolvers.
#[inline]
pub fn dot_long(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let mut acc = [0.0f64; 8];
    let (ac, bc) = (a.chunks_exact(8), b.chunks_exact(8));
    let tail: f64 = ac
        .remainder()
        .iter()
        .zip(bc.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ac.zip(bc) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7])) + tail
}

/// ‖a‖₂.
#[inline]
pub fn norm2(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// max |aᵢ| (0 for an empty slice).
#[inline]
pub fn norm_inf(a: &[f64]) -> f64 {
    a.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// Index of the entry of largest magnitude (0 for an empty slice).
pub fn argmax_abs(v: &[f64]) -> usize {
    (0..v.len())
        .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
        .unwrap_or(0)
}

/// y ← y + a x.
#[inline]
pub fn axpy(a: f64, x: &[f64], y: &mut [f64]) {
    y.iter_mut().zip(x).for_each(|(yi, xi)| *yi += a * xi);
}

/// x ← a x.
#[inline]
pub fn scale(a: f64, x: &mut [f64]) {
    x.iter_mut().for_each(|v| *v *= a);
}

/// max |xᵢ|·wᵢ (wᵢ = 1 without weights; NaNs skipped, as `f64::max` does;
/// 0 for none), in four running maxima: the maximum does not depend on the
/// order, and four chains take a quarter of the one chain's latency. Each
/// running maximum takes a term only if it is larger (a NaN never is): the
/// `f64::max` of terms that are never −0, as one vector compare and blend
/// (`f64::max`'s NaN test on either side costs three more instructions a
/// term). The transient integrator's Newton norm, twice an iteration.
#[inline]
pub fn largest_weighted(x: &[f64], w: Option<&[f64]>) -> f64 {
    match w {
        None => largest_of(x, |_, x| x.abs()),
        Some(w) => {
            let w = &w[..x.len()];
            largest_of(x, |i, x| x.abs() * w[i])
        }
    }
}

#[inline(always)]
fn largest_of(x: &[f64], term: impl Fn(usize, f64) -> f64) -> f64 {
    let mut m = [0.0f64; 4];
    let whole = x.len() / 4 * 4;
    for (c, chunk) in x[..whole].chunks_exact(4).enumerate() {
        for (k, m) in m.iter_mut().enumerate() {
            let t = term(4 * c + k, chunk[k]);
            *m = if t > *m { t } else { *m };
        }
    }
    for (i, &xi) in x.iter().enumerate().skip(whole) {
        m[0] = m[0].max(term(i, xi));
    }
    m[0].max(m[1]).max(m[2].max(m[3]))
}

/// A deterministic value in [−1, 1) for entry (i, c) of a start block
/// (SplitMix64 of the pair): columns independent of each other, with every
/// mode present (a family like sin(a·i + b·c) spans two vectors only).
pub fn scrambled(i: usize, c: usize) -> f64 {
    let mut z = (i as u64)
        .wrapping_mul(0x9E37_79B9_7F4A_7C15)
        .wrapping_add((c as u64).wrapping_mul(0xD1B5_4A32_D192_ED03))
        .wrapping_add(0x2545_F491_4F6C_DD1D);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The four running maxima give the plain left-to-right `f64::max`
        /// of the terms to the bit, NaNs (skipped) and infinities included.
        #[test]
        fn largest_weighted_is_the_plain_maximum(
            x in proptest::collection::vec(
                prop_oneof![-1e3..1e3f64, Just(f64::NAN), Just(f64::INFINITY), Just(-0.0)],
                0..14,
            ),
            w in proptest::collection::vec(prop_oneof![0.0..10.0f64, Just(0.0)], 14),
        ) {
            let plain = |w: &dyn Fn(usize) -> f64| {
                x.iter().enumerate().fold(0.0f64, |m, (i, v)| m.max(v.abs() * w(i)))
            };
            prop_assert_eq!(largest_weighted(&x, None).to_bits(), plain(&|_| 1.0).to_bits());
            prop_assert_eq!(
                largest_weighted(&x, Some(&w)).to_bits(),
                plain(&|i| w[i]).to_bits()
            );
        }
    }

    /// The interleaved sum is the plain one up to round-off, for every
    /// length around the 8-wide chunks; on integers it is exact.
    #[test]
    fn dot_long_agrees_with_the_plain_sum() {
        for n in [0, 1, 7, 8, 9, 15, 16, 17, 1000, 1003] {
            let a: Vec<f64> = (0..n).map(|i| (i % 13) as f64 - 6.0).collect();
            let b: Vec<f64> = (0..n).map(|i| (i % 7) as f64 + 1.0).collect();
            assert_eq!(dot_long(&a, &b), dot(&a, &b), "integers, n = {n}");
            let c: Vec<f64> = (0..n).map(|i| (0.37 * i as f64).sin()).collect();
            let d: Vec<f64> = (0..n).map(|i| (1.3 * i as f64).cos()).collect();
            let scale: f64 = c.iter().zip(&d).map(|(x, y)| (x * y).abs()).sum();
            let diff = (dot_long(&c, &d) - dot(&c, &d)).abs();
            assert!(
                diff <= 4.0 * n as f64 * f64::EPSILON * scale,
                "n = {n}: {diff:e}"
            );
        }
    }
}
