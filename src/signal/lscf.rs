//! The least-squares complex-frequency (LSCF) seeds of the modal fit (see
//! [`super::fit`]): a common-denominator polynomial in Ω = e^(−iωΔt) fitted
//! to the band's FRF at each even order, its roots the candidate poles.
//! The stabilization and the choice of modes are [`super::fit`]'s.

use nalgebra::DMatrix;
use realfft::num_complex::Complex64;

use super::fit::MAX_DAMPING;

/// Most Schur (QR) sweeps per root of the companion matrix.
const SCHUR_SWEEPS_PER_ROOT: usize = 100;
/// How LSCF's variable Ω = e^(−iωΔt) covers the band: the band, shifted
/// down by `shift_hz`, is mapped onto the upper half of the unit circle,
/// Δt = 1/(2 (f_hi − shift)). A band from near zero is not shifted. A
/// narrow band far from zero is shifted to start at zero: unshifted it
/// covers a short arc, where the powers Ω^k are nearly dependent (on a
/// 900–1100 Hz zoom LSCF could not be solved past order 8, and a 1000 and
/// a 1012 Hz mode at ζ 0.5 % were not found). Shifted, the real
/// polynomials put a mirror image of each pole below the band's start,
/// outside it, where it is left out.
#[derive(Debug, Clone, Copy)]
struct Mapping {
    dt: f64,
    shift_hz: f64,
}

/// Bands starting above this fraction of their width are shifted
/// ([`Mapping`]).
const ZOOM_SHIFT: f64 = 0.25;

impl Mapping {
    fn of(f_lo: f64, f_hi: f64) -> Mapping {
        let shift_hz = if f_lo > ZOOM_SHIFT * (f_hi - f_lo) {
            f_lo
        } else {
            0.0
        };
        Mapping {
            dt: 0.5 / (f_hi - shift_hz),
            shift_hz,
        }
    }

    /// Ω at `f` Hz.
    fn omega(self, f: f64) -> Complex64 {
        Complex64::from_polar(
            1.0,
            -2.0 * std::f64::consts::PI * (f - self.shift_hz) * self.dt,
        )
    }

    /// The pole s whose Ω is the root `z`.
    fn pole(self, z: Complex64) -> Complex64 {
        -z.ln() / self.dt + Complex64::new(0.0, 2.0 * std::f64::consts::PI * self.shift_hz)
    }
}

/// Poles (f Hz, ζ, s) of one LSCF order from the Toeplitz lag sums.
fn poles_of_order(
    n: usize,
    r: &DMatrix<f64>,
    s: &DMatrix<f64>,
    t: &DMatrix<f64>,
    mapping: Mapping,
    (f_lo, f_hi): (f64, f64),
) -> Option<Vec<(f64, f64, Complex64)>> {
    let m = n + 1;
    let rr = r.view((0, 0), (m, m)).into_owned();
    let ss = s.view((0, 0), (m, m)).into_owned();
    let tt = t.view((0, 0), (m, m)).into_owned();
    let rinv_s = rr.cholesky().map(|c| c.solve(&ss))?;
    let mm = tt - ss.transpose() * rinv_s;
    let a00 = mm.view((0, 0), (n, n)).into_owned();
    let rhs = -mm.view((0, n), (n, 1)).into_owned();
    let a = a00
        .lu()
        .solve(&rhs)
        .filter(|a| a.iter().all(|v| v.is_finite()))?;
    // Companion matrix of z^n + a_{n-1} z^{n-1} + … + a_0.
    let mut c = DMatrix::<f64>::zeros(n, n);
    for i in 0..n - 1 {
        c[(i, i + 1)] = 1.0;
    }
    for j in 0..n {
        c[(n - 1, j)] = -a[j];
    }
    // nalgebra's `complex_eigenvalues` iterates without a bound and did
    // not return on a generated record (property suite): the Schur
    // iteration is bounded, and an order whose roots it does not find
    // adds no poles.
    let schur = c.try_schur(f64::EPSILON, SCHUR_SWEEPS_PER_ROOT * n)?;
    let poles = schur
        .complex_eigenvalues()
        .iter()
        .filter_map(|z| {
            let z = Complex64::new(z.re, z.im);
            if z.norm() == 0.0 {
                return None;
            }
            let sp = mapping.pole(z);
            let w = sp.norm();
            let f = w / (2.0 * std::f64::consts::PI);
            let zeta = -sp.re / w;
            (sp.im > 0.0 && zeta > 0.0 && zeta < MAX_DAMPING && f >= f_lo && f <= f_hi)
                .then_some((f, zeta, sp))
        })
        .collect();
    Some(poles)
}

/// The poles (f Hz, ζ, s) in [f_lo, f_hi] of the LSCF fits of orders 2, 4,
/// …, `n_max` to the bins of `band`, with those orders.
#[allow(clippy::type_complexity)]
pub fn orders(
    band: &[(f64, Complex64)],
    f_lo: f64,
    f_hi: f64,
    n_max: usize,
) -> (Vec<usize>, Vec<Vec<(f64, f64, Complex64)>>) {
    let scale = band.iter().map(|(_, h)| h.norm()).fold(0.0, f64::max);
    if scale == 0.0 {
        return (Vec::new(), Vec::new());
    }
    let mapping = Mapping::of(f_lo, f_hi);
    // Lag sums Σ Ω^l, Σ H Ω^l, Σ |H|² Ω^l for l = 0..=n_max (Ω^(−l) is the
    // conjugate for the real parts taken below).
    let mut p0 = vec![Complex64::new(0.0, 0.0); n_max + 1];
    let mut p1 = vec![Complex64::new(0.0, 0.0); 2 * n_max + 1];
    let mut p2 = vec![Complex64::new(0.0, 0.0); n_max + 1];
    for (f, hk) in band {
        let hk = hk / scale;
        let omega = mapping.omega(*f);
        let mut pw = Complex64::new(1.0, 0.0);
        let mut pw_inv = Complex64::new(1.0, 0.0);
        for l in 0..=n_max {
            p0[l] += pw;
            p2[l] += hk.norm_sqr() * pw;
            p1[n_max + l] += hk * pw;
            if l > 0 {
                p1[n_max - l] += hk * pw_inv;
            }
            pw *= omega;
            pw_inv *= omega.conj();
        }
    }
    let m = n_max + 1;
    // R_ij = Re Σ Ω^(j−i); S_ij = −Re Σ H Ω^(j−i); T_ij = Re Σ |H|² Ω^(j−i).
    let lag = |v: &[Complex64], i: usize, j: usize| -> f64 {
        if j >= i {
            v[j - i].re
        } else {
            v[i - j].re
        }
    };
    let r = DMatrix::from_fn(m, m, |i, j| lag(&p0, i, j));
    let t = DMatrix::from_fn(m, m, |i, j| lag(&p2, i, j));
    let s = DMatrix::from_fn(m, m, |i, j| {
        -p1[(n_max as isize + j as isize - i as isize) as usize].re
    });
    // An order whose normal equations the arithmetic cannot solve (a
    // narrow band far from zero makes them ill-conditioned past some
    // order: on a 400–750 Hz band every order above 18) is left out, so
    // that it does not count against the stability of the others.
    (2..=n_max)
        .step_by(2)
        .filter_map(|n| poles_of_order(n, &r, &s, &t, mapping, (f_lo, f_hi)).map(|p| (n, p)))
        .unzip()
}
