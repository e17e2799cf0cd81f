//! Must-show geometry and statics of issue 11: closed-form q = 1 coordinates, wheel and
//! extended-wheel counts, level sizes, the rim-supported q = 1 tread's self-stress.

use michell3d::MichellParams;
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::statics::statics_summary;
use tbar_wheel::{BarBase, Layout, TbarError, TbarGeometry, TbarParams};

fn cyl(q: usize, phi: f64, delta: f64) -> TbarParams {
    TbarParams::tread(MichellParams::cylindrical(q, 1.3, FRAC_PI_6, phi, delta))
}

fn node<'a>(g: &'a TbarGeometry, label: &str) -> &'a Vector3<f64> {
    let i = g.labels.iter().position(|l| l == label).unwrap();
    &g.nodes[i]
}

#[test]
fn q1_coordinates_match_the_closed_form() {
    // n_UDLR = r₁[𝕏δ, cos ℤφ, sin ℤφ] (§5.1), tip [0, r₀, 0], bar base [0, r₁, 0]
    let (phi, delta) = (PI / 8.0, 0.25);
    let p = cyl(1, phi, delta);
    let g = TbarGeometry::new(p).unwrap();
    let r0 = 1.3;
    let a = FRAC_PI_6.sin() / (FRAC_PI_6 + phi).sin();
    let r1 = r0 * a;
    assert_eq!(
        g.labels,
        ["tip", "bar_base", "1010", "1001", "0110", "0101"]
    );
    let want = |x: f64, z: f64| r1 * Vector3::new(x * delta, (z * phi).cos(), (z * phi).sin());
    for (label, x, z) in [
        ("1010", 1.0, 1.0),
        ("1001", -1.0, 1.0),
        ("0110", 1.0, -1.0),
        ("0101", -1.0, -1.0),
    ] {
        assert!((node(&g, label) - want(x, z)).norm() < 1e-12, "{label}");
    }
    assert!((node(&g, "tip") - Vector3::new(0.0, r0, 0.0)).norm() < 1e-15);
    assert!((node(&g, "bar_base") - Vector3::new(0.0, r1, 0.0)).norm() < 1e-15);
    assert_eq!(g.bars, [[1, 0]]);
    assert_eq!(g.strings.len(), 4);
    assert_eq!(g.supported, [false, true, true, true, true, true]);
    let chord = TbarGeometry::new(p.with_bar_base(BarBase::Chord)).unwrap();
    assert!((node(&chord, "bar_base") - Vector3::new(0.0, r1 * phi.cos(), 0.0)).norm() < 1e-15);
}

#[test]
fn spherical_q1_coordinates() {
    let (phi, eps) = (PI / 8.0, 0.2);
    let p = TbarParams::tread(MichellParams::spherical(1, 1.0, FRAC_PI_6, phi, eps));
    let g = TbarGeometry::new(p).unwrap();
    let r1 = p.rim_radius();
    let n = node(&g, "0101");
    let want = r1 * Vector3::new(phi.cos() * (-eps).tan(), phi.cos(), -phi.sin());
    assert!((n - want).norm() < 1e-12);
}

#[test]
fn wheel_and_extended_wheel_counts() {
    let p = cyl(1, PI / 8.0, 0.25).with_layout(Layout::Wheel);
    let g = TbarGeometry::new(p).unwrap();
    assert_eq!(
        (g.treads(), g.nodes.len(), g.bars.len(), g.strings.len()),
        (8, 32, 8, 32)
    );
    // 8 tips and 8 bar bases free of sharing, 16 shared rim nodes
    assert_eq!(g.supported.iter().filter(|s| **s).count(), 24);
    let e = TbarGeometry::new(p.with_layout(Layout::Extended { offset: 0.4 })).unwrap();
    assert_eq!(
        (e.treads(), e.nodes.len(), e.bars.len(), e.strings.len()),
        (16, 64, 16, 64)
    );
    // the copy is the wheel translated along ι̂₁
    for i in 0..32 {
        assert!((e.nodes[32 + i] - e.nodes[i] - Vector3::new(0.4, 0.0, 0.0)).norm() < 1e-12);
    }
    // tread 1 is tread 0 rotated by 2φ: its tip
    let t1 = node(&g, "t1.tip");
    let ang = PI / 4.0;
    assert!((t1 - 1.3 * Vector3::new(0.0, ang.cos(), ang.sin())).norm() < 1e-12);
    assert!(e.structure().is_ok());
}

#[test]
fn level_sizes_and_bar_base_merge() {
    let g = TbarGeometry::new(cyl(4, PI / 16.0, 0.1)).unwrap();
    assert_eq!(g.level_sizes, [1, 4, 9, 16, 25]);
    // even q: the rim bar base is the lattice node 2222, one node: 55 lattice nodes + 0
    assert_eq!(g.nodes.len(), 55);
    assert!(!g.labels.iter().any(|l| l == "2222"));
    assert_eq!(g.strings.len(), 4 * (1 + 4 + 9 + 16));
    // odd q: a separate base
    let g3 = TbarGeometry::new(cyl(3, PI / 16.0, 0.1)).unwrap();
    assert_eq!(g3.nodes.len(), 30 + 1);
    // chord base: never a lattice node
    let g4c = TbarGeometry::new(cyl(4, PI / 16.0, 0.1).with_bar_base(BarBase::Chord)).unwrap();
    assert_eq!(g4c.nodes.len(), 56);
}

#[test]
fn non_integer_tread_count_is_a_clear_error() {
    let p = cyl(1, 0.3, 0.25).with_layout(Layout::Wheel);
    match TbarGeometry::new(p) {
        Err(TbarError::InvalidParameter(p)) => assert_eq!(p.name, "phi"),
        other => panic!("expected an invalid phi, got {other:?}"),
    }
    let e = cyl(1, PI / 8.0, 0.25).with_layout(Layout::Extended { offset: 0.0 });
    assert!(matches!(
        TbarGeometry::new(e),
        Err(TbarError::InvalidParameter(p)) if p.name == "extended"
    ));
    assert!(TbarGeometry::new(cyl(1, PI / 8.0, 0.0)).is_err());
}

#[test]
fn rim_supported_q1_tread_has_two_self_stresses_and_is_prestressable() {
    for base in [BarBase::Rim, BarBase::Chord] {
        let s = TbarGeometry::new(cyl(1, PI / 8.0, 0.25).with_bar_base(base))
            .unwrap()
            .structure()
            .unwrap();
        let sum = statics_summary(&s).unwrap();
        assert_eq!(sum.free_dofs, 3);
        assert_eq!(sum.rank, 3);
        assert_eq!(sum.self_stress_dim, 2);
        assert_eq!(sum.internal_mechanisms, 0);
        assert!(sum.prestressable, "{base:?}");
        assert!(sum.prestress_margin > 0.05);
    }
}
