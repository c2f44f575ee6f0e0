//! Several parameters and/or several targets: damped Gauss–Newton
//! (Levenberg–Marquardt with Marquardt's diagonal scaling).
//!
//! Unknowns are u = ln p, so every parameter stays positive and parameters of
//! different units and magnitudes weigh alike; bounds are boxes in u and
//! steps are projected onto them. Residuals are relative, rᵢ = (fᵢ − tᵢ)/tᵢ,
//! with the Jacobian Jᵢⱼ = pⱼ (∂fᵢ/∂pⱼ)/tᵢ from the analytic sensitivities.
//! Each step solves (JᵀJ + μ diag(JᵀJ)) δ = −Jᵀr; a step that lowers |r|²
//! is taken and μ shrinks ×10, otherwise μ grows ×10 and the step is retried.

use nalgebra::{DMatrix, DVector};

/// One evaluated point: parameters, frequencies and ∂f/∂p.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    pub p: Vec<f64>,
    pub f: Vec<f64>,
    /// ∂fᵢ/∂pⱼ [Hz per parameter unit].
    pub dfdp: Vec<Vec<f64>>,
}

/// Settings of the iteration.
#[derive(Debug, Clone, PartialEq)]
pub struct LmSettings {
    /// Converged when every |fᵢ − tᵢ| ≤ tolerance_hz[i].
    pub tolerance_hz: Vec<f64>,
    /// Stalled when a taken step changes no ln p by more than this.
    pub step_tolerance: f64,
    /// Most evaluations, the start included.
    pub max_evaluations: usize,
}

/// How the iteration ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LmStop {
    /// All targets met within tolerance.
    Converged,
    /// No further progress (a least-squares optimum, or a bound).
    Stalled,
    /// Evaluation budget used up.
    Exhausted,
}

/// The result: the best point, the stop reason, and which evaluations were
/// accepted as iterates (0 = the start).
#[derive(Debug, Clone, PartialEq)]
pub struct LmResult {
    pub best: Point,
    pub stop: LmStop,
    pub accepted: Vec<usize>,
    pub evaluations: usize,
}

/// Relative residuals and Jacobian in u = ln p.
pub fn residual_jacobian(pt: &Point, targets: &[f64]) -> (DVector<f64>, DMatrix<f64>) {
    let m = targets.len();
    let n = pt.p.len();
    let r = DVector::from_fn(m, |i, _| (pt.f[i] - targets[i]) / targets[i]);
    let j = DMatrix::from_fn(m, n, |i, k| pt.p[k] * pt.dfdp[i][k] / targets[i]);
    (r, j)
}

fn met(pt: &Point, targets: &[f64], tol: &[f64]) -> bool {
    pt.f.iter()
        .zip(targets)
        .zip(tol)
        .all(|((f, t), tol)| (f - t).abs() <= *tol)
}

/// Minimize Σ rᵢ² from `start` within [lower, upper] (parameter units).
pub fn solve<E>(
    start: Point,
    targets: &[f64],
    lower: &[f64],
    upper: &[f64],
    settings: &LmSettings,
    mut eval: impl FnMut(&[f64]) -> Result<Point, E>,
) -> Result<LmResult, E> {
    let n = start.p.len();
    let lo: Vec<f64> = lower.iter().map(|v| v.ln()).collect();
    let hi: Vec<f64> = upper.iter().map(|v| v.ln()).collect();
    let mut current = start;
    let mut evaluations = 1;
    let mut accepted = vec![0];
    let (mut r, mut j) = residual_jacobian(&current, targets);
    let mut cost = r.norm_squared();
    let jtj = j.transpose() * &j;
    let mut mu = 1e-3 * (0..n).map(|k| jtj[(k, k)]).fold(0.0, f64::max).max(1e-300);
    let mu_floor = 1e-12;
    loop {
        if met(&current, targets, &settings.tolerance_hz) {
            return Ok(LmResult {
                best: current,
                stop: LmStop::Converged,
                accepted,
                evaluations,
            });
        }
        if evaluations >= settings.max_evaluations {
            return Ok(LmResult {
                best: current,
                stop: LmStop::Exhausted,
                accepted,
                evaluations,
            });
        }
        let jtj = j.transpose() * &j;
        let g = j.transpose() * &r;
        let u: Vec<f64> = current.p.iter().map(|p| p.ln()).collect();
        // Parameters held at a bound by a gradient that points outward are
        // left out of the step (projected Gauss–Newton).
        let free: Vec<usize> = (0..n)
            .filter(|&k| !((u[k] <= lo[k] && g[k] > 0.0) || (u[k] >= hi[k] && g[k] < 0.0)))
            .collect();
        if free.is_empty() {
            return Ok(LmResult {
                best: current,
                stop: LmStop::Stalled,
                accepted,
                evaluations,
            });
        }
        let nf = free.len();
        let diag: Vec<f64> = free.iter().map(|&k| jtj[(k, k)].max(1e-30)).collect();
        let mut a = DMatrix::from_fn(nf, nf, |i, k| jtj[(free[i], free[k])]);
        for (k, d) in diag.iter().enumerate() {
            a[(k, k)] += mu * d;
        }
        let rhs = DVector::from_fn(nf, |i, _| -g[free[i]]);
        let delta_free = match a.cholesky() {
            Some(c) => c.solve(&rhs),
            None => {
                mu *= 10.0;
                continue;
            }
        };
        let mut delta = vec![0.0; n];
        for (i, &k) in free.iter().enumerate() {
            delta[k] = delta_free[i];
        }
        let u_new: Vec<f64> = (0..n)
            .map(|k| (u[k] + delta[k]).clamp(lo[k], hi[k]))
            .collect();
        let moved = (0..n).map(|k| (u_new[k] - u[k]).abs()).fold(0.0, f64::max);
        if moved <= settings.step_tolerance {
            return Ok(LmResult {
                best: current,
                stop: LmStop::Stalled,
                accepted,
                evaluations,
            });
        }
        let p_new: Vec<f64> = u_new.iter().map(|v| v.exp()).collect();
        let trial = eval(&p_new)?;
        evaluations += 1;
        let (r_new, j_new) = residual_jacobian(&trial, targets);
        let cost_new = r_new.norm_squared();
        if cost_new < cost {
            // A taken step that gains nothing measurable: a least-squares
            // optimum (or a bound) has been reached.
            let stalled = cost - cost_new <= 1e-12 * cost;
            current = trial;
            r = r_new;
            j = j_new;
            cost = cost_new;
            accepted.push(evaluations - 1);
            mu = (mu / 10.0).max(mu_floor * diag.iter().fold(0.0, |a: f64, b| a.max(*b)));
            if stalled && !met(&current, targets, &settings.tolerance_hz) {
                return Ok(LmResult {
                    best: current,
                    stop: LmStop::Stalled,
                    accepted,
                    evaluations,
                });
            }
        } else {
            mu *= 10.0;
            let scale = diag.iter().fold(0.0, |a: f64, b| a.max(*b));
            if mu > 1e16 * scale {
                return Ok(LmResult {
                    best: current,
                    stop: LmStop::Stalled,
                    accepted,
                    evaluations,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// f₁ = 3 a b, f₂ = a / b²: exact solution from two targets.
    #[test]
    fn solves_a_square_nonlinear_system() {
        let model = |p: &[f64]| Point {
            p: p.to_vec(),
            f: vec![3.0 * p[0] * p[1], p[0] / (p[1] * p[1])],
            dfdp: vec![
                vec![3.0 * p[1], 3.0 * p[0]],
                vec![1.0 / (p[1] * p[1]), -2.0 * p[0] / (p[1] * p[1] * p[1])],
            ],
        };
        let truth = [2.0, 0.5];
        let t = model(&truth).f;
        let settings = LmSettings {
            tolerance_hz: vec![1e-12; 2],
            step_tolerance: 1e-15,
            max_evaluations: 50,
        };
        let out = solve::<()>(
            model(&[1.0, 1.0]),
            &t,
            &[0.01, 0.01],
            &[100.0, 100.0],
            &settings,
            |p| Ok(model(p)),
        )
        .unwrap();
        assert_eq!(out.stop, LmStop::Converged);
        for (p, t) in out.best.p.iter().zip(truth) {
            assert!((p - t).abs() < 1e-10, "{:?}", out.best.p);
        }
    }
}
