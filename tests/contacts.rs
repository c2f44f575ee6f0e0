//! Contacts: one-degree-of-freedom impacts against closed forms and an
//! independent integration, energy of a sliding pin, friction work,
//! statics onto a Hertz wall from a gap, the pre-stressed contact
//! frequency, and the consistent contact tangent against finite
//! differences.

mod common;
use ancf_modal::analysis::prestress::modal_at_equilibrium;
use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::analysis::transient::{Integrator, State, TransientSettings};
use ancf_modal::analysis::ModalSettings;
use ancf_modal::mechanics::pair::{PairGrad, PairHess};
use ancf_modal::mechanics::spring::ForceElement;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};
use common::model;
use serde_json::{json, Value};
use std::f64::consts::PI;

const MASS: f64 = 1e-3;
const K_HERTZ: f64 = 1e9;

/// A point mass (1 g) whose centre is a pin of radius 0.4 mm in a slot of
/// width 1 mm along x (ground) from x = −1 mm to x = +1 mm; clearance
/// 0.1 mm. A half-sine pulse along +x of `impulse` [N s] over `duration`
/// pushes it into the end cap at x = 1 mm.
fn pin_in_slot(law: Value, impulse: f64, duration: f64) -> ValidModel {
    let amplitude = impulse * PI / (2.0 * duration);
    model(json!({
        "name": "pin_in_slot",
        "point_masses": [{"id": "pin", "mass": MASS, "position": [0.0, 0.0]}],
        "contacts": [{
            "id": "slot", "type": "pin_slot",
            "slot": {"ground": true, "from": [-1e-3, 0.0], "to": [1e-3, 0.0], "width": 1e-3},
            "pin": {"body": "pin"}, "pin_radius": 0.4e-3, "law": law
        }],
        "loads": [{"at": {"body": "pin"}, "force": [amplitude, 0.0],
                   "time": {"half_sine": {"duration": duration}}}]
    }))
}

/// Impact record of the pin: (speed before, speed after, largest
/// penetration, contact duration by linear interpolation of δ at the
/// crossings).
struct Impact {
    v_in: f64,
    v_out: f64,
    max_penetration: f64,
    duration: f64,
}

fn run_impact(model: &ValidModel, step: f64, end: f64) -> Impact {
    let sys = System::new(model);
    let settings = TransientSettings {
        step,
        end_time: end,
        spectral_radius: 1.0,
        ..TransientSettings::default()
    };
    let mut integ = Integrator::new(&sys, settings).unwrap();
    let mut state = integ.initial_state().unwrap();
    let c = &sys.contacts[0];
    let mut prev: Option<(f64, f64, f64)> = None; // (t, δ, v)
    let (mut v_in, mut v_out, mut dmax) = (f64::NAN, f64::NAN, 0.0f64);
    let (mut t_on, mut t_off) = (f64::NAN, f64::NAN);
    integ
        .run(&mut state, |st: &State| {
            let d = c.penetration(&st.q);
            let v = st.v[0];
            if let Some((t0, d0, v0)) = prev {
                if d0 <= 0.0 && d > 0.0 && t_on.is_nan() {
                    t_on = t0 + (st.t - t0) * (-d0) / (d - d0);
                    v_in = v0;
                }
                if d0 > 0.0 && d <= 0.0 && t_off.is_nan() {
                    t_off = t0 + (st.t - t0) * d0 / (d0 - d);
                    v_out = v;
                }
            }
            dmax = dmax.max(d);
            prev = Some((st.t, d, v));
        })
        .unwrap();
    Impact {
        v_in,
        v_out,
        max_penetration: dmax,
        duration: t_off - t_on,
    }
}

#[test]
fn hertz_impact_matches_the_closed_forms() {
    // v₀ = 0.1 m/s: the pulse's impulse over the mass.
    let v0 = 0.1;
    let law = json!({"model": "hertz", "stiffness": K_HERTZ});
    // A pulse of 500 steps: the trapezoidal rule's impulse error
    // (π/500)²/12 = 3e-6.
    let m = pin_in_slot(law, MASS * v0, 1e-3);
    // The pin reaches the cap (0.1 mm + 1 mm away) after ~11 ms.
    let r = run_impact(&m, 2e-6, 14e-3);
    assert!(
        ((r.v_in - v0) / v0).abs() < 1e-5,
        "momentum before impact = the pulse's impulse: v = {} vs {v0}",
        r.v_in
    );
    let v0 = r.v_in;
    let dmax = (5.0 * MASS * v0 * v0 / (4.0 * K_HERTZ)).powf(0.4);
    assert!(
        ((r.max_penetration - dmax) / dmax).abs() < 1e-3,
        "δ_max {} vs (5mv²/4K)^(2/5) = {dmax}",
        r.max_penetration
    );
    // 2.94 is the rounded constant; the exact one is 2.9432 (Johnson,
    // Contact Mechanics, §11.4: t_c = 2.9432 δ_max/v₀).
    let tc = 2.9432 * dmax / v0;
    assert!(
        ((r.duration - tc) / tc).abs() < 1e-3,
        "contact time {} vs 2.9432 δ_max/v₀ = {tc}",
        r.duration
    );
    assert!(
        ((-r.v_out / r.v_in) - 1.0).abs() < 1e-3,
        "restitution {} vs 1",
        -r.v_out / r.v_in
    );
}

/// m δ̈ = −F(δ, δ̇), integrated from δ = 0, δ̇ = v₀ with RK4 at a tiny
/// step: the rebound speed and the largest penetration.
fn reference_impact(force: impl Fn(f64, f64) -> f64, v0: f64, dt: f64) -> (f64, f64) {
    let (mut d, mut v, mut dmax) = (0.0f64, v0, 0.0f64);
    let acc = |d: f64, v: f64| {
        if d > 0.0 {
            -force(d, v).max(0.0) / MASS
        } else {
            0.0
        }
    };
    loop {
        let (k1d, k1v) = (v, acc(d, v));
        let (k2d, k2v) = (
            v + 0.5 * dt * k1v,
            acc(d + 0.5 * dt * k1d, v + 0.5 * dt * k1v),
        );
        let (k3d, k3v) = (
            v + 0.5 * dt * k2v,
            acc(d + 0.5 * dt * k2d, v + 0.5 * dt * k2v),
        );
        let (k4d, k4v) = (v + dt * k3v, acc(d + dt * k3d, v + dt * k3v));
        d += dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d);
        v += dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        dmax = dmax.max(d);
        if d <= 0.0 || (v < 0.0 && acc(d, v) == 0.0) {
            return (v, dmax);
        }
    }
}

#[test]
fn damped_laws_match_an_independent_integration() {
    let v0 = 0.1;
    let cr: f64 = 0.6;
    let n = 1.5;
    let cases = [
        ("lankarani_nikravesh", 3.0 * (1.0 - cr * cr) / 4.0),
        ("hunt_crossley", 3.0 * (1.0 - cr) / 2.0),
        ("flores", 8.0 * (1.0 - cr) / (5.0 * cr)),
    ];
    for (name, xi) in cases {
        let law = json!({"model": name, "stiffness": K_HERTZ, "restitution": cr});
        let r = run_impact(&pin_in_slot(law, MASS * v0, 1e-4), 2e-6, 14e-3);
        let vin = r.v_in;
        let (v_ref, d_ref) = reference_impact(
            |d, dd| K_HERTZ * d.powf(n) * (1.0 + xi * dd / vin),
            vin,
            1e-9,
        );
        assert!(
            ((r.v_out - v_ref) / v_ref).abs() < 2e-3,
            "{name}: rebound {} vs independent {v_ref}",
            r.v_out
        );
        assert!(
            ((r.max_penetration - d_ref) / d_ref).abs() < 1e-3,
            "{name}: δ_max {} vs independent {d_ref}",
            r.max_penetration
        );
    }
    // Linear spring–dashpot with the clamp F ≥ 0.
    let (k, c) = (1e6, 5.0);
    let law = json!({"model": "linear", "stiffness": k, "damping": c});
    let r = run_impact(&pin_in_slot(law, MASS * v0, 1e-4), 5e-7, 14e-3);
    let (v_ref, d_ref) = reference_impact(|d, dd| k * d + c * dd, r.v_in, 1e-9);
    assert!(
        ((r.v_out - v_ref) / v_ref).abs() < 2e-3,
        "linear: rebound {} vs independent {v_ref}",
        r.v_out
    );
    assert!(
        ((r.max_penetration - d_ref) / d_ref).abs() < 1e-3,
        "linear: δ_max {} vs independent {d_ref}",
        r.max_penetration
    );
}

/// A point mass on a vertical guide above a Hertz wall (the ground line
/// y = 0), radius 0.5 mm, a gap of `gap`, pressed down by `force`.
fn mass_on_wall(force: f64, gap: f64) -> ValidModel {
    let r = 0.5e-3;
    model(json!({
        "name": "mass_on_wall",
        "point_masses": [{"id": "m", "mass": MASS, "position": [0.0, r + gap]}],
        "joints": [{"type": "slider", "a": {"ground": [0.0, 0.0]}, "b": {"body": "m"}, "axis": [0.0, 1.0]}],
        "contacts": [{
            "id": "wall", "type": "point_line", "point": {"body": "m"}, "radius": r, "side": "left",
            "line": {"ground": true, "from": [-1e-3, 0.0], "to": [1e-3, 0.0]},
            "law": {"model": "hertz", "stiffness": K_HERTZ}
        }],
        "loads": [{"at": {"body": "m"}, "force": [0.0, -force]}]
    }))
}

#[test]
fn statics_settles_on_a_hertz_wall_from_a_gap_and_modal_gives_its_frequency() {
    let f = 2.0;
    for gap in [0.0, 1e-7, 1e-5] {
        let m = mass_on_wall(f, gap);
        let sys = System::new(&m);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).unwrap();
        let d0 = (f / K_HERTZ).powf(1.0 / 1.5);
        let d = sys.contacts[0].penetration(&eq.q);
        assert!(
            ((d - d0) / d0).abs() < 1e-9,
            "gap {gap}: δ₀ = {d} vs (F/K)^(1/n) = {d0}"
        );
        let modal = modal_at_equilibrium(&sys, &eq, &ModalSettings::default()).unwrap();
        let expected = (1.5 * K_HERTZ * d0.sqrt() / MASS).sqrt() / (2.0 * PI);
        let got = modal.modes[0].frequency_hz;
        assert!(
            ((got - expected) / expected).abs() < 1e-9,
            "gap {gap}: f = {got} vs √(nKδ₀ⁿ⁻¹/m)/2π = {expected}"
        );
    }
}

/// A pin sliding along the flat of a slot whose body turns: the contact's
/// gradient and Hessian against central differences of its energy and
/// gradient.
#[test]
fn contact_tangent_matches_finite_differences() {
    let base = |pin: Value, local: [f64; 2]| {
        model(json!({
            "name": "fd",
            "rigid_bodies": [{"id": "slot", "mass": 1e-3, "inertia": 1e-8,
                              "position": [0.0, 0.0], "angle_deg": 20.0}],
            "beams": [{"id": "b", "start": local, "angle_deg": 60.0, "length": 5e-3,
                       "elements": 2, "section": {"height": 5e-4, "width": 1e-3},
                       "material": {"young": 1e9, "density": 1000.0}}],
            "contacts": [{"id": "c", "type": "pin_slot",
                          "slot": {"body": "slot", "from": [-1e-3, 0.0], "to": [1e-3, 0.0], "width": 1e-3},
                          "pin": pin, "pin_radius": 0.3e-3,
                          "law": {"model": "hertz", "stiffness": 1e9}}]
        }))
    };
    // Pin = node 0 of the beam, placed in the flat part (penetrating the
    // upper side) and beyond the end cap.
    for start in [[0.3e-3, 0.45e-3], [1.3e-3, 0.4e-3]] {
        let (s, c) = 20f64.to_radians().sin_cos();
        let global = [c * start[0] - s * start[1], s * start[0] + c * start[1]];
        let m = base(json!({"beam": "b", "s": 0.0}), global);
        let sys = System::new(&m);
        let contact = &sys.contacts[0];
        let q = sys.q0.clone();
        assert!(contact.penetration(&q) > 0.0, "the pin penetrates");
        let dofs: Vec<usize> = contact.pair().dofs().collect();
        let (mut g, mut h) = (PairGrad::zeros(), PairHess::zeros());
        contact.gradient(&q, &mut g);
        contact.hessian(&q, &mut h);
        for (j, &dj) in dofs.iter().enumerate() {
            let step = 1e-7
                * if dj >= 3 && (dj - 3) % 4 >= 2 {
                    1.0
                } else {
                    1e-3
                };
            let mut qp = q.clone();
            let mut qm = q.clone();
            qp[dj] += step;
            qm[dj] -= step;
            let fd_g = (contact.energy(&qp) - contact.energy(&qm)) / (2.0 * step);
            assert!(
                (fd_g - g[j]).abs() <= 1e-6 * g.abs().max(),
                "∂U/∂q[{j}] {} vs FD {fd_g}",
                g[j]
            );
            let (mut gp, mut gm) = (PairGrad::zeros(), PairGrad::zeros());
            contact.gradient(&qp, &mut gp);
            contact.gradient(&qm, &mut gm);
            for i in 0..dofs.len() {
                let fd_h = (gp[i] - gm[i]) / (2.0 * step);
                assert!(
                    (fd_h - h[(i, j)]).abs() <= 1e-6 * h.abs().max(),
                    "∂²U/∂q[{i}]∂q[{j}] {} vs FD {fd_h}",
                    h[(i, j)]
                );
            }
        }
    }
}

/// A pin under gravity resting on the lower flat of a long slot, launched
/// along it: without friction its energy stays; with friction μ the energy
/// lost equals μ m g times the distance slid.
#[test]
fn sliding_pin_keeps_its_energy_and_friction_takes_mu_n_per_metre() {
    let g = 9.81;
    let slide = |mu: Option<f64>| {
        let mut contact = json!({
            "id": "slot", "type": "pin_slot",
            "slot": {"ground": true, "from": [-1.0, 0.0], "to": [1.0, 0.0], "width": 1e-3},
            "pin": {"body": "pin"}, "pin_radius": 0.4e-3,
            "law": {"model": "hertz", "stiffness": K_HERTZ}
        });
        if let Some(mu) = mu {
            contact["friction"] = json!(mu);
        }
        let m = model(json!({
            "name": "slide", "gravity": [0.0, -g],
            "point_masses": [{"id": "pin", "mass": MASS, "position": [0.0, -0.1e-3]}],
            "contacts": [contact]
        }));
        let sys = System::new(&m);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).unwrap();
        let settings = TransientSettings {
            step: 1e-5,
            end_time: 0.1,
            spectral_radius: 1.0,
            ..TransientSettings::default()
        };
        let mut integ = Integrator::new(&sys, settings).unwrap();
        let mut v = vec![0.0; sys.ndof()];
        v[0] = 0.5;
        let mut state = integ.state_at(eq.q.clone(), v).unwrap();
        let energy = |st: &State| {
            0.5 * MASS * (st.v[0].powi(2) + st.v[1].powi(2))
                + MASS * g * st.q[1]
                + sys.strain_energy(&st.q).springs
        };
        let e0 = energy(&state);
        let x0 = state.q[0];
        let mut drift = 0.0f64;
        integ
            .run(&mut state, |st| drift = drift.max((energy(st) - e0).abs()))
            .unwrap();
        assert_eq!(integ.stats.steps, 10_000);
        (e0 - energy(&state), state.q[0] - x0, drift)
    };
    let (_, _, drift) = slide(None);
    let kinetic = 0.5 * MASS * 0.25;
    assert!(
        drift <= 1e-6 * kinetic,
        "frictionless: energy drift {drift:.3e} J over 10⁴ steps vs 1e-6 × {kinetic:.3e} J"
    );
    let mu = 0.2;
    let (lost, distance, _) = slide(Some(mu));
    let expected = mu * MASS * g * distance;
    assert!(
        ((lost - expected) / expected).abs() < 1e-3,
        "friction work {lost:.6e} J vs μ m g × distance {expected:.6e} J"
    );
}

/// Each bad contact gives one error naming its JSON path.
#[test]
fn bad_contacts_are_clear_errors() {
    use ancf_modal::error::Source;
    let base = |contact: Value| {
        json!({
            "name": "bad",
            "rigid_bodies": [{"id": "slot", "mass": 1e-3, "inertia": 1e-9, "position": [0.0, 0.0]}],
            "point_masses": [{"id": "pin", "mass": 1e-3, "position": [0.0, 0.0]}],
            "contacts": [contact]
        })
        .to_string()
    };
    let slot = |width: f64, to: [f64; 2], law: Value| {
        json!({"id": "c", "type": "pin_slot",
               "slot": {"body": "slot", "from": [-1e-3, 0.0], "to": to, "width": width},
               "pin": {"body": "pin"}, "pin_radius": 0.4e-3, "law": law})
    };
    let ln = |c: f64| json!({"model": "lankarani_nikravesh", "stiffness": 1e9, "restitution": c});
    let cases = [
        (
            slot(0.8e-3, [1e-3, 0.0], ln(0.5)),
            "contacts[0].pin_radius",
            "below half the slot width",
        ),
        (
            slot(1e-3, [1e-3, 0.0], ln(1.5)),
            "contacts[0].law.restitution",
            "outside",
        ),
        (
            slot(1e-3, [1e-3, 0.0], ln(0.0)),
            "contacts[0].law.restitution",
            "outside",
        ),
        (
            slot(1e-3, [-1e-3, 0.0], ln(0.5)),
            "contacts[0].slot",
            "end points coincide",
        ),
        (
            slot(
                1e-3,
                [1e-3, 0.0],
                json!({"model": "nonsense", "stiffness": 1e9}),
            ),
            // Inside the tagged contact serde names the contact, and the
            // message lists the laws.
            "contacts[0]",
            "unknown variant `nonsense`, expected one of `linear`, `hertz`",
        ),
        (
            json!({"id": "c", "type": "pin_slot",
                   "slot": {"body": "nope", "from": [-1e-3, 0.0], "to": [1e-3, 0.0], "width": 1e-3},
                   "pin": {"body": "pin"}, "pin_radius": 0.4e-3, "law": ln(0.5)}),
            "contacts[0].slot.body",
            "no rigid body with id `nope`",
        ),
    ];
    for (contact, path, what) in cases {
        let err = Model::from_json(&base(contact), Source::BuiltIn)
            .expect_err("invalid contact")
            .to_string();
        assert!(err.contains(path) && err.contains(what), "{path}: {err}");
        assert_eq!(err.lines().count(), 1, "one line: {err}");
    }
}

/// A 0.5 kg pendulum bob on a 10 mm steel leaf (0.1 × 5 mm), pushed aside
/// by 0.3 N under gravity: its lateral stiffness is about mg/L = 19 N/m.
/// With `stop_at` [m], a Hunt–Crossley stop (K = 1e8 N/m^1.5) on a vertical
/// line that far to the right of the bob.
fn pushed_pendulum(stop_at: Option<f64>) -> ValidModel {
    let mut v = json!({
        "name": "pendulum",
        "gravity": [0.0, -9.81],
        "beams": [{"id": "leaf", "start": [0.0, 0.0], "angle_deg": -90.0, "length": 0.01,
                   "elements": 8, "section": {"height": 1e-4, "width": 5e-3},
                   "material": {"young": 2e11, "density": 7850.0}}],
        "rigid_bodies": [{"id": "bob", "mass": 0.5, "inertia": 1e-3, "position": [0.0, -0.26]}],
        "joints": [
            {"id": "clamp", "type": "weld", "a": {"ground": [0.0, 0.0]}, "b": {"beam": "leaf", "s": 0.0}},
            {"id": "fix", "type": "weld", "a": {"beam": "leaf", "s": 0.01}, "b": {"body": "bob"}}],
        "loads": [{"id": "push", "at": {"body": "bob"}, "force": [0.3, 0.0]}]
    });
    if let Some(x) = stop_at {
        v["contacts"] = json!([{
            "id": "stop", "type": "point_line", "point": {"body": "bob"}, "radius": 0.01,
            "line": {"ground": true, "from": [x, -0.28], "to": [x, -0.24]}, "side": "left",
            "law": {"model": "hunt_crossley", "stiffness": 1e8, "exponent": 1.5, "restitution": 0.8}
        }]);
    }
    model(v)
}

/// An open contact does not change the equilibrium (outside-eyes trial: a
/// stop 190 mm from the pendulum's bob made `static` and `switch-off` fail,
/// the open contact's regularizing stiffness, 4.7e5 N/m, swamping the
/// bob's 19 N/m). Whatever the stop's distance, the equilibrium is the
/// stop-free one to 1e-12 of the bob's travel.
#[test]
fn an_open_contact_leaves_a_soft_structures_equilibrium_alone() {
    let free = {
        let m = pushed_pendulum(None);
        solve_equilibrium(&System::new(&m), &StaticSettings::default()).unwrap()
    };
    let n = free.q.len();
    let travel = free.q[n - 3].abs();
    assert!(travel > 5e-3, "the bob moves {travel} m");
    for stop in [0.05, 0.2, 1.0] {
        let m = pushed_pendulum(Some(stop));
        let sys = System::new(&m);
        let eq = solve_equilibrium(&sys, &StaticSettings::default()).unwrap();
        assert!(
            sys.contacts[0].penetration(&eq.q) <= 0.0,
            "open at {stop} m"
        );
        let off =
            eq.q.iter()
                .zip(&free.q)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(off <= 1e-12 * travel, "stop at {stop} m: off by {off:e} m");
    }
}
