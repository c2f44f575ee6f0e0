//! Signal processing on sampled records, for simulated and measured data
//! alike: nothing here knows a model or a file.
//!
//! * [`window`] — the one [`Window`] type: rect, hann, flattop, blackman,
//!   force:P and exponential:P, with their coherent gains and noise
//!   bandwidths in closed form and the exponential window's decay rate;
//! * [`spectrum`] — the windowed, zero-padded FFT, single-sided amplitude
//!   spectra and sub-bin peaks;
//! * [`frf`] — the one FRF estimator: averaged auto and cross spectra of
//!   force–response pairs, giving H1, H2 and the coherence γ²;
//! * [`resample`] — linear interpolation of non-uniform samples onto a
//!   uniform grid, and Kaiser-windowed sinc resampling to a lower rate;
//! * [`fit`] — modal parameters from an FRF: LSCF poles with a
//!   stabilization diagram;
//! * [`lsfd`] — the modal model of a band: residues by least squares, poles
//!   refined, the physical and significant ones chosen;
//! * [`projection`] — the linear least-squares fit of the model's
//!   coefficients for given poles, and the poles' refinement by variable
//!   projection with its exact Jacobian;
//! * [`pole_basis`] — the pole term of the FRF's origin (continuous,
//!   sampled, filtered);
//! * [`residual_search`] — modes the LSCF seeds missed, found where the fit
//!   residual stands above the noise;
//! * [`zoom`] — each chosen pole refined again over a band around it, the
//!   other poles held: a strong mode's misfit no longer bends it;
//! * [`harmonics`] — poles at multiples, sums and differences of stronger
//!   modes' frequencies: a nonlinear response's harmonics and combination
//!   tones, not modes;
//! * [`lm`] — the one bounded Levenberg–Marquardt loop (the calibration of
//!   model parameters and the pole refinement both use it);
//! * [`mac`] — the modal assurance criterion between two mode sets.
//!
//! Units: time in s, frequency and sample rates in Hz, decay rates in 1/s;
//! amplitudes keep the unit of the signal (an FRF: response unit per force
//! unit).

pub mod fit;
pub mod frf;
pub mod harmonics;
pub mod lm;
pub mod lscf;
pub mod lsfd;
pub mod mac;
pub mod pole_basis;
pub mod projection;
pub mod resample;
pub mod residual_search;
pub mod spectrum;
pub mod split;
pub mod window;
pub mod zoom;

pub use window::Window;
