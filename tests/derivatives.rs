//! Layer 2: analytic derivatives against central finite differences at
//! random deformed states: the element tangent ∂Q_s/∂e, the system tangent
//! (springs, torsion springs, rigid-body loads), the constraint Jacobian C_q
//! and the constraint Hessian term ∂(C_qᵀλ)/∂q.

mod common;
use ancf_modal::mechanics::element::{CableElement, CableSection, Mat8, Vec8};
use ancf_modal::system::Linearization;
use ancf_modal::System;
use common::*;
use faer::Mat;
use serde_json::json;

/// Small deterministic generator (xorshift) so failures reproduce.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// Max relative difference, relative to the largest entry of the reference.
fn rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

#[test]
fn element_tangent_equals_central_differences_of_elastic_force() {
    let le = 3e-3;
    let el = CableElement::new(le, CableSection::rectangle(E, RHO, H, W));
    let mut rng = Rng(0x9e3779b97f4a7c15);
    for trial in 0..20 {
        // A straight element at a random angle, then large random perturbations
        // of positions (up to 10 % of Le) and slopes (up to 20 %).
        let a = std::f64::consts::PI * rng.uniform();
        let mut e = CableElement::straight(
            le,
            nalgebra::Vector2::new(rng.uniform(), rng.uniform()) * 1e-2,
            nalgebra::Vector2::new(a.cos(), a.sin()),
        );
        for i in 0..8 {
            let size = if i % 4 < 2 { 0.1 * le } else { 0.2 };
            e[i] += size * rng.uniform();
        }
        let mut k = Mat8::zeros();
        el.tangent_into(&e, &mut k);
        for j in 0..8 {
            let h = if j % 4 < 2 { 1e-6 * le } else { 1e-6 };
            let (mut ep, mut em) = (e, e);
            ep[j] += h;
            em[j] -= h;
            let (mut fp, mut fm) = (Vec8::zeros(), Vec8::zeros());
            el.elastic_force_into(&ep, &mut fp);
            el.elastic_force_into(&em, &mut fm);
            let fd: Vec<f64> = (0..8).map(|i| (fp[i] - fm[i]) / (2.0 * h)).collect();
            let an: Vec<f64> = (0..8).map(|i| k[(i, j)]).collect();
            let d = rel_diff(&an, &fd);
            assert!(
                d <= 1e-6,
                "trial {trial}, column {j}: |K − FD| / max|FD| = {d:e} (limit 1e-6)"
            );
        }
        // K is a Hessian of the strain energy: symmetric.
        let asym = (k - k.transpose()).abs().max() / k.abs().max();
        assert!(asym <= 1e-12, "trial {trial}: tangent asymmetry {asym:e}");
    }
}

#[test]
fn elastic_force_is_the_gradient_of_strain_energy() {
    let le = 3e-3;
    let el = CableElement::new(le, CableSection::rectangle(E, RHO, H, W));
    let mut rng = Rng(42);
    let mut e = CableElement::straight(
        le,
        nalgebra::Vector2::zeros(),
        nalgebra::Vector2::new(0.6, 0.8),
    );
    for i in 0..8 {
        e[i] += if i % 4 < 2 { 0.05 * le } else { 0.1 } * rng.uniform();
    }
    let mut f = Vec8::zeros();
    el.elastic_force_into(&e, &mut f);
    let energy = |x: &Vec8| {
        let s = el.strain_energy(x);
        s.axial + s.bending
    };
    let fd: Vec<f64> = (0..8)
        .map(|j| {
            let h = if j % 4 < 2 { 1e-6 * le } else { 1e-6 };
            let (mut ep, mut em) = (e, e);
            ep[j] += h;
            em[j] -= h;
            (energy(&ep) - energy(&em)) / (2.0 * h)
        })
        .collect();
    let d = rel_diff(f.as_slice(), &fd);
    assert!(d <= 1e-6, "|Q_s − ∂U/∂e (FD)| / max = {d:e}");
}

/// A model with every kind of force element and constraint: beam–rigid weld,
/// beam–point-mass pin, pin with torsion spring between two beams, slider,
/// preloaded translational spring, off-centre load on a rigid body.
fn kitchen_sink() -> System {
    let m = model(json!({
        "name": "kitchen sink",
        "beams": [
            {"id": "b1", "start": [0.0, 0.0], "angle_deg": 10.0, "length": 0.02, "elements": 3,
             "section": {"height": 1e-3, "width": 5e-3}, "material": {"young": 1e11, "density": 8000.0}},
            {"id": "b2", "start": [0.0196961550602442, 0.00347296355333861], "angle_deg": -30.0, "length": 0.015, "elements": 2,
             "section": {"height": 1e-3, "width": 5e-3}, "material": {"young": 1e11, "density": 8000.0}}
        ],
        "rigid_bodies": [{"id": "r", "mass": 1e-3, "inertia": 2e-9, "position": [0.003, 0.004], "angle_deg": 25.0}],
        "point_masses": [{"id": "p", "mass": 3e-4, "position": [0.0, 0.0]}],
        "joints": [
            {"type": "weld", "a": {"body": "r"}, "b": {"beam": "b1", "s": 0.01}},
            {"type": "pin", "a": {"body": "p"}, "b": {"beam": "b1", "s": 0.0}},
            {"type": "pin", "a": {"beam": "b1", "s": 0.02}, "b": {"beam": "b2", "s": 0.0}, "torsion_stiffness": 0.3},
            {"type": "slider", "a": {"body": "r", "local": [0.0, 0.0]}, "b": {"beam": "b2", "s": 0.015}, "axis": [0.029686536117010737, -0.008027036446661393]}
        ],
        "springs": [{"a": {"ground": [0.03, 0.02]}, "b": {"beam": "b2", "s": 0.007}, "stiffness": 500.0, "preload": -2.0}],
        "loads": [{"at": {"body": "r", "local": [0.002, -0.001]}, "force": [1.5, -0.7]}]
    }));
    System::new(&m)
}

fn perturbed_state(sys: &System, seed: u64) -> Vec<f64> {
    let mut rng = Rng(seed);
    sys.q0.iter().map(|&x| x + 1e-4 * rng.uniform()).collect()
}

#[test]
fn system_tangent_equals_central_differences_of_residual_force() {
    let sys = kitchen_sink();
    let n = sys.ndof();
    let q = perturbed_state(&sys, 7);
    let at = Linearization {
        q: &q,
        lambda: None,
        time: 0.0,
        load_scale: 1.0,
    };
    let mut k = Mat::zeros(n, n);
    sys.tangent_stiffness(&at, &mut k);
    let residual = |x: &[f64]| {
        let (mut fi, mut fe) = (vec![0.0; n], vec![0.0; n]);
        sys.internal_force(x, &mut fi);
        sys.external_force(x, 0.0, 1.0, &mut fe);
        fi.iter().zip(&fe).map(|(a, b)| a - b).collect::<Vec<f64>>()
    };
    let mut worst = 0.0f64;
    let scale = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |m, (i, j)| m.max(k[(i, j)].abs()));
    for j in 0..n {
        let h = 1e-7;
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[j] += h;
        qm[j] -= h;
        let (rp, rm) = (residual(&qp), residual(&qm));
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            worst = worst.max((k[(i, j)] - fd).abs() / scale);
        }
    }
    assert!(
        worst <= 1e-6,
        "system tangent vs FD: max |ΔK|/max|K| = {worst:e} (limit 1e-6)"
    );
}

#[test]
fn constraint_jacobian_and_hessian_equal_central_differences() {
    let sys = kitchen_sink();
    let (n, m) = (sys.ndof(), sys.constraint_count());
    let q = perturbed_state(&sys, 11);
    let mut rng = Rng(5);
    let lambda: Vec<f64> = (0..m).map(|_| rng.uniform()).collect();
    let mut cq = Mat::zeros(m, n);
    sys.constraint_jacobian(&q, &mut cq);
    let mut hess = Mat::zeros(n, n);
    sys.add_constraint_hessian(&q, &lambda, &mut hess);
    let h = 1e-7;
    let (mut worst_j, mut worst_h) = (0.0f64, 0.0f64);
    let jscale = (0..m)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |s, (i, j)| s.max(cq[(i, j)].abs()));
    let hscale = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |s, (i, j)| s.max(hess[(i, j)].abs()));
    for j in 0..n {
        let (mut qp, mut qm) = (q.clone(), q.clone());
        qp[j] += h;
        qm[j] -= h;
        let (mut cp, mut cm) = (vec![0.0; m], vec![0.0; m]);
        sys.constraint_residual(&qp, &mut cp);
        sys.constraint_residual(&qm, &mut cm);
        for i in 0..m {
            worst_j = worst_j.max(((cp[i] - cm[i]) / (2.0 * h) - cq[(i, j)]).abs() / jscale);
        }
        let (mut jp, mut jm) = (Mat::zeros(m, n), Mat::zeros(m, n));
        sys.constraint_jacobian(&qp, &mut jp);
        sys.constraint_jacobian(&qm, &mut jm);
        for i in 0..n {
            let fd: f64 = (0..m)
                .map(|r| lambda[r] * (jp[(r, i)] - jm[(r, i)]))
                .sum::<f64>()
                / (2.0 * h);
            worst_h = worst_h.max((fd - hess[(i, j)]).abs() / hscale);
        }
    }
    assert!(worst_j <= 1e-6, "C_q vs FD of C: {worst_j:e}");
    assert!(worst_h <= 1e-6, "∂(C_qᵀλ)/∂q vs FD of C_qᵀλ: {worst_h:e}");
}

/// The energy form ½φᵀKφ that the modal analysis uses for its Rayleigh
/// quotients (strain variations at the quadrature points, Hessians of the
/// springs, loads and joint forces) equals the product with the assembled
/// tangent at a stretched, bent, loaded state with joint forces; evaluating
/// several shapes at once gives each shape's value bit for bit.
#[test]
fn stiffness_energy_form_equals_half_phi_k_phi() {
    let sys = kitchen_sink();
    let n = sys.ndof();
    let q = perturbed_state(&sys, 11);
    let mut rng = Rng(5);
    let lambda: Vec<f64> = (0..sys.constraint_count()).map(|_| rng.uniform()).collect();
    let at = Linearization {
        q: &q,
        lambda: Some(&lambda),
        time: 0.0,
        load_scale: 1.0,
    };
    let mut k = Mat::zeros(n, n);
    sys.tangent_stiffness(&at, &mut k);
    let shapes: Vec<Vec<f64>> = (0..5)
        .map(|_| (0..n).map(|_| rng.uniform()).collect())
        .collect();
    let phis: Vec<&[f64]> = shapes.iter().map(|s| s.as_slice()).collect();
    let mut batch = vec![Default::default(); phis.len()];
    sys.stiffness_quadratic_forms(&at, &phis, &mut batch);
    for (phi, together) in phis.iter().zip(&batch) {
        let alone = sys.stiffness_quadratic_form(&at, phi);
        assert_eq!(alone, *together, "one shape alone vs in a batch of 5");
        let (mut product, mut magnitude) = (0.0, 0.0);
        for i in 0..n {
            for j in 0..n {
                product += phi[i] * k[(i, j)] * phi[j];
                magnitude += (phi[i] * k[(i, j)] * phi[j]).abs();
            }
        }
        let form = 2.0 * alone.total();
        let err = (form - product).abs() / magnitude;
        assert!(
            err <= 1e-14,
            "2·U(φ) = {form:e} vs φᵀKφ = {product:e}: error {err:e} of Σ|φᵢKᵢⱼφⱼ| (limit 1e-14; measured ≤ 1.6e-16)"
        );
        assert!(
            alone.springs != 0.0 && alone.other != 0.0,
            "springs and joint terms present"
        );
    }
}
