//! The generalized-α constant-acceleration predictor, coordinate by
//! coordinate in vector registers (`pulp`, AVX2 where the CPU has it):
//!
//! ā₁ = (a₀ − α_m ā₀)/(1 − α_m),
//! q₁ = q₀ + h v₀ + h² ((½ − β) ā₀ + β ā₁),
//! v₁ = v₀ + h ((1 − γ) ā₀ + γ ā₁),
//!
//! each operation IEEE lane by lane and in the scalar formula's order (no
//! fused multiply–add), so every lane holds the bits the scalar loop gives:
//! the division is what a step of a small model waited for, one at a time.
//! Units: q [SI: m or 1], v [1/s], a and ā [1/s²], h [SI: s].

use pulp::Simd;

/// The step and the method's constants.
#[derive(Clone, Copy)]
pub struct Coefficients {
    pub h: f64,
    pub alpha_m: f64,
    pub beta: f64,
    pub gamma: f64,
}

/// The state the step starts from.
pub struct From<'a> {
    pub q: &'a [f64],
    pub v: &'a [f64],
    pub a: &'a [f64],
    pub abar: &'a [f64],
}

/// Where the predicted q, v and ā go.
pub struct Into<'a> {
    pub q: &'a mut [f64],
    pub v: &'a mut [f64],
    pub abar: &'a mut [f64],
}

/// Predicts `into` from `from` (all slices of one length).
pub fn predict(c: Coefficients, from: From, into: Into) {
    pulp::Arch::new().dispatch(Predict { c, from, into });
}

struct Predict<'a> {
    c: Coefficients,
    from: From<'a>,
    into: Into<'a>,
}

impl pulp::WithSimd for Predict<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, simd: S) {
        let Predict { c, from, into } = self;
        let n = into.q.len();
        let lanes = std::mem::size_of::<S::f64s>() / std::mem::size_of::<f64>();
        let whole = n / lanes * lanes;
        let (q0, v0) = (head::<S>(from.q, whole), head::<S>(from.v, whole));
        let (a0, ab0) = (head::<S>(from.a, whole), head::<S>(from.abar, whole));
        let q1 = S::as_mut_simd_f64s(&mut into.q[..whole]).0;
        let v1 = S::as_mut_simd_f64s(&mut into.v[..whole]).0;
        let ab1 = S::as_mut_simd_f64s(&mut into.abar[..whole]).0;
        let sp = |x: f64| simd.splat_f64s(x);
        let (am, one_am) = (sp(c.alpha_m), sp(1.0 - c.alpha_m));
        let (h, hh) = (sp(c.h), sp(c.h * c.h));
        let (half_b, b) = (sp(0.5 - c.beta), sp(c.beta));
        let (one_g, g) = (sp(1.0 - c.gamma), sp(c.gamma));
        let (add, mul) = (|x, y| simd.add_f64s(x, y), |x, y| simd.mul_f64s(x, y));
        for i in 0..q1.len() {
            let abar = simd.div_f64s(simd.sub_f64s(a0[i], mul(am, ab0[i])), one_am);
            ab1[i] = abar;
            q1[i] = add(
                add(q0[i], mul(h, v0[i])),
                mul(hh, add(mul(half_b, ab0[i]), mul(b, abar))),
            );
            v1[i] = add(v0[i], mul(h, add(mul(one_g, ab0[i]), mul(g, abar))));
        }
        let Coefficients {
            h,
            alpha_m,
            beta,
            gamma,
        } = c;
        for i in whole..n {
            let abar = (from.a[i] - alpha_m * from.abar[i]) / (1.0 - alpha_m);
            into.abar[i] = abar;
            into.q[i] =
                from.q[i] + h * from.v[i] + h * h * ((0.5 - beta) * from.abar[i] + beta * abar);
            into.v[i] = from.v[i] + h * ((1.0 - gamma) * from.abar[i] + gamma * abar);
        }
    }
}

/// The first `whole` entries of x as vector registers.
#[inline(always)]
fn head<S: Simd>(x: &[f64], whole: usize) -> &[S::f64s] {
    S::as_simd_f64s(&x[..whole]).0
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Every coordinate, in the registers' head and in the tail past
        /// it, holds the bits of the scalar formula, at any length and for
        /// the coefficients of any spectral radius.
        #[test]
        fn lanes_are_the_scalar_formula_bit_for_bit(
            x in proptest::collection::vec(-1e3..1e3f64, 4..=80),
            rho in 0.0..=1.0f64,
            h in 1e-9..1e-3f64,
        ) {
            let n = x.len() / 4;
            let (q0, v0, a0, ab0) = (&x[..n], &x[n..2 * n], &x[2 * n..3 * n], &x[3 * n..4 * n]);
            // Generalized-α of spectral radius ρ∞ (Chung and Hulbert).
            let alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
            let alpha_f = rho / (rho + 1.0);
            let gamma = 0.5 - alpha_m + alpha_f;
            let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
            let c = Coefficients { h, alpha_m, beta, gamma };
            let (mut q1, mut v1, mut ab1) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            predict(
                c,
                From { q: q0, v: v0, a: a0, abar: ab0 },
                Into { q: &mut q1, v: &mut v1, abar: &mut ab1 },
            );
            for i in 0..n {
                let abar = (a0[i] - alpha_m * ab0[i]) / (1.0 - alpha_m);
                let q = q0[i] + h * v0[i] + h * h * ((0.5 - beta) * ab0[i] + beta * abar);
                let v = v0[i] + h * ((1.0 - gamma) * ab0[i] + gamma * abar);
                prop_assert_eq!(ab1[i].to_bits(), abar.to_bits(), "abar[{}] of {}", i, n);
                prop_assert_eq!(q1[i].to_bits(), q.to_bits(), "q[{}] of {}", i, n);
                prop_assert_eq!(v1[i].to_bits(), v.to_bits(), "v[{}] of {}", i, n);
            }
        }
    }
}
