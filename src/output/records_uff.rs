//! Simulated records as UFF 58 time data (function type 1, real double,
//! even abscissa in s): the force (ordinate type 13, N) and the sensor
//! (8 displacement m, 11 velocity m/s, 12 acceleration m/s²), in that
//! order, so that `frf` and pyuff read them as a hammer test.

use crate::measured::uff::{d58, Function, FunctionType, Ordinate, SpecDataType};
use crate::model::SensorQuantity;

/// UFF 58 text of the force and sensor records sampled at `time` (uniform
/// from `time[0]`); `provenance` goes into ID lines 2 and 3.
pub fn time_records_uff(
    time: &[f64],
    force: &[f64],
    signal: &[f64],
    sensor: &str,
    quantity: SensorQuantity,
    provenance: &[String; 2],
) -> String {
    let dx = if time.len() > 1 {
        time[1] - time[0]
    } else {
        0.0
    };
    let (qtype, qname, qunit) = match quantity {
        SensorQuantity::Displacement => (SpecDataType::DISPLACEMENT, "displacement", "m"),
        SensorQuantity::Velocity => (SpecDataType::VELOCITY, "velocity", "m/s"),
        SensorQuantity::Acceleration => (SpecDataType::ACCELERATION, "acceleration", "m/s^2"),
    };
    let record =
        |name: &str, node: i64, t: SpecDataType, label: &str, unit: &str, v: &[f64]| Function {
            id: [
                name.to_string(),
                provenance[0].clone(),
                provenance[1].clone(),
                String::new(),
                String::new(),
            ],
            function_type: FunctionType::Time,
            response_entity: name.chars().take(10).collect(),
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
            ordinate: Ordinate::Real(v.to_vec()),
            data_line: 0,
            lines: Vec::new(),
        };
    let mut s = String::new();
    d58::write(
        &mut s,
        &record("force", 1, SpecDataType::FORCE, "force", "N", force),
    );
    d58::write(&mut s, &record(sensor, 2, qtype, qname, qunit, signal));
    s
}
