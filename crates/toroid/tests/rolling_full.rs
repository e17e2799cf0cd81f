//! The full tensegrity model rolling down an incline: the Fig. 3.10 trend, the start from
//! rest, and agreement of the contact force with the weight while the wheel sits still.

use toroid::roll::scene;
use toroid::{build, ToroidParams};
use wheel_rolling::fidelity::auto_fidelity;
use wheel_rolling::{ContactModel, Fidelity, FullRolling, FullRun, RollingResult};

fn wheel(n: usize) -> toroid::Toroid {
    build(
        &ToroidParams::default().sides(n),
        "spokes,inner".parse().unwrap(),
        1.0,
    )
    .unwrap()
}

/// The toroid's full run with the default strings (2·10⁴ N/m, 20 N minimum prestress).
fn full(roll: &FullRolling, t: &toroid::Toroid, t_end: f64) -> FullRun {
    roll.run_scene(&scene(t, 2e4, 20.0).unwrap(), t_end)
        .unwrap()
}

#[test]
fn axle_height_oscillation_decreases_with_n_in_the_full_model() {
    // thesis contact (damping 200 N s/m), 50°, strings 2e4 N/m with a 20 N minimum prestress
    let roll = FullRolling {
        contact: ContactModel::Thesis { damping: 200.0 },
        ..FullRolling::default()
    };
    let mut values = Vec::new();
    for n in [8, 12, 16, 24] {
        let r = full(&roll, &wheel(n), 2.0).result;
        assert!(r.mean_speed > 1.0, "n = {n}: the wheel rolls downhill");
        values.push(r.axle_height_oscillation);
    }
    assert!(values.windows(2).all(|w| w[1] < w[0]), "{values:?}");
    assert!(values[0] / values[3] > 10.0, "{values:?}");
}

#[test]
fn on_level_ground_the_contact_carries_the_weight_on_average() {
    // impulse balance: ∫N dt = m g T + m Δv_z; balanced on a pair the wheel barely moves in
    // 1 s, so the mean normal force is the weight (the strings keep vibrating, so N itself
    // oscillates about it)
    let t = wheel(8);
    let mass = toroid::wheel_mass(&t.structure);
    let roll = FullRolling {
        incline: 0.0,
        ..FullRolling::default()
    };
    let r = full(&roll, &t, 1.0).result;
    let mean_normal = r.samples.iter().map(|s| s.normal).sum::<f64>() / r.samples.len() as f64;
    let weight = mass * 9.81;
    assert!(
        (mean_normal - weight).abs() < 0.01 * weight,
        "{mean_normal} vs {weight}"
    );
    // it starts on a side, hub at s = −R_o sin(π/n) from the downhill pair, and stays there
    let s0 = -(std::f64::consts::PI / 8.0).sin();
    assert!(
        r.samples.iter().all(|s| (s.s - s0).abs() < 1e-2),
        "no slope, no rolling"
    );
    assert!(r.validity.valid(), "{:?}", r.validity.warnings);
    assert!(r.validity.airborne_fraction < 0.01);
}

#[test]
fn auto_fidelity_follows_the_string_stiffness() {
    let mass = toroid::wheel_mass(&wheel(8).structure);
    assert_eq!(auto_fidelity(mass, 9.81, 2e4, 1.0), Fidelity::Full);
    assert_eq!(auto_fidelity(mass, 9.81, 1e6, 1.0), Fidelity::Rigid);
}

#[test]
fn bad_full_rolling_settings_are_named() {
    let t = wheel(8);
    let bad = FullRolling {
        incline: 2.0,
        ..FullRolling::default()
    };
    assert!(bad
        .run_scene(&scene(&t, 2e4, 20.0).unwrap(), 1.0)
        .unwrap_err()
        .to_string()
        .contains("incline"));
    let e = scene(&t, 1.0, 20.0).unwrap_err().to_string();
    assert!(
        e.contains("string_stiffness") && e.contains("rest length"),
        "{e}"
    );
}

#[test]
fn a_slippery_penalty_ground_makes_the_wheel_slide() {
    let t = wheel(8);
    let on = |mu: f64| {
        let roll = FullRolling {
            incline: 30f64.to_radians(),
            contact: ContactModel::Penalty {
                stiffness: 1e5,
                damping: 200.0,
                mu_static: mu,
                mu_kinetic: 0.75 * mu,
            },
            ..FullRolling::default()
        };
        full(&roll, &t, 1.0).result
    };
    let (ice, rubber) = (on(0.05), on(1.0));
    assert!(
        ice.mean_slip_speed > 5.0 * rubber.mean_slip_speed,
        "{} vs {}",
        ice.mean_slip_speed,
        rubber.mean_slip_speed
    );
    // on ice the wheel slides down with little rolling: more distance per turn
    let turns = |r: &RollingResult| r.samples.iter().map(|s| s.omega).sum::<f64>() * 1e-3;
    let last = |r: &RollingResult| r.samples.last().unwrap().s;
    assert!(
        last(&ice) / turns(&ice).abs().max(1e-9) > last(&rubber) / turns(&rubber).abs().max(1e-9)
    );
}

#[test]
fn the_full_model_keeps_its_bar_lengths_through_impacts() {
    // RK4 alone drifted the bar lengths by ~10⁻⁴ relative in 1.5 s of this run (5·10⁻³ in 3 s);
    // the state is projected onto the bar lengths and joints after every step, so the frames
    // (a rigid transform of the node positions) keep them to round-off even after impacts
    let w = wheel(8);
    let roll = FullRolling {
        frame_times: vec![0.0, 0.75, 1.5],
        ..FullRolling::default()
    };
    let run = full(&roll, &w, 1.5);
    assert!(run.result.impact_log.len() >= 2, "the run passes impacts");
    assert!(
        run.result.validity.valid(),
        "{:?}",
        run.result.validity.warnings
    );
    let nodes = w.structure.nodes();
    assert_eq!(run.frames.len(), 3);
    let mut worst: f64 = 0.0;
    for frame in &run.frames {
        for bar in w.structure.bars() {
            let [a, b] = bar.nodes;
            let l0 = (nodes[b] - nodes[a]).norm();
            let l = (frame.nodes[b] - frame.nodes[a]).norm();
            worst = worst.max((l - l0).abs() / l0);
        }
    }
    assert!(worst < 1e-10, "bar lengths drifted by {worst:e}");
}

#[test]
fn a_run_that_fails_midway_keeps_what_it_computed_and_says_so() {
    // strings of 10⁹ N/m are far too stiff for RK4 at 0.1 ms: the integration diverges at
    // t = 0.3 ms; the run returns the states before the failure, flagged, instead of an error
    // that would lose them
    let stiff = scene(&wheel(8), 1e9, 20.0).unwrap();
    let r = FullRolling::default()
        .run_scene(&stiff, 0.01)
        .unwrap()
        .result;
    let t = r.validity.stopped_at.expect("the run stopped early");
    assert!((0.0..0.01).contains(&t), "{t}");
    assert!(!r.validity.valid());
    assert!(
        r.validity
            .warnings
            .iter()
            .any(|w| w.kind() == "stopped_early" && w.to_string().contains("`dt`")),
        "{:?}",
        r.validity.warnings
    );
    assert!(r.samples.last().is_some_and(|s| s.t <= t + 1e-12));
    // a run that completes has no stop time
    let ok = full(&FullRolling::default(), &wheel(8), 0.01).result;
    assert_eq!(ok.validity.stopped_at, None);
}
