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
