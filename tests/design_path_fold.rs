//! The design path's secant predictor and a fold
//! ([`ancf_modal::analysis::statics::design_path`], its module doc "Folds").
//!
//! The switch-off's uncalibrated companion (F_x² at the blade tip) is
//! continued from the calibrated built-in design, with its spring housing
//! raised by 0, 0.1 and 0.4 mm. With the housing raised 0.1 mm the branch
//! the path leaves on folds back near τ = 0.61: the secant path follows it
//! into the fold and stops there, and the path the design path then runs
//! (each step from the last state) jumps the fold. Physics asserted on
//! every end state, each on its own design's system and independently of
//! the path: the force balance and the constraints hold
//! ([`unbalanced_force`] to [`BALANCE_TOLERANCE`]), the contacts closed in
//! the start's equilibrium (the pin in its slot, the pad on the fixed
//! contact) still press, and the secant path reaches the equilibrium the
//! other ways find (the path without the secant, the load-factor
//! continuation from the design's own reference), a rigid body's rotation
//! taken modulo whole turns (unraised, the path without the secant turns
//! the slot five times round on the way).

use ancf_modal::analysis::statics::balance::{unbalanced_force, BALANCE_TOLERANCE};
use ancf_modal::analysis::statics::design_path::{
    equilibrium_along_from, equilibrium_along_with, DesignPathError, PathStart, Predictor,
};
use ancf_modal::analysis::statics::{solve_equilibrium, Equilibrium, StaticSettings};
use ancf_modal::mechanics::spring::ForceElement;
use ancf_modal::model::ValidModel;
use ancf_modal::{Model, System};

/// The size the coordinates are compared against [m] (the assembly is a
/// few cm across).
const SIZE: f64 = 0.025;

/// The uncalibrated companion with its spring housing raised by `dy` [m].
fn raised(dy: f64) -> ValidModel {
    let mut m = Model::switch_off_uncalibrated_builtin().into_model();
    m.springs[0].a.ground.as_mut().unwrap()[1] += dy;
    m.validated().unwrap()
}

/// The path's end state with `predictor` (`None`: the design path's own
/// choice, the secant and then, when it stops, the last state).
fn path_end(
    design: &ValidModel,
    predictor: Option<Predictor>,
) -> Result<(Equilibrium, usize), DesignPathError> {
    let path = Model::switch_off_builtin().path_to(design).unwrap();
    let build = |tau| path.at(tau).map(|m| System::new(&m));
    let (start, settings) = (PathStart::new(), StaticSettings::default());
    match predictor {
        Some(p) => equilibrium_along_with(build, &start, &settings, p),
        None => equilibrium_along_from(build, &start, &settings),
    }
}

/// The physics of an end state on its own design's system (module doc).
fn assert_holds(design: &ValidModel, eq: &Equilibrium, what: &str) {
    let sys = System::new(design);
    let b = unbalanced_force(&sys, &eq.q, Some(&eq.lambda), eq.time, eq.load_scale);
    assert!(b.is_balanced(BALANCE_TOLERANCE), "{what}: {b:?}");
    for label in ["pin_in_slot", "fixed_contact"] {
        let c = sys.contacts.iter().find(|c| c.label == label).unwrap();
        let force = c.elastic_force(&eq.q);
        assert!(force > 0.0, "{what}: contact {label} at {force} N");
    }
}

/// The largest difference between two states of `design` [m, –]; a rigid
/// body's rotation counts modulo whole turns (the same configuration).
fn largest_difference(design: &ValidModel, a: &[f64], b: &[f64]) -> f64 {
    let sys = System::new(design);
    assert_eq!(a.len(), b.len());
    let turn = std::f64::consts::TAU;
    (0..a.len()).fold(0.0f64, |m, i| {
        let d = a[i] - b[i];
        let d = if sys.dof_label(i).ends_with("rotation") {
            d - turn * (d / turn).round()
        } else {
            d
        };
        m.max(d.abs())
    })
}

#[test]
fn the_secant_path_stops_at_the_fold_and_the_path_without_it_jumps_it() {
    let fold = raised(1e-4);
    match path_end(&fold, Some(Predictor::Secant)) {
        Err(DesignPathError::Stalled { at, .. }) => {
            assert!(
                (0.55..0.7).contains(&at),
                "the secant path stalls at τ = {at}"
            )
        }
        other => panic!("the fold's design: the secant path gives {other:?}"),
    }
    let (eq, _) = path_end(&fold, None).unwrap_or_else(|e| panic!("across the fold: {e}"));
    assert_holds(&fold, &eq, "across the fold");
    let (last, _) = path_end(&fold, Some(Predictor::LastState)).unwrap();
    let off = largest_difference(&fold, &eq.q, &last.q);
    assert!(
        off <= 1e-8 * SIZE,
        "{off:e} from the path without the secant"
    );
}

/// The secant path's end against the same design's equilibrium found
/// two other ways, wherever they find it: the path without the secant,
/// and the load-factor continuation from the design's own reference (the
/// switch-off's fallback). With the housing raised 0.4 mm the path
/// without the secant loses stability at τ ≈ 0.54 and only the reference
/// finds it; unraised, both do.
#[test]
fn the_secant_path_ends_where_the_other_ways_find_the_design() {
    for dy in [0.0, 4e-4] {
        let design = raised(dy);
        let (secant, _) = path_end(&design, Some(Predictor::Secant))
            .unwrap_or_else(|e| panic!("housing +{dy} m, secant: {e}"));
        assert_holds(&design, &secant, "secant");
        // The design path's own answer is the secant path's.
        let (own, _) = path_end(&design, None).unwrap();
        assert_eq!(own.q, secant.q, "housing +{dy} m");
        let last = path_end(&design, Some(Predictor::LastState)).map(|(eq, _)| eq);
        let reference = solve_equilibrium(&System::new(&design), &StaticSettings::default());
        let mut compared = 0;
        for (way, other) in [("last state", last.ok()), ("reference", reference.ok())] {
            let Some(other) = other else { continue };
            assert_holds(&design, &other, way);
            let off = largest_difference(&design, &secant.q, &other.q);
            assert!(
                off <= 1e-8 * SIZE,
                "housing +{dy} m: {off:e} from the {way}'s"
            );
            compared += 1;
        }
        assert!(compared > 0, "housing +{dy} m: found one way only");
    }
}
