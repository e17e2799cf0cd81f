//! Lean while rolling down a cross-sloped plane: the set-up's closed forms and a case each side
//! of the outcome (the conclusion's stability claim is a measured study, docs/guide/sweeps.md).

use toroid::rolling_lean::LeanRolling;
use toroid::WheelSpec;

#[test]
fn a_wheel_on_a_flat_plane_stays_upright_and_its_static_limit_is_the_closed_form() {
    let wheel = WheelSpec::default().build().unwrap();
    let r = LeanRolling {
        incline: 0.0,
        side_slope: 0.0,
        t_end: 0.5,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap();
    let h = (std::f64::consts::PI / 8.0).cos();
    assert!((r.static_critical_side_slope - (0.4 / (2.0 * h)).atan()).abs() < 1e-15);
    assert!(r.max_lean < 1e-6, "{}", r.max_lean);
    assert!(r.downhill.abs() < 1e-4, "{}", r.downhill);
    assert!(!r.fell);
}

#[test]
fn a_side_slope_beyond_the_static_limit_topples_the_wheel_at_rest() {
    // on a side, 22.5° > 15° incline: it does not roll, and 20° across exceeds atan(T/2h) ≈ 12°
    let wheel = WheelSpec::default().build().unwrap();
    let r = LeanRolling {
        incline: 15f64.to_radians(),
        side_slope: 20f64.to_radians(),
        t_end: 2.0,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap();
    assert!(r.side_slope > r.static_critical_side_slope);
    assert!(r.fell, "max lean {}", r.max_lean);
    let r = LeanRolling {
        incline: 15f64.to_radians(),
        side_slope: 6f64.to_radians(),
        t_end: 2.0,
        ..Default::default()
    }
    .run(&wheel)
    .unwrap();
    assert!(!r.fell, "max lean {}", r.max_lean);
    assert!(
        r.downhill < 0.1,
        "an octagon does not roll down 15°: {}",
        r.downhill
    );
}

/// `tipover --rolling` on its defaults (30° down, 5° across, 3 s at 2.5e-5 s): valid. The
/// wheel wobbles past both tip angles, so the lean's phase quantities are chaotic, each with
/// the 95 % interval of another run, and whether it ends fallen is a draw (the final lean's
/// interval lies on both sides of −α₋); no quantity is flagged converged that a finer run
/// contradicts (`a_quarter_step_lies_inside_the_default_run_s_intervals`).
#[test]
fn the_default_rolling_run_is_valid_and_its_wobble_is_chaotic() {
    use tensegrity_dynamics::convergence::Status;
    let r = toroid::TipoverRollingRequest::default().report().unwrap();
    assert!(r.valid, "{:?}", r.warnings);
    let c = r.convergence.as_ref().unwrap();
    // the refined run (from the twin's start) moved the wobble: the twin ran after it
    assert_eq!(c.cost, 3.0);
    assert!(c.refinement.ends_with("; twin at dt"), "{}", c.refinement);
    for name in ["max_lean", "rms_lean", "final_lean", "fell"] {
        let q = c.quantities.iter().find(|q| q.name == name).unwrap();
        assert_eq!(q.status, Status::Chaotic, "{name}: {q:?}");
    }
    let q = |name: &str| c.quantities.iter().find(|q| q.name == name).unwrap();
    let [lo, hi] = q("final_lean").interval.unwrap();
    let [_, minus] = r.tip_angles;
    assert!(lo < -minus && hi > -minus, "[{lo}, {hi}] against -{minus}");
    // the wobble is resolved: its RMS is well above the damped 0.045 rad of a 1e-4 s step
    assert!(
        r.rms_lean > 0.1 && r.rms_lean <= r.max_lean,
        "{}",
        r.rms_lean
    );
    let [lo, hi] = q("rms_lean").interval.unwrap();
    assert!(lo <= r.rms_lean && r.rms_lean <= hi);
}

/// A run at a quarter of the default step (6.25e-6 s, 480,000 RK4 steps) lies inside each
/// chaotic interval of the default run and within tolerance of each converged quantity
/// (measured: max lean 0.407 in [0.19, 0.77], RMS 0.148 in [0.126, 0.200], final −0.204 in
/// [−0.85, −0.09], downhill 8.511 m in [8.42, 8.70]; it ends inside its tip angle where the
/// default run ends past it, which the check reports as a draw).
#[test]
#[ignore = "slow: about 20 s in the test profile; run with --ignored"]
fn a_quarter_step_lies_inside_the_default_run_s_intervals() {
    use tensegrity_dynamics::convergence::Status;
    let request = toroid::TipoverRollingRequest::default();
    let r = request.report().unwrap();
    let mut fine = request;
    fine.dt *= 0.25;
    fine.checks.convergence_check = false;
    let f = fine.report().unwrap();
    let value = |name: &str| match name {
        "max_lean" => Some(f.max_lean),
        "rms_lean" => Some(f.rms_lean),
        "final_lean" => Some(f.final_lean),
        "downhill" => Some(f.downhill),
        "fall_time" => f.fall_time,
        _ => Some(f64::from(u8::from(f.fell))),
    };
    for q in &r.convergence.as_ref().unwrap().quantities {
        match (q.status, q.interval, value(&q.name)) {
            (Status::Chaotic, Some([lo, hi]), Some(v)) => {
                assert!(lo <= v && v <= hi, "{}: {v} outside [{lo}, {hi}]", q.name)
            }
            (Status::Converged, _, Some(v)) => {
                let x = q.value.unwrap();
                let change = (v - x).abs() / v.abs().max(x.abs()).max(0.01);
                assert!(change <= q.tolerance, "{}: {x} against {v}", q.name);
            }
            _ => {}
        }
    }
}
