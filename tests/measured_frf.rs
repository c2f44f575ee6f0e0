//! H1, H2 and coherence against the generating FRF of a synthetic hammer
//! test (tests/measured_support).

mod measured_support;

use ancf_modal::measured::frf::estimate;
use ancf_modal::signal::Window;
use measured_support::{frf, hammer_records, peak, pulse, respond, TestMode};

const FS: f64 = 10_240.0;
const N: usize = 5_120; // 0.5 s

fn two_modes() -> Vec<TestMode> {
    vec![
        TestMode {
            f: 800.0,
            zeta: 0.01,
            inv_mass: 500.0,
        },
        TestMode {
            f: 2100.0,
            zeta: 0.02,
            inv_mass: 800.0,
        },
    ]
}

#[test]
fn noise_free_h1_equals_the_generating_frf_and_coherence_is_one() {
    let modes = two_modes();
    let records = hammer_records(&modes, FS, N, 3, 0.0, 0.0, 1);
    let e = estimate(&records, Window::Rectangular).unwrap();
    assert_eq!(e.averages, 3);
    let mut checked = 0;
    for (k, f) in e.frequency_hz.iter().enumerate() {
        // The 0.1 ms pulses excite well up to 5 kHz (first zero 15 kHz).
        if *f < 10.0 || *f > 4_000.0 {
            continue;
        }
        let truth = frf(&modes, FS, *f);
        let rel = (e.h1[k] - truth).norm() / truth.norm();
        assert!(rel < 1e-8, "H1 at {f} Hz: {} vs {truth} ({rel:e})", e.h1[k]);
        let rel2 = (e.h2[k] - truth).norm() / truth.norm();
        assert!(rel2 < 1e-8, "H2 at {f} Hz: {rel2:e}");
        assert!(
            (e.coherence[k] - 1.0).abs() < 1e-10,
            "γ² at {f} Hz = {}",
            e.coherence[k]
        );
        checked += 1;
    }
    assert!(checked > 1900);
}

#[test]
fn response_noise_lowers_coherence_where_the_response_is_weak_and_h1_stays_unbiased() {
    let modes = two_modes();
    let clean = respond(&modes, FS, &pulse(N, FS, 4.0, 1e-4, 2e-4));
    let sigma = 2e-2 * peak(&clean);
    let records = hammer_records(&modes, FS, N, 20, 0.0, sigma, 7);
    let e = estimate(&records, Window::Rectangular).unwrap();
    let bin = |f: f64| (f * N as f64 / FS).round() as usize;
    // |H1| = γ²|H2| ≤ |H2| at every bin.
    for k in 1..e.h1.len() - 1 {
        if e.h1[k].re.is_finite() {
            assert!(e.h1[k].norm() <= e.h2[k].norm() * (1.0 + 1e-12));
            let ratio = e.h1[k].norm() / e.h2[k].norm();
            assert!((ratio - e.coherence[k]).abs() < 1e-9);
        }
    }
    // At the resonance the signal dominates: γ² ≈ 1 and H1 within 2 % in
    // magnitude and 0.02 rad in phase of the truth.
    for f0 in [800.0, 2100.0] {
        let k = bin(f0);
        let truth = frf(&modes, FS, e.frequency_hz[k]);
        assert!(e.coherence[k] > 0.99, "γ² at {f0} Hz = {}", e.coherence[k]);
        let rel = (e.h1[k].norm() - truth.norm()).abs() / truth.norm();
        assert!(rel < 0.02, "|H1| at {f0} Hz off by {rel:e}");
        let dphi = (e.h1[k] / truth).arg().abs();
        assert!(dphi < 0.02, "phase of H1 at {f0} Hz off by {dphi} rad");
    }
    // Far above both modes the response is at the noise floor: γ² drops.
    let k = bin(4_500.0);
    assert!(e.coherence[k] < 0.9, "γ² at 4.5 kHz = {}", e.coherence[k]);
    assert!(e
        .coherence
        .iter()
        .filter(|c| c.is_finite())
        .all(|c| (0.0..=1.0).contains(c)));
}

#[test]
fn h1_reads_low_and_h2_high_with_noise_on_both_channels() {
    let modes = two_modes();
    let force = pulse(N, FS, 4.0, 1e-4, 2e-4);
    let clean = respond(&modes, FS, &force);
    let records = hammer_records(&modes, FS, N, 30, 2e-2 * 4.0, 2e-2 * peak(&clean), 11);
    let e = estimate(&records, Window::Rectangular).unwrap();
    // Band-averaged log ratios over 3-4.5 kHz, where both noises matter.
    let (mut l1, mut l2, mut count) = (0.0, 0.0, 0.0);
    for (k, f) in e.frequency_hz.iter().enumerate() {
        if (3_000.0..4_500.0).contains(f) {
            let t = frf(&modes, FS, *f).norm();
            l1 += (e.h1[k].norm() / t).ln();
            l2 += (e.h2[k].norm() / t).ln();
            count += 1.0;
        }
    }
    let (r1, r2) = ((l1 / count).exp(), (l2 / count).exp());
    assert!(
        r1 < 0.98 && r2 > 1.02,
        "mean |H1|/|H| = {r1}, |H2|/|H| = {r2}"
    );
}

#[test]
fn exponential_window_reports_its_decay_rate() {
    let modes = two_modes();
    let records = hammer_records(&modes, FS, N, 1, 0.0, 0.0, 1);
    let e = estimate(&records, Window::Exponential { end_value: 0.01 }).unwrap();
    // w = P^(i/(n−1)) ⇒ σ_w = −ln P · fs/(n−1).
    let expect = -(0.01f64).ln() * FS / (N - 1) as f64;
    assert!((e.window_decay_rate - expect).abs() < 1e-12 * expect);
}
