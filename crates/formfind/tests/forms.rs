//! Closed forms of the built-in topologies: the prism's twist and force-density ratios, the
//! expanded octahedron's bar spacing and string/bar ratio, towers and grids.

use formfind::{builtin, form_find, prism_twist, FormFound, Method, Settings, Topology};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The settings of `method` with the statics of the form asked for (the assertions below
/// check them).
fn settings(method: Method) -> Settings {
    Settings {
        method,
        analyse: true,
        ..Settings::default()
    }
}

/// The topology with every given force density removed (groups kept): only connectivity
/// and kinds remain for the adaptive method.
fn without_force_densities(mut t: Topology) -> Topology {
    for g in t.groups.values_mut() {
        g.force_density = None;
    }
    for m in t.bars.iter_mut().chain(t.strings.iter_mut()) {
        m.force_density = None;
    }
    t
}

/// Twist of the top polygon against the bottom one about the axis from the bottom centroid
/// to the top centroid, and the two radii.
fn prism_measures(n: usize, f: &FormFound) -> (f64, f64, f64) {
    let cb: Vector3<f64> = f.nodes[..n].iter().sum::<Vector3<f64>>() / n as f64;
    let ct: Vector3<f64> = f.nodes[n..].iter().sum::<Vector3<f64>>() / n as f64;
    let axis = (ct - cb).normalize();
    let flat = |v: Vector3<f64>| v - axis * axis.dot(&v);
    let b0 = flat(f.nodes[0] - cb);
    let t0 = flat(f.nodes[n] - ct);
    let twist = axis.dot(&b0.cross(&t0)).atan2(b0.dot(&t0));
    let rb = b0.norm();
    let rt = t0.norm();
    // Every node on its circle, every step 2π/N.
    for i in 0..n {
        assert!(((flat(f.nodes[i] - cb)).norm() - rb).abs() < 1e-10 * rb);
        assert!(((flat(f.nodes[n + i] - ct)).norm() - rt).abs() < 1e-10 * rt);
    }
    (twist.rem_euclid(2.0 * PI), rb, rt)
}

fn check_prism(n: usize, f: &FormFound) {
    let (twist, rb, rt) = prism_measures(n, f);
    let expected = prism_twist(n);
    assert!(
        (twist - expected).abs() < 1e-10,
        "prism:{n} ({}): twist {twist} vs π/2 + π/N = {expected}",
        f.method
    );
    let q = &f.force_density;
    let vertical = q[3 * n];
    let s = (PI / n as f64).sin();
    let ratios = [
        (q[0] / vertical, -1.0),
        (q[n] / vertical, rt / (2.0 * rb * s)),
        (q[2 * n] / vertical, rb / (2.0 * rt * s)),
    ];
    for (k, (got, want)) in ratios.iter().enumerate() {
        assert!(
            (got - want).abs() < 1e-10,
            "prism:{n} ({}) ratio {k}: {got} vs {want}",
            f.method
        );
    }
    // Group equalities.
    for i in 0..n {
        for (a, b) in [(0, i), (n, n + i), (2 * n, 2 * n + i), (3 * n, 3 * n + i)] {
            assert!((q[a] - q[b]).abs() < 1e-10 * q[a].abs());
        }
    }
    assert!(
        f.prestressable == Some(true) && f.prestress_stable == Some(true),
        "prism:{n}: {f:?}"
    );
    assert_eq!(f.self_stress_dim, Some(1), "prism:{n}");
    assert!(
        f.residual < 1e-10 * f.structure_size(),
        "prism:{n}: {}",
        f.residual
    );
}

#[test]
fn prism_twist_and_force_density_ratios_by_fdm() {
    for n in 3..=12 {
        let t = builtin(&format!("prism:{n}")).unwrap();
        let f = form_find(&t, &settings(Method::Fdm)).unwrap();
        check_prism(n, &f);
    }
}

#[test]
fn prism_twist_is_found_from_a_wrong_initial_twist() {
    for n in [3, 7, 12] {
        let mut t = builtin(&format!("prism:{n}")).unwrap();
        let nodes = t.nodes.as_mut().unwrap();
        for i in 0..n {
            let a = 2.0 * PI * i as f64 / n as f64 + 0.3;
            nodes[n + i] = [1.3 * a.cos(), 1.3 * a.sin(), 0.7];
        }
        let f = form_find(&t, &settings(Method::Fdm)).unwrap();
        check_prism(n, &f);
    }
}

#[test]
fn prism_canonical_form_without_nodes_is_right_handed() {
    for n in 3..=12 {
        let mut t = builtin(&format!("prism:{n}")).unwrap();
        t.nodes = None;
        let f = form_find(&t, &settings(Method::Fdm)).unwrap();
        check_prism(n, &f);
    }
}

#[test]
fn fixed_nodes_may_stand_alone() {
    // A string between two held nodes and one free node pulled by two strings: a held node
    // on no member is an anchor of nothing, accepted.
    let t = Topology {
        n_nodes: 4,
        strings: vec![
            formfind::Member::new(0, 2).force_density(1.0),
            formfind::Member::new(2, 1).force_density(3.0),
        ],
        fixed: vec![
            formfind::FixedNode {
                node: 0,
                position: [0.0, 0.0, 0.0],
            },
            formfind::FixedNode {
                node: 1,
                position: [4.0, 0.0, 0.0],
            },
            formfind::FixedNode {
                node: 3,
                position: [9.0, 9.0, 9.0],
            },
        ],
        ..Topology::default()
    };
    let f = form_find(&t, &settings(Method::default())).unwrap();
    // q₁ (x − 0) = q₂ (4 − x): x = 3.
    assert!((f.nodes[2] - Vector3::new(3.0, 0.0, 0.0)).norm() < 1e-14);
}

#[test]
fn prism_force_densities_found_by_the_adaptive_method() {
    for n in 3..=12 {
        let t = without_force_densities(builtin(&format!("prism:{n}")).unwrap());
        let f = form_find(&t, &settings(Method::Adaptive)).unwrap();
        assert_eq!(f.method, Method::Adaptive);
        check_prism(n, &f);
    }
}

#[test]
fn adaptive_prism_from_unequal_rings_keeps_a_valid_family_member() {
    // Start with bottom ≠ top: the adaptive method lands on a prism with r_t ≠ r_b, still
    // in the closed-form ratios.
    let mut t = builtin("prism:5").unwrap();
    t.groups.get_mut("bottom").unwrap().force_density = Some(0.5);
    t.groups.get_mut("top").unwrap().force_density = Some(1.5);
    let f = form_find(&t, &settings(Method::Adaptive)).unwrap();
    check_prism(5, &f);
    // The default method never falls back: q that admit no form are the error, naming the
    // adaptive method; `auto` falls back to it and says why.
    let e = form_find(&t, &settings(Method::default())).unwrap_err();
    assert!(
        matches!(e, formfind::FormFindError::RankDeficiency { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("`method = adaptive`"), "{e}");
    let auto = form_find(&t, &settings(Method::Auto)).unwrap();
    assert_eq!(auto.method, Method::Adaptive);
    let why = auto.choice.unwrap();
    assert!(why.starts_with("method auto chose adaptive: the force density method found no form (the force density matrix has rank deficiency 2"), "{why}");
    let exact = form_find(&builtin("prism:5").unwrap(), &settings(Method::default())).unwrap();
    assert_eq!((exact.method, exact.choice), (Method::Fdm, None));
}

fn check_octahedron(f: &FormFound) {
    let bar = |b: usize| (f.nodes[2 * b], f.nodes[2 * b + 1]);
    for pair in 0..3 {
        let (a0, a1) = bar(2 * pair);
        let (b0, b1) = bar(2 * pair + 1);
        let da = a1 - a0;
        let db = b1 - b0;
        let len = da.norm();
        assert!(
            da.normalize().cross(&db.normalize()).norm() < 1e-10,
            "bars {} and {} not parallel",
            2 * pair,
            2 * pair + 1
        );
        // Distance between the two parallel lines.
        let u = da / len;
        let w = b0 - a0;
        let dist = (w - u * u.dot(&w)).norm();
        assert!(
            (dist - 0.5 * len).abs() < 1e-10 * len,
            "pair {pair}: distance {dist} vs half the bar length {}",
            0.5 * len
        );
    }
    let q = &f.force_density;
    for k in 6..30 {
        assert!(
            (q[k] / q[0] + 2.0 / 3.0).abs() < 1e-10,
            "string {k}: {}",
            q[k] / q[0]
        );
    }
    assert!(f.prestressable == Some(true) && f.prestress_stable == Some(true));
}

#[test]
fn octahedron_bars_half_a_length_apart_at_minus_two_thirds() {
    let t = builtin("octahedron").unwrap();
    assert_eq!((t.bars.len(), t.strings.len()), (6, 24));
    let f = form_find(&t, &settings(Method::Fdm)).unwrap();
    check_octahedron(&f);
    let f = form_find(&without_force_densities(t), &settings(Method::Adaptive)).unwrap();
    check_octahedron(&f);
}

#[test]
fn octahedron_from_the_canonical_normalisation() {
    // Without initial nodes the canonical form (isotropic, principal axes) is an affine
    // image; the force densities and the statics do not depend on it.
    let mut t = builtin("octahedron").unwrap();
    t.nodes = None;
    let f = form_find(&t, &settings(Method::Fdm)).unwrap();
    assert!(f.residual < 1e-10 * f.structure_size());
    assert!(f.prestressable == Some(true) && f.prestress_stable == Some(true));
    let mean_bar: f64 = (0..6)
        .map(|b| (f.nodes[2 * b + 1] - f.nodes[2 * b]).norm())
        .sum::<f64>()
        / 6.0;
    assert!((mean_bar - 1.0).abs() < 1e-12);
}

#[test]
fn towers_are_in_equilibrium_and_stable() {
    for (n, m) in [(3, 2), (4, 3), (6, 4)] {
        let t = builtin(&format!("tower:{n}:{m}")).unwrap();
        assert_eq!(t.bars.len(), n * m);
        assert_eq!(t.strings.len(), n * (m + 1) + n * m);
        let f = form_find(&t, &settings(Method::default())).unwrap();
        assert_eq!(f.method, Method::Fdm);
        assert!(f.residual < 1e-10 * f.structure_size(), "{}", f.residual);
        assert!(
            f.prestressable == Some(true) && f.prestress_stable == Some(true),
            "tower:{n}:{m}"
        );
        // Each stage twisted by π/2 + π/N against the one below (layer l at l·twist).
        for l in 1..=m {
            let a = f.nodes[l * n];
            let b = f.nodes[0];
            let twist = a.y.atan2(a.x) - b.y.atan2(b.x);
            let want = l as f64 * prism_twist(n);
            let d = (twist - want).rem_euclid(2.0 * PI);
            assert!(d.min(2.0 * PI - d) < 1e-10, "tower:{n}:{m} layer {l}");
        }
    }
}

#[test]
fn grids_are_in_equilibrium_with_the_boundary_fixed() {
    for k in [1, 2, 4] {
        let t = builtin(&format!("grid:{k}")).unwrap();
        assert_eq!(t.bars.len(), 4 * k * k);
        assert_eq!(t.strings.len(), 2 * k * (k + 1) + 8 * k * k);
        let f = form_find(&t, &settings(Method::default())).unwrap();
        assert_eq!(f.method, Method::Fdm);
        // The exact lattice comes back.
        for (p, p0) in f.nodes.iter().zip(t.nodes.as_ref().unwrap()) {
            assert!((p - Vector3::from(*p0)).amax() < 1e-12);
        }
        assert!(f.residual < 1e-12, "grid:{k}: {}", f.residual);
        assert!(
            f.prestressable == Some(true) && f.prestress_stable == Some(true),
            "grid:{k}"
        );
    }
}

#[test]
fn the_grid_of_ten_thousand_members_exists() {
    let t = builtin("grid:27").unwrap();
    assert!(t.n_members() >= 10_000, "{}", t.n_members());
}

#[test]
fn large_grid_is_form_found_sparsely() {
    // 10 260 members: the sparse path (timed by the bench and the README's table, never here).
    let t = builtin("grid:27").unwrap();
    let f = form_find(&t, &settings(Method::default())).unwrap();
    assert!(f.residual < 1e-10, "{}", f.residual);
    assert!(f.prestressable == Some(true) && f.prestress_stable == Some(true));
}

#[test]
fn the_planar_x_module_is_a_square() {
    // Two crossing bars inside a ring of four strings: D has rank deficiency 3, a planar
    // form; with bar q = −1 and string q = 1 the ring is a square (closed form).
    let t = Topology {
        n_nodes: 4,
        bars: vec![
            formfind::Member::new(0, 2).force_density(-1.0),
            formfind::Member::new(1, 3).force_density(-1.0),
        ],
        strings: (0..4)
            .map(|i| formfind::Member::new(i, (i + 1) % 4).force_density(1.0))
            .collect(),
        ..Topology::default()
    };
    let f = form_find(&t, &settings(Method::Fdm)).unwrap();
    assert!(f.nodes.iter().all(|p| p.z == 0.0));
    let side: Vec<f64> = (0..4)
        .map(|i| (f.nodes[(i + 1) % 4] - f.nodes[i]).norm())
        .collect();
    let diag = (f.nodes[2] - f.nodes[0]).norm();
    for s in &side {
        assert!((s / side[0] - 1.0).abs() < 1e-12);
    }
    assert!((diag / side[0] - 2f64.sqrt()).abs() < 1e-12);
    assert!(f.residual < 1e-12 && f.prestressable == Some(true));
    assert_eq!(f.self_stress_dim, Some(1));
}

#[test]
fn the_result_serialises_with_the_contract_keys() {
    let f = form_find(&builtin("prism:3").unwrap(), &settings(Method::default())).unwrap();
    let v = serde_json::to_value(&f).unwrap();
    for key in [
        "method",
        "nodes",
        "force_density",
        "self_stress_dim",
        "prestressable",
        "prestress_stable",
        "residual",
        "iterations",
    ] {
        assert!(v.get(key).is_some(), "{key}");
    }
    assert_eq!(v["method"], "fdm");
    assert_eq!(v["nodes"].as_array().unwrap().len(), 6);
    assert_eq!(v["nodes"][0].as_array().unwrap().len(), 3);
    assert_eq!(v["force_density"].as_array().unwrap().len(), 12);
}

#[test]
fn estimates_grow_with_the_topology() {
    let small = formfind::estimate(&builtin("prism:4").unwrap(), &settings(Method::default()));
    let large = formfind::estimate(&builtin("grid:27").unwrap(), &settings(Method::default()));
    assert!(small.work_s < large.work_s && small.memory_bytes < large.memory_bytes);
    assert!(large.work_s < 60.0, "{large:?}");
    let adaptive = formfind::estimate(
        &builtin("tower:12:99").unwrap(),
        &settings(Method::Adaptive),
    );
    assert!(adaptive.work_s > large.work_s, "{adaptive:?}");
}

#[test]
fn a_large_prism_takes_the_sparse_anchored_path() {
    // 1202 nodes, over DENSE_MAX_NODES: four anchors, sparse LU, affine fit to the guess.
    let n = 601;
    assert!(2 * n > formfind::DENSE_MAX_NODES);
    let f = form_find(
        &builtin(&format!("prism:{n}")).unwrap(),
        &settings(Method::Fdm),
    )
    .unwrap();
    check_prism(n, &f);
}

#[test]
fn a_large_tower_with_folds_is_refused_not_garbled() {
    // Stacked prisms sharing planar rings: D has null vectors beyond the affine maps (a fold
    // at every inner ring), so four anchors do not fix the form. Over DENSE_MAX_NODES the
    // sparse path must say so.
    let (n, m) = (13, 100);
    assert!(n * (m + 1) > formfind::DENSE_MAX_NODES);
    assert!(builtin(&format!("tower:{n}:{m}")).is_err());
    let small = builtin("tower:13:1").unwrap();
    let a = prism_twist(n);
    let mut t = Topology {
        n_nodes: n * (m + 1),
        groups: small.groups.clone(),
        ..Topology::default()
    };
    let mut nodes = Vec::new();
    for l in 0..=m {
        for i in 0..n {
            let th = 2.0 * PI * i as f64 / n as f64 + l as f64 * a;
            nodes.push([th.cos(), th.sin(), l as f64]);
        }
    }
    t.nodes = Some(nodes);
    for s in 0..m {
        for i in 0..n {
            t.bars
                .push(formfind::Member::new(s * n + i, (s + 1) * n + i).group("bars"));
            t.strings.push(
                formfind::Member::new(s * n + i, (s + 1) * n + (i + n - 1) % n).group("vertical"),
            );
        }
    }
    for l in 0..=m {
        let g = if l == 0 || l == m {
            "ring_end"
        } else {
            "ring_inner"
        };
        for i in 0..n {
            t.strings
                .push(formfind::Member::new(l * n + i, l * n + (i + 1) % n).group(g));
        }
    }
    match form_find(&t, &settings(Method::Fdm)) {
        Err(formfind::FormFindError::RankDeficiency { hint, .. }) => {
            assert!(hint.contains("held nodes"), "{hint}")
        }
        other => panic!("{other:?}"),
    }
}
