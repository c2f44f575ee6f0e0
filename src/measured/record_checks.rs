//! Signs in the records themselves that a fit's output would not show:
//! channels that look swapped, and records too short to resolve a mode.
//!
//! **Swapped channels.** A hammer's force is a blow of a fraction of a
//! millisecond; the response rings for as long as the structure's decay
//! lasts. The span over which a channel stands at or above a tenth of its
//! peak (first to last such sample) is therefore shorter for the force
//! than for the response, noise on either channel well under a tenth of
//! its peak not counting (a span of the channel's energy would: noise
//! spread over a long record holds a share of a blow's energy). A record
//! whose force channel spans over twice its response's has them swapped,
//! or a force that is not a blow.
//!
//! **Noise on the force.** Outside the blow a force transducer records
//! only noise. Its variance σ², taken over the samples farther than four
//! blow spans from it ([`force_noise_variance`]), is what the records
//! say of the force's noise without a fit: it inflates G_ff by hits·σ²Σw²
//! under the force window w, a share ε of G_ff. To first order that lowers
//! the H1 of several hits by ε(1 − 1/hits) (one hit's H1 = X/F is not
//! lowered on average) and scatters it by √(ε/(hits(1 − ε)))
//! ([`crate::signal::frf::CrossSpectra::force_noise_share`]).
//!
//! **Slow sampling.** A hammer record sampled below 20 Hz has its time
//! in other units than seconds ([`slow_sampling`]).
//!
//! **Ringing at the end.** A mode whose decay hardly falls over the
//! records has its residue undetermined ([`ringing_at_end`]).
//!
//! **Short records.** A mode of damping ζ at f spreads over 2ζf Hz, a
//! record of T s resolves lines 1/T apart: a fit that finds nothing in a
//! record a few lines per mode long says how long the record was.

use super::frf::FrfEstimate;
use super::TimeRecord;
use crate::signal::Window;

/// The largest |x|.
fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// The first and the last sample at which |x| reaches a tenth of its
/// peak; `None` for a silent channel.
fn loud_range(x: &[f64]) -> Option<(usize, usize)> {
    let peak = peak(x);
    if peak <= 0.0 {
        return None;
    }
    let loud = |v: &f64| v.abs() >= 0.1 * peak;
    Some((x.iter().position(loud)?, x.iter().rposition(loud)?))
}

/// Samples from the first to the last at which |x| reaches a tenth of
/// its peak (module doc); 0 for a silent channel.
pub fn active_span(x: &[f64]) -> usize {
    loud_range(x).map_or(0, |(first, last)| last - first)
}

/// Fewest samples outside the blow for a force-noise estimate.
pub const MIN_NOISE_SAMPLES: usize = 64;

/// The variance of a record's force outside its blow, N² (module doc):
/// the samples farther than four times the blow's span (at least 32
/// samples: an anti-alias filter's ringing belongs to the blow) from the
/// first and the last sample at a tenth of its peak, about their mean.
/// `None` with fewer than [`MIN_NOISE_SAMPLES`] such samples or a silent
/// channel.
pub fn force_noise_variance(force: &[f64]) -> Option<f64> {
    let (first, last) = loud_range(force)?;
    let margin = (4 * (last - first)).max(MIN_NOISE_SAMPLES / 2);
    let quiet: Vec<f64> = force[..first.saturating_sub(margin)]
        .iter()
        .chain(force.get(last + margin + 1..).unwrap_or(&[]))
        .copied()
        .collect();
    if quiet.len() < MIN_NOISE_SAMPLES {
        return None;
    }
    let n = quiet.len() as f64;
    let mean = quiet.iter().sum::<f64>() / n;
    Some(quiet.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n)
}

/// Smallest H1 bias from noise on the force (the share ε of G_ff it
/// makes) that is said.
pub const FORCE_NOISE_BIAS: f64 = 0.01;

/// A note when the noise the force records show outside their blows
/// biases H1 somewhere in the fit band by over [`FORCE_NOISE_BIAS`] (module
/// doc; the median and the largest bias over the band are said, and the
/// scatter at the median). Unless the window already is one, a `force:P`
/// window that keeps twice the blows' span is suggested (it keeps the
/// blow and cuts the noise).
pub fn force_noise_note(
    records: &[TimeRecord],
    estimate: &FrfEstimate,
    band: (f64, f64),
) -> Option<String> {
    let noise = &estimate.force_noise;
    let first = records.first()?;
    let mut share: Vec<f64> = estimate
        .frequency_hz
        .iter()
        .zip(&noise.share)
        .filter(|(f, _)| **f >= band.0 && **f <= band.1)
        .map(|(_, e)| *e)
        .collect();
    share.sort_by(f64::total_cmp);
    let (Some(&median), Some(&worst)) = (share.get(share.len() / 2), share.last()) else {
        return None;
    };
    if noise.variance <= 0.0 || worst < FORCE_NOISE_BIAS {
        return None;
    }
    let hits = estimate.averages.max(1) as f64;
    let scatter = (median / (hits * (1.0 - median).max(f64::MIN_POSITIVE))).sqrt();
    let peak = peak(&first.force);
    let rms = noise.variance.sqrt();
    // To first order E[H1]/H = 1 − ε(1 − 1/hits): one hit's H1 = X/F is
    // scattered by the noise, not lowered; an average over hits is
    // lowered by the noise power its Σ|F|² holds.
    let lowered = match estimate.averages {
        0 | 1 => "which a single hit's H1 = X/F does not lower on average".to_string(),
        n => format!(
            "which lowers the {n} hits' H1 by about {:.1} % (ε(1 − 1/hits))",
            100.0 * median * (1.0 - 1.0 / n as f64)
        ),
    };
    let effect = format!(
        "the force channel `{}` shows noise outside the blow (RMS {rms:.3e} N, {:.2} % of its peak): over the fit band it makes a median ε = {:.1} % of Σ|F|² (up to {:.1} % where the force is weakest), {lowered}, and scatters H1 by ±{:.1} % per line",
        first.force_label,
        100.0 * rms / peak.max(f64::MIN_POSITIVE),
        100.0 * median,
        100.0 * worst,
        100.0 * scatter
    );
    if matches!(estimate.window, Window::Force { .. }) {
        return Some(format!("{effect}; more hits average the scatter down"));
    }
    let blow_end = records
        .iter()
        .filter_map(|r| loud_range(&r.force).map(|(_, last)| last))
        .max()
        .unwrap_or(0);
    let keep =
        (2.0 * (blow_end + 1) as f64 / estimate.samples.max(1) as f64 * 100.0).ceil() / 100.0;
    Some(format!(
        "{effect}; a force:{} window keeps the blow and cuts that noise",
        keep.clamp(0.01, 1.0)
    ))
}

/// A note per record whose force spans over twice its response (module
/// doc).
pub fn swapped_channels(records: &[TimeRecord]) -> Vec<String> {
    records
        .iter()
        .filter_map(|r| {
            let (f, x) = (active_span(&r.force), active_span(&r.response));
            (f > 2 * x).then(|| {
                let ms = |n: usize| 1e3 * n as f64 / r.sample_rate_hz;
                format!(
                    "{}: the force channel `{}` stands above a tenth of its peak for {:.3} ms, the response `{}` for {:.3} ms; a hammer's blow is the shorter: are the channels swapped?",
                    r.file.display(),
                    r.force_label,
                    ms(f),
                    r.response_label,
                    ms(x)
                )
            })
        })
        .collect()
}

/// Slowest sample rate of a hammer record taken as meant, Hz: a blow
/// lasts milliseconds, and even a bridge's hammer test samples at
/// hundreds of hertz. A time column in ms read as seconds makes a
/// 2048 Hz record a 2.048 Hz one.
pub const MIN_HAMMER_RATE_HZ: f64 = 20.0;

/// A note when the records are sampled below [`MIN_HAMMER_RATE_HZ`].
pub fn slow_sampling(records: &[TimeRecord]) -> Option<String> {
    let r = records.first()?;
    (r.sample_rate_hz < MIN_HAMMER_RATE_HZ).then(|| {
        format!(
            "{}: the records are sampled at {} Hz, below the {MIN_HAMMER_RATE_HZ} Hz of any hammer test: is the time in ms or µs? (a CSV time column is read in ms or µs when its name says so: time_ms, t [us])",
            r.file.display(),
            crate::model::number::significant(r.sample_rate_hz, 4)
        )
    })
}

/// Largest amplitude e^(Re(s)·T) a mode's decay may keep at the records'
/// end, without its residue tied to it ([`super::cut_off`]), for its
/// residue (and |H| at its peak) to be given: the decay cut off there
/// enters H1 as a term of the same pole, weighted by 1/F, which for a
/// short blow is nearly a constant multiple of the residue's term.
pub const RINGING_AT_END: f64 = 0.05;

/// A note naming the modes (those whose residue [`super::cut_off`] could
/// not tie to their cut-off decay) whose decay, under the window's when
/// one decays, keeps over [`RINGING_AT_END`] of its amplitude at the
/// records' end: their residues and peak |H| are not determined.
pub fn ringing_at_end(
    modes: &[crate::signal::fit::FittedMode],
    estimate: &FrfEstimate,
) -> Option<String> {
    let duration = estimate.samples as f64 / estimate.sample_rate_hz;
    let ringing: Vec<String> = modes
        .iter()
        .filter_map(|m| {
            let left = ((m.pole.re - estimate.window_decay_rate) * duration).exp();
            (left > RINGING_AT_END).then(|| {
                format!(
                    "{} Hz (e^(Re(s)T) = {})",
                    crate::model::number::significant(m.frequency_hz, 6),
                    crate::model::number::significant(left, 2)
                )
            })
        })
        .collect();
    (!ringing.is_empty()).then(|| {
        format!(
            "still ringing at the records' end: {}; the decay cut off there hardly falls over the record, so it cannot be told from the residue: these modes' residues and |H| at their peaks are not determined (their frequencies and damping are); records long enough for the decay to fall under {RINGING_AT_END} of its start, or an exponential window, determine them",
            ringing.join(", ")
        )
    })
}

/// A note when a fit of time records found no mode: their length and line
/// spacing (module doc).
pub fn short_records(records: &[TimeRecord], modes_found: usize) -> Option<String> {
    let r = records.first()?;
    if modes_found > 0 || r.sample_rate_hz <= 0.0 {
        return None;
    }
    let t = r.force.len() as f64 / r.sample_rate_hz;
    Some(format!(
        "no mode found: the records last {:.4} s, so their lines are {:.3} Hz apart; a mode of damping ζ at f spans 2ζf Hz, and one narrower than a few lines is not resolved (longer records resolve more)",
        t,
        1.0 / t
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A blow of 5 samples spans at most 5; a decay e^(−k/τ) spans
    /// τ ln 10 (where it falls to a tenth), and with noise of ±3 % of its
    /// peak within the bounds that noise allows; a silent channel spans 0.
    #[test]
    fn spans_of_a_blow_and_a_decay() {
        let mut blow = vec![0.0; 4096];
        for (k, v) in blow.iter_mut().enumerate().skip(10).take(5) {
            *v = (std::f64::consts::PI * (k - 9) as f64 / 6.0).sin();
        }
        assert!(active_span(&blow) <= 5);
        let tau = 200.0;
        let closed = tau * 10f64.ln();
        let mut state = 7_u64;
        let mut noise = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
            0.03 * (((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0)
        };
        for noisy in [false, true] {
            let decay: Vec<f64> = (0..4096)
                .map(|k| (-(k as f64) / tau).exp() + if noisy { noise() } else { 0.0 })
                .collect();
            let span = active_span(&decay) as f64;
            // Noise ±a moves the peak within 1 ± a and the crossing of a
            // tenth of it within e^(−k/τ) = 0.1(1 ± a) ± a.
            let (lo, hi) = if noisy {
                let a: f64 = 0.03;
                (
                    tau * (1.0 / (0.1 * (1.0 + a) + a)).ln() - 1.0,
                    tau * (1.0 / (0.1 * (1.0 - a) - a)).ln() + 1.0,
                )
            } else {
                (closed - 1.0, closed + 1.0)
            };
            assert!(
                span >= lo && span <= hi,
                "{span} outside [{lo}, {hi}] (closed form {closed})"
            );
        }
        assert_eq!(active_span(&[0.0; 8]), 0);
    }

    /// A 0.05 s record at 10,240 Hz has lines 1/T = 20 Hz apart; the
    /// note is given only when the fit found nothing.
    #[test]
    fn a_short_record_is_said_when_nothing_is_found() {
        let r = TimeRecord {
            file: "hit.csv".into(),
            sample_rate_hz: 10_240.0,
            force: vec![0.0; 512],
            response: vec![0.0; 512],
            force_label: "force".into(),
            response_label: "vel".into(),
            lines: (2..514).collect(),
        };
        let note = short_records(std::slice::from_ref(&r), 0).unwrap();
        assert!(
            note.contains("0.0500 s") && note.contains("20.000 Hz apart"),
            "{note}"
        );
        assert!(short_records(&[r], 1).is_none());
    }
}
