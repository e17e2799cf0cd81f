//! Loads in the force density method (issue 43, item 4): point loads and self-weight on a
//! topology with fixed nodes, D_ff X_f = P_f − D_fx X_x, the reactions r_i = (D X)_i − p_i at
//! the fixed nodes and the equilibrium residual of the free nodes.
//!
//! Known answers: a node held by four strings (x_f = (Σ q_k x_k + p) / Σ q_k exactly, and
//! under self-weight z = −a / √(1 − a²), a = w / 2q), jax_fdm's loaded arch (its test suite's
//! baseline coordinates, `tests/baselines/arch_coordinates.json`, and the closed form
//! z_i = 0.1 i (10 − i)), a cable net under uniform loads against an independent dense solve,
//! and Σ r + Σ p = 0 in every case. Bad inputs are refused naming the item.

use formfind::{
    find, form_find, FixedNode, FormFindError, FormFound, Group, Member, Method, NodeLoad,
    Settings, Synthesis, Topology,
};
use nalgebra::{DMatrix, Vector3};
use std::collections::BTreeMap;

/// Σ r + Σ p (over every node's load, the held ones included), relative to Σ |r| + Σ |p|.
fn imbalance(found: &FormFound) -> f64 {
    let mut sum = Vector3::zeros();
    let mut size = 0.0;
    for f in found.reactions.iter().chain(&found.loads) {
        let v = Vector3::from(f.force);
        sum += v;
        size += v.norm();
    }
    sum.norm() / size
}

fn reaction(found: &FormFound, node: usize) -> Vector3<f64> {
    let r = found.reactions.iter().find(|r| r.node == node).unwrap();
    Vector3::from(r.force)
}

const ANCHORS: [[f64; 3]; 4] = [
    [0.0, 0.0, 1.0],
    [3.0, 0.5, 0.0],
    [1.0, 2.5, 0.5],
    [-0.5, 1.0, 2.0],
];

/// Node 4 held by one string to each of the four anchors (nodes 0–3).
fn star(q: [f64; 4], load: [f64; 3]) -> Topology {
    Topology {
        n_nodes: 5,
        strings: (0..4)
            .map(|k| Member::new(k, 4).force_density(q[k]))
            .collect(),
        fixed: (0..4)
            .map(|k| FixedNode {
                node: k,
                position: ANCHORS[k],
            })
            .collect(),
        loads: vec![NodeLoad {
            node: 4,
            force: load,
        }],
        ..Topology::default()
    }
}

#[test]
fn a_node_held_by_four_strings_sits_at_the_weighted_mean_shifted_by_the_load() {
    let q = [1.0, 2.0, 3.0, 4.0];
    let p = Vector3::new(0.3, -0.2, -5.0);
    let t = star(q, p.into());
    let found = form_find(&t, &Settings::default()).unwrap();
    assert_eq!(found.method, Method::Fdm);
    assert_eq!(found.iterations, 1);
    // x_f = (Σ q_k x_k + p) / Σ q_k = ((7, 12.5, 10.5) + (0.3, −0.2, −5)) / 10
    let want = Vector3::new(0.73, 1.23, 0.55);
    let mut weighted = p;
    for (k, a) in ANCHORS.iter().enumerate() {
        weighted += q[k] * Vector3::from(*a);
    }
    assert!((weighted / 10.0 - want).norm() < 1e-15, "{weighted:?}");
    assert!(
        (found.nodes[4] - want).norm() < 1e-14,
        "{:?}",
        found.nodes[4]
    );
    // r_k = (D X)_k − p_k = q_k (x_k − x_f) at anchor k; they sum to −p
    for (k, a) in ANCHORS.iter().enumerate() {
        let r = q[k] * (Vector3::from(*a) - want);
        assert!((reaction(&found, k) - r).norm() < 1e-13, "anchor {k}");
    }
    let total: Vector3<f64> = (0..4).map(|k| reaction(&found, k)).sum();
    assert!((total + p).norm() <= 1e-12 * p.norm(), "{total:?}");
    assert!(imbalance(&found) < 1e-12);
    assert_eq!(found.loads.len(), 1);
    assert_eq!(found.loads[0].force, [0.3, -0.2, -5.0]);
    let e = found.equilibrium_residual.unwrap();
    assert!(e < 1e-14, "{e}");
    // ‖A q + p‖ / ‖q‖ vanishes with the load in it (it is 5.0 / ‖q‖ without)
    assert!(found.residual < 1e-14, "{}", found.residual);

    // a load on a held node goes straight into its reaction and moves nothing
    let mut held = t.clone();
    held.loads.push(NodeLoad {
        node: 0,
        force: [1.0, 2.0, 3.0],
    });
    let moved = form_find(&held, &Settings::default()).unwrap();
    assert!((moved.nodes[4] - want).norm() < 1e-14);
    let shift = reaction(&moved, 0) - reaction(&found, 0);
    assert!(
        (shift + Vector3::new(1.0, 2.0, 3.0)).norm() < 1e-13,
        "{shift:?}"
    );
    assert!(imbalance(&moved) < 1e-12);
    // two loads on one node add up
    let mut twice = t.clone();
    twice.loads = vec![
        NodeLoad {
            node: 4,
            force: [0.1, -0.2, -2.0],
        },
        NodeLoad {
            node: 4,
            force: [0.2, 0.0, -3.0],
        },
    ];
    let split = form_find(&twice, &Settings::default()).unwrap();
    assert!((split.nodes[4] - want).norm() < 1e-14);
}

#[test]
fn loads_are_physical_the_force_densities_scale_the_sag_and_huge_ones_do_not_overflow() {
    let p = [0.0, 0.0, -5.0];
    let base = form_find(&star([1.0; 4], p), &Settings::default()).unwrap();
    // with q doubled the load displaces the node half as far from the anchors' mean
    let double = form_find(&star([2.0; 4], p), &Settings::default()).unwrap();
    let mean: Vector3<f64> = ANCHORS
        .iter()
        .map(|a| Vector3::from(*a))
        .sum::<Vector3<f64>>()
        / 4.0;
    assert!((base.nodes[4] - mean - Vector3::new(0.0, 0.0, -1.25)).norm() < 1e-14);
    assert!((double.nodes[4] - mean - Vector3::new(0.0, 0.0, -0.625)).norm() < 1e-14);
    // q and p near the largest double: the same form (solved for q / max|q|, p / max|q|)
    let huge = form_find(&star([1e300; 4], [0.0, 0.0, -5e300]), &Settings::default()).unwrap();
    assert!((huge.nodes[4] - base.nodes[4]).norm() < 1e-14);
    let r = reaction(&huge, 0);
    assert!(r.iter().all(|x| x.is_finite()));
    assert!((r / 1e300 - reaction(&base, 0)).norm() < 1e-13);
}

/// jax_fdm's `arch_network` fixture (tests/conftest.py): a 10-segment line from
/// (−2.5, 0, 0) to (2.5, 0, 0), both ends anchored, q = −1 on every edge (our bars), a load
/// (0, 0, −0.2) on every free node.
fn arch() -> Topology {
    Topology {
        n_nodes: 11,
        bars: (0..10)
            .map(|k| Member::new(k, k + 1).force_density(-1.0))
            .collect(),
        fixed: vec![
            FixedNode {
                node: 0,
                position: [-2.5, 0.0, 0.0],
            },
            FixedNode {
                node: 10,
                position: [2.5, 0.0, 0.0],
            },
        ],
        loads: (1..10)
            .map(|node| NodeLoad {
                node,
                force: [0.0, 0.0, -0.2],
            })
            .collect(),
        ..Topology::default()
    }
}

#[test]
fn jax_fdm_s_loaded_arch_is_reproduced_to_its_baseline() {
    let mut found = form_find(&arch(), &Settings::default()).unwrap();
    // jax_fdm tests/baselines/arch_coordinates.json (x, z of nodes 0…10; y = 0)
    let baseline: [[f64; 2]; 11] = [
        [-2.5, 0.0],
        [-1.9999999999999998, 0.9],
        [-1.4999999999999996, 1.6],
        [-0.9999999999999997, 2.1],
        [-0.49999999999999983, 2.400000000000001],
        [1.3877787807814457e-16, 2.500000000000001],
        [0.5000000000000001, 2.400000000000001],
        [1.0, 2.1000000000000005],
        [1.5, 1.6000000000000003],
        [2.0, 0.9000000000000001],
        [2.5, 0.0],
    ];
    for (i, [x, z]) in baseline.iter().enumerate() {
        let p = found.nodes[i];
        assert!(
            (p.x - x).abs() < 1e-12 && p.y.abs() < 1e-12 && (p.z - z).abs() < 1e-12,
            "node {i}: {p:?}"
        );
        // the closed form: −(z_{i−1} − 2 z_i + z_{i+1}) = 0.2 with z_0 = z_10 = 0
        let closed = 0.1 * (i * (10 - i)) as f64;
        assert!(
            (p.z - closed).abs() < 1e-12,
            "node {i}: {} vs {closed}",
            p.z
        );
    }
    // the supports take the thrust q Δx = 0.5 inwards and half the 1.8 N each
    assert!((reaction(&found, 0) - Vector3::new(0.5, 0.0, 0.9)).norm() < 1e-12);
    assert!((reaction(&found, 10) - Vector3::new(-0.5, 0.0, 0.9)).norm() < 1e-12);
    assert!(imbalance(&found) < 1e-12);
    assert!(found.equilibrium_residual.unwrap() < 1e-14);
    // a hinged arch of bars is a mechanism its compression does not stiffen (the statics
    // added to the form found without them, as asked)
    assert_eq!(found.prestress_stable, None);
    found.analyse(&arch()).unwrap();
    assert_eq!(found.prestress_stable, Some(false));

    // the report: no strings, so no prestress to scale; the member forces are q L
    let made = find(
        arch(),
        "arch".into(),
        &Settings::default(),
        &Synthesis::default(),
    )
    .unwrap();
    let force = made.report.member_force.as_ref().unwrap();
    let l0 = (0.5f64 * 0.5 + 0.9 * 0.9).sqrt();
    assert!((force[0] + l0).abs() < 1e-12, "{force:?}");
    assert_eq!(made.report.prestress, 0.0);
    let s = made.structure.as_ref().unwrap();
    assert_eq!((s.supports().len(), s.loads().len()), (2, 9));
}

/// A k × k cable net: nodes (i, j) for i, j in 0..=k+1 without the corners, the boundary
/// ones held at z = 0, x strings q = `qx`, y strings q = `qy`, a load `pz` on every inner
/// node. Returns the topology and every node's grid position.
fn net(k: usize, qx: f64, qy: f64, pz: f64) -> (Topology, Vec<[usize; 2]>) {
    let mut at = Vec::new();
    let mut index = BTreeMap::new();
    for j in 0..=k + 1 {
        for i in 0..=k + 1 {
            let corner = (i == 0 || i == k + 1) && (j == 0 || j == k + 1);
            if !corner {
                index.insert([i, j], at.len());
                at.push([i, j]);
            }
        }
    }
    let inner = |[i, j]: [usize; 2]| (1..=k).contains(&i) && (1..=k).contains(&j);
    let mut strings = Vec::new();
    for (&[i, j], &a) in &index {
        for (next, group) in [([i + 1, j], "x"), ([i, j + 1], "y")] {
            if let Some(&b) = index.get(&next) {
                if inner([i, j]) || inner(next) {
                    strings.push(Member::new(a, b).group(group));
                }
            }
        }
    }
    let group = |q| Group {
        force_density: Some(q),
        ..Group::default()
    };
    let t = Topology {
        n_nodes: at.len(),
        strings,
        groups: BTreeMap::from([("x".into(), group(qx)), ("y".into(), group(qy))]),
        fixed: (0..at.len())
            .filter(|&n| !inner(at[n]))
            .map(|n| FixedNode {
                node: n,
                position: [at[n][0] as f64, at[n][1] as f64, 0.0],
            })
            .collect(),
        loads: (0..at.len())
            .filter(|&n| inner(at[n]))
            .map(|n| NodeLoad {
                node: n,
                force: [0.0, 0.0, pz],
            })
            .collect(),
        ..Topology::default()
    };
    (t, at)
}

#[test]
fn a_cable_net_under_uniform_loads_equals_an_independent_dense_solve() {
    let (k, qx, qy, pz) = (5, 1.0, 2.5, -1.5);
    let (t, at) = net(k, qx, qy, pz);
    let analysed = Settings {
        analyse: true,
        ..Settings::default()
    };
    let found = form_find(&t, &analysed).unwrap();
    // the dense solve: D = Cᵀ diag(q) C assembled from the incidence matrix, its free block
    // solved by nalgebra's LU with partial pivoting
    let q = t.force_densities().unwrap();
    let n = t.n_nodes;
    let mut c = DMatrix::zeros(q.len(), n);
    for (row, m) in t.strings.iter().enumerate() {
        c[(row, m.nodes[0])] = -1.0;
        c[(row, m.nodes[1])] = 1.0;
    }
    let d = c.transpose() * DMatrix::from_diagonal(&nalgebra::DVector::from_vec(q)) * &c;
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    let free: Vec<usize> = (0..n).filter(|i| !held.contains(i)).collect();
    let xx = DMatrix::from_fn(held.len(), 3, |r, a| t.fixed[r].position[a]);
    let dff = d.select_rows(&free).select_columns(&free);
    let dfx = d.select_rows(&free).select_columns(&held);
    let pf = DMatrix::from_fn(free.len(), 3, |_, a| if a == 2 { pz } else { 0.0 });
    let xf = dff.lu().solve(&(pf - dfx * xx)).unwrap();
    let mut worst = 0.0f64;
    for (r, &i) in free.iter().enumerate() {
        for a in 0..3 {
            worst = worst.max((found.nodes[i][a] - xf[(r, a)]).abs());
        }
    }
    let sag = found.nodes.iter().fold(0.0f64, |m, p| m.max(-p.z));
    assert!(worst <= 1e-12 * sag, "{worst:e} against a sag of {sag}");
    assert!(sag > 0.5, "{sag}");
    // the form keeps the net's symmetries: i ↔ k + 1 − i and j ↔ k + 1 − j
    for (a, &[i, j]) in at.iter().enumerate() {
        let b = at
            .iter()
            .position(|&p| p == [k + 1 - i, k + 1 - j])
            .unwrap();
        assert!((found.nodes[a].z - found.nodes[b].z).abs() < 1e-12);
    }
    // the reactions carry the 25 loads, and nothing in x, y overall
    let total: Vector3<f64> = found.reactions.iter().map(|r| Vector3::from(r.force)).sum();
    let want = -((k * k) as f64) * pz;
    assert!(
        (total - Vector3::new(0.0, 0.0, want)).norm() <= 1e-12 * want,
        "{total:?}"
    );
    assert!(imbalance(&found) < 1e-12);
    assert!(found.equilibrium_residual.unwrap() < 1e-14);
    // a loaded net is stable under its loads (D_ff positive definite), has no self-stress
    assert_eq!(found.prestress_stable, Some(true));
    assert_eq!(found.self_stress_dim, Some(0));
    assert_eq!(found.prestressable, Some(false));
    // added later to the form found without them: the same
    let mut lazy = form_find(&t, &Settings::default()).unwrap();
    assert_eq!(lazy.nodes, found.nodes);
    lazy.analyse(&t).unwrap();
    assert_eq!(lazy, found);
}

#[test]
fn the_synthesised_structure_carries_the_loads_with_the_forces_q_l() {
    let (t, _) = net(3, 1.0, 2.0, -1.0);
    let synthesis = Synthesis {
        prestress: 1234.0,
        ..Synthesis::default()
    };
    let made = find(t.clone(), "net".into(), &Settings::default(), &synthesis).unwrap();
    let q = &made.found.force_density;
    let force = made.report.member_force.as_ref().unwrap();
    let s = made.structure.as_ref().unwrap();
    let mut largest = 0.0f64;
    for (k, m) in t.strings.iter().enumerate() {
        let l = (made.found.nodes[m.nodes[1]] - made.found.nodes[m.nodes[0]]).norm();
        // the loads fix the forces: q L, not scaled to the 1234 N asked for
        assert!((force[k] - q[k] * l).abs() < 1e-12 * q[k] * l, "string {k}");
        largest = largest.max(q[k] * l);
        // the written string's tension k (L − s0) is that force
        let st = &s.strings()[k];
        let tension = st.stiffness.unwrap() * (l - st.rest_length.unwrap());
        assert!((tension - q[k] * l).abs() < 1e-9 * q[k] * l, "string {k}");
    }
    assert_eq!(made.report.prestress, largest);
    assert_eq!(s.supports().len(), t.fixed.len());
    assert_eq!(s.loads().len(), 9);
    let w = s.W();
    for l in &t.loads {
        assert_eq!(w[(2, l.node)], -1.0);
    }
    // the report's loads, reactions and residual (keys of the JSON)
    let json = serde_json::to_value(&made.report).unwrap();
    assert_eq!(json["loads"].as_array().unwrap().len(), 9);
    assert_eq!(json["reactions"].as_array().unwrap().len(), t.fixed.len());
    assert!(json["equilibrium_residual"].as_f64().unwrap() < 1e-14);
    // a loaded net needs no self-stress: no `not prestressable` warning
    assert!(
        made.report.warnings.is_empty(),
        "{:?}",
        made.report.warnings
    );
    // a free-standing prism has none of the three keys
    let prism = find(
        formfind::builtin("prism:3").unwrap(),
        "prism".into(),
        &Settings::default(),
        &Synthesis::default(),
    )
    .unwrap();
    let json = serde_json::to_value(&prism.report).unwrap();
    for key in ["loads", "reactions", "equilibrium_residual"] {
        assert!(json.get(key).is_none(), "{key}");
    }
}

#[test]
fn self_weight_is_a_fixed_point_that_matches_the_closed_form() {
    // node 4 hangs from four anchors at (±1, 0, 0), (0, ±1, 0) by strings of q = 1 and weight
    // w = 1 N/m: 4 q z = −4 (w L / 2), L = √(1 + z²), so z = −a / √(1 − a²), a = w / 2q
    let anchors = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let t = Topology {
        n_nodes: 5,
        strings: (0..4).map(|k| Member::new(k, 4).group("cable")).collect(),
        groups: BTreeMap::from([(
            "cable".into(),
            Group {
                force_density: Some(1.0),
                weight: Some(1.0),
                ..Group::default()
            },
        )]),
        fixed: (0..4)
            .map(|k| FixedNode {
                node: k,
                position: anchors[k],
            })
            .collect(),
        ..Topology::default()
    };
    let a: f64 = 0.5;
    let z = -a / (1.0 - a * a).sqrt(); // −1/√3
    assert!((z + 1.0 / 3f64.sqrt()).abs() < 1e-15);
    // at the default tolerance (a change of 10⁻¹² of the size, 2 m) the fixed point is met
    // to a few 10⁻¹² m; at 10⁻¹⁵ to round-off
    let loose = form_find(&t, &Settings::default()).unwrap();
    assert!((loose.nodes[4] - Vector3::new(0.0, 0.0, z)).norm() < 1e-11);
    assert_eq!(loose.tolerance, Some(1e-12));
    let tight = Settings {
        tolerance: 1e-15,
        ..Settings::default()
    };
    let found = form_find(&t, &tight).unwrap();
    assert!(
        (found.nodes[4] - Vector3::new(0.0, 0.0, z)).norm() < 1e-14,
        "{:?}",
        found.nodes[4]
    );
    assert!(found.iterations > loose.iterations, "{}", found.iterations);
    // the loads: half of each string's weight w L = 2/√3 at each end
    let half = 1.0 / 3f64.sqrt();
    assert_eq!(found.loads.len(), 5);
    for l in &found.loads {
        let want = if l.node == 4 { 4.0 * half } else { half };
        assert!((l.force[2] + want).abs() < 1e-12, "{l:?}");
    }
    // the reactions carry the whole weight 4 w L = 8/√3
    let total: f64 = found.reactions.iter().map(|r| r.force[2]).sum();
    assert!((total - 8.0 / 3f64.sqrt()).abs() < 1e-12, "{total}");
    assert!(imbalance(&found) < 1e-12);
    assert!(found.equilibrium_residual.unwrap() < 1e-11);

    // a = w / 2q ≥ 1 has no equilibrium: the fixed point runs away, named
    let mut heavy = t.clone();
    heavy.groups.get_mut("cable").unwrap().weight = Some(4.0);
    let settings = Settings {
        max_iterations: 200,
        ..Settings::default()
    };
    let e = form_find(&heavy, &settings).unwrap_err();
    assert!(
        matches!(e, FormFindError::NotConverged { ref method, .. } if method.contains("self-weight")),
        "{e}"
    );
}

#[test]
fn bad_loads_are_refused_by_name() {
    let p = [0.0, 0.0, -1.0];
    let err = |t: &Topology| form_find(t, &Settings::default()).unwrap_err().to_string();
    let mut t = star([1.0; 4], p);
    t.loads[0].node = 9;
    assert_eq!(
        err(&t),
        "loads[0]: node 9 out of range (the topology has 5 nodes)"
    );
    let mut t = star([1.0; 4], p);
    t.loads[0].force[1] = f64::NAN;
    assert!(err(&t).starts_with("loads[0].force: [0.0, NaN, -1.0] must be finite"));
    let mut t = star([1.0; 4], p);
    t.strings[2].weight = Some(-1.0);
    assert!(err(&t).starts_with("strings[2].weight: -1 must be finite and not negative"));
    // free-standing: loads that do not sum to zero, self-balanced ones, weights
    let mut prism = formfind::builtin("prism:3").unwrap();
    prism.loads = vec![NodeLoad { node: 0, force: p }];
    let e = err(&prism);
    assert!(
        e.starts_with("loads: 1 load(s) on a free-standing topology")
            && e.contains("sum to [0.0, 0.0, -1.0] N")
            && e.contains("`fixed`"),
        "{e}"
    );
    prism.loads.push(NodeLoad {
        node: 3,
        force: [0.0, 0.0, 1.0],
    });
    assert!(err(&prism).contains("even self-balanced loads"));
    let mut prism = formfind::builtin("prism:3").unwrap();
    prism.strings[1].weight = Some(0.5);
    assert!(err(&prism).starts_with("strings[1].weight: self-weight on a free-standing topology"));
    // other methods take no loads: asked for, or chosen by the data
    let t = star([1.0; 4], p);
    let adaptive = Settings {
        method: Method::Adaptive,
        ..Settings::default()
    };
    let e = form_find(&t, &adaptive).unwrap_err().to_string();
    assert!(
        e.starts_with("loads[0]: the adaptive method takes no loads")
            && e.contains("`method = fdm`"),
        "{e}"
    );
    let mut bare = star([1.0; 4], p);
    for m in &mut bare.strings {
        m.force_density = None;
    }
    let e = err(&bare);
    assert!(
        e.starts_with("loads[0]: the adaptive method takes no loads"),
        "{e}"
    );
    // lengths: dynamic relaxation chosen, the weight refused by name
    let mut dr = bare.clone();
    dr.loads.clear();
    dr.nodes = Some(vec![
        ANCHORS[0],
        ANCHORS[1],
        ANCHORS[2],
        ANCHORS[3],
        [1.0, 1.0, 0.5],
    ]);
    for m in &mut dr.strings {
        m.length = Some(1.0);
    }
    dr.strings[3].weight = Some(0.1);
    let e = err(&dr);
    assert!(
        e.starts_with("strings[3].weight: the dr method takes no loads"),
        "{e}"
    );
    // auto with every force density: fdm, loads taken
    let auto = Settings {
        method: Method::Auto,
        ..Settings::default()
    };
    assert_eq!(form_find(&t, &auto).unwrap().method, Method::Fdm);
}

#[test]
fn with_every_node_held_the_loads_go_straight_into_the_reactions() {
    // one string of q = 3 between two held nodes 2 m apart, 1 N sideways on node 0:
    // r_0 = q (x_0 − x_1) − p_0, r_1 = q (x_1 − x_0)
    let t = Topology {
        n_nodes: 2,
        strings: vec![Member::new(0, 1).force_density(3.0)],
        fixed: vec![
            FixedNode {
                node: 0,
                position: [0.0, 0.0, 0.0],
            },
            FixedNode {
                node: 1,
                position: [2.0, 0.0, 0.0],
            },
        ],
        loads: vec![NodeLoad {
            node: 0,
            force: [0.0, 1.0, 0.0],
        }],
        ..Topology::default()
    };
    let found = form_find(&t, &Settings::default()).unwrap();
    assert_eq!(reaction(&found, 0), Vector3::new(-6.0, -1.0, 0.0));
    assert_eq!(reaction(&found, 1), Vector3::new(6.0, 0.0, 0.0));
    assert_eq!(found.equilibrium_residual, Some(0.0));
    assert!(imbalance(&found) < 1e-15);
}
