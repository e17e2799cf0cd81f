//! The T-bar side of `tbar roll` (moved from the CLI): the polygon of the wheel and its
//! impact ratio, the request's defaults and refusals, and the full model against the rigid
//! polygon through the first pivot.

use super::*;
use crate::rolling::{impact_ratio, mass_properties};
use tensegrity_core::request::Params;

/// The request of `--beta pi/6 --cylindrical 0.25 --t-end 2`.
fn request() -> TbarRollRequest {
    TbarRollRequest {
        t_end: Some(2.0),
        ..TbarRollRequest::default()
    }
}

#[test]
fn the_request_describes_every_field() {
    tensegrity_core::request::check_description::<TbarRollRequest>().unwrap();
    // 24 and the two result checks (strict, convergence_check)
    assert_eq!(TbarRollRequest::params().len(), 26);
    // the full model's contact defaults to friction that sticks
    assert_eq!(TbarRollRequest::default().contact, ContactKind::Stick);
}

#[test]
fn the_defaults_depend_on_the_fidelity() {
    let rigid = TbarRollRequest::default();
    assert_eq!((rigid.t_end(), rigid.treads()), (10.0, vec![8, 12, 16, 24]));
    assert_eq!(rigid.rim().unwrap(), RimMode::Fixed);
    let full = TbarRollRequest {
        fidelity: FidelityChoice::Full,
        ..rigid.clone()
    };
    assert_eq!((full.t_end(), full.treads()), (1.0, vec![8]));
    assert_eq!(full.rim().unwrap(), RimMode::Body);
    assert!((full.mu_kinetic() - 0.6).abs() < 1e-15);
    // a light rim body for the full model, the treads' bar density for the rigid one; 30°
    assert_eq!((full.rim_density(), rigid.rim_density()), (0.05, 1.0));
    assert!((rigid.settings.incline - 30f64.to_radians()).abs() < 1e-15);
    assert_eq!(rigid.settings.ground_stiffness, 1e6);
    // `auto` may run the full model: its defaults
    let auto = TbarRollRequest {
        fidelity: FidelityChoice::Auto,
        ..rigid
    };
    assert_eq!((auto.t_end(), auto.treads()), (1.0, vec![8]));
    assert_eq!(
        (auto.rim().unwrap(), auto.rim_density()),
        (RimMode::Body, 0.05)
    );
}

#[test]
fn what_the_command_line_refuses_is_refused_by_name() {
    let refused = |pairs: &[(&str, serde_json::Value)]| {
        TbarRollRequest::from_values(pairs.iter().map(|(k, v)| (k.to_string(), v.clone())))
            .unwrap_err()
            .name
            .to_string()
    };
    use serde_json::json;
    let full_fixed = [("fidelity", json!("full")), ("rim", json!("fixed"))];
    assert_eq!(refused(&full_fixed), "rim");
    assert_eq!(refused(&[("restitution", json!(1.5))]), "restitution");
    assert_eq!(refused(&[("incline", json!("90deg"))]), "incline");
    assert_eq!(refused(&[("treads", json!("8,1"))]), "treads");
    // fewer than three treads is no polygon (`roll` refuses sides below 3 alike)
    for t in ["0", "1", "2", "8,2"] {
        assert_eq!(refused(&[("treads", json!(t))]), "treads", "{t}");
    }
    assert_eq!(refused(&[("restitution", json!(2))]), "restitution");
    // above the T-bar wheel's limit: refused before any row is built
    assert_eq!(refused(&[("treads", json!("8,100000"))]), "treads");
    assert_eq!(refused(&[("r0", json!(0))]), "r0");
    let both = [("spherical", json!("pi/8")), ("cylindrical", json!(0.25))];
    assert_eq!(refused(&both), "spherical");
    let nan = TbarRollRequest {
        r0: f64::NAN,
        ..TbarRollRequest::default()
    };
    assert_eq!(nan.validate().unwrap_err().name, "r0");
    // the spherical parameterisation alone (the cylindrical default applies to neither given)
    let ok = TbarRollRequest::from_values([
        ("spherical".to_string(), json!("pi/8")),
        ("treads".to_string(), json!("6,12")),
    ])
    .unwrap();
    assert_eq!(ok.treads(), [6, 12]);
    assert!((ok.spherical.unwrap() - PI / 8.0).abs() < 1e-15);
    let spherical = ok.tbar_params(8, RimMode::Fixed).michell.geometry;
    assert_eq!(
        spherical,
        michell3d::Geometry::Spherical {
            epsilon: ok.spherical.unwrap()
        }
    );
    // neither given: the documented δ = 0.25
    let neither = TbarRollRequest::default().tbar_params(8, RimMode::Fixed);
    assert_eq!(
        neither.michell.geometry,
        michell3d::Geometry::Cylindrical {
            delta: DEFAULT_CYLINDRICAL
        }
    );
}

#[test]
fn the_tbar_model_is_the_polygon_of_the_wheel_and_its_impact_ratio_the_formula() {
    let a = TbarRollRequest {
        extended: Some(0.5),
        ..request()
    };
    let p = a.tbar_params(12, RimMode::Fixed);
    assert_eq!(p.layout, Layout::Extended { offset: 0.5 });
    let g = TbarGeometry::new(p).unwrap();
    let mp = mass_properties(&g, 1.0).unwrap();
    let polygon = mp.polygon();
    assert_eq!((polygon.sides, polygon.outer_radius), (12, 1.0));
    assert_eq!((polygon.mass, polygon.i1), (mp.mass, mp.i1));
    let mr2 = mp.mass;
    let want = (mp.i1 + mr2 * (PI / 6.0).cos()) / (mp.i1 + mr2);
    assert!((polygon.impact_ratio() - want).abs() < 1e-14);
    assert!((impact_ratio(&mp) - want).abs() < 1e-14);
    let model = wheel_rolling::RigidRolling::new(&polygon, &a.spec(FidelityChoice::Rigid));
    assert!((model.mu_kinetic - 0.6).abs() < 1e-15);
}

#[test]
fn rigid_rows_roll_the_polygon_and_report_the_tipover() {
    let a = TbarRollRequest {
        extended: Some(0.4),
        ..request()
    };
    let rows: Vec<TbarRollRow> = [8, 12]
        .iter()
        .map(|&n| a.tbar_row(n, RimMode::Fixed))
        .collect();
    for row in &rows {
        assert!(row.errors.is_empty(), "{:?}", row.errors);
        let t = row.tbar.as_ref().unwrap();
        // 50° > π/n: the polygon rolls and bumps
        assert!(t.summary.impacts > 0 && t.model == Fidelity::Rigid);
        let tip = row.tipover.as_ref().unwrap();
        let mg = row.mass_properties.unwrap().mass * 9.81;
        assert!((tip.critical_lateral_force - 0.5 * mg * 0.4).abs() < 1e-12);
    }
    // more treads, smaller oscillation
    let osc = |i: usize| {
        rows[i]
            .tbar
            .as_ref()
            .unwrap()
            .summary
            .axle_height_oscillation
    };
    assert!(osc(1) < osc(0));
}

#[test]
fn full_and_rigid_agree_through_the_first_pivot() {
    // n = 6 treads (φ = π/6), 40° > π/6, μ = 1.2 (no slip), e = 0; stiff strings
    // (2·10⁶ N/m) and ground (10⁶ N/m), a light rim body (0.05 kg/m): the full wheel
    // pivots about its downhill tip like the rigid polygon of the same mass and I₁. Both
    // slide a little at the end of the pivot (the pivot unloads), so ω⁻ stays below the
    // no-slip energy bound ½(I₁ + m r₀²) ω⁻² = 2 m g r₀ sin φ sin(π/n) (≈ 12 % below).
    // Measured (RK4 at 0.1 ms): t 1.0301 / 1.0302 s, ω⁻ 2.6015 / 2.5967 rad/s (0.2 %); at
    // 0.05 ms 1.02955 s and 2.6011 rad/s. About 10 s.
    let a = TbarRollRequest {
        fidelity: FidelityChoice::Full,
        treads: Some(vec![6]),
        t_end: Some(1.1),
        settings: RollSettings {
            incline: 40f64.to_radians(),
            string_stiffness: 2e6,
            ground_stiffness: 1e6,
            dt: Some(1e-4),
            ..RollSettings::default()
        },
        mu_static: 1.2,
        rim_density: Some(0.05),
        ..TbarRollRequest::default()
    };
    let p = a.tbar_params(6, RimMode::Body);
    let (full, details, w) = a.full_run(&p).unwrap();
    let rigid = a.rigid_run(&w.mass.polygon()).unwrap();
    let (m, i1, g, phi) = (w.mass.mass, w.mass.i1, 9.81, 40f64.to_radians());
    let omega = (4.0 * m * g * phi.sin() * (PI / 6.0).sin() / (i1 + m)).sqrt();
    let (r, f) = (
        rigid.summary.first_impact.unwrap(),
        full.summary.first_impact.unwrap(),
    );
    assert!(r.omega_before < omega && r.omega_before > 0.8 * omega);
    assert!((f.t - r.t).abs() < 0.03 * r.t, "{} vs {}", f.t, r.t);
    assert!((f.omega_before - r.omega_before).abs() < 0.01 * r.omega_before);
    assert!(full.summary.max_penetration < 0.01 && full.summary.min_normal_force >= 0.0);
    assert_eq!((details.rim_bars, details.redundant_rim_bars), (54, 7));
    assert_eq!(details.rim_spokes, 30);
    assert_eq!((details.nodes, details.bars, details.strings), (26, 60, 24));
}
