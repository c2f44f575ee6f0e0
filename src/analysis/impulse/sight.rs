//! Which modes a sensor sees.
//!
//! A sensor reads one material point along one direction. A mode whose
//! shape does not move that point along that direction leaves no peak in
//! its record, whatever the hammer does: a slider does not move in a
//! coupler's symmetric bending, a sensor on a node line of a plate-like
//! mode reads nothing of it. The impulse then finds the nearest other peak
//! in the band of the mode and reports it as the mode.
//!
//! The sensor's sight of a mode φ is the reading of its velocity channel at
//! the state struck with the velocities φ (the linear part of every
//! quantity and frame a sensor has: displacement, velocity and
//! acceleration of a mode differ by factors ω and ω²), relative to the
//! mode's largest translation at a node, a rigid body's centre or a point
//! mass [–]. Below [`BLIND_RATIO`] the sensor is blind to the mode, and the
//! point of that largest translation, with its direction, would see it.

use super::sensor::SensorProbe;
use crate::analysis::transient::State;
use crate::model::SensorQuantity;
use crate::system::System;

/// A sensor that reads less than this fraction of a mode's largest
/// translation does not see the mode [–].
pub const BLIND_RATIO: f64 = 1e-3;

/// A sensor's sight of one mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Sight {
    /// The sensor's reading of the mode over the mode's largest
    /// translation [–] (about 1 at the antinode, 0 on a node line).
    pub ratio: f64,
    /// Where the mode moves most: "beam `coupler` at s = 5.000e-2 m",
    /// "rigid body `mass` (its centre)", "point mass `tip`".
    pub best_point: String,
    /// The unit direction it moves there (global frame).
    pub best_direction: [f64; 2],
}

impl Sight {
    /// Whether the sensor does not see the mode.
    pub fn blind(&self) -> bool {
        self.ratio.is_nan() || self.ratio < BLIND_RATIO
    }
}

/// The sight of the mode `shape` (full coordinates) by `probe`, at the
/// state struck `q`.
pub fn sight(system: &System, probe: &SensorProbe, q: &[f64], shape: &[f64]) -> Sight {
    let n = q.len();
    let state = State {
        t: 0.0,
        q: q.to_vec(),
        v: shape.to_vec(),
        a: vec![0.0; n],
        abar: vec![0.0; n],
        lambda: Vec::new(),
    };
    let seen = probe.read_as(&state, SensorQuantity::Velocity).abs();
    let mut best = (0.0f64, String::new(), [0.0, 0.0]);
    let mut consider = |i: usize, label: &dyn Fn() -> String| {
        let (x, y) = (shape[i], shape[i + 1]);
        let amp = x.hypot(y);
        if amp > best.0 {
            best = (amp, label(), [x / amp, y / amp]);
        }
    };
    for b in &system.beams {
        for (k, &s) in b.node_s.iter().enumerate() {
            consider(b.dof0 + 4 * k, &|| {
                format!("beam `{}` at s = {s:.4e} m", b.id)
            });
        }
    }
    for r in &system.rigid_bodies {
        consider(r.dof0, &|| format!("rigid body `{}` (its centre)", r.id));
    }
    for p in &system.point_masses {
        consider(p.dof0, &|| format!("point mass `{}`", p.id));
    }
    let ratio = if best.0 > 0.0 { seen / best.0 } else { 0.0 };
    Sight {
        ratio,
        best_point: best.1,
        best_direction: best.2,
    }
}
