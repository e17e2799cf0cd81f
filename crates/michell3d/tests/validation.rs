//! Every invalid parameter gives a clear error naming it; no panic, no NaN.

use michell3d::*;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_6, PI};

fn name_of(p: MichellParams) -> String {
    match MichellTruss::new(p) {
        Err(MichellError::InvalidParameter(e)) => {
            assert!(!e.reason.is_empty());
            e.name.into_owned()
        }
        other => panic!("expected InvalidParameter for {p:?}, got {other:?}"),
    }
}

#[test]
fn invalid_parameters_are_named() {
    let ok = MichellParams::cylindrical(3, 1.0, FRAC_PI_6, 0.3, 0.2);
    assert!(MichellTruss::new(ok).is_ok());
    let cases: Vec<(MichellParams, &str)> = vec![
        (ok.with_complexity(0), "complexity"),
        (
            ok.with_complexity(params::MAX_COMPLEXITY_3D + 1),
            "complexity",
        ),
        (MichellParams { r0: 0.0, ..ok }, "r0"),
        (MichellParams { r0: f64::NAN, ..ok }, "r0"),
        (MichellParams { beta: 0.0, ..ok }, "beta"),
        (MichellParams { beta: -0.2, ..ok }, "beta"),
        (
            MichellParams {
                beta: FRAC_PI_2,
                ..ok
            },
            "beta",
        ),
        (MichellParams { phi: 0.0, ..ok }, "phi"),
        (
            MichellParams {
                phi: f64::INFINITY,
                ..ok
            },
            "phi",
        ),
        (
            MichellParams {
                beta: 2.0,
                phi: 1.2,
                ..ok
            },
            "beta",
        ), // β + φ ≥ π
        (
            MichellParams::cylindrical(3, 1.0, FRAC_PI_6, 0.3, 0.0),
            "delta",
        ),
        (
            MichellParams::cylindrical(3, 1.0, FRAC_PI_6, 0.3, f64::NAN),
            "delta",
        ),
        (
            MichellParams::spherical(3, 1.0, FRAC_PI_6, 0.3, 0.0),
            "epsilon",
        ),
        (
            MichellParams::spherical(3, 1.0, FRAC_PI_6, 0.3, 0.6),
            "epsilon",
        ), // |qε| ≥ π/2
        (
            MichellParams::spherical(3, 1.0, FRAC_PI_6, 0.3, -0.6),
            "epsilon",
        ),
        // ERRATA 4.9: q = 2, φ = π/2 merges n₁₀₁₀ and n₁₀₀₁ (cos φ = 0).
        (
            MichellParams::spherical(2, 1.0, FRAC_PI_6, FRAC_PI_2, 0.1),
            "phi",
        ),
        // With φ = π/8 spherical trusses are valid only up to q = 3.
        (
            MichellParams::spherical(4, 1.0, FRAC_PI_6, PI / 8.0, 0.05),
            "phi",
        ),
        // a^q underflows.
        (MichellParams::planar(1000, 1.0, 0.01, 3.0), "complexity"),
    ];
    for (p, expected) in cases {
        assert_eq!(name_of(p), expected, "{p:?}");
    }
    assert!(MichellTruss::new(MichellParams::spherical(3, 1.0, FRAC_PI_6, PI / 8.0, 0.05)).is_ok());
}

#[test]
fn invalid_loads_are_named() {
    let err = |r: Result<nalgebra::Vector3<f64>>| match r {
        Err(MichellError::InvalidParameter(e)) => e.name.into_owned(),
        other => panic!("{other:?}"),
    };
    assert_eq!(err(tip_load(0.0, 0.0, PI)), "load");
    assert_eq!(err(tip_load(-5.0, 0.0, PI)), "load");
    assert_eq!(err(tip_load(f64::NAN, 0.0, PI)), "load");
    assert_eq!(err(tip_load(1.0, f64::NAN, PI)), "azimuth");
    assert_eq!(err(tip_load(1.0, 0.0, f64::INFINITY)), "polar");

    // A planar truss refuses out-of-plane loads but accepts φ_w = 0, γ = π (w_x ≈ 1e-13).
    let planar = MichellTruss::new(MichellParams::planar(3, 1.0, 0.5, 0.3)).unwrap();
    let out = NodalLoads::tip(tip_load(10.0, 0.0, 1.0).unwrap());
    for m in [Method::Recursive, Method::Global] {
        assert!(matches!(
            propagate(&planar, &out, m),
            Err(MichellError::OutOfPlaneLoad { w_x, .. }) if w_x.abs() > 1.0
        ));
        let s = propagate(
            &planar,
            &NodalLoads::tip(tip_load(10.0, 0.0, PI).unwrap()),
            m,
        )
        .unwrap();
        assert!(s.force_density.iter().all(|q| q.is_finite()));
    }
    // Overflow is an error, not inf/NaN.
    let t = MichellTruss::new(MichellParams::cylindrical(2, 1.0, 0.5, 0.3, 0.1)).unwrap();
    let huge = NodalLoads::tip(nalgebra::Vector3::new(1e308, 1e308, -1e308));
    assert!(matches!(
        propagate_recursive(&t, &huge),
        Err(MichellError::NonFinite { .. })
    ));
    assert!(propagate(&t, &huge, Method::Global).is_err());
    // Unknown nodes and members.
    let t = MichellTruss::new(MichellParams::cylindrical(2, 1.0, 0.5, 0.3, 0.1)).unwrap();
    let bad = NodalLoads::new().add(999, nalgebra::Vector3::x());
    assert!(matches!(
        propagate_recursive(&t, &bad),
        Err(MichellError::UnknownNode { index: 999, .. })
    ));
    let grid = AngleGrid::new(0.0, 1.0, 3);
    assert!(matches!(
        sign_maps(&t, &[12], 1.0, grid, grid, Method::Recursive),
        Err(MichellError::UnknownMember {
            index: 12,
            count: 12
        })
    ));
    assert!(matches!(
        sign_maps(&planar, &[0], 1.0, grid, grid, Method::Recursive),
        Err(MichellError::NeedsThreeD { .. })
    ));
    let empty = AngleGrid::new(0.0, 1.0, 0);
    assert!(matches!(
        sign_maps(&t, &[0], 1.0, empty, grid, Method::Recursive),
        Err(MichellError::EmptyGrid { name: "azimuth" })
    ));
}

#[test]
fn analysis_errors_name_the_item() {
    let p = MichellParams::cylindrical(2, 1.0, 0.5, 0.3, 0.1);
    let mut req = AnalysisRequest::new(p);
    req.material = "unobtainium".into();
    let msg = analyse(&req).unwrap_err().to_string();
    assert!(msg.contains("unobtainium"), "{msg}");
    let mut req = AnalysisRequest::new(p);
    req.extra_strings = Some(-1.0);
    assert!(matches!(
        analyse(&req),
        Err(MichellError::InvalidParameter(e)) if e.name == "extra-strings"
    ));
    let mut req = AnalysisRequest::new(p.with_complexity(1));
    req.extra_strings = Some(10.0);
    assert!(matches!(
        analyse(&req),
        Err(MichellError::InvalidParameter(e)) if e.name == "complexity"
    ));
    let mut req = AnalysisRequest::new(p);
    req.load = 0.0;
    assert!(matches!(
        analyse(&req),
        Err(MichellError::InvalidParameter(e)) if e.name == "load"
    ));
}
