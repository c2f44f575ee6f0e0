//! Impulse results as a table, a JSON document and CSV.

use crate::analysis::impulse::{Excitation, ImpulseResult};
use crate::model::reference::Errors;

use std::fmt::Write;

/// Readable report; `reference_hz` is the measured first bending frequency.
/// The state the blow struck, in words.
fn struck_words(r: &ImpulseResult) -> String {
    use crate::analysis::statics::start::Start;
    match (r.equilibrium_iterations, r.settings.start) {
        (Some(n), _) => format!(
            "in the static equilibrium under the loads at t = 0 ({n} static iterations): the eigenvalues are the pre-stressed ones"
        ),
        (None, Start::Equilibrium) => {
            String::from("in the reference configuration (it balances the loads at t = 0)")
        }
        (None, Start::Reference) => {
            String::from("in the reference configuration, as asked (not the equilibrium)")
        }
    }
}

pub fn impulse_table(model_name: &str, r: &ImpulseResult, reference_hz: Option<f64>) -> String {
    let mut s = String::new();
    let t = &r.settings.transient;
    let st = &r.stats;
    let _ = writeln!(
        s,
        "model {model_name}: {} steps of {:.3e} s to {:.3e} s, spectral radius {}",
        st.steps, t.step, t.end_time, t.spectral_radius
    );
    let _ = writeln!(
        s,
        "Newton: {:.2} iterations/step, {} factorizations; joints held to {:.1e} m and {:.1e} rad",
        st.newton_iterations as f64 / st.steps.max(1) as f64,
        st.factorizations,
        st.max_length_residual,
        st.max_angle_residual
    );
    let _ = writeln!(
        s,
        "{}: {}",
        match r.excitation {
            Excitation::HalfSine => "hammer (half-sine loads)",
            Excitation::Step => "excitation: the step loads (the model has no half-sine load)",
        },
        r.excitation_loads.join(", ")
    );
    let _ = writeln!(s, "struck at rest {}", struck_words(r));
    let _ = writeln!(
        s,
        "sensor `{}` ({:?}), {} samples at {} Hz, {} window",
        r.sensor,
        r.quantity,
        r.signal.len(),
        crate::model::number::significant(r.sample_rate_hz, 7),
        r.spectrum.window
    );
    if r.settings.sample_rate.is_some() {
        if let Some(&t0) = r.time.first() {
            let _ = writeln!(
                s,
                "acquisition: force and sensor behind the same zero-phase anti-aliasing low-pass (no delay between or on them), from {t0:.4e} s (a pre-trigger ahead of the blow)"
            );
        }
    }
    let _ = writeln!(s, "spectrum peaks:");
    let _ = writeln!(s, "  {:>12}  {:>12}", "f [Hz]", "magnitude");
    for p in &r.peaks {
        let _ = writeln!(s, "  {:>12.3}  {:>12.4e}", p.frequency_hz, p.magnitude);
    }
    match &r.first_bending {
        Some(fb) => {
            let _ = writeln!(s, "first bending frequency:");
            let _ = writeln!(
                s,
                "  FFT peak (raw)                {:>10.3} Hz   vs eigen {:+.2e}",
                fb.raw_hz,
                fb.raw_error()
            );
            let _ = writeln!(
                s,
                "  FFT, integrator-corrected     {:>10.3} Hz   vs eigen {:+.2e}",
                fb.corrected_hz,
                fb.corrected_error()
            );
            let _ = writeln!(
                s,
                "  eigenvalue problem            {:>10.3} Hz",
                fb.eigen_hz
            );
            if let Some(exp) = reference_hz {
                let e = Errors::new(fb.corrected_hz, exp);
                let _ = writeln!(s, "  experiment (reference)        {:>10.3} Hz", exp);
                let _ = writeln!(
                    s,
                    "  error (model − exp)/exp {:+.3} %; paper's convention (exp − model)/model {:+.3} %",
                    e.error_percent, e.paper_error_percent
                );
            }
        }
        None => match r.blind_sentence() {
            Some(blind) => {
                let _ = writeln!(s, "first bending frequency: {blind}");
            }
            None => match crate::analysis::impulse::first_bending_band(&r.modal) {
                Some((eigen, lo, hi)) => {
                    let _ = writeln!(
                        s,
                        "first bending frequency: not identified: no peak of the spectrum stands in the band of the eigenvalue {eigen:.3} Hz at the state struck ({lo:.3}–{hi:.3} Hz)"
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        "first bending frequency: not identified: the model has no bending mode among the modes computed"
                    );
                }
            },
        },
    }
    if let Some(d) = &r.damping {
        let _ = writeln!(s, "first bending damping ratio:");
        let _ = writeln!(
            s,
            "  fitted from force and sensor (H1, LSCF)  {:>9.5} %   at {:.3} Hz",
            100.0 * d.identified_ratio,
            d.identified_hz
        );
        let _ = writeln!(
            s,
            "  model (Rayleigh φᵀ(αM + βK₀)φ/(2ω))       {:>9.5} %",
            100.0 * d.modal_ratio
        );
        let _ = writeln!(
            s,
            "  integrator's numerical damping           {:>9.5} %",
            100.0 * d.numerical_ratio
        );
        match d.relative_error() {
            Some(e) => {
                let _ = writeln!(s, "  fitted vs model + numerical {e:+.2e}");
            }
            None => {
                let _ = writeln!(
                    s,
                    "  (the model has no damping: the fitted ratio is the integrator's and the record's, not compared)"
                );
            }
        }
    }
    s
}

/// CSV of the sensor time series: t [s], signal, force [N].
pub fn signal_csv(r: &ImpulseResult) -> String {
    let mut s = format!("time_s,{}_{:?},force_n\n", r.sensor, r.quantity).to_lowercase();
    for ((t, y), f) in r.time.iter().zip(&r.signal).zip(&r.force) {
        let _ = writeln!(s, "{t:.9e},{y:.9e},{f:.9e}");
    }
    s
}

/// CSV of the amplitude spectrum: f [Hz], magnitude, dB.
pub fn spectrum_csv(r: &ImpulseResult) -> String {
    let mut s = String::from("frequency_hz,magnitude,magnitude_db\n");
    let db = r.spectrum.magnitude_db();
    for ((f, m), d) in r
        .spectrum
        .frequency_hz
        .iter()
        .zip(&r.spectrum.magnitude)
        .zip(&db)
    {
        let _ = writeln!(s, "{f:.6},{m:.9e},{d:.4}");
    }
    s
}
