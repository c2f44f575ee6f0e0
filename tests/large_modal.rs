//! The shift-invert Lanczos path of the modal analysis against the dense
//! path (same model, all 12 lowest modes) and against Euler–Bernoulli theory
//! on beams large enough that the discretization error is round-off.

mod common;

use ancf_modal::analysis::{modal_at_reference, EigenMethod, ModalResult, ModalSettings, ModeKind};
use ancf_modal::{Model, System};
use common::*;
use faer::Mat;

fn run(model: &Model, method: EigenMethod) -> (System, ModalResult) {
    let system = System::new(model);
    let settings = ModalSettings {
        modes: Some(12),
        method,
        ..ModalSettings::default()
    };
    let r = modal_at_reference(&system, &settings).expect("modal analysis succeeds");
    (system, r)
}

/// M-orthonormality and the residual of every mode, projected on the null
/// space (Nᵀ(Kφ − λMφ) = 0: the constraint forces are removed).
fn check_shapes(system: &System, r: &ModalResult, what: &str) {
    let n = system.ndof();
    let m = system.mass_matrix();
    let mut k = Mat::zeros(n, n);
    system.tangent_stiffness(&system.reference(), &mut k);
    let mut cq = Mat::zeros(system.constraint_count(), n);
    system.constraint_jacobian(&system.q0, &mut cq);
    let ns = ancf_modal::analysis::reduce::NullSpace::new(&cq);
    let mul = |a: &Mat<f64>, x: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| (0..n).map(|j| a[(i, j)] * x[j]).sum())
            .collect()
    };
    let mphi: Vec<Vec<f64>> = r.modes.iter().map(|md| mul(&m, &md.shape)).collect();
    for (a, ma) in r.modes.iter().zip(&mphi) {
        for b in &r.modes {
            let g: f64 = b.shape.iter().zip(ma).map(|(x, y)| x * y).sum();
            let expect = if a.index == b.index { 1.0 } else { 0.0 };
            assert!(
                (g - expect).abs() <= 1e-9,
                "{what}: φ{}ᵀMφ{} = {g:e}, expected {expect} (tolerance 1e-9)",
                a.index,
                b.index
            );
        }
        // Residual in the reduced coordinates: Nᵀ(Kφ − λMφ).
        let kphi = mul(&k, &a.shape);
        let full: Vec<f64> = kphi
            .iter()
            .zip(ma)
            .map(|(x, y)| x - a.eigenvalue * y)
            .collect();
        let red = ns.restrict(&full);
        let res = red.iter().map(|x| x * x).sum::<f64>().sqrt();
        // Normwise backward-error scale ‖|K||φ| + |λ||M||φ|‖: what rounding
        // in forming Kφ leaves (‖Kφ‖ itself is ε·λ_max‖Mφ‖-noisy for low modes).
        let abs = |a: &Mat<f64>, x: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| (0..n).map(|j| (a[(i, j)] * x[j]).abs()).sum())
                .collect()
        };
        let (ka, mabs) = (abs(&k, &a.shape), abs(&m, &a.shape));
        let scale = ka
            .iter()
            .zip(&mabs)
            .map(|(x, y)| (x + a.eigenvalue.abs() * y).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(
            res <= 1e-8 * scale,
            "{what}: mode {} ({}) relative residual ‖Kφ − λMφ‖ = {:e} > 1e-8",
            a.index,
            a.kind,
            res / scale
        );
    }
}

fn compare(model: &Model, what: &str) {
    let (system, dense) = run(model, EigenMethod::Dense);
    let (_, lanczos) = run(model, EigenMethod::Lanczos);
    println!(
        "{what}: reduced size {}, rigid modes dense {} / Lanczos {}",
        dense.reduced_dofs, dense.rigid_modes, lanczos.rigid_modes
    );
    assert_eq!(
        dense.rigid_modes, lanczos.rigid_modes,
        "{what}: rigid-mode count, dense vs Lanczos"
    );
    assert_eq!(dense.modes.len(), 12, "{what}: 12 dense modes");
    assert_eq!(lanczos.modes.len(), 12, "{what}: 12 Lanczos modes");
    for (d, l) in dense.modes.iter().zip(&lanczos.modes) {
        assert_eq!(d.kind, l.kind, "{what}: kind of mode {}", d.index);
        if d.kind == ModeKind::Rigid {
            continue;
        }
        let e = rel(l.frequency_hz, d.frequency_hz).abs();
        println!(
            "  mode {:2} {:8} dense {:.10e} Hz, Lanczos rel. diff {e:.2e}",
            d.index, d.kind, d.frequency_hz
        );
        assert!(
            e <= 1e-10,
            "{what}: mode {} frequency Lanczos {} vs dense {} Hz: relative {e:e} > 1e-10",
            d.index,
            l.frequency_hz,
            d.frequency_hz
        );
    }
    check_shapes(&system, &lanczos, what);
}

#[test]
fn lanczos_matches_dense_on_a_free_128_element_beam() {
    compare(&free_beam(128), "free 128-element beam");
}

#[test]
fn lanczos_matches_dense_on_the_builtin_assembly() {
    compare(&Model::builtin(), "built-in assembly");
}

fn bending_vs_euler_bernoulli(r: &ModalResult, bl: &[f64], what: &str) {
    let f = freqs(r, ModeKind::Bending);
    for (i, &b) in bl.iter().take(3).enumerate() {
        let exact = euler_bernoulli_hz(b, L, H);
        let e = rel(f[i], exact).abs();
        println!(
            "{what}: bending {} {:.10e} Hz vs EB {exact:.10e}: {e:.2e}",
            i + 1,
            f[i]
        );
        assert!(
            e <= 1e-6,
            "{what}: bending mode {} {} Hz vs Euler–Bernoulli {exact} Hz: relative {e:e} > 1e-6",
            i + 1,
            f[i]
        );
    }
}

#[test]
fn free_500_element_beam_via_lanczos_matches_euler_bernoulli() {
    let (_, r) = run(&free_beam(500), EigenMethod::Lanczos);
    assert_eq!(r.rigid_modes, 3, "free planar beam: 3 rigid modes");
    bending_vs_euler_bernoulli(&r, &FREE_FREE_BL, "free 500-element beam");
}

#[test]
fn cantilever_300_elements_via_lanczos_matches_euler_bernoulli() {
    let (_, r) = run(&cantilever(300), EigenMethod::Lanczos);
    assert_eq!(r.rigid_modes, 0, "welded cantilever: no rigid modes");
    bending_vs_euler_bernoulli(&r, &CANTILEVER_BL, "300-element cantilever");
}
