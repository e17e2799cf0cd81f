//! The linear response at the structure's geometry ([`linear_response`]) against closed
//! forms:
//!
//! - a bar pinned at one end, its other end held along the bar's (skew) axis and across it,
//!   pushed by δ along the axis: Δt = EA δ / L and reactions ±EA δ / L along the axis (10⁻¹²);
//! - two bars in series, the far support displaced: the springs in series, k₁k₂/(k₁ + k₂) δ;
//! - a prestressed string pulled through an elastic support whose anchor moves by a: the
//!   series stiffness k_s k/(k_s + k) a, the spring's force its reaction, the string slack
//!   (and named) when pulled the other way past its prestress;
//! - the inclined roller under its load: the determinate structure's load-solve forces and
//!   reactions (the statics report), and the displacement along the incline by hand;
//! - bad input: a member without an axial stiffness (named), a mechanism (an error naming
//!   it, no NaN), a displacement off the held directions.

use nalgebra::Vector3;
use std::f64::consts::PI;
use tensegrity_core::error::{CoreError, ModelError, StaticsError};
use tensegrity_core::{Bar, Material, StringMember, Structure, Support};
use tensegrity_statics::report::{statics_report, StaticsRequest};
use tensegrity_statics::response::linear_response;

/// A material whose bars of radius 1 cm have EA = `ea`.
fn with_ea(ea: f64) -> Material {
    Material::new(1000.0, ea / (PI * 1e-4), 1e6)
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs().max(1e-300)
}

#[test]
fn a_bar_pushed_along_its_skew_axis_carries_ea_delta_over_l() {
    // the axis d_a = (1, 2, 2)/3 with L = 3 m; d_b, d_c complete an orthonormal frame
    let d_a = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    let d_b = [2.0 / 3.0, 1.0 / 3.0, -2.0 / 3.0];
    let d_c = [-2.0 / 3.0, 2.0 / 3.0, -1.0 / 3.0];
    let (ea, l, delta) = (2.2e7, 3.0, 1.3e-3);
    let s = Structure::builder()
        .material("m", with_ea(ea))
        .nodes([[0.0, 0.0, 0.0], [1.0, 2.0, 2.0]])
        .bar(Bar::new(0, 1).material("m").radius(0.01))
        .support(Support::pinned(0))
        .support(Support::along(1, [[d_a.x, d_a.y, d_a.z], d_b, d_c]))
        .build()
        .unwrap();
    let r = linear_response(&s, &[None, Some(d_a * delta)]).unwrap();
    let expected = ea * delta / l;
    let dt = r.member_force_change[0];
    assert!(close(dt, expected, 1e-12), "{dt} against {expected}");
    // the held node moved by the prescribed displacement, the pinned one not at all
    for a in 0..3 {
        assert!((r.displacements[1][a] - d_a[a] * delta).abs() < 1e-18);
        assert_eq!(r.displacements[0][a], 0.0);
    }
    assert!(close(r.max_displacement, delta, 1e-15));
    // the support pushes the node out along the axis, the pin pulls back: equal and opposite
    let along = &r.reactions[1].along;
    assert!(close(along[0], expected, 1e-12), "{along:?}");
    assert!(along[1].abs() < 1e-12 * expected && along[2].abs() < 1e-12 * expected);
    for a in 0..3 {
        let pin = r.reactions[0].force[a];
        assert!((pin + expected * d_a[a]).abs() < 1e-12 * expected, "{pin}");
        assert!((pin + r.reactions[1].force[a]).abs() < 1e-12 * expected);
    }
    assert!(
        r.slack.is_empty() && r.warnings.is_empty(),
        "{:?}",
        r.warnings
    );
    // no prestress
    assert_eq!(r.initial_force, vec![0.0]);
}

#[test]
fn two_bars_in_series_share_the_settlement_as_springs_in_series() {
    // k₁ = 1000/1, k₂ = 3000/2 N/m; node 1 free along x only; node 2 pinned, moved by δ
    let (k1, k2, delta) = (1000.0, 1500.0, 0.02);
    let s = Structure::builder()
        .material("a", with_ea(1000.0))
        .material("b", with_ea(3000.0))
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("a").radius(0.01))
        .bar(Bar::new(1, 2).material("b").radius(0.01))
        .support(Support::pinned(0))
        .support(Support::directions(1, [false, true, true]))
        .support(Support::pinned(2))
        .build()
        .unwrap();
    let d = Vector3::new(delta, 0.0, 0.0);
    let r = linear_response(&s, &[None, None, Some(d)]).unwrap();
    let t = k1 * k2 / (k1 + k2) * delta;
    assert!(close(r.member_force_change[0], t, 1e-12), "{r:?}");
    assert!(close(r.member_force_change[1], t, 1e-12), "{r:?}");
    assert!(close(r.displacements[1][0], k2 / (k1 + k2) * delta, 1e-12));
    assert!(close(r.reactions[2].force[0], t, 1e-12));
    assert!(close(r.reactions[0].force[0], -t, 1e-12));
    // the roller carries nothing along its held y and z
    assert!(r.reactions[1].force.iter().all(|f| f.abs() < 1e-12 * t));
}

/// A string along x (k = 200 N/m, 1.5 m, rest length 1.4 m: 20 N of prestress) from a pin to
/// a node on springs of 600 N/m along x, y and z, whose anchor moves by `a` along x.
fn string_on_a_spring() -> Structure {
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.5, 0.0, 0.0]])
        .string(StringMember::new(0, 1).stiffness(200.0).rest_length(1.4))
        .support(Support::pinned(0))
        .support(Support::pinned(1).elastic(600.0))
        .build()
        .unwrap()
}

#[test]
fn a_string_pulled_through_a_spring_has_the_series_stiffness() {
    let (k, ks, t0) = (200.0, 600.0, 20.0);
    let series = k * ks / (k + ks);
    let s = string_on_a_spring();
    let a = 0.01;
    let r = linear_response(&s, &[None, Some(Vector3::new(a, 0.0, 0.0))]).unwrap();
    assert!(
        close(r.initial_force[0], t0, 1e-12),
        "{:?}",
        r.initial_force
    );
    assert!(close(r.member_force_change[0], series * a, 1e-12), "{r:?}");
    assert!(close(r.displacements[1][0], ks * a / (k + ks), 1e-12));
    assert!(r.displacements[1][1] == 0.0 && r.displacements[1][2] == 0.0);
    // the spring's force pulls the node along +x by k_s (a − u): the string's change
    assert!(close(r.reactions[1].force[0], series * a, 1e-12));
    assert!(close(r.reactions[0].force[0], -series * a, 1e-12));
    assert!(r.slack.is_empty());
    // pushed 0.2 m the other way: Δt = −30 N against 20 N of prestress, the string slack
    let r = linear_response(&s, &[None, Some(Vector3::new(-0.2, 0.0, 0.0))]).unwrap();
    assert!(close(r.member_force_change[0], -0.2 * series, 1e-12));
    assert_eq!(r.slack, vec![0]);
    assert!(
        r.warnings
            .iter()
            .any(|w| w.contains("string 0 would go slack")),
        "{:?}",
        r.warnings
    );
}

#[test]
fn the_inclined_roller_responds_with_the_load_solve_forces_and_reactions() {
    // examples/inclined_roller.toml: EA = 3141.6 N, L = 2 m along x, node 1 free along the 30°
    // incline t = (cos 30°, 0, sin 30°), 1 kN down on it
    let (c, sn) = (30f64.to_radians().cos(), 0.5);
    let ea = 1e7 * PI * 1e-4;
    let s = Structure::builder()
        .material("soft", Material::new(1000.0, 1e7, 1e6))
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("soft").radius(0.01))
        .support(Support::pinned(0))
        .support(Support::along(1, [[-sn, 0.0, c], [0.0, 1.0, 0.0]]))
        .load(1, [0.0, 0.0, -1000.0])
        .build()
        .unwrap();
    let r = linear_response(&s, &[]).unwrap();
    let statics = statics_report(&s, &StaticsRequest::default()).unwrap();
    let f = statics.member_force.unwrap()[0];
    assert!(
        close(r.member_force_change[0], f, 1e-12),
        "{r:?} against {f}"
    );
    for (mine, theirs) in r.reactions.iter().zip(statics.reactions.unwrap()) {
        for a in 0..3 {
            assert!(
                (mine.force[a] - theirs.force[a]).abs() < 1e-9,
                "{mine:?} {theirs:?}"
            );
        }
        assert_eq!(mine.along.len(), theirs.along.len());
    }
    // along the incline: (EA/L) cos²30° s = P · t = −500 N
    let slide = -500.0 / (ea / 2.0 * c * c);
    assert!(close(r.displacements[1][0], slide * c, 1e-12), "{r:?}");
    assert!(close(r.displacements[1][2], slide * sn, 1e-12), "{r:?}");
    assert!(r.displacements[1][1].abs() < 1e-15);
}

#[test]
fn a_member_without_axial_stiffness_is_named() {
    let bare_bar = Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .build()
        .unwrap();
    let e = linear_response(&bare_bar, &[None, Some(Vector3::new(0.01, 0.0, 0.0))]).unwrap_err();
    assert!(
        matches!(
            e,
            CoreError::Model(ModelError::MissingProperty {
                property: "material",
                ..
            })
        ),
        "{e}"
    );
    assert!(
        e.to_string().starts_with("bar 0: the linear response"),
        "{e}"
    );
    let bare_string = Structure::builder()
        .material("m", with_ea(1e4))
        .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
        .bar(Bar::new(0, 1).material("m").radius(0.01))
        .string(StringMember::new(1, 2).stiffness(10.0))
        .string(StringMember::new(0, 2))
        .support(Support::pinned(0))
        .support(Support::pinned(1))
        .support(Support::pinned(2))
        .build()
        .unwrap();
    let e = linear_response(&bare_string, &[]).unwrap_err().to_string();
    assert!(
        e.starts_with("string 1: ") && e.contains("stiffness"),
        "{e}"
    );
}

#[test]
fn a_mechanism_is_an_error_naming_it_not_nan() {
    // the bar's far end held along the bar only: it swings freely across (no prestress)
    let s = Structure::builder()
        .material("m", with_ea(1e4))
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("m").radius(0.01))
        .support(Support::pinned(0))
        .support(Support::directions(1, [true, false, false]))
        .build()
        .unwrap();
    let e = linear_response(&s, &[None, Some(Vector3::new(0.01, 0.0, 0.0))]).unwrap_err();
    match &e {
        CoreError::Statics(StaticsError::SingularStiffness {
            mechanisms,
            node,
            direction,
        }) => {
            assert_eq!((*mechanisms, *node), (2, 1));
            // the swing is across the bar
            assert!(direction[0].abs() < 1e-12, "{direction:?}");
        }
        other => panic!("{other}"),
    }
    assert!(e.to_string().contains("2 mechanism(s)"), "{e}");
    // a prestressed string across the gap stiffens the swing: an answer again, no NaN
    let s = Structure::builder()
        .material("m", with_ea(1e4))
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [4.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("m").radius(0.01))
        .string(StringMember::new(1, 2).stiffness(100.0).rest_length(1.9))
        .support(Support::pinned(0))
        .support(Support::pinned(2))
        .build()
        .unwrap();
    let r = linear_response(&s, &[None, Some(Vector3::new(0.01, 0.0, 0.0))]).unwrap();
    assert!(r.displacements.iter().flatten().all(|u| u.is_finite()));
    // node 1 between the bar (5000 N/m) and the string (100 N/m), the string's end moved
    let u = 100.0 * 0.01 / (5000.0 + 100.0);
    assert!(close(r.displacements[1][0], u, 1e-12), "{r:?}");
}

#[test]
fn a_displacement_off_the_held_directions_is_refused() {
    let s = Structure::builder()
        .material("m", with_ea(1e4))
        .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
        .bar(Bar::new(0, 1).material("m").radius(0.01))
        .support(Support::pinned(0))
        .support(Support::directions(1, [true, true, false]))
        .build()
        .unwrap();
    let e = linear_response(&s, &[None, Some(Vector3::new(0.0, 0.0, 0.1))])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("support 1 (node 1)") && e.contains("held"),
        "{e}"
    );
    let e = linear_response(&s, &[None]).unwrap_err().to_string();
    assert!(e.contains("support displacements"), "{e}");
}
