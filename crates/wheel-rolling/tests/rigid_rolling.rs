//! The rigid rolling model against conservation laws and the rimless-wheel limit cycle's
//! admissibility (the Fig. 3.10 claim on the toroid is in `crates/toroid/tests/rolling.rs`).

use approx::assert_relative_eq;
use std::f64::consts::PI;
use wheel_rolling::RigidRolling;

fn octagon(incline_deg: f64) -> RigidRolling {
    RigidRolling {
        sides: 8,
        outer_radius: 1.0,
        mass: 12.0,
        i1: 7.5,
        incline: incline_deg.to_radians(),
        gravity: 9.81,
        dt: 1e-4,
        output_dt: 1e-3,
        mu_static: 1.2,
        mu_kinetic: 0.9,
        restitution: 0.0,
    }
}

#[test]
fn energy_is_conserved_while_pivoting_and_lost_only_at_impacts() {
    let model = octagon(30.0);
    let r = model.run(4.0).unwrap();
    assert!(r.impacts >= 3);
    let ia = model.i1 + model.mass;
    let ratio = model.impact_ratio();
    let half = PI / 8.0;
    let phi = model.incline;
    let step = 2.0 * half.sin();
    let pure = |s: &wheel_rolling::RollingSample| s.slip == 0.0 && s.normal > 0.0;
    let impact_between = |a: f64, b: f64| r.impact_log.iter().any(|p| p.t > a && p.t <= b);
    let mut drops = 0;
    for w in r.samples.windows(2) {
        let (a, b) = (w[0], w[1]);
        if impact_between(a.t, b.t) {
            assert!(b.energy < a.energy, "an impact loses energy");
            drops += 1;
        } else if pure(&a) && pure(&b) {
            assert!(
                (b.energy - a.energy).abs() < 1e-9 * (1.0 + a.energy.abs()),
                "t = {}",
                b.t
            );
        }
    }
    assert!(drops >= 3);
    // on the second pivot, until the wheel first slips or flies:
    // ½ I_A ω² = ½ I_A (r ω₁)² + m g R (cos(φ − π/n) − cos(θ + φ)), with
    // ω₁² = 2 m g R (cos(φ − π/n) − cos(φ + π/n)) / I_A from the first pivot
    let drop = |theta: f64| {
        2.0 * model.mass * model.gravity * ((phi - half).cos() - (theta + phi).cos()) / ia
    };
    let omega_after_first = drop(half).sqrt() * ratio;
    let left_pivot = r
        .samples
        .iter()
        .find(|s| !pure(s))
        .map_or(f64::INFINITY, |s| s.t);
    let second: Vec<_> = r
        .samples
        .iter()
        .filter(|s| (s.pivot - step).abs() < 1e-12 && s.t < left_pivot)
        .collect();
    assert!(second.len() > 10);
    for s in second {
        let theta = (s.s - s.pivot).atan2(s.h);
        let predicted = (omega_after_first.powi(2) + drop(theta)).sqrt();
        assert_relative_eq!(s.omega, predicted, max_relative = 1e-7);
    }
}

#[test]
fn the_rimless_wheel_limit_cycle_on_thirty_five_degrees_would_need_a_pulling_ground() {
    // the fixed point of ω⁻² = r² ω⁻² + 2 m g R (cos(φ − π/n) − cos(φ + π/n)) / I_A has
    // ω⁻² R cos(π/n) > g cos φ: at the end of a pivot the contact would have to pull, so the
    // unilateral wheel leaves the slope before reaching it
    let model = octagon(35.0);
    let (half, phi) = (PI / 8.0, model.incline);
    let ia = model.i1 + model.mass;
    let rr = model.impact_ratio();
    let w_star = (2.0 * model.mass * model.gravity * ((phi - half).cos() - (phi + half).cos())
        / (ia * (1.0 - rr * rr)))
        .sqrt();
    assert!(w_star.powi(2) * half.cos() > model.gravity * phi.cos());
    let r = model.run(10.0).unwrap();
    assert!(r.validity.airborne_fraction > 0.0, "{:?}", r.validity);
    assert!(r.validity.min_normal_force >= 0.0);
    assert!(r.samples.iter().all(|s| s.normal >= 0.0));
    assert!(r.validity.energy_balance_error < 1e-9);
}

#[test]
fn a_gentle_slope_does_not_start_the_wheel() {
    let r = octagon(20.0).run(3.0).unwrap(); // 20° < π/8 = 22.5°
    assert_eq!(r.impacts, 0);
    assert_eq!(r.mean_speed, 0.0);
    // at rest on its edge the two pairs share the weight: this pair carries N ≤ m g cos φ
    let s = r.samples[10];
    assert!(s.normal > 0.0 && s.normal <= 12.0 * 9.81 * 20f64.to_radians().cos() + 1e-9);
}

#[test]
fn invalid_rolling_parameters_are_named() {
    let mut m = octagon(30.0);
    m.incline = 2.0;
    assert!(m.run(1.0).unwrap_err().to_string().contains("incline"));
    assert!(octagon(30.0)
        .run(-1.0)
        .unwrap_err()
        .to_string()
        .contains("t_end"));
    let mut m = octagon(30.0);
    m.i1 = f64::NAN;
    assert!(m.run(1.0).unwrap_err().to_string().contains("i1"));
    for (field, value) in [
        ("mu_static", -0.1),
        ("mu_kinetic", 2.0),
        ("restitution", 1.5),
    ] {
        let mut m = octagon(30.0);
        match field {
            "mu_static" => m.mu_static = value,
            "mu_kinetic" => m.mu_kinetic = value,
            _ => m.restitution = value,
        }
        assert!(m.run(1.0).unwrap_err().to_string().contains(field));
    }
    // a triangle with a light hub and strong friction: sliding has no solution (Painlevé)
    let m = RigidRolling {
        sides: 3,
        i1: 0.5,
        mu_static: 3.0,
        mu_kinetic: 3.0,
        ..octagon(30.0)
    };
    let err = m.run(1.0).unwrap_err().to_string();
    assert!(
        err.contains("mu_kinetic") && err.contains("Painlev"),
        "{err}"
    );
}
