//! What a response channel measures: displacement, velocity or
//! acceleration [SI: m, m/s, m/s²], and the unit of its FRF (per newton).

use super::uff::SpecDataType;

/// What the response channel measures (the FRF's numerator).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ResponseQuantity {
    Displacement,
    #[default]
    Velocity,
    Acceleration,
}

impl ResponseQuantity {
    /// Every quantity.
    pub const ALL: [ResponseQuantity; 3] = [
        ResponseQuantity::Displacement,
        ResponseQuantity::Velocity,
        ResponseQuantity::Acceleration,
    ];

    /// The quantity a channel's name ends with (`tip_velocity`,
    /// `tip (velocity)`), any case.
    pub fn named(name: &str) -> Option<ResponseQuantity> {
        let name = name.trim_end_matches(')').to_ascii_lowercase();
        Self::ALL.into_iter().find(|q| name.ends_with(q.name()))
    }

    pub fn name(self) -> &'static str {
        match self {
            ResponseQuantity::Displacement => "displacement",
            ResponseQuantity::Velocity => "velocity",
            ResponseQuantity::Acceleration => "acceleration",
        }
    }
    /// SI unit of the FRF (response per newton).
    pub fn frf_unit(self) -> &'static str {
        match self {
            ResponseQuantity::Displacement => "m/N",
            ResponseQuantity::Velocity => "m/s/N",
            ResponseQuantity::Acceleration => "m/s²/N",
        }
    }
    /// SI unit of the response.
    pub fn unit(self) -> &'static str {
        match self {
            ResponseQuantity::Displacement => "m",
            ResponseQuantity::Velocity => "m/s",
            ResponseQuantity::Acceleration => "m/s^2",
        }
    }
    /// The UFF 58 specific data type of the response.
    pub fn uff_type(self) -> SpecDataType {
        match self {
            ResponseQuantity::Displacement => SpecDataType::DISPLACEMENT,
            ResponseQuantity::Velocity => SpecDataType::VELOCITY,
            ResponseQuantity::Acceleration => SpecDataType::ACCELERATION,
        }
    }
}
