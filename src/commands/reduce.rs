//! `reduce`: the assembly as a reduced flexible body for a multibody code
//! (Craig–Bampton or free-interface, [`crate::analysis::reduce`]), with
//! its own check against the full model and the 3D node form Exudyn
//! imports. Interface points are material points on beams (beam id, arc
//! length [SI: m]); one that is not a mesh node is made one. Ground
//! supports are removed unless `keep_supports`; with `prestress` the body
//! is linearized at the static equilibrium of the supported model under
//! its loads × `load_scale`: it keeps the stiffening of that state, not its
//! preload forces.

use super::{CommandError, ModelInput, Run};
use crate::analysis::reduce::{
    check, reduce, rigid_stiffening, CheckCondition, NodeForm, NodeKind, ReduceError, Reduction,
    ReductionMethod,
};
use crate::analysis::statics::{solve_equilibrium, StaticSettings};
use crate::model::resolved::ResolvedPoint;
use crate::model::PointSpec;
use crate::output::npz::{npz, NpyArray};
use crate::output::reduce_report::reduce_table;
use crate::results::reduce::{rows, InterfacePoint, NodeFormDoc, ReducedBody};
use crate::system::Linearization;
use crate::System;
use std::path::Path;

/// What `reduce` computes.
#[derive(Debug, Clone, PartialEq)]
pub struct ReduceRequest {
    /// Interface points: (beam id, arc length [SI: m]).
    pub interface: Vec<(String, f64)>,
    /// Component modes: fixed-interface (Craig–Bampton) or free
    /// (free-interface) [–] (≥ 1).
    pub modes: usize,
    pub method: ReductionMethod,
    /// Reduce at the static equilibrium under the loads.
    pub prestress: bool,
    /// Factor on the applied loads for `prestress` [–].
    pub load_scale: f64,
    /// Keep the ground supports in the body.
    pub keep_supports: bool,
}

impl Default for ReduceRequest {
    fn default() -> Self {
        ReduceRequest {
            interface: Vec::new(),
            modes: 8,
            method: ReductionMethod::CraigBampton,
            prestress: false,
            load_scale: 1.0,
            keep_supports: false,
        }
    }
}

/// The shortest element an interface point may make, as a fraction of the
/// beam's element length L/elements [–]. On a 12.5 mm mesh (a steel strip,
/// 40 elements) a point 0.1 µm from a node gave a negative ω² in the basis
/// and 1.5 µm a check error of −3.7e-3 (below the full model: round-off,
/// not truncation), while 10 µm matched a point far from any node.
const MIN_ELEMENT_FRACTION: f64 = 5e-4;

/// A check error above which `reduce` warns [–].
const POOR_CHECK: f64 = 0.1;

/// `reduce`'s output.
#[derive(Debug)]
pub struct ReduceRun {
    /// The body's system (supports removed unless kept).
    pub system: System,
    /// The constraint multipliers at the equilibrium (`prestress`), in the
    /// body's rows [SI: N, N m].
    pub lambda: Option<Vec<f64>>,
    pub reduction: Reduction,
    /// The reduced body with its check.
    pub document: Run<ReducedBody>,
}

/// Runs `reduce` on `input`.
pub fn run(input: &ModelInput, request: &ReduceRequest) -> Result<ReduceRun, CommandError> {
    super::checks::modes_and_load_scale(request.modes, request.load_scale)?;
    if !request.prestress && request.load_scale != 1.0 {
        return Err(CommandError::argument(
            "load_scale",
            request.load_scale,
            "applies to the pre-stressed reduction only: ask for prestress too",
        ));
    }
    if request.interface.is_empty() {
        return Err(CommandError::argument(
            "interface",
            "[]",
            "give at least one interface point (beam id, arc length)",
        ));
    }
    let model = &input.model;
    let mut points = Vec::new();
    for (i, (beam, s)) in request.interface.iter().enumerate() {
        let spec = PointSpec {
            beam: Some(beam.clone()),
            s: Some(*s),
            ..PointSpec::default()
        };
        let value = format!("{beam}:{s}");
        match model.resolve_point(&spec, &format!("interface[{i}]")) {
            Ok(ResolvedPoint::Beam { index, s }) => points.push((index, s)),
            Ok(_) => {
                return Err(CommandError::argument(
                    "interface",
                    value,
                    format!("beam `{beam}` is rigid: interface points are on flexible beams"),
                ))
            }
            Err(e) => {
                return Err(CommandError::argument(
                    "interface",
                    value,
                    e.problem.to_string(),
                ))
            }
        }
    }
    let fail = |e| CommandError::analysis(input.label(), e);
    let supported = System::with_nodes(model, &points);
    let (q, lambda) = if request.prestress {
        let settings = StaticSettings {
            load_scale: request.load_scale,
            ..StaticSettings::default()
        };
        let eq = solve_equilibrium(&supported, &settings).map_err(fail)?;
        (eq.q, Some(eq.lambda))
    } else {
        (supported.q0.clone(), None)
    };
    let mut system = System::with_nodes(model, &points);
    let free = if request.keep_supports {
        None
    } else {
        Some(system.remove_supports())
    };
    let lambda = match (&lambda, &free) {
        (Some(l), Some(f)) => Some(f.kept_rows.iter().map(|&r| l[r]).collect::<Vec<_>>()),
        (Some(l), None) => Some(l.clone()),
        _ => None,
    };
    let at = Linearization {
        q: &q,
        lambda: lambda.as_deref(),
        time: 0.0,
        load_scale: if request.prestress {
            request.load_scale
        } else {
            0.0
        },
    };
    let mut interface = Vec::new();
    let mut coordinates = Vec::new();
    for (&(index, s), (beam, _)) in points.iter().zip(&request.interface) {
        let mesh = &system.beams[index];
        let node = (0..mesh.node_count())
            .min_by(|&a, &b| {
                (mesh.node_s[a] - s)
                    .abs()
                    .total_cmp(&(mesh.node_s[b] - s).abs())
            })
            .unwrap_or(0);
        let g = mesh.dof0 + 4 * node;
        let value = format!("{beam}:{s}");
        if coordinates.contains(&g) {
            return Err(CommandError::argument(
                "interface",
                value,
                "repeats an interface point: give each point once",
            ));
        }
        // A point a hair's breadth from a node makes an element so short
        // that its stiffness (EI/h³) swamps the rest in round-off.
        let elements = model
            .beams
            .iter()
            .find(|b| b.id == mesh.id)
            .map_or(mesh.elements.len(), |b| b.elements);
        let nominal = mesh.node_s[mesh.node_count() - 1] / elements as f64;
        let shortest = [node.checked_sub(1), Some(node + 1)]
            .into_iter()
            .flatten()
            .filter(|&k| k < mesh.node_count())
            .map(|k| (mesh.node_s[k] - mesh.node_s[node]).abs())
            .fold(f64::INFINITY, f64::min);
        if shortest < MIN_ELEMENT_FRACTION * nominal {
            return Err(CommandError::argument(
                "interface",
                value,
                format!(
                    "lies {shortest:.3e} m from the next mesh node or interface point: \
                     closer than {MIN_ELEMENT_FRACTION:e} of an element ({:.3e} m), the \
                     element between them spoils the reduction in round-off; put it on \
                     that point or farther away",
                    MIN_ELEMENT_FRACTION * nominal
                ),
            ));
        }
        coordinates.extend(g..g + 4);
        interface.push((beam.clone(), mesh.node_s[node], g));
    }
    let label = |a: usize| system.dof_label(coordinates[a]);
    let reduce_fail = |e: ReduceError| CommandError::Reduce {
        model: input.label(),
        source: e,
    };
    let reduction = reduce(
        &system,
        &at,
        &coordinates,
        request.method,
        request.modes,
        !request.keep_supports,
        &label,
    )
    .map_err(|e| match e {
        ReduceError::TooManyModes {
            requested,
            available,
            problem,
        } => CommandError::argument(
            "modes",
            requested,
            format!("at most {available} (the {problem} problem's mode count)"),
        ),
        e => reduce_fail(e),
    })?;
    let condition = match request.method {
        ReductionMethod::CraigBampton => CheckCondition::Free,
        ReductionMethod::FreeInterface => CheckCondition::Held { point: 1 },
    };
    let checked = check(&system, &at, &reduction, condition, request.modes).map_err(reduce_fail)?;
    let nodes = NodeForm::new(&system, &at, &reduction.basis);
    let hz = |w: f64| w.signum() * w.abs().sqrt() / (2.0 * std::f64::consts::PI);
    let document = ReducedBody {
        model: model.name.clone(),
        method: request.method,
        modes: request.modes,
        prestress: request.prestress,
        load_scale: if request.prestress {
            request.load_scale
        } else {
            1.0
        },
        keep_supports: request.keep_supports,
        removed_supports: free.map(|f| f.removed).unwrap_or_default(),
        interface: interface
            .iter()
            .map(|(beam, s, g)| InterfacePoint {
                beam: beam.clone(),
                s: *s,
                coordinates: [*g, g + 1, g + 2, g + 3],
                nodes: nodes.beam_node(*g).unwrap_or([0, 0]),
            })
            .collect(),
        coordinates: system.ndof(),
        q: q.clone(),
        origin: [system.origin.x, system.origin.y],
        total_mass_kg: system.total_mass(),
        inertia_kg_m2: rotation_inertia(&system, &q),
        component_hz: reduction
            .component_eigenvalues
            .iter()
            .map(|&w| hz(w))
            .collect(),
        basis_hz: reduction.eigenvalues.iter().map(|&w| hz(w)).collect(),
        mass: rows(&reduction.mass(&system)),
        stiffness: rows(&reduction.stiffness(&system, &at)),
        basis: rows(&reduction.basis),
        rigid: rows(&reduction.rigid),
        nodes: NodeFormDoc {
            positions: nodes.positions.clone(),
            kinds: nodes.kinds.clone(),
            mass: nodes.mass.clone(),
            stiffness: nodes.stiffness.clone(),
            basis: rows(&nodes.basis),
        },
        check: checked,
    };
    let mut notes = Vec::new();
    if request.prestress {
        let lost = rigid_stiffening(&system, &at, &reduction);
        let first = reduction.eigenvalues.first().copied().unwrap_or(f64::NAN);
        notes.push(format!(
            "prestress: the body keeps the pre-stress stiffening on its modal coordinates only; \
             the frame's rigid motions lose it in the multibody code (their ω² under the \
             pre-stress reach {:.3e} rad²/s², {:.3e} of the first flexible ω² = {:.3e} rad²/s²): \
             modes with a rigid part in the frame (any the joints or clamps there make turn \
             or move the body) come out wrong there; the check lists the full model's \
             stiffened rigid motions apart",
            lost,
            lost / first,
            first
        ));
    }
    let check = &document.check;
    if let Some((i, e)) = check
        .relative_error
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .filter(|(_, e)| e.abs() > POOR_CHECK)
    {
        notes.push(format!(
            "the reduced body misses the full model by {e:.2e} on mode {} of the check \
             ({:.3} Hz against {:.3} Hz): more component modes or interface points bring it \
             closer",
            i + 1,
            check.reduced_hz[i],
            check.full_hz[i]
        ));
    }
    Ok(ReduceRun {
        document: Run::of(input, document).warn(input, notes),
        system,
        lambda,
        reduction,
    })
}

/// The moment of inertia about the z axis through the centre of mass
/// [SI: kg m²]: the kinetic form of the unit rotation field ẑ × (r − c),
/// slopes turning with it, rigid bodies' angles at rate 1.
fn rotation_inertia(system: &System, q: &[f64]) -> f64 {
    let n = system.ndof();
    let m = system.total_mass();
    let mass = system.mass();
    // The centre of mass from the translation field's momentum.
    let mut c = [0.0; 2];
    let mut mv = vec![0.0; n];
    for axis in 0..2 {
        let mut t = vec![0.0; n];
        for i in system.point_coordinates() {
            t[i + axis] = 1.0;
        }
        mass.mul_vec(&t, &mut mv);
        let moment: f64 = (0..n)
            .map(|i| mv[i] * position_component(system, q, i, axis))
            .sum();
        c[axis] = moment / m;
    }
    let mut v = vec![0.0; n];
    for i in system.point_coordinates() {
        v[i] = -(q[i + 1] - c[1]);
        v[i + 1] = q[i] - c[0];
    }
    for b in &system.beams {
        for k in 0..b.node_count() {
            let i = b.dof0 + 4 * k + 2;
            v[i] = -q[i + 1];
            v[i + 1] = q[i];
        }
    }
    for r in &system.rigid_bodies {
        v[r.dof0 + 2] = 1.0;
    }
    mass.quadratic_form(&v)
}

/// q_i when coordinate i is an `axis` component of a position or a beam
/// slope, else 0: with the translation field t, tᵀM of these is the
/// first moment of mass m c along `axis` (the beam's r(x) = S e).
fn position_component(system: &System, q: &[f64], i: usize, axis: usize) -> f64 {
    let is_position = system.point_coordinates().any(|p| p + axis == i);
    let is_slope = system
        .beams
        .iter()
        .any(|b| (0..b.node_count()).any(|k| b.dof0 + 4 * k + 2 + axis == i));
    if is_position || is_slope {
        q[i]
    } else {
        0.0
    }
}

impl ReduceRun {
    /// Where the body was linearized: the reference, or the equilibrium
    /// with its multipliers and the loads' factor.
    pub fn linearization(&self) -> Linearization<'_> {
        let doc = &self.document.output;
        Linearization {
            q: &doc.q,
            lambda: self.lambda.as_deref(),
            time: 0.0,
            load_scale: if doc.prestress { doc.load_scale } else { 0.0 },
        }
    }

    /// The command line's report: the reduction and its check.
    pub fn text(&self) -> String {
        reduce_table(&self.document.output)
    }

    /// Writes the reduced body to `path`, atomically: `.json` (the
    /// document) or `.npz` (its arrays, for numpy: [`ReduceRun::arrays`]).
    pub fn write(&self, path: &Path) -> Result<(), CommandError> {
        let bad = |why: String| CommandError::argument("out", path.display(), why);
        let ext = path.extension().and_then(|e| e.to_str());
        let bytes = match ext.map(str::to_ascii_lowercase).as_deref() {
            Some("json") => serde_json::to_string(&self.document.document())
                .map_err(|e| bad(e.to_string()))?
                .into_bytes(),
            Some("npz") => npz(&self.arrays()).map_err(|e| bad(e.to_string()))?,
            _ => return Err(bad("must end in .json or .npz".to_string())),
        };
        crate::output::files::write_atomic(path, &bytes)?;
        Ok(())
    }

    /// The body as named arrays (the `.npz` file), with the document's
    /// units: `model`, `method`, `modes`, `prestress`, `keep_supports`,
    /// `removed_supports`, `coordinates`, `interface_beam` and
    /// `interface_s` (p), `node_kinds` (N), `check_condition` (`free` or
    /// `held`), `check_held_point` (1-based, 0 when free),
    /// `check_zero_modes`, `mass`, `stiffness` (m × m), `basis` (n × m), `rigid`
    /// (n × r), `q` (n), `origin` (2), `interface_coordinates` (p × 4) and
    /// `interface_nodes` (p × 2) as integers, `node_positions` (N × 3),
    /// `node_mass` and `node_stiffness` as [row, column, value] rows,
    /// `node_basis` (3N × m), `load_scale`, `total_mass_kg`, `inertia_kg_m2`,
    /// `component_hz`, `basis_hz`, and the check's `check_full_hz`,
    /// `check_reduced_hz`, `check_relative_error` and `check_frame_hz`.
    pub fn arrays(&self) -> Vec<NpyArray> {
        let doc = &self.document.output;
        let (n, m, r) = (
            doc.coordinates,
            self.reduction.basis.ncols(),
            self.reduction.rigid.ncols(),
        );
        let vector = |name: &str, v: &[f64]| NpyArray::f64(name, &[v.len()], v.to_vec());
        let scalar = |name: &str, v: f64| NpyArray::f64(name, &[], vec![v]);
        let integers = |name: &str, rows: Vec<Vec<usize>>, width: usize| {
            let values = rows.concat().into_iter().map(|i| i as i64).collect();
            NpyArray::i64(name, &[rows.len(), width], values)
        };
        let triplets = |name: &str, t: &[(usize, usize, f64)]| {
            let values = t.iter().flat_map(|&(i, j, v)| [i as f64, j as f64, v]);
            NpyArray::f64(name, &[t.len(), 3], values.collect())
        };
        let nodes = &doc.nodes;
        let text = |name: &str, v: &str| NpyArray::text(name, &[], vec![v.to_string()]);
        let texts = |name: &str, v: Vec<String>| NpyArray::text(name, &[v.len()], v);
        let count = |name: &str, v: usize| NpyArray::i64(name, &[], vec![v as i64]);
        let flag = |name: &str, v: bool| NpyArray::bool(name, &[], vec![v]);
        let kind = |k: &NodeKind| {
            serde_json::to_value(k)
                .ok()
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or_default()
        };
        let (condition, held) = match doc.check.condition {
            CheckCondition::Free => ("free", 0),
            CheckCondition::Held { point } => ("held", point),
        };
        vec![
            text("model", &doc.model),
            text("method", doc.method.name()),
            count("modes", doc.modes),
            flag("prestress", doc.prestress),
            flag("keep_supports", doc.keep_supports),
            texts("removed_supports", doc.removed_supports.clone()),
            count("coordinates", doc.coordinates),
            texts(
                "interface_beam",
                doc.interface.iter().map(|p| p.beam.clone()).collect(),
            ),
            vector(
                "interface_s",
                &doc.interface.iter().map(|p| p.s).collect::<Vec<_>>(),
            ),
            texts("node_kinds", nodes.kinds.iter().map(kind).collect()),
            text("check_condition", condition),
            count("check_held_point", held),
            count("check_zero_modes", doc.check.zero_modes),
            NpyArray::rows("mass", &doc.mass, m),
            NpyArray::rows("stiffness", &doc.stiffness, m),
            NpyArray::rows("basis", &doc.basis, m),
            NpyArray::rows("rigid", &doc.rigid, r),
            NpyArray::f64("q", &[n], doc.q.clone()),
            vector("origin", &doc.origin),
            integers(
                "interface_coordinates",
                doc.interface
                    .iter()
                    .map(|p| p.coordinates.to_vec())
                    .collect(),
                4,
            ),
            integers(
                "interface_nodes",
                doc.interface.iter().map(|p| p.nodes.to_vec()).collect(),
                2,
            ),
            NpyArray::f64(
                "node_positions",
                &[nodes.positions.len(), 3],
                nodes.positions.concat(),
            ),
            triplets("node_mass", &nodes.mass),
            triplets("node_stiffness", &nodes.stiffness),
            NpyArray::rows("node_basis", &nodes.basis, m),
            scalar("load_scale", doc.load_scale),
            scalar("total_mass_kg", doc.total_mass_kg),
            scalar("inertia_kg_m2", doc.inertia_kg_m2),
            vector("component_hz", &doc.component_hz),
            vector("basis_hz", &doc.basis_hz),
            vector("check_full_hz", &doc.check.full_hz),
            vector("check_reduced_hz", &doc.check.reduced_hz),
            vector("check_relative_error", &doc.check.relative_error),
            vector("check_frame_hz", &doc.check.frame_hz),
        ]
    }
}
