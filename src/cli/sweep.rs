//! `tensegrity sweep SPEC.toml --out results.csv [--threads N] [--shard K/N] [--resume]
//! [--quiet] [--units]` and `tensegrity sweep merge A.csv B.csv … --out all.csv`: parse the
//! flags, make one call into the sweeps crate ([`sweeps::run`], [`sweeps::merge`]) and draw
//! its progress (an indicatif bar with ETA on a terminal; nothing when stderr is piped or
//! with `--quiet`).

use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
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
    /// Worker threads (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
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
}

/// Subcommands of `tensegrity sweep`.
#[derive(clap::Subcommand, Debug)]
pub enum SweepCommand {
    /// Combine the files of the shards of one sweep into the single-run file.
    Merge(MergeArgs),
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
}

fn parse_shard(s: &str) -> Result<Shard, String> {
    s.parse().map_err(|e: sweeps::SweepError| e.to_string())
}

/// The progress bar (hidden when not on a terminal or when quiet).
struct Bar(ProgressBar);

impl sweeps::Progress for Bar {
    fn start(&mut self, total: usize, done: usize) {
        self.0.set_length(total as u64);
        self.0.set_position(done as u64);
        self.0.reset_eta();
    }

    fn row(&mut self, error: bool) {
        if error {
            self.0.set_message("(with error rows)");
        }
        self.0.inc(1);
    }

    fn finish(&mut self) {
        self.0.finish_and_clear();
    }
}

fn bar(quiet: bool) -> Bar {
    let target = if quiet || !std::io::stderr().is_terminal() {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let bar = ProgressBar::with_draw_target(Some(0), target);
    if let Ok(style) = ProgressStyle::with_template(
        "{elapsed_precise} [{wide_bar}] {pos}/{len} cases, ETA {eta_precise} {msg}",
    ) {
        bar.set_style(style);
    }
    Bar(bar)
}

/// Runs `tensegrity sweep`.
pub fn run(args: &SweepArgs) -> Result<()> {
    if let Some(SweepCommand::Merge(m)) = &args.command {
        return merge(m);
    }
    let (Some(spec_path), Some(out)) = (&args.spec, &args.out) else {
        anyhow::bail!("usage: tensegrity sweep SPEC.toml --out results.csv");
    };
    let spec = Spec::read(spec_path)?;
    let opts = RunOptions {
        threads: args.threads.map(usize::from),
        shard: args.shard.unwrap_or(Shard::ALL),
        resume: args.resume,
        units: args.units,
    };
    let summary = sweeps::run(&spec, out, &opts, &mut bar(args.quiet))
        .with_context(|| format!("sweep {}", spec_path.display()))?;
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

fn merge(args: &MergeArgs) -> Result<()> {
    let s = sweeps::merge(&args.inputs, &args.out)?;
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
