//! `tensegrity sweep SPEC.toml --out results.csv [--threads N [--oversubscribe]] [--shard K/N]
//! [--resume] [--quiet] [--units]`, `tensegrity sweep merge A.csv B.csv … --out all.csv` and
//! `tensegrity sweep plot RESULTS.csv --x COL --y COL [--group COL] [--where COL=VALUE]…
//! [--log-x] [--log-y] [--title T] [--xlabel T] [--ylabel T] --out fig.svg`: parse the
//! flags, make one call into the sweeps crate ([`sweeps::run`], [`sweeps::merge`]) and draw
//! its progress ([`tensegrity_io::progress`]: a bar with ETA on a terminal, a line with
//! percent and ETA every few seconds when stderr is a file or a pipe; nothing with `--quiet`).
//! The spec is read under the limits ([`Spec::read_within`]: its axes sized before their
//! values are made, a refusal naming the axis and the flag that raises the limit), and
//! `--threads` above the machine's cores is capped at them unless `--oversubscribe`, with a
//! note on stderr ([`sweeps::Threads`]).

use anyhow::{Context, Result};
use std::path::PathBuf;
use sweeps::{RunOptions, Shard, Spec};

/// Arguments of `tensegrity sweep`.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    /// `merge`: combine shard files.
    #[command(subcommand)]
    pub command: Option<SweepCommand>,
    /// The sweep spec (TOML: study, [fixed], [axes], [derived], [output]).
    #[arg(value_name = "SPEC.toml", required = true)]
    pub spec: Option<PathBuf>,
    /// Output CSV; rows are appended to it as the cases finish, in case order.
    #[arg(long, value_name = "FILE", required = true)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: one per core; more than the cores only with --oversubscribe).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Run the --threads asked for even when they are more than the machine's cores (else
    /// they are capped at the cores, with a note on stderr).
    #[arg(long, requires = "threads")]
    pub oversubscribe: bool,
    /// Run only the cases with id ≡ K−1 (mod N); combine the files with `sweep merge`.
    #[arg(long, value_name = "K/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Continue the rows already in --out (after an interruption) instead of starting anew.
    #[arg(long)]
    pub resume: bool,
    /// No progress bar and no summary.
    #[arg(long)]
    pub quiet: bool,
    /// Write a `# units: …` comment line before the header.
    #[arg(long)]
    pub units: bool,
    /// Print the summary (cases, rows written, resumed, error rows, file) as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Subcommands of `tensegrity sweep`.
#[derive(clap::Subcommand, Debug)]
pub enum SweepCommand {
    /// Combine the files of the shards of one sweep into the single-run file.
    Merge(MergeArgs),
    /// Plot one result column against another, one curve per value of a group column.
    Plot(Box<PlotArgs>),
}

/// Arguments of `tensegrity sweep plot`.
#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// The results (a sweep's CSV; error rows are left out).
    #[arg(value_name = "RESULTS.csv")]
    pub results: PathBuf,
    /// Column on the x axis.
    #[arg(long, value_name = "COL")]
    pub x: String,
    /// Column on the y axis.
    #[arg(long, value_name = "COL")]
    pub y: String,
    /// One curve per value of this column.
    #[arg(long, value_name = "COL")]
    pub group: Option<String>,
    /// Only the rows whose column COL holds exactly VALUE (as written in the file); repeat
    /// for several columns.
    #[arg(long = "where", value_name = "COL=VALUE", value_parser = parse_where)]
    pub filter: Vec<(String, String)>,
    /// Logarithmic x axis.
    #[arg(long)]
    pub log_x: bool,
    /// Logarithmic y axis.
    #[arg(long)]
    pub log_y: bool,
    /// The title (default: the file name); drawn as written, math only between `$` pairs
    /// (`$F_f/F_e$`).
    #[arg(long, value_name = "TEXT")]
    pub title: Option<String>,
    /// The x-axis label (default: the x column, with `[deg]` for angles); text as for --title.
    #[arg(long, value_name = "TEXT")]
    pub xlabel: Option<String>,
    /// The y-axis label (default: the y column, with `[deg]` for angles); text as for --title.
    #[arg(long, value_name = "TEXT")]
    pub ylabel: Option<String>,
    /// The figure: SVG, PNG or PDF by the extension.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Print what was plotted as JSON (columns, curves, points).
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// `tensegrity sweep plot`: [`tensegrity_figures::sweep_plot`] into the figure sink.
fn plot(args: &PlotArgs) -> Result<()> {
    let sink = args.figure.open_required("--out", &args.out)?;
    let (figure, report) = tensegrity_figures::sweep_plot::SweepPlot {
        results: args.results.clone(),
        x: args.x.clone(),
        y: args.y.clone(),
        group: args.group.clone(),
        filter: args.filter.clone(),
        log_x: args.log_x,
        log_y: args.log_y,
        title: args.title.clone(),
        x_label: args.xlabel.clone(),
        y_label: args.ylabel.clone(),
    }
    .build()?;
    sink.finish(&figure)?;
    if args.json {
        super::output::print_json(&report)?;
    } else {
        println!("wrote {}", args.out.display());
    }
    Ok(())
}

/// Arguments of `tensegrity sweep merge`.
#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// The shard files.
    #[arg(value_name = "FILE.csv", required = true, num_args = 1..)]
    pub inputs: Vec<PathBuf>,
    /// The merged file.
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// No summary.
    #[arg(long)]
    pub quiet: bool,
    /// Print the summary (rows, files, output) as JSON.
    #[arg(long)]
    pub json: bool,
}

fn parse_where(s: &str) -> Result<(String, String), String> {
    s.split_once('=')
        .map(|(c, v)| (c.trim().to_string(), v.to_string()))
        .filter(|(c, _)| !c.is_empty())
        .ok_or_else(|| format!("expected COL=VALUE, got `{s}`"))
}

fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse().map_err(|e: sweeps::SweepError| e.to_string())
}

/// Runs `tensegrity sweep`.
pub fn run(args: &SweepArgs) -> Result<()> {
    match &args.command {
        Some(SweepCommand::Merge(m)) => return merge(m),
        Some(SweepCommand::Plot(p)) => return plot(p),
        None => {}
    }
    let (Some(spec_path), Some(out)) = (&args.spec, &args.out) else {
        anyhow::bail!("usage: tensegrity sweep SPEC.toml --out results.csv");
    };
    let spec = read_spec(spec_path)?;
    let threads = sweeps::Threads::choose(args.threads.map(usize::from), args.oversubscribe);
    if threads.capped() {
        eprintln!(
            "note: --threads {} capped at the {} cores of this machine (--oversubscribe runs more threads than cores)",
            threads.requested.unwrap_or_default(),
            threads.cores
        );
    }
    let progress = super::guard::sweep(spec.case_count()?, args.quiet)?;
    // the workers stop at a signal; the file keeps its rows, marked incomplete (exit 130)
    let _polled = tensegrity_io::interrupt::polled();
    let opts = RunOptions {
        threads: Some(threads.used),
        shard: args.shard.unwrap_or(Shard::ALL),
        resume: args.resume,
        units: args.units,
        limits: Some(super::guard::limits()),
    };
    let summary = sweeps::run(&spec, out, &opts, &mut progress.handle())
        .with_context(|| format!("sweep {}", spec_path.display()))?;
    if args.json {
        return super::output::print_json(&serde_json::json!({
            "total_cases": summary.total_cases, "shard_cases": summary.shard_cases,
            "written": summary.written, "resumed": summary.resumed, "errors": summary.errors,
            "threads": threads.used, "out": out.display().to_string()}));
    }
    if !args.quiet {
        println!(
            "{} of {} cases in {} ({} written now, {} already there; {} error rows)",
            summary.resumed + summary.written,
            summary.shard_cases,
            out.display(),
            summary.written,
            summary.resumed,
            summary.errors
        );
    }
    Ok(())
}

/// The spec under the limits of this process: an axis whose values, or a product whose
/// CSV, is estimated over a limit is refused before the values are made, by the guard (the
/// flag that raises the limit, exit code 2).
fn read_spec(path: &std::path::Path) -> Result<Spec> {
    match Spec::read_within(path, &super::guard::limits()) {
        Err(sweeps::SweepError::OverBudget { over }) => {
            // the same estimate against the same limits: the guard's refusal names the flag
            let refused = super::guard::check(over.estimate.clone()).err();
            let e = refused.unwrap_or_else(|| sweeps::SweepError::OverBudget { over }.into());
            Err(e.context(format!("sweep {}", path.display())))
        }
        other => Ok(other?),
    }
}

fn merge(args: &MergeArgs) -> Result<()> {
    let s = sweeps::merge(&args.inputs, &args.out)?;
    if args.json {
        let out = args.out.display().to_string();
        return super::output::print_json(
            &serde_json::json!({"rows": s.rows, "files": s.files, "out": out}),
        );
    }
    if !args.quiet {
        println!(
            "merged {} rows from {} files into {}",
            s.rows,
            s.files,
            args.out.display()
        );
    }
    Ok(())
}
