//! `ancf-modal frf`: measured hammer records (CSV or UFF 58) or a measured
//! FRF in, H1/H2/coherence and the identified modes out.

use super::common::write_output;
use ancf_modal::measured::analysis::{analyse, AnalysisSettings, Estimator, FrfAnalysis};
use ancf_modal::measured::{read_measurement_noted, Channel, Channels};
use ancf_modal::output::frf_report::{frf_csv, frf_figure, frf_table, frf_uff, ResponseQuantity};
use ancf_modal::output::plot::{render, Figure, Format, PlotSize};
use ancf_modal::results::fit::{FrfOutput, ModelOverlay};
use ancf_modal::signal::Window;
use anyhow::Result;
use clap::Args;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct FrfArgs {
    /// Measurement files: CSV (header row; time in the first column) or UFF
    /// 58 (time records, or an FRF). Several hits are averaged.
    #[arg(required = true, value_name = "SIGNALS")]
    pub files: Vec<PathBuf>,
    #[command(flatten)]
    pub output: super::output::OutputArgs,
    #[command(flatten)]
    pub measured: MeasuredArgs,
    /// Overlay this model's FRF (modal superposition, its Rayleigh damping
    /// or 0.5 % if it has none) at the sensor --at, per newton of its first
    /// load.
    #[arg(long, value_name = "MODEL.json", requires = "at")]
    pub model: Option<PathBuf>,
    /// The model's sensor for --model.
    #[arg(long, value_name = "SENSOR", requires = "model")]
    pub at: Option<String>,
}

/// The model's FRF on the measured frequencies (the library's defaults:
/// [`ancf_modal::results::fit::OVERLAY_MODES`] modes, its Rayleigh damping
/// or [`ancf_modal::results::fit::OVERLAY_DAMPING_RATIO`]), its values and
/// the model file's SHA-256.
fn model_overlay(
    path: &std::path::Path,
    sensor: &str,
    q: ResponseQuantity,
    f: &[f64],
) -> Result<(ModelOverlay, Vec<realfft::num_complex::Complex64>, String)> {
    use anyhow::Context;
    let bytes =
        std::fs::read(path).with_context(|| format!("{}: cannot read the file", path.display()))?;
    let sha = ancf_modal::results::provenance::sha256_hex(&bytes);
    let model = ancf_modal::Model::from_file(path)?;
    super::common::check_units(&model, Some(path));
    let (overlay, h) =
        ModelOverlay::new(&model, sensor, q, f).with_context(|| path.display().to_string())?;
    Ok((overlay, h, sha))
}

/// How measurement files are read and analysed (shared with `identify
/// --measured`).
#[derive(Debug, Args, Clone)]
pub struct MeasuredArgs {
    /// Force channel: CSV column name or 1-based index (default the one
    /// column whose name holds `force`, else 2), UFF record label or index (default
    /// the force record).
    #[arg(long, value_name = "COL")]
    pub force: Option<Channel>,
    /// Response channel: CSV column name or 1-based index (default the
    /// first column after time that is not the force).
    #[arg(long, value_name = "COL")]
    pub response: Option<Channel>,
    /// What the response measures (the FRF's unit).
    #[arg(long, value_enum, default_value_t = Quantity::Velocity)]
    pub response_quantity: Quantity,
    /// rect, hann, flattop, blackman, force:P (keep the first fraction P of
    /// the force record), exponential:P (decay to P at the end; its damping
    /// is removed).
    #[arg(long, default_value = "rect")]
    pub window: Window,
    /// FRF estimator the modal fit uses.
    #[arg(long, value_enum, default_value_t = EstimatorArg::H1)]
    pub estimator: EstimatorArg,
    /// Fit band LO:HI in Hz (default: where the hammer excited the
    /// structure, up to 0.8 × Nyquist).
    #[arg(long, value_name = "LO:HI", allow_hyphen_values = true, value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Highest model order of the stabilization diagram.
    #[arg(long, default_value_t = 40, allow_hyphen_values = true, value_parser = |s: &str| super::values::whole(s, 2, Some(200)))]
    pub max_order: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Quantity {
    Displacement,
    Velocity,
    Acceleration,
}

impl From<Quantity> for ResponseQuantity {
    fn from(q: Quantity) -> Self {
        match q {
            Quantity::Displacement => ResponseQuantity::Displacement,
            Quantity::Velocity => ResponseQuantity::Velocity,
            Quantity::Acceleration => ResponseQuantity::Acceleration,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum EstimatorArg {
    H1,
    H2,
}

pub fn parse_band(s: &str) -> Result<(f64, f64), String> {
    let (a, b) = s
        .split_once(':')
        .ok_or_else(|| format!("`{s}` is not LO:HI (Hz)"))?;
    let lo = super::args::finite(a)?;
    let hi = super::args::finite(b)?;
    if lo >= 0.0 && hi > lo {
        Ok((lo, hi))
    } else {
        Err(format!("the band needs 0 ≤ LO < HI, got {lo}:{hi}"))
    }
}

impl MeasuredArgs {
    /// Reads the files and runs the analysis.
    pub fn analyse(&self, files: &[PathBuf]) -> Result<FrfAnalysis> {
        let channels = Channels {
            force: self.force.clone(),
            response: self.response.clone(),
        };
        let read = files
            .iter()
            .map(|f| read_measurement_noted(f, &channels))
            .collect::<Result<Vec<_>, _>>()?;
        // The UFF datasets skipped: a warning line and `warnings` in JSON.
        let measurements = read
            .into_iter()
            .map(|(m, notes)| {
                notes.into_iter().for_each(super::common::warn);
                m
            })
            .collect();
        let analysis = analyse(
            measurements,
            AnalysisSettings {
                window: self.window,
                estimator: match self.estimator {
                    EstimatorArg::H1 => Estimator::H1,
                    EstimatorArg::H2 => Estimator::H2,
                },
                band: self.band,
                max_order: self.max_order as usize,
            },
        )?;
        analysis
            .warnings()
            .into_iter()
            .for_each(super::common::warn);
        Ok(analysis)
    }
}

pub fn run(args: FrfArgs) -> Result<()> {
    let a = args.measured.analyse(&args.files)?;
    let q: ResponseQuantity = args.measured.response_quantity.into();
    let overlay = match (&args.model, &args.at) {
        (Some(m), Some(at)) => Some(model_overlay(m, at, q, &a.frequency_hz)?),
        _ => None,
    };
    let sha = overlay.as_ref().map(|o| o.2.as_str());
    let label = overlay.as_ref().map(|o| o.0.label());
    // Everything is rendered before anything is written: an error leaves
    // no output file behind.
    let plot = match &args.output.plot {
        Some(p) => {
            let ov = overlay
                .as_ref()
                .zip(label.as_ref())
                .map(|((_, h, _), label)| {
                    (label.as_str(), a.frequency_hz.as_slice(), h.as_slice())
                });
            let fig: Figure = frf_figure(&a, q, ov).into();
            let size = PlotSize {
                height: 1100,
                ..PlotSize::default()
            };
            Some((p, render(&fig, Format::from_path(p)?, size)?))
        }
        None => None,
    };
    let csv = args.output.csv.as_ref().map(|p| (p, frf_csv(&a)));
    let uff = args.output.uff.as_ref().map(|p| (p, frf_uff(&a, q, sha)));
    if let Some((p, bytes)) = plot {
        ancf_modal::output::files::write_atomic(p, &bytes)?;
    }
    if let Some((p, text)) = csv {
        write_output(p, &text)?;
    }
    if let Some((p, text)) = uff {
        write_output(p, &text)?;
    }
    if args.output.json {
        let sha = sha.map(str::to_string);
        let doc = FrfOutput::new(&a, q, overlay.map(|o| o.0));
        let doc = ancf_modal::results::document(&doc, sha.as_deref(), &super::common::warnings())?;
        outln!("{}", serde_json::to_string_pretty(&doc)?);
    } else {
        out!("{}", frf_table(&a, q));
    }
    Ok(())
}
