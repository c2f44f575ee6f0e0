//! The in-house dense symmetric eigensolver (analysis::small_eigen) and the
//! generalized solver built on it (analysis::eigen::solve_generalized),
//! checked against independent facts: an analytic spectrum, faer's
//! eigenvalues, residuals, orthonormality, a triple zero eigenvalue, and
//! Sturm counts (analysis::bisection) against known spectra.

use ancf_modal::analysis::bisection::ROUGH;
use ancf_modal::analysis::eigen::solve_generalized;
use ancf_modal::analysis::eigen::Spectrum;
use ancf_modal::analysis::small_eigen::{lowest_eigenpairs, SturmCounts, Tridiagonal};
use faer::{Mat, Side};

const EPS: f64 = f64::EPSILON;

/// Deterministic numbers in [−0.5, 0.5) (a Weyl sequence per seed).
struct Weyl(f64);
impl Weyl {
    fn next(&mut self) -> f64 {
        self.0 = (self.0 + 0.618_033_988_749_894_9).fract();
        (self.0 * 7.0).fract() - 0.5
    }
}

/// Q diag(values) Qᵀ with Q a product of three Householder reflectors of
/// pseudo-random vectors (exactly orthogonal up to rounding).
fn with_spectrum(values: &[f64], seed: u64) -> Mat<f64> {
    let n = values.len();
    let mut rng = Weyl((seed as f64 * 0.414_213_562_373_095).fract());
    let mut q = Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 });
    for _ in 0..3 {
        let v: Vec<f64> = (0..n).map(|_| rng.next()).collect();
        let vv: f64 = v.iter().map(|x| x * x).sum();
        let h = Mat::from_fn(n, n, |i, j| {
            (if i == j { 1.0 } else { 0.0 }) - 2.0 * v[i] * v[j] / vv
        });
        q = &h * &q;
    }
    let d = Mat::from_fn(n, n, |i, j| if i == j { values[i] } else { 0.0 });
    let a = &q * &d * q.transpose();
    Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]))
}

fn column_major(a: &Mat<f64>) -> Vec<f64> {
    let n = a.nrows();
    (0..n * n).map(|k| a[(k % n, k / n)]).collect()
}

fn norm_inf(a: &Mat<f64>) -> f64 {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

fn norm2(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum::<f64>().sqrt()
}

fn mat_vec(a: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)] * x[j]).sum())
        .collect()
}

/// Column j of a row-major n × w block.
fn column(block: &[f64], w: usize, j: usize) -> Vec<f64> {
    block.chunks_exact(w).map(|row| row[j]).collect()
}

/// max |xᵢᵀ B xⱼ − δᵢⱼ| over the columns of a row-major block (B = I if None).
fn orthonormality_error(block: &[f64], w: usize, b: Option<&Mat<f64>>) -> f64 {
    let cols: Vec<Vec<f64>> = (0..w).map(|j| column(block, w, j)).collect();
    let mut worst = 0.0f64;
    for (i, x) in cols.iter().enumerate() {
        for (j, y) in cols.iter().enumerate() {
            let by = b.map_or_else(|| y.clone(), |b| mat_vec(b, y));
            let g: f64 = x.iter().zip(&by).map(|(p, q)| p * q).sum();
            worst = worst.max((g - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    worst
}

/// Residuals ‖Ax − λx‖ ≤ `tol` for the w vectors of a row-major block and
/// max |XᵀX − I| ≤ 10·n·ε.
fn assert_standard_pairs(a: &Mat<f64>, values: &[f64], vectors: &[f64], w: usize, tol: f64) {
    let n = a.nrows();
    for (j, &lambda) in values.iter().enumerate().take(w) {
        let x = column(vectors, w, j);
        let ax = mat_vec(a, &x);
        let r: Vec<f64> = ax.iter().zip(&x).map(|(p, q)| p - lambda * q).collect();
        assert!(
            norm2(&r) <= tol,
            "pair {j} (λ = {lambda:e}): residual ‖Ax − λx‖ = {:e} above {tol:e}",
            norm2(&r)
        );
    }
    let orth = orthonormality_error(vectors, w, None);
    assert!(
        orth <= 10.0 * n as f64 * EPS,
        "max |XᵀX − I| = {orth:e} above 10·n·ε"
    );
}

#[test]
fn second_difference_matrix_has_the_analytic_spectrum() {
    // tridiag(−1, 2, −1): λ_k = 2 − 2 cos(kπ/(n+1)), k = 1…n.
    let n = 60;
    let t = Tridiagonal {
        diag: vec![2.0; n],
        off: vec![-1.0; n - 1],
    };
    let exact: Vec<f64> = (1..=n)
        .map(|k| 2.0 - 2.0 * (k as f64 * std::f64::consts::PI / (n + 1) as f64).cos())
        .collect();
    let tol = 10.0 * n as f64 * EPS * 4.0;
    let sturm = SturmCounts::new(&t).unwrap();
    let all: Vec<usize> = (0..n).collect();
    for (got, want) in sturm.eigenvalues(&all).iter().zip(&exact) {
        assert!(
            (got - want).abs() <= tol,
            "bisection eigenvalue {got} vs analytic {want}: error above 10·n·ε·‖T‖ = {tol:e}"
        );
    }
    // Indices in any order and repeated.
    let picked = sturm.eigenvalues(&[59, 0, 30, 30]);
    for (got, k) in picked.iter().zip([59, 0, 30, 30]) {
        assert!(
            (got - exact[k]).abs() <= tol,
            "bisection eigenvalue {k}: {got} vs analytic {}",
            exact[k]
        );
    }
    // Counts between the analytic eigenvalues: k below the k-th gap.
    for k in 0..=n {
        let x = match k {
            0 => -0.5,
            k if k == n => 4.5,
            k => 0.5 * (exact[k - 1] + exact[k]),
        };
        assert_eq!(sturm.count_below(x), k, "Sturm count below {x}");
    }
    // The same matrix dense, through tridiagonalization and inverse iteration.
    let a = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 2.0,
        1 => -1.0,
        _ => 0.0,
    });
    let w = 10;
    let e = lowest_eigenpairs(column_major(&a), n, w).unwrap();
    for (got, want) in e.values.iter().zip(&exact) {
        assert!(
            (got - want).abs() <= tol,
            "dense eigenvalue {got} vs analytic {want}: error above 10·n·ε·‖A‖ = {tol:e}"
        );
    }
    assert_standard_pairs(&a, &e.values, &e.vectors, w, tol);
}

#[test]
fn eigenvalues_of_a_graded_matrix_equal_faers() {
    // Ten decades of spectrum, like a beam model's ω².
    let n = 35;
    let spectrum: Vec<f64> = (0..n)
        .map(|k| {
            let sign = if k % 7 == 3 { -1.0 } else { 1.0 };
            sign * 10f64.powf(10.0 * k as f64 / (n - 1) as f64)
        })
        .collect();
    let a = with_spectrum(&spectrum, 7);
    let reference = a.self_adjoint_eigen(Side::Lower).unwrap();
    let e = lowest_eigenpairs(column_major(&a), n, 5).unwrap();
    let tol = 10.0 * n as f64 * EPS * norm_inf(&a);
    for (i, got) in e.values.iter().enumerate() {
        let want = reference.S()[i];
        assert!(
            (got - want).abs() <= tol,
            "eigenvalue {i}: {got:e} vs faer {want:e}, difference above 10·n·ε·‖A‖ = {tol:e}"
        );
    }
}

#[test]
fn triple_zero_eigenvalue_gets_an_orthonormal_basis() {
    // Three exact zeros (rounding puts them at ~ε‖A‖), then 1…1e8.
    let n = 30;
    let mut spectrum = vec![0.0; 3];
    spectrum.extend((3..n).map(|k| 10f64.powf(8.0 * (k - 3) as f64 / (n - 4) as f64)));
    let a = with_spectrum(&spectrum, 11);
    let norm = norm_inf(&a);
    let w = 6;
    let e = lowest_eigenpairs(column_major(&a), n, w).unwrap();
    let tol = 10.0 * n as f64 * EPS * norm;
    for j in 0..3 {
        assert!(
            e.values[j].abs() <= tol,
            "zero eigenvalue {j} = {:e}, above 10·n·ε·‖A‖ = {tol:e}",
            e.values[j]
        );
    }
    assert_standard_pairs(&a, &e.values, &e.vectors, w, tol);
}

/// The zero count of the whole spectrum is the same whether the returned
/// values reach past the zero cluster (counted among them) or not (Sturm
/// counts of the tridiagonal form): three for a triple zero eigenvalue.
#[test]
fn zero_count_does_not_depend_on_how_many_values_were_returned() {
    let n = 30;
    let mut spectrum = vec![0.0; 3];
    spectrum.extend((3..n).map(|k| 10f64.powf(8.0 * (k - 3) as f64 / (n - 4) as f64)));
    let k = with_spectrum(&spectrum, 5);
    let m = Mat::<f64>::identity(n, n);
    let tol = 64.0 * EPS * norm_inf(&k);
    for wanted in [1, 2, 3, 4, 12] {
        let e = solve_generalized(&k, &m, wanted).unwrap();
        assert_eq!(
            e.count_within(tol),
            Some(3),
            "{wanted} values returned: zero eigenvalues within 64ε‖K‖"
        );
    }
}

#[test]
fn generalized_pairs_have_small_residuals_and_are_mass_orthonormal() {
    // K with a triple zero eigenvalue (a free body), M banded SPD.
    let n = 40;
    let mut rng = Weyl(0.3);
    let m = Mat::from_fn(n, n, |i, j| match i.abs_diff(j) {
        0 => 4.0 + (i % 5) as f64,
        1 => 1.0,
        2 => 0.25,
        _ => 0.0,
    });
    let mut spectrum = vec![0.0; 3];
    spectrum.extend((3..n).map(|k| 1e3 * (1.0 + rng.next()) * k as f64 * k as f64));
    let k = with_spectrum(&spectrum, 5);
    let wanted = 9;
    let e = solve_generalized(&k, &m, wanted).unwrap();
    assert_eq!(
        e.values.len(),
        wanted,
        "the wanted eigenvalues are returned"
    );
    let zero = 100.0 * n as f64 * EPS * norm_inf(&k);
    assert_eq!(
        e.spectrum.count_within(zero),
        Some(3),
        "eigenvalues within 100·n·ε·‖K‖ of zero: the triple zero of K"
    );
    assert_eq!(
        e.vectors.ncols(),
        wanted,
        "vectors only for the wanted ones"
    );
    let kn = norm_inf(&k);
    let mut block = vec![0.0; n * wanted];
    for j in 0..wanted {
        let x: Vec<f64> = (0..n).map(|i| e.vectors[(i, j)]).collect();
        let (kx, mx) = (mat_vec(&k, &x), mat_vec(&m, &x));
        let r: Vec<f64> = kx
            .iter()
            .zip(&mx)
            .map(|(p, q)| p - e.values[j] * q)
            .collect();
        let limit = 100.0 * n as f64 * EPS * kn * norm2(&x);
        assert!(
            norm2(&r) <= limit,
            "pair {j} (λ = {:e}): ‖Kx − λMx‖ = {:e} above 100·n·ε·‖K‖‖x‖ = {limit:e}",
            e.values[j],
            norm2(&r)
        );
        for i in 0..n {
            block[i * wanted + j] = x[i];
        }
    }
    let orth = orthonormality_error(&block, wanted, Some(&m));
    assert!(
        orth <= 100.0 * n as f64 * EPS,
        "max |XᵀMX − I| = {orth:e} above 100·n·ε"
    );
}

#[test]
fn generalized_with_identity_mass_matches_faer() {
    let n = 24;
    let spectrum: Vec<f64> = (0..n).map(|k| (k as f64 - 5.0) * 3.5).collect();
    let k = with_spectrum(&spectrum, 13);
    let id = Mat::from_fn(n, n, |i, j| if i == j { 1.0 } else { 0.0 });
    let e = solve_generalized(&k, &id, n).unwrap();
    let reference = k.self_adjoint_eigen(Side::Lower).unwrap();
    let tol = 10.0 * n as f64 * EPS * norm_inf(&k);
    // Largest |λ| of the spectrum from 5 wanted values only: 18 · 3.5 = 63,
    // to the relative accuracy the bisection promises for it (a scale only).
    let partial = solve_generalized(&k, &id, 5).unwrap();
    let max_abs = partial.spectrum.max_abs().unwrap();
    let rough = 63.0 * ROUGH + tol;
    assert!(
        (max_abs - 63.0).abs() <= rough,
        "max |λ| {max_abs} vs 63 from the constructed spectrum, within 63·2⁻³⁰ + 10·n·ε·‖K‖ = {rough:e}"
    );
    assert!(
        matches!(partial.spectrum, Spectrum::Counts { .. }),
        "n = 24 takes the in-house path with Sturm counts"
    );
    // Exactly one eigenvalue (λ = 0, k = 5) within 1 of zero.
    assert_eq!(
        partial.spectrum.count_within(1.0),
        Some(1),
        "zero eigenvalues"
    );
    for i in 0..n {
        assert!(
            (e.values[i] - reference.S()[i]).abs() <= tol,
            "eigenvalue {i}: {} vs faer {}, difference above 10·n·ε·‖K‖ = {tol:e}",
            e.values[i],
            reference.S()[i]
        );
    }
}

#[test]
fn tiny_sizes() {
    let e = lowest_eigenpairs(vec![3.5], 1, 1).unwrap();
    assert_eq!((e.values, e.vectors), (vec![3.5], vec![1.0]), "1 × 1");
    let e = lowest_eigenpairs(Vec::new(), 0, 3).unwrap();
    assert!(e.values.is_empty() && e.vectors.is_empty(), "0 × 0");
    let e = lowest_eigenpairs(vec![0.0; 16], 4, 3).unwrap();
    assert_eq!(e.values, vec![0.0; 3], "4 × 4 zero matrix: eigenvalues");
    assert_eq!(e.max_abs, 0.0, "4 × 4 zero matrix: largest |λ|");
    let orth = orthonormality_error(&e.vectors, 3, None);
    assert!(
        orth == 0.0,
        "4 × 4 zero matrix: unit vectors, |XᵀX − I| = {orth:e}"
    );
    // 2 × 2 [[2, 1], [1, 2]]: eigenvalues 1 and 3.
    let e = lowest_eigenpairs(vec![2.0, 1.0, 1.0, 2.0], 2, 2).unwrap();
    assert!(
        (e.values[0] - 1.0).abs() <= 4.0 * EPS && (e.values[1] - 3.0).abs() <= 8.0 * EPS,
        "2 × 2 eigenvalues {:?} vs [1, 3] within a few ε",
        e.values
    );
}

#[test]
fn bisection_survives_underflowing_minors() {
    // One entry of 1 and a graded rest 1e-8·k with off-diagonals 1e-13:
    // the leading minors at shifts near the small eigenvalues fall like
    // (1e-7)ⁱ, far below the product form's safe range, so the counts must
    // come from the guarded ratio form. Eigenvalues: the diagonal, moved by
    // at most e²/gap ≈ 1e-18 (second-order perturbation).
    let n = 48;
    let mut diag: Vec<f64> = (0..n).map(|k| 1e-8 * k as f64).collect();
    diag[n - 1] = 1.0;
    let t = Tridiagonal {
        diag: diag.clone(),
        off: vec![1e-13; n - 1],
    };
    let sturm = SturmCounts::new(&t).unwrap();
    let all: Vec<usize> = (0..n).collect();
    let tol = 4.0 * EPS;
    for (k, got) in sturm.eigenvalues(&all).iter().enumerate() {
        assert!(
            (got - diag[k]).abs() <= tol,
            "eigenvalue {k}: {got:e} vs diagonal {:e}, error above 4ε‖T‖ = {tol:e}",
            diag[k]
        );
    }
}
