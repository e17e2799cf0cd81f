//! Branch switching on a sparse tangent (above `factor::DENSE_MAX` free coordinates, whose
//! mode comes from shift-invert iteration): the pitchfork of `branch.rs` — a stiff bar on a
//! pinned base, its top held in the x–z plane by two prestressed strings — beside 100
//! unloaded two-bar trusses (two free coordinates each: 202 in all) that only make the
//! tangent sparse. The bifurcation is found at the closed-form load, with its mode on the
//! bar's top, and the path leaves along it onto the buckled branch.

use nalgebra::Vector3;
use tensegrity_path::dofs::Dofs;
use tensegrity_path::factor::DENSE_MAX;
use tensegrity_path::point::Event;
use tensegrity_path::{follow, ElasticMember, ElasticModel, MemberKind, PathSettings, Support};

const K: f64 = 100.0;
const T0: f64 = 10.0;
const P: f64 = 100.0;
const EA_BAR: f64 = 1e9;

/// The column of `branch.rs` and 100 small unloaded trusses inside its bounding box (so that
/// the structure's size, which scales the switched branch's steps, is the column's).
fn padded_column() -> ElasticModel {
    let l0 = 1.0 - T0 / K; // the strings' rest length: tension t0 at length 1
    let string = |anchor| ElasticMember {
        nodes: [1, anchor],
        kind: MemberKind::String,
        ea: K * l0,
        rest_length: l0,
    };
    let mut nodes = vec![
        Vector3::zeros(),
        Vector3::z(),
        Vector3::new(-1.0, 0.0, 1.0),
        Vector3::new(1.0, 0.0, 1.0),
    ];
    let mut members = vec![
        ElasticMember {
            nodes: [0, 1],
            kind: MemberKind::Bar,
            ea: EA_BAR,
            rest_length: 1.0,
        },
        string(2),
        string(3),
    ];
    let mut supports = vec![
        Support::pinned(0),
        Support {
            node: 1,
            directions: vec![Vector3::y()],
            stiffness: None,
        },
        Support::pinned(2),
        Support::pinned(3),
    ];
    for t in 0..100 {
        let z = 0.009 * t as f64;
        let first = nodes.len();
        nodes.extend([
            Vector3::new(0.45, 0.0, z),
            Vector3::new(0.55, 0.0, z),
            Vector3::new(0.5, 0.0, z + 0.05),
        ]);
        for end in [first, first + 1] {
            members.push(ElasticMember {
                nodes: [end, first + 2],
                kind: MemberKind::Bar,
                ea: 1000.0,
                rest_length: (nodes[first + 2] - nodes[end]).norm(),
            });
            supports.push(Support::pinned(end));
        }
        supports.push(Support::along(first + 2, vec![Vector3::y()]));
    }
    let mut load = vec![Vector3::zeros(); nodes.len()];
    load[1] = Vector3::new(0.0, 0.0, -P);
    ElasticModel {
        nodes,
        members,
        clusters: Vec::new(),
        supports,
        load,
        drivers: Default::default(),
    }
    .validated()
    .unwrap()
}

/// λ on the buckled branch with the top at (x, 0, z), a rigid bar of length 1 (`branch.rs`).
fn buckled_lambda(x: f64, z: f64) -> f64 {
    let l0 = 1.0 - T0 / K;
    let top = Vector3::new(x, 0.0, z);
    let across = Vector3::new(z, 0.0, -x);
    let mut f = Vector3::zeros();
    for anchor in [Vector3::new(-1.0, 0.0, 1.0), Vector3::new(1.0, 0.0, 1.0)] {
        let d = anchor - top;
        let t = K * (d.norm() - l0);
        f += d / d.norm() * t.max(0.0);
    }
    -f.dot(&across) / (P * x)
}

#[test]
fn the_path_switches_branch_at_a_bifurcation_on_a_sparse_tangent() {
    let model = padded_column();
    let dofs = Dofs::of(&model).unwrap();
    assert!(dofs.len() > DENSE_MAX, "{} coordinates", dofs.len());
    let path = follow(
        &model,
        &PathSettings {
            target: 2.5,
            switch_branch: true,
            ..PathSettings::default()
        },
    )
    .unwrap();
    let (lambda_c, switched) = path
        .events
        .iter()
        .find_map(|e| match e {
            Event::Bifurcation {
                lambda,
                switched,
                mode,
                ..
            } => {
                // the mode: the top moving sideways, nothing else
                assert_eq!(mode.len(), model.nodes.len());
                assert!(
                    (mode[1][0].abs() - 1.0).abs() < 1e-9 && mode[1][2].abs() < 1e-6,
                    "{:?}",
                    mode[1]
                );
                let elsewhere = mode
                    .iter()
                    .enumerate()
                    .filter(|&(i, _)| i != 1)
                    .map(|(_, v)| v.iter().fold(0.0f64, |m, c| m.max(c.abs())))
                    .fold(0.0, f64::max);
                assert!(elsewhere < 1e-6, "{elsewhere:e}");
                Some((*lambda, *switched))
            }
            _ => None,
        })
        .expect("a bifurcation");
    assert!(switched, "{:?}", path.events);
    let share = EA_BAR / (EA_BAR + 2.0 * T0);
    let mut expected = 2.0 * K / P;
    for _ in 0..5 {
        expected = 2.0 * K * (1.0 - expected * P * share / EA_BAR) / (P * share);
    }
    println!(
        "{} coordinates: bifurcation at λ = {lambda_c} (closed form {expected}), {} points",
        dofs.len(),
        path.points.len()
    );
    assert!(
        (lambda_c - expected).abs() < 1e-8 * expected,
        "{lambda_c} against {expected}"
    );
    // after the switch: the top leans, every point on the closed form of the buckled branch
    let after: Vec<_> = path
        .points
        .iter()
        .filter(|p| p.nodes[1][0].abs() > 1e-3)
        .collect();
    assert!(after.len() >= 3, "{} points off the axis", after.len());
    for p in &after {
        let [x, _, z] = p.nodes[1];
        let expected = buckled_lambda(x, z);
        assert!(
            (p.lambda - expected).abs() < 1e-5 * expected,
            "x = {x}: λ {} against {expected}",
            p.lambda
        );
    }
}
