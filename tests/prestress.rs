//! Modal analysis at the static equilibrium (pre-stress): axial load on a
//! pinned beam, Euler buckling, the constraint-force term ∂(C_qᵀλ)/∂q, and
//! the symmetry and exactness of the pre-stressed tangent.

mod common;
use ancf_modal::analysis::prestress::{modal_at_equilibrium, prestressed_modal};
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::analysis::{modal, ModalSettings, ModeKind};
use ancf_modal::error::AnalysisError;
use ancf_modal::model::ValidModel;
use ancf_modal::system::Linearization;
use ancf_modal::{Model, System};
use common::*;
use serde_json::json;
use std::f64::consts::PI;

/// Beam on the x axis, pinned to the ground at s = 0, its end s = L on a
/// roller (slider along x) that carries the axial load `p` [N] (tension
/// positive).
fn pinned_roller(elements: usize, h: f64, p: f64) -> ValidModel {
    model(json!({
        "name": "pinned_roller",
        "beams": [{
            "id": "b", "start": [0.0, 0.0], "angle_deg": 0.0, "length": L,
            "elements": elements, "nodes_at_attachments": false,
            "section": {"height": h, "width": W},
            "material": {"young": E, "density": RHO}
        }],
        "joints": [
            {"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "b", "s": 0.0}},
            {"type": "slider", "a": {"ground": [L, 0.0]}, "b": {"beam": "b", "s": L}, "axis": [1.0, 0.0]}
        ],
        "loads": [{"at": {"beam": "b", "s": L}, "force": [p, 0.0]}]
    }))
}

fn section(h: f64) -> (f64, f64) {
    (E * W * h.powi(3) / 12.0, RHO * W * h)
}

/// Euler's load π²EI/L² [N].
fn euler_load(h: f64) -> f64 {
    PI * PI * section(h).0 / (L * L)
}

/// Eigenvalues ω² of the transverse (bending) modes at the equilibrium under
/// the model's load × s, ascending. Modes are picked by shape (transverse
/// node displacements dominate), independently of the energy label that
/// `labels_follow_the_shape_under_tension` checks.
fn bending_eigenvalues(m: &ValidModel, s: f64, check: bool) -> Vec<f64> {
    let sys = System::new(m);
    let settings = StaticSettings {
        load_scale: s,
        check_stability: check,
        ..StaticSettings::default()
    };
    let eq = solve_equilibrium(&sys, &settings).expect("equilibrium");
    let r = modal_at_equilibrium(&sys, &eq, &ModalSettings::default()).expect("modal");
    r.modes
        .iter()
        .filter(|m| !m.kind.is_zero())
        .filter(|m| is_transverse(&sys, &m.shape))
        .map(|m| m.eigenvalue)
        .collect()
}

/// Transverse displacement dominates the mode shape.
fn is_transverse(sys: &System, shape: &[f64]) -> bool {
    let beam = &sys.beams[0];
    let (mut ux, mut uy) = (0.0, 0.0);
    for k in 0..beam.node_count() {
        ux += shape[beam.dof0 + 4 * k].powi(2);
        uy += shape[beam.dof0 + 4 * k + 1].powi(2);
    }
    uy > ux
}

#[test]
fn labels_follow_the_shape_under_tension() {
    // At 10 P_cr most of a transverse mode's stiffness is the tension's
    // (string-like); it must still be labelled bending, and the stretching
    // modes axial.
    let h = 2e-3 * L;
    let m = pinned_roller(16, h, 10.0 * euler_load(h));
    let sys = System::new(&m);
    let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
    let r = modal_at_equilibrium(&sys, &eq, &ModalSettings::default()).expect("modal");
    for mode in r.modes.iter().filter(|m| !m.kind.is_zero()).take(12) {
        let expected = if is_transverse(&sys, &mode.shape) {
            ModeKind::Bending
        } else {
            ModeKind::Axial
        };
        assert_eq!(
            mode.kind, expected,
            "mode {} at {:.1} Hz: label vs shape",
            mode.index, mode.frequency_hz
        );
    }
}

#[test]
fn pinned_beam_under_tension_matches_string_beam_formula() {
    // ω_k² = (kπ/L)⁴ EI/ρA + (kπ/L)² P/ρA (inextensible Euler–Bernoulli beam
    // under axial tension P), k = 1..3, P from 0 to 10 P_cr; compared as
    // frequencies ω_k. (ω² doubles the relative error: 16 Hermite elements
    // put mode 3, 5.3 elements per half-wave, 8e-5 high in frequency at P = 0.)
    let h = 2e-3 * L;
    let (ei, rho_a) = section(h);
    let pcr = euler_load(h);
    let mut worst: f64 = 0.0;
    for ratio in [0.0, 0.5, 1.0, 2.0, 5.0, 10.0] {
        let p = ratio * pcr;
        let w2 = bending_eigenvalues(&pinned_roller(16, h, p), 1.0, true);
        for k in 1..=3 {
            let kl = k as f64 * PI / L;
            let exact = kl.powi(4) * ei / rho_a + kl * kl * p / rho_a;
            let e = (w2[k - 1] / exact).sqrt() - 1.0;
            worst = worst.max(e.abs());
            assert!(
                e.abs() <= 1e-4,
                "P = {ratio} P_cr, mode {k}: ω_k relative error {e:e} (limit 1e-4)"
            );
        }
    }
    eprintln!("worst relative ω error over P = 0…10 P_cr, k = 1…3: {worst:e}");
}

#[test]
fn stubby_beam_deviation_is_the_cable_stretch() {
    // The paper's blade (h/L = 0.044) at 10 P_cr stretches by ε = P/EA =
    // 1.6 %, which the inextensible formula ignores. The cable's own
    // linearization about the stretched straight state is, per unit reference
    // length, EI w''²/(1+ε)² (κ = r'×r''/|r'|²) and N/(1+ε) w'² (geometric
    // part of EA ε), with ρA ẇ²: ω² = [(kπ/L)⁴ EI/(1+ε)² + (kπ/L)² P/(1+ε)]/ρA.
    let h = H;
    let (ei, rho_a) = section(h);
    let ea = E * W * h;
    let p = 10.0 * euler_load(h);
    let eps = p / ea;
    let w2 = bending_eigenvalues(&pinned_roller(16, h, p), 1.0, true);
    for k in 1..=3 {
        let kl = k as f64 * PI / L;
        let rigid = (kl.powi(4) * ei + kl * kl * p) / rho_a;
        let stretched = (kl.powi(4) * ei / (1.0 + eps).powi(2) + kl * kl * p / (1.0 + eps)) / rho_a;
        let e_inext = (w2[k - 1] / rigid).sqrt() - 1.0;
        let e_str = (w2[k - 1] / stretched).sqrt() - 1.0;
        eprintln!("h/L = {:.3}, P = 10 P_cr, ε = {eps:.4e}, mode {k}: vs inextensible {e_inext:e}, vs stretched cable {e_str:e}", h / L);
        assert!(
            e_inext < -3e-3,
            "mode {k}: the stretch lowers ω below the inextensible value ({e_inext:e})"
        );
        assert!(
            e_str.abs() <= 1e-4,
            "mode {k}: ω vs the stretched-cable formula: {e_str:e} (limit 1e-4)"
        );
    }
}

#[test]
fn first_frequency_vanishes_at_euler_load() {
    let h = 2e-3 * L;
    let pcr = euler_load(h);
    let m = pinned_roller(16, h, -pcr);
    // ω₁² on both sides of the critical load (the straight state is an
    // equilibrium on both; past P_cr it is unstable), interpolated to zero.
    let (s0, s1) = (0.95, 1.05);
    let (w0, w1) = (
        bending_eigenvalues(&m, s0, false)[0],
        bending_eigenvalues(&m, s1, false)[0],
    );
    assert!(
        w0 > 0.0 && w1 < 0.0,
        "ω₁² changes sign across P_cr: {w0:e}, {w1:e}"
    );
    let crossing = s0 - w0 * (s1 - s0) / (w1 - w0);
    assert!(
        (crossing - 1.0).abs() <= 1e-3,
        "f₁ reaches zero at {crossing:.6} P_cr (Euler: 1, limit 1e-3)"
    );
    // The static solver refuses the load past it and names the critical factor.
    let sys = System::new(&m);
    match solve_equilibrium(
        &sys,
        &StaticSettings {
            load_scale: 1.05,
            ..Default::default()
        },
    ) {
        Err(AnalysisError::Unstable {
            load_factor, dof, ..
        }) => {
            eprintln!("critical load factor reported: {load_factor:.8}; interpolated crossing {crossing:.8}");
            assert!(
                (load_factor - 1.0).abs() <= 1e-3,
                "reported critical load factor {load_factor:.6} (Euler: 1, limit 1e-3)"
            );
            assert!(
                dof.contains("beam `b`"),
                "the buckling motion is the beam's: {dof}"
            );
        }
        other => panic!("expected a loss of stability at 1.05 P_cr, got {other:?}"),
    }
    // Below it, the solver returns the equilibrium.
    assert!(solve_equilibrium(
        &sys,
        &StaticSettings {
            load_scale: 0.95,
            ..Default::default()
        }
    )
    .is_ok());
}

/// A rigid body (mass m, inertia J_c about its centre) hanging under gravity
/// from a pin d above its centre, with an optional torsion spring k_t.
fn pendulum(torsion: Option<f64>) -> (ValidModel, f64, f64, f64, f64) {
    let (m, jc, d, g) = (2.0e-3, 3.0e-8, 4.0e-3, 9.81);
    let mut pin = json!({"type": "pin", "a": {"ground": [0.0, 0.0]}, "b": {"body": "bob"}});
    if let Some(k) = torsion {
        pin["torsion_stiffness"] = json!(k);
    }
    let model = model(json!({
        "name": "pendulum",
        "gravity": [0.0, -g],
        "rigid_bodies": [{"id": "bob", "mass": m, "inertia": jc, "position": [0.0, -d]}],
        "joints": [pin]
    }));
    (model, m, jc, d, g)
}

#[test]
fn constraint_term_gives_the_pendulum_its_stiffness() {
    for torsion in [None, Some(2.0e-4)] {
        let (model, m, jc, d, g) = pendulum(torsion);
        let kt = torsion.unwrap_or(0.0);
        let j_pin = jc + m * d * d;
        let exact = (kt + m * g * d) / j_pin;
        let sys = System::new(&model);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
        // The pin carries the weight: the joint force on the bob, −λ, is m g upwards.
        assert!(
            (eq.lambda[1] + m * g).abs() <= 1e-12 * m * g,
            "pin multiplier {} vs weight {}",
            eq.lambda[1],
            m * g
        );
        let with = modal(&sys, &eq.linearization(), &ModalSettings::default()).unwrap();
        let without = modal(
            &sys,
            &Linearization {
                lambda: None,
                ..eq.linearization()
            },
            &ModalSettings::default(),
        )
        .unwrap();
        let w_with = with.modes[0].eigenvalue;
        let w_without = if without.modes[0].kind == ModeKind::Rigid {
            0.0
        } else {
            without.modes[0].eigenvalue
        };
        let e = (w_with - exact) / exact;
        assert!(
            e.abs() <= 1e-9,
            "k_t = {kt}: ω² = {w_with} vs (k_t + m g d)/J_pin = {exact}: relative error {e:e}"
        );
        let e_without = (w_without - exact) / exact;
        assert!(
            e_without.abs() >= 0.1,
            "k_t = {kt}: without ∂(C_qᵀλ)/∂q, ω² = {w_without} should miss (k_t + m g d)/J_pin = {exact} measurably"
        );
        // Without the term it is the spring alone: k_t/J_pin (or a zero mode).
        let spring_only = kt / j_pin;
        assert!(
            (w_without - spring_only).abs() <= 1e-9 * exact,
            "without the term: {w_without} vs k_t/J_pin = {spring_only}"
        );
    }
}

/// The pre-stressed paper assembly at its equilibrium.
fn paper_prestressed() -> (ValidModel, System) {
    let m = Model::from_file(std::path::Path::new("models/rcbo_prestressed.json"))
        .expect("models/rcbo_prestressed.json is valid");
    let sys = System::new(&m);
    (m, sys)
}

/// g(q) = Q_int − Q_ext + C_qᵀλ at fixed λ.
fn generalized_residual(sys: &System, q: &[f64], lambda: &[f64]) -> Vec<f64> {
    let n = sys.ndof();
    let (mut fi, mut fe) = (vec![0.0; n], vec![0.0; n]);
    sys.internal_force(q, &mut fi);
    sys.external_force(q, 0.0, 1.0, &mut fe);
    let mut cq = faer::Mat::zeros(sys.constraint_count(), n);
    sys.constraint_jacobian(q, &mut cq);
    (0..n)
        .map(|j| {
            fi[j] - fe[j]
                + (0..sys.constraint_count())
                    .map(|i| cq[(i, j)] * lambda[i])
                    .sum::<f64>()
        })
        .collect()
}

#[test]
fn prestressed_tangent_is_symmetric_and_the_derivative_of_the_residual() {
    let (_, sys) = paper_prestressed();
    let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
    let n = sys.ndof();
    let mut k = faer::Mat::zeros(n, n);
    sys.tangent_stiffness(&eq.linearization(), &mut k);
    let kmax = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max(k[(i, j)].abs()));
    let asym = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .fold(0.0f64, |a, (i, j)| a.max((k[(i, j)] - k[(j, i)]).abs()));
    assert!(
        asym <= 1e-12 * kmax,
        "pre-stressed tangent asymmetry {asym:e} vs max entry {kmax:e} (conservative loads: a Hessian)"
    );
    // Central differences of g at fixed λ, column by column; the steps are
    // 1e-9 m for positions and 1e-7 for slopes and angles.
    let mut worst: f64 = 0.0;
    for j in 0..n {
        let h = if sys.dof_label(j).contains("r'") || sys.dof_label(j).contains("rotation") {
            1e-7
        } else {
            1e-9
        };
        let (mut qp, mut qm) = (eq.q.clone(), eq.q.clone());
        qp[j] += h;
        qm[j] -= h;
        let (gp, gm) = (
            generalized_residual(&sys, &qp, &eq.lambda),
            generalized_residual(&sys, &qm, &eq.lambda),
        );
        let col: Vec<f64> = (0..n).map(|i| (gp[i] - gm[i]) / (2.0 * h)).collect();
        let cmax = (0..n).fold(0.0f64, |a, i| a.max(k[(i, j)].abs()));
        for (i, c) in col.iter().enumerate() {
            worst = worst.max((c - k[(i, j)]).abs() / cmax);
        }
    }
    assert!(
        worst <= 1e-5,
        "tangent vs central differences: worst column-relative error {worst:e} (limit 1e-5)"
    );
}

#[test]
fn prestressed_assembly_is_in_force_and_moment_balance() {
    // Newton's third law on the whole moving contact: the constant loads, the
    // spring's force on the blade (k (l − l₀) from its geometry) and the
    // forces of the two ground joints must cancel, and so must their moments.
    let (m, sys) = paper_prestressed();
    let eq = solve_equilibrium(&sys, &StaticSettings::default()).expect("equilibrium");
    let report = ancf_modal::output::static_report::static_report(&m, &sys, &eq);
    let anchor = |id: &str| -> nalgebra::Vector2<f64> {
        let c = sys
            .constraints
            .iter()
            .chain(std::iter::empty())
            .find(|c| c.label() == id);
        match c {
            Some(c) => c.pair().b.position(&eq.q),
            None => sys
                .force_elements
                .iter()
                .find(|f| f.label() == id)
                .unwrap()
                .pair()
                .b
                .position(&eq.q),
        }
    };
    let mut force = nalgebra::Vector2::zeros();
    let mut moment = 0.0;
    let mut add = |at: nalgebra::Vector2<f64>, f: nalgebra::Vector2<f64>| {
        force += f;
        moment += at.x * f.y - at.y * f.x;
    };
    for l in &sys.loads {
        add(l.anchor.position(&eq.q), l.force);
    }
    for j in ["fixed_pin", "fixed_contact"] {
        let r = report.reactions.iter().find(|r| r.joint == j).unwrap();
        add(anchor(j), nalgebra::Vector2::new(r.force[0], r.force[1]));
    }
    let spring = &m.springs[0];
    // The system works about the model's centre of mass (`sys.origin`).
    let ground = nalgebra::Vector2::new(spring.a.ground.unwrap()[0], spring.a.ground.unwrap()[1])
        - sys.origin;
    let blade_point = anchor("helical_spring");
    let d = ground - blade_point;
    let l0 = (ground - sys.force_elements[0].pair().b.position(&sys.q0)).norm()
        - spring.preload.unwrap() / spring.stiffness;
    let tension = spring.stiffness * (d.norm() - l0);
    add(blade_point, d / d.norm() * tension);
    let scale = 11.77;
    assert!(
        force.norm() <= 1e-8 * scale,
        "net force on the assembly {force:?} N"
    );
    assert!(
        moment.abs() <= 1e-8 * scale * 0.025,
        "net moment on the assembly {moment:e} N m"
    );
}

#[test]
fn zero_load_gives_the_reference_frequencies() {
    // Without loads, gravity or preload the equilibrium is the reference and
    // the pre-stressed modes are the unstressed ones.
    let h = 2e-3 * L;
    let sys = System::new(&pinned_roller(16, h, euler_load(h)));
    let r = prestressed_modal(
        &sys,
        &StaticSettings {
            load_scale: 0.0,
            ..Default::default()
        },
        &ModalSettings::default(),
    )
    .expect("pre-stressed modal");
    let moved = r
        .equilibrium
        .q
        .iter()
        .zip(&sys.q0)
        .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
    assert!(
        moved <= 1e-14,
        "equilibrium at zero load is the reference (to round-off): moved {moved:e}"
    );
    for (a, b) in r.reference.modes.iter().zip(&r.prestressed.modes) {
        assert!(
            (a.frequency_hz - b.frequency_hz).abs() <= 1e-9 * a.frequency_hz.max(1.0),
            "mode {}: {} vs {} Hz",
            a.index + 1,
            a.frequency_hz,
            b.frequency_hz
        );
    }
}

#[test]
fn a_pendulum_at_its_balanced_reference_is_said_to_leave_gravity_out() {
    // A 2 kg sign (I = 0.05 kg m²) hanging 0.3 m under a hinge with a
    // torsion spring of 10 N m/rad, under gravity (outside-eyes trial of
    // issue 36): the reference balances gravity, but plain `modal` leaves
    // out its pendulum stiffness m g d. About the hinge J = I + m d².
    use ancf_modal::commands::modal::{run, ModalRequest};
    use ancf_modal::commands::ModelInput;
    use ancf_modal::error::Source;
    let (m, i, d, kt, g) = (2.0, 0.05, 0.3, 10.0, 9.81);
    let sign = serde_json::json!({
        "name": "sign", "gravity": [0.0, -g],
        "rigid_bodies": [{"id": "sign", "mass": m, "inertia": i, "position": [0.0, 0.0]}],
        "joints": [{"id": "hinge", "type": "pin", "a": {"ground": [0.0, d]},
            "b": {"body": "sign", "local": [0.0, d]}, "torsion_stiffness": kt}]
    });
    let input = ModelInput::parse(&sign.to_string(), Source::BuiltIn).unwrap();
    let j = i + m * d * d;
    let hz = |k: f64| (k / j).sqrt() / (2.0 * std::f64::consts::PI);
    let plain = run(&input, &ModalRequest::default()).unwrap();
    let f = plain.outcome.result().modes[0].frequency_hz;
    assert!((f / hz(kt) - 1.0).abs() < 1e-9, "{f} against {}", hz(kt));
    let said = plain.document.warnings.iter().any(|w| {
        w.contains("gravity acts at the reference, which balances them") && w.contains("prestress")
    });
    assert!(said, "{:?}", plain.document.warnings);
    let stressed = ModalRequest {
        prestress: true,
        ..ModalRequest::default()
    };
    let pre = run(&input, &stressed).unwrap();
    let f = pre.outcome.result().modes[0].frequency_hz;
    let want = hz(kt + m * g * d);
    assert!((f / want - 1.0).abs() < 1e-9, "{f} against {want}");
    // Without gravity nothing is left out, and nothing is said.
    let mut free = sign.clone();
    free["gravity"] = serde_json::json!([0.0, 0.0]);
    let input = ModelInput::parse(&free.to_string(), Source::BuiltIn).unwrap();
    let run_free = run(&input, &ModalRequest::default()).unwrap();
    assert!(
        run_free.document.warnings.is_empty(),
        "{:?}",
        run_free.document.warnings
    );
}
