//! Simulated records as UFF 58 time data (function type 1, real double,
//! even abscissa in s): forces (ordinate type 13, N) and sensors
//! (8 displacement m, 11 velocity m/s, 12 acceleration m/s²), so that
//! `frf` and pyuff read them as a hammer test. `impulse --uff` writes its
//! force and sensor; `transient --uff` every sensor and every
//! time-varying load's force magnitude.

use crate::measured::uff::{d58, Function, FunctionType, Ordinate, SpecDataType};
use crate::model::SensorQuantity;

/// What one record holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordKind {
    /// A force [SI: N].
    Force,
    /// A sensor of the given quantity.
    Sensor(SensorQuantity),
}

impl RecordKind {
    /// UFF ordinate type, its label and unit.
    fn ordinate(self) -> (SpecDataType, &'static str, &'static str) {
        match self {
            RecordKind::Force => (SpecDataType::FORCE, "force", "N"),
            RecordKind::Sensor(SensorQuantity::Displacement) => {
                (SpecDataType::DISPLACEMENT, "displacement", "m")
            }
            RecordKind::Sensor(SensorQuantity::Velocity) => {
                (SpecDataType::VELOCITY, "velocity", "m/s")
            }
            RecordKind::Sensor(SensorQuantity::Acceleration) => {
                (SpecDataType::ACCELERATION, "acceleration", "m/s^2")
            }
        }
    }
}

/// One named record sampled on the common time grid.
#[derive(Debug, Clone, Copy)]
pub struct Record<'a> {
    pub name: &'a str,
    pub kind: RecordKind,
    pub values: &'a [f64],
}

/// UFF 58 text of records sampled at `time` (uniform from `time[0]`), one
/// dataset each, response nodes 1, 2, … in order, direction 2 (y);
/// `provenance` goes into ID lines 2 and 3.
pub fn records_uff(time: &[f64], records: &[Record], provenance: &[String; 2]) -> String {
    let dx = if time.len() > 1 {
        time[1] - time[0]
    } else {
        0.0
    };
    let mut s = String::new();
    for (node, r) in (1..).zip(records) {
        let (t, label, unit) = r.kind.ordinate();
        let f = Function {
            id: [
                r.name.to_string(),
                provenance[0].clone(),
                provenance[1].clone(),
                String::new(),
                String::new(),
            ],
            function_type: FunctionType::Time,
            response_entity: r.name.chars().take(10).collect(),
            response_node: node,
            response_direction: 2,
            reference_entity: "NONE".into(),
            reference_node: 0,
            reference_direction: 0,
            even: true,
            x_min: time.first().copied().unwrap_or(0.0),
            dx,
            x: Vec::new(),
            abscissa_type: SpecDataType::TIME,
            abscissa_label: "Time".into(),
            abscissa_units: "s".into(),
            ordinate_type: t,
            ordinate_label: label.into(),
            ordinate_units: unit.into(),
            denominator_type: SpecDataType::UNKNOWN,
            denominator_label: "NONE".into(),
            denominator_units: "NONE".into(),
            ordinate: Ordinate::Real(r.values.to_vec()),
            data_line: 0,
            lines: Vec::new(),
        };
        d58::write(&mut s, &f);
    }
    s
}

/// UFF 58 text of one force and one sensor record (the force first), as
/// `impulse --uff` writes them.
pub fn time_records_uff(
    time: &[f64],
    force: &[f64],
    signal: &[f64],
    sensor: &str,
    quantity: SensorQuantity,
    provenance: &[String; 2],
) -> String {
    records_uff(
        time,
        &[
            Record {
                name: "force",
                kind: RecordKind::Force,
                values: force,
            },
            Record {
                name: sensor,
                kind: RecordKind::Sensor(quantity),
                values: signal,
            },
        ],
        provenance,
    )
}
