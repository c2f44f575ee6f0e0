//! Objectivity behind the integrator's rotation-compensated Jacobian reuse
//! (src/analysis/transient/frame.rs): turning a deformed, loaded state of the paper's
//! assembly rigidly by φ turns its tangent stiffness and constraint
//! Jacobian as 𝐑 K 𝐑ᵀ and 𝐑 C_q 𝐑ᵀ, the mass matrix stays, and the
//! best-fit rotation recovers φ.

use ancf_modal::analysis::frame::RotatingFrame;
use ancf_modal::system::Linearization;
use ancf_modal::{Model, System};
use faer::Mat;

/// Deterministic pseudo-random numbers in [−1, 1].
fn noise(seed: u64, count: usize) -> Vec<f64> {
    let mut x = seed;
    (0..count)
        .map(|_| {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

/// q turned by φ about the origin and shifted by `shift`, written from the
/// coordinate layout (positions and slopes turn, body angles add φ).
fn turned(sys: &System, q: &[f64], phi: f64, shift: [f64; 2]) -> Vec<f64> {
    let (s, c) = phi.sin_cos();
    let mut out = q.to_vec();
    let mut turn = |i: usize, moved: bool| {
        let (x, y) = (q[i], q[i + 1]);
        let (dx, dy) = if moved {
            (shift[0], shift[1])
        } else {
            (0.0, 0.0)
        };
        out[i] = c * x - s * y + dx;
        out[i + 1] = s * x + c * y + dy;
    };
    for b in &sys.beams {
        for node in 0..b.node_count() {
            turn(b.dof0 + 4 * node, true);
            turn(b.dof0 + 4 * node + 2, false);
        }
    }
    for r in &sys.rigid_bodies {
        turn(r.dof0, true);
    }
    for p in &sys.point_masses {
        turn(p.dof0, true);
    }
    for r in &sys.rigid_bodies {
        out[r.dof0 + 2] += phi;
    }
    out
}

/// The matrix of `frame.from_reference` on [q; λ] (size n + m).
fn rotation_matrix(frame: &RotatingFrame, size: usize) -> Mat<f64> {
    let mut r = Mat::zeros(size, size);
    for j in 0..size {
        let mut e = vec![0.0; size];
        e[j] = 1.0;
        frame.from_reference(&mut e);
        for i in 0..size {
            r[(i, j)] = e[i];
        }
    }
    r
}

fn max_abs(a: &Mat<f64>) -> f64 {
    let mut m = 0.0f64;
    for j in 0..a.ncols() {
        for i in 0..a.nrows() {
            m = m.max(a[(i, j)].abs());
        }
    }
    m
}

#[test]
fn a_rigid_turn_turns_tangent_and_constraint_jacobian() {
    let sys = System::new(&Model::builtin());
    let (n, m) = (sys.ndof(), sys.constraint_count());
    // A deformed state (1 µm, 1 mrad scale) with joint forces (~1 N).
    let q: Vec<f64> = sys
        .q0
        .iter()
        .zip(noise(7, n))
        .map(|(q, e)| q + 1e-6 * e)
        .collect();
    let lambda: Vec<f64> = noise(11, m);
    let phi = 0.7;
    let q_turned = turned(&sys, &q, phi, [3e-3, -2e-3]);

    let mut frame = RotatingFrame::new(&sys);
    frame.anchor(&q);
    frame.update(&q_turned);
    assert!(
        (frame.angle() - phi).abs() < 1e-12,
        "best-fit angle {} vs turned {phi} rad (tolerance 1e-12)",
        frame.angle()
    );
    let r = rotation_matrix(&frame, n + m);
    let rq = r.as_ref().submatrix(0, 0, n, n).to_owned();
    let rc = r.as_ref().submatrix(n, n, m, m).to_owned();

    let mut lambda_turned = vec![0.0; n + m];
    lambda_turned[n..].copy_from_slice(&lambda);
    frame.from_reference(&mut lambda_turned);
    let tangent = |q: &[f64], lambda: &[f64]| {
        let mut k = Mat::zeros(n, n);
        let at = Linearization {
            q,
            lambda: Some(lambda),
            time: 0.0,
            load_scale: 0.0,
        };
        sys.tangent_stiffness(&at, &mut k);
        k
    };
    let k0 = tangent(&q, &lambda);
    let k1 = tangent(&q_turned, &lambda_turned[n..]);
    let expected = &rq * &k0 * rq.transpose();
    let err = max_abs(&(&k1 - &expected)) / max_abs(&k0);
    assert!(
        err < 1e-13,
        "K(Rq) vs R K(q) Rᵀ: relative error {err:e} (tolerance 1e-13; measured 3e-15)"
    );

    let jacobian = |q: &[f64]| {
        let mut cq = Mat::zeros(m, n);
        sys.constraint_jacobian(q, &mut cq);
        cq
    };
    let c0 = jacobian(&q);
    let c1 = jacobian(&q_turned);
    let expected = &rc * &c0 * rq.transpose();
    let err = max_abs(&(&c1 - &expected)) / max_abs(&c0);
    assert!(
        err < 1e-14,
        "C_q(Rq) vs R C_q(q) Rᵀ: relative error {err:e} (tolerance 1e-14; measured 2e-17)"
    );

    let mass = sys.mass_matrix();
    let err = max_abs(&(&rq * &mass * rq.transpose() - &mass)) / max_abs(&mass);
    assert!(
        err < 1e-14,
        "R M Rᵀ vs M: relative error {err:e} (tolerance 1e-14)"
    );
}

#[test]
fn turning_to_the_reference_and_back_is_the_identity() {
    let sys = System::new(&Model::builtin());
    let size = sys.ndof() + sys.constraint_count();
    let mut frame = RotatingFrame::new(&sys);
    frame.anchor(&sys.q0);
    frame.update(&turned(&sys, &sys.q0, -2.5, [0.0, 0.0]));
    let x = noise(3, size);
    let mut y = x.clone();
    frame.to_reference(&mut y);
    let moved = x
        .iter()
        .zip(&y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        moved > 0.1,
        "a 2.5 rad turn must change the vector (max change {moved})"
    );
    frame.from_reference(&mut y);
    let err = x
        .iter()
        .zip(&y)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        err < 1e-15,
        "Rᵀ then R: max error {err:e} (tolerance 1e-15)"
    );
}
