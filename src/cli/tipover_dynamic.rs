//! `tensegrity tipover --dynamic [flags of toroid::TipoverDynamicRequest] [--out lean.csv]
//! [--json]`: the static tip-over threshold checked by the full 3-D dynamics (one call to
//! [`TipoverDynamicRequest::run`]); `--rolling` the lean while rolling down a cross-sloped
//! plane ([`TipoverRollingRequest::run`]).
//!
//! `--animate FILE.gif|FILE.webm` (with `--dynamic`) draws the wheel under the ramp from the run's
//! samples ([`super::animate`]). `--out` is opened before the run (a bad path: exit 2 at once) and renamed into place once
//! its rows are written; the runs do not poll the interrupt flag, so SIGINT leaves no file.

use super::animate::AnimateArgs;
use anyhow::{Context, Result};
use nalgebra::Vector3;
use std::path::Path;
use tensegrity_core::Structure;
use tensegrity_dynamics::Ground;
use tensegrity_figures::animation::Scenery;
use tensegrity_io::sink::{CsvSink, NodeFrames};
use toroid::tipover_dynamic::DynamicTipoverReport;
use toroid::tipover_dynamic::FrameWatch;
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};

/// Opens the lean history of `--out` with `header`.
fn open_history(out: Option<&Path>, header: &[&str]) -> Result<Option<CsvSink>> {
    super::output::open("--out", out, |p| {
        CsvSink::with_header(p, "lean history", header)
    })
}

/// Writes `rows` (each a row of numbers) to the opened history and renames it into place.
fn write_history<const N: usize>(
    sink: Option<CsvSink>,
    rows: impl Iterator<Item = [f64; N]>,
) -> Result<()> {
    if let Some(mut sink) = sink {
        for row in rows {
            sink.record(row.map(|x| x.to_string()))?;
        }
        sink.finish()?;
    }
    Ok(())
}

/// Runs the lean-while-rolling study and prints its report.
pub fn run_rolling(req: &TipoverRollingRequest, out: Option<&Path>, json: bool) -> Result<()> {
    let _progress = super::guard::estimated(req)?;
    let sink = open_history(out, &["t", "lean", "downhill", "across"])?;
    let r = req.report().context("rolling lean run failed")?;
    for w in &r.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    let rows = r
        .samples
        .iter()
        .map(|s| [s.t, s.lean, s.downhill, s.across]);
    write_history(sink, rows)?;
    if json {
        super::output::print_json(&r)?;
    } else {
        println!(
            "n = {}, T = {} m rolling {:.2}° down with a {:.2}° side slope (static limit {:.2}°){}",
            r.sides,
            r.outer_tread,
            r.incline.to_degrees(),
            r.side_slope.to_degrees(),
            r.static_critical_side_slope.to_degrees(),
            super::output::invalid_mark(r.valid)
        );
        println!(
            "largest lean {:.4} rad, final {:.4} rad, {:.3} m downhill: {}",
            r.max_lean,
            r.final_lean,
            r.downhill,
            match r.fall_time {
                Some(t) => format!("fell at t = {t:.3} s (ends past its tip angle)"),
                None => "did not fall (ends inside its tip angle)".to_string(),
            }
        );
        if r.convergence
            .as_ref()
            .is_some_and(|c| c.chaotic().contains(&"fell"))
        {
            println!("whether it fell is a draw: it wobbles past its tip angles and the final lean's interval lies on both sides of one");
        }
        println!("{}", validity_line(r.valid, r.max_penetration));
        super::output::print_convergence(r.convergence.as_ref());
    }
    Ok(wheel_rolling::strict_check(req.checks.strict, &r.warnings)?)
}

/// Runs the dynamic check and prints its report.
pub fn run(
    req: &TipoverDynamicRequest,
    out: Option<&Path>,
    json: bool,
    animate: &AnimateArgs,
) -> Result<()> {
    let header = ["t", "force", "lean", "near_normal", "far_normal"];
    let _progress = super::guard::estimated(req)?;
    let sink = open_history(out, &header)?;
    let (mut opened, mut animation) = (animate.open()?, None);
    let t_end = req.settings.t_end();
    let mut watch = |s: &Structure, g: &Ground, t: f64, nodes: &[Vector3<f64>]| {
        if let Some(o) = opened.take() {
            let mut scenery = Scenery::structure("tip-over under a lateral force", s, Some(g));
            scenery.along_y = true; // the lean about ι2 shows in the (x, z) plane
            animation = Some(o.start(scenery, t_end));
        }
        if let Some(a) = animation.as_mut() {
            let _ = a.frame(t, nodes); // keeping a frame cannot fail
        }
    };
    let watched = animate
        .animate
        .is_some()
        .then_some(&mut watch as &mut FrameWatch<'_>);
    let report = req
        .report_watched(watched)
        .context("dynamic tip-over run failed")?;
    super::animate::finish(animation, animate.animate.as_deref())?;
    for w in &report.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    let rows = report
        .samples
        .iter()
        .map(|s| [s.t, s.force, s.lean, s.near_normal, s.far_normal]);
    write_history(sink, rows)?;
    if json {
        super::output::print_json(&report)?;
    } else {
        print(&report);
    }
    Ok(wheel_rolling::strict_check(
        req.checks.strict,
        &report.warnings,
    )?)
}

fn print(r: &DynamicTipoverReport) {
    println!(
        "n = {}, T = {} m, mass {:.4} kg, resting on a side (hub height {:.4} m){}",
        r.sides,
        r.outer_tread,
        r.mass_kg,
        r.hub_height,
        super::output::invalid_mark(r.valid)
    );
    println!("static threshold (m g/2)(T/h): {:.4} N", r.static_threshold);
    match (r.dynamic_threshold, r.relative_difference) {
        (Some(d), Some(rel)) => println!(
            "dynamic threshold (near tread edge unloads): {d:.4} N ({:+.2} %)",
            100.0 * rel
        ),
        _ => println!("the near tread edge never unloaded: the wheel did not tip"),
    }
    let verdict = match r.tip_time {
        Some(t) => format!("tipped over at t = {t:.3} s (lean past the tip angle of the load)"),
        None => "did not tip".to_string(),
    };
    println!(
        "largest lean {:.4} rad, final {:.4} rad (static tip angle {:.4} rad): {verdict}",
        r.max_lean, r.final_lean, r.static_tip_angle
    );
    println!("{}", validity_line(r.valid, r.max_penetration));
    super::output::print_convergence(r.convergence.as_ref());
}

fn validity_line(valid: bool, max_penetration: f64) -> String {
    format!(
        "validity: {}; max penetration {max_penetration:.3e} m",
        if valid {
            "valid"
        } else {
            "NOT valid (see the warnings)"
        }
    )
}
