//! `frf`: measured hammer records in (CSV or UFF 58 files, or force [N]
//! and response [m, m/s or m/s²] arrays sampled at `fs` [Hz]), the
//! averaged H1 = G_fx/G_ff and H2 = G_xx/G_xf [response unit per N] and the
//! coherence γ² [–] out, with the modes' frequencies [Hz] and damping
//! ratios ζ [–] fitted by LSCF over the band the hammer excited
//! ([`crate::measured::analysis`]). With a model and one of its sensors,
//! the model's FRF at that sensor (modal superposition, per newton of its
//! first load) beside the measured one ([`ModelOverlay`]).
//!
//! `frf` runs without a model: its document's `model_sha256` is then null.
//! Its own warnings are about the records (UFF datasets skipped, a taper on
//! impact records, what the records show); they are not named by a model.

use super::{CommandError, ModelInput, Run};
use crate::measured::analysis::{analyse, AnalysisSettings, Estimator, FrfAnalysis};
use crate::measured::{
    check_force, read_measurement_noted, Channel, Channels, Measurement, TimeRecord, MIN_SAMPLES,
};
use crate::output::frf_report::{frf_csv, frf_figure, frf_table, frf_uff, ResponseQuantity};
use crate::output::plot::{render, Figure, Format, PlotSize};
use crate::results::fit::{FrfOutput, ModelOverlay};
use crate::signal::Window;
use realfft::num_complex::Complex64;
use std::path::{Path, PathBuf};

/// The hammer records `frf` analyses.
#[derive(Debug, Clone, PartialEq)]
pub enum FrfRecords {
    /// Measurement files: CSV (header row, time [s] in the first column) or
    /// UFF 58 (time records, or one FRF). Several files are hits,
    /// averaged.
    Files(Vec<PathBuf>),
    /// Hits as arrays, one row per hit (averaged): `force` [N] and
    /// `response` [the unit of the response quantity], sampled at `fs`
    /// [Hz]. Named `<array>` (one hit) or `<array row I>` in the document.
    Arrays {
        force: Vec<Vec<f64>>,
        response: Vec<Vec<f64>>,
        fs: f64,
    },
}

/// What `frf` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct FrfRequest {
    /// The records (none by default: a run needs at least one file).
    pub records: FrfRecords,
    /// The force channel of the files: a CSV column name or 1-based index,
    /// a UFF record label or index; `None`: the one column whose name holds
    /// `force`, else column 2 (UFF: the force record).
    pub force: Option<Channel>,
    /// The response channel of the files; `None`: the first column after
    /// time that is not the force.
    pub response: Option<Channel>,
    /// What the response measures (the FRF's unit); `None`: what the
    /// response channels' names say (`…_displacement`, `…_velocity`,
    /// `…_acceleration`, as `impulse` and `transient` write them), else
    /// velocity.
    pub response_quantity: Option<ResponseQuantity>,
    /// The window of the time records.
    pub window: Window,
    /// The estimator the modal fit uses.
    pub estimator: Estimator,
    /// Fit band (LO, HI) [Hz], 0 ≤ LO < HI; `None`: where the hammer
    /// excited the structure, up to 0.8 × Nyquist.
    pub band: Option<(f64, f64)>,
    /// Highest model order of the stabilization diagram [–] (2 to 200).
    pub max_order: usize,
    /// The model's sensor whose FRF is drawn beside the measured one (with
    /// a model only).
    pub at: Option<String>,
}

impl Default for FrfRequest {
    fn default() -> Self {
        let settings = AnalysisSettings::default();
        FrfRequest {
            records: FrfRecords::Files(Vec::new()),
            force: None,
            response: None,
            response_quantity: None,
            window: Window::Rectangular,
            estimator: settings.estimator,
            band: None,
            max_order: settings.max_order,
            at: None,
        }
    }
}

/// The model's FRF at a sensor on the measured frequency lines.
#[derive(Debug, Clone)]
pub struct Overlay {
    /// Its document (`model_frf`).
    pub overlay: ModelOverlay,
    /// Its values [FRF unit], one per line.
    pub h: Vec<Complex64>,
}

/// `frf`'s output: the analysis, the model's FRF and the document.
#[derive(Debug)]
pub struct FrfRun {
    /// H1, H2, coherence and the fit.
    pub analysis: FrfAnalysis,
    /// What the response measures.
    pub quantity: ResponseQuantity,
    /// The model's FRF (with a model).
    pub overlay: Option<Overlay>,
    /// The document with the run's warnings.
    pub document: Run<FrfOutput>,
}

impl FrfRequest {
    /// The analysis settings, the request's ranges checked.
    fn settings(&self) -> Result<AnalysisSettings, CommandError> {
        if let Some((lo, hi)) = self.band {
            if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
                return Err(CommandError::argument(
                    "band",
                    format!("({lo}, {hi})"),
                    "the band needs 0 ≤ LO < HI [Hz]",
                ));
            }
        }
        if !(2..=200).contains(&self.max_order) {
            return Err(CommandError::argument(
                "max_order",
                self.max_order,
                "must be a whole number from 2 to 200",
            ));
        }
        Ok(AnalysisSettings {
            window: self.window,
            estimator: self.estimator,
            band: self.band,
            max_order: self.max_order,
        })
    }

    /// The measurements and the notes of their reading (UFF datasets
    /// skipped).
    fn measurements(&self) -> Result<(Vec<Measurement>, Vec<String>), CommandError> {
        match &self.records {
            FrfRecords::Files(files) => {
                if files.is_empty() {
                    return Err(CommandError::argument(
                        "records",
                        "[]",
                        "give at least one file",
                    ));
                }
                let channels = Channels {
                    force: self.force.clone(),
                    response: self.response.clone(),
                };
                let mut notes = Vec::new();
                let mut measurements = Vec::with_capacity(files.len());
                for f in files {
                    let (m, n) = read_measurement_noted(f, &channels)?;
                    measurements.push(m);
                    notes.extend(n);
                }
                Ok((measurements, notes))
            }
            FrfRecords::Arrays {
                force,
                response,
                fs,
            } => Ok((arrays(force, response, *fs)?, Vec::new())),
        }
    }
}

/// Hits given as arrays as time records, their shapes and forces checked.
fn arrays(
    force: &[Vec<f64>],
    response: &[Vec<f64>],
    fs: f64,
) -> Result<Vec<Measurement>, CommandError> {
    if !(fs.is_finite() && fs > 0.0) {
        return Err(CommandError::argument("fs", fs, "must be a number > 0"));
    }
    let shape = |r: &[Vec<f64>]| {
        format!(
            "{} hits of {} samples",
            r.len(),
            r.first().map_or(0, Vec::len)
        )
    };
    if force.len() != response.len() || force.iter().zip(response).any(|(a, b)| a.len() != b.len())
    {
        return Err(CommandError::argument(
            "response",
            shape(response),
            format!("must have the force's shape, {}", shape(force)),
        ));
    }
    let samples = force.first().map_or(0, Vec::len);
    if samples < MIN_SAMPLES {
        return Err(CommandError::argument(
            "force",
            format!("{samples} samples"),
            format!("a hit needs at least {MIN_SAMPLES} samples"),
        ));
    }
    let single = force.len() == 1;
    let mut measurements = Vec::with_capacity(force.len());
    for (i, (f, x)) in force.iter().zip(response).enumerate() {
        let name = if single {
            String::from("<array>")
        } else {
            format!("<array row {i}>")
        };
        let r = TimeRecord {
            file: PathBuf::from(name),
            sample_rate_hz: fs,
            force: f.clone(),
            response: x.clone(),
            force_label: String::from("force"),
            response_label: String::from("response"),
            lines: Vec::new(),
        };
        check_force(&r)?;
        measurements.push(Measurement::Time(r));
    }
    Ok(measurements)
}

/// Runs `frf` on the request's records; with `model`, its FRF at the
/// sensor `request.at` beside them.
pub fn run(model: Option<&ModelInput>, request: &FrfRequest) -> Result<FrfRun, CommandError> {
    let settings = request.settings()?;
    let at = match (model, &request.at) {
        (Some(_), None) => {
            return Err(CommandError::argument(
                "at",
                "none",
                "the model's FRF needs one of its sensors",
            ))
        }
        (None, Some(at)) => {
            return Err(CommandError::argument(
                "at",
                at,
                "names a sensor of the model, and no model was given",
            ))
        }
        (Some(m), Some(at)) => Some((m, at)),
        (None, None) => None,
    };
    let (measurements, mut notes) = request.measurements()?;
    let analysis = analyse(measurements, settings)?;
    notes.extend(analysis.warnings());
    if let (Some(given), Some(file)) = (request.response_quantity, analysis.file_quantity) {
        if given != file {
            notes.push(format!(
                "the records' FRF is of {} ({}), but {} ({}) was asked for: the response is taken as {}, and the file's units are overridden",
                file.name(),
                file.frf_unit(),
                given.name(),
                given.frf_unit(),
                given.name()
            ));
        }
    }
    let q = request
        .response_quantity
        .or(analysis.file_quantity)
        .unwrap_or_else(|| named_quantity(&analysis.channels));
    let overlay = match at {
        Some((m, sensor)) => {
            let (overlay, h) = ModelOverlay::new(&m.model, sensor, q, &analysis.frequency_hz)
                .map_err(|source| CommandError::Overlay {
                    model: m.label(),
                    source,
                })?;
            Some(Overlay { overlay, h })
        }
        None => None,
    };
    let output = FrfOutput::new(&analysis, q, overlay.as_ref().map(|o| o.overlay.clone()));
    // The model's unit warnings first, then the records' notes (not the
    // model's: they carry no model name).
    let mut warnings = model.map_or_else(Vec::new, ModelInput::unit_warnings);
    let model_warnings = warnings.len();
    warnings.extend(notes);
    let document = Run {
        output,
        warnings,
        model_sha256: model.map(|m| m.sha256.clone()),
        model_warnings,
    };
    Ok(FrfRun {
        analysis,
        quantity: q,
        overlay,
        document,
    })
}

/// What the response channels' names say they measure, when they all say
/// the same: `impulse` and `transient` name a sensor's CSV column
/// `<sensor>_<quantity>`, and a UFF record's name carries its ordinate
/// type's (`tip (velocity)`). Velocity otherwise.
fn named_quantity(channels: &[[String; 2]]) -> ResponseQuantity {
    let mut names = channels
        .iter()
        .map(|[_, response]| ResponseQuantity::named(response));
    match names.next() {
        Some(Some(first)) if names.all(|q| q == Some(first)) => first,
        _ => ResponseQuantity::Velocity,
    }
}

impl FrfRun {
    /// The command line's table of the identified modes.
    pub fn text(&self) -> String {
        frf_table(&self.analysis, self.quantity)
    }

    /// The spectra as CSV (`--csv`): frequency, H1, H2, coherence and the
    /// fitted model.
    pub fn csv(&self) -> String {
        frf_csv(&self.analysis)
    }

    /// H1 and the coherence as UFF 58 (`--uff`), stamped with the model's
    /// hash (`none` without a model).
    pub fn uff(&self) -> String {
        frf_uff(
            &self.analysis,
            self.quantity,
            self.document.model_sha256.as_deref(),
        )
    }

    /// The figure (`--plot`): FRF magnitude and phase with the fit and the
    /// model's FRF, the coherence, the stabilization diagram; rendered as
    /// `format`.
    pub fn plot(&self, format: Format) -> Result<Vec<u8>, CommandError> {
        let a = &self.analysis;
        let label = self.overlay.as_ref().map(|o| o.overlay.label());
        let overlay = self
            .overlay
            .as_ref()
            .zip(label.as_deref())
            .map(|(o, label)| (label, a.frequency_hz.as_slice(), o.h.as_slice()));
        let figure: Figure = frf_figure(a, self.quantity, overlay).into();
        let size = PlotSize {
            height: 1100,
            ..PlotSize::default()
        };
        Ok(render(&figure, format, size)?)
    }

    /// Draws the figure to `path` (.svg or .png).
    pub fn write_plot(&self, path: &Path) -> Result<(), CommandError> {
        let bytes = self.plot(Format::from_path(path)?)?;
        crate::output::files::write_atomic(path, &bytes)?;
        Ok(())
    }
}
