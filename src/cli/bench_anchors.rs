//! `tensegrity bench anchors [--quick] [--repeats K] [--no-instructions] [--json] [--csv FILE]`:
//! the anchor scenes against the reference codes' times and the scaling series with their
//! cost exponents (the engine's [`bench_anchors`]); the instructions per step are counted by
//! running this binary's hidden `bench anchor-run NAME --steps K` under callgrind when
//! valgrind is installed ([`Callgrind`]).

use super::output;
use super::request_args::RequestArgs;
use anyhow::{anyhow, Result};
use std::path::PathBuf;
use std::process::Command;
use tensegrity_engine::bench::{
    bench_anchors, callgrind_total, Anchor, AnchorsReport, AnchorsRequest, InstructionCounter,
};
use tensegrity_io::sink::CsvSink;

/// Arguments of `tensegrity bench anchors`.
#[derive(clap::Args, Debug)]
pub struct AnchorsArgs {
    #[command(flatten)]
    request: RequestArgs<AnchorsRequest>,
    /// Print the report as JSON.
    #[arg(long)]
    json: bool,
    /// Write one row per anchor and per series point to FILE (CSV).
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
}

/// Arguments of the hidden `tensegrity bench anchor-run`: one anchor run, nothing printed
/// (what callgrind counts).
#[derive(clap::Args, Debug)]
pub struct AnchorRunArgs {
    /// The anchor (motes_dbar, motes_prism, tsgfem_tbar, double_pendulum_rk4).
    anchor: String,
    /// Steps to run (default: the scene's).
    #[arg(long)]
    steps: Option<u64>,
}

/// Runs `tensegrity bench anchors`.
pub fn anchors(args: &AnchorsArgs) -> Result<()> {
    let request: AnchorsRequest = args.request.request()?;
    let csv = output::open("--csv", args.csv.as_deref(), |p| {
        CsvSink::open(p, "bench CSV")
    })?;
    let counter = Callgrind::find();
    let counter = counter.as_ref().map(|c| c as &dyn InstructionCounter);
    let report = bench_anchors(&request, counter)?;
    if let Some(mut csv) = csv {
        csv.extend(report.rows())?;
        csv.finish()?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print(&report);
    }
    Ok(())
}

/// Runs the hidden `tensegrity bench anchor-run`.
pub fn anchor_run(args: &AnchorRunArgs) -> Result<()> {
    let anchor: Anchor = args.anchor.parse().map_err(|e: String| anyhow!(e))?;
    anchor.run(args.steps)?;
    Ok(())
}

fn print(r: &AnchorsReport) {
    println!("anchor                steps   best ms  µs/step  instr/step  final error m       reference       ratio");
    for a in &r.anchors {
        let instr = a
            .instructions_per_step
            .map_or("-".to_string(), |i| format!("{i:.0}"));
        println!(
            "{:<20} {:>6} {:>9.3} {:>8.3} {:>11} {:>8.1e} (≤ {:.0e}) {:<7}{:>6.2} s {:>8.0}×",
            a.anchor.name(),
            a.steps,
            a.best_s * 1e3,
            a.per_step_s * 1e6,
            instr,
            a.final_error_m,
            a.final_tolerance_m,
            a.reference.code,
            a.reference.seconds,
            a.ratio
        );
    }
    println!("{}", r.reference_note);
    if let Some(note) = &r.instructions_note {
        println!("instructions not counted: {note}");
    }
    for s in &r.series {
        let points: Vec<String> = s
            .points
            .iter()
            .map(|p| match p.per_step_s {
                Some(t) => format!("{} {:.2} µs/step", p.size, t * 1e6),
                None => format!("{} {:.3} ms", p.size, p.best_s * 1e3),
            })
            .collect();
        let fit = s.fit.map_or("-".into(), |f| format!("{:.2}", f.exponent));
        println!(
            "{} ({}): {}; exponent {fit}",
            s.series.name(),
            s.parameter,
            points.join(", ")
        );
    }
}

/// The instruction counter of this binary under callgrind.
struct Callgrind {
    exe: PathBuf,
}

impl Callgrind {
    /// When valgrind runs and this binary's path is known.
    fn find() -> Option<Self> {
        let works = Command::new("valgrind").arg("--version").output();
        if !works.is_ok_and(|o| o.status.success()) {
            return None;
        }
        std::env::current_exe().ok().map(|exe| Callgrind { exe })
    }
}

impl InstructionCounter for Callgrind {
    fn count(&self, anchor: Anchor, steps: u64) -> Result<u64, String> {
        let file =
            std::env::temp_dir().join(format!("tensegrity-callgrind-{}.out", std::process::id()));
        let out = Command::new("valgrind")
            .arg("--tool=callgrind")
            .arg(format!("--callgrind-out-file={}", file.display()))
            .arg(&self.exe)
            .args(["bench", "anchor-run", anchor.name(), "--steps"])
            .arg(steps.to_string())
            .output()
            .map_err(|e| format!("valgrind: {e}"));
        let _ = std::fs::remove_file(&file);
        let out = out?;
        if !out.status.success() {
            return Err(format!(
                "the callgrind run of {anchor} failed ({})",
                out.status
            ));
        }
        callgrind_total(&String::from_utf8_lossy(&out.stderr))
            .ok_or_else(|| "no instruction total in callgrind's output".to_string())
    }
}
