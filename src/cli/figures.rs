//! `tensegrity figures --out DIR [--quick] [--only LIST] [--png] [--threads N]`: every figure
//! of the thesis the project computes, one file each (`fig_3_10.svg`, …), built in parallel
//! by [`tensegrity_figures::build_figures`] from the table [`tensegrity_figures::FIGURES`].
//! The directory, its `data/` (the sweeps' CSVs) and one figure sink per figure — and one for
//! its data, `fig_3_10.csv` — are opened before any work; a figure that fails is reported and
//! the others are still written, and the command then exits non-zero naming the failed
//! figures. The chosen figures' work is estimated first
//! ([`tensegrity_figures::estimate::figures`]) and refused above `--max-work`, naming
//! `--only`. `index.json` and `index.md` list every figure: caption, files, the command that
//! reproduces it and what differs from the thesis.

use super::output;
use super::request_args::usage;
use anyhow::Result;
use serde_json::json;
use std::path::PathBuf;
use tensegrity_figures::{Built, FigureError, FigureIndex, FigureSpec, FiguresRequest, IndexEntry};
use tensegrity_io::figure::RenderOptions;
use tensegrity_io::progress::Measure;
use tensegrity_io::sink::{CsvSink, FigureSink, FileSink, JsonSink, OutputDir};

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
    /// Print the figures written, failed and warned about as JSON.
    #[arg(long)]
    pub json: bool,
    /// No progress report on stderr.
    #[arg(long)]
    pub quiet: bool,
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
    let (chosen, options) = chosen(args, &request)?;
    // the work of every chosen figure against --max-work, before any directory is made
    let estimate = tensegrity_figures::estimate::figures(&request, &chosen);
    let measure = Measure::Count {
        total: chosen.len(),
        unit: "figures",
    };
    let guarded = super::guard::counted(estimate, "figures", measure, !args.quiet)?;
    let ext = if args.pdf { "pdf" } else { request.extension() };
    let dir = output::open_required("--out", &args.out, OutputDir::create)?;
    let data = output::open_required("--out", &dir.join("data"), OutputDir::create)?;
    let index_sinks = (
        output::open_required("--out", &dir.join("index.json"), JsonSink::open)?,
        output::open_required("--out", &dir.join("index.md"), FileSink::open)?,
    );
    let progress = guarded.handle();
    // two sinks per figure (picture, data), before any work; a figure whose files cannot be
    // opened fails alone
    let jobs = chosen
        .into_iter()
        .map(|f| (f, figure_sinks(dir.path(), f, ext, options)))
        .collect();
    let built =
        tensegrity_figures::build_figures(&request, data.path(), jobs, |f, sinks, build| {
            let write = || {
                let (sink, data_sink) = sinks?;
                let path = sink.path().to_path_buf();
                let drawn = build()?;
                sink.finish(&drawn.figure)?;
                drawn.data.write(data_sink)?;
                anyhow::Ok(path)
            };
            let written = write();
            progress.inc(1.0);
            (f, written)
        });
    progress.finish();
    dir.keep();
    data.keep();
    let index = index_of(args, ext, &built);
    index_sinks.0.finish(&index)?;
    index_sinks.1.finish_with(index.to_markdown())?;
    match args.json {
        true => report_json(ext, built),
        false => report(ext, built),
    }
}

/// The figures chosen and the render options, checked against every one of them before any
/// is computed ([`tensegrity_figures::page::check_options`]); a bad `--only`, `--size` or
/// `--dpi` is a usage error naming the flag.
fn chosen(
    args: &FiguresArgs,
    request: &FiguresRequest,
) -> Result<(Vec<&'static FigureSpec>, RenderOptions)> {
    let bad = |e| match e {
        FigureError::InvalidParameter(p) => usage(p),
        e => e.into(),
    };
    let chosen = request.selected().map_err(bad)?;
    let options = args.figure.options()?;
    tensegrity_figures::page::check_options(&chosen, &options, args.png).map_err(bad)?;
    Ok((chosen, options))
}

/// The picture's and the data's sinks of one figure.
fn figure_sinks(
    dir: &std::path::Path,
    f: &FigureSpec,
    ext: &str,
    options: RenderOptions,
) -> tensegrity_io::Result<(FigureSink, CsvSink)> {
    let picture = FigureSink::open_with(&dir.join(f.file_name(ext)), options)?;
    let data = CsvSink::open_records(&dir.join(f.file_name("csv")), "figure data")?;
    Ok((picture, data))
}

/// [`report`] as one JSON object: `figures` (number, description, file, data), `failed`
/// (number, file, error), `warnings` (figure, message).
fn report_json(ext: &str, built: Built<(&FigureSpec, Result<PathBuf>)>) -> Result<()> {
    let (mut figures, mut failed) = (Vec::new(), Vec::new());
    for (f, outcome) in built.outcomes {
        let (number, description) = (f.number, f.description);
        match outcome {
            Ok(p) => figures.push(json!({"number": number, "description": description,
                "file": p.display().to_string(),
                "data": p.with_extension("csv").display().to_string()})),
            Err(e) => failed.push(json!({"number": number, "file": f.file_name(ext),
                "error": format!("{e:#}")})),
        }
    }
    let warnings: Vec<_> = built
        .warnings
        .iter()
        .map(|w| {
            let mut v = serde_json::to_value(&w.warning).unwrap_or_default();
            v["figure"] = json!(w.figure);
            v
        })
        .collect();
    let n = failed.len();
    let report = json!({"figures": figures, "failed": failed, "warnings": warnings});
    super::output::print_json(&report)?;
    match n {
        0 => Ok(()),
        n => anyhow::bail!("{n} figure(s) failed"),
    }
}

/// The index of the run: every figure, its files and the command that reproduces it.
fn index_of(
    args: &FiguresArgs,
    ext: &str,
    built: &Built<(&FigureSpec, Result<PathBuf>)>,
) -> FigureIndex {
    let figures = built
        .outcomes
        .iter()
        .map(|(f, outcome)| {
            let mut command = format!(
                "tensegrity figures --out {} --only {}",
                args.out.display(),
                f.number
            );
            for (on, flag) in [
                (args.quick, " --quick"),
                (args.png, " --png"),
                (args.pdf, " --pdf"),
            ] {
                if on {
                    command.push_str(flag);
                }
            }
            let files = vec![f.file_name(ext), f.file_name("csv")];
            let error = outcome.as_ref().err().map(|e| format!("{e:#}"));
            let mut entry = IndexEntry::new(f, files, command, error);
            entry.warnings = built
                .warnings
                .iter()
                .filter(|w| w.figure == f.number)
                .map(|w| w.warning.clone())
                .collect();
            entry
        })
        .collect();
    FigureIndex {
        quick: args.quick,
        figures,
    }
}

/// Prints the files written, the failures and the warnings; fails naming the failed files.
fn report(ext: &str, built: Built<(&FigureSpec, Result<PathBuf>)>) -> Result<()> {
    let mut failed = Vec::new();
    for (f, outcome) in built.outcomes {
        match outcome {
            Ok(path) => println!(
                "wrote {} and its data {}  (Fig. {}: {})",
                path.display(),
                f.file_name("csv"),
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
