//! Cross-validation of the two rolling models from the same start (at rest on a side, about
//! to pivot about the downhill pair): the reduced rigid model with unilateral contact against
//! the full tensegrity model with stiff strings (2·10⁶ N/m) and a stiff penalty ground
//! (10⁶ N/m per node), the same μ and e = 0 (the penalty damping matched to it).
//!
//! The default test checks the first pivot, where both models apply; the ignored harness
//! prints the table of docs/notes/ROLLING.md:
//! `cargo test --release -p toroid --test integration roll_crossval:: -- --ignored --nocapture`.

use std::f64::consts::PI;
use toroid::{roll, FidelityChoice, RollReport, RollRequest, WheelSpec};
use wheel_rolling::{RollSettings, RollingSample, RunChecks};

/// The stiff full model and the rigid model of one case.
fn pair(sides: usize, incline_deg: f64, mu: f64, t_end: f64) -> (RollReport, RollReport) {
    let base = RollRequest {
        wheel: WheelSpec::with_sides(sides),
        settings: RollSettings {
            incline: incline_deg.to_radians(),
            restitution: 0.0,
            string_stiffness: 2e6,
            ground_stiffness: 1e6,
            dt: Some(5e-5),
            ..RollSettings::default()
        },
        mu,
        t_end,
        // the comparison of the two models is the check here
        checks: RunChecks::NONE,
        ..RollRequest::default()
    };
    let rigid = roll(&RollRequest {
        fidelity: FidelityChoice::Rigid,
        ..base
    })
    .unwrap();
    let full = roll(&RollRequest {
        fidelity: FidelityChoice::Full,
        ..base
    })
    .unwrap();
    (rigid, full)
}

/// Largest distance between the two axle tracks (s, h) over the samples with t ≤ `until`.
fn track_difference(a: &[RollingSample], b: &[RollingSample], until: f64) -> f64 {
    a.iter()
        .zip(b)
        .filter(|(x, _)| x.t <= until + 1e-12)
        .map(|(x, y)| (x.s - y.s).hypot(x.h - y.h))
        .fold(0.0, f64::max)
}

#[test]
fn rigid_and_full_agree_through_the_first_pivot_on_30_degrees() {
    // n = 8, 30°, μ = 1.2, e = 0: the rigid model's first impact is the closed form (time
    // from the pivot equation, ω⁻ from energy: ½(I₁ + m R²) ω⁻² = 2 m g R sin φ sin(π/n)).
    // The full wheel starts at rest in its deformed shape under gravity (`FullStart`: a stiff
    // wheel), so it pivots as the rigid one does; tolerances 1 % on the impact time, 0.5 % on
    // ω⁻ and 1 % of R_o on the axle track up to the first impact (measured: +0.19 %,
    // −0.012 %, 1.9 mm; released from its unloaded shape it sagged into the ground and led:
    // 1.4 %, 0.14 %, 3.3 cm).
    let (rigid, full) = pair(8, 30.0, 1.2, 1.15);
    assert!(rigid.summary.valid && full.summary.max_penetration < 0.01);
    let (r, f) = (
        rigid.summary.first_impact.unwrap(),
        full.summary.first_impact.unwrap(),
    );
    let (m, i1, g, phi) = (rigid.mass_kg, rigid.i1, 9.81, 30f64.to_radians());
    let omega = (4.0 * m * g * phi.sin() * (PI / 8.0).sin() / (i1 + m)).sqrt();
    assert!((r.omega_before - omega).abs() < 1e-6 * omega);
    assert!((f.t - r.t).abs() < 0.01 * r.t, "{} vs {}", f.t, r.t);
    assert!((f.omega_before - r.omega_before).abs() < 0.005 * r.omega_before);
    let d = track_difference(&rigid.samples, &full.samples, r.t.min(f.t));
    assert!(d < 0.01, "axle tracks differ by {d} m");
    // both start from the same pose: the downhill pair at s = 0, the axle above the side; the
    // full wheel's axle lower and turned by its static deformation (measured: s +0.22 mm,
    // h −0.05 mm)
    let (a, b) = (&rigid.samples[0], &full.samples[0]);
    assert!((a.s - b.s).abs() < 1e-3 && (a.h - b.h).abs() < 1e-3);
    assert!((a.h - (PI / 8.0).cos()).abs() < 1e-12);
}

#[test]
fn the_first_landing_on_40_degrees_is_the_first_impact_for_n_16() {
    // n = 16, 40°, μ = 1.2, e = 0 (issue 21): the next pair's touch-down chatters on the
    // stiff penalty ground (loaded at 0.49670 s, off one 50 µs step later, loaded again
    // 0.1 ms after that while the old pivot still carries). The monitor used to drop the
    // first touch as a graze and ignore the second as chatter (shorter than the re-arm time),
    // so the full run's first impact was its landing after the rebound, 0.699 s. Measured now:
    // full 0.49670 s against rigid 0.49705 s (−0.07 %), ω⁻ 1.7279 against 1.7304 rad/s.
    let (rigid, full) = pair(16, 40.0, 1.2, 0.55);
    let (r, f) = (
        rigid.summary.first_impact.unwrap(),
        full.summary.first_impact.unwrap(),
    );
    // the rigid model's closed form: ½(I₁ + m R²) ω⁻² = 2 m g R sin φ sin(π/n), R = 1
    let (m, i1, g, phi) = (rigid.mass_kg, rigid.i1, 9.81, 40f64.to_radians());
    let omega = (4.0 * m * g * phi.sin() * (PI / 16.0).sin() / (i1 + m)).sqrt();
    assert!((r.omega_before - omega).abs() < 1e-6 * omega);
    assert!((f.t - r.t).abs() < 0.01 * r.t, "{} vs {}", f.t, r.t);
    assert!((f.omega_before - r.omega_before).abs() < 0.005 * r.omega_before);
    assert_eq!(full.impact_log.len(), 1, "{:?}", full.impact_log);
}

fn cell(a: f64, b: f64) -> String {
    format!("{a:.3} / {b:.3}")
}

/// The cross-validation table (slopes 10°–50°, n = 8…24), printed as Markdown.
#[test]
#[ignore = "slow: 20 full runs; cargo test --release -p toroid --test integration roll_crossval:: -- --ignored --nocapture"]
fn cross_validation_table() {
    println!("| φ | n | first impact t [s] | ω⁻ [rad/s] | ω⁺ [rad/s] | track diff. to 1st impact [m] | to 3rd rigid impact [m] | mean speed [m/s] | airborne | valid | run time [s] |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for phi in [10.0, 20.0, 30.0, 40.0, 50.0] {
        for n in [8, 12, 16, 24] {
            let (r, f) = pair(n, phi, 1.2, 2.0);
            let none = toroid::FirstImpact {
                t: f64::NAN,
                omega_before: f64::NAN,
                omega_after: f64::NAN,
            };
            let (ri, fi) = (
                r.summary.first_impact.unwrap_or(none),
                f.summary.first_impact.unwrap_or(none),
            );
            let first = if ri.t.is_finite() { ri.t } else { 2.0 };
            let third = r.impact_log.get(2).map_or(2.0, |i| i.t);
            println!(
                "| {phi}° | {n} | {} | {} | {} | {:.4} | {:.4} | {} | {} | {} / {} | {:.4} / {:.2} |",
                cell(ri.t, fi.t),
                cell(ri.omega_before, fi.omega_before),
                cell(ri.omega_after, fi.omega_after),
                track_difference(&r.samples, &f.samples, first),
                track_difference(&r.samples, &f.samples, third),
                cell(r.summary.mean_speed, f.summary.mean_speed),
                cell(r.summary.airborne_fraction, f.summary.airborne_fraction),
                r.summary.valid,
                f.summary.valid,
                r.wall_time_s,
                f.wall_time_s,
            );
        }
    }
}

/// First impacts of the two models on slopes and wheels outside the table (issue 21), with
/// the rigid wheel's pivot from rest: within 1 % in time (measured −0.42 … +0.25 %, ω⁻
/// −0.54 … +0.18 %; the landing chatter of the stiff penalty ground, the uphill pair's
/// chatter at the start on 15°, n = 20, and the sliding pivot's hops on 55°, n = 6, which
/// each made a wrong first impact before, are not impacts).
#[test]
#[ignore = "slow: 17 full runs; cargo test --release -p toroid --test integration roll_crossval:: -- --ignored --nocapture"]
fn first_impacts_agree_on_a_sweep() {
    for phi in [15.0f64, 25.0, 35.0, 45.0, 55.0] {
        for n in [6usize, 10, 14, 20] {
            if phi.to_radians() <= PI / n as f64 {
                continue; // the rigid wheel rests
            }
            let (r, f) = pair(n, phi, 1.2, 1.6);
            let (a, b) = (
                r.summary.first_impact.unwrap(),
                f.summary.first_impact.unwrap(),
            );
            println!(
                "{phi}° n = {n}: rigid {:.4} s, full {:.4} s ({:+.3} %), ω⁻ {:+.3} %",
                a.t,
                b.t,
                100.0 * (b.t - a.t) / a.t,
                100.0 * (b.omega_before - a.omega_before) / a.omega_before
            );
            assert!((b.t - a.t).abs() < 0.01 * a.t, "{phi}°, n = {n}");
            assert!((b.omega_before - a.omega_before).abs() < 0.01 * a.omega_before);
        }
    }
}
