//! The element-by-element inertial force used by the time integrator
//! (`System::inertial_and_internal_force`) against the assembled mass
//! matrix and against Newton's second law for a uniform acceleration.

use ancf_modal::{Model, System};

#[test]
fn element_inertial_force_equals_the_assembled_mass_matrix_product() {
    let sys = System::new(&Model::builtin());
    let n = sys.ndof();
    let a: Vec<f64> = (0..n).map(|i| ((i * 7 + 3) as f64).sin() * 1e3).collect();
    let q = &sys.q0;
    let mut combined = vec![0.0; n];
    sys.inertial_and_internal_force(q, &a, &mut combined);
    let mut internal = vec![0.0; n];
    sys.internal_force(q, &mut internal);
    let m = sys.mass_matrix();
    let scale = (0..n)
        .map(|i| (0..n).map(|j| (m[(i, j)] * a[j]).abs()).sum::<f64>())
        .fold(0.0, f64::max);
    for i in 0..n {
        let ma: f64 = (0..n).map(|j| m[(i, j)] * a[j]).sum();
        let err = (combined[i] - internal[i] - ma).abs() / scale;
        assert!(
            err < 1e-15,
            "(M a)[{i}] element-wise vs assembled: relative error {err:e} (tolerance 1e-15)"
        );
    }
}

#[test]
fn a_uniform_acceleration_needs_the_total_mass_times_it() {
    let sys = System::new(&Model::builtin());
    let n = sys.ndof();
    let acc = [3.0, -7.0];
    // Every material point accelerates by `acc`: positions do, slopes and
    // body angles do not.
    let mut a = vec![0.0; n];
    let mut positions = Vec::new();
    for b in &sys.beams {
        positions.extend((0..b.node_count()).map(|k| b.dof0 + 4 * k));
    }
    positions.extend(sys.rigid_bodies.iter().map(|r| r.dof0));
    positions.extend(sys.point_masses.iter().map(|p| p.dof0));
    for &i in &positions {
        a[i] = acc[0];
        a[i + 1] = acc[1];
    }
    let mut f = vec![0.0; n];
    sys.inertial_and_internal_force(&sys.q0, &a, &mut f);
    // At the unstressed reference Q_int = 0; the position components of
    // M a sum to m·a because the position shape functions sum to one.
    for axis in 0..2 {
        let total: f64 = positions.iter().map(|&i| f[i + axis]).sum();
        let expected = sys.total_mass() * acc[axis];
        let err = (total - expected).abs() / expected.abs();
        assert!(
            err < 1e-15,
            "Σ force along axis {axis}: {total} N vs m a = {expected} N (relative {err:e}, tolerance 1e-15)"
        );
    }
}
