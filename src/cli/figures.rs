//! `tensegrity figures --out DIR [--quick] [--only LIST] [--png] [--threads N]`: every figure
//! of the thesis the project computes, one file each (`fig_3_10.svg`, …), built in parallel
//! by [`tensegrity_figures::build_figures`] from the table [`tensegrity_figures::FIGURES`].
//! The directory, its `data/` (the sweeps' CSVs) and one figure sink per figure are opened
//! before any work; a figure that fails is reported and the others are still written, and the
//! command then exits non-zero naming the failed figures.

use super::output;
use super::request_args::usage;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_figures::{Built, FigureError, FigureSpec, FiguresRequest};
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
    /// Write PDF files (one page each, the figure's size or --size) instead of SVG.
    #[arg(long, conflicts_with = "png")]
    pub pdf: bool,
    /// Figures drawn at once (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
}

/// Runs `tensegrity figures`.
pub fn run(args: &FiguresArgs) -> Result<()> {
    let request = FiguresRequest {
        quick: args.quick,
        only: args.only.clone(),
        png: args.png,
        threads: args.threads.map(usize::from),
    };
    let chosen = request.selected().map_err(|e| match e {
        FigureError::InvalidParameter(p) => usage(p),
        e => e.into(),
    })?;
    let ext = if args.pdf { "pdf" } else { request.extension() };
    let options = args.figure.options()?;
    let dir = output::open_required("--out", &args.out, OutputDir::create)?;
    let data = output::open_required("--out", &dir.join("data"), OutputDir::create)?;
    // one sink per figure, before any work; a figure whose file cannot be opened fails alone
    let jobs = chosen
        .into_iter()
        .map(|f| {
            (
                f,
                FigureSink::open_with(&dir.join(f.file_name(ext)), options),
            )
        })
        .collect();
    let built = tensegrity_figures::build_figures(&request, data.path(), jobs, |f, sink, build| {
        let write = || {
            let sink = sink?;
            let path = sink.path().to_path_buf();
            sink.finish(&build()?)?;
            anyhow::Ok(path)
        };
        (f, write())
    });
    dir.keep();
    data.keep();
    report(ext, built)
}

/// Prints the files written, the failures and the warnings; fails naming the failed files.
fn report(ext: &str, built: Built<(&FigureSpec, Result<PathBuf>)>) -> Result<()> {
    let mut failed = Vec::new();
    for (f, outcome) in built.outcomes {
        match outcome {
            Ok(path) => println!(
                "wrote {}  (Fig. {}: {})",
                path.display(),
                f.number,
                f.description
            ),
            Err(e) => {
                eprintln!("Fig. {} failed: {e:#}", f.number);
                failed.push(f.file_name(ext));
            }
        }
    }
    for w in built.warnings {
        println!("warning: {w}");
    }
    if !failed.is_empty() {
        anyhow::bail!("{} figure(s) failed: {}", failed.len(), failed.join(", "));
    }
    Ok(())
}
