//! The T-bar wheel's symmetry-adapted statics against the dense path: wheels and extended
//! wheels, cylindrical and spherical, rim and chord bar bases, complexities 1 and 2.

use michell3d::MichellParams;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::statics::statics_summary;
use tbar_wheel::symmetry::{symmetric_statics_summary, wheel_symmetry};
use tbar_wheel::{BarBase, Layout, TbarGeometry, TbarParams};

#[test]
fn symmetric_statics_equal_dense_statics() {
    let mut nontrivial = false;
    for q in [1, 2] {
        for (michell, n) in [
            (
                MichellParams::cylindrical(q, 1.0, FRAC_PI_6, PI / 8.0, 0.25),
                8,
            ),
            (MichellParams::cylindrical(q, 1.3, 0.4, PI / 6.0, 0.6), 6),
            (
                MichellParams::spherical(q, 1.0, FRAC_PI_6, PI / 8.0, 0.3),
                8,
            ),
        ] {
            for base in [BarBase::Rim, BarBase::Chord] {
                for layout in [Layout::Wheel, Layout::Extended { offset: 0.7 }] {
                    let p = TbarParams::tread(michell)
                        .with_layout(layout)
                        .with_bar_base(base);
                    let g = TbarGeometry::new(p).unwrap();
                    let s = g.structure().unwrap();
                    assert_eq!(wheel_symmetry(&g, &s).unwrap().order(), n);
                    let a = symmetric_statics_summary(&g).unwrap();
                    let b = statics_summary(&s).unwrap();
                    let what = format!("q = {q}, {base:?}, {layout:?}, n = {n}");
                    assert_eq!(
                        (a.free_dofs, a.rank, a.self_stress_dim, a.mechanisms),
                        (b.free_dofs, b.rank, b.self_stress_dim, b.mechanisms),
                        "{what}"
                    );
                    assert_eq!(a.internal_mechanisms, b.internal_mechanisms, "{what}");
                    assert_eq!(a.prestressable, b.prestressable, "{what}");
                    assert!(
                        (a.prestress_margin - b.prestress_margin).abs() < 1e-9,
                        "{what}: {} vs {}",
                        a.prestress_margin,
                        b.prestress_margin
                    );
                    nontrivial |= a.prestressable && a.self_stress_dim > 1;
                }
            }
        }
    }
    assert!(
        nontrivial,
        "some wheel is prestressable with several self-stresses"
    );
}

#[test]
fn a_single_tread_has_no_cyclic_symmetry() {
    let m = MichellParams::cylindrical(1, 1.0, FRAC_PI_6, PI / 8.0, 0.25);
    let g = TbarGeometry::new(TbarParams::tread(m)).unwrap();
    let err = wheel_symmetry(&g, &g.structure().unwrap()).unwrap_err();
    assert!(err.to_string().contains("n ≥ 3"), "{err}");
}
