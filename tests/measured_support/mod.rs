//! A synthetic hammer test, written independently of the library: modes
//! given by (f, ζ, 1/m), each a discrete second-order recursion obtained by
//! impulse invariance (its impulse response is T·e^(−σt) sin(ω_d t)/(m ω_d)
//! at the samples, whose poles are exactly the continuous ones), driven by a
//! sampled half-sine force; Gaussian noise from a fixed-seed generator.
#![allow(dead_code)]

use std::f64::consts::PI;
use std::path::PathBuf;

use ancf_modal::measured::TimeRecord;
use realfft::num_complex::Complex64;

#[derive(Debug, Clone, Copy)]
pub struct TestMode {
    pub f: f64,
    pub zeta: f64,
    /// 1/modal mass, 1/kg.
    pub inv_mass: f64,
}

/// Two well-separated modes, 800 Hz at 1 % and 2100 Hz at 2 %.
#[allow(dead_code)]
pub fn two_modes() -> Vec<TestMode> {
    vec![
        TestMode {
            f: 800.0,
            zeta: 0.01,
            inv_mass: 500.0,
        },
        TestMode {
            f: 2_100.0,
            zeta: 0.02,
            inv_mass: 800.0,
        },
    ]
}

/// Coefficients (a1, a2, b1) of y[k] = a1 y[k−1] + a2 y[k−2] + b1 x[k−1].
fn coefficients(m: &TestMode, fs: f64) -> (f64, f64, f64) {
    let t = 1.0 / fs;
    let w = 2.0 * PI * m.f;
    let sigma = m.zeta * w;
    let wd = w * (1.0 - m.zeta * m.zeta).sqrt();
    let e = (-sigma * t).exp();
    (
        2.0 * e * (wd * t).cos(),
        -e * e,
        t * m.inv_mass * e * (wd * t).sin() / wd,
    )
}

/// Displacement response of the modes to `force`.
pub fn respond(modes: &[TestMode], fs: f64, force: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; force.len()];
    for m in modes {
        let (a1, a2, b1) = coefficients(m, fs);
        let (mut y1, mut y2, mut x1) = (0.0, 0.0, 0.0);
        for (k, yk) in y.iter_mut().enumerate() {
            let v = a1 * y1 + a2 * y2 + b1 * x1;
            *yk += v;
            y2 = y1;
            y1 = v;
            x1 = force[k];
        }
    }
    y
}

/// The generator's exact FRF at `f` (sum of the modes' recursions).
pub fn frf(modes: &[TestMode], fs: f64, f: f64) -> Complex64 {
    let z1 = Complex64::from_polar(1.0, -2.0 * PI * f / fs);
    modes
        .iter()
        .map(|m| {
            let (a1, a2, b1) = coefficients(m, fs);
            b1 * z1 / (1.0 - a1 * z1 - a2 * z1 * z1)
        })
        .sum()
}

/// Half-sine pulse of `amplitude` N and `duration` s starting at `start` s.
pub fn pulse(n: usize, fs: f64, amplitude: f64, duration: f64, start: f64) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let t = k as f64 / fs - start;
            if (0.0..=duration).contains(&t) {
                amplitude * (PI * t / duration).sin()
            } else {
                0.0
            }
        })
        .collect()
}

/// xorshift64* with Box–Muller: reproducible Gaussian noise.
pub struct Noise(u64);

impl Noise {
    pub fn new(seed: u64) -> Self {
        Noise(seed.max(1))
    }
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let v = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D);
        ((v >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    pub fn gauss(&mut self) -> f64 {
        let (u1, u2) = (self.uniform(), self.uniform());
        (-2.0 * u1.ln()).sqrt() * (2.0 * PI * u2).cos()
    }
}

/// `hits` hammer records: pulses of varying amplitude and width, noise of
/// standard deviation `force_noise` (N) and `response_noise` (m) added.
pub fn hammer_records(
    modes: &[TestMode],
    fs: f64,
    n: usize,
    hits: usize,
    force_noise: f64,
    response_noise: f64,
    seed: u64,
) -> Vec<TimeRecord> {
    let mut noise = Noise::new(seed);
    (0..hits)
        .map(|i| {
            let amp = 4.0 * (1.0 + 0.1 * i as f64);
            let dur = 1.0e-4 * (1.0 + 0.15 * (i % 3) as f64);
            let clean = pulse(n, fs, amp, dur, 2.0e-4);
            let resp = respond(modes, fs, &clean);
            let force = clean
                .iter()
                .map(|v| v + force_noise * noise.gauss())
                .collect();
            let response = resp
                .iter()
                .map(|v| v + response_noise * noise.gauss())
                .collect();
            TimeRecord {
                file: PathBuf::from(format!("hit{i}.csv")),
                sample_rate_hz: fs,
                force,
                response,
                force_label: "force".into(),
                response_label: "response".into(),
                lines: (2..n + 2).collect(),
            }
        })
        .collect()
}

/// Peak of |response| over records, for noise levels.
pub fn peak(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a, b| a.max(b.abs()))
}

/// `hits` records at 10.24 kHz, 0.5 s (force noise 1e-3 N, response noise
/// 1e-9), written as CSV files `hit{i}.csv` (columns time, force, response)
/// in `dir`.
pub fn write_csv_hits(
    dir: &std::path::Path,
    modes: &[TestMode],
    hits: usize,
    seed: u64,
) -> Vec<PathBuf> {
    use std::fmt::Write;
    let (fs, n) = (10_240.0, 5_120);
    hammer_records(modes, fs, n, hits, 1e-3, 1e-9, seed)
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let mut s = String::from("time,force,response\n");
            for k in 0..n {
                let _ = writeln!(
                    s,
                    "{:.9e},{:.9e},{:.9e}",
                    k as f64 / fs,
                    r.force[k],
                    r.response[k]
                );
            }
            let p = dir.join(format!("hit{i}.csv"));
            std::fs::write(&p, s).unwrap();
            p
        })
        .collect()
}

/// A UFF 58 FRF record "H1 tip / hammer" (the tip's node 2 over the
/// hammer's node 1, both along y) of `h` on lines `dx` Hz apart from 0,
/// its response measuring `ordinate` (named `label`, in `units`) per N.
pub fn frf_function(
    h: Vec<Complex64>,
    dx: f64,
    (ordinate, label, units): (ancf_modal::measured::uff::SpecDataType, &str, &str),
) -> ancf_modal::measured::uff::Function {
    use ancf_modal::measured::uff::{Function, FunctionType, Ordinate, SpecDataType};
    Function {
        id: [
            "H1 tip / hammer".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
        ],
        function_type: FunctionType::Frf,
        response_entity: "tip".into(),
        response_node: 2,
        response_direction: 2,
        reference_entity: "hammer".into(),
        reference_node: 1,
        reference_direction: 2,
        even: true,
        x_min: 0.0,
        dx,
        x: Vec::new(),
        abscissa_type: SpecDataType::FREQUENCY,
        abscissa_label: "Frequency".into(),
        abscissa_units: "Hz".into(),
        ordinate_type: ordinate,
        ordinate_label: label.into(),
        ordinate_units: units.into(),
        denominator_type: SpecDataType::FORCE,
        denominator_label: "hammer".into(),
        denominator_units: "N".into(),
        ordinate: Ordinate::Complex(h),
        data_line: 0,
        lines: Vec::new(),
    }
}
