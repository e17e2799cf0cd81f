//! `tensegrity tipover --dynamic [flags of toroid::TipoverDynamicRequest] [--out lean.csv]
//! [--json]`: the static tip-over threshold checked by the full 3-D dynamics (one call to
//! [`TipoverDynamicRequest::run`]); `--rolling` the lean while rolling down a cross-sloped
//! plane ([`TipoverRollingRequest::run`]).

use anyhow::{Context, Result};
use std::path::Path;
use toroid::tipover_dynamic::{DynamicTipoverReport, LeanSample};
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};

/// Runs the lean-while-rolling study and prints its report.
pub fn run_rolling(req: &TipoverRollingRequest, out: Option<&Path>, json: bool) -> Result<()> {
    let r = req.run().context("rolling lean run failed")?;
    for w in &r.warnings {
        eprintln!("warning: {}", super::spell::flags(w));
    }
    if let Some(path) = out {
        use std::fmt::Write;
        let mut text = String::from("t,lean,downhill,across\n");
        for s in &r.samples {
            let _ = writeln!(text, "{},{},{},{}", s.t, s.lean, s.downhill, s.across);
        }
        tensegrity_io::write_text(path, "lean history", &text)
            .with_context(|| format!("writing the lean history {}", path.display()))?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&r)?);
    } else {
        println!(
            "n = {}, T = {} m rolling {:.2}° down with a {:.2}° side slope (static limit {:.2}°)",
            r.sides,
            r.outer_tread,
            r.incline.to_degrees(),
            r.side_slope.to_degrees(),
            r.static_critical_side_slope.to_degrees()
        );
        println!(
            "largest lean {:.4} rad, final {:.4} rad, {:.3} m downhill: {}",
            r.max_lean,
            r.final_lean,
            r.downhill,
            match r.fall_time {
                Some(t) => format!("fell at t = {t:.3} s"),
                None => "stayed up".to_string(),
            }
        );
        println!("{}", validity_line(r.valid, r.max_penetration));
    }
    Ok(())
}

/// Runs the dynamic check and prints its report.
pub fn run(req: &TipoverDynamicRequest, out: Option<&Path>, json: bool) -> Result<()> {
    let report = req.run().context("dynamic tip-over run failed")?;
    if let Some(path) = out {
        write_history(path, &report.samples)?;
    }
    if json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print(&report);
    }
    Ok(())
}

fn write_history(path: &Path, samples: &[LeanSample]) -> Result<()> {
    use std::fmt::Write;
    let mut text = String::from("t,force,lean,near_normal,far_normal\n");
    for s in samples {
        let _ = writeln!(
            text,
            "{},{},{},{},{}",
            s.t, s.force, s.lean, s.near_normal, s.far_normal
        );
    }
    tensegrity_io::write_text(path, "lean history", &text)
        .with_context(|| format!("writing the lean history {}", path.display()))
}

fn print(r: &DynamicTipoverReport) {
    println!(
        "n = {}, T = {} m, mass {:.4} kg, resting on a side (hub height {:.4} m)",
        r.sides, r.outer_tread, r.mass_kg, r.hub_height
    );
    println!("static threshold (m g/2)(T/h): {:.4} N", r.static_threshold);
    match (r.dynamic_threshold, r.relative_difference) {
        (Some(d), Some(rel)) => println!(
            "dynamic threshold (near tread edge unloads): {d:.4} N ({:+.2} %)",
            100.0 * rel
        ),
        _ => println!("the near tread edge never unloaded: the wheel did not tip"),
    }
    println!(
        "largest lean {:.4} rad, final {:.4} rad: {}",
        r.max_lean,
        r.final_lean,
        if r.tipped { "tipped over" } else { "upright" }
    );
    println!("{}", validity_line(r.valid, r.max_penetration));
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
