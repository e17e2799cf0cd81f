//! The full model started at rest (`wheel_rolling::full::FullStart`) against the rigid model's
//! closed-form pivot: with stiff strings and ground (10⁶ N/m, μ = 1.2, e = 0, stick contact),
//! the first impact time and the axle travel at 0.9 of the rigid first impact agree within
//! 1 % (issue 21's first must-show), on several wheels and slopes where the wheel pivots.
//!
//! The travel is the axle's distance along the slope from its start, s(0.9 t₁) − s(0), t₁ the
//! rigid model's first impact. Measured (this test, debug profile): n = 8 on 30°: −0.07 % and
//! +0.19 %; n = 12 on 30°: −0.15 % and +0.21 %; n = 16 on 40°: −0.29 % and +0.19 %. Released
//! from its unloaded shape (`FullStart::Unloaded`, the model before) the n = 8 wheel was
//! −2.0 % and +6.3 % off.

use toroid::{roll_observed, RollRequest};
use wheel_rolling::RunChecks;
use wheel_rolling::{ContactKind, FidelityChoice, Flow, Observer, RollSettings, RollingSample};

/// Keeps every sample.
#[derive(Default)]
struct Keep(Vec<RollingSample>);

impl Observer for Keep {
    fn sample(&mut self, s: &RollingSample) -> Flow {
        self.0.push(*s);
        Flow::Continue
    }
}

/// The pivot of `sides` on `incline_deg`: μ = 1.2, e = 0, strings and ground 10⁶ N/m, RK4 at
/// 5·10⁻⁵ s, until `t_end`.
fn request(fidelity: FidelityChoice, sides: usize, incline_deg: f64, t_end: f64) -> RollRequest {
    RollRequest {
        fidelity,
        t_end,
        mu: 1.2,
        contact: ContactKind::Stick,
        settings: RollSettings {
            incline: incline_deg.to_radians(),
            restitution: 0.0,
            string_stiffness: 1e6,
            ground_stiffness: 1e6,
            dt: Some(5e-5),
            ..RollSettings::default()
        },
        checks: RunChecks::NONE,
        ..RollRequest::with_sides(sides)
    }
}

/// First impact time, the samples, and whether the run is valid.
fn run(req: &RollRequest) -> (f64, Vec<RollingSample>, bool) {
    let mut keep = Keep::default();
    let r = roll_observed(req, &[], Some(&mut keep)).unwrap();
    let t1 = r
        .summary
        .first_impact
        .expect("the wheel reaches its next side")
        .t;
    (t1, keep.0, r.summary.valid)
}

/// s(t) − s(0) at the sample nearest `t`.
fn travel(samples: &[RollingSample], t: f64) -> f64 {
    let at = samples
        .iter()
        .min_by(|a, b| (a.t - t).abs().total_cmp(&(b.t - t).abs()))
        .unwrap();
    at.s - samples[0].s
}

/// (relative difference of the first impact, of the travel at 0.9 t₁) full against rigid.
fn against_rigid(sides: usize, incline_deg: f64) -> (f64, f64) {
    let rigid = request(FidelityChoice::Rigid, sides, incline_deg, 2.0);
    let (t_r, s_r, valid) = run(&rigid);
    assert!(valid);
    // the closed form of the rigid pivot from rest: θ̈₀ > 0, the wheel pivots
    assert!(incline_deg.to_radians() > std::f64::consts::PI / sides as f64);
    let full = request(FidelityChoice::Full, sides, incline_deg, 1.02 * t_r);
    let (t_f, s_f, valid) = run(&full);
    assert!(
        valid,
        "n = {sides} on {incline_deg}°: the full run is valid"
    );
    let (d_r, d_f) = (travel(&s_r, 0.9 * t_r), travel(&s_f, 0.9 * t_r));
    assert!(d_r > 0.1, "the wheel rolls: {d_r} m");
    ((t_f - t_r) / t_r, (d_f - d_r) / d_r)
}

#[test]
fn the_full_pivot_from_rest_agrees_with_the_rigid_one_within_one_percent() {
    for (sides, incline) in [(8, 30.0), (12, 30.0), (16, 40.0)] {
        let (impact, travel) = against_rigid(sides, incline);
        eprintln!(
            "n = {sides} on {incline}°: first impact {impact:+.4}, travel at 0.9 t1 {travel:+.4}"
        );
        assert!(
            impact.abs() < 0.01,
            "n = {sides} on {incline}°: first impact {impact:+.4}"
        );
        assert!(
            travel.abs() < 0.01,
            "n = {sides} on {incline}°: travel {travel:+.4}"
        );
    }
}

/// The start is what closes the gap: the same n = 8 run through `FullRolling` directly,
/// started at rest (the default for this stiff wheel: the relaxation converges, in a few
/// thousand steps) and released from its unloaded shape (`FullStart::Unloaded`, measured
/// +6.3 % of axle travel at 0.9 t₁).
#[test]
fn released_unloaded_the_stiff_wheel_leads_the_rigid_pivot() {
    use wheel_rolling::full::FullStart;
    let rigid = request(FidelityChoice::Rigid, 8, 30.0, 2.0);
    let (t_r, s_r, _) = run(&rigid);
    let d_r = travel(&s_r, 0.9 * t_r);
    let req = request(FidelityChoice::Full, 8, 30.0, 0.9 * t_r + 0.01);
    let scene = toroid::roll::scene(
        &toroid::build(
            &toroid::ToroidParams::default().sides(8),
            "spokes,inner".parse().unwrap(),
            1.0,
        )
        .unwrap(),
        1e6,
        req.min_tension,
    )
    .unwrap();
    let spec = req.spec();
    let base = wheel_rolling::FullRolling::new(&spec, &scene.polygon());
    let lead = |start: FullStart| {
        let roll = wheel_rolling::FullRolling {
            start,
            ..base.clone()
        };
        let run = roll.run_scene(&scene, req.t_end).unwrap();
        let d = travel(&run.result.samples, 0.9 * t_r);
        ((d - d_r) / d_r, run.settled)
    };
    let (rest, settled) = lead(FullStart::Auto);
    let settled = settled.expect("a stiff wheel starts at rest");
    assert!(
        settled.pivots && settled.converged && settled.steps < 5000,
        "{settled:?}"
    );
    assert!(rest.abs() < 0.01, "{rest:+.4}");
    let (unloaded, none) = lead(FullStart::Unloaded);
    assert!(none.is_none());
    assert!(unloaded > 0.03, "{unloaded:+.4}");
}
