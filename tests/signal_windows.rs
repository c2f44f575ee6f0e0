//! The one window type: every window's coherent gain and equivalent noise
//! bandwidth against independent values (Harris 1978, table I; MATLAB's
//! flattopwin documentation; the continuous integrals of the force and
//! exponential windows), the closed forms against the summed samples, and
//! the exponential window's decay: it moves a pole by exactly σ_w, and the
//! modal fit moves it back.

use std::f64::consts::PI;

use ancf_modal::signal::fit::{fit, FitSettings, PoleBasis};
use ancf_modal::signal::Window;
use realfft::num_complex::Complex64;

/// The closed forms equal Σw/n and n Σw²/(Σw)² of the force channel's
/// weights, summed sample by sample.
fn closed_forms_match_sums(w: Window, n: usize) {
    let weights = w.force_weights(n);
    let sum: f64 = weights.iter().sum();
    let sum_sq: f64 = weights.iter().map(|v| v * v).sum();
    let cg = sum / n as f64;
    let enbw = n as f64 * sum_sq / (sum * sum);
    assert!(
        (w.coherent_gain(n) - cg).abs() < 1e-12 * cg,
        "{w}, n = {n}: coherent gain {} against the sum {cg}",
        w.coherent_gain(n)
    );
    assert!(
        (w.enbw_bins(n) - enbw).abs() < 1e-10 * enbw,
        "{w}, n = {n}: ENBW {} against the sum {enbw}",
        w.enbw_bins(n)
    );
}

#[test]
fn cosine_windows_match_the_literature() {
    // Harris (1978) table I; MATLAB flattopwin: coherent gain 0.2156, ENBW
    // 3.77 bins.
    let cases = [
        (Window::Rectangular, 1.0, 1.0),
        (Window::Hann, 0.5, 1.5),
        (Window::Blackman, 0.42, 1.73),
        (Window::FlatTop, 0.2156, 3.77),
    ];
    for (w, cg, enbw) in cases {
        for n in [16, 1000, 5120] {
            assert!((w.coherent_gain(n) - cg).abs() < 1e-4, "{w}");
            assert!(
                (w.enbw_bins(n) - enbw).abs() < 5e-3,
                "{w}: {}",
                w.enbw_bins(n)
            );
            closed_forms_match_sums(w, n);
        }
    }
}

#[test]
fn force_window_keeps_its_fraction() {
    // Weights 1 on the first P·n samples: Σw = Σw² = P n, so the coherent
    // gain is P and the ENBW 1/P bins.
    for (p, n) in [(0.25, 1000), (0.01, 5100), (0.5, 16), (1.0, 64)] {
        let w = Window::Force { fraction: p };
        assert!((w.coherent_gain(n) - p).abs() < 1e-15, "{w}");
        assert!((w.enbw_bins(n) - 1.0 / p).abs() < 1e-12 / p, "{w}");
        closed_forms_match_sums(w, n);
        // The response channel is not weighted.
        assert!(w.response_weights(n).iter().all(|&v| v == 1.0));
    }
    // Fewer samples than one: one sample is kept.
    let tiny = Window::Force { fraction: 1e-6 };
    assert_eq!(tiny.coherent_gain(100), 0.01);
}

#[test]
fn exponential_window_tends_to_its_continuous_integrals() {
    // w(x) = P^x on [0, 1]: ∫w = (1 − P)/L and ∫w² = (1 − P²)/(2L), L = −ln P,
    // so the coherent gain tends to (1 − P)/L and the ENBW to
    // (1 + P) L / (2 (1 − P)). The sums are trapezoid-like rules of these
    // integrals, off by O(1/n).
    for p in [0.5, 0.01, 1e-3, 1e-6] {
        let w = Window::Exponential { end_value: p };
        let l = -f64::ln(p);
        let cg = (1.0 - p) / l;
        let enbw = (1.0 + p) * l / (2.0 * (1.0 - p));
        for n in [16, 1000, 5120, 100_000] {
            closed_forms_match_sums(w, n);
            let bound = 2.0 * (1.0 + l) / n as f64;
            assert!(
                (w.coherent_gain(n) - cg).abs() < bound * cg,
                "{w}, n = {n}: {} against {cg}",
                w.coherent_gain(n)
            );
            assert!(
                (w.enbw_bins(n) - enbw).abs() < bound * enbw,
                "{w}, n = {n}: {} against {enbw}",
                w.enbw_bins(n)
            );
        }
    }
    // P = 1 is the rectangle.
    let flat = Window::Exponential { end_value: 1.0 };
    assert_eq!((flat.coherent_gain(100), flat.enbw_bins(100)), (1.0, 1.0));
}

/// The window sampled at t_i = i/f_s is e^(−σ_w t_i): a free decay
/// e^(λ t) becomes e^((λ − σ_w) t) sample by sample.
#[test]
fn exponential_window_shifts_a_pole_by_its_decay_rate() {
    let (fs, n) = (10_240.0, 4096);
    for p in [0.5, 1e-2, 1e-4] {
        let w = Window::Exponential { end_value: p };
        let sigma_w = w.decay_rate(n, fs);
        let lambda = Complex64::new(-3.0, 2.0 * PI * 700.0);
        for (i, wi) in w.response_weights(n).iter().enumerate() {
            let t = i as f64 / fs;
            let windowed = (lambda * t).exp() * wi;
            let shifted = ((lambda - sigma_w) * t).exp();
            assert!(
                (windowed - shifted).norm() < 1e-12,
                "{w}, sample {i}: {windowed} against {shifted}"
            );
        }
        // Force and response share the exponential weights.
        assert_eq!(w.force_weights(n), w.response_weights(n));
    }
}

/// An FRF made of one pole pair moved by σ_w (what the window leaves) is fitted
/// with the window's decay rate: the fit returns the unwindowed pole (to
/// rounding: the data are exactly the fitted model).
#[test]
fn the_fit_moves_the_pole_back() {
    let (f0, zeta) = (700.0, 0.002);
    let w0 = 2.0 * PI * f0;
    let pole = Complex64::new(-zeta * w0, w0 * (1.0 - zeta * zeta).sqrt());
    let residue = Complex64::new(0.0, -50.0);
    let window = Window::Exponential { end_value: 1e-3 };
    let sigma_w = window.decay_rate(4096, 10_240.0);
    assert!(sigma_w > zeta * w0, "the window dominates the decay");
    let windowed = pole - sigma_w;
    let df = 10_240.0 / 4096.0;
    let frequency_hz: Vec<f64> = (0..2049).map(|k| k as f64 * df).collect();
    let h: Vec<Complex64> = frequency_hz
        .iter()
        .map(|f| {
            let iw = Complex64::new(0.0, 2.0 * PI * f);
            residue / (iw - windowed) + residue.conj() / (iw - windowed.conj())
        })
        .collect();
    let settings = FitSettings {
        f_lo: 400.0,
        f_hi: 1_000.0,
        max_order: 20,
        window_decay_rate: sigma_w,
        basis: PoleBasis::Continuous,
    };
    let result = fit(&frequency_hz, &h, &settings);
    assert_eq!(result.modes.len(), 1, "{:?}", result.modes);
    let m = &result.modes[0];
    assert!(
        (m.pole - pole).norm() < 1e-12 * pole.norm(),
        "{} against {pole}",
        m.pole
    );
    assert!(
        (m.frequency_hz - f0).abs() < 1e-12 * f0,
        "{}",
        m.frequency_hz
    );
    // ζ = −Re s/|s|: an error of 1e-12 |s| in s moves ζ by at most 1e-12.
    assert!(
        (m.damping_ratio - zeta).abs() < 1e-12,
        "{}",
        m.damping_ratio
    );
}

#[test]
fn text_forms_round_trip() {
    for w in [
        Window::Rectangular,
        Window::Hann,
        Window::FlatTop,
        Window::Blackman,
        Window::Force { fraction: 0.02 },
        Window::Exponential { end_value: 1e-3 },
    ] {
        assert_eq!(w.to_string().parse::<Window>(), Ok(w));
        let json = serde_json::to_string(&w).unwrap();
        assert_eq!(serde_json::from_str::<Window>(&json).unwrap(), w);
    }
    for (alias, w) in [
        ("Rect", Window::Rectangular),
        ("rectangular", Window::Rectangular),
        ("hanning", Window::Hann),
        ("flat-top", Window::FlatTop),
        ("exp:0.5", Window::Exponential { end_value: 0.5 }),
    ] {
        assert_eq!(alias.parse::<Window>(), Ok(w), "{alias}");
    }
    for bad in [
        "kaiser",
        "force",
        "force:0",
        "exponential:2",
        "hann:0.5",
        "force:x",
    ] {
        let e = bad.parse::<Window>().unwrap_err().to_string();
        assert!(!e.is_empty() && !e.contains('\n'), "{bad}: {e}");
    }
}
