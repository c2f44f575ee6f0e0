//! The one bounded Levenberg–Marquardt loop on problems it was not tuned
//! for: random box-constrained linear least squares, min |A x − b|² over
//! lower ≤ x ≤ upper. The problem is convex, so the Karush–Kuhn–Tucker
//! conditions certify the optimum independently of the loop: with the
//! gradient g = Aᵀ(A x − b), every free unknown has g_k = 0, an unknown at
//! its lower bound has g_k ≥ 0 and one at its upper bound g_k ≤ 0.

use ancf_modal::signal::lm::{self, Problem, Scale, Settings};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

struct Linear {
    a: DMatrix<f64>,
    b: DVector<f64>,
}

impl Problem for Linear {
    type Point = DVector<f64>;
    type Error = ();
    fn evaluate(&mut self, x: &[f64]) -> Result<DVector<f64>, ()> {
        Ok(&self.a * DVector::from_column_slice(x) - &self.b)
    }
    fn residuals(&self, r: &DVector<f64>) -> DVector<f64> {
        r.clone()
    }
    fn jacobian(
        &mut self,
        _: &[f64],
        _: &DVector<f64>,
        _: &DVector<f64>,
    ) -> Result<DMatrix<f64>, ()> {
        Ok(self.a.clone())
    }
}

const SETTINGS: Settings = Settings {
    initial_damping: Scale::Relative(1e-3),
    grow: 10.0,
    shrink: 10.0,
    damping_floor: Scale::Relative(1e-12),
    damping_ceiling: 1e16,
    max_rejections: usize::MAX,
    step_tolerance: 1e-14,
    min_relative_decrease: 1e-14,
    max_evaluations: 2_000,
    max_iterations: usize::MAX,
};

/// A problem of n unknowns and m = n + extra residuals, entries in
/// [−1, 1] plus a diagonal that keeps AᵀA well conditioned, and a box of
/// half-widths in [0.05, 2] around a random centre.
fn problems() -> impl Strategy<Value = (DMatrix<f64>, DVector<f64>, Vec<(f64, f64)>)> {
    (1usize..6, 0usize..5).prop_flat_map(|(n, extra)| {
        let m = n + extra;
        (
            prop::collection::vec(-1.0f64..1.0, m * n),
            prop::collection::vec(-3.0f64..3.0, m),
            prop::collection::vec((-1.0f64..1.0, 0.05f64..2.0), n),
        )
            .prop_map(move |(entries, b, boxes)| {
                let mut a = DMatrix::from_vec(m, n, entries);
                for k in 0..n {
                    a[(k, k)] += 2.0;
                }
                let bounds = boxes.into_iter().map(|(c, h)| (c - h, c + h)).collect();
                (a, DVector::from_vec(b), bounds)
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    #[test]
    fn reaches_the_kkt_point_of_a_box_constrained_linear_problem(
        (a, b, bounds) in problems()
    ) {
        let n = a.ncols();
        let (lower, upper): (Vec<f64>, Vec<f64>) = bounds.iter().copied().unzip();
        let x0: Vec<f64> = bounds.iter().map(|(l, u)| 0.5 * (l + u)).collect();
        let mut problem = Linear { a: a.clone(), b: b.clone() };
        let start = problem.evaluate(&x0).unwrap();
        let out = lm::solve(&mut problem, x0, start, &lower, &upper, &SETTINGS).unwrap();
        prop_assert_ne!(out.stop, lm::Stop::Exhausted);
        let x = DVector::from_column_slice(&out.x);
        let g = a.transpose() * (&a * &x - &b);
        // The loop stops once a step lowers |r|² by at most 1e-14 of itself,
        // which leaves a free gradient up to about |A|·1e-7·|r| ≤ 1e-7 |A||b|.
        let tol = 1e-6 * (1.0 + a.norm() * b.norm());
        for k in 0..n {
            prop_assert!(x[k] >= lower[k] && x[k] <= upper[k], "x{} = {} outside", k, x[k]);
            let at_lower = x[k] <= lower[k];
            let at_upper = x[k] >= upper[k];
            if at_lower {
                prop_assert!(g[k] >= -tol, "x{} at its lower bound with g = {}", k, g[k]);
            } else if at_upper {
                prop_assert!(g[k] <= tol, "x{} at its upper bound with g = {}", k, g[k]);
            } else {
                prop_assert!(g[k].abs() <= tol, "free x{} with g = {} (stop {:?})", k, g[k], out.stop);
            }
        }
    }
}
