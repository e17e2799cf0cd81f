//! TsgFEM's published static examples (its repository's `Software_Verification_and_Examples/
//! Statics_Examples`), run under GNU Octave 7.3 with TsgFEM's own functions: each example's
//! model (nodes, members, EA, rest lengths, supports) and drivers (load, forced motion of
//! supported nodes, rest-length changes, all ramped by one load factor over TsgFEM's 100
//! substeps) and its final state after `static_solver2` were exported to
//! `tests/data/tsgfem_*.json` by `scripts/tsgfem-export` (which documents the Octave run).
//! The same model followed here to λ = 1 reaches the same final nodes and member forces.
//!
//! TsgFEM's `material{2} = 0` (no slack, as in these examples, for the comparison with ANSYS)
//! lets strings carry compression: every member is a bar here.

use crate::common;
use common::{floats, vec3s};

use nalgebra::Vector3;
use tensegrity_path::model::Drivers;
use tensegrity_path::{
    follow, load_steps, ElasticMember, ElasticModel, MemberKind, PathSettings, Support,
};

/// The model and TsgFEM's final state of an exported example.
struct Example {
    model: ElasticModel,
    nodes_end: Vec<Vector3<f64>>,
    t_end: Vec<f64>,
}

fn example(name: &str) -> Example {
    let path = format!(
        "{}/tests/data/tsgfem_{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let nodes = vec3s(&d["nodes"]);
    let n = nodes.len();
    let (ea, l0, l0_end) = (floats(&d["ea"]), floats(&d["l0"]), floats(&d["l0_end"]));
    let members: Vec<ElasticMember> = d["members"]
        .as_array()
        .unwrap()
        .iter()
        .enumerate()
        .map(|(k, m)| {
            let m: Vec<usize> = m
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_u64().unwrap() as usize)
                .collect();
            ElasticMember {
                nodes: [m[0], m[1]],
                kind: MemberKind::Bar,
                ea: ea[k],
                rest_length: l0[k],
            }
        })
        .collect();
    let load = floats(&d["load"]);
    let motion = floats(&d["motion"]);
    let held: Vec<usize> = floats(&d["held"]).iter().map(|&x| x as usize).collect();
    let axes = [Vector3::x(), Vector3::y(), Vector3::z()];
    let supports = (0..n)
        .filter_map(|i| {
            let directions: Vec<Vector3<f64>> = (0..3)
                .filter(|a| held.contains(&(3 * i + a)))
                .map(|a| axes[a])
                .collect();
            (!directions.is_empty()).then_some(Support {
                node: i,
                directions,
                stiffness: None,
            })
        })
        .collect();
    let model = ElasticModel {
        nodes,
        members,
        clusters: Vec::new(),
        supports,
        load: (0..n)
            .map(|i| Vector3::new(load[3 * i], load[3 * i + 1], load[3 * i + 2]))
            .collect(),
        drivers: Drivers {
            rest_length_changes: l0_end.iter().zip(&l0).map(|(a, b)| a - b).collect(),
            displacements: (0..n)
                .map(|i| Vector3::new(motion[3 * i], motion[3 * i + 1], motion[3 * i + 2]))
                .collect(),
            dead_load: Vec::new(),
            ..Default::default()
        },
    };
    Example {
        model,
        nodes_end: vec3s(&d["nodes_end"]),
        t_end: floats(&d["t_end"]),
    }
}

/// TsgFEM's nodes and member forces at every substep k (load factor k/(substeps − 1)).
fn substeps(name: &str) -> Vec<(f64, Vec<Vector3<f64>>, Vec<f64>)> {
    let path = format!(
        "{}/tests/data/tsgfem_{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let d: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let lambdas = floats(&d["lambdas"]);
    let nodes = d["nodes_steps"].as_array().unwrap();
    let forces = d["t_steps"].as_array().unwrap();
    lambdas
        .iter()
        .zip(nodes.iter().zip(forces))
        .map(|(&l, (x, t))| {
            let x = floats(x);
            let x = (0..x.len() / 3)
                .map(|i| Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]))
                .collect();
            (l, x, floats(t))
        })
        .collect()
}

/// The largest node and force differences of a path point from TsgFEM's state.
fn differences(p: &tensegrity_path::PathPoint, x: &[Vector3<f64>], t: &[f64]) -> (f64, f64) {
    let nodes = p
        .nodes
        .iter()
        .zip(x)
        .map(|(a, b)| (Vector3::from(*a) - b).amax())
        .fold(0.0, f64::max);
    let forces = p
        .tensions
        .iter()
        .zip(t)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    (nodes, forces)
}

/// Follows `name` to λ = 1 and compares with TsgFEM: nodes to `tol` of the structure's size,
/// member forces to `tol` of the largest.
fn agrees(name: &str, tol: f64) {
    let e = example(name);
    let path = follow(&e.model, &PathSettings::default()).unwrap();
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, 1.0, "{:?}", path.stop);
    let size = e.model.nodes.iter().map(|x| x.amax()).fold(0.0, f64::max);
    let node_error = last
        .nodes
        .iter()
        .zip(&e.nodes_end)
        .map(|(a, b)| (Vector3::from(*a) - b).amax())
        .fold(0.0, f64::max);
    let largest = e.t_end.iter().map(|t| t.abs()).fold(0.0, f64::max);
    let force_error = last
        .tensions
        .iter()
        .zip(&e.t_end)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!(
        "{name}: {} points, nodes {:.3e} of {size} m, forces {:.3e} of {largest:.3e} N",
        path.points.len(),
        node_error,
        force_error
    );
    assert!(
        node_error <= tol * size,
        "{name}: nodes differ by {node_error:.3e} m"
    );
    assert!(
        force_error <= tol * largest,
        "{name}: forces differ by {force_error:.3e} N"
    );
}

/// 01_tower: a two-stage prism tower pinned at its base, 9 kN across on node 4, its top nodes
/// lifted by 5 m and its first bar shortened by 0.3 m.
#[test]
fn the_tower_reaches_tsgfem_s_final_state() {
    agrees("tower", 1e-9);
}

/// Every one of TsgFEM's 100 substeps of the tower, by load steps on the same grid of λ.
#[test]
fn every_substep_of_the_tower_is_tsgfem_s() {
    let e = example("tower");
    let steps = substeps("tower");
    let path = load_steps(&e.model, steps.len() - 1, 1.0).unwrap();
    let largest = e.t_end.iter().map(|t| t.abs()).fold(0.0, f64::max);
    for (p, (lambda, x, t)) in path.points.iter().zip(&steps) {
        assert!((p.lambda - lambda).abs() < 1e-15);
        let (dx, dt) = differences(p, x, t);
        assert!(
            dx < 1e-9 * 60.0 && dt < 1e-9 * largest,
            "λ {lambda}: nodes {dx:.3e} m, forces {dt:.3e} N"
        );
    }
}

/// 05_cable_dome: a cable dome of 60 nodes and 156 members (24 struts), its outer ring
/// pinned, 4 MN down on each of its 12 top nodes and 0.2 MN on 12 others, in 20 substeps.
///
/// Both follow the symmetric path to λ = 0.114, where it bifurcates (a tangent eigenvalue
/// crosses zero; then a symmetric pair): TsgFEM's substeps at λ = 1/19 and 2/19 are ours to
/// 10⁻⁹. Beyond it TsgFEM's modified Newton (its tangent shifted to positive definite, an
/// energy line search) leaves the symmetric path for a stable equilibrium off it, where ours
/// follows the symmetric path and reports it unstable with the bifurcation located (branch
/// switching is not done yet): TsgFEM's final state is an equilibrium of this same model
/// (residual below 10⁻¹¹ of the load) with a positive definite tangent.
#[test]
fn the_cable_dome_agrees_with_tsgfem_up_to_its_bifurcation() {
    use tensegrity_path::point::Event;
    use tensegrity_path::stability::{spectrum, Stability};
    let e = example("cable_dome");
    let steps = substeps("cable_dome");
    let largest = e.t_end.iter().map(|t| t.abs()).fold(0.0, f64::max);
    let path = load_steps(&e.model, steps.len() - 1, 1.0).unwrap();
    for (p, (lambda, x, t)) in path.points.iter().zip(&steps).take(3) {
        let (dx, dt) = differences(p, x, t);
        assert!(
            dx < 1e-9 * 50.0 && dt < 1e-9 * largest,
            "λ {lambda}: nodes {dx:.3e} m, forces {dt:.3e} N"
        );
    }
    let arc = follow(&e.model, &PathSettings::default()).unwrap();
    let first = arc.events.iter().find_map(|e| match e {
        Event::Bifurcation { lambda, .. } => Some(*lambda),
        _ => None,
    });
    let first = first.expect("the symmetric path bifurcates");
    assert!(
        (first - 0.114).abs() < 1e-3 && first > steps[2].0,
        "{first}"
    );
    assert_eq!(arc.points.last().unwrap().stability, Stability::Unstable);
    // TsgFEM's final state: an equilibrium of this model, and a stable one
    let dofs = tensegrity_path::dofs::Dofs::of(&e.model).unwrap();
    let states = tensegrity_path::forces::member_states(&e.model, &e.nodes_end, 1.0);
    let r = tensegrity_path::newton::residual(&e.model, &dofs, &e.nodes_end, &states, 1.0);
    assert!(r.amax() < 1e-11 * 4e6, "{}", r.amax());
    let k = tensegrity_path::tangent::tangent_stiffness(&e.model, &dofs, &states);
    assert_eq!(spectrum(&k).stability, Stability::Stable);
}
