//! The reduced body's report: what was reduced, the basis, and its check
//! against the full model (frequencies [Hz], relative error [–]).

use crate::analysis::reduce::CheckCondition;
use crate::results::reduce::ReducedBody;

/// The command line's table.
pub fn reduce_table(body: &ReducedBody) -> String {
    let mut s = format!(
        "model {}: {} reduction, {} component modes, {} interface point(s), {} coordinates → {} flexible + {} rigid (frame)\n",
        body.model,
        body.method.name(),
        body.modes,
        body.interface.len(),
        body.coordinates,
        body.basis_hz.len(),
        body.rigid.first().map_or(0, Vec::len),
    );
    let points: Vec<String> = body
        .interface
        .iter()
        .map(|p| {
            format!(
                "{}:{} (q[{}..{}])",
                p.beam,
                p.s,
                p.coordinates[0],
                p.coordinates[3] + 1
            )
        })
        .collect();
    s.push_str(&format!("interface: {}\n", points.join(", ")));
    if body.prestress {
        s.push_str("at the static equilibrium: the stiffening kept, the preload forces not\n");
    }
    if !body.removed_supports.is_empty() {
        s.push_str(&format!(
            "supports removed: {}\n",
            body.removed_supports.join(", ")
        ));
    }
    s.push_str(&format!(
        "mass {:.6e} kg, inertia about the centre of mass {:.6e} kg m²\n",
        body.total_mass_kg, body.inertia_kg_m2
    ));
    let check = &body.check;
    let condition = match check.condition {
        CheckCondition::Free => "every interface point free".to_string(),
        CheckCondition::Held { point } => {
            format!("interface point {point} held (position and slope)")
        }
    };
    s.push_str(&format!(
        "check: reduced body against the full model, {condition}{}\n",
        if check.zero_modes > 0 {
            format!(" ({} zero-frequency modes left out)", check.zero_modes)
        } else {
            String::new()
        }
    ));
    if !check.frame_hz.is_empty() {
        // An imaginary frequency (ω² < 0) as `modal` prints it.
        let list: Vec<String> = check
            .frame_hz
            .iter()
            .map(|&f| {
                if f < 0.0 {
                    format!("{:.3}i", -f)
                } else {
                    format!("{f:.3}")
                }
            })
            .collect();
        s.push_str(&format!(
            "rigid motions the pre-stress stiffens (or, with an i, softens: unstable), not \
             compared: {} Hz in the full model, 0 Hz on the multibody code's frame\n",
            list.join(", ")
        ));
    }
    s.push_str(" mode    full [Hz]  reduced [Hz]  rel. error\n");
    for (i, ((f, g), e)) in check
        .full_hz
        .iter()
        .zip(&check.reduced_hz)
        .zip(&check.relative_error)
        .enumerate()
    {
        s.push_str(&format!(
            "{:>5} {:>12.3} {:>13.3} {:>11.2e}\n",
            i + 1,
            f,
            g,
            e
        ));
    }
    s
}
