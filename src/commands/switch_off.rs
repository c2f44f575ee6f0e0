//! `switch-off`: the paper's switch-off experiment (Section 4, Figs. 7–9)
//! on a model, by default the built-in switch-off assembly: the
//! pre-stressed ON state as a static equilibrium, the release of the
//! pre-stress loads, and the transient (steps of `step` [s] to `end_time`
//! [s], samples at `sample_rate` [Hz]); the time [s] for a tracked point
//! to travel `distance` [m] along `direction`, optionally beside the model
//! with rigid beams and the same run at half the step
//! ([`crate::analysis::switch_off`]); with `fig10`, the paper's Fig. 10
//! study beside it: the pre-stress doubled, c_t lowered and the spring's
//! attachment moved −1 mm, each alone and all three together, each a
//! prediction ([`crate::analysis::switch_off_study`]).

use super::{CommandError, ModelInput, Run};
use crate::analysis::switch_off::{run_switch_off, SwitchOffResult, SwitchOffSettings};
use crate::analysis::switch_off_study::{run_study, SwitchOffStudy};
use crate::model::Model;
use crate::model::PointSpec;
use crate::output::figures::switch_off::write_switch_off_figures;
use crate::output::plot::PlotSize;
use crate::output::switch_off_report::{study_table, switch_off_csv, switch_off_table};
use crate::results::SwitchOffOutput;
use std::path::Path;

/// What `switch-off` computes. The defaults are the paper's: 2 mm along
/// x, the camera's 67.2 kHz ([`SwitchOffSettings`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SwitchOffRequest {
    /// End time [s] (> 0).
    pub end_time: f64,
    /// Time step [s] (> 0).
    pub step: f64,
    /// Travel distance of the tracked point [m] (> 0).
    pub distance: f64,
    /// Travel direction (dx, dy), global, any non-zero length.
    pub direction: [f64; 2],
    /// The tracked point; `None`: node 0 of the first beam.
    pub point: Option<PointSpec>,
    /// Output sample rate [Hz] (≥ 0).
    pub sample_rate: f64,
    /// Also run the model with every beam rigid (the paper's rigid model).
    pub compare_rigid: bool,
    /// Skip the check run at half the step.
    pub no_step_check: bool,
    /// Also run the paper's Fig. 10 study (the three changes alone and
    /// together, with the same settings).
    pub fig10: bool,
}

impl Default for SwitchOffRequest {
    fn default() -> Self {
        let s = SwitchOffSettings::default();
        SwitchOffRequest {
            end_time: s.end_time,
            step: s.step,
            distance: s.distance,
            direction: s.direction,
            point: s.point,
            sample_rate: s.sample_rate,
            compare_rigid: s.compare_rigid,
            no_step_check: false,
            fig10: false,
        }
    }
}

/// `BEAM:S` (the arc length S in m along beam BEAM) or `BODY` (a rigid
/// body or point mass): a tracked point as the command line and Python
/// write it; the error says what is wrong with `text`.
pub fn parse_point(text: &str) -> Result<PointSpec, String> {
    match text.split_once(':') {
        Some((beam, arc)) => {
            let s = arc
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("`{arc}` is not an arc length in m"))?;
            Ok(PointSpec {
                beam: Some(beam.to_string()),
                s: Some(s),
                ..PointSpec::default()
            })
        }
        None => Ok(PointSpec {
            body: Some(text.to_string()),
            ..PointSpec::default()
        }),
    }
}

/// `switch-off`'s output: the runs and the document.
#[derive(Debug)]
pub struct SwitchOffRun {
    /// The flexible run, the rigid one and the half-step check.
    pub result: SwitchOffResult,
    /// The paper's Fig. 10 study (`fig10`), else `None`.
    pub study: Option<SwitchOffStudy>,
    /// The document with the run's warnings (the analysis's own warnings
    /// are the result's, [`SwitchOffResult::warnings`], at the head of the
    /// document's list).
    pub document: Run<SwitchOffOutput>,
}

/// Runs `switch-off` on `input`.
pub fn run(input: &ModelInput, request: &SwitchOffRequest) -> Result<SwitchOffRun, CommandError> {
    super::checks::time_span(request.end_time, request.step)?;
    super::checks::positive("distance", request.distance)?;
    let rate = request.sample_rate;
    super::checks::sample_rate(rate)?;
    let [dx, dy] = request.direction;
    if !(dx.is_finite() && dy.is_finite()) {
        return Err(CommandError::argument(
            "direction",
            format!("({dx}, {dy})"),
            "must be finite",
        ));
    }
    let settings = SwitchOffSettings {
        step: request.step,
        end_time: request.end_time,
        sample_rate: rate,
        distance: request.distance,
        direction: request.direction,
        point: request.point.clone(),
        compare_rigid: request.compare_rigid,
        halve_step: !request.no_step_check,
        ..SwitchOffSettings::default()
    };
    let result = run_switch_off(&input.model, &settings)
        .map_err(|e| CommandError::simulation(input.label(), e))?;
    let study = if request.fig10 {
        Some(fig10(input, &result)?)
    } else {
        None
    };
    let mut output = SwitchOffOutput::new(&result);
    output.fig10 = study.clone();
    Ok(SwitchOffRun {
        document: Run::of(input, output),
        result,
        study,
    })
}

/// The paper's Fig. 10 study beside the switch-off `result` of `input`'s
/// model: the same settings, the ON states continued from the built-in
/// model's as the switch-off's.
pub fn fig10(input: &ModelInput, result: &SwitchOffResult) -> Result<SwitchOffStudy, CommandError> {
    run_study(
        &input.model,
        &Model::switch_off_builtin(),
        &result.settings,
        result.flexible.time_to_distance_s,
        &result.calibrated,
    )
    .map_err(|source| CommandError::Study {
        model: input.label(),
        source: Box::new(source),
    })
}

impl SwitchOffRun {
    /// The command line's report.
    pub fn text(&self) -> String {
        let mut text = switch_off_table(&self.result);
        if let Some(study) = &self.study {
            text.push_str(&study_table(study, &self.result));
        }
        text
    }

    /// The tracked point's samples as CSV (`--csv`).
    pub fn csv(&self) -> String {
        switch_off_csv(&self.result)
    }

    /// Draws the travel against time to `path` (.svg or .png) and the
    /// trajectory beside it, as `--plot`.
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        write_switch_off_figures(&self.result, path, PlotSize::default())?;
        Ok(())
    }
}
