//! The paper's Fig. 10: the switch-off's parameter study, run on a model
//! of the switch-off assembly (by default the built-in one).
//!
//! The paper (Section 3.1) varies three parameters of its validated model
//! and states one result: "a doubled pre-stress and a decreased stiffness
//! c_t and a change in the attachment of the helical spring u_P,y^s from
//! 0 mm to −1 mm would result in 2 mm of distance in approximately 0.6 ms,
//! which is approximately 1/3 of the current switch-off time". It gives no
//! number for any parameter alone (Fig. 10 shows curves only). The study
//! runs, beside the model as it is (the reference):
//!
//! * the pre-stress doubled: the released force `F_x2` [N] and the preload
//!   [N] of `helical_spring` ×2 (the contact force F_c follows from the ON
//!   state's balance);
//! * c_t lowered: the torsion stiffness of joint `hybrid` (the slot–blade
//!   "hybrid rigid connection") set to [`LOWERED_CT`] N m/rad;
//! * the spring's attachment: the y of `helical_spring`'s ground point
//!   moved by [`ATTACHMENT_SHIFT_M`] m;
//! * all three together,
//!
//! each a model changed as `sweep --param` changes it (the same parameter
//! texts, [`super::sweep::param`]) and run as the switch-off runs it
//! ([`run_switch_off_from`], the reference's settings without the rigid
//! and half-step runs): the time [s] for the tracked point to travel the
//! distance, and its ratio [–] to the reference's. Every time is a
//! prediction of the model; what the model has calibrated is listed with
//! the study ([`SwitchOffStudy::calibrated`]).

use super::sweep::{PointError, Quantity, Sweep, SweepError, SweepSettings};
use super::switch_off::{run_switch_off_from, Calibrated, SwitchOffSettings};
use crate::model::ValidModel;
use rayon::prelude::*;

/// The paper's statement for the three changes together: 2 mm in about
/// 0.6 ms [SI: s] ...
pub const PAPER_COMBINED_TIME_S: f64 = 0.6e-3;
/// ... "approximately 1/3 of the current switch-off time" [–].
pub const PAPER_COMBINED_RATIO: f64 = 1.0 / 3.0;
/// The factor on the pre-stress (the paper's "doubled pre-stress") [–].
pub const PRESTRESS_FACTOR: f64 = 2.0;
/// The lowered c_t [SI: N m/rad]: the low end of the README's c_t sweep
/// (the paper gives no value, only "a decreased stiffness").
pub const LOWERED_CT: f64 = 1.0;
/// The move of the spring's ground point in y [SI: m] (the paper's
/// "u_P,y^s from 0 mm to −1 mm").
pub const ATTACHMENT_SHIFT_M: f64 = -1e-3;

/// Why the study cannot run on a model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StudyError {
    /// A change names what the model does not have (the built-in switch-off
    /// model's load `F_x2`, spring `helical_spring`, joint `hybrid`).
    #[error("the Fig. 10 change `{change}` does not apply to this model (it needs the built-in switch-off model's load F_x2, spring helical_spring and joint hybrid)")]
    Parameters {
        change: String,
        #[source]
        source: SweepError,
    },
    /// A change makes a model that validation refuses.
    #[error("the Fig. 10 change `{change}` makes a model that is refused")]
    Model {
        change: String,
        #[source]
        source: PointError,
    },
}

/// What the paper's text says of a row.
const PAPER_ALONE: &str = "not given alone (the text gives the three together only)";

/// One change of the study: its name and the `sweep --param` texts that
/// make it.
#[derive(Debug, Clone, PartialEq)]
pub struct Change {
    pub name: String,
    pub params: Vec<String>,
}

/// The three changes alone and together, on a model whose joint `hybrid`
/// has torsion stiffness `ct` [SI: N m/rad] (for the name).
pub fn changes(ct: Option<f64>) -> Vec<Change> {
    let prestress = format!("load_scale:F_x2,helical_spring={PRESTRESS_FACTOR}");
    let stiffness = format!("joints[hybrid].torsion_stiffness={LOWERED_CT}");
    let attachment = format!("springs[helical_spring].a.ground[1]+={ATTACHMENT_SHIFT_M}");
    let from = ct.map_or(String::new(), |c| format!(" (from {c})"));
    vec![
        Change {
            name: format!("pre-stress × {PRESTRESS_FACTOR} (F_x2 and the spring's preload)"),
            params: vec![prestress.clone()],
        },
        Change {
            name: format!("c_t = {LOWERED_CT} N m/rad{from}"),
            params: vec![stiffness.clone()],
        },
        Change {
            name: format!(
                "spring attachment u_P,y^s {} mm",
                signed(ATTACHMENT_SHIFT_M * 1e3)
            ),
            params: vec![attachment.clone()],
        },
        Change {
            name: String::from("all three together"),
            params: vec![prestress, stiffness, attachment],
        },
    ]
}

/// `v` with a typographic sign (−1, +1).
fn signed(v: f64) -> String {
    if v < 0.0 {
        format!("−{}", -v)
    } else {
        format!("+{v}")
    }
}

/// One row of the study.
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct StudyRow {
    /// What was changed ("reference" for the model as it is).
    pub change: String,
    /// The change as `sweep` parameters (values SI; `+=` an offset).
    pub parameters: Vec<String>,
    /// Time for the tracked point to travel the distance [s]; null when it
    /// does not within the end time, or when the run failed.
    pub time_to_distance_s: Option<f64>,
    /// `time_to_distance_s` over the reference's [–].
    pub ratio_to_reference: Option<f64>,
    /// What the paper's text says of this change.
    pub paper: String,
    /// Why the run failed (a contact let go in the ON state, a Newton
    /// failure); null when it ran.
    pub error: Option<String>,
}

/// The study: a prediction of the model (`calibrated` lists what the model
/// has calibrated; empty: nothing).
#[derive(Debug, Clone, PartialEq, serde::Serialize, schemars::JsonSchema)]
pub struct SwitchOffStudy {
    /// The reference and each change (the three alone, then together).
    pub rows: Vec<StudyRow>,
    /// The three together over the reference [–] (a prediction).
    pub combined_ratio: Option<f64>,
    /// The paper's "approximately 0.6 ms" for the three together [s].
    pub paper_combined_time_s: f64,
    /// The paper's "approximately 1/3 of the current switch-off time" [–].
    pub paper_combined_ratio: f64,
    /// Model quantities calibrated to a measurement (as the switch-off's);
    /// empty: every time of the study is a prediction.
    pub calibrated: Vec<Calibrated>,
}

/// Runs the study on `model` (a design of `base`'s assembly, whose ON
/// state the runs continue, as [`run_switch_off_from`]) with the settings
/// of the switch-off run whose time to distance is `reference_s` [s];
/// `calibrated` is that run's list. Errors only when the changes do not
/// apply to the model (it lacks the ids `F_x2`, `helical_spring`,
/// `hybrid`); a run that fails is a row with its error.
pub fn run_study(
    model: &ValidModel,
    base: &ValidModel,
    settings: &SwitchOffSettings,
    reference_s: Option<f64>,
    calibrated: &[Calibrated],
) -> Result<SwitchOffStudy, StudyError> {
    let ct = model
        .joints
        .iter()
        .find(|j| j.id.as_deref() == Some("hybrid"))
        .and_then(|j| j.torsion_stiffness);
    let changed: Vec<(Change, ValidModel)> = changes(ct)
        .into_iter()
        .map(|change| {
            let settings = SweepSettings::new(Quantity::TimeToDistance);
            let sweep = Sweep::new(model, &change.params, settings).map_err(|source| {
                StudyError::Parameters {
                    change: change.name.clone(),
                    source,
                }
            })?;
            let m = sweep
                .model_at(&sweep.grid.values(0))
                .map_err(|source| StudyError::Model {
                    change: change.name.clone(),
                    source,
                })?;
            Ok((change, m))
        })
        .collect::<Result<_, StudyError>>()?;
    let own = SwitchOffSettings {
        compare_rigid: false,
        halve_step: false,
        ..settings.clone()
    };
    let ratio = |t: Option<f64>| match (t, reference_s) {
        (Some(t), Some(r)) => Some(t / r),
        _ => None,
    };
    let mut rows = vec![StudyRow {
        change: String::from("reference"),
        parameters: Vec::new(),
        time_to_distance_s: reference_s,
        ratio_to_reference: reference_s.map(|_| 1.0),
        paper: String::from("~1.75 ms (Fig. 7, measured; the paper's \"current switch-off time\")"),
        error: None,
    }];
    let last = changed.len() - 1;
    let runs: Vec<StudyRow> = changed
        .into_par_iter()
        .enumerate()
        .map(|(k, (change, m))| {
            let (time, error) = match run_switch_off_from(&m, base, &own) {
                Ok(r) => (r.flexible.time_to_distance_s, None),
                Err(e) => (None, Some(crate::error::chain_text(&e))),
            };
            StudyRow {
                change: change.name,
                parameters: change.params,
                time_to_distance_s: time,
                ratio_to_reference: ratio(time),
                paper: if k == last {
                    String::from("≈ 0.6 ms, \"approximately 1/3 of the current switch-off time\"")
                } else {
                    String::from(PAPER_ALONE)
                },
                error,
            }
        })
        .collect();
    let combined_ratio = runs.last().and_then(|r| r.ratio_to_reference);
    rows.extend(runs);
    Ok(SwitchOffStudy {
        rows,
        combined_ratio,
        paper_combined_time_s: PAPER_COMBINED_TIME_S,
        paper_combined_ratio: PAPER_COMBINED_RATIO,
        calibrated: calibrated.to_vec(),
    })
}
