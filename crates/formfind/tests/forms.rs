//! Closed forms of the built-in topologies: the prism's twist and force-density ratios, the
//! expanded octahedron's bar spacing and string/bar ratio, towers and grids.

use formfind::{builtin, form_find, prism_twist, FormFound, Method, Settings, Topology};
use nalgebra::Vector3;
use std::f64::consts::PI;

fn settings(method: Method) -> Settings {
    Settings {
        method,
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
    assert!(f.prestressable && f.prestress_stable, "prism:{n}: {f:?}");
    assert_eq!(f.self_stress_dim, 1, "prism:{n}");
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
    // The default method falls back to the adaptive one when the given q admit no form.
    let auto = form_find(&t, &Settings::default()).unwrap();
    assert_eq!(auto.method, Method::Adaptive);
    let exact = form_find(&builtin("prism:5").unwrap(), &Settings::default()).unwrap();
    assert_eq!(exact.method, Method::Fdm);
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
    assert!(f.prestressable && f.prestress_stable);
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
    assert!(f.prestressable && f.prestress_stable);
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
        let f = form_find(&t, &Settings::default()).unwrap();
        assert_eq!(f.method, Method::Fdm);
        assert!(f.residual < 1e-10 * f.structure_size(), "{}", f.residual);
        assert!(f.prestressable && f.prestress_stable, "tower:{n}:{m}");
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
        let f = form_find(&t, &Settings::default()).unwrap();
        assert_eq!(f.method, Method::Fdm);
        // The exact lattice comes back.
        for (p, p0) in f.nodes.iter().zip(t.nodes.as_ref().unwrap()) {
            assert!((p - Vector3::from(*p0)).amax() < 1e-12);
        }
        assert!(f.residual < 1e-12, "grid:{k}: {}", f.residual);
        assert!(f.prestressable && f.prestress_stable, "grid:{k}");
    }
}

#[test]
fn the_grid_of_ten_thousand_members_exists() {
    let t = builtin("grid:27").unwrap();
    assert!(t.n_members() >= 10_000, "{}", t.n_members());
}

#[test]
#[ignore = "the large grid in a debug build takes a while: cargo test --release -p formfind -- --ignored"]
fn large_grid_is_form_found_sparsely() {
    let t = builtin("grid:27").unwrap();
    let f = form_find(&t, &Settings::default()).unwrap();
    assert!(f.residual < 1e-10, "{}", f.residual);
    assert!(f.prestressable && f.prestress_stable);
}
