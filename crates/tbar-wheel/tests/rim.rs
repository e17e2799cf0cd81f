//! The rim body (issue 11 item 1), the single loop against the extended wheel (item 2), and
//! the mass properties and tip-over of item 5.

use michell3d::MichellParams;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::rolling::{impact_ratio, mass_properties, tipover};
use tbar_wheel::standing::{loop_study, Stance, StandingRow};
use tbar_wheel::{tbar_report, Layout, RimMode, TbarError, TbarGeometry, TbarParams, TbarRequest};

fn tread(q: usize, phi: f64) -> TbarParams {
    TbarParams::tread(MichellParams::cylindrical(q, 1.0, FRAC_PI_6, phi, 0.25))
}

/// Rim bars from the closed form (see the `rim` module docs): n treads per wheel, c copies;
/// `None` where no closed form is derived here (a single tread of q > 1).
fn rim_bars_closed_form(q: usize, n: usize, c: usize, layout: Layout) -> Option<usize> {
    let lattice = (q + 1) * c; // rim lattice nodes at one angle
    let (points, ring) = match (layout, q % 2) {
        // a q = 1 tread: groups at −φ (2 nodes), 0 (the base), +φ (2 nodes)
        (Layout::Tread, _) if q == 1 => (2 * lattice + 1, 2 * lattice),
        (Layout::Tread, _) => return None,
        (_, 1) => (n * lattice + n * c, 2 * n * lattice * c),
        (_, _) => (n * lattice, n * lattice * lattice),
    };
    Some(1 + 2 * points + ring)
}

#[test]
fn rim_body_counts_follow_the_closed_form() {
    let n = 8;
    for (q, layout, c) in [
        (1, Layout::Tread, 1),
        (1, Layout::Wheel, 1),
        (1, Layout::Extended { offset: 0.5 }, 2),
        (2, Layout::Wheel, 1),
        (2, Layout::Extended { offset: -0.4 }, 2),
        (3, Layout::Wheel, 1),
    ] {
        let fixed = TbarGeometry::new(tread(q, PI / n as f64).with_layout(layout)).unwrap();
        let body = TbarGeometry::new(
            tread(q, PI / n as f64)
                .with_layout(layout)
                .with_rim(RimMode::Body),
        )
        .unwrap();
        let rim = body.rim.as_ref().unwrap();
        let want = rim_bars_closed_form(q, n, c, layout);
        assert_eq!(Some(rim.bars.len()), want, "q = {q}, {layout:?}");
        assert_eq!(body.nodes.len(), fixed.nodes.len() + 2);
        assert_eq!(
            rim.rim_points.len(),
            fixed.supported.iter().filter(|&&s| s).count()
        );
        assert_eq!(rim.spokes, 2 * rim.rim_points.len());
        assert!(body.supported.iter().all(|&s| !s));
        assert_eq!(
            (body.bars.len(), body.strings.len()),
            (fixed.bars.len(), fixed.strings.len())
        );
        assert_eq!(
            body.labels[body.nodes.len() - 2..],
            ["hub_left", "hub_right"]
        );
    }
    // the q = 1, φ = π/8 figures: 81 rim bars for the wheel, 225 for the extended one
    assert_eq!(rim_bars_closed_form(1, 8, 1, Layout::Wheel), Some(81));
    assert_eq!(
        rim_bars_closed_form(1, 8, 2, Layout::Extended { offset: 1.0 }),
        Some(225)
    );
}

#[test]
fn a_rim_body_wheel_is_a_free_rigid_body_with_the_rigid_rim_margin() {
    let fixed = tbar_report(&TbarRequest::new(
        tread(1, PI / 8.0).with_layout(Layout::Wheel),
    ))
    .unwrap();
    let p = tread(1, PI / 8.0)
        .with_layout(Layout::Wheel)
        .with_rim(RimMode::Body);
    let r = tbar_report(&TbarRequest::new(p)).unwrap();
    assert_eq!(r.rim, RimMode::Body);
    assert_eq!((r.nodes, r.bars, r.rim_bars, r.strings), (34, 89, 81, 32));
    // six rigid-body motions and nothing else: the rim body and the treads are rigid
    assert_eq!((r.mechanisms, r.internal_mechanisms), (6, 0));
    // rank–nullity: s − m = members − dofs
    assert_eq!(
        r.self_stress_dim as i64 - r.mechanisms as i64,
        (r.bars + r.strings) as i64 - 3 * r.nodes as i64
    );
    // the rim bars' sign is free: the treads' margin is the rigid rim's (independent LPs)
    assert!((r.prestress_margin - fixed.prestress_margin).abs() < 1e-9);
    assert!((fixed.prestress_margin - 0.2212894728).abs() < 1e-9);
    assert!(r.min_prestress.is_none() && !r.warnings.is_empty());
    let j = serde_json::to_value(&r).unwrap();
    assert_eq!(j["rim"], "body");
    assert_eq!(j["params"]["rim"], "body");
}

fn row<'a>(rows: &'a [StandingRow], structure: &str, stance: Stance) -> &'a StandingRow {
    rows.iter()
        .find(|r| r.structure == structure && r.stance == stance)
        .unwrap()
}

#[test]
fn the_copy_removes_the_out_of_plane_mechanism_of_the_loop() {
    let rows = loop_study(&tread(1, PI / 8.0), 0.5).unwrap();
    assert_eq!(rows.len(), 6);
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
    for r in &rows {
        assert!(close(r.rigid + r.internal, r.mechanisms as f64), "{r:?}");
        assert!(close(r.internal, 0.0), "{r:?}");
        assert!((r.prestress_margin - 0.2212894728).abs() < 1e-8, "{r:?}");
    }
    // (structure, stance, contacts, mechanisms, in-plane, out-of-plane)
    for (s, st, contacts, mech, inp, outp) in [
        ("wheel", Stance::Free, 0, 6, 3.0, 3.0),
        ("wheel", Stance::Vertex, 1, 3, 1.0, 2.0),
        ("wheel", Stance::Edge, 2, 1, 0.0, 1.0),
        ("extended wheel", Stance::Free, 0, 6, 3.0, 3.0),
        ("extended wheel", Stance::Vertex, 2, 1, 1.0, 0.0),
        ("extended wheel", Stance::Edge, 4, 0, 0.0, 0.0),
    ] {
        let r = row(&rows, s, st);
        assert_eq!((r.contacts, r.mechanisms), (contacts, mech), "{r:?}");
        assert!(
            close(r.in_plane, inp) && close(r.out_of_plane, outp),
            "{r:?}"
        );
    }
    // four contacts pin six rigid-body motions with 12 constraints: 6 more self-stresses
    let (free, edge) = (
        row(&rows, "extended wheel", Stance::Free),
        row(&rows, "extended wheel", Stance::Edge),
    );
    assert_eq!(edge.self_stress_dim, free.self_stress_dim + 6);
}

#[test]
fn the_q2_loop_has_the_same_mechanisms_and_no_prestress() {
    let rows = loop_study(&tread(2, PI / 8.0), 0.5).unwrap();
    let mech: Vec<usize> = rows.iter().map(|r| r.mechanisms).collect();
    assert_eq!(mech, [6, 3, 1, 6, 1, 0]);
    let edge = row(&rows, "wheel", Stance::Edge);
    assert!((edge.out_of_plane - 1.0).abs() < 1e-9 && edge.internal.abs() < 1e-9);
    // q = 2 treads are not prestressable (README finding), with a rim body too
    assert!(rows.iter().all(|r| r.prestress_margin < 1e-8));
}

#[test]
fn mass_and_inertia_equal_a_hand_sum() {
    // rigid rim, q = 1: n radial bars from r₁ to r₀, I₁ = n ρ (r₀ − r₁)(r₁² + r₁r₀ + r₀²)/3
    let (n, rho) = (12usize, 2.5);
    let p = tread(1, PI / n as f64).with_layout(Layout::Wheel);
    let g = TbarGeometry::new(p).unwrap();
    let mp = mass_properties(&g, rho).unwrap();
    let (r0, r1) = (1.0, p.rim_radius());
    let l = r0 - r1;
    assert!((mp.mass - n as f64 * rho * l).abs() < 1e-12);
    let i1 = n as f64 * rho * l * (r1 * r1 + r1 * r0 + r0 * r0) / 3.0;
    assert!((mp.i1 - i1).abs() < 1e-12);
    assert_eq!((mp.sides, mp.rim_mass), (n, 0.0));
    // the rim body adds its bars: the axle bar has no I₁, a spoke from a rim point at
    // radius r₁ to a hub on the axle has (m/3) r₁²
    let gb = TbarGeometry::new(p.with_rim(RimMode::Body)).unwrap();
    let mb = mass_properties(&gb, rho).unwrap();
    let rim = gb.rim.as_ref().unwrap();
    let mut hand = (0.0, 0.0);
    for &[a, b] in &rim.bars {
        let (pa, pb) = (gb.nodes[a], gb.nodes[b]);
        let m = rho * (pb - pa).norm();
        let (ra, rb) = (pa.yz(), pb.yz());
        hand.0 += m;
        hand.1 += m / 3.0 * (ra.norm_squared() + ra.dot(&rb) + rb.norm_squared());
    }
    assert!((mb.rim_mass - hand.0).abs() < 1e-9 && (mb.i1 - i1 - hand.1).abs() < 1e-9);
    // the impact ratio of the polygon
    let mr2 = mp.mass * r0 * r0;
    let want = (mp.i1 + mr2 * (2.0 * PI / n as f64).cos()) / (mp.i1 + mr2);
    assert!((impact_ratio(&mp) - want).abs() < 1e-15);
    assert!(mass_properties(&g, -1.0).is_err());
}

#[test]
fn tipover_threshold_is_the_closed_form_with_the_offset_track() {
    let offset = 0.35;
    let phi = PI / 8.0;
    let g =
        TbarGeometry::new(tread(1, phi).with_layout(Layout::Extended { offset: -offset })).unwrap();
    let (m, grav) = (3.0, 9.81);
    let t = tipover(&g, m, grav).unwrap();
    // F_e > (m g / 2)(T / R_o), T = |offset|, R_o = r₀ = 1
    assert!((t.critical_lateral_force - 0.5 * m * grav * offset).abs() < 1e-12);
    assert!((t.critical_lateral_force_edge - 0.5 * m * grav * offset / phi.cos()).abs() < 1e-12);
    assert!((t.min_friction_to_tip - offset / 2.0).abs() < 1e-15);
    assert!(t.warnings.is_empty());
    let single = TbarGeometry::new(tread(1, phi).with_layout(Layout::Wheel)).unwrap();
    let s = tipover(&single, m, grav).unwrap();
    assert_eq!(s.critical_lateral_force, 0.0);
    assert_eq!(s.warnings.len(), 1);
    assert!(matches!(
        tipover(&g, 0.0, grav),
        Err(TbarError::InvalidParameter(p)) if p.name == "mass"
    ));
}
