//! Harmonics and combination tones among the fitted poles.
//!
//! A response that is not quite linear (a beam's large deflection, a
//! contact, a clamp that slips) carries beside its ringing modes
//! e^(s_i t) the terms of their products: e^((s_i + s_j)t) and
//! e^((s_i + s̄_j)t), poles at the sums and differences of the modes'
//! frequencies, decaying at the sums of their decay rates; with i = j, the
//! harmonics 2f_i, and 3f_i and 2f_i ± f_j from the cubes. The fit finds
//! them as it finds modes:
//! - the paper's blade, undamped, struck by 4 N: a pole at 9137.215 Hz,
//!   2 × 4568.611 Hz to 1e-6, with a residue 1e-5 of the mode's;
//! - a Rayleigh-damped tuning fork (modes 271, 397, 1442, 2525, 3722 Hz)
//!   struck by 5 N: poles at 668 = 271 + 397, 1171 = 1442 − 271,
//!   1839 = 1442 + 397, 2254 = 2525 − 271 Hz, … each about 1 % of the
//!   modes' level, with decay rates the sums of theirs to 5 %;
//! - the cantilever with a 0.5 g block pinned at its tip (modes
//!   126.3, 925.2, 1269.2 Hz): a pole at 1521.8 = 1269.2 + 2 × 126.3 Hz,
//!   decaying at 80.3 1/s against 68.6 + 2 × 5.6.
//!
//! A pole is taken for such a term of two modes (or of one, k ≤
//! [`HIGHEST_ORDER`]) when
//! - its frequency is their combination's within [`LINE_FRACTION`] of a
//!   line plus [`BAND_FRACTION`] of its half-power half-width in the
//!   (windowed) records;
//! - its residue is under [`RESIDUE_RATIO`] of each of theirs;
//! - its decay rate is within a factor [`DECAY_FACTOR`] of the sum of
//!   theirs, where that sum is large enough for the record to show it
//!   (over one line, 1/T).
//!
//! It stays in the fitted model, since it is in the records, and is not
//! reported as a mode.

use super::fit::FittedMode;
use std::f64::consts::PI;

/// Highest harmonic order k looked for.
pub const HIGHEST_ORDER: u32 = 3;
/// Largest distance from the combination's frequency, in lines of the FRF.
pub const LINE_FRACTION: f64 = 0.1;
/// And of its half-power half-width ζf: a damped pole's frequency is
/// fitted to a fraction of it.
pub const BAND_FRACTION: f64 = 0.25;
/// Largest |residue| of a combination, as a fraction of its modes'.
pub const RESIDUE_RATIO: f64 = 0.1;
/// Largest ratio between a combination's decay rate and the sum of its
/// modes' (either way).
pub const DECAY_FACTOR: f64 = 2.0;
/// The same for the cubic terms 2f_a ± f_b: there are four per pair of
/// modes, and with [`DECAY_FACTOR`] a real mode fell on one (a cantilever
/// with a tip mass: 155.9 Hz, decaying at 9.7 1/s, taken for 196.5 − 2 ×
/// 20.1 Hz at 15.7 1/s). The issue's own combination decays at 80.3 1/s
/// against 79.9.
pub const CUBIC_DECAY_FACTOR: f64 = 1.25;

/// For each of `modes`, whether it is a harmonic or combination tone of
/// stronger ones; `line_hz` is the FRF's line spacing [Hz], `window_decay`
/// the exponential window's decay rate [1/s] (0 without one: the poles in
/// the windowed records are that much wider). A pole taken for one is no
/// parent of another.
pub fn combinations(modes: &[FittedMode], line_hz: f64, window_decay: f64) -> Vec<bool> {
    let mut found = vec![false; modes.len()];
    // The weakest first: a parent must be ten times stronger, so the
    // strong are never taken for combinations of the weak.
    let mut order: Vec<usize> = (0..modes.len()).collect();
    order.sort_by(|&a, &b| modes[a].residue.norm().total_cmp(&modes[b].residue.norm()));
    for &i in &order {
        let m = &modes[i];
        let parents: Vec<&FittedMode> = (modes.iter().enumerate())
            .filter(|&(j, p)| {
                j != i && !found[j] && m.residue.norm() < RESIDUE_RATIO * p.residue.norm()
            })
            .map(|(_, p)| p)
            .collect();
        found[i] = terms(&parents)
            .any(|(f, sigma, factor)| matches(m, (f, sigma), factor, line_hz, window_decay));
    }
    found
}

/// The damped frequency [Hz], decay rate [1/s] and the decay's tolerance
/// factor of every harmonic and combination of `parents`.
fn terms<'a>(parents: &'a [&'a FittedMode]) -> impl Iterator<Item = (f64, f64, f64)> + 'a {
    let of = |p: &FittedMode| (p.pole.im / (2.0 * PI), -p.pole.re);
    let harmonics = parents.iter().flat_map(move |p| {
        let (f, s) = of(p);
        (2..=HIGHEST_ORDER).map(move |k| (k as f64 * f, k as f64 * s, DECAY_FACTOR))
    });
    let pairs = parents.iter().enumerate().flat_map(move |(a, p)| {
        parents[a + 1..].iter().flat_map(move |q| {
            let ((fa, sa), (fb, sb)) = (of(p), of(q));
            [
                (fa + fb, sa + sb, DECAY_FACTOR),
                ((fa - fb).abs(), sa + sb, DECAY_FACTOR),
                // The cubic terms: e^((2s_a ± s_b)t) and e^((s_a ± 2s_b)t).
                (2.0 * fa + fb, 2.0 * sa + sb, CUBIC_DECAY_FACTOR),
                ((2.0 * fa - fb).abs(), 2.0 * sa + sb, CUBIC_DECAY_FACTOR),
                (fa + 2.0 * fb, sa + 2.0 * sb, CUBIC_DECAY_FACTOR),
                ((fa - 2.0 * fb).abs(), sa + 2.0 * sb, CUBIC_DECAY_FACTOR),
            ]
        })
    });
    harmonics.chain(pairs)
}

/// Whether `m` sits at the term (f Hz, σ 1/s), its decay within `factor`
/// of σ, in records under a window of decay rate `window` [1/s].
fn matches(m: &FittedMode, (f, sigma): (f64, f64), factor: f64, line_hz: f64, window: f64) -> bool {
    // Decay rates as the windowed records show them.
    let (own, sigma) = (-m.pole.re + window, sigma + window);
    let within = LINE_FRACTION * line_hz + BAND_FRACTION * own.max(0.0) / (2.0 * PI);
    if (m.pole.im / (2.0 * PI) - f).abs() > within {
        return false;
    }
    sigma < line_hz || (own < factor * sigma && sigma < factor * own)
}
