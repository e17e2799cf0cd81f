//! `scale_with_n`: the tread offset scaled with the number of sides, D_n = D · 8 / n
//! (0.8/n for the reference D = 0.1), keeps large wheels prestressable where the fixed
//! D = 0.1 does not (n = 100: margin 0); every request of the wheel reads the flag.

use toroid::{toroid_report, RollRequest, TipoverRequest, ToroidRequest, WheelSpec};

fn margin(sides: usize, scale_with_n: bool) -> (bool, f64) {
    let wheel = WheelSpec {
        scale_with_n,
        ..WheelSpec::with_sides(sides)
    };
    let r = toroid_report(&ToroidRequest {
        wheel,
        ..Default::default()
    })
    .unwrap();
    (r.prestressable, r.prestress_margin)
}

#[test]
fn the_scaled_offset_keeps_large_wheels_prestressable() {
    // the reference offset at n = 100 is not prestressable
    assert_eq!(margin(100, false), (false, 0.0));
    // measured: 0.00195 at n = 100 and 1.4e-5 at n = 1000
    let (ok, m) = margin(100, true);
    assert!(ok && (m - 0.001952).abs() < 1e-5, "{m}");
    let (ok, m) = margin(1000, true);
    assert!(ok && m > 0.0 && (m - 1.435e-5).abs() < 1e-7, "{m}");
    // at the reference n = 8 the rule changes nothing
    assert_eq!(margin(8, true), margin(8, false));
}

#[test]
fn every_wheel_request_reads_the_flag_and_keeps_the_offset_asked() {
    let roll: RollRequest =
        serde_json::from_str(r#"{"sides": 100, "scale_with_n": true}"#).unwrap();
    assert!(roll.wheel.scale_with_n && roll.wheel.params.offset == 0.1);
    assert!((roll.wheel.geometry().offset - 0.008).abs() < 1e-16);
    assert!((roll.wheel.build().unwrap().params.offset - 0.008).abs() < 1e-16);
    // the serde form writes back what was asked (no double scaling on a round trip)
    let again: RollRequest = serde_json::from_value(serde_json::to_value(roll).unwrap()).unwrap();
    assert_eq!(again, roll);
    let tip: TipoverRequest =
        serde_json::from_str(r#"{"sides": 40, "scale_with_n": true, "offset": 0.2}"#).unwrap();
    assert!((tip.wheel_spec().geometry().offset - 0.2 * 8.0 / 40.0).abs() < 1e-16);
    let toroid: ToroidRequest = serde_json::from_str(r#"{"scale_with_n": true}"#).unwrap();
    assert!(toroid.wheel.scale_with_n);
    // the parameter is described once, as a flag
    let params = <ToroidRequest as tensegrity_core::request::Params>::params();
    assert_eq!(
        params.iter().filter(|p| p.name == "scale_with_n").count(),
        1
    );
}
