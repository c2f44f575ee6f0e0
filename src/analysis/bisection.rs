//! Selected eigenvalues of a symmetric tridiagonal matrix T by bisection on
//! Sturm counts (Barth, Martin & Wilkinson, Numer. Math. 9 (1967) 386–393;
//! Golub & Van Loan, *Matrix Computations*, §8.4.1). In the modal analysis T
//! is the tridiagonal form of L⁻¹KL⁻ᵀ, eigenvalues ω² [SI: rad²/s²].
//!
//! The leading principal minors pᵢ(x) = det(Tᵢ − xI) obey
//!
//! ```text
//! p₀ = 1,  p₁ = d₀ − x,  pᵢ = (dᵢ₋₁ − x) pᵢ₋₁ − eᵢ₋₂² pᵢ₋₂,
//! ```
//!
//! and the number of sign changes along p₀ … pₙ is the number of eigenvalues
//! below x. Evaluated in floating point, the recurrence is exact for a T whose
//! entries are perturbed by a few ε‖T‖, so the count is that of a nearby
//! matrix and bisection down to an interval of width ε‖T‖ finds every
//! eigenvalue to an absolute error of a few ε‖T‖: the accuracy of the QR
//! algorithm, for the eigenvalues asked for only.
//!
//! The work is done on T/‖T‖∞, whose eigenvalues lie in [−1, 1]; 53 halvings
//! of that interval reach 2⁻⁵²·(1 + margin) ≈ ε. A first count at a ladder
//! of shifts 4⁻ᵏ brackets each eigenvalue within a factor 4 (a beam model's
//! lowest ω² lie 4–16 decades below ‖T‖), which saves the first 10–25
//! halvings; the largest eigenvalue, wanted only as a scale, stops at a
//! relative width of 2⁻³⁰. Sixteen eigenvalues are
//! bisected side by side, one lane each, so the sixteen recurrences are
//! independent and vectorize; the chain of one multiply-add per row is the
//! critical path. With ‖T‖∞ = 1 and |x| ≤ 1, max(|pᵢ|, |pᵢ₋₁|) grows at most
//! 3× per row, so nothing overflows up to n = [`MAX_PRODUCT_SIZE`]
//! (3⁴⁰⁰ < 10¹⁹¹). Minors do shrink far: near the low end of a beam model's
//! spectrum (ω² over 16 decades) pₙ reaches 10⁻¹⁵⁰ and below. Small pairs
//! are therefore rescaled by a power of two every 16 rows; should a pair
//! have come near underflow between two checks anyway, the count is redone
//! by the ratio form dᵢ = pᵢ/pᵢ₋₁ = (dᵢ₋₁ − x) − eᵢ₋₂²/dᵢ₋₁ with LAPACK's
//! pivot guard (dlaneg), which cannot underflow but needs a division per
//! row.
//!
//! On x86-64 CPUs with AVX2 or AVX-512 and FMA the kernel is compiled for
//! those features (chosen at run time) and the recurrence uses fused
//! multiply-adds; elsewhere it is plain arithmetic. Both evaluate the same
//! recurrence, so both have the accuracy above; results may differ in the
//! last bits between the two.

use super::eigen::EigenFailure;
use super::small_eigen::Tridiagonal;

/// Eigenvalues bisected side by side.
const LANES: usize = 16;

/// Halvings of the start interval [−(1 + 2⁻⁴⁰), 1 + 2⁻⁴⁰].
const ROUNDS: usize = 53;

/// Largest size for which the product form cannot overflow.
const MAX_PRODUCT_SIZE: usize = 400;

/// Sturm counts of T − xI, on T scaled to ‖T‖∞ = 1.
#[derive(Debug, Clone)]
pub struct SturmCounts {
    /// ‖T‖∞ [units of T].
    norm: f64,
    /// Diagonal of T/‖T‖∞.
    diag: Vec<f64>,
    /// Squared off-diagonal of T/‖T‖∞.
    off2: Vec<f64>,
}

impl SturmCounts {
    /// Scale T; fails if T holds non-finite entries.
    pub fn new(t: &Tridiagonal) -> Result<Self, EigenFailure> {
        let norm = t.norm_inf();
        if !norm.is_finite() {
            return Err(EigenFailure::NoConvergence);
        }
        let s = if norm > 0.0 { 1.0 / norm } else { 1.0 };
        Ok(SturmCounts {
            norm,
            diag: t.diag.iter().map(|d| d * s).collect(),
            off2: t.off.iter().map(|e| (e * s) * (e * s)).collect(),
        })
    }

    /// Order of T.
    pub fn size(&self) -> usize {
        self.diag.len()
    }

    /// Number of eigenvalues of T below `x` [units of T] (ratio form).
    pub fn count_below(&self, x: f64) -> usize {
        if self.norm == 0.0 {
            return if x > 0.0 { self.size() } else { 0 };
        }
        ratio_count(self, x / self.norm) as usize
    }

    /// Number of eigenvalues λ with |λ| ≤ `tol` [units of T].
    pub fn count_within(&self, tol: f64) -> usize {
        // Eigenvalues ≤ tol are those below the next float up.
        let above = tol.abs().next_up();
        self.count_below(above) - self.count_below(-tol.abs())
    }

    /// The eigenvalues with the given 0-based indices in ascending order
    /// [units of T], each to an absolute error of a few ε‖T‖.
    pub fn eigenvalues(&self, indices: &[usize]) -> Vec<f64> {
        self.bisect_all(indices, &vec![0.0; indices.len()])
    }

    /// The lowest `count` eigenvalues [units of T] as [`Self::eigenvalues`]
    /// gives them, and the largest eigenvalue to a relative error of
    /// [`ROUGH`] (enough for a scale of tolerances), bisected alongside.
    pub fn lowest_and_largest(&self, count: usize) -> (Vec<f64>, f64) {
        let n = self.size();
        if n == 0 {
            return (Vec::new(), 0.0);
        }
        let count = count.min(n);
        let mut indices: Vec<usize> = (0..count).collect();
        indices.push(n - 1);
        let mut rel = vec![0.0; count];
        rel.push(ROUGH);
        let mut values = self.bisect_all(&indices, &rel);
        let largest = values.pop().unwrap_or(0.0);
        (values, largest)
    }

    /// Bisection for every index; lane j stops at a width of
    /// max(2⁻⁵², rel[j]·|λ|) of T/‖T‖.
    fn bisect_all(&self, indices: &[usize], rel: &[f64]) -> Vec<f64> {
        let n = self.size();
        assert!(indices.iter().all(|&i| i < n), "eigenvalue index beyond n");
        if self.norm == 0.0 {
            return vec![0.0; indices.len()];
        }
        let mut out = Vec::with_capacity(indices.len());
        for (batch, rel) in indices.chunks(LANES).zip(rel.chunks(LANES)) {
            let mut lanes = Lanes {
                index: [batch[0] as u64; LANES],
                rel: [rel[0]; LANES],
            };
            lanes
                .index
                .iter_mut()
                .zip(batch)
                .for_each(|(l, &i)| *l = i as u64);
            lanes.rel.iter_mut().zip(rel).for_each(|(l, &r)| *l = r);
            let mid = bisect(self, &lanes);
            out.extend(mid[..batch.len()].iter().map(|m| m * self.norm));
        }
        out
    }
}

/// Relative accuracy of the largest eigenvalue from
/// [`SturmCounts::lowest_and_largest`].
pub const ROUGH: f64 = 9.313_225_746_154_785e-10; // 2⁻³⁰

/// One batch of bisections: which eigenvalue each lane seeks, and its
/// relative stopping width.
struct Lanes {
    index: [u64; LANES],
    rel: [f64; LANES],
}

/// Bisection for one batch of eigenvalue indices (scaled units).
fn bisect(s: &SturmCounts, lanes: &Lanes) -> [f64; LANES] {
    #[cfg(target_arch = "x86_64")]
    if s.size() <= MAX_PRODUCT_SIZE && std::arch::is_x86_feature_detected!("fma") {
        // The wider kernel first; both use fused multiply-adds.
        if std::arch::is_x86_feature_detected!("avx512f") {
            // SAFETY: the CPU has the features the function is compiled for.
            return unsafe { bisect_avx512(s, lanes) };
        }
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: as above.
            return unsafe { bisect_avx2(s, lanes) };
        }
    }
    if s.size() <= MAX_PRODUCT_SIZE {
        bisect_lanes::<PLAIN>(s, lanes)
    } else {
        bisect_lanes::<RATIO>(s, lanes)
    }
}

/// How [`bisect_lanes`] counts: product form with or without fused
/// multiply-adds, or the ratio form only.
const PLAIN: u8 = 0;
const FUSED: u8 = 1;
const RATIO: u8 = 2;

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,fma")]
fn bisect_avx512(s: &SturmCounts, lanes: &Lanes) -> [f64; LANES] {
    bisect_lanes::<FUSED>(s, lanes)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
fn bisect_avx2(s: &SturmCounts, lanes: &Lanes) -> [f64; LANES] {
    bisect_lanes::<FUSED>(s, lanes)
}

/// Bisection per lane: eigenvalue index[j] stays in [lo[j], hi[j]). A first
/// count at the [`PROBES`] gives each lane its start bracket; halvings
/// follow until every lane is narrower than its stopping width.
#[inline(always)]
fn bisect_lanes<const MODE: u8>(s: &SturmCounts, lanes: &Lanes) -> [f64; LANES] {
    let counts = |x: &[f64; LANES]| {
        let product = match MODE {
            PLAIN => product_counts::<false>(s, x),
            FUSED => product_counts::<true>(s, x),
            _ => None,
        };
        match product {
            Some(c) => c,
            None => ratio_counts(s, x),
        }
    };
    let idx = &lanes.index;
    let bound = 1.0 + f64::powi(2.0, -40);
    let (mut lo, mut hi) = ([-bound; LANES], [bound; LANES]);
    let probed = counts(&PROBES);
    for j in 0..LANES {
        for (&x, &c) in PROBES.iter().zip(&probed) {
            if c <= idx[j] {
                lo[j] = lo[j].max(x);
            } else {
                hi[j] = hi[j].min(x);
            }
        }
        if lo[j] >= hi[j] {
            // Counts not monotone across the probes (rounding): start wide.
            (lo[j], hi[j]) = (-bound, bound);
        }
    }
    let mut mid = [0.0; LANES];
    for _ in 0..ROUNDS {
        let wide = (0..LANES).any(|j| {
            let scale = lo[j].abs().max(hi[j].abs());
            hi[j] - lo[j] > ABS_WIDTH.max(lanes.rel[j] * scale)
        });
        if !wide {
            break;
        }
        for j in 0..LANES {
            mid[j] = 0.5 * (lo[j] + hi[j]);
        }
        let c = counts(&mid);
        for j in 0..LANES {
            // c[j] eigenvalues lie below mid[j]: idx[j] among them or not.
            if c[j] > idx[j] {
                hi[j] = mid[j];
            } else {
                lo[j] = mid[j];
            }
        }
    }
    for j in 0..LANES {
        mid[j] = 0.5 * (lo[j] + hi[j]);
    }
    mid
}

/// Stopping width of T/‖T‖'s eigenvalues: what 53 halvings of [−1, 1] give.
const ABS_WIDTH: f64 = f64::EPSILON;

/// First shifts, ascending: −1, −4⁻¹³ and 4⁻¹³, 4⁻¹², …, 1. A beam model's
/// lowest ω² lie decades below ‖T‖, so a geometric ladder brackets each
/// within a factor 4 (the zero ones within ±4⁻¹³ ≈ 1.5e-8) and saves the
/// halvings from [−1, 1] down to there.
const PROBES: [f64; LANES] = {
    let mut p = [0.0; LANES];
    p[0] = -1.0;
    let mut i = 0;
    while i < LANES - 1 {
        // p[1] = −4⁻¹³, p[2 + k] = 4^(k − 13).
        let e = if i == 0 { 13 } else { 13 - (i - 1) as i32 };
        let mut v = 1.0;
        let mut k = 0;
        while k < e {
            v /= 4.0;
            k += 1;
        }
        p[i + 1] = if i == 0 { -v } else { v };
        i += 1;
    }
    p
};

/// Sign changes of the minors p₀ … pₙ at every lane's shift, or None if a
/// lane may have come near underflow.
///
/// Every [`CHECK_EVERY`] rows a lane whose pair (pᵢ₋₁, pᵢ) has fallen
/// below [`RESCALE_BELOW`] is multiplied by its inverse (a power of two, so
/// exact; the recurrence is homogeneous, so the signs ahead are unchanged).
/// A pair may shrink without bound in one row but grows at most 3× per row;
/// so if at a check a pair is above [`SUSPECT`] = 3¹⁶·10⁻²⁹⁰·(margin), every
/// pair since the previous check was above 10⁻²⁹⁰, where rounding an
/// underflowed product perturbs T by less than 10⁻³⁰ relatively.
#[inline(always)]
fn product_counts<const FMA: bool>(s: &SturmCounts, x: &[f64; LANES]) -> Option<[u64; LANES]> {
    let (d, e2) = (&s.diag, &s.off2);
    let mut prev = [1.0f64; LANES];
    let mut cur = [0.0f64; LANES];
    let mut count = [0u64; LANES];
    let mut low = [1.0f64; LANES];
    for j in 0..LANES {
        cur[j] = d[0] - x[j];
        count[j] = cur[j].to_bits() >> 63;
    }
    for (i, (&a, &b)) in d[1..].iter().zip(e2).enumerate() {
        for j in 0..LANES {
            let p = if FMA {
                (a - x[j]).mul_add(cur[j], -(b * prev[j]))
            } else {
                (a - x[j]) * cur[j] - b * prev[j]
            };
            count[j] += (p.to_bits() ^ cur[j].to_bits()) >> 63;
            prev[j] = cur[j];
            cur[j] = p;
        }
        if i % CHECK_EVERY == CHECK_EVERY - 1 {
            check_pairs(&mut prev, &mut cur, &mut low);
        }
    }
    check_pairs(&mut prev, &mut cur, &mut low);
    if low.iter().all(|&m| m >= SUSPECT) {
        Some(count)
    } else {
        None
    }
}

/// Rows between checks of the minors' size.
const CHECK_EVERY: usize = 16;

/// A pair of minors below this is rescaled by its inverse, 2³⁰⁰.
const RESCALE_BELOW: f64 = 4.909_093_465_297_727e-91; // 2⁻³⁰⁰

/// A pair below this at a check may have passed through 10⁻²⁹⁰ since the
/// previous check (3¹⁶ ≈ 4·10⁷).
const SUSPECT: f64 = 1e-270;

/// Rescale small pairs and keep each lane's smallest pair size in `low`.
#[inline(always)]
fn check_pairs(prev: &mut [f64; LANES], cur: &mut [f64; LANES], low: &mut [f64; LANES]) {
    for j in 0..LANES {
        let (u, v) = (prev[j].abs(), cur[j].abs());
        let m = if u > v { u } else { v };
        low[j] = if m < low[j] { m } else { low[j] };
        let f = if m < RESCALE_BELOW {
            1.0 / RESCALE_BELOW
        } else {
            1.0
        };
        prev[j] *= f;
        cur[j] *= f;
    }
}

/// Sign changes by the ratio form: the count of negative dᵢ = pᵢ/pᵢ₋₁, with
/// a pivot of magnitude below `pivmin` replaced by −pivmin (dlaneg).
fn ratio_count(s: &SturmCounts, x: f64) -> u64 {
    let pivmin = f64::MIN_POSITIVE / f64::EPSILON;
    let guard = |r: f64| if r.abs() < pivmin { -pivmin } else { r };
    let mut r = guard(s.diag[0] - x);
    let mut count = u64::from(r < 0.0);
    for (&a, &b) in s.diag[1..].iter().zip(&s.off2) {
        r = guard((a - x) - b / r);
        count += u64::from(r < 0.0);
    }
    count
}

fn ratio_counts(s: &SturmCounts, x: &[f64; LANES]) -> [u64; LANES] {
    x.map(|x| ratio_count(s, x))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every kernel (plain and fused product form, ratio form) on
    /// tridiag(−1, 2, −1), whose eigenvalues are 2 − 2cos(kπ/(n+1)).
    #[test]
    fn every_kernel_finds_the_analytic_spectrum() {
        let n = 40;
        let t = Tridiagonal {
            diag: vec![2.0; n],
            off: vec![-1.0; n - 1],
        };
        let s = SturmCounts::new(&t).unwrap();
        let mut lanes = Lanes {
            index: [0; LANES],
            rel: [0.0; LANES],
        };
        for (j, i) in lanes.index.iter_mut().enumerate() {
            *i = (2 * j) as u64;
        }
        let idx = lanes.index;
        let exact =
            |k: u64| 2.0 - 2.0 * ((k + 1) as f64 * std::f64::consts::PI / (n + 1) as f64).cos();
        let mut runs = vec![
            ("plain", bisect_lanes::<PLAIN>(&s, &lanes)),
            ("ratio", bisect_lanes::<RATIO>(&s, &lanes)),
        ];
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("fma") && std::arch::is_x86_feature_detected!("avx2")
        {
            // SAFETY: the CPU has the features.
            runs.push(("avx2", unsafe { bisect_avx2(&s, &lanes) }));
        }
        for (name, got) in runs {
            for (g, &k) in got.iter().zip(&idx) {
                let err = (g * s.norm - exact(k)).abs();
                assert!(
                    err <= 4.0 * f64::EPSILON * s.norm,
                    "{name} kernel, eigenvalue {k}: error {err:e} above 4ε‖T‖"
                );
            }
        }
    }
}
