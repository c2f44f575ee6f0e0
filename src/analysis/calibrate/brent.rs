//! One parameter, one target: bracket the root of g(x) = f(x) − f_target,
//! then Brent's method (inverse quadratic interpolation and secant steps,
//! safeguarded by bisection; Brent 1973, "Algorithms for minimization
//! without derivatives", ch. 4).
//!
//! The bracket is found from the starting point: a Newton step when the
//! derivative is known (else a 5 % probe), then steps that double until g
//! changes sign or a bound is reached. Near-linear problems (bending
//! frequency ∝ height) converge in 2–4 evaluations after the bracket.

/// A point of g.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub x: f64,
    /// g(x) = f(x) − target [SI: Hz].
    pub g: f64,
    /// dg/dx, when the evaluator knows it.
    pub slope: Option<f64>,
}

/// Settings of the search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BrentSettings {
    /// Stop when |g| ≤ this [SI: Hz].
    pub g_tolerance: f64,
    /// Stop when the bracket is narrower than this fraction of |x|.
    pub x_tolerance: f64,
    /// Most evaluations, the start included.
    pub max_evaluations: usize,
}

/// How the search ended.
#[derive(Debug, Clone, PartialEq)]
pub enum BrentOutcome {
    /// The best point (|g| smallest).
    Root(Sample),
    /// g has one sign on the whole of [lower, upper]: the samples at the
    /// bounds (lower first).
    NoSignChange { lower: Sample, upper: Sample },
    /// The evaluation budget ran out: the best point.
    Exhausted(Sample),
}

/// Find x in [lower, upper] with g(x) = 0, starting from `start` (already
/// evaluated). `eval` is called for every new point.
pub fn solve<E>(
    start: Sample,
    lower: f64,
    upper: f64,
    settings: &BrentSettings,
    mut eval: impl FnMut(f64) -> Result<Sample, E>,
) -> Result<BrentOutcome, E> {
    let mut evaluations = 1;
    if start.g.abs() <= settings.g_tolerance {
        return Ok(BrentOutcome::Root(start));
    }
    // --- Bracketing ---------------------------------------------------
    let first_step = match start.slope {
        Some(d) if d != 0.0 && d.is_finite() => -start.g / d,
        _ => 0.05 * start.x * (if start.g > 0.0 { -1.0 } else { 1.0 }),
    };
    let mut prev = start;
    let mut step = first_step;
    let mut lower_sample: Option<Sample> = None;
    let mut upper_sample: Option<Sample> = None;
    let (a, b) = loop {
        let x = (prev.x + step).clamp(lower, upper);
        if x == prev.x {
            // Stuck at a bound in the direction that reduces |g|: check the
            // other bound to report the reachable range.
            let other_x = if x == upper { lower } else { upper };
            let other = match (lower_sample, upper_sample) {
                (Some(s), _) if other_x == lower => s,
                (_, Some(s)) if other_x == upper => s,
                _ => {
                    evaluations += 1;
                    eval(other_x)?
                }
            };
            if other.g.signum() != prev.g.signum() {
                break (prev, other);
            }
            let (lo, hi) = if x == upper {
                (other, prev)
            } else {
                (prev, other)
            };
            return Ok(BrentOutcome::NoSignChange {
                lower: lo,
                upper: hi,
            });
        }
        evaluations += 1;
        let s = eval(x)?;
        if x == lower {
            lower_sample = Some(s);
        }
        if x == upper {
            upper_sample = Some(s);
        }
        if s.g.abs() <= settings.g_tolerance {
            return Ok(BrentOutcome::Root(s));
        }
        if s.g.signum() != prev.g.signum() {
            break (prev, s);
        }
        if evaluations >= settings.max_evaluations {
            return Ok(BrentOutcome::Exhausted(best(prev, s)));
        }
        // Same sign: continue past s, at least doubling the step.
        let newton = match s.slope {
            Some(d) if d != 0.0 && d.is_finite() => -s.g / d,
            _ => (x - prev.x) * s.g / (prev.g - s.g),
        };
        let doubled = 2.0 * (x - prev.x);
        step = if newton.signum() == doubled.signum() && newton.is_finite() {
            if newton.abs() > doubled.abs() {
                newton
            } else {
                // A Newton step that stays short would creep; go 1.5× past it.
                (1.5 * newton).clamp(-doubled.abs(), doubled.abs())
            }
        } else {
            doubled
        };
        prev = s;
    };
    // --- Brent --------------------------------------------------------
    let (mut a, mut b) = (a, b);
    let mut c = a;
    let mut d = b.x - a.x;
    let mut e = d;
    loop {
        if b.g.signum() == c.g.signum() {
            c = a;
            d = b.x - a.x;
            e = d;
        }
        if c.g.abs() < b.g.abs() {
            a = b;
            b = c;
            c = a;
        }
        let tol = 2.0 * f64::EPSILON * b.x.abs() + 0.5 * settings.x_tolerance * b.x.abs();
        let m = 0.5 * (c.x - b.x);
        if b.g.abs() <= settings.g_tolerance || m.abs() <= tol {
            return Ok(BrentOutcome::Root(b));
        }
        if evaluations >= settings.max_evaluations {
            return Ok(BrentOutcome::Exhausted(b));
        }
        if e.abs() >= tol && a.g.abs() > b.g.abs() {
            let s = b.g / a.g;
            let (mut p, mut q);
            if a.x == c.x {
                p = 2.0 * m * s;
                q = 1.0 - s;
            } else {
                let qa = a.g / c.g;
                let r = b.g / c.g;
                p = s * (2.0 * m * qa * (qa - r) - (b.x - a.x) * (r - 1.0));
                q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
            }
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        a = b;
        let x = if d.abs() > tol {
            b.x + d
        } else {
            b.x + tol.copysign(m)
        };
        evaluations += 1;
        b = eval(x)?;
    }
}

fn best(a: Sample, b: Sample) -> Sample {
    if a.g.abs() <= b.g.abs() {
        a
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(g: impl Fn(f64) -> f64, x0: f64) -> (BrentOutcome, usize) {
        let mut n = 0;
        let settings = BrentSettings {
            g_tolerance: 1e-12,
            x_tolerance: 1e-15,
            max_evaluations: 60,
        };
        let start = Sample {
            x: x0,
            g: g(x0),
            slope: None,
        };
        let out = solve::<()>(start, 0.1, 10.0, &settings, |x| {
            n += 1;
            Ok(Sample {
                x,
                g: g(x),
                slope: None,
            })
        })
        .unwrap();
        (out, n)
    }

    #[test]
    fn finds_roots_of_smooth_functions() {
        // x³ = 2 from 1: root 2^(1/3).
        let (out, n) = run(|x| x * x * x - 2.0, 1.0);
        match out {
            BrentOutcome::Root(s) => {
                assert!((s.x - 2f64.cbrt()).abs() < 1e-12, "root {} after {n}", s.x)
            }
            o => panic!("{o:?}"),
        }
        assert!(n < 15, "{n} evaluations");
    }

    #[test]
    fn reports_no_sign_change() {
        let (out, _) = run(|x| x * x + 1.0, 1.0);
        match out {
            BrentOutcome::NoSignChange { lower, upper } => {
                assert_eq!((lower.x, upper.x), (0.1, 10.0));
            }
            o => panic!("{o:?}"),
        }
    }
}
