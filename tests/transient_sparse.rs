//! The integrator's sparse path (faer's sparse LU of the iteration matrix)
//! on a model large enough to take it: a cantilever of 200 elements
//! (807 unknowns) in free vibration from Euler–Bernoulli's first mode
//! shape. It must give the dense path's states, and the frequency of
//! Euler–Bernoulli's first cantilever mode with the energy kept.

mod common;
use ancf_modal::analysis::dispersion::GenAlpha;
use ancf_modal::analysis::transient::{
    Integrator, LinearSolver, State, TransientSettings, SPARSE_THRESHOLD,
};
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use common::*;
use std::f64::consts::PI;

/// Elements of the large cantilever.
const ELEMENTS: usize = 200;
/// Tip amplitude of the initial mode shape [SI: m] for the comparison of
/// the paths (0.4 % of the length). The paths differ by round-off of the
/// coordinates (~1e-15 m at positions of ~1e-2 m over 300 steps), so the
/// amplitude sets how small their relative difference can be.
const COMPARED_AMPLITUDE: f64 = 1e-4;
/// Tip amplitude [SI: m] for the frequency check: linear vibration (the
/// geometric stiffening is of order (A/L)² ~ 1e-7).
const AMPLITUDE: f64 = 1e-5;
/// Newton tolerance of both tests: the default 1e-10 (relative to the
/// assembly's size) leaves errors that show at these amplitudes (measured:
/// energy drift 4e-3 over 500 steps at A = 1e-7 m, 1e-11 at 1e-12).
const NEWTON_TOLERANCE: f64 = 1e-12;
/// Largest difference between the dense and the sparse path's
/// displacements from q₀, relative to the largest displacement (slopes in
/// metres: times the element length). Velocities, accelerations and
/// multipliers get this times the scheme's amplification (see the test).
const PATHS_AGREE: f64 = 1e-10;
/// Tip vibration frequency (corrected for the scheme) against
/// Euler–Bernoulli's first cantilever frequency, relative (measured 9e-10:
/// 200 Hermite elements and the scheme's exact dispersion correction leave
/// the zero-crossing estimate over five periods).
const FREQUENCY_TOLERANCE: f64 = 1e-8;
/// Drift of the total (kinetic + strain) energy at ρ∞ = 1 over five
/// periods, relative (measured 8e-9).
const ENERGY_TOLERANCE: f64 = 1e-7;

/// `models/cantilever.json` (weld clamp at s = 0, beam along x) with more
/// elements and without its tip load: free vibration.
fn cantilever_model(elements: usize) -> ValidModel {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/models/cantilever.json");
    let mut model = Model::from_file(std::path::Path::new(path))
        .unwrap()
        .into_model();
    model.beams[0].elements = elements;
    model.loads.clear();
    model.validated().unwrap()
}

/// The beam bent into Euler–Bernoulli's first cantilever mode without
/// stretching it: the slope angle θ(x) = c φ′(x), with
/// φ(x) = cosh βx − cos βx − σ(sinh βx − sin βx),
/// σ = (cosh βL + cos βL)/(sinh βL + sin βL), and c such that the tip
/// deflects by about `amplitude`; r′ = (cos θ, sin θ), r = ∫ r′ (Simpson,
/// 32 panels per element). Smooth, so that its consistent initial
/// acceleration is too (a point load's is dominated by the mesh's highest
/// modes), and unstretched (displacing only ry by c φ would stretch the
/// beam by ½(cφ′)² and start an axial vibration).
fn first_mode_shape(sys: &System, amplitude: f64) -> Vec<f64> {
    let beam = &sys.beams[0];
    let b = CANTILEVER_BL[0] / L;
    let bl = CANTILEVER_BL[0];
    let sigma = (bl.cosh() + bl.cos()) / (bl.sinh() + bl.sin());
    let phi = |x: f64| (b * x).cosh() - (b * x).cos() - sigma * ((b * x).sinh() - (b * x).sin());
    let dphi =
        |x: f64| b * ((b * x).sinh() + (b * x).sin() - sigma * ((b * x).cosh() - (b * x).cos()));
    let c = amplitude / phi(L);
    let slope = |x: f64| [(c * dphi(x)).cos(), (c * dphi(x)).sin()];
    let mut q = sys.q0.clone();
    // From the clamped node 0 where the system has it (about the centre).
    let mut r = [beam.start.x, beam.start.y];
    for (k, &x) in beam.node_s.iter().enumerate() {
        if k > 0 {
            let (x0, panels) = (beam.node_s[k - 1], 32);
            let dx = (x - x0) / panels as f64;
            for p in 0..panels {
                let (a, m, e) = (
                    x0 + p as f64 * dx,
                    x0 + (p as f64 + 0.5) * dx,
                    x0 + (p + 1) as f64 * dx,
                );
                let (sa, sm, se) = (slope(a), slope(m), slope(e));
                for (axis, r) in r.iter_mut().enumerate() {
                    *r += dx / 6.0 * (sa[axis] + 4.0 * sm[axis] + se[axis]);
                }
            }
        }
        let d = beam.dof0 + 4 * k;
        let s = slope(x);
        q[d..d + 4].copy_from_slice(&[r[0], r[1], s[0], s[1]]);
    }
    q
}

/// The tip node's ry coordinate.
fn tip_y(sys: &System) -> usize {
    let beam = &sys.beams[0];
    beam.dof0 + 4 * (beam.node_count() - 1) + 1
}

fn run(
    sys: &System,
    settings: TransientSettings,
    amplitude: f64,
    observe: impl FnMut(&State),
) -> (State, bool) {
    let mut integ = Integrator::new(sys, settings).unwrap();
    let mut st = integ
        .state_at(first_mode_shape(sys, amplitude), vec![0.0; sys.ndof()])
        .unwrap();
    integ.run(&mut st, observe).unwrap();
    (st, integ.is_sparse())
}

/// max |a − b| / max |b| over the coordinates (or their rates) in metres:
/// slopes times the element length, the displacement they cause (as in the
/// integrator's Newton norm), so that a slope and a position weigh alike.
fn relative_difference(sys: &System, a: &[f64], b: &[f64]) -> f64 {
    let le = L / ELEMENTS as f64;
    let metres = |i: usize, x: f64| {
        if (i - sys.beams[0].dof0) % 4 >= 2 {
            le * x
        } else {
            x
        }
    };
    let scale = b
        .iter()
        .enumerate()
        .fold(0.0f64, |m, (i, x)| m.max(metres(i, *x).abs()));
    let diff = a
        .iter()
        .zip(b)
        .enumerate()
        .fold(0.0f64, |m, (i, (x, y))| m.max(metres(i, x - y).abs()));
    diff / scale
}

#[test]
fn auto_takes_the_sparse_path_above_the_threshold_only() {
    let large = System::new(&cantilever_model(ELEMENTS));
    let small = System::new(&Model::builtin());
    let unknowns = |s: &System| s.ndof() + s.constraint_count();
    assert!(unknowns(&large) > SPARSE_THRESHOLD);
    assert!(unknowns(&small) <= SPARSE_THRESHOLD);
    let settings = TransientSettings::default();
    assert!(
        Integrator::new(&large, settings).unwrap().is_sparse(),
        "{} unknowns: sparse",
        unknowns(&large)
    );
    assert!(
        !Integrator::new(&small, settings).unwrap().is_sparse(),
        "the built-in assembly ({} unknowns): dense",
        unknowns(&small)
    );
}

#[test]
fn dense_and_sparse_paths_give_the_same_states() {
    let sys = System::new(&cantilever_model(ELEMENTS));
    // 300 steps of 1 µs at the default ρ∞: about a third of the first period.
    let h = 1e-6;
    let settings = |solver| TransientSettings {
        step: h,
        end_time: 300.0 * h,
        tolerance: NEWTON_TOLERANCE,
        solver,
        ..TransientSettings::default()
    };
    let a = COMPARED_AMPLITUDE;
    let (dense, dense_path) = run(&sys, settings(LinearSolver::Dense), a, |_| {});
    let (sparse, sparse_path) = run(&sys, settings(LinearSolver::Sparse), a, |_| {});
    assert!(
        !dense_path && sparse_path,
        "each run took the path it was given"
    );
    assert_eq!(dense.t, sparse.t);
    let tip = tip_y(&sys);
    let moved = (dense.q[tip] - first_mode_shape(&sys, a)[tip]).abs();
    assert!(
        moved > 0.1 * a,
        "the tip has moved by {moved:e} m (at least a tenth of the amplitude)"
    );
    // The two paths differ by round-off in the coordinates. The scheme
    // makes velocities, accelerations and multipliers from the coordinates
    // with the factors γ′ = γ/(βh) and β′ ≈ 1/(βh²), so their differences,
    // relative to ωA and ω²A, are larger by γ′/ω and β′/ω² (~300 and ~8e4).
    let coef =
        GenAlpha::from_spectral_radius(TransientSettings::default().spectral_radius).unwrap();
    let omega = 2.0 * PI * euler_bernoulli_hz(CANTILEVER_BL[0], L, H);
    let gamma_p = coef.gamma / (coef.beta * h);
    let beta_p = (1.0 - coef.alpha_m) / ((1.0 - coef.alpha_f) * coef.beta * h * h);
    let displacement =
        |s: &State| -> Vec<f64> { s.q.iter().zip(&sys.q0).map(|(q, q0)| q - q0).collect() };
    let lambda_difference = sparse
        .lambda
        .iter()
        .zip(&dense.lambda)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
        / dense.lambda.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for (name, d, limit) in [
        (
            "displacement",
            relative_difference(&sys, &displacement(&sparse), &displacement(&dense)),
            PATHS_AGREE,
        ),
        (
            "velocity",
            relative_difference(&sys, &sparse.v, &dense.v),
            PATHS_AGREE * gamma_p / omega,
        ),
        (
            "acceleration",
            relative_difference(&sys, &sparse.a, &dense.a),
            PATHS_AGREE * beta_p / (omega * omega),
        ),
        (
            "multipliers",
            lambda_difference,
            PATHS_AGREE * beta_p / (omega * omega),
        ),
    ] {
        eprintln!("sparse against dense after 300 steps, {name}: {d:e} (limit {limit:e})");
        assert!(
            d <= limit,
            "{name}: sparse and dense paths differ by {d:e} (relative; limit {limit:e})"
        );
    }
}

#[test]
fn sparse_path_cantilever_vibrates_at_the_euler_bernoulli_frequency() {
    let sys = System::new(&cantilever_model(ELEMENTS));
    let exact = euler_bernoulli_hz(CANTILEVER_BL[0], L, H);
    // Five periods at ρ∞ = 1 (no numerical damping, energy kept).
    let h = 2e-6;
    let settings = TransientSettings {
        step: h,
        end_time: 5.0 / exact,
        spectral_radius: 1.0,
        tolerance: NEWTON_TOLERANCE,
        solver: LinearSolver::Sparse,
        ..TransientSettings::default()
    };
    let tip = tip_y(&sys);
    let mut samples: Vec<(f64, f64)> = Vec::new();
    let mut energy: Vec<f64> = Vec::new();
    let (_, sparse_path) = run(&sys, settings, AMPLITUDE, |s| {
        samples.push((s.t, s.q[tip] - sys.q0[tip]));
        energy.push(0.5 * sys.mass().quadratic_form(&s.v) + sys.strain_energy(&s.q).total());
    });
    assert!(sparse_path);
    // Zero crossings (linear interpolation; y = A cos ωt has no curvature
    // there): half periods.
    let crossings: Vec<f64> = samples
        .windows(2)
        .filter(|w| w[0].1 * w[1].1 < 0.0)
        .map(|w| w[0].0 - w[0].1 * (w[1].0 - w[0].0) / (w[1].1 - w[0].1))
        .collect();
    assert!(crossings.len() >= 9, "{} zero crossings", crossings.len());
    let half_period =
        (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let observed = PI / half_period;
    let corrected = GenAlpha::from_spectral_radius(1.0)
        .unwrap()
        .true_frequency_from_observed(observed, h)
        .unwrap()
        / (2.0 * PI);
    let error = (corrected - exact) / exact;
    let e0 = energy[0];
    let drift = energy
        .iter()
        .fold(0.0f64, |m, e| m.max(((e - e0) / e0).abs()));
    eprintln!(
        "sparse path, {ELEMENTS} elements: tip vibrates at {corrected} Hz (raw {} Hz), Euler–Bernoulli {exact} Hz: {error:e}; energy drift {drift:e}",
        observed / (2.0 * PI)
    );
    assert!(
        error.abs() <= FREQUENCY_TOLERANCE,
        "tip vibration {corrected} Hz vs Euler–Bernoulli {exact} Hz: {error:e} (limit {FREQUENCY_TOLERANCE:e})"
    );
    assert!(
        drift <= ENERGY_TOLERANCE,
        "energy drift {drift:e} over five periods (limit {ENERGY_TOLERANCE:e})"
    );
}
