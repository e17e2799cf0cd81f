//! `tensegrity bench anchors [--quick] [--repeats K] [--no-instructions] [--json] [--csv FILE]`:
//! the anchor scenes against the reference codes' times and the scaling series with their
//! cost exponents (the engine's [`bench_anchors`]); the instructions (per anchor step, per
//! series point) are counted by running this binary's hidden `bench anchor-run NAME --steps K`
//! and `bench series-run SERIES SIZE --reps R` under callgrind when valgrind is installed
//! ([`Callgrind`], several runs side by side).

use super::output;
use super::request_args::RequestArgs;
use anyhow::{anyhow, Result};
use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use tensegrity_bench::series::{run_counted, Series, SeriesKind};
use tensegrity_bench::{
    bench_anchors, callgrind_total, Anchor, AnchorsReport, AnchorsRequest, CountedRun,
    InstructionCounter,
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

/// Arguments of the hidden `tensegrity bench series-run`: one series point's input, then
/// `--reps` calls (steps for rolling), nothing printed (what callgrind counts).
#[derive(clap::Args, Debug)]
pub struct SeriesRunArgs {
    /// The series (toroid, towers, michell, rolling).
    series: String,
    /// The size.
    size: usize,
    /// Calls after the setup (0: the setup alone); steps for the rolling series.
    #[arg(long, default_value_t = 1)]
    reps: u64,
}

/// Runs `tensegrity bench anchors`: the suite's estimate ([`tensegrity_bench::estimate`]:
/// its repeats, its callgrind runs side by side, its CSV) checked against the limits
/// (`--max-work`, `--max-memory`, `--max-output`) before anything runs or is written.
pub fn anchors(args: &AnchorsArgs) -> Result<()> {
    let request: AnchorsRequest = args.request.request()?;
    let counter = Callgrind::find();
    let counted = request.instructions && counter.is_some();
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    let e = tensegrity_bench::estimate::estimate(&request, counted, workers, args.csv.is_some())?;
    let _progress = super::guard::check(e)?;
    let csv = output::open("--csv", args.csv.as_deref(), |p| {
        CsvSink::open(p, "bench CSV")
    })?;
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

/// Runs the hidden `tensegrity bench series-run`.
pub fn series_run(args: &SeriesRunArgs) -> Result<()> {
    let kind = SeriesKind::ALL
        .into_iter()
        .find(|k| k.name() == args.series)
        .ok_or_else(|| {
            let names: Vec<&str> = SeriesKind::ALL.iter().map(|k| k.name()).collect();
            anyhow!(
                "unknown series `{}` (one of {})",
                args.series,
                names.join(", ")
            )
        })?;
    run_counted(kind, args.size, args.reps)?;
    Ok(())
}

fn print(r: &AnchorsReport) {
    println!("anchor                steps   best ms  µs/step  instr/step  final error m       stored reference (not this run)");
    for a in &r.anchors {
        let instr = a
            .instructions_per_step
            .map_or("-".to_string(), |i| format!("{i:.0}"));
        println!(
            "{:<20} {:>6} {:>9.3} {:>8.3} {:>11} {:>8.1e} (≤ {:.0e}) {:<7}{:>6.2} s ({})",
            a.anchor.name(),
            a.steps,
            a.best_s * 1e3,
            a.per_step_s * 1e6,
            instr,
            a.final_error_m,
            a.final_tolerance_m,
            a.reference.code,
            a.reference.seconds,
            a.reference.measured
        );
    }
    println!("{}", r.reference_note);
    if let Some(note) = &r.instructions_note {
        println!("instructions not counted: {note}");
    }
    for s in &r.series {
        print_series(s);
    }
}

fn print_series(s: &Series) {
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
    let counts: Vec<String> = s
        .points
        .iter()
        .filter_map(|p| match p.instructions_per_step {
            Some(i) => Some(format!("{} {i:.0}/step", p.size)),
            None => Some(format!("{} {:.0}", p.size, p.instructions?)),
        })
        .collect();
    match (&s.instructions_note, s.instructions_fit) {
        (Some(note), _) => println!("  instructions: - ({note})"),
        (None, fit) => println!(
            "  instructions: {}; exponent {}",
            counts.join(", "),
            fit.map_or("-".into(), |f| format!("{:.2}", f.exponent))
        ),
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

impl Callgrind {
    /// Instructions of this binary run with `args` under callgrind.
    fn total(&self, args: &[String], what: &str) -> Result<u64, String> {
        static RUN: AtomicUsize = AtomicUsize::new(0);
        let file = std::env::temp_dir().join(format!(
            "tensegrity-callgrind-{}-{}.out",
            std::process::id(),
            RUN.fetch_add(1, Ordering::Relaxed)
        ));
        let out = Command::new("valgrind")
            .arg("--tool=callgrind")
            .arg(format!("--callgrind-out-file={}", file.display()))
            .arg(&self.exe)
            .args(args)
            .output()
            .map_err(|e| format!("valgrind: {e}"));
        let _ = std::fs::remove_file(&file);
        let out = out?;
        if !out.status.success() {
            return Err(format!(
                "the callgrind run of {what} failed ({})",
                out.status
            ));
        }
        callgrind_total(&String::from_utf8_lossy(&out.stderr))
            .ok_or_else(|| "no instruction total in callgrind's output".to_string())
    }
}

impl InstructionCounter for Callgrind {
    fn count(&self, anchor: Anchor, steps: u64) -> Result<u64, String> {
        let args = ["bench", "anchor-run", anchor.name(), "--steps"];
        let mut args: Vec<String> = args.map(String::from).to_vec();
        args.push(steps.to_string());
        self.total(&args, anchor.name())
    }

    fn count_series(&self, kind: SeriesKind, size: usize, reps: u64) -> Result<u64, String> {
        let args = [
            "bench",
            "series-run",
            kind.name(),
            &size.to_string(),
            "--reps",
        ];
        let mut args: Vec<String> = args.map(String::from).to_vec();
        args.push(reps.to_string());
        self.total(&args, &format!("{} {size}", kind.name()))
    }

    /// The runs side by side, one per available core (each run is one thread).
    fn count_batch(&self, runs: &[CountedRun]) -> Vec<Result<u64, String>> {
        let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
        let next = AtomicUsize::new(0);
        let results: Vec<Mutex<Option<Result<u64, String>>>> =
            runs.iter().map(|_| Mutex::new(None)).collect();
        std::thread::scope(|scope| {
            for _ in 0..workers.min(runs.len()) {
                scope.spawn(|| loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&run) = runs.get(i) else { break };
                    let count = self.count_run(run);
                    if let Ok(mut slot) = results[i].lock() {
                        *slot = Some(count);
                    }
                });
            }
        });
        let lost = || Err("a callgrind run was lost".to_string());
        results
            .into_iter()
            .map(|m| m.into_inner().ok().flatten().unwrap_or_else(lost))
            .collect()
    }
}
