//! Elastic supports on a load path: a spring of stiffness k along each held direction, the
//! node's direction a free coordinate (k d dᵀ in the tangent, k d (d·(u − λ a)) in the
//! resisting forces, the spring's force as the reaction).
//!
//! - A string pulled against a spring: the series stiffness 1/k = 1/k_s + L₀/EA.
//! - A leaning bar held at its top by a horizontal spring, loaded down to a large
//!   displacement: the state built by hand to balance (the bar's force and the spring's).
//! - A spring's anchor driven by `displacement`: the node follows by k/(k + EA/L₀).
//! - Bad stiffnesses and dependent directions: errors naming the support.

use nalgebra::Vector3;
use tensegrity_path::{
    follow, load_steps, ElasticMember, ElasticModel, MemberKind, PathSettings, Support,
};

/// Node 0 on springs k_s in x, y and z; a string of axial stiffness EA and rest length L₀
/// (shorter than its 2 m, so taut) to node 1, held in y and z; a dead load P₀ along x on node
/// 1 keeps the string taut at λ = 0, the load P along x grows with λ.
fn string_on_spring(k_s: f64, ea: f64, p0: f64, p: f64) -> ElasticModel {
    let string = ElasticMember {
        nodes: [0, 1],
        kind: MemberKind::String,
        ea,
        rest_length: 2.0 * (1.0 - 1e-3),
    };
    ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::new(2.0, 0.0, 0.0)],
        members: vec![string],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0).elastic(k_s),
            Support::along(1, vec![Vector3::y(), Vector3::z()]),
        ],
        load: vec![Vector3::zeros(), Vector3::new(p, 0.0, 0.0)],
        drivers: tensegrity_path::model::Drivers {
            dead_load: vec![Vector3::zeros(), Vector3::new(p0, 0.0, 0.0)],
            ..Default::default()
        },
    }
}

#[test]
fn a_string_pulled_against_a_spring_has_the_series_stiffness() {
    let (k_s, ea, l0) = (1.0e4, 2.0e3, 2.0 * (1.0 - 1e-3));
    let (p0, p) = (10.0, 1.0);
    let path = load_steps(&string_on_spring(k_s, ea, p0, p), 4, 1.0).unwrap();
    let (start, end) = (&path.points[0], &path.points[4]);
    // from the prestressed start (tension P₀) to λ = 1: P more along the string
    let moved = end.nodes[1][0] - start.nodes[1][0];
    let series = p * (1.0 / k_s + l0 / ea);
    assert!(
        ((moved - series) / series).abs() < 1e-8,
        "{moved} against {series}"
    );
    assert!((end.tensions[0] - (p0 + p)).abs() < 1e-9 * (p0 + p));
    // the spring carries the tension: its reaction −k u₀ along x, nothing across
    let spring_x = end
        .reactions
        .iter()
        .find(|r| r.node == 0 && r.direction == [1.0, 0.0, 0.0])
        .unwrap();
    assert!(
        (spring_x.force + (p0 + p)).abs() < 1e-9 * (p0 + p),
        "{spring_x:?}"
    );
    assert!((end.nodes[0][0] - (p0 + p) / k_s).abs() < 1e-12);
    let across: f64 = (end.reactions.iter())
        .filter(|r| r.node == 0 && r.direction[0] == 0.0)
        .map(|r| r.force.abs())
        .sum();
    assert!(across < 1e-12, "{across}");
    // the arc-length path agrees
    let arc = follow(&string_on_spring(k_s, ea, p0, p), &PathSettings::default()).unwrap();
    let last = arc.points.last().unwrap();
    assert!((last.nodes[1][0] - end.nodes[1][0]).abs() < 1e-12);
}

/// A bar (EA = 10⁴ N) from the pinned origin to node 1 at (1, 0, 1), node 1 on springs k
/// along x and y, loaded by P down; k and P chosen by hand so that node 1 balances at
/// (1 + u, 0, 1 + w) (module docs).
fn leaning_bar(u: f64, w: f64) -> (ElasticModel, f64, f64) {
    let ea = 1.0e4;
    let l0 = 2f64.sqrt();
    let (x, z) = (1.0 + u, 1.0 + w);
    let l = (x * x + z * z).sqrt();
    // the bar's tension T (compression negative) pushes node 1 along (x, 0, z)/L: along z it
    // balances the load, −P − T z/L = 0; along x the spring, −k u − T x/L = 0
    let t = ea * (l - l0) / l0;
    let p = -t * z / l;
    let k = -t * x / (l * u);
    let bar = ElasticMember {
        nodes: [0, 1],
        kind: MemberKind::Bar,
        ea,
        rest_length: l0,
    };
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::new(1.0, 0.0, 1.0)],
        members: vec![bar],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support::along(1, vec![Vector3::x(), Vector3::y()]).elastic(k),
        ],
        load: vec![Vector3::zeros(), Vector3::new(0.0, 0.0, -p)],
        drivers: Default::default(),
    };
    (model, k, p)
}

#[test]
fn a_leaning_bar_on_a_spring_reaches_the_state_built_by_hand() {
    // down by 0.3 m and out by 0.22 m: the bar turns by 11°, its compression 54 N
    let (u, w) = (0.22, -0.3);
    let (model, k, p) = leaning_bar(u, w);
    assert!(
        (k - 213.48).abs() < 0.01 && (p - 26.947).abs() < 0.001,
        "{k} {p}"
    );
    let path = follow(&model, &PathSettings::default()).unwrap();
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, 1.0);
    let [x, y, z] = last.nodes[1];
    assert!((x - (1.0 + u)).abs() < 1e-9, "{x}");
    assert!(y.abs() < 1e-12 && (z - (1.0 + w)).abs() < 1e-9, "{y} {z}");
    assert_eq!(path.limit_points(), 0);
    // the spring's reaction is −k u along x
    let spring = last.reactions.iter().find(|r| r.node == 1).unwrap();
    assert_eq!(spring.direction, [1.0, 0.0, 0.0]);
    assert!((spring.force + k * u).abs() < 1e-8 * k * u, "{spring:?}");
    // load control lands on the same state
    let steps = load_steps(&model, 10, 1.0).unwrap();
    let [x2, _, z2] = steps.points[10].nodes[1];
    assert!((x2 - x).abs() < 1e-9 && (z2 - z).abs() < 1e-9);
}

/// `PathReport` has no count of limit points: the events'.
trait LimitPoints {
    fn limit_points(&self) -> usize;
}

impl LimitPoints for tensegrity_path::PathReport {
    fn limit_points(&self) -> usize {
        (self.events.iter())
            .filter(|e| matches!(e, tensegrity_path::Event::LimitPoint { .. }))
            .count()
    }
}

#[test]
fn a_driven_anchor_moves_its_node_through_the_spring() {
    // node 0 on springs k (x, y, z) whose anchor moves by λ (0.1, 0, 0) m; a bar of EA/L₀
    // to the pinned node 1: springs and bar in series, node 0 moves by 0.1 k/(k + EA/L₀)
    let (k, ea, l0) = (3.0e4, 1.0e4, 1.0);
    let bar = ElasticMember {
        nodes: [0, 1],
        kind: MemberKind::Bar,
        ea,
        rest_length: l0,
    };
    let model = ElasticModel {
        nodes: vec![Vector3::zeros(), Vector3::new(l0, 0.0, 0.0)],
        members: vec![bar],
        clusters: Vec::new(),
        supports: vec![Support::pinned(0).elastic(k), Support::pinned(1)],
        load: vec![Vector3::zeros(); 2],
        drivers: tensegrity_path::model::Drivers {
            displacements: vec![Vector3::new(0.1, 0.0, 0.0), Vector3::zeros()],
            ..Default::default()
        },
    };
    let path = load_steps(&model, 2, 1.0).unwrap();
    let end = &path.points[2];
    let expected = 0.1 * k / (k + ea / l0);
    assert!(
        (end.nodes[0][0] - expected).abs() < 1e-12,
        "{:?}",
        end.nodes[0]
    );
    // the bar is compressed by what the spring pushes, k (0.1 − u₀)
    let push = k * (0.1 - expected);
    assert!((end.tensions[0] + push).abs() < 1e-9 * push);
    // a driven motion across the spring's directions is refused, naming the node
    let mut across = model;
    across.supports[0] = Support::along(0, vec![Vector3::y()]).elastic(k);
    let e = load_steps(&across, 2, 1.0).unwrap_err().to_string();
    assert!(e.contains("displacement of node 0"), "{e}");
}

#[test]
fn bad_stiffnesses_and_dependent_directions_name_the_support() {
    let model = string_on_spring(1e4, 2e3, 10.0, 1.0);
    for (k, shown) in [
        (-1.0, "-1"),
        (f64::NAN, "NaN"),
        (f64::INFINITY, "inf"),
        (0.0, "0"),
    ] {
        let mut bad = model.clone();
        bad.supports[0].stiffness = Some(k);
        let e = bad.validated().unwrap_err().to_string();
        assert!(
            e.starts_with("support 0 (node 0): its stiffness k = ")
                && e.contains(shown)
                && e.contains("must be finite and positive"),
            "{e}"
        );
    }
    let mut bad = model;
    bad.supports[1].directions = vec![Vector3::y(), Vector3::new(0.0, -2.0, 0.0)];
    let e = bad.validated().unwrap_err().to_string();
    assert!(
        e.starts_with("support 1 (node 1): its directions are dependent"),
        "{e}"
    );
}

/// A spring more than 10¹⁰ times stiffer than the string beside it (or a string 10⁻³⁰⁰ as
/// stiff as its spring) is refused naming both items: Newton's residual floor would hold the
/// soft one in round-off, and near the largest double the tangent overflows (its eigenvalues
/// NaN, which once read "stable"). At 10⁹ the string's series stiffness is found to 10⁻⁴.
#[test]
fn stiffness_ratios_beyond_double_precision_name_both_items() {
    let ea = 2e3;
    let l0 = 2.0 * (1.0 - 1e-3);
    let string = ea / l0;
    for k_s in [1.01e10 * string, 1e308] {
        let e = string_on_spring(k_s, ea, 10.0, 1.0)
            .validated()
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("support 0 (node 0): stiffness: ")
                && e.contains("member 0 (string): EA/L0")
                && e.contains("double precision"),
            "{e}"
        );
    }
    let e = string_on_spring(1e4, 1e-300, 10.0, 1.0)
        .validated()
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("support 0 (node 0): stiffness: "), "{e}");
    // within the ratio: the string's extension under 1 N on top of the dead load
    let k_s = 1e9 * string;
    let model = string_on_spring(k_s, ea, 10.0, 1.0).validated().unwrap();
    let path = load_steps(&model, 1, 1.0).unwrap();
    let moved = path.points[1].nodes[1][0] - path.points[0].nodes[1][0];
    let series = 1.0 / (1.0 / k_s + 1.0 / string);
    assert!((moved * series - 1.0).abs() < 1e-4, "{moved}");
}
