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
//! **Short records.** A mode of damping ζ at f spreads over 2ζf Hz, a
//! record of T s resolves lines 1/T apart: a fit that finds nothing in a
//! record a few lines per mode long says how long the record was.

use super::TimeRecord;

/// Samples from the first to the last at which |x| reaches a tenth of
/// its peak (module doc); 0 for a silent channel.
pub fn active_span(x: &[f64]) -> usize {
    let peak = x.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if peak <= 0.0 {
        return 0;
    }
    let loud = |v: &f64| v.abs() >= 0.1 * peak;
    match (x.iter().position(loud), x.iter().rposition(loud)) {
        (Some(first), Some(last)) => last - first,
        _ => 0,
    }
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
