//! The MAC matrix between two mode sets as a heat map: one cell per pair
//! (row: a mode of this model, column: a mode of the other set, numbered
//! 1, 2, … in ascending frequency), coloured by
//! MAC = |φᵢᵀψⱼ|²/((φᵢᵀφᵢ)(ψⱼᵀψⱼ)) ∈ [0, 1] [–] and labelled with its value
//! to two decimals. Matching modes give a bright diagonal.

use crate::output::plot::{Figure, HeatMap, LabelledHeatMap, Scale};
use nalgebra::DMatrix;

/// The MAC heat map of `mac` (rows: this model's modes, columns: the other
/// set's, both in ascending frequency).
pub fn mac_figure(title: &str, mac: &DMatrix<f64>) -> Figure {
    let index = |n: usize| (1..=n).map(|k| k as f64).collect::<Vec<f64>>();
    let z: Vec<Vec<f64>> = mac
        .row_iter()
        .map(|r| r.iter().copied().collect())
        .collect();
    let labels = z
        .iter()
        .map(|r| r.iter().map(|v| format!("{v:.2}")).collect())
        .collect();
    LabelledHeatMap {
        map: HeatMap {
            title: title.to_string(),
            x_label: "Mode of the other set".into(),
            x_scale: Scale::none(),
            y_label: "Mode of this model".into(),
            y_scale: Scale::none(),
            x: index(mac.ncols()),
            y: index(mac.nrows()),
            z,
            z_label: "MAC".into(),
            z_scale: Scale::none(),
            ..HeatMap::default()
        },
        labels,
    }
    .into()
}
