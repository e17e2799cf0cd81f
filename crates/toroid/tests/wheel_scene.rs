//! The generic entry of the full rolling model: the toroid's own scene satisfies the
//! contract, and a scene off its starting side is refused with the node named.

use toroid::WheelSpec;
use wheel_rolling::{FullRolling, RollingError, WheelScene};

fn scene() -> WheelScene {
    let t = WheelSpec::with_sides(8).build().unwrap();
    toroid::roll::scene(&t, 2e4, 20.0).unwrap()
}

#[test]
fn the_toroid_scene_stands_on_prisms_zero_and_one() {
    let s = scene();
    assert!(s.validate().is_ok());
    assert_eq!(s.sides(), 8);
    let z = -(std::f64::consts::PI / 8.0).cos();
    assert!((s.plane_z() - z).abs() < 1e-15);
    let x = s.structure.nodes();
    for &i in s.contact_groups[0].iter().chain(&s.contact_groups[1]) {
        assert!((x[i].z - z).abs() < 1e-12);
    }
    assert_eq!(s.group_of()[5], Some(1));
    assert_eq!(s.group_of()[2], None);
}

#[test]
fn a_scene_off_its_starting_side_is_refused() {
    let mut s = scene();
    s.contact_groups.swap(0, 1);
    let e = s.validate().unwrap_err();
    assert!(
        matches!(
            &e,
            RollingError::InvalidParameter(p) if p.name == "contact_groups"
        ),
        "{e}"
    );
    let mut s = scene();
    s.rim.push(10_000);
    assert!(s.validate().unwrap_err().to_string().contains("10000"));
    let err = FullRolling::default().run_scene(&s, 0.01).unwrap_err();
    assert!(err.to_string().contains("node"), "{err}");
}

/// Stops the run after `k` samples.
struct StopAfter(usize, Vec<f64>);

impl wheel_rolling::Observer for StopAfter {
    fn sample(&mut self, s: &wheel_rolling::RollingSample) -> wheel_rolling::Flow {
        self.1.push(s.t);
        if self.1.len() >= self.0 {
            wheel_rolling::Flow::Stop
        } else {
            wheel_rolling::Flow::Continue
        }
    }
}

#[test]
fn a_full_run_stopped_by_its_observer_keeps_the_samples_it_handed_out() {
    use toroid::{roll_observed, FidelityChoice, RollRequest};
    let request = RollRequest {
        fidelity: FidelityChoice::Full,
        t_end: 0.5,
        ..RollRequest::default()
    };
    let mut obs = StopAfter(40, Vec::new());
    let r = roll_observed(&request, &[], Some(&mut obs)).unwrap();
    assert_eq!(r.samples.len(), 40);
    assert_eq!(r.samples.iter().map(|s| s.t).collect::<Vec<_>>(), obs.1);
    let t = r.samples[39].t;
    assert!((t - 0.039).abs() < 1e-9, "{t}");
    assert_eq!(r.summary.stopped_at, Some(t));
    assert!(!r.summary.valid);
    assert!(r
        .summary
        .warnings
        .iter()
        .any(|w| w.kind() == "interrupted" && w.to_string().contains("interrupted")));
    // the JSON carries the stop like an integration failure's
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["stopped_at"].as_f64(), Some(t));
}
