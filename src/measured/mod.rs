//! Measured data in, modal data out: hammer-test records, frequency-response
//! estimates, modal parameters and the files that carry them between this
//! tool and the usual experimental-modal-analysis tools (pyFRF,
//! sdypy-EMA, pyuff).
//!
//! The flow is one way:
//!
//! * [`csv`] and [`uff`] read *records*: a force and a response sampled
//!   together at a uniform rate (time data, [`TimeRecord`]), or an FRF
//!   already estimated elsewhere ([`MeasuredFrf`]). Bad files are typed
//!   errors naming the file and line ([`MeasuredError`]).
//! * [`frf`] checks that the hits of one test agree (rate, length) and
//!   averages them with the one estimator of [`crate::signal::frf`]
//!   (H1, H2, coherence), windowed by [`crate::signal::Window`];
//! * [`analysis`] runs the hammer-test pipeline: the band the hammer
//!   excited, the modal fit of [`crate::signal::fit`] over it and over the
//!   rest of the spectrum, and the modes outside the band;
//! * [`band`] chooses that band from the force spectrum;
//! * [`experiment`] picks the fitted mode `identify` compares the model
//!   with (a peak of the fit and of the records) and checks it against
//!   the records.
//!
//! Units: time in s, frequency in Hz, force in N, response in the unit of
//! its quantity (m, m/s or m/s²); an FRF is response per newton.

pub mod analysis;
pub mod band;
pub mod csv;
pub mod cut_off;
pub mod error;
pub mod experiment;
pub mod frf;
mod quantity;
pub mod record_checks;
pub mod uff;

pub use error::MeasuredError;
pub use quantity::ResponseQuantity;

use std::path::{Path, PathBuf};

use realfft::num_complex::Complex64;

/// Fewest samples a time record must have.
pub const MIN_SAMPLES: usize = 16;

/// One hit: force and response sampled together at a uniform rate.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeRecord {
    /// The file it came from, for messages.
    pub file: PathBuf,
    /// Samples per second, Hz.
    pub sample_rate_hz: f64,
    /// Force, N.
    pub force: Vec<f64>,
    /// Response, in the unit of its quantity.
    pub response: Vec<f64>,
    /// Names of the two channels (header or UFF labels).
    pub force_label: String,
    pub response_label: String,
    /// The file line (1-based) of each sample, for messages; empty for
    /// a record given as arrays (messages then name 0-based samples).
    pub lines: Vec<usize>,
}

impl TimeRecord {
    /// Record length n/fs, s.
    pub fn duration(&self) -> f64 {
        self.force.len() as f64 / self.sample_rate_hz
    }
}

/// An FRF read from a file (UFF 58 function type 4), with its coherence if
/// the file holds one.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredFrf {
    pub file: PathBuf,
    pub frequency_hz: Vec<f64>,
    pub h: Vec<Complex64>,
    pub coherence: Option<Vec<f64>>,
    /// What the response measures, when the file says (a UFF 58 FRF's
    /// ordinate type: 8 displacement, 11 velocity, 12 acceleration).
    pub quantity: Option<ResponseQuantity>,
}

/// What a measurement file holds.
#[derive(Debug, Clone, PartialEq)]
pub enum Measurement {
    Time(TimeRecord),
    Frf(MeasuredFrf),
}

/// A channel chosen by header name (or UFF label) or by 1-based index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Channel {
    Name(String),
    Index(usize),
}

impl std::str::FromStr for Channel {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        if s.is_empty() {
            return Err("a channel is a column name or a 1-based index".into());
        }
        match s.parse::<usize>() {
            Ok(0) => Err("channel indices start at 1".into()),
            Ok(i) => Ok(Channel::Index(i)),
            Err(_) => Ok(Channel::Name(s.to_string())),
        }
    }
}

impl std::fmt::Display for Channel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Channel::Name(n) => write!(f, "{n}"),
            Channel::Index(i) => write!(f, "{i}"),
        }
    }
}

/// Which channels hold the force and the response. CSV: columns (default
/// the 2nd and 3rd, the 1st being time). UFF: records (default the first
/// force record and the first other record).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Channels {
    pub force: Option<Channel>,
    pub response: Option<Channel>,
}

/// Reads one measurement file: UFF when its first non-blank line is `-1`,
/// CSV otherwise. Time records are checked for a usable force (not all
/// zero, a single impact). The notes of the reading are dropped
/// ([`read_measurement_noted`] keeps them).
pub fn read_measurement(path: &Path, channels: &Channels) -> Result<Measurement, MeasuredError> {
    Ok(read_measurement_noted(path, channels)?.0)
}

/// [`read_measurement`] with the notes the user must see: the UFF datasets
/// the file holds but the tool does not use, which were skipped
/// ([`uff::skipped_note`]).
pub fn read_measurement_noted(
    path: &Path,
    channels: &Channels,
) -> Result<(Measurement, Vec<String>), MeasuredError> {
    let bytes = std::fs::read(path).map_err(|io| MeasuredError::Read {
        file: path.to_path_buf(),
        io,
    })?;
    parse_measurement_noted(path, &bytes, channels)
}

/// [`read_measurement`] on the bytes of a file already read; `path` names
/// it in messages.
pub fn parse_measurement(
    path: &Path,
    bytes: &[u8],
    channels: &Channels,
) -> Result<Measurement, MeasuredError> {
    Ok(parse_measurement_noted(path, bytes, channels)?.0)
}

/// [`read_measurement_noted`] on the bytes of a file already read.
pub fn parse_measurement_noted(
    path: &Path,
    bytes: &[u8],
    channels: &Channels,
) -> Result<(Measurement, Vec<String>), MeasuredError> {
    let text = String::from_utf8_lossy(bytes);
    let first = text.lines().map(str::trim).find(|l| !l.is_empty());
    let (m, notes) = match first {
        None => {
            return Err(MeasuredError::Empty {
                file: path.to_path_buf(),
            })
        }
        Some("-1") => {
            let (m, note) = uff::measurement_from_uff(path, bytes, channels)?;
            (m, note.into_iter().collect())
        }
        Some(_) => (
            Measurement::Time(csv::parse_csv(path, &text, channels)?),
            Vec::new(),
        ),
    };
    if let Measurement::Time(r) = &m {
        check_force(r)?;
    }
    Ok((m, notes))
}

/// Force fraction of the peak below which an impact has ended.
pub const IMPACT_END_FRACTION: f64 = 0.05;
/// Force fraction of the peak that, after the impact ended, is a second hit.
pub const DOUBLE_IMPACT_FRACTION: f64 = 0.2;

/// The force must not be all zero, and must hold one impact: after the
/// force falls below 5 % of its peak it must not rise again above 20 %.
/// (For random or sine excitation this check does not apply; it is only
/// called on records that look like impacts, i.e. whose force peak is at
/// least ten times its RMS.)
pub fn check_force(r: &TimeRecord) -> Result<(), MeasuredError> {
    let (peak_i, peak) = r
        .force
        .iter()
        .map(|v| v.abs())
        .enumerate()
        .fold((0, 0.0), |acc, (i, v)| if v > acc.1 { (i, v) } else { acc });
    if peak == 0.0 {
        return Err(MeasuredError::ZeroForce {
            file: r.file.clone(),
            channel: r.force_label.clone(),
        });
    }
    let rms = (r.force.iter().map(|v| v * v).sum::<f64>() / r.force.len() as f64).sqrt();
    if peak < 10.0 * rms {
        return Ok(());
    }
    let Some(end) =
        (peak_i..r.force.len()).find(|&i| r.force[i].abs() < IMPACT_END_FRACTION * peak)
    else {
        return Ok(());
    };
    if let Some(j) =
        (end..r.force.len()).find(|&i| r.force[i].abs() > DOUBLE_IMPACT_FRACTION * peak)
    {
        let percent = 100.0 * r.force[j].abs() / peak;
        return Err(match (r.lines.get(j), r.lines.get(end)) {
            (Some(&line), Some(&end_line)) => MeasuredError::DoubleImpact {
                file: r.file.clone(),
                line,
                end_line,
                percent,
            },
            _ => MeasuredError::DoubleImpactInSamples {
                file: r.file.clone(),
                sample: j,
                end_sample: end,
                percent,
            },
        });
    }
    Ok(())
}
