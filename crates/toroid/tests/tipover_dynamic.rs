//! Dynamic tip-over (§3.3.2) with the full 3-D dynamics against the static threshold
//! F = (m g / 2)(T / h), h = R_o cos(π/n) for a wheel resting on a side.

use toroid::tipover_dynamic::DynamicTipover;

/// A lean (rad) well beyond the elastic one of a loaded, upright wheel.
const TIPPED_LEAN: f64 = 0.1;
use toroid::{analyse, WheelSpec};

#[test]
fn a_quasi_static_ramp_tips_the_wheel_within_five_percent_of_the_static_threshold() {
    let wheel = WheelSpec::default().build().unwrap();
    let r = DynamicTipover::default().run(&wheel).unwrap();
    // the static threshold is the closed form of the starting pose
    let m = analyse(&wheel).unwrap().mass_kg;
    let h = wheel.params.outer_radius * (std::f64::consts::PI / 8.0).cos();
    let expected = 0.5 * m * 9.81 * wheel.params.outer_tread / h;
    assert!((r.static_threshold - expected).abs() < 1e-12 * expected);
    let dynamic = r.dynamic_threshold.expect("the near tread edge unloads");
    assert!(
        (dynamic / r.static_threshold - 1.0).abs() < 0.05,
        "dynamic {dynamic} vs static {}",
        r.static_threshold
    );
    assert!(
        r.tipped,
        "at 1.3× the threshold the wheel tips: max lean {}",
        r.max_lean
    );
    // before the ramp the edges share the weight equally
    let rest = r.samples.iter().find(|s| s.t >= 0.45).unwrap();
    assert!((rest.near_normal + rest.far_normal - m * 9.81).abs() < 1e-2 * m * 9.81);
    assert!((rest.near_normal - rest.far_normal).abs() < 1e-2 * m * 9.81);
}

/// Below the threshold the near edge stays loaded and the lean stays elastic (small).
#[test]
fn a_ramp_that_stops_below_the_threshold_keeps_both_edges_loaded() {
    let wheel = WheelSpec::default().build().unwrap();
    let below = DynamicTipover {
        ramp_to: 0.8,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap();
    assert!(
        below.dynamic_threshold.is_none(),
        "{:?}",
        below.dynamic_threshold
    );
    assert!(below.max_lean < 0.1 * TIPPED_LEAN, "{}", below.max_lean);
    let last = below.samples.last().unwrap();
    // the near edge carries what the rigid moment balance leaves it, within 10 % of m g
    let m_g = last.near_normal + last.far_normal;
    let rigid = 0.5 * m_g - last.force * below.hub_height / wheel.params.outer_tread;
    assert!(
        (last.near_normal - rigid).abs() < 0.1 * m_g,
        "{} vs {rigid}",
        last.near_normal
    );
}

/// A force held just below the threshold leaves the wheel standing; just above, it tips.
#[test]
fn a_held_force_below_the_threshold_is_carried_and_above_it_tips_the_wheel() {
    let wheel = WheelSpec::default().build().unwrap();
    let hold = |ramp_to: f64| {
        DynamicTipover {
            ramp_to,
            hold: 1.5,
            ..Default::default()
        }
        .run(&wheel)
        .unwrap()
    };
    let below = hold(0.9);
    assert!(below.valid, "{:?}", below.warnings);
    assert!(below.dynamic_threshold.is_none() && !below.tipped);
    assert!(below.max_lean < 0.1 * TIPPED_LEAN, "{}", below.max_lean);
    let above = hold(1.1);
    assert!(above.valid, "{:?}", above.warnings);
    // it tipped, and ends past the static tip angle: on its way to its side
    assert!(
        above.tipped && above.final_lean > above.static_tip_angle,
        "{} {:?}",
        above.final_lean,
        above.tip_time
    );
}

#[test]
fn bad_settings_name_the_parameter() {
    let wheel = WheelSpec::default().build().unwrap();
    let err = DynamicTipover {
        ramp_time: 0.0,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap_err();
    assert!(err.to_string().contains("ramp_time"), "{err}");
}

/// A step too large for the stiff standing wheel (2·10⁻³ s; it diverges within 5 ms) is an
/// error that names this run's only remedy, a smaller `dt`, and not the integrators the
/// request does not take; its time is where the run stopped.
#[test]
fn a_diverged_run_names_the_step_it_ran_at_and_no_integrator() {
    let wheel = WheelSpec::default().build().unwrap();
    let e = DynamicTipover {
        dt: 2e-3,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap_err();
    let toroid::ToroidError::TipoverDiverged { t, dt, .. } = &e else {
        panic!("{e}");
    };
    assert_eq!(*dt, 2e-3);
    assert!(*t > 0.0 && *t < 0.01, "{t}");
    let text = e.to_string();
    assert!(text.contains("use a smaller `dt`"), "{text}");
    assert!(!text.contains("integrator"), "{text}");
}

/// The convergence check's coarse companion (2 dt, ground stiffness / 2) does not serve the
/// default ramp: RK4 takes the ground's 2000 N·s/m damper explicitly, and its rate puts 2 dt
/// far past the stability bound (a run at 2·10⁻⁴ s reads a threshold 12 % low), so the
/// companion stays refined and the label says why; the coarse resolution itself is 2 dt and
/// k/2.
#[test]
fn the_default_ramp_keeps_its_refined_companion() {
    let wheel = WheelSpec::default().build().unwrap();
    let d = DynamicTipover::default();
    let why = d.coarse_refused(&wheel).unwrap().expect("2 dt is unstable");
    assert!(
        why.starts_with("2 dt times λ") && why.contains("exceeds 0.5 × rk4's stability bound 2.6"),
        "{why}"
    );
    let c = d.coarse();
    assert_eq!(
        (c.dt, c.ground_stiffness),
        (2.0 * d.dt, 0.5 * d.ground_stiffness)
    );
}
