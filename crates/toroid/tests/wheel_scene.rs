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
