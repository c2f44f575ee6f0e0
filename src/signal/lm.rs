//! The one bounded Levenberg–Marquardt loop: min |r(x)|² over a box
//! lower ≤ x ≤ upper, for the calibration of model parameters and for the
//! refinement of fitted poles.
//!
//! Each iteration solves (JᵀJ + μ D) δ = −Jᵀr with Marquardt's scaling
//! D = diag(JᵀJ) by Cholesky. Unknowns held at a bound by a gradient that
//! points outward are left out of the step (projected Gauss–Newton), and the
//! step is clamped onto the box. A step that lowers |r|² is taken and μ
//! shrinks; otherwise μ grows and the step is retried from the same point.
//! The Jacobian is asked for only at taken points, so a finite-difference
//! Jacobian costs nothing on rejected trials.
//!
//! The loop stops when the problem says its targets are met
//! ([`Problem::converged`]), when a taken step lowers |r|² by no more than
//! [`Settings::min_relative_decrease`], when a step would move no unknown by
//! more than [`Settings::step_tolerance`], when μ passes its ceiling or too
//! many trials in a row are rejected (a least-squares optimum, or a bound),
//! or when the evaluation or iteration budget is used up.
//!
//! Units are the problem's: x is whatever it chooses (the calibration uses
//! ln p, so bounds are ratios and parameters of different units weigh
//! alike), r is dimensionless or in one unit throughout.

use nalgebra::{DMatrix, DVector};

/// A least-squares problem as the loop sees it.
pub trait Problem {
    /// One evaluation at some x (whatever the residuals and the Jacobian
    /// are computed from).
    type Point;
    type Error;
    /// Evaluates the problem at `x`.
    fn evaluate(&mut self, x: &[f64]) -> Result<Self::Point, Self::Error>;
    /// The residual vector of an evaluated point.
    fn residuals(&self, point: &Self::Point) -> DVector<f64>;
    /// ∂r/∂x at a taken point `x` with residuals `r`.
    fn jacobian(
        &mut self,
        x: &[f64],
        point: &Self::Point,
        r: &DVector<f64>,
    ) -> Result<DMatrix<f64>, Self::Error>;
    /// Whether the point meets the problem's own targets (stops the loop).
    fn converged(&self, _point: &Self::Point) -> bool {
        false
    }
}

/// A value given outright, or relative to the largest diagonal entry of
/// JᵀJ (of the unknowns free at that step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scale {
    Absolute(f64),
    Relative(f64),
}

impl Scale {
    fn of(self, largest_diagonal: f64) -> f64 {
        match self {
            Scale::Absolute(v) => v,
            Scale::Relative(v) => v * largest_diagonal,
        }
    }
}

/// Settings of [`solve`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// μ at the start.
    pub initial_damping: Scale,
    /// μ is multiplied by this after a rejected trial.
    pub grow: f64,
    /// μ is divided by this after a taken step ...
    pub shrink: f64,
    /// ... but kept at least this.
    pub damping_floor: Scale,
    /// Stalled when μ passes this, relative to the largest diagonal.
    pub damping_ceiling: f64,
    /// Stalled after this many rejected trials in a row.
    pub max_rejections: usize,
    /// Stalled when a step would move no unknown by more than this.
    pub step_tolerance: f64,
    /// Stalled when a taken step lowers |r|² by at most this fraction.
    pub min_relative_decrease: f64,
    /// Most evaluations, the start included.
    pub max_evaluations: usize,
    /// Most Jacobians, the start's included.
    pub max_iterations: usize,
}

/// How the loop ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The problem's targets are met.
    Converged,
    /// No further progress (a least-squares optimum, or a bound).
    Stalled,
    /// The evaluation or iteration budget is used up.
    Exhausted,
}

/// The best point, its x, why the loop stopped, and which evaluations were
/// taken as iterates (0 = the start).
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome<P> {
    pub x: Vec<f64>,
    pub best: P,
    pub stop: Stop,
    pub accepted: Vec<usize>,
    pub evaluations: usize,
}

/// Smallest diagonal of D, relative to the largest: keeps the scaled
/// system definite when an unknown has no effect.
const DIAGONAL_FLOOR: f64 = 1e-30;

/// Minimises |r(x)|² from `x0` (evaluated as `start`) within
/// [lower, upper] (module doc).
pub fn solve<Q: Problem>(
    problem: &mut Q,
    x0: Vec<f64>,
    start: Q::Point,
    lower: &[f64],
    upper: &[f64],
    settings: &Settings,
) -> Result<Outcome<Q::Point>, Q::Error> {
    let n = x0.len();
    let mut x = x0;
    let mut current = start;
    let mut evaluations = 1;
    let mut iterations = 1;
    let mut accepted = vec![0];
    let mut r = problem.residuals(&current);
    // The Jacobian at the current point, computed when a step needs it:
    // not after the step the loop stops on.
    let j0 = problem.jacobian(&x, &current, &r)?;
    let largest = |m: &DMatrix<f64>| (0..m.ncols()).map(|k| m[(k, k)]).fold(0.0, f64::max);
    let mut mu = settings
        .initial_damping
        .of(largest(&(j0.transpose() * &j0)))
        .max(1e-300);
    let mut jacobian = Some(j0);
    let mut cost = r.norm_squared();
    let mut rejections = 0;
    let stop = loop {
        if problem.converged(&current) {
            break Stop::Converged;
        }
        if evaluations >= settings.max_evaluations {
            break Stop::Exhausted;
        }
        let j = match jacobian.take() {
            Some(j) => j,
            None if iterations >= settings.max_iterations => break Stop::Exhausted,
            None => {
                iterations += 1;
                problem.jacobian(&x, &current, &r)?
            }
        };
        let jtj = j.transpose() * &j;
        let g = j.transpose() * &r;
        let free: Vec<usize> = (0..n)
            .filter(|&k| !((x[k] <= lower[k] && g[k] > 0.0) || (x[k] >= upper[k] && g[k] < 0.0)))
            .collect();
        if free.is_empty() {
            break Stop::Stalled;
        }
        let nf = free.len();
        let top = free.iter().map(|&k| jtj[(k, k)]).fold(0.0, f64::max);
        let diag: Vec<f64> = free
            .iter()
            .map(|&k| jtj[(k, k)].max(DIAGONAL_FLOOR * top).max(f64::MIN_POSITIVE))
            .collect();
        let scale = diag.iter().fold(0.0, |a: f64, b| a.max(*b));
        let mut a = DMatrix::from_fn(nf, nf, |i, k| jtj[(free[i], free[k])]);
        for (k, d) in diag.iter().enumerate() {
            a[(k, k)] += mu * d;
        }
        let rhs = DVector::from_fn(nf, |i, _| -g[free[i]]);
        let Some(delta_free) = a.cholesky().map(|c| c.solve(&rhs)) else {
            jacobian = Some(j);
            mu *= settings.grow;
            rejections += 1;
            if rejections >= settings.max_rejections {
                break Stop::Stalled;
            }
            continue;
        };
        let mut x_new = x.clone();
        for (i, &k) in free.iter().enumerate() {
            x_new[k] = (x[k] + delta_free[i]).clamp(lower[k], upper[k]);
        }
        let moved = (0..n).map(|k| (x_new[k] - x[k]).abs()).fold(0.0, f64::max);
        if moved <= settings.step_tolerance {
            break Stop::Stalled;
        }
        let trial = problem.evaluate(&x_new)?;
        evaluations += 1;
        let r_new = problem.residuals(&trial);
        let cost_new = r_new.norm_squared();
        if cost_new < cost {
            let small = cost - cost_new <= settings.min_relative_decrease * cost;
            x = x_new;
            current = trial;
            r = r_new;
            cost = cost_new;
            rejections = 0;
            accepted.push(evaluations - 1);
            mu = (mu / settings.shrink).max(settings.damping_floor.of(scale));
            if small && !problem.converged(&current) {
                break Stop::Stalled;
            }
        } else {
            jacobian = Some(j);
            mu *= settings.grow;
            rejections += 1;
            if mu > settings.damping_ceiling * scale || rejections >= settings.max_rejections {
                break Stop::Stalled;
            }
        }
    };
    Ok(Outcome {
        x,
        best: current,
        stop,
        accepted,
        evaluations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f₁ = 3 a b, f₂ = a / b² in x = ln p: an exact solution from two
    /// targets, with the Jacobian in closed form.
    struct TwoByTwo {
        targets: [f64; 2],
    }

    fn model(p: &[f64]) -> [f64; 2] {
        [3.0 * p[0] * p[1], p[0] / (p[1] * p[1])]
    }

    impl Problem for TwoByTwo {
        type Point = Vec<f64>;
        type Error = ();
        fn evaluate(&mut self, x: &[f64]) -> Result<Vec<f64>, ()> {
            Ok(x.iter().map(|u| u.exp()).collect())
        }
        fn residuals(&self, p: &Vec<f64>) -> DVector<f64> {
            let f = model(p);
            DVector::from_fn(2, |i, _| (f[i] - self.targets[i]) / self.targets[i])
        }
        fn jacobian(
            &mut self,
            _: &[f64],
            p: &Vec<f64>,
            _: &DVector<f64>,
        ) -> Result<DMatrix<f64>, ()> {
            // ∂f/∂ln p = p ∂f/∂p: f₁ → (f₁, f₁), f₂ → (f₂, −2 f₂).
            let f = model(p);
            Ok(DMatrix::from_row_slice(
                2,
                2,
                &[
                    f[0] / self.targets[0],
                    f[0] / self.targets[0],
                    f[1] / self.targets[1],
                    -2.0 * f[1] / self.targets[1],
                ],
            ))
        }
        fn converged(&self, p: &Vec<f64>) -> bool {
            self.residuals(p).amax() <= 1e-13
        }
    }

    fn settings() -> Settings {
        Settings {
            initial_damping: Scale::Relative(1e-3),
            grow: 10.0,
            shrink: 10.0,
            damping_floor: Scale::Relative(1e-12),
            damping_ceiling: 1e16,
            max_rejections: usize::MAX,
            step_tolerance: 1e-15,
            min_relative_decrease: 1e-12,
            max_evaluations: 50,
            max_iterations: usize::MAX,
        }
    }

    #[test]
    fn solves_a_square_nonlinear_system() {
        let truth = [2.0, 0.5];
        let mut problem = TwoByTwo {
            targets: model(&truth),
        };
        let x0 = vec![0.0, 0.0];
        let start = problem.evaluate(&x0).unwrap();
        let (lo, hi) = ([0.01f64.ln(); 2], [100f64.ln(); 2]);
        let out = solve(&mut problem, x0, start, &lo, &hi, &settings()).unwrap();
        assert_eq!(out.stop, Stop::Converged);
        for (p, t) in out.best.iter().zip(truth) {
            assert!((p - t).abs() < 1e-10, "{:?}", out.best);
        }
    }

    /// With the solution outside the box, the loop stops on the bound it
    /// presses against, with the other unknown at its best value there.
    #[test]
    fn stops_on_a_bound() {
        let truth = [2.0, 0.5];
        let mut problem = TwoByTwo {
            targets: model(&truth),
        };
        let x0 = vec![0.0, 0.0];
        let start = problem.evaluate(&x0).unwrap();
        // a ≤ 1.5 while the targets need a = 2.
        let (lo, hi) = ([0.01f64.ln(); 2], [1.5f64.ln(), 100f64.ln()]);
        let out = solve(&mut problem, x0, start, &lo, &hi, &settings()).unwrap();
        assert_eq!(out.stop, Stop::Stalled);
        assert!((out.best[0] - 1.5).abs() < 1e-12, "{:?}", out.best);
        // At a = 1.5 the best b minimises the two relative residuals: the
        // gradient in ln b vanishes, r₁ f₁ − 2 r₂ f₂ = 0 (targets scaled).
        let r = problem.residuals(&out.best);
        let f = model(&out.best);
        let t = model(&truth);
        let grad_b = r[0] * f[0] / t[0] - 2.0 * r[1] * f[1] / t[1];
        assert!(grad_b.abs() < 1e-6, "gradient {grad_b}");
    }
}
