//! Windows for frequency-response estimation, as in impact testing (pyFRF's
//! names).
//!
//! * `rect` — no weighting: right for an impact response that decays inside
//!   the record.
//! * `hann` — the periodic Hann window on force and response (random or
//!   periodic excitation).
//! * `force:P` — on the force channel only: 1 over the first fraction P of
//!   the record, 0 after, which removes the noise the force transducer
//!   records after the impact; the response is not weighted.
//! * `exponential:P` — w_i = P^(i/(n−1)) on force and response, decaying to
//!   P at the last sample, which forces a lightly damped response to die
//!   out inside the record. It multiplies every mode's free decay
//!   e^(−ζωt) by e^(−σ_w t) with σ_w = −ln P / ((n − 1) Δt): each pole
//!   λ = −ζω ± iω_d moves to λ − σ_w. [`Window::decay_rate`] returns σ_w
//!   (1/s) so that the fit can move the identified poles back
//!   (`fit::remove_window_decay`).

use std::fmt;
use std::str::FromStr;

/// A window of [`super::frf`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Window {
    #[default]
    Rectangular,
    Hann,
    /// Keeps the first `fraction` of the force record.
    Force {
        fraction: f64,
    },
    /// Decays to `end_value` at the record's last sample.
    Exponential {
        end_value: f64,
    },
}

impl FromStr for Window {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (name, arg) = match s.split_once(':') {
            Some((n, a)) => (n, Some(a)),
            None => (s, None),
        };
        let param = |what: &str| -> Result<f64, String> {
            let a = arg.ok_or_else(|| format!("`{name}` needs a parameter: {name}:P ({what})"))?;
            let p: f64 = a
                .parse()
                .map_err(|_| format!("`{a}` is not a number (window {name}:P)"))?;
            if p > 0.0 && p <= 1.0 {
                Ok(p)
            } else {
                Err(format!("{name}:P needs 0 < P ≤ 1 ({what}), got {a}"))
            }
        };
        match (name.to_ascii_lowercase().as_str(), arg) {
            ("rect" | "rectangular" | "none", None) => Ok(Window::Rectangular),
            ("hann", None) => Ok(Window::Hann),
            ("force", _) => Ok(Window::Force {
                fraction: param("the fraction of the record kept")?,
            }),
            ("exponential" | "exp", _) => Ok(Window::Exponential {
                end_value: param("the value at the record's end")?,
            }),
            _ => Err(format!(
                "unknown window `{s}`: expected rect, hann, force:P or exponential:P"
            )),
        }
    }
}

impl fmt::Display for Window {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Window::Rectangular => write!(f, "rect"),
            Window::Hann => write!(f, "hann"),
            Window::Force { fraction } => write!(f, "force:{fraction}"),
            Window::Exponential { end_value } => write!(f, "exponential:{end_value}"),
        }
    }
}

impl Window {
    /// The n weights applied to the force channel.
    pub fn force_weights(self, n: usize) -> Vec<f64> {
        match self {
            Window::Force { fraction } => {
                let keep = (fraction * n as f64).round() as usize;
                (0..n)
                    .map(|i| if i < keep.max(1) { 1.0 } else { 0.0 })
                    .collect()
            }
            _ => self.response_weights(n),
        }
    }

    /// The n weights applied to the response channel.
    pub fn response_weights(self, n: usize) -> Vec<f64> {
        match self {
            Window::Rectangular | Window::Force { .. } => vec![1.0; n],
            Window::Hann => (0..n)
                .map(|i| 0.5 - 0.5 * (2.0 * std::f64::consts::PI * i as f64 / n as f64).cos())
                .collect(),
            Window::Exponential { end_value } => {
                let last = (n.max(2) - 1) as f64;
                (0..n)
                    .map(|i| (end_value.ln() * i as f64 / last).exp())
                    .collect()
            }
        }
    }

    /// Decay rate σ_w (1/s) the window adds to every mode of a record of n
    /// samples at `sample_rate_hz`; 0 for the other windows.
    pub fn decay_rate(self, n: usize, sample_rate_hz: f64) -> f64 {
        match self {
            Window::Exponential { end_value } => {
                -end_value.ln() * sample_rate_hz / (n.max(2) - 1) as f64
            }
            _ => 0.0,
        }
    }
}
