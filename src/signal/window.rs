//! Data windows: the one weighting applied to a record before its FFT, by
//! the amplitude spectrum of a simulated response and by the FRF estimator
//! of measured hits alike.
//!
//! * `rect` — no weighting: right for an impact response that decays inside
//!   the record (its transform is then a sample of the continuous one).
//! * `hann`, `blackman`, `flattop` — periodic ("DFT-even") cosine-sum
//!   windows w_i = Σ_k (−1)^k a_k cos(2π k i / n) (F. J. Harris, "On the use
//!   of windows for harmonic analysis with the discrete Fourier transform",
//!   Proc. IEEE 66(1), 1978; flat top: MATLAB `flattopwin`'s coefficients).
//!   Hann is the default for peak frequencies; the flat top gives the most
//!   accurate amplitudes but the ripple on its flat main lobe moves the
//!   maximum by up to 0.27/T, so it does not locate frequencies.
//! * `force:P` — on the force channel only: 1 over the first fraction P of
//!   the record, 0 after, which removes the noise the force transducer
//!   records after the impact; the response is not weighted.
//! * `exponential:P` — w_i = P^(i/(n−1)) on force and response, decaying to
//!   P at the last sample, which forces a lightly damped response to die
//!   out inside the record. Sampled at t_i = i/f_s it is exactly
//!   e^(−σ_w t_i) with σ_w = −ln P · f_s/(n − 1): it multiplies every
//!   mode's free decay e^(−ζωt) by e^(−σ_w t), so each pole λ moves to
//!   λ − σ_w. [`Window::decay_rate`] returns σ_w (1/s) so that a modal fit
//!   can move the identified poles back.
//!
//! Two figures describe a window of n samples: the coherent gain Σw/n, the
//! factor by which it scales a sinusoid's amplitude, and the equivalent
//! noise bandwidth n Σw²/(Σw)² in bins of 1/T. Both are exact closed forms
//! here for every window ([`Window::coherent_gain`], [`Window::enbw_bins`]),
//! of the force channel's weights (the response's too, but for `force:P`).

use std::fmt;
use std::str::FromStr;

/// A window's text was not understood.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WindowError {
    /// Not one of the window names.
    #[error(
        "unknown window `{0}`: expected rect, hann, flattop, blackman, force:P or exponential:P"
    )]
    Unknown(String),
    /// `force` or `exponential` without its `:P`.
    #[error("`{name}` needs a parameter: {name}:P ({what})")]
    MissingParameter {
        name: &'static str,
        what: &'static str,
    },
    /// The parameter is not a number.
    #[error("`{given}` is not a number (window {name}:P)")]
    NotANumber { name: &'static str, given: String },
    /// The parameter lies outside (0, 1].
    #[error("{name}:P needs 0 < P ≤ 1 ({what}), got {given}")]
    OutOfRange {
        name: &'static str,
        what: &'static str,
        given: String,
    },
    /// A cosine window or `rect` was given a parameter.
    #[error("window `{name}` takes no parameter, got `{given}`")]
    UnexpectedParameter { name: String, given: String },
}

/// A data window (module doc). Its text form is the name, with `:P` for
/// the two windows that take a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Window {
    /// No weighting.
    Rectangular,
    /// Hann (raised cosine).
    #[default]
    Hann,
    /// Flat top (MATLAB `flattopwin`).
    FlatTop,
    /// Classic Blackman (0.42, 0.5, 0.08).
    Blackman,
    /// Keeps the first `fraction` of the force record; the response is not
    /// weighted.
    Force { fraction: f64 },
    /// Decays to `end_value` at the record's last sample, on both channels.
    Exponential { end_value: f64 },
}

impl Window {
    /// Coefficients `a_k` of a cosine-sum window; `None` for the force and
    /// exponential windows.
    fn cosine_terms(self) -> Option<&'static [f64]> {
        match self {
            Window::Rectangular => Some(&[1.0]),
            Window::Hann => Some(&[0.5, 0.5]),
            Window::Blackman => Some(&[0.42, 0.5, 0.08]),
            Window::FlatTop => Some(&[
                0.215_578_95,
                0.416_631_58,
                0.277_263_158,
                0.083_578_947,
                0.006_947_368,
            ]),
            Window::Force { .. } | Window::Exponential { .. } => None,
        }
    }

    /// Samples kept by the force window of a record of n samples (at least
    /// one).
    fn kept(fraction: f64, n: usize) -> usize {
        ((fraction * n as f64).round() as usize).max(1)
    }

    /// The n weights of the response channel (and of a single signal's
    /// spectrum): 1 for `rect` and `force:P`.
    pub fn response_weights(self, n: usize) -> Vec<f64> {
        match self {
            Window::Rectangular | Window::Force { .. } => vec![1.0; n],
            Window::Exponential { end_value } => {
                let last = (n.max(2) - 1) as f64;
                (0..n)
                    .map(|i| (end_value.ln() * i as f64 / last).exp())
                    .collect()
            }
            cosine => {
                let terms = cosine.cosine_terms().unwrap_or(&[1.0]);
                (0..n)
                    .map(|i| {
                        let x = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                        terms
                            .iter()
                            .enumerate()
                            .map(|(k, a)| {
                                let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
                                sign * a * (k as f64 * x).cos()
                            })
                            .sum()
                    })
                    .collect()
            }
        }
    }

    /// The n weights of the force channel: the kept fraction for
    /// `force:P`, the response weights otherwise.
    pub fn force_weights(self, n: usize) -> Vec<f64> {
        match self {
            Window::Force { fraction } => {
                let keep = Self::kept(fraction, n);
                (0..n).map(|i| if i < keep { 1.0 } else { 0.0 }).collect()
            }
            _ => self.response_weights(n),
        }
    }

    /// Coherent gain Σw/n of the force weights (which for every window but
    /// `force:P` are the response weights too) for n samples, in closed
    /// form: a₀ for a cosine window (exact for n above the number of terms),
    /// kept/n for `force:P`, and (1 − r^n)/(n(1 − r)), r = P^(1/(n−1)), for
    /// `exponential:P`. Tends to (1 − P)/(−ln P) for large n.
    pub fn coherent_gain(self, n: usize) -> f64 {
        let n_f = n as f64;
        match self {
            Window::Force { fraction } => Self::kept(fraction, n) as f64 / n_f,
            Window::Exponential { end_value } => {
                let (sum, _) = geometric_sums(end_value, n);
                sum / n_f
            }
            cosine => cosine.cosine_terms().map_or(1.0, |t| t[0]),
        }
    }

    /// Equivalent noise bandwidth n Σw²/(Σw)² of the force weights in
    /// bins of 1/T, in closed form: (a₀² + ½ Σ_{k≥1} a_k²)/a₀² for a cosine
    /// window (1.5 for Hann), n/kept for `force:P`, and from the geometric
    /// sums for `exponential:P` (tends to (1 + P)(−ln P)/(2(1 − P))).
    pub fn enbw_bins(self, n: usize) -> f64 {
        let n_f = n as f64;
        match self {
            Window::Force { fraction } => n_f / Self::kept(fraction, n) as f64,
            Window::Exponential { end_value } => {
                let (sum, sum_sq) = geometric_sums(end_value, n);
                n_f * sum_sq / (sum * sum)
            }
            cosine => {
                let terms = cosine.cosine_terms().unwrap_or(&[1.0]);
                let a0 = terms[0];
                let rest: f64 = terms[1..].iter().map(|a| 0.5 * a * a).sum();
                (a0 * a0 + rest) / (a0 * a0)
            }
        }
    }

    /// Half width of the main lobe (first zero) in bins of 1/T: the number
    /// of cosine terms (1 rectangular, 2 Hann, 3 Blackman, 5 flat top). 1
    /// for `force:P`, which leaves the response unweighted, and for
    /// `exponential:P`, whose transform has no zero: its half-power half
    /// width, −ln P/(2π) bins, is 0.7–1.1 bins for the end values impact
    /// testing uses (10⁻² to 10⁻³).
    pub fn main_lobe_half_width_bins(self) -> f64 {
        self.cosine_terms().map_or(1.0, |t| t.len() as f64)
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

/// Σ r^i and Σ r^(2i), i = 0..n−1, r = P^(1/(n−1)): the exponential
/// window's sums in closed form.
fn geometric_sums(end_value: f64, n: usize) -> (f64, f64) {
    if n < 2 || end_value == 1.0 {
        return (n as f64, n as f64);
    }
    let ln_r = end_value.ln() / (n - 1) as f64;
    // (1 − r^n)/(1 − r) with expm1 for accuracy when r is close to 1.
    let series = |ln_q: f64| (ln_q * n as f64).exp_m1() / ln_q.exp_m1();
    (series(ln_r), series(2.0 * ln_r))
}

impl FromStr for Window {
    type Err = WindowError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim();
        let (name, arg) = match s.split_once(':') {
            Some((n, a)) => (n, Some(a)),
            None => (s, None),
        };
        let param = |name: &'static str, what: &'static str| -> Result<f64, WindowError> {
            let a = arg.ok_or(WindowError::MissingParameter { name, what })?;
            let p: f64 = a.trim().parse().map_err(|_| WindowError::NotANumber {
                name,
                given: a.to_string(),
            })?;
            if p > 0.0 && p <= 1.0 {
                Ok(p)
            } else {
                Err(WindowError::OutOfRange {
                    name,
                    what,
                    given: a.to_string(),
                })
            }
        };
        let plain = match name.to_ascii_lowercase().as_str() {
            "rect" | "rectangular" | "boxcar" | "none" => Window::Rectangular,
            "hann" | "hanning" => Window::Hann,
            "flattop" | "flat-top" | "flat_top" => Window::FlatTop,
            "blackman" => Window::Blackman,
            "force" => {
                return Ok(Window::Force {
                    fraction: param("force", "the fraction of the record kept")?,
                })
            }
            "exponential" | "exp" => {
                return Ok(Window::Exponential {
                    end_value: param("exponential", "the value at the record's end")?,
                })
            }
            _ => return Err(WindowError::Unknown(s.to_string())),
        };
        match arg {
            None => Ok(plain),
            Some(a) => Err(WindowError::UnexpectedParameter {
                name: name.to_string(),
                given: a.to_string(),
            }),
        }
    }
}

impl fmt::Display for Window {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Window::Rectangular => write!(f, "rect"),
            Window::Hann => write!(f, "hann"),
            Window::FlatTop => write!(f, "flattop"),
            Window::Blackman => write!(f, "blackman"),
            Window::Force { fraction } => write!(f, "force:{fraction}"),
            Window::Exponential { end_value } => write!(f, "exponential:{end_value}"),
        }
    }
}

/// Written as its text form (`"hann"`, `"force:0.02"`).
impl serde::Serialize for Window {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Read from its text form, any accepted spelling.
impl<'de> serde::Deserialize<'de> for Window {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

impl schemars::JsonSchema for Window {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Window".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        schemars::json_schema!({
            "type": "string",
            "description": "Data window: rect, hann, flattop, blackman, force:P (the first fraction P of the force record kept) or exponential:P (decaying to P at the record's end), 0 < P ≤ 1.",
            "pattern": "^(rect|hann|flattop|blackman|(force|exponential):[0-9.eE+-]+)$"
        })
    }
}
