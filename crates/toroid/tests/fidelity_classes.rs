//! The fidelity policy of `auto` (`wheel_rolling::fidelity`): its table of scene classes is
//! a measurement of rigid against full, and `auto` follows whatever the table says.
//!
//! - `measure_the_scene_classes` (ignored, release: `cargo test --release -p toroid --test
//!   fidelity_classes -- --ignored --nocapture`, a few minutes) rolls one scene per class
//!   with both models, each with its convergence check, and prints the rows of
//!   `wheel_rolling::fidelity::MEASURED` (the rule of the module docs: per headline quantity
//!   the difference d between the models against the uncertainty U of both; the row keeps
//!   the largest d/U). It asserts that each scene is of its class and that the table in the
//!   code says the same as the measurement (agrees or not).
//! - The default tests check that `auto` picks rigid exactly where the table's row agrees
//!   and covers the scene, and says why.

use toroid::{roll_observed, FidelityChoice, RollReport, RollRequest};
use wheel_rolling::fidelity::{ClassAgreement, SceneClass, MEASURED};
use wheel_rolling::{Fidelity, RollSettings, RunChecks};

/// One measured scene: its class, slope (degrees), sides and time (s).
struct Scene {
    class: SceneClass,
    incline_deg: f64,
    sides: usize,
    t_end: f64,
}

/// One scene per class (the `scenes` of `MEASURED`).
const SCENES: [Scene; 4] = [
    Scene {
        class: SceneClass::AtRest,
        incline_deg: 10.0,
        sides: 8,
        t_end: 1.0,
    },
    Scene {
        class: SceneClass::FirstPivot,
        incline_deg: 30.0,
        sides: 8,
        t_end: 1.0,
    },
    Scene {
        class: SceneClass::Rolling,
        incline_deg: 20.0,
        sides: 16,
        t_end: 2.0,
    },
    Scene {
        class: SceneClass::Hopping,
        incline_deg: 50.0,
        sides: 8,
        t_end: 2.0,
    },
];

/// The measured settings (`MEASURED_SETTINGS`): stiff strings and ground, μ_s = 1.2, e = 0,
/// RK4 at 50 µs; `fidelity` and the checks as given.
fn stiff(
    incline_deg: f64,
    sides: usize,
    t_end: f64,
    fidelity: FidelityChoice,
    checks: RunChecks,
) -> RollRequest {
    let mut r = RollRequest {
        fidelity,
        t_end,
        mu: 1.2,
        settings: RollSettings {
            incline: incline_deg.to_radians(),
            string_stiffness: 2e6,
            ground_stiffness: 1e6,
            dt: Some(5e-5),
            ..RollSettings::default()
        },
        checks,
        ..RollRequest::default()
    };
    r.wheel.params.sides = sides;
    r
}

/// The report's value of a headline quantity by its key.
fn value(json: &serde_json::Value, key: &str) -> Option<f64> {
    key.split('.')
        .try_fold(json, |v, k| v.get(k))
        .and_then(serde_json::Value::as_f64)
}

/// The scale floor of a quantity in the relative difference (as the convergence check's).
fn floor(name: &str) -> f64 {
    match name {
        "impacts" | "airborne_fraction" | "slip_fraction" => 1.0,
        "axle_height_oscillation" | "mean_speed" | "final_speed" => 1e-3,
        _ => 0.0,
    }
}

/// A model's uncertainty of quantity `name` (relative): its tolerance when its check says
/// converged, else its change at the refinement (at least the tolerance).
fn uncertainty(r: &RollReport, name: &str) -> f64 {
    let c = r.summary.convergence.as_ref().expect("checked");
    let q = c
        .quantities
        .iter()
        .find(|q| q.name == name)
        .expect("headline");
    if q.converged {
        q.tolerance
    } else {
        q.relative_change.unwrap_or(1.0).max(q.tolerance)
    }
}

/// The quantity with the largest d/U of rigid against full: (name, d, U).
fn worst(rigid: &RollReport, full: &RollReport) -> (String, f64, f64) {
    let (a, b) = (
        serde_json::to_value(rigid).unwrap(),
        serde_json::to_value(full).unwrap(),
    );
    let mut out = (String::new(), 0.0, 1.0);
    for name in wheel_rolling::RunSummary::headline_names() {
        let (Some(x), Some(y)) = (value(&a, name), value(&b, name)) else {
            continue;
        };
        let d = (x - y).abs() / x.abs().max(y.abs()).max(floor(name)).max(1e-300);
        let u = uncertainty(rigid, name) + uncertainty(full, name);
        if d / u > out.1 / out.2 || out.0.is_empty() {
            out = (name.to_string(), d, u);
        }
    }
    out
}

#[test]
#[ignore = "release, a few minutes: re-measures the fidelity table"]
fn measure_the_scene_classes() {
    for s in &SCENES {
        let run = |f| {
            let r = stiff(s.incline_deg, s.sides, s.t_end, f, RunChecks::default());
            roll_observed(&r, &[], None).unwrap()
        };
        let (rigid, full) = (run(FidelityChoice::Rigid), run(FidelityChoice::Full));
        let probe = wheel_rolling::RigidRolling::new(
            &wheel_rolling::Polygon {
                sides: s.sides,
                outer_radius: 1.0,
                mass: rigid.mass_kg,
                i1: rigid.i1,
            },
            &stiff(
                s.incline_deg,
                s.sides,
                s.t_end,
                FidelityChoice::Rigid,
                RunChecks::NONE,
            )
            .spec(),
        )
        .run(s.t_end)
        .unwrap();
        assert_eq!(SceneClass::of(&probe), s.class, "{}", s.class.name());
        let (name, d, u) = worst(&rigid, &full);
        println!(
            "{:?}: `{name}` differs by {d:.3} against {u:.3} ({}); rigid valid {}, full valid {}: {:?}",
            s.class,
            if d <= u { "agree" } else { "differ" },
            rigid.summary.valid,
            full.summary.valid,
            full.summary.warnings
        );
        let row = ClassAgreement::of(s.class);
        assert_eq!(row.agrees(), d <= u, "the table's row of {:?}", s.class);
    }
}

/// `auto` on stiff strings: the rigid run decides the class, and the answer is rigid exactly
/// where the table's row agrees (the scene is inside its measured range); the reason names
/// the class and the measurement.
#[test]
fn auto_follows_the_measured_table() {
    // one short scene per class where the rigid probe is cheap: at rest and the first pivot
    for (deg, t_end, class) in [
        (10.0, 0.05, SceneClass::AtRest),
        (30.0, 0.05, SceneClass::FirstPivot),
    ] {
        let checks = RunChecks::NONE;
        let r = roll_observed(
            &stiff(deg, 8, t_end, FidelityChoice::Auto, checks),
            &[],
            None,
        )
        .unwrap();
        let row = ClassAgreement::of(class);
        assert!(row.covers(7.05e-5, 1e6), "{row:?}");
        let expected = if row.agrees() {
            Fidelity::Rigid
        } else {
            Fidelity::Full
        };
        assert_eq!(r.fidelity, expected, "{}", r.fidelity_reason);
        assert!(
            r.fidelity_reason.contains(class.name()),
            "{}",
            r.fidelity_reason
        );
        assert!(
            r.fidelity_reason.contains("measured"),
            "{}",
            r.fidelity_reason
        );
    }
    // the default strings stretch: full without a rigid run
    let soft = roll_observed(
        &RollRequest {
            t_end: 0.05,
            checks: RunChecks::NONE,
            ..RollRequest::default()
        },
        &[],
        None,
    )
    .unwrap();
    assert_eq!(soft.fidelity, Fidelity::Full);
    assert!(soft.fidelity_reason.starts_with("the strings stretch"));
}

/// The table is consistent: one row per class, each a difference and an uncertainty that
/// are numbers, the verdict their comparison.
#[test]
fn the_table_has_one_measured_row_per_class() {
    for class in SceneClass::ALL {
        let rows: Vec<_> = MEASURED.iter().filter(|r| r.class == class).collect();
        assert_eq!(rows.len(), 1, "{class:?}");
        let r = rows[0];
        assert!(r.difference.is_finite() && r.uncertainty > 0.0, "{r:?}");
        assert_eq!(r.agrees(), r.difference <= r.uncertainty);
        assert!(r.measured().contains(r.quantity));
    }
}
