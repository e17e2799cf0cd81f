//! `tensegrity figures --out DIR [--quick] [--only LIST] [--png] [--threads N]`: regenerates every
//! figure of the thesis the project computes, one SVG each (`fig_3_10.svg`, …), in parallel.
//!
//! Each figure is one library call (or one sweep) and one drawing through the io crate's
//! figure module: the structure drawings (Figs. 3.3, 3.9, 4.2, 4.4, 4.6–4.12, 4.19, 5.1–5.3)
//! project the members of the library's structures; the studies are the sweeps crate's —
//! Fig. 3.13 a `tipover` sweep and Fig. 4.18 two `michell` sweeps (their CSVs are kept under
//! `DIR/data/`), Figs. 4.14–4.16 [`sweeps::grids::sign_maps`] — and the rolling figures
//! (3.8, 3.10, 3.11) [`toroid::roll`] and [`toroid::rolling_series`] with the default
//! request. `--quick` uses coarser grids and shorter runs on the reduced rigid rolling model
//! (a smoke test in seconds). A figure that fails is reported and the others are still
//! written; the command then exits non-zero naming the failed figures.

mod draw;
mod michell;
mod tbar;
mod wheel;

use super::output;
use anyhow::{Context, Result};
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use sweeps::{RunOptions, Silent, Spec};
use tensegrity_io::figure::Figure;
use tensegrity_io::sink::{FigureSink, OutputDir};

/// Arguments of `tensegrity figures`.
#[derive(clap::Args, Debug)]
pub struct FiguresArgs {
    /// Output directory (created if missing; its parent must exist); the sweeps' CSVs go to
    /// DIR/data/.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Coarser grids and shorter runs (reduced rigid rolling model) for a quick check.
    #[arg(long)]
    pub quick: bool,
    /// Only these figures, e.g. `3.10,4.18` (default: all).
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    pub only: Vec<String>,
    /// Write PNG images (embedded font, no system library) instead of SVG.
    #[arg(long)]
    pub png: bool,
    /// Figures drawn at once (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
}

/// What every figure's builder gets.
pub struct Ctx {
    /// `--quick`.
    pub quick: bool,
    /// Where the sweeps write their CSVs.
    pub data: PathBuf,
    /// The figures' file extension, `svg` or `png`.
    pub ext: &'static str,
    /// The rolling runs shared by Figs. 3.10 and 3.11 (computed once).
    pub rolling: std::sync::OnceLock<std::result::Result<Vec<toroid::RollReport>, String>>,
    /// Warnings of figures drawn from a model used outside its assumptions.
    pub warnings: Mutex<Vec<String>>,
}

impl Ctx {
    /// Records a warning for figure `number`, printed with the list of files.
    pub fn warn(&self, number: &str, message: String) {
        let mut w = self.warnings.lock().unwrap_or_else(|e| e.into_inner());
        w.push(format!("warning: Fig. {number}: {message}"));
    }

    /// Runs the sweep `spec` (TOML text) to `data/NAME.csv` and reads columns `x` and `y`
    /// back as curves, one per value of `group` (`""`: one curve).
    pub fn sweep(
        &self,
        name: &str,
        spec: &str,
        x: &str,
        y: &str,
        group: &str,
    ) -> Result<Vec<tensegrity_io::csv::Curve>> {
        let spec = Spec::parse(spec).with_context(|| format!("the sweep spec of {name}"))?;
        let path = self.data.join(format!("{name}.csv"));
        let opts = RunOptions {
            threads: Some(1),
            ..RunOptions::default()
        };
        let summary = sweeps::run(&spec, &path, &opts, &mut Silent)?;
        if summary.errors > 0 {
            anyhow::bail!(
                "{} of {} cases of {} are error rows",
                summary.errors,
                summary.written,
                path.display()
            );
        }
        let group = (!group.is_empty()).then_some(group);
        Ok(tensegrity_io::csv::read_series(&path, x, y, group)?)
    }
}

type Builder = fn(&Ctx) -> Result<Figure>;

/// Every figure: number, what it shows, its builder.
pub const FIGURES: [(&str, &str, Builder); 24] = [
    (
        "3.3",
        "toroid stabilising options (1,2), (1,3), (2,3)",
        wheel::fig_3_3,
    ),
    ("3.8", "n = 8 wheel rolling, three instants", wheel::fig_3_8),
    ("3.9", "wheels of complexity 6, 24, 100", wheel::fig_3_9),
    (
        "3.10",
        "axle height of n = 8, 12, 16, 24 wheels on 50°",
        wheel::fig_3_10,
    ),
    (
        "3.11",
        "contact reaction of n = 8, 16 wheels",
        wheel::fig_3_11,
    ),
    (
        "3.13",
        "F_f/F_e against σ and ε (tipover sweep)",
        wheel::fig_3_13,
    ),
    ("4.2", "planar Michell spirals, q = 1…4", michell::fig_4_2),
    ("4.4", "planar q = 4: force regions", michell::fig_4_4),
    (
        "4.6",
        "cylindrical q = 4, δ = 0.25: side and top",
        michell::fig_4_6,
    ),
    (
        "4.7",
        "cylindrical q = 4, δ = 0.25: isometric",
        michell::fig_4_7,
    ),
    ("4.8", "spherical q = 1, ε = π/12", michell::fig_4_8),
    ("4.9", "spherical q = 2, ε = π/12: x–y", michell::fig_4_9),
    (
        "4.10",
        "spherical q = 2, ε = π/12: isometric",
        michell::fig_4_10,
    ),
    (
        "4.11",
        "spherical q = 4, ε = π/12: y–z and x–y",
        michell::fig_4_11,
    ),
    (
        "4.12",
        "spherical q = 4, ε = π/12: isometric",
        michell::fig_4_12,
    ),
    ("4.14", "sign map of λ1010", michell::fig_4_14),
    ("4.15", "sign map of λ1001", michell::fig_4_15),
    ("4.16", "sign map of λ0100", michell::fig_4_16),
    (
        "4.18",
        "mass against complexity (michell sweeps)",
        michell::fig_4_18,
    ),
    ("4.19", "extra strings, q = 2 and 3", michell::fig_4_19),
    (
        "4.20",
        "member forces over γ, low and high prestress",
        michell::fig_4_20,
    ),
    ("5.1", "T-bar tread", tbar::fig_5_1),
    ("5.2", "T-bar wheel", tbar::fig_5_2),
    ("5.3", "extended T-bar wheel", tbar::fig_5_3),
];

/// `fig_3_10.svg` for `3.10` (`ext` = `svg` or `png`).
pub fn file_name(number: &str, ext: &str) -> String {
    format!("fig_{}.{ext}", number.replace('.', "_"))
}

/// Builds one figure and writes it into its sink (opened before any work).
fn make(ctx: &Ctx, sink: FigureSink, build: Builder) -> Result<PathBuf> {
    let figure = build(ctx)?;
    let path = sink.path().to_path_buf();
    sink.finish(&figure)?;
    Ok(path)
}

/// The directory and its `data/` (a bad `--out` fails here), and one figure sink per chosen
/// figure, all opened before any work; a figure whose file cannot be opened fails alone.
fn open_outputs(args: &FiguresArgs, chosen: &[usize], ext: &str) -> Result<Outputs> {
    let dir = output::open_required("--out", &args.out, OutputDir::create)?;
    let data = output::open_required("--out", &dir.join("data"), OutputDir::create)?;
    let sinks = chosen
        .iter()
        .map(|&i| Ok(FigureSink::open(&dir.join(file_name(FIGURES[i].0, ext)))?))
        .collect();
    Ok((dir, data, sinks))
}

type Outputs = (OutputDir, OutputDir, Vec<Result<FigureSink>>);

/// The figures `--only` selects, checked against the list.
fn selected(args: &FiguresArgs) -> Result<Vec<usize>> {
    if args.only.is_empty() {
        return Ok((0..FIGURES.len()).collect());
    }
    let mut chosen = args
        .only
        .iter()
        .map(|n| {
            let n = n.trim().trim_start_matches("fig_").replace('_', ".");
            FIGURES.iter().position(|f| f.0 == n).ok_or_else(|| {
                let all: Vec<&str> = FIGURES.iter().map(|f| f.0).collect();
                anyhow::anyhow!("--only: no figure {n} (known: {})", all.join(", "))
            })
        })
        .collect::<Result<Vec<_>>>()?;
    // one sink per file: a figure named twice is drawn once
    chosen.sort_unstable();
    chosen.dedup();
    Ok(chosen)
}

/// Runs `tensegrity figures`.
pub fn run(args: &FiguresArgs) -> Result<()> {
    let chosen = selected(args)?;
    let ext = if args.png { "png" } else { "svg" };
    let (dir, data, sinks) = open_outputs(args, &chosen, ext)?;
    let ctx = Ctx {
        quick: args.quick,
        data: data.path().to_path_buf(),
        ext,
        rolling: std::sync::OnceLock::new(),
        warnings: Mutex::new(Vec::new()),
    };
    let threads = args.threads.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        usize::from,
    );
    let outcomes = build_all(&ctx, sinks, &chosen, threads);
    dir.keep();
    data.keep();
    let mut failed = Vec::new();
    for (&i, outcome) in chosen.iter().zip(outcomes) {
        let (number, caption, _) = FIGURES[i];
        match outcome {
            Ok(path) => println!("wrote {}  (Fig. {number}: {caption})", path.display()),
            Err(e) => {
                eprintln!("Fig. {number} failed: {e:#}");
                failed.push(file_name(number, ctx.ext));
            }
        }
    }
    let warnings = ctx.warnings.into_inner().unwrap_or_else(|e| e.into_inner());
    for w in warnings {
        println!("{w}");
    }
    if !failed.is_empty() {
        anyhow::bail!("{} figure(s) failed: {}", failed.len(), failed.join(", "));
    }
    Ok(())
}

/// Builds the `chosen` figures on `threads` workers; outcomes in the order of `chosen`.
fn build_all(
    ctx: &Ctx,
    sinks: Vec<Result<FigureSink>>,
    chosen: &[usize],
    threads: usize,
) -> Vec<Result<PathBuf>> {
    let next = AtomicUsize::new(0);
    let sinks: Mutex<Vec<Option<Result<FigureSink>>>> =
        Mutex::new(sinks.into_iter().map(Some).collect());
    let slots: Mutex<Vec<Option<Result<PathBuf>>>> =
        Mutex::new((0..chosen.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.clamp(1, chosen.len().max(1)) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = chosen.get(k) else { break };
                let (_, _, build) = FIGURES[i];
                let sink = sinks.lock().unwrap_or_else(|e| e.into_inner())[k].take();
                let outcome = match sink {
                    Some(Ok(sink)) => std::panic::catch_unwind(|| make(ctx, sink, build))
                        .unwrap_or_else(|_| Err(anyhow::anyhow!("the figure's code panicked"))),
                    Some(Err(e)) => Err(e),
                    None => break,
                };
                slots.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(outcome);
            });
        }
    });
    slots
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .map(|o| o.unwrap_or_else(|| Err(anyhow::anyhow!("not built"))))
        .collect()
}
