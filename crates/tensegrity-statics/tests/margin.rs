//! The prestress margin's derivative in the node positions (`tensegrity_statics::sensitivity::
//! prestress_margin`, issue 47 item 3) against extrapolated central differences of the
//! margin to 10⁻⁶ relative, on five generic prestressable structures: complete graphs on 5
//! and 6 free-standing nodes (one and three self-stresses), a bar held by strings to pinned
//! anchors (three self-stresses; the anchors' gradients too), a triangle held by nine members
//! to pinned anchors (three), and an overbraced Snelson prism with its nodes moved off symmetry. And what it says
//! where there is no derivative: the Snelson prism (its self-stress lives on a special
//! geometry), a symmetric structure (a tie), a tetrahedron (no self-stress: zero), a structure
//! with no sign-consistent self-stress (margin at 0).

use crate::common::{node_central_differences, worst_node_error};
use nalgebra::{DVector, Vector3};
use tensegrity_core::test_models::{snelson, snelson_twist};
use tensegrity_core::{Bar, StringMember, Structure, Support};
use tensegrity_statics::sensitivity::{prestress_margin, MarginDerivative, MarginSmoothness};
use tensegrity_statics::Statics;

/// A structure on `nodes` with a member on each pair of `pairs`: a bar where `kind` < 0, a
/// string where > 0, and the `pinned` nodes held.
fn structure(
    nodes: &[[f64; 3]],
    pairs: &[(usize, usize)],
    kind: &[f64],
    pinned: &[usize],
) -> Structure {
    let mut b = Structure::builder().nodes(nodes.iter().copied());
    for (&(i, j), &k) in pairs.iter().zip(kind) {
        b = if k < 0.0 {
            b.bar(Bar::new(i, j))
        } else {
            b.string(StringMember::new(i, j))
        };
    }
    for &p in pinned {
        b = b.support(Support::pinned(p));
    }
    b.build().unwrap()
}

/// The members of `pairs` made bars or strings by the sign of `coefficients` · (self-stress
/// basis) of the framework: a structure prestressable by construction.
fn signed_by_self_stress(
    nodes: &[[f64; 3]],
    pairs: &[(usize, usize)],
    coefficients: &[f64],
    pinned: &[usize],
) -> Structure {
    let frame = structure(nodes, pairs, &vec![-1.0; pairs.len()], pinned);
    let v = Statics::new(&frame).unwrap().self_stress_basis();
    assert_eq!(v.ncols(), coefficients.len(), "self-stresses of the frame");
    let q = &v * DVector::from_column_slice(coefficients);
    structure(nodes, pairs, q.as_slice(), pinned)
}

fn complete(n: usize) -> Vec<(usize, usize)> {
    (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .collect()
}

/// Checks `exact.nodes` against central differences of the margin ((4 D(h/2) − D(h)) / 3,
/// h = 10⁻⁵ of the size) for every coordinate of every node; returns the worst error relative
/// to the largest derivative.
fn check(name: &str, s: &Structure, exact: &MarginDerivative) -> f64 {
    assert_eq!(
        exact.smoothness,
        MarginSmoothness::Differentiable,
        "{name}: {exact:?}"
    );
    let nodes: Vec<Vector3<f64>> = s.nodes().to_vec();
    let size = nodes.iter().fold(0.0f64, |m, x| m.max(x.amax()));
    let largest = exact.nodes.iter().fold(0.0f64, |m, x| m.max(x.amax()));
    assert!(largest > 1e-3, "{name}: a gradient of {largest}");
    let fd = node_central_differences(s, 1e-5 * size, |moved| {
        let d = prestress_margin(moved).unwrap();
        assert_eq!(d.smoothness, MarginSmoothness::Differentiable, "{name}");
        d.margin
    });
    let worst = worst_node_error(name, &exact.nodes, &fd, largest);
    // a rigid motion of the whole changes nothing (free-standing): Σ g_i = 0, Σ x_i × g_i = 0
    if s.supports().is_empty() {
        let force: Vector3<f64> = exact.nodes.iter().sum();
        let moment: Vector3<f64> = nodes
            .iter()
            .zip(&exact.nodes)
            .map(|(x, g)| x.cross(g))
            .sum();
        assert!(force.norm() < 1e-10 * largest && moment.norm() < 1e-10 * largest * size);
    }
    // the polished margin is the LP's, to its tolerance
    let lp = Statics::new(s).unwrap().prestressability().unwrap();
    assert!((lp.margin - exact.margin).abs() < 1e-8, "{name}");
    assert!(exact.margin > 0.0 && exact.prestress_level == 0.0);
    assert!(exact.axial_stiffnesses.iter().all(|&a| a == 0.0));
    worst
}

/// Five points in general position, and a sixth.
const POINTS: [[f64; 3]; 6] = [
    [0.0, 0.0, 0.0],
    [1.1, 0.1, -0.2],
    [0.3, 0.9, 0.15],
    [0.2, 0.3, 1.05],
    [0.65, 0.55, 0.4],
    [-0.4, 0.8, 0.7],
];

/// Nodes, member pairs and pinned nodes.
type Frame = (Vec<[f64; 3]>, Vec<(usize, usize)>, Vec<usize>);

/// A bar held at each end by strings to pinned anchors.
fn held_bar() -> Frame {
    // the bar pushes its ends apart: each end's strings pull it back towards the middle
    let nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.1, 0.05],
        [0.45, 1.0, 0.2],
        [0.4, -1.0, -0.3],
        [0.35, 0.1, 1.0],
        [0.5, -0.2, -1.1],
        [0.6, 1.0, 0.4],
        [0.55, -0.9, 0.1],
        [0.65, 0.0, -1.1],
        [0.5, 0.2, 0.9],
    ];
    let mut pairs = vec![(0, 1)];
    pairs.extend((2..6).map(|a| (0, a)));
    pairs.extend((6..10).map(|a| (1, a)));
    (nodes, pairs, (2..10).collect())
}

/// The 3-bar Snelson prism with a diagonal string on each side face (overbraced: its
/// self-stresses survive node moves) and its nodes moved off symmetry.
fn braced_prism() -> Structure {
    let base = snelson(3, snelson_twist(3), 1.0, 1.0, 1.0).build().unwrap();
    let moves = [
        [0.01, -0.02, 0.0],
        [0.0, 0.015, 0.01],
        [-0.02, 0.0, 0.02],
        [0.01, 0.01, -0.01],
        [0.0, -0.01, 0.0],
        [0.02, 0.0, 0.01],
    ];
    let nodes: Vec<[f64; 3]> = base
        .nodes()
        .iter()
        .zip(moves)
        .map(|(x, d)| [x.x + d[0], x.y + d[1], x.z + d[2]])
        .collect();
    let mut pairs: Vec<(usize, usize)> = base.member_nodes().iter().map(|&[i, j]| (i, j)).collect();
    let n = base.n_bars();
    // each bottom node i to the top node that is not its bar's nor its side string's
    let used: Vec<(usize, usize)> = pairs.clone();
    for i in 0..3 {
        let j = (3..6)
            .find(|&j| !used.contains(&(i, j)) && !used.contains(&(j, i)))
            .unwrap();
        pairs.push((i, j));
    }
    let kind: Vec<f64> = (0..pairs.len())
        .map(|k| if k < n { -1.0 } else { 1.0 })
        .collect();
    structure(&nodes, &pairs, &kind, &[])
}

#[test]
fn the_margin_gradient_matches_central_differences_on_five_structures() {
    let k5 = signed_by_self_stress(&POINTS[..5], &complete(5), &[1.0], &[]);
    let k6 = signed_by_self_stress(&POINTS, &complete(6), &[1.0, 0.6, -0.35], &[]);
    let (nodes, pairs, pinned) = held_bar();
    let kind: Vec<f64> = (0..pairs.len())
        .map(|k| if k == 0 { -1.0 } else { 1.0 })
        .collect();
    let held = structure(&nodes, &pairs, &kind, &pinned);
    // a triangle held by three members from each corner to pinned anchors (twelve members
    // on nine free dofs), the kinds from a combination of its three self-stresses
    let anchored_nodes = [
        [0.0, 0.0, 0.0],
        [1.0, 0.1, 0.05],
        [0.4, 0.9, -0.1],
        [-0.8, -0.3, 0.4],
        [-0.5, 0.2, -0.9],
        [1.7, -0.4, 0.3],
        [1.5, 0.6, -0.8],
        [0.3, 1.8, 0.5],
        [0.7, 1.2, -1.2],
        [0.1, -0.9, 0.8],
    ];
    let anchored_pairs = [
        (0, 1),
        (1, 2),
        (0, 2),
        (0, 3),
        (0, 4),
        (0, 9),
        (1, 5),
        (1, 6),
        (1, 9),
        (2, 7),
        (2, 8),
        (2, 3),
    ];
    let anchored = signed_by_self_stress(
        &anchored_nodes,
        &anchored_pairs,
        &[1.0, -0.4, 0.7],
        &[3, 4, 5, 6, 7, 8, 9],
    );
    let cases = [
        ("K5", k5),
        ("K6", k6),
        ("held bar", held),
        ("anchored triangle", anchored),
        ("braced prism", braced_prism()),
    ];
    for (name, s) in cases {
        let exact = prestress_margin(&s).unwrap();
        let worst = check(name, &s, &exact);
        eprintln!(
            "{name}: margin {:.6}, worst {worst:.1e}, {} at the margin",
            exact.margin,
            exact.at_margin.len()
        );
    }
}

#[test]
fn the_margin_says_why_it_has_no_derivative() {
    // the Snelson prism: its one self-stress lives at the twist of 150° (a mechanism couples)
    let prism = snelson(3, snelson_twist(3), 1.0, 1.0, 1.0).build().unwrap();
    let d = prestress_margin(&prism).unwrap();
    assert!(d.margin > 0.1, "{d:?}");
    match d.smoothness {
        MarginSmoothness::SpecialGeometry {
            mechanisms,
            coupling,
        } => assert!(mechanisms == 1 && coupling > 1e-2, "{d:?}"),
        _ => panic!("the prism: {d:?}"),
    }
    assert!(d.nodes.is_empty());
    // its bars and vertical strings at |q| = 1 and its six ring strings at the margin 1/√3,
    // reported all the same
    assert_eq!((d.at_bound.len(), d.at_margin.len()), (6, 6), "{d:?}");
    // moved off the twist by ~10⁻³ of its size, A's smallest singular value grows from
    // round-off to the size of the move: the self-stress is gone (to within the rank
    // tolerance, which keeps it for data rounded that much), and no derivative could have
    // predicted that
    let smallest = |s: &Structure| {
        let st = Statics::new(s).unwrap();
        *st.singular_values().last().unwrap()
    };
    let mut x = prism.nodes().to_vec();
    x[0] += Vector3::new(1e-3, 2e-3, -1.5e-3);
    let moved = prism.with_nodes(x).unwrap();
    let (at, off) = (smallest(&prism), smallest(&moved));
    assert!(at < 1e-12 && off > 1e-4, "{at} {off}");

    // a symmetric held bar: its strings tie at the margin
    let nodes = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.4, 1.0, 0.0],
        [0.4, -1.0, 0.0],
        [0.6, 1.0, 0.0],
        [0.6, -1.0, 0.0],
        [0.4, 0.0, 1.0],
        [0.4, 0.0, -1.0],
        [0.6, 0.0, 1.0],
        [0.6, 0.0, -1.0],
    ];
    let pairs = [
        (0, 1),
        (0, 2),
        (0, 3),
        (0, 6),
        (0, 7),
        (1, 4),
        (1, 5),
        (1, 8),
        (1, 9),
    ];
    let kind = [-1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0];
    let sym = structure(&nodes, &pairs, &kind, &[2, 3, 4, 5, 6, 7, 8, 9]);
    let d = prestress_margin(&sym).unwrap();
    assert!(d.margin > 0.1 && d.nodes.is_empty(), "{d:?}");
    match d.smoothness {
        MarginSmoothness::Tie {
            at_margin,
            at_bound,
            unknowns,
        } => assert!(at_margin + at_bound > unknowns, "{d:?}"),
        _ => panic!("the symmetric held bar: {d:?}"),
    }

    // a tetrahedron: no self-stress, margin 0 near it, zero gradient
    let tet = structure(&POINTS[..4], &complete(4), &[1.0; 6], &[]);
    let d = prestress_margin(&tet).unwrap();
    assert_eq!(d.smoothness, MarginSmoothness::NoSelfStress);
    assert!(d.margin == 0.0 && d.nodes.iter().all(|g| g.norm() == 0.0));

    // K5 all strings: a self-stress, none with every string in tension
    let k5 = structure(&POINTS[..5], &complete(5), &[1.0; 10], &[]);
    let d = prestress_margin(&k5).unwrap();
    assert_eq!((d.margin, d.smoothness), (0.0, MarginSmoothness::AtZero));
}

#[test]
fn the_margin_derivative_refuses_clusters() {
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .cluster(tensegrity_core::Cluster::new(vec![0, 1, 2]).stiffness(100.0))
        .support(Support::pinned(0))
        .support(Support::pinned(2))
        .build()
        .unwrap();
    let e = prestress_margin(&s).unwrap_err().to_string();
    assert!(e.contains("cluster 0") || e.contains("clusters"), "{e}");
}
