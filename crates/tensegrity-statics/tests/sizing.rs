//! Minimum-mass sizing against the published benchmark values (thesis eq. 4.54–4.61).

use crate::common;

use approx::assert_relative_eq;
use common::*;
use nalgebra::DVector;
use tensegrity_core::{Bar, CoreError, MemberId, StaticsError, StringMember, Structure, Support};
use tensegrity_statics::sizing::{self, Governing};
use tensegrity_statics::Statics;

#[test]
fn one_aluminium_bar_two_metres_ten_kilonewtons() {
    let s = Structure::builder()
        .material("alu", alu())
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("alu"))
        .support(Support::pinned(0))
        .load(1, [-1.0e4, 0.0, 0.0])
        .build()
        .unwrap();
    let sol = Statics::new(&s).unwrap().solve_loads();
    assert_relative_eq!(sol.member_force[0], -1.0e4, max_relative = 1e-12);
    let report = sizing::size_structure(&s, &sol.member_force).unwrap();
    assert_relative_eq!(report.total_mass, 4.975116, epsilon = 5e-7);
    assert_eq!(report.members[0].governing, Governing::Buckling);
    // yield alone would need far less: ρ/σ · |f| · l
    assert_relative_eq!(
        report.yield_only_mass,
        2700.0 / 110e6 * 1e4 * 2.0,
        max_relative = 1e-14
    );
    // the buckling radius makes the Euler load equal the applied load
    let r = report.members[0].radius;
    let euler = std::f64::consts::PI.powi(3) * 60e9 * r.powi(4) / (4.0 * 2.0 * 2.0);
    assert_relative_eq!(euler, 1.0e4, max_relative = 1e-12);
}

#[test]
fn forty_five_degree_dbar_two_metres_ten_kilonewtons() {
    let s = loaded_dbar(2.0, 1.0e4);
    let sol = Statics::new(&s).unwrap().solve_loads();
    let report = sizing::size_structure(&s, &sol.member_force).unwrap();
    assert_relative_eq!(report.total_mass, 8.858023, epsilon = 5e-7);
    // four buckling-governed bars, one yield-governed string
    assert!(report.members[..4]
        .iter()
        .all(|m| m.governing == Governing::Buckling));
    assert_eq!(report.members[4].governing, Governing::Yield);
    assert_relative_eq!(
        report.string_mass,
        2700.0 / 110e6 * 1e4 * 2.0,
        max_relative = 1e-12
    );
}

#[test]
fn mass_scales_as_published_exponents() {
    // yield mass ∝ f, buckling mass ∝ √f: doubling the load scales the two parts accordingly
    let a = loaded_dbar(2.0, 1.0e4);
    let b = loaded_dbar(2.0, 4.0e4);
    let ma =
        sizing::size_structure(&a, &Statics::new(&a).unwrap().solve_loads().member_force).unwrap();
    let mb =
        sizing::size_structure(&b, &Statics::new(&b).unwrap().solve_loads().member_force).unwrap();
    assert_relative_eq!(mb.bar_mass, 2.0 * ma.bar_mass, max_relative = 1e-12);
    assert_relative_eq!(mb.string_mass, 4.0 * ma.string_mass, max_relative = 1e-12);
}

#[test]
fn short_stocky_bars_are_yield_governed() {
    // r_B > r_Y  ⇔  f < π E l² ... for a 1 cm bar under 1 MN yield governs
    let m = sizing::size_bar(&alu(), -1.0e6, 0.01);
    assert_eq!(m.governing, Governing::Yield);
    assert_relative_eq!(m.mass, 2700.0 / 110e6 * 1e6 * 0.01, max_relative = 1e-14);
}

#[test]
fn strings_in_compression_and_missing_materials_are_reported() {
    let s = Structure::builder()
        .material("alu", alu())
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
        .bar(Bar::new(0, 1).material("alu"))
        .string(StringMember::new(1, 2).material("alu"))
        .string(StringMember::new(2, 0))
        .build()
        .unwrap();
    let err = sizing::size_structure(&s, &DVector::from_row_slice(&[-1.0, -2.0, 0.0])).unwrap_err();
    assert!(matches!(
        err,
        CoreError::Statics(StaticsError::StringInCompression {
            member: MemberId::String(0),
            ..
        })
    ));
    assert!(err.to_string().contains("string 0"));
    let err = sizing::size_structure(&s, &DVector::from_row_slice(&[-1.0, 2.0, 3.0])).unwrap_err();
    assert!(err.to_string().contains("string 1") && err.to_string().contains("material"));
    // an unloaded member needs no material
    let ok = sizing::size_structure(&s, &DVector::from_row_slice(&[-1.0, 2.0, 0.0])).unwrap();
    assert_eq!(ok.members[2].mass, 0.0);
}
