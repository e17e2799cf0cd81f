//! Helpers shared by the load-path tests: the row of two-bar trusses and the readers of the
//! exported TsgFEM data.
#![allow(dead_code)]

use nalgebra::Vector3;
use tensegrity_path::{ElasticMember, ElasticModel, MemberKind, Support};

/// Two-bar (von Mises) trusses side by side, each from supports at x = c ± 1 to an apex at
/// its height h (`heights`, m), EA = 1000 N, pushed down by 100 N: two free coordinates a
/// truss. Past its fold (apex below w*: 0.278 m for h = 0.5 m, 0.0577 m for h = 0.1 m) a
/// truss's tangent has one negative eigenvalue.
pub fn von_mises_row(heights: &[f64]) -> ElasticModel {
    let (mut nodes, mut members, mut supports, mut load) = (vec![], vec![], vec![], vec![]);
    for (t, &h) in heights.iter().enumerate() {
        let c = 3.0 * t as f64;
        let first = nodes.len();
        nodes.extend([
            Vector3::new(c - 1.0, 0.0, 0.0),
            Vector3::new(c + 1.0, 0.0, 0.0),
            Vector3::new(c, h, 0.0),
        ]);
        for end in [first, first + 1] {
            members.push(ElasticMember {
                nodes: [end, first + 2],
                kind: MemberKind::Bar,
                ea: 1000.0,
                rest_length: (1.0 + h * h).sqrt(),
            });
            supports.push(Support::pinned(end));
        }
        supports.push(Support::along(first + 2, vec![Vector3::z()]));
        load.extend([
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::new(0.0, -100.0, 0.0),
        ]);
    }
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

/// Rows of three numbers as vectors.
pub fn vec3s(v: &serde_json::Value) -> Vec<Vector3<f64>> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|r| {
            let r = floats(r);
            Vector3::new(r[0], r[1], r[2])
        })
        .collect()
}

/// An array of numbers, or one number as an array of one.
pub fn floats(v: &serde_json::Value) -> Vec<f64> {
    match v {
        serde_json::Value::Array(a) => a.iter().map(|x| x.as_f64().unwrap()).collect(),
        x => vec![x.as_f64().unwrap()],
    }
}

/// Every number of a point is finite (no NaN reaches a report).
pub fn assert_finite(p: &tensegrity_path::point::PathPoint) {
    let numbers = p
        .nodes
        .iter()
        .chain(&p.displacements)
        .flatten()
        .chain(&p.tensions)
        .chain(&p.smallest_eigenvalues)
        .chain(p.reactions.iter().map(|r| &r.force))
        .chain([&p.lambda, &p.residual, &p.max_displacement]);
    for v in numbers {
        assert!(v.is_finite(), "step {}: {v}", p.step);
    }
}
