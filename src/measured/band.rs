//! The automatic fit band of a hammer test: where the measured FRF carries
//! the structure and not noise.
//!
//! H1 = G_fx/G_ff is meaningful only where the hammer put energy in *and*
//! the response stands above the measurement noise. With several hits the
//! coherence shows both; with one hit γ² ≡ 1 and shows nothing, so two
//! spectra bound the band instead, and it ends at the lower of:
//!
//! - **the force drop**: the highest frequency at which the force spectrum
//!   G_ff (smoothed) is within 20 dB of its peak; beyond it the hammer
//!   excited nothing and H1 divides noise by almost nothing;
//! - **the noise floor**: the highest frequency at which the response
//!   spectrum G_xx (smoothed, unwindowed) stands 10 dB above the noise
//!   floor. The floor is the spectrum of the record's quiet tail (its last
//!   eighth, where a hammer response has decayed), scaled by the length
//!   ratio: white noise of variance σ² gives E|X(f)|² = nσ² for n samples
//!   in an unscaled DFT. A tail whose mean square is not 10 dB under the
//!   record's first eighth is no quiet tail (the response still rings
//!   there), and sets no floor;
//!
//! and at 0.8 × Nyquist (where anti-aliasing filters act) when neither
//! comes first. Spectra are smoothed by a moving average over ±0.5 % of
//! the bins (at least ±2), so a single noise bin does not decide.
//! Frequencies in Hz, spectra in (unit)² of an unscaled DFT.

use super::TimeRecord;
use crate::signal::spectrum::power_spectrum;

/// Force level (dB below its maximum) that bounds the automatic band.
pub const FORCE_BAND_DB: f64 = 20.0;
/// Margin (dB) by which the response must stand above the noise floor.
pub const NOISE_MARGIN_DB: f64 = 10.0;
/// Fraction of the record taken as its quiet tail.
pub const TAIL_FRACTION: f64 = 0.125;
/// Upper limit of the automatic band, as a fraction of Nyquist.
pub const NYQUIST_FRACTION: f64 = 0.8;

/// What ended the fit band.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BandEnd {
    /// The band was given (`band` of the settings).
    Given,
    /// The force spectrum fell 20 dB below its peak.
    ForceDrop,
    /// The response spectrum reached the noise floor of the quiet tail.
    NoiseFloor,
    /// 0.8 × Nyquist (or the FRF's last frequency).
    Limit,
}

impl BandEnd {
    /// The reason in words, for tables and JSON.
    pub fn describe(self) -> &'static str {
        match self {
            BandEnd::Given => "as given",
            BandEnd::ForceDrop => "where the force spectrum is 20 dB below its peak",
            BandEnd::NoiseFloor => {
                "where the response spectrum reaches the noise floor of the record's quiet tail"
            }
            BandEnd::Limit => "at 0.8 × Nyquist",
        }
    }

    /// A short key for JSON (`given`, `force_drop`, `noise_floor`, `limit`).
    pub fn key(self) -> &'static str {
        match self {
            BandEnd::Given => "given",
            BandEnd::ForceDrop => "force_drop",
            BandEnd::NoiseFloor => "noise_floor",
            BandEnd::Limit => "limit",
        }
    }
}

/// Moving average over ±`half` bins (shorter at the ends).
fn smooth(v: &[f64], half: usize) -> Vec<f64> {
    let mut prefix = Vec::with_capacity(v.len() + 1);
    prefix.push(0.0);
    for x in v {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + x);
    }
    (0..v.len())
        .map(|k| {
            let (a, b) = (k.saturating_sub(half), (k + half + 1).min(v.len()));
            (prefix[b] - prefix[a]) / (b - a) as f64
        })
        .collect()
}

fn half_width(bins: usize) -> usize {
    (bins / 200).max(2)
}

/// Highest bin at which the smoothed `spectrum` is at least `floor(k)`.
fn last_above(spectrum: &[f64], floor: impl Fn(usize) -> f64) -> Option<usize> {
    let s = smooth(spectrum, half_width(spectrum.len()));
    s.iter().enumerate().rposition(|(k, v)| *v >= floor(k))
}

/// The last bin of the response above the noise floor of the records'
/// quiet tails (module doc); `None` when the records are too short.
fn noise_floor_end(records: &[TimeRecord], bins: usize) -> Option<usize> {
    let n = records.first()?.response.len();
    let m = (n as f64 * TAIL_FRACTION) as usize;
    if m < 16 || bins < 2 {
        return None;
    }
    let mut response = vec![0.0; bins];
    let mut tail = vec![0.0; m / 2 + 1];
    let (mut mean_square, mut tail_square) = (0.0, 0.0);
    for r in records {
        if r.response.len() != n {
            return None;
        }
        mean_square += r.response[..m].iter().map(|x| x * x).sum::<f64>() / m as f64;
        tail_square += r.response[n - m..].iter().map(|x| x * x).sum::<f64>() / m as f64;
        for (a, p) in response.iter_mut().zip(power_spectrum(&r.response)) {
            *a += p;
        }
        for (a, p) in tail.iter_mut().zip(power_spectrum(&r.response[n - m..])) {
            *a += p;
        }
    }
    let margin = 10f64.powf(NOISE_MARGIN_DB / 10.0);
    // A tail that still rings is no floor: a response that has not decayed
    // [`NOISE_MARGIN_DB`] below its first eighth's mean square by the end
    // holds the structure there, not noise (an undamped cantilever's 0.2 s
    // record was cut at 1.16 kHz, its modes ringing to 14.6 kHz).
    if tail_square * margin >= mean_square {
        return None;
    }
    let tail = smooth(&tail, half_width(tail.len()));
    let scale = n as f64 / m as f64 * margin;
    // Bin k of the full record is at k/n of the rate; in the tail that is
    // bin k·m/n.
    let floor = |k: usize| {
        let x = k as f64 * m as f64 / n as f64;
        let i = (x.floor() as usize).min(tail.len() - 1);
        let j = (i + 1).min(tail.len() - 1);
        let w = x - i as f64;
        scale * ((1.0 - w) * tail[i] + w * tail[j])
    };
    last_above(&response, floor)
}

/// The automatic band over `frequency_hz` and what ended it: from the
/// second bin to the lowest of the force drop, the noise floor (time
/// records only) and 0.8 × the last frequency (module doc).
pub fn automatic_band(
    frequency_hz: &[f64],
    force_power: Option<&[f64]>,
    records: &[TimeRecord],
) -> ((f64, f64), BandEnd) {
    let n = frequency_hz.len();
    let lo = frequency_hz.get(1).copied().unwrap_or(0.0);
    let top = frequency_hz.last().copied().unwrap_or(0.0);
    let mut end = (NYQUIST_FRACTION * top, BandEnd::Limit);
    if let Some(g) = force_power.filter(|g| g.len() == n) {
        let s = smooth(g, half_width(n));
        let max = s.iter().cloned().fold(0.0, f64::max);
        let floor = max * 10f64.powf(-FORCE_BAND_DB / 10.0);
        if let Some(k) = s.iter().rposition(|v| *v >= floor) {
            if frequency_hz[k] < end.0 {
                end = (frequency_hz[k], BandEnd::ForceDrop);
            }
        }
    }
    if let Some(k) = noise_floor_end(records, n) {
        if frequency_hz[k] < end.0 {
            end = (frequency_hz[k], BandEnd::NoiseFloor);
        }
    }
    ((lo, end.0.max(lo)), end.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn smoothing_keeps_a_constant_and_averages_a_step() {
        assert_eq!(smooth(&[2.0; 7], 2), vec![2.0; 7]);
        let s = smooth(&[0.0, 0.0, 0.0, 3.0, 3.0, 3.0], 1);
        assert_eq!(s, vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0]);
    }
}
