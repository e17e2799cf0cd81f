//! Form-finding with clustered strings (issue 44, item 3): one prescribed tension t along a
//! string through several nodes, its segments' force densities t / l_i found with the form by
//! the fixed point of the force density method (held nodes) or applied as forces t e_i by
//! dynamic relaxation; rest-length synthesis of the whole cluster, L₀ = L − t / k.
//!
//! Known answers: the ring on a clothesline (a free node on a cluster between two held ones
//! under a point load W: equal tensions, so the load bisects the angle of the two segments,
//! each at sin φ = W / 2t from the horizontal, and the ring sits at
//! x = (D − H tan φ⁻¹…) below — see [`clothesline`]); a symmetric cable net whose cluster
//! runs through its loaded centre (the sag from the one-unknown equation of vertical
//! balance, solved by bisection) and the same net solved by the plain force density method
//! with the segments' force densities t / l_i computed by hand; the equilibrium residual
//! recomputed here from the forces t e_i; the rest lengths against L − t/k and L / (1 + t/EA);
//! dynamic relaxation of a prism whose bottom ring is one cluster against the force density
//! form. A fixed point that is not reached is an error, never a result.

use formfind::{
    find, form_find, rest_lengths, synthesize, ClusterString, FixedNode, FormFindError, FormFound,
    Member, Method, NodeLoad, Settings, Synthesis, Topology,
};
use nalgebra::Vector3;

fn held(node: usize, position: [f64; 3]) -> FixedNode {
    FixedNode { node, position }
}

/// A weight W on a frictionless ring (node 1) on a clothesline of tension t between the held
/// nodes 0 at the origin and 2 at (D, 0, H).
fn clothesline(d: f64, h: f64, w: f64, t: f64) -> Topology {
    Topology {
        n_nodes: 3,
        fixed: vec![held(0, [0.0; 3]), held(2, [d, 0.0, h])],
        loads: vec![NodeLoad {
            node: 1,
            force: [0.0, 0.0, -w],
        }],
        clusters: vec![ClusterString::new([0, 1, 2], t)],
        ..Topology::default()
    }
}

/// The residual of the free nodes recomputed from the forces t e_i of the clusters, the
/// members' q (x_j − x_i) and the loads, relative to the largest force.
fn equilibrium(t: &Topology, found: &FormFound) -> f64 {
    let x = &found.nodes;
    let mut f = vec![Vector3::zeros(); t.n_nodes];
    for (m, q) in t.members().zip(&found.force_density) {
        let [i, j] = m.nodes;
        f[i] += *q * (x[j] - x[i]);
        f[j] -= *q * (x[j] - x[i]);
    }
    let mut largest = 0.0f64;
    for c in &t.clusters {
        let tension = c.force.unwrap();
        largest = largest.max(tension);
        for [i, j] in c.segments() {
            let e = (x[j] - x[i]).normalize();
            f[i] += tension * e;
            f[j] -= tension * e;
        }
    }
    for l in &t.loads {
        f[l.node] += Vector3::from(l.force);
        largest = largest.max(Vector3::from(l.force).norm());
    }
    let held: Vec<usize> = t.fixed.iter().map(|f| f.node).collect();
    let worst = (0..t.n_nodes)
        .filter(|i| !held.contains(i))
        .map(|i| f[i].norm())
        .fold(0.0, f64::max);
    worst / largest
}

#[test]
fn the_ring_on_a_clothesline_sits_where_the_load_bisects_the_angle() {
    let (d, h, w, t) = (4.0, 1.0, 10.0, 10.0);
    let topology = clothesline(d, h, w, t);
    let found = form_find(&topology, &Settings::default()).unwrap();
    assert_eq!(found.method, Method::Fdm);
    // both segments at sin φ = W / 2t from the horizontal: c = W/2t, s = √(1 − c²);
    // −z / l₁ = (H − z) / l₂ = c and x / l₁ = (D − x) / l₂ = s give x = (D − H s/c) / 2 and
    // z = −x c / s
    let c = w / (2.0 * t);
    let s = (1.0 - c * c).sqrt();
    let x = (d - h * s / c) / 2.0;
    let z = -x * c / s;
    let ring = found.nodes[1];
    // the fixed point stops within tolerance × size (10⁻¹² × 4.1 m) of its limit
    assert!(
        (ring - Vector3::new(x, 0.0, z)).amax() < 1e-11,
        "{ring:?} against ({x}, 0, {z})"
    );
    let tight = Settings {
        tolerance: 1e-15,
        ..Settings::default()
    };
    let exact = form_find(&topology, &tight).unwrap().nodes[1];
    assert!(
        (exact - Vector3::new(x, 0.0, z)).amax() < 1e-14,
        "{exact:?} against ({x}, 0, {z})"
    );
    // the load bisects the angle: e₁ + e₂ is vertical, W/t long
    let e1 = (found.nodes[0] - ring).normalize();
    let e2 = (found.nodes[2] - ring).normalize();
    assert!((e1 + e2 - Vector3::new(0.0, 0.0, w / t)).amax() < 1e-11);
    // iterated, to the tolerance, and the residual of tension exactly t checked here too
    assert!(found.iterations > 5, "{}", found.iterations);
    assert_eq!(found.tolerance, Some(1e-12));
    assert!(found.equilibrium_residual.unwrap() < 1e-12);
    assert!(equilibrium(&topology, &found) < 1e-12);
    let cluster = &found.clusters[0];
    assert_eq!(cluster.tension, t);
    for (q, l) in cluster
        .segment_force_density
        .iter()
        .zip(&cluster.segment_length)
    {
        assert!((q * l - t).abs() < 1e-12 * t);
    }
    // the reactions are t e at the anchors: Σ r + Σ p = 0
    let r0 = Vector3::from(found.reactions[0].force);
    let toward_ring = (ring - found.nodes[0]).normalize();
    assert!((r0 + t * toward_ring).amax() < 1e-11, "{r0:?}");
    let total: Vector3<f64> = found.reactions.iter().map(|r| Vector3::from(r.force)).sum();
    assert!((total + Vector3::new(0.0, 0.0, -w)).amax() < 1e-11);
}

#[test]
fn a_fixed_point_not_reached_is_an_error_not_a_result() {
    let few = Settings {
        max_iterations: 3,
        ..Settings::default()
    };
    let e = form_find(&clothesline(4.0, 1.0, 10.0, 10.0), &few).unwrap_err();
    match &e {
        FormFindError::NotConverged {
            iterations,
            residual,
            ..
        } => assert!(*iterations == 3 && *residual > 1e-12, "{e}"),
        _ => panic!("{e}"),
    }
    assert!(e.to_string().contains("q_i = t/l_i"), "{e}");
    // a load the tension cannot carry (W > 2t: no equilibrium) never converges either
    let heavy = form_find(&clothesline(4.0, 0.0, 30.0, 10.0), &Settings::default());
    let e = heavy.unwrap_err().to_string();
    assert!(
        e.contains("diverged") && e.contains("no equilibrium"),
        "{e}"
    );
}

/// The cross: anchors 0 = (−2, 0, 0), 1 = (2, 0, 0), 2 = (0, −2, 0), 3 = (0, 2, 0); the
/// centre 4 loaded by P, on a cluster 0 → 4 → 1 of tension t and strings 4–2, 4–3 of q.
fn cross(t: f64, q: f64, p: f64) -> Topology {
    let anchors = [
        [-2.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, -2.0, 0.0],
        [0.0, 2.0, 0.0],
    ];
    Topology {
        n_nodes: 5,
        strings: vec![
            Member::new(4, 2).force_density(q),
            Member::new(4, 3).force_density(q),
        ],
        fixed: (0..4).map(|k| held(k, anchors[k])).collect(),
        loads: vec![NodeLoad {
            node: 4,
            force: [0.0, 0.0, -p],
        }],
        clusters: vec![ClusterString::new([0, 4, 1], t)],
        ..Topology::default()
    }
}

#[test]
fn a_symmetric_net_with_a_cluster_matches_its_hand_solution() {
    let (t, q, p) = (5.0, 1.0, 6.0);
    let topology = cross(t, q, p);
    let found = form_find(&topology, &Settings::default()).unwrap();
    // vertical balance of the centre at (0, 0, −s): 2 t s / √(4 + s²) + 2 q s = P
    let f = |s: f64| 2.0 * t * s / (4.0 + s * s).sqrt() + 2.0 * q * s - p;
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    let sag = 0.5 * (lo + hi);
    let centre = found.nodes[4];
    assert!(
        (centre - Vector3::new(0.0, 0.0, -sag)).amax() < 1e-12,
        "{centre:?} against sag {sag}"
    );
    // the same net with the cluster's two segments as strings of q = t / l, l = √(4 + s²)
    // by hand: the plain force density method finds the same form in one solve
    let l = (4.0 + sag * sag).sqrt();
    let mut plain = topology.clone();
    plain.clusters.clear();
    plain.strings.push(Member::new(0, 4).force_density(t / l));
    plain.strings.push(Member::new(4, 1).force_density(t / l));
    let by_hand = form_find(&plain, &Settings::default()).unwrap();
    assert_eq!(by_hand.iterations, 1);
    assert!((by_hand.nodes[4] - centre).amax() < 1e-12);
    for (a, b) in found.clusters[0]
        .segment_force_density
        .iter()
        .zip([t / l; 2])
    {
        assert!((a - b).abs() < 1e-12 * b, "{a} against {b}");
    }
    assert!(equilibrium(&topology, &found) < 1e-12);
    // a loaded form's prestress is its largest string tension: the cluster's t here
    let report = find(
        topology,
        "cross".into(),
        &Settings::default(),
        &Synthesis::default(),
    );
    let report = report.unwrap().report;
    assert!((report.prestress - t).abs() < 1e-12, "{}", report.prestress);
}

/// A cluster through two free nodes, each also held sideways by a string: not symmetric in
/// the segments' lengths, so the segments' force densities differ while the tension is one.
fn zigzag() -> Topology {
    Topology {
        n_nodes: 6,
        strings: vec![
            Member::new(1, 4).force_density(2.0),
            Member::new(2, 5).force_density(3.0),
        ],
        fixed: vec![
            held(0, [0.0, 0.0, 0.0]),
            held(3, [5.0, 0.0, 1.0]),
            held(4, [1.0, 2.0, 0.5]),
            held(5, [3.5, -2.0, 0.0]),
        ],
        loads: vec![
            NodeLoad {
                node: 1,
                force: [0.0, 0.0, -4.0],
            },
            NodeLoad {
                node: 2,
                force: [0.0, 0.5, -2.0],
            },
        ],
        clusters: vec![ClusterString::new([0, 1, 2, 3], 7.0)],
        ..Topology::default()
    }
}

#[test]
fn an_unsymmetric_cluster_keeps_one_tension_and_the_plain_method_agrees() {
    let topology = zigzag();
    let found = form_find(&topology, &Settings::default()).unwrap();
    let c = &found.clusters[0];
    let (l, q) = (&c.segment_length, &c.segment_force_density);
    assert!(
        (q[0] - q[1]).abs() > 1e-3 && (q[1] - q[2]).abs() > 1e-3,
        "{q:?}"
    );
    assert!((c.length - l.iter().sum::<f64>()).abs() < 1e-15);
    assert!(
        equilibrium(&topology, &found) < 1e-11,
        "{}",
        equilibrium(&topology, &found)
    );
    // q_i = t / l_i as plain strings: the same nodes in one solve
    let plain = as_strings(&topology, 7.0, l);
    let by_hand = form_find(&plain, &Settings::default()).unwrap();
    for (a, b) in by_hand.nodes.iter().zip(&found.nodes) {
        assert!((a - b).amax() < 1e-11, "{a:?} against {b:?}");
    }
}

#[test]
fn self_weight_and_a_cluster_iterate_together() {
    // the zigzag's strings weigh 0.3 N/m: the loads and the segments' q both follow the form
    let mut topology = zigzag();
    for s in topology.strings.iter_mut() {
        s.weight = Some(0.3);
    }
    let found = form_find(&topology, &Settings::default()).unwrap();
    let l = &found.clusters[0].segment_length;
    let plain = as_strings(&topology, 7.0, l);
    // the plain method's own self-weight fixed point with those q: the same form and loads
    let by_hand = form_find(&plain, &Settings::default()).unwrap();
    for (a, b) in by_hand.nodes.iter().zip(&found.nodes) {
        assert!((a - b).amax() < 1e-11, "{a:?} against {b:?}");
    }
    for (a, b) in by_hand.loads.iter().zip(&found.loads) {
        assert_eq!(a.node, b.node);
        let d = Vector3::from(a.force) - Vector3::from(b.force);
        assert!(d.amax() < 1e-11, "{a:?} against {b:?}");
    }
    assert!(found.equilibrium_residual.unwrap() < 1e-11);
}

#[test]
fn rest_lengths_of_a_cluster_are_l_minus_t_over_k() {
    let topology = zigzag();
    let found = form_find(&topology, &Settings::default()).unwrap();
    let syn = Synthesis {
        stiffness: 3e4,
        ..Synthesis::default()
    };
    let r = rest_lengths(&topology, &found, &syn).unwrap();
    let c = &r.clusters[0];
    let (t, big_l) = (7.0, found.clusters[0].length);
    // a loaded form is not scaled: the cluster carries its t
    assert!((c.tension - t).abs() < 1e-12 * t);
    assert_eq!(c.axial_stiffness, 3e4);
    assert!((c.rest_length - big_l / (1.0 + t / 3e4)).abs() < 1e-12 * big_l);
    assert!((c.rest_length - (big_l - t / c.stiffness)).abs() < 1e-12 * big_l);
    assert!((c.stiffness - 3e4 / c.rest_length).abs() < 1e-12 * c.stiffness);
    // the structure carries it as a core cluster: k (L − L₀) = t at the found nodes
    let s = synthesize(&topology, &found, &syn).unwrap();
    let core = &s.clusters()[0];
    assert_eq!(core.nodes, vec![0, 1, 2, 3]);
    let k = core.stiffness.unwrap();
    let l0 = core.rest_length.unwrap();
    assert!((k * (big_l - l0) - t).abs() < 1e-9 * t);
    // its own stiffness, or E A of its material, wins over the synthesis'
    let mut own = topology.clone();
    own.clusters[0].material = Some("steel".into());
    own.clusters[0].area = Some(1e-6);
    let r = rest_lengths(&own, &found, &syn).unwrap();
    assert!((r.clusters[0].axial_stiffness - 206e9 * 1e-6).abs() < 1e-6);
    own.clusters[0].area = None;
    own.clusters[0].stiffness = Some(5e4);
    let r = rest_lengths(&own, &found, &syn).unwrap();
    assert_eq!(r.clusters[0].axial_stiffness, 5e4);
}

#[test]
fn dynamic_relaxation_with_a_clustered_ring_finds_the_force_density_form() {
    // the 3-bar prism: the force density form and its tensions at 100 N
    let t = formfind::builtin("prism:3").unwrap();
    let fdm = Settings {
        method: Method::Fdm,
        ..Settings::default()
    };
    let found = form_find(&t, &fdm).unwrap();
    let syn = Synthesis::default();
    let r = rest_lengths(&t, &found, &syn).unwrap();
    // its bottom ring (strings 0–2: 0→1→2→0, one tension by symmetry) as one cluster of
    // that tension, every other member with its rest length
    let nb = t.bars.len();
    let ring = r.tension[nb];
    let mut dr = t.with_lengths(&r.rest_length, &r.stiffness);
    dr.strings.drain(0..3);
    for g in dr.groups.values_mut() {
        g.length = None;
    }
    dr.groups.remove("bottom");
    dr.clusters = vec![ClusterString::new([0, 1, 2, 0], ring)];
    let wobble = |i: usize, k: usize| 0.01 * ((i * 7 + k * 13) as f64 * 0.37).sin();
    let start = found.nodes.iter().enumerate();
    let start = start.map(|(i, p)| [p.x + wobble(i, 0), p.y + wobble(i, 1), p.z + wobble(i, 2)]);
    dr.nodes = Some(start.collect());
    let analysed = Settings {
        analyse: true,
        ..Settings::default()
    };
    let relaxed = form_find(&dr, &analysed).unwrap();
    assert_eq!(relaxed.method, Method::Dr);
    for (k, &[i, j]) in t.member_nodes().iter().enumerate() {
        let l = |x: &[Vector3<f64>]| (x[j] - x[i]).norm();
        let (a, b) = (l(&found.nodes), l(&relaxed.nodes));
        assert!((a - b).abs() < 1e-8 * a, "member {k}: {b} against {a}");
    }
    let c = &relaxed.clusters[0];
    assert_eq!(c.tension, ring);
    assert_eq!(relaxed.prestressable, Some(true), "{relaxed:?}");
    // synthesised again at 100 N (the largest string tension, as before): the ring carries
    // its tension, and the written cluster k (L − L₀) gives it back
    let again = rest_lengths(&dr, &relaxed, &syn).unwrap();
    let cr = &again.clusters[0];
    assert!(
        (cr.tension - ring).abs() < 1e-6 * ring,
        "{} against {ring}",
        cr.tension
    );
    let s = synthesize(&dr, &relaxed, &syn).unwrap();
    let core = &s.clusters()[0];
    let (k, l0) = (core.stiffness.unwrap(), core.rest_length.unwrap());
    assert!((k * (c.length - l0) - cr.tension).abs() < 1e-9 * ring);
}

#[test]
fn methods_that_cannot_take_clusters_refuse_them_by_name() {
    // free-standing under the force density method
    let mut free = formfind::builtin("prism:3").unwrap();
    free.n_nodes = 7;
    free.nodes = None;
    free.clusters = vec![ClusterString::new([0, 6, 4], 1.0)];
    for s in free.strings.iter_mut() {
        s.force_density = Some(1.0);
    }
    for b in free.bars.iter_mut() {
        b.force_density = Some(-1.0);
        b.group = None;
    }
    for s in free.strings.iter_mut() {
        s.group = None;
    }
    free.groups.clear();
    let e = form_find(&free, &Settings::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("clusters[0]: the force density method takes clusters on held nodes"),
        "{e}"
    );
    // the adaptive method
    let adaptive = Settings {
        method: Method::Adaptive,
        ..Settings::default()
    };
    let e = form_find(&zigzag(), &adaptive).unwrap_err().to_string();
    assert!(e.starts_with("clusters[0]: the adaptive method"), "{e}");
    // no tension, a bad one, two nodes, a segment on a member
    let mut t = zigzag();
    t.clusters[0].force = None;
    let e = form_find(&t, &Settings::default()).unwrap_err().to_string();
    assert!(e.starts_with("clusters[0].force: no tension given"), "{e}");
    t.clusters[0].force = Some(-1.0);
    let e = form_find(&t, &Settings::default()).unwrap_err().to_string();
    assert!(
        e.starts_with("clusters[0].force: -1 must be finite and positive"),
        "{e}"
    );
    let mut t = zigzag();
    t.clusters[0].nodes = vec![0, 1];
    let e = form_find(&t, &Settings::default()).unwrap_err().to_string();
    assert!(
        e.contains("clusters[0]") && e.contains("at least three"),
        "{e}"
    );
    let mut t = zigzag();
    t.clusters[0].nodes = vec![0, 1, 4];
    let e = form_find(&t, &Settings::default()).unwrap_err().to_string();
    assert!(
        e.contains("clusters[0]: its segment joins nodes 1 and 4, as strings[0] does"),
        "{e}"
    );
}

/// `topology` with its one cluster (tension `t`) given as plain strings of force densities
/// t / l_i at the segments' lengths `l`: one linear force density solve of the same form.
fn as_strings(topology: &Topology, t: f64, l: &[f64]) -> Topology {
    let mut plain = topology.clone();
    plain.clusters.clear();
    for (s, [a, b]) in topology.clusters[0].segments().enumerate() {
        plain
            .strings
            .push(Member::new(a, b).force_density(t / l[s]));
    }
    plain
}
