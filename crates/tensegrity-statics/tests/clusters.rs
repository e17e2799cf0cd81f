//! The statics of clustered strings (`tensegrity_core::Cluster`, one column per cluster of
//! unknown q_c = t_c / L_c: `tensegrity_statics::cluster_columns`), against hand counts and
//! closed forms:
//!
//! - a mass hanging from an anchor over one frictionless pulley: one unknown, t = W in both
//!   segments, the anchor's and the pulley's reactions in closed form (1e-12);
//! - the Snelson prism with its bottom ring clustered: the counts derived by hand (below),
//!   the prestress the unclustered prism's, and the unclustered prism's usual counts;
//! - the tangent stiffness of a cluster against a central difference of its nodal forces
//!   (1e-7 relative), and its stress matrix against a difference of t ∂L/∂x;
//! - the back-ends that do not model clusters refuse them, naming the cluster.

use nalgebra::{DVector, Vector3};
use tensegrity_core::{Bar, Cluster, StringMember, Structure, Support};
use tensegrity_statics::report::{statics_report, StaticsRequest};
use tensegrity_statics::{stiffness, DofMap, StaticsMethod, StaticsSettings};

/// Anchor (0, 0, 0) and pulley (4, 0, 3), both pinned; the mass at (4, 0, 1) hangs from the
/// pulley: segment 0 → 1 of length 5 along e₁ = (0.8, 0, 0.6), segment 1 → 2 of length 2
/// along e₂ = (0, 0, −1); W = 10 N down on node 2.
fn pulley(w: f64) -> Structure {
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [4.0, 0.0, 3.0], [4.0, 0.0, 1.0]])
        .cluster(Cluster::new([0, 1, 2]))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .load(2, [0.0, 0.0, -w])
        .build()
        .unwrap()
}

#[test]
fn a_mass_over_a_pulley_pulls_both_segments_with_its_weight() {
    let w = 10.0;
    let s = pulley(w);
    let r = statics_report(&s, &StaticsRequest::default()).unwrap();
    // one column, three free dofs (node 2): rank 1, no self-stress, two swinging motions
    assert_eq!((r.clusters, r.rank, r.self_stress_dim), (1, 1, 0));
    assert_eq!((r.mechanisms, r.load_carried), (2, Some(true)));
    let (q, f) = (r.force_density.unwrap(), r.member_force.unwrap());
    assert_eq!((q.len(), f.len()), (1, 1));
    // t = W, q_c = t / L_c with L_c = 5 + 2
    assert!((f[0] - w).abs() < 1e-12 * w, "{f:?}");
    assert!((q[0] - w / 7.0).abs() < 1e-12 * w, "{q:?}");
    assert!(r.residual.unwrap() < 1e-12 * w);
    // the string pulls the anchor with t e₁ and the pulley with t (−e₁ + e₂) (unit vectors
    // from the pulley towards its neighbours); the supports push back
    let (e1, e2) = (Vector3::new(0.8, 0.0, 0.6), Vector3::new(0.0, 0.0, -1.0));
    let reactions = r.reactions.unwrap();
    let anchor = Vector3::from(reactions[0].force);
    let pulley = Vector3::from(reactions[1].force);
    assert!((anchor - (-w * e1)).norm() < 1e-12 * w, "{anchor}");
    assert!((pulley - (-w * (-e1 + e2))).norm() < 1e-12 * w, "{pulley}");
    // [8, 0, 16] N on the pulley: the two segments' pulls added
    assert!((pulley - Vector3::new(8.0, 0.0, 16.0)).norm() < 1e-12 * w);
}

/// The Snelson prism of `examples/prism.toml` (unit radius and height, twist 30°); with
/// `clustered`, its bottom ring strings (0, 1), (1, 2), (2, 0) are one cluster [0, 1, 2, 0].
fn prism(clustered: bool) -> Structure {
    let node = |deg: f64, z: f64| {
        let a = deg.to_radians();
        [a.cos(), a.sin(), z]
    };
    let mut b = Structure::builder()
        .nodes((0..3).map(|i| node(120.0 * i as f64, 0.0)))
        .nodes((0..3).map(|i| node(120.0 * i as f64 + 30.0, 1.0)))
        .bars((0..3).map(|i| Bar::new(i, 3 + (i + 1) % 3)));
    if clustered {
        b = b.cluster(Cluster::new([0, 1, 2, 0]));
    } else {
        b = b.strings((0..3).map(|i| StringMember::new(i, (i + 1) % 3)));
    }
    b.strings((0..3).map(|i| StringMember::new(3 + i, 3 + (i + 1) % 3)))
        .strings((0..3).map(|i| StringMember::new(i, 3 + i)))
        .build()
        .unwrap()
}

/// The unclustered prism: 3 bars + 9 strings = 12 columns, 18 dofs, one self-stress, so
/// rank 11 and 18 − 11 = 7 mechanisms: 6 rigid-body motions and the twist.
#[test]
fn the_unclustered_prism_has_the_usual_counts() {
    let r = statics_report(&prism(false), &StaticsRequest::default()).unwrap();
    assert_eq!((r.clusters, r.rank, r.self_stress_dim), (0, 11, 1));
    assert_eq!((r.mechanisms, r.internal_mechanisms), (7, 1));
    assert!(r.prestressable);
}

/// The clustered prism, by hand: the cluster's column is Σ_i (L/l_i) × (ring string i's
/// column), L/l_i = 3 for the three equal segments, so the columns of the clustered matrix
/// are those of the unclustered one times an injective 12 × 10 map T. Its null space is
/// {y : T y ∈ null(A)}; the prism's one self-stress has equal ring force densities, so it
/// lies in the range of T: one self-stress still. Columns 3 + 6 + 1 = 10, so rank 10 − 1 = 9
/// (two fewer than 11: the three ring columns span one), and 18 − 9 = 9 mechanisms: the 6
/// rigid-body motions, the twist, and 2 sliding motions (three segment lengths held by one
/// constraint on their sum). The self-stress is the unclustered one with q_c = q_ring / 3,
/// i.e. the ring tension t = q_c L = q_ring l: the three ring strings' equal tension.
#[test]
fn the_clustered_prism_counts_its_sliding_and_keeps_the_ring_tension() {
    let r = statics_report(&prism(true), &StaticsRequest::default()).unwrap();
    assert_eq!((r.bars, r.strings, r.clusters), (3, 6, 1));
    assert_eq!((r.rank, r.self_stress_dim), (9, 1));
    assert_eq!((r.mechanisms, r.internal_mechanisms), (9, 3));
    assert!(r.prestressable);
    let clustered = r.prestress.unwrap();
    let plain = statics_report(&prism(false), &StaticsRequest::default())
        .unwrap()
        .prestress
        .unwrap();
    // the order: bars 0..3, strings 3..9 (top ring, verticals), the cluster last
    assert_eq!(clustered.len(), 10);
    let ring = prism(false).member_lengths()[3];
    let l_cluster = 3.0 * ring;
    // both scaled to max|q| = 1 on the bars: the same bars, top ring and verticals
    for k in 0..3 {
        assert!((clustered[k] - plain[k]).abs() < 1e-12, "bar {k}");
    }
    for k in 0..6 {
        assert!(
            (clustered[3 + k] - plain[6 + k]).abs() < 1e-12,
            "string {k}"
        );
    }
    // the ring strings' equal tension q_ring l is the cluster's q_c L_c
    for k in 3..6 {
        assert!((plain[k] - plain[3]).abs() < 1e-12);
        assert!((clustered[9] * l_cluster - plain[k] * ring).abs() < 1e-12);
    }
}

/// Four nodes off any plane, a cluster 0 → 1 → 2 → 3 (k = 500 N/m, L₀ = 0.8 L) and a string
/// 3 → 0 (k = 200 N/m, taut) beside it.
fn stretched_cluster(x: &[[f64; 3]]) -> Structure {
    let l = |a: usize, b: usize| (Vector3::from(x[b]) - Vector3::from(x[a])).norm();
    let total = l(0, 1) + l(1, 2) + l(2, 3);
    Structure::builder()
        .nodes(x.iter().copied())
        .cluster(
            Cluster::new([0, 1, 2, 3])
                .stiffness(500.0)
                .rest_length(0.8 * total),
        )
        .string(
            StringMember::new(3, 0)
                .stiffness(200.0)
                .rest_length(0.9 * l(3, 0)),
        )
        .build()
        .unwrap()
}

const X: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.2, 0.1],
    [1.3, 1.1, -0.4],
    [0.2, 0.9, 0.7],
];

/// The nodal forces the members exert (N, 12 numbers), written out independently: the
/// cluster's −t_c ∂L/∂x with t_c = k (L − L₀) (L₀ fixed at the base state's), the string's
/// ±t e.
fn nodal_forces(x: &[f64]) -> DVector<f64> {
    let p = |i: usize| Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    let base: Vec<Vector3<f64>> = X.iter().map(|v| Vector3::from(*v)).collect();
    let l0 = 0.8 * (0..3).map(|i| (base[i + 1] - base[i]).norm()).sum::<f64>();
    let s0 = 0.9 * (base[0] - base[3]).norm();
    let mut f = DVector::zeros(12);
    let length: f64 = (0..3).map(|i| (p(i + 1) - p(i)).norm()).sum();
    let t = 500.0 * (length - l0);
    for i in 0..3 {
        let e = (p(i + 1) - p(i)).normalize();
        for d in 0..3 {
            f[3 * i + d] += t * e[d];
            f[3 * (i + 1) + d] -= t * e[d];
        }
    }
    let m = p(0) - p(3);
    let ts = 200.0 * (m.norm() - s0);
    for d in 0..3 {
        f[9 + d] += ts * m[d] / m.norm();
        f[d] -= ts * m[d] / m.norm();
    }
    f
}

#[test]
fn the_tangent_of_a_cluster_is_the_derivative_of_its_forces() {
    let s = stretched_cluster(&X);
    let dofs = DofMap::stiffness_of(&s);
    let q = stiffness::string_force_densities(&s).unwrap();
    let axial = stiffness::axial_stiffness(&s).unwrap();
    assert_eq!((q.len(), axial.len()), (2, 2));
    assert_eq!(axial[1], 500.0);
    let k = stiffness::tangent_stiffness(&s, &dofs, &q, &axial);
    let x0: Vec<f64> = X.iter().flatten().copied().collect();
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for c in 0..12 {
        let (mut xp, mut xm) = (x0.clone(), x0.clone());
        xp[c] += h;
        xm[c] -= h;
        // K = −∂F/∂x
        let column = -(nodal_forces(&xp) - nodal_forces(&xm)) / (2.0 * h);
        worst = worst.max((k.column(c) - column).amax());
    }
    println!(
        "tangent against the difference: {:.2e} relative",
        worst / k.amax()
    );
    assert!(worst < 1e-7 * k.amax(), "{worst:e} of {:e}", k.amax());
    // the material part couples segments 0 and 2, which share no node
    assert!(k[(0, 9)].abs() > 1.0 && k[(0, 6)].abs() > 1.0);
}

/// The stress matrix of the cluster is its geometric stiffness t_c ∇²L_c: K with the axial
/// stiffnesses set to 0, and the difference of t ∂L/∂x at fixed t.
#[test]
fn the_stress_matrix_of_a_cluster_is_t_times_the_hessian_of_its_length() {
    let s = stretched_cluster(&X);
    let dofs = DofMap::of(&s);
    let q = stiffness::string_force_densities(&s).unwrap();
    let omega = stiffness::stress_matrix(&s, &dofs, &q);
    let k0 = stiffness::tangent_stiffness(&s, &dofs, &q, &[0.0, 0.0]);
    // the string's block differs: q I against q (I − e eᵀ); compare the cluster's nodes 1, 2
    // (the string 3 → 0 touches neither)
    for r in 3..9 {
        for c in 3..9 {
            assert!((omega[(r, c)] - k0[(r, c)]).abs() < 1e-12 * k0.amax());
        }
    }
    // columns: the string (member 0), then the cluster
    let t = q[1] * s.clusters()[0].length(s.nodes());
    let grad = |x: &[f64]| {
        let p = |i: usize| Vector3::new(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
        let mut g = DVector::zeros(12);
        for i in 0..3 {
            let e = (p(i + 1) - p(i)).normalize();
            for d in 0..3 {
                g[3 * i + d] -= e[d];
                g[3 * (i + 1) + d] += e[d];
            }
        }
        g
    };
    let x0: Vec<f64> = X.iter().flatten().copied().collect();
    let h = 1e-6;
    for c in 3..9 {
        let (mut xp, mut xm) = (x0.clone(), x0.clone());
        xp[c] += h;
        xm[c] -= h;
        let column = (grad(&xp) - grad(&xm)) * (t / (2.0 * h));
        for r in 3..9 {
            assert!(
                (omega[(r, c)] - column[r]).abs() < 1e-7 * omega.amax(),
                "({r}, {c})"
            );
        }
    }
}

#[test]
fn back_ends_that_do_not_model_clusters_refuse_them_by_name() {
    let s = prism(true);
    // the sparse QR models the cluster: the hand count (10 columns, rank 9, one self-stress,
    // three internal mechanisms) and the dense report's prestress
    let sparse = StaticsRequest {
        settings: StaticsSettings::default().method(StaticsMethod::Sparse),
        ..StaticsRequest::default()
    };
    let r = statics_report(&s, &sparse).unwrap();
    assert_eq!(
        (r.rank, r.self_stress_dim, r.internal_mechanisms),
        (9, 1, 3)
    );
    let dense = StaticsRequest {
        settings: StaticsSettings::default().method(StaticsMethod::Dense),
        ..StaticsRequest::default()
    };
    let d = statics_report(&s, &dense).unwrap();
    let (qs, qd) = (r.prestress.unwrap(), d.prestress.unwrap());
    let scale = qd.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    for (a, b) in qs.iter().zip(&qd) {
        assert!((a - b).abs() < 1e-12 * scale, "{a} vs {b}");
    }
    assert_eq!(r.prestress_stable, d.prestress_stable);
    let e = tensegrity_statics::NestedStatics::with_settings(&s, StaticsSettings::default())
        .map(|_| ())
        .unwrap_err();
    assert!(e.to_string().contains("nested-dissection"), "{e}");
    // the dense method models it
    let request = StaticsRequest {
        settings: StaticsSettings::default().method(StaticsMethod::Dense),
        ..StaticsRequest::default()
    };
    assert_eq!(statics_report(&s, &request).unwrap().self_stress_dim, 1);
}

/// The linear response of the pulley with the hanging node on a vertical guide (held in x
/// and y) and the cluster just taut (k = 1000 N/m, L₀ = 7 m − 1 µm: t₀ = 1 mN, whose
/// geometric stiffness (t₀/l)(I − e₂e₂ᵀ) does not act along e₂): one free coordinate,
/// K = k (∂L/∂z₂)² = k, so u_z = −W/k, Δt = k δL = W, and the pulley reacts with
/// Δt (e₁ − e₂) = (8, 0, 16) N.
#[test]
fn the_linear_response_of_the_pulley_is_the_closed_form() {
    let (w, k) = (10.0, 1000.0);
    let s = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [4.0, 0.0, 3.0], [4.0, 0.0, 1.0]])
        .cluster(Cluster::new([0, 1, 2]).stiffness(k).rest_length(7.0 - 1e-6))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .support(Support::directions(2, [true, true, false]))
        .load(2, [0.0, 0.0, -w])
        .build()
        .unwrap();
    let r = tensegrity_statics::response::linear_response(&s, &[]).unwrap();
    assert!(
        (r.displacements[2][2] + w / k).abs() < 1e-15,
        "{:?}",
        r.displacements
    );
    assert!((r.member_force_change[0] - w).abs() < 1e-12);
    assert!((r.initial_force[0] - 1e-3).abs() < 1e-12 && r.slack_clusters.is_empty());
    let pulley = Vector3::from(r.reactions[1].force);
    assert!(
        (pulley - Vector3::new(8.0, 0.0, 16.0)).norm() < 1e-12,
        "{pulley}"
    );
    let anchor = Vector3::from(r.reactions[0].force);
    assert!(
        (anchor + Vector3::new(8.0, 0.0, 6.0)).norm() < 1e-12,
        "{anchor}"
    );
}

/// The pulley pushed up (W = −10 N down, i.e. 10 N up) puts the cluster in compression
/// (t = −10 N): the sizing warns naming it, sized for yield on |t| over its whole length;
/// without a material the loaded cluster is a sizing error naming it.
#[test]
fn a_cluster_in_compression_is_named_by_the_sizing() {
    let steel = tensegrity_core::Material::new(7862.0, 210e9, 690e6);
    let build = |material: bool| {
        let cluster = Cluster::new([0, 1, 2]);
        let b = Structure::builder()
            .material("rope", steel)
            .nodes([[0.0, 0.0, 0.0], [4.0, 0.0, 3.0], [4.0, 0.0, 1.0]])
            .cluster(if material {
                cluster.material("rope")
            } else {
                cluster
            })
            .bar(Bar::new(0, 2).material("rope"))
            .support(Support::pinned(0))
            .support(Support::pinned(1))
            .load(2, [0.0, 0.0, 10.0]);
        b.build().unwrap()
    };
    let r = statics_report(&build(true), &StaticsRequest::default()).unwrap();
    let warning = r.sizing_warning.expect("a warning");
    assert!(warning.contains("cluster 0 in compression"), "{warning}");
    let f = r.member_force.unwrap();
    let masses = r.member_mass_kg.unwrap();
    // columns: the bar, then the cluster (its force −|t| for the total length 7 m)
    assert_eq!(f.len(), 2);
    assert!(
        (masses[1] - 7862.0 / 690e6 * f[1].abs() * 7.0).abs() < 1e-15,
        "{masses:?}"
    );
    assert!(f[1] < 0.0, "{f:?}");
    let r = statics_report(&build(false), &StaticsRequest::default()).unwrap();
    let e = r.sizing_error.expect("a sizing error");
    assert!(e.starts_with("cluster 0: sizing needs its material"), "{e}");
}
