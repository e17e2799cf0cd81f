//! The unilateral rigid rolling model against closed forms: the first pivot and impact of a
//! rimless wheel from rest, the plastic and elastic impact laws, ballistic flight, block
//! sliding on a side, and the admissibility of the default reference run.

use approx::assert_relative_eq;
use std::f64::consts::PI;
use wheel_rolling::{Polygon, RigidRolling, RollingResult, RunSpec};

fn octagon(incline_deg: f64, mu: f64, restitution: f64) -> RigidRolling {
    RigidRolling {
        sides: 8,
        outer_radius: 1.0,
        mass: 12.0,
        i1: 7.5,
        incline: incline_deg.to_radians(),
        gravity: 9.81,
        dt: 1e-4,
        output_dt: 1e-3,
        mu_static: mu,
        mu_kinetic: 0.75 * mu,
        restitution,
    }
}

/// The polygon of the reference toroid (thesis errata: n = 8, R_o = 1, spokes + inner rings,
/// 1 kg/m bars; m and I₁ as `toroid::analyse` computes them) with the default settings.
fn reference(incline_deg: f64) -> RigidRolling {
    let polygon = Polygon {
        sides: 8,
        outer_radius: 1.0,
        mass: 14.355256659489193,
        i1: 9.269648818025633,
    };
    let mut spec = RunSpec::default();
    spec.settings.incline = incline_deg.to_radians();
    RigidRolling::new(&polygon, &spec)
}

/// Adaptive Simpson quadrature of f on [a, b] to `tol`.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64) -> f64 {
    fn rec(f: &dyn Fn(f64) -> f64, a: f64, b: f64, fa: f64, fm: f64, fb: f64, tol: f64) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let whole = (b - a) / 6.0 * (fa + 4.0 * fm + fb);
        let halves = (b - a) / 12.0 * (fa + 4.0 * flm + 2.0 * fm + 4.0 * frm + fb);
        if (halves - whole).abs() <= 15.0 * tol || b - a < 1e-12 {
            halves + (halves - whole) / 15.0
        } else {
            rec(f, a, m, fa, flm, fm, 0.5 * tol) + rec(f, m, b, fm, frm, fb, 0.5 * tol)
        }
    }
    let m = 0.5 * (a + b);
    rec(f, a, b, f(a), f(m), f(b), tol)
}

#[test]
fn first_impact_from_rest_on_thirty_degrees_matches_the_closed_forms() {
    // pivot: (I₁ + m R²) θ̈ = m g R sin(θ + φ) from θ = −π/n at rest, so
    // θ̇² = K (cos(φ − π/n) − cos(θ + φ)), K = 2 m g R / (I₁ + m R²);
    // ω⁻ = θ̇ at θ = π/n, ω⁺ = ω⁻ (I₁ + m R² cos 2π/n)/(I₁ + m R²) (angular momentum about the
    // new contact), t = ∫ dθ/θ̇ with θ = −π/n + x² removing the endpoint singularity
    let model = octagon(30.0, 1.2, 0.0);
    let r = model.run(1.5).unwrap();
    let (m, g, rr, i1) = (model.mass, model.gravity, model.outer_radius, model.i1);
    let (phi, half) = (model.incline, PI / 8.0);
    let k = 2.0 * m * g * rr / (i1 + m * rr * rr);
    let a = phi - half;
    // cos a − cos(a + x²) = 2 sin(a + x²/2) sin(x²/2), free of cancellation
    let integrand = |x: f64| {
        if x == 0.0 {
            2.0 / (k * a.sin()).sqrt()
        } else {
            2.0 * x / (2.0 * k * (a + 0.5 * x * x).sin() * (0.5 * x * x).sin()).sqrt()
        }
    };
    let t1 = simpson(&integrand, 0.0, (2.0 * half).sqrt(), 1e-13);
    let omega_minus = (k * ((phi - half).cos() - (phi + half).cos())).sqrt();
    let ratio = (i1 + m * rr * rr * (2.0 * half).cos()) / (i1 + m * rr * rr);
    let first = r.impact_log[0];
    assert_relative_eq!(first.t, t1, max_relative = 1e-6);
    assert_relative_eq!(first.omega_before, omega_minus, max_relative = 1e-6);
    assert_relative_eq!(first.omega_after, ratio * omega_minus, max_relative = 1e-6);
    assert_relative_eq!(ratio, model.impact_ratio(), max_relative = 1e-14);
    // the samples before it pivot: no slip, no flight, the contact pushes
    for s in r.samples.iter().filter(|s| s.t < first.t) {
        assert!(
            s.normal > 0.0 && s.slip == 0.0 && s.pivot == 0.0,
            "t = {}",
            s.t
        );
        assert!(s.tangential.abs() <= model.mu_static * s.normal);
    }
}

#[test]
fn elastic_impact_reverses_the_normal_velocity_by_e_and_sticks_tangentially() {
    // before the first impact the wheel pivots about vertex 0 at θ = π/n: axle velocity
    // R ω⁻ (cos π/n, −sin π/n), new vertex velocity (0, −2 R sin(π/n) ω⁻); after the impulse
    // P its velocity is (u⁺ − R ω⁺ cos π/n, v⁺ − R ω⁺ sin π/n) with u⁺ = u⁻ + P_t/m, v⁺ = v⁻ + P_n/m
    for e in [0.0, 0.3, 0.5, 0.9] {
        let model = octagon(30.0, 1.2, e);
        let r = model.run(1.2).unwrap();
        let p = r.impact_log[0];
        let (m, rr, half) = (model.mass, model.outer_radius, PI / 8.0);
        let (sin, cos) = half.sin_cos();
        let approach = -2.0 * rr * sin * p.omega_before;
        let u = rr * p.omega_before * cos + p.tangential_impulse / m;
        let v = -rr * p.omega_before * sin + p.normal_impulse / m;
        let (ct, cn) = (u - rr * p.omega_after * cos, v - rr * p.omega_after * sin);
        assert_relative_eq!(cn, -e * approach, epsilon = 1e-12, max_relative = 1e-9);
        assert!(ct.abs() < 1e-12, "e = {e}: tangential velocity {ct}");
        assert!(p.tangential_impulse.abs() <= model.mu_static * p.normal_impulse);
        // the angular impulse about the new contact is zero: (I₁ + m R²) ω changes only
        // through the normal impulse's restitution part
        if e == 0.0 {
            assert_relative_eq!(
                p.omega_after / p.omega_before,
                model.impact_ratio(),
                max_relative = 1e-12
            );
        }
    }
}

/// Checks a run of flight samples against s = s₀ + u₀ τ + g sin φ τ²/2,
/// h = h₀ + v₀ τ − g cos φ τ²/2 with u₀, v₀ from its first two samples; ω and the last contact
/// stay constant. Returns the number of samples checked.
fn check_parabola(segment: &[wheel_rolling::RollingSample], gs: f64, gn: f64) -> usize {
    if segment.len() < 3 {
        return 0;
    }
    let (a, b) = (segment[0], segment[1]);
    let dt = b.t - a.t;
    let u0 = (b.s - a.s) / dt - 0.5 * gs * dt;
    let v0 = (b.h - a.h) / dt + 0.5 * gn * dt;
    for s in segment {
        let tau = s.t - a.t;
        assert!(
            (s.s - (a.s + u0 * tau + 0.5 * gs * tau * tau)).abs() < 1e-9,
            "{s:?}"
        );
        assert!(
            (s.h - (a.h + v0 * tau - 0.5 * gn * tau * tau)).abs() < 1e-9,
            "{s:?}"
        );
        assert_eq!((s.omega, s.pivot), (a.omega, a.pivot));
    }
    segment.len()
}

fn assert_admissible(r: &RollingResult, mu_static: f64) {
    assert!(r.validity.min_normal_force >= 0.0);
    assert!(r.samples.iter().all(|s| s.normal >= 0.0));
    assert!(r
        .samples
        .iter()
        .all(|s| s.tangential.abs() <= mu_static * s.normal * (1.0 + 1e-12) + 1e-9));
    assert!(r.impact_log.iter().all(|p| p.normal_impulse >= 0.0
        && p.tangential_impulse.abs() <= mu_static * p.normal_impulse * (1.0 + 1e-12)));
    assert_eq!(r.validity.max_penetration, 0.0);
    assert!(r.validity.warnings.is_empty(), "{:?}", r.validity.warnings);
}

#[test]
fn on_fifty_degrees_the_reference_wheel_flies_never_pulls_and_its_energy_budget_closes() {
    let model = reference(50.0);
    let r = model.run(10.0).unwrap();
    assert_admissible(&r, model.mu_static);
    assert!(r.validity.airborne_fraction > 0.5, "{:?}", r.validity);
    assert!(r.validity.slip_fraction > 0.0);
    assert!(r.validity.energy_balance_error < 1e-9, "{:?}", r.validity);
    assert_eq!(r.impacts, r.impact_log.len());
    assert!(r.impacts > 5);
    // no terminal speed: 50° is steeper than the friction angle atan 0.8 ≈ 38.7°
    assert!(r.final_speed > r.mean_speed && r.final_speed > 20.0);
}

#[test]
fn flight_between_lift_off_and_touchdown_is_the_ballistic_parabola() {
    let model = reference(50.0);
    let r = model.run(4.0).unwrap();
    let (gs, gn) = (
        model.gravity * model.incline.sin(),
        model.gravity * model.incline.cos(),
    );
    // the samples between two consecutive events (impacts, and lift-offs where N drops to 0)
    let mut cuts: Vec<f64> = r.impact_log.iter().map(|p| p.t).collect();
    cuts.push(f64::INFINITY);
    let mut checked = 0;
    let mut segment: Vec<wheel_rolling::RollingSample> = Vec::new();
    let mut next_cut = 0;
    for s in r.samples.iter().chain(std::iter::once(&r.samples[0])) {
        let crossed = s.t >= cuts[next_cut] || s.t == 0.0;
        while s.t >= cuts[next_cut] {
            next_cut += 1;
        }
        if crossed || s.normal != 0.0 {
            checked += check_parabola(&segment, gs, gn);
            segment.clear();
        }
        if s.normal == 0.0 {
            segment.push(*s);
        }
    }
    assert!(checked > 1000, "{checked} flight samples");
}

#[test]
fn a_triangle_that_cannot_roll_slides_on_its_side_like_a_block() {
    // n = 3 on 20° < π/3 cannot tip; tan 20° > μ_s = 0.1: it slides with
    // s̈ = g (sin φ − μ_k cos φ), ω = 0, dissipating μ_k m g cos φ per metre
    let model = RigidRolling {
        sides: 3,
        mu_static: 0.1,
        mu_kinetic: 0.08,
        ..octagon(20.0, 0.1, 0.0)
    };
    let r = model.run(2.0).unwrap();
    let (sin, cos) = model.incline.sin_cos();
    let accel = model.gravity * (sin - model.mu_kinetic * cos);
    let s0 = r.samples[0];
    for s in &r.samples {
        assert_relative_eq!(s.s - s0.s, 0.5 * accel * s.t * s.t, epsilon = 1e-12);
        assert_eq!((s.h, s.omega), (s0.h, 0.0));
        let work = model.mu_kinetic * model.mass * model.gravity * cos * (s.s - s0.s);
        let potential = -model.mass * model.gravity * sin * (s.s - s0.s);
        let kinetic = 0.5 * model.mass * (accel * s.t).powi(2);
        assert_relative_eq!(s.energy, potential + kinetic, epsilon = 1e-9);
        assert_relative_eq!(s.energy + work, 0.0, epsilon = 1e-9);
    }
    assert_relative_eq!(r.validity.slip_fraction, 1.0);
    assert_eq!((r.impacts, r.validity.airborne_fraction), (0, 0.0));
    assert!(r.validity.energy_balance_error < 1e-12);
    // with μ_s ≥ tan φ the same triangle stays put
    let rest = RigidRolling {
        mu_static: 0.5,
        mu_kinetic: 0.4,
        ..model
    };
    let r = rest.run(1.0).unwrap();
    assert!(r.samples.iter().all(|s| s.s == s0.s && s.energy == 0.0));
    assert!(r.validity.valid() && r.validity.slip_fraction == 0.0);
}

#[test]
fn a_wheel_that_cannot_hold_its_pivot_slips_with_kinetic_friction() {
    // 40° with μ_s = 0.55 below the |F_t|/N ≈ 0.56 the pivot needs at the start, and
    // μ_k = 0.5 > tan(π/8) (a sliding side would tip): the wheel pivots and slips on its
    // downhill vertex from t = 0; the friction force is exactly μ_k N against the slip, and the
    // budget (including the friction work ∫ μ_k N |w| dt) closes
    let model = RigidRolling {
        mu_kinetic: 0.5,
        ..octagon(40.0, 0.55, 0.0)
    };
    let r = model.run(2.0).unwrap();
    let early = r.samples[20];
    assert!(
        early.slip > 0.0 && early.omega > 0.0 && early.pivot > 0.0,
        "{early:?}"
    );
    let slipping: Vec<_> = r.samples.iter().filter(|s| s.slip > 0.0).collect();
    assert!(slipping.len() > 100);
    for s in slipping {
        assert_relative_eq!(
            s.tangential.abs(),
            model.mu_kinetic * s.normal,
            max_relative = 1e-12
        );
        assert!(
            s.tangential < 0.0,
            "friction acts uphill against a downhill slip"
        );
    }
    assert!(r.validity.slip_fraction > 0.05);
    assert!(r.validity.energy_balance_error < 1e-9, "{:?}", r.validity);
    assert_admissible(&r, model.mu_static);
    // with μ_k = 0.2 < tan(π/8) a side slides without tipping even on 30° > π/8: friction,
    // not the slope, turns a sliding block over
    let block = octagon(30.0, 0.3, 0.0);
    let r = block.run(1.0).unwrap();
    assert!(r.samples.iter().all(|s| s.omega == 0.0 && s.slip >= 0.0));
    assert_relative_eq!(r.validity.slip_fraction, 1.0);
}

#[test]
fn gentle_slopes_leave_the_wheel_at_rest_and_valid() {
    for (deg, n) in [(20.0, 8), (5.0, 24), (0.0, 3)] {
        let model = RigidRolling {
            sides: n,
            ..octagon(deg, 0.8, 0.0)
        };
        let r = model.run(1.0).unwrap();
        assert_eq!((r.impacts, r.mean_speed, r.final_speed), (0, 0.0, 0.0));
        assert!(r.validity.valid());
        let weight = model.mass * model.gravity;
        let s = r.samples[10];
        assert_relative_eq!(s.normal, weight * model.incline.cos());
        assert_relative_eq!(s.tangential, -weight * model.incline.sin());
    }
}

#[test]
fn events_and_impacts_are_converged_in_the_step() {
    // events are located to round-off on the RK4 solution, so halving the step changes the
    // first impacts of the hopping reference wheel only by RK4's own error (≈ 10⁻¹² here)
    let coarse = reference(50.0).run(2.0).unwrap();
    let fine = RigidRolling {
        dt: 5e-5,
        ..reference(50.0)
    }
    .run(2.0)
    .unwrap();
    assert_eq!(coarse.impacts, fine.impacts);
    for (a, b) in coarse.impact_log.iter().zip(&fine.impact_log) {
        assert_relative_eq!(a.t, b.t, max_relative = 1e-9);
        assert_relative_eq!(a.omega_after, b.omega_after, max_relative = 1e-9);
        assert_relative_eq!(a.normal_impulse, b.normal_impulse, max_relative = 1e-8);
    }
}

#[test]
fn elastic_impacts_with_friction_never_create_energy() {
    // e = 1 with a light hub on 30°: Newton restitution with a sticking friction impulse would
    // gain energy at some touchdowns; the model lowers e there, so the energy (kinetic +
    // potential) never rises between samples, and the budget still closes
    let model = RigidRolling {
        mass: 10.0,
        i1: 3.0,
        mu_static: 0.8,
        mu_kinetic: 0.6,
        ..octagon(30.0, 0.8, 1.0)
    };
    let r = model.run(3.0).unwrap();
    assert!(r.impacts > 3);
    for w in r.samples.windows(2) {
        assert!(w[1].energy <= w[0].energy + 1e-9, "t = {}", w[1].t);
    }
    assert!(r.validity.valid(), "{:?}", r.validity);
    assert!(r.validity.energy_balance_error < 1e-9);
}
