//! The switch-off's ON state over the design space of DESIGN §7: the
//! torsional stiffness c_t 0.2–1000 N m/rad, the spring's ground point
//! ±2 mm, the pre-stress (F_x² and the spring's preload together)
//! × 0.5–3, the pad contact's stiffness 1e8–1e11 N/m^1.5, one at a time
//! from the built-in model. Each must find its equilibrium with the pad
//! against the fixed contact. Closed forms: with everything else fixed the
//! pad force comes from the balance of the assembly about the pin, so it
//! does not depend on the contact's stiffness, and it scales with the
//! pre-stress (up to gravity, ~0.02 N, and the small change of geometry).
//! The 16 corners of the box combined are found by continuation in the
//! design from the built-in one
//! ([`ancf_modal::analysis::statics::design_path`]), on two different
//! paths (geometric in c_t, K and the pre-stress; the straight line the
//! switch-off uses) that must reach the same equilibrium; a design beyond
//! the one where the pad lets go is reported as having no equilibrium with
//! the pad closed, where the linear balance says.

mod common;

use ancf_modal::analysis::statics::{solve_equilibrium, StaticSettings};
use ancf_modal::mechanics::spring::ForceElement;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};

/// Paper, Table 4 [N].
const PAPER_F_C: f64 = 2.92;

/// The pad force [N] in the ON equilibrium of `m` (0 when the pad is off
/// the fixed contact), found as `switch-off` finds it: continued from the
/// built-in design's (from its own reference the load path of a tripled
/// pre-stress loses the pin's contact on the way, a mechanism).
fn pad_force(m: &ValidModel) -> f64 {
    let sys = System::new(m);
    let eq = ancf_modal::analysis::statics::design_path::on_state_equilibrium(
        m,
        &Model::switch_off_builtin(),
        System::new,
        &StaticSettings::default(),
    )
    .unwrap_or_else(|e| panic!("{}: {e}", m.name));
    let c = sys
        .contacts
        .iter()
        .find(|c| c.label == "fixed_contact")
        .unwrap_or_else(|| {
            let labels: Vec<&str> = sys.contacts.iter().map(|c| c.label.as_str()).collect();
            panic!("{}: contacts {labels:?}", m.name)
        });
    c.elastic_force(&eq.q)
}

fn variant(name: &str, edit: impl Fn(&mut Model)) -> ValidModel {
    let mut m = Model::switch_off_builtin().into_model();
    m.name = name.to_string();
    edit(&mut m);
    m.validated().unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn contact_stiffness(m: &mut Model, k: f64) {
    for c in &mut m.contacts {
        if let ancf_modal::model::Contact::PointLine { law, .. } = c {
            law.stiffness = k;
        }
    }
}

#[test]
fn the_on_state_holds_over_the_design_space() {
    let reference = pad_force(&Model::switch_off_builtin());
    assert!(
        ((reference - PAPER_F_C) / PAPER_F_C).abs() < 0.01,
        "reference pad force {reference} N vs Table 4's {PAPER_F_C} N"
    );
    for ct in [0.2, 1.0, 50.0, 1000.0] {
        let f = pad_force(&variant(&format!("c_t = {ct}"), |m| {
            m.joints[0].torsion_stiffness = Some(ct);
        }));
        assert!(f > 0.0, "c_t = {ct} N m/rad: the pad is off the contact");
    }
    for dy in [-2e-3, -1e-3, 1e-3, 2e-3] {
        let f = pad_force(&variant(&format!("ground y {dy:+}"), |m| {
            m.springs[0].a.ground.as_mut().unwrap()[1] += dy;
        }));
        assert!(
            f > 0.0,
            "spring ground {dy:+} m: the pad is off the contact"
        );
    }
    for k in [1e8, 1e9, 1e11] {
        let f = pad_force(&variant(&format!("K = {k:e}"), |m| contact_stiffness(m, k)));
        assert!(
            ((f - reference) / reference).abs() < 1e-3,
            "K = {k:e}: pad force {f} N vs {reference} N at 1e10 (statically determinate)"
        );
    }
    for s in [0.5, 1.5, 2.0, 3.0] {
        let f = pad_force(&variant(&format!("pre-stress × {s}"), |m| {
            m.loads[0].force[0] *= s;
            let p = m.springs[0].preload.as_mut().unwrap();
            *p *= s;
        }));
        assert!(
            ((f / s - reference) / reference).abs() < 0.01,
            "pre-stress × {s}: pad force {f} N vs {s} × {reference} N"
        );
    }
}

/// The built-in model with c_t, the spring's ground offset dy [m], the
/// pre-stress factor s and the pad contact's K, each a fraction τ of the
/// way from the built-in value (K and s geometrically).
fn design(tau: f64, [ct, dy, s, k]: [f64; 4]) -> ValidModel {
    let base = Model::switch_off_builtin();
    let ct0 = base.joints[0].torsion_stiffness.unwrap();
    let geo = |a: f64, b: f64| a * (b / a).powf(tau);
    variant("corner", |m| {
        m.joints[0].torsion_stiffness = Some(geo(ct0, ct));
        m.springs[0].a.ground.as_mut().unwrap()[1] += tau * dy;
        let scale = geo(1.0, s);
        m.loads[0].force[0] *= scale;
        *m.springs[0].preload.as_mut().unwrap() *= scale;
        contact_stiffness(m, geo(1e10, k));
    })
}

fn path_settings() -> StaticSettings {
    StaticSettings::default()
}

fn fixed_contact_force(sys: &System, q: &[f64]) -> f64 {
    let c = sys.contacts.iter().find(|c| c.label == "fixed_contact");
    c.expect("the built-in model's pad contact")
        .elastic_force(q)
}

#[test]
fn the_corners_of_the_design_space_are_found_or_have_no_closed_equilibrium() {
    use ancf_modal::analysis::statics::design_path::{
        equilibrium_along, on_state_equilibrium, DesignPathError,
    };
    let mut report = Vec::new();
    let mut unfound = 0;
    for ct in [0.2, 1000.0] {
        for dy in [-2e-3, 2e-3] {
            for s in [0.5, 3.0] {
                let mut forces = Vec::new();
                for k in [1e8, 1e11] {
                    let p = [ct, dy, s, k];
                    let r =
                        equilibrium_along(|tau| Ok(System::new(&design(tau, p))), &path_settings());
                    let (eq, steps) = r.unwrap_or_else(|e| panic!("{p:?}: {e}"));
                    let sys = System::new(&design(1.0, p));
                    let f = fixed_contact_force(&sys, &eq.q);
                    assert!(f > 0.0, "{p:?}: the pad is off");
                    // The switch-off's own path: the straight line from
                    // the built-in design, another way to the same state.
                    let straight = on_state_equilibrium(
                        &design(1.0, p),
                        &Model::switch_off_builtin(),
                        System::new,
                        &path_settings(),
                    )
                    .unwrap_or_else(|e| panic!("{p:?}, straight path: {e}"));
                    let g = fixed_contact_force(&sys, &straight.q);
                    assert!(
                        ((f - g) / f).abs() < 1e-6,
                        "{p:?}: pad {f} N on the geometric path, {g} N on the straight one"
                    );
                    // Solved from its own reference without a path: the
                    // same state wherever it is found with the pad on.
                    let own = match solve_equilibrium(&sys, &path_settings()) {
                        Ok(own) if fixed_contact_force(&sys, &own.q) > 0.0 => {
                            let off = (own.q.iter().zip(&eq.q))
                                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
                            assert!(off <= 1e-8 * 0.025, "{p:?}: {off:e} m from the path's");
                            "found from the reference too"
                        }
                        Ok(_) => "from the reference: another branch, the pad off",
                        Err(_) => {
                            unfound += 1;
                            "not found from the reference"
                        }
                    };
                    forces.push(f);
                    report.push(format!("{p:?}: pad {f:.4} N ({steps} steps); {own}"));
                }
                // Statically determinate: the pad force does not depend on
                // the contact's stiffness.
                if let [a, b] = forces[..] {
                    assert!(((a - b) / b).abs() < 1e-3, "{ct} {dy} {s}: {a} vs {b} N");
                }
            }
        }
    }
    eprintln!(
        "{}\nnot found from the reference: {unfound} of 16",
        report.join("\n")
    );
    // F_x² alone lowered by a factor 1 − τ: the balance about the pin
    // takes its lost moment from the pad, whose force falls; at the
    // reference geometry linearly, F(τ) = F(0) − τ·2(F(0) − F(½)), to 0 at
    // τ_lin = F(0)/(2(F(0) − F(½))). The pin rolls round its end cap as the
    // load turns, so the fall is not quite linear: the secant through the
    // forces at τ = ½ and ¾ reaches 0 at τ_sec. The path to F_x² = 0 must
    // report that no closed equilibrium exists beyond the last closed state
    // (τ = ¾) and between the two estimates.
    let lowered = |to: f64| {
        move |tau: f64| {
            Ok(System::new(&variant("F_x2 lowered", |m| {
                m.loads[0].force[0] *= 1.0 + (to - 1.0) * tau;
            })))
        }
    };
    let pad_at = |tau: f64| {
        let (eq, _) = equilibrium_along(lowered(1.0 - tau), &path_settings()).unwrap();
        let sys = lowered(1.0 - tau)(1.0).unwrap();
        let c = sys.contacts.iter().find(|c| c.label == "fixed_contact");
        c.unwrap().elastic_force(&eq.q)
    };
    let f0 = pad_force(&Model::switch_off_builtin());
    let (f_half, f_3q) = (pad_at(0.5), pad_at(0.75));
    assert!(
        f0 > f_half && f_half > f_3q && f_3q > 0.0,
        "{f0} {f_half} {f_3q} N"
    );
    let linear = f0 / (2.0 * (f0 - f_half));
    let secant = 0.75 + f_3q * 0.25 / (f_half - f_3q);
    match equilibrium_along(lowered(0.0), &path_settings()) {
        Err(DesignPathError::ContactOpens { contact, at }) => {
            assert_eq!(contact, "fixed_contact");
            assert!(
                at > 0.75 && at >= linear.min(secant) - 0.01 && at <= linear.max(secant) + 0.01,
                "opens at τ = {at:.4}: the linear balance says {linear:.4}, the secant {secant:.4}"
            );
        }
        other => panic!("F_x² to 0: {other:?}"),
    }
}

/// The command line at a corner whose ON state the load-factor
/// continuation from the reference once did not find (c_t = 0.2 N m/rad,
/// ground −2 mm, pre-stress × 0.5, K = 1e11: "a mechanism"; since the
/// statics tries the exact tangent of far-open contacts it does, and both
/// must agree): `switch-off` on the model file and a one-point `sweep`
/// from the built-in model both start from the equilibrium the design path
/// finds (the pad force at t = 0 is the library's) and reach 2 mm at the
/// same time.
#[test]
fn the_command_line_continues_a_changed_design_from_the_built_in_one() {
    let p = [0.2, -2e-3, 0.5, 1e11];
    let corner = design(1.0, p);
    let sys = System::new(&corner);
    let on = ancf_modal::analysis::statics::design_path::on_state_equilibrium(
        &corner,
        &Model::switch_off_builtin(),
        System::new,
        &StaticSettings::default(),
    )
    .unwrap();
    if let Ok(own) = solve_equilibrium(&sys, &StaticSettings::default()) {
        let off = own
            .q
            .iter()
            .zip(&on.q)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            off <= 1e-8 * 0.025,
            "from its reference and along the design path: {off:e} m apart"
        );
    }
    let pad = fixed_contact_force(&sys, &on.q);
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("corner.json");
    std::fs::write(&file, serde_json::to_string(&corner).unwrap()).unwrap();
    let run = |args: &[&str]| -> serde_json::Value {
        serde_json::from_slice(&common::run_ok(args)).unwrap()
    };
    // Half the pre-stress and the spring 2 mm lower open slowly: 6 ms.
    let so = run(&[
        "switch-off",
        file.to_str().unwrap(),
        "--json",
        "--end-time",
        "0.006",
    ]);
    let contacts = so["contacts"].as_array().unwrap();
    let fixed = contacts
        .iter()
        .find(|c| c["id"] == "fixed_contact")
        .unwrap();
    let f0 = fixed["force_n"][0].as_f64().unwrap();
    assert!(
        ((f0 - pad) / pad).abs() < 1e-9,
        "{f0} N at t = 0 vs {pad} N"
    );
    let t = so["time_to_distance_s"].as_f64().expect("2 mm reached");
    let sweep = run(&[
        "sweep",
        "--param",
        "load_scale:F_x2,helical_spring=0.5:0.5:1",
        "--param",
        "joints[hybrid].torsion_stiffness=0.2:0.2:1",
        "--param",
        "springs[helical_spring].a.ground[1]+=-2e-3:-2e-3:1",
        "--param",
        "contacts[fixed_contact].law.stiffness=1e11:1e11:1",
        "--quantity",
        "time_to_distance_s",
        "--end-time",
        "0.006",
        "--json",
    ]);
    let point = &sweep["points"][0];
    let ts = point["result"]
        .as_f64()
        .unwrap_or_else(|| panic!("{point}"));
    assert!(
        ((ts - t) / t).abs() < 1e-9,
        "sweep {ts} s vs switch-off {t} s"
    );
}
