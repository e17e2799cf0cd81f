//! The parallel driver of the figure table: [`build_figures`] builds the chosen figures on
//! worker threads, each from its builder's library calls, and hands each figure, as soon as
//! it is built, to the front end's `deliver` — which finishes the figure's sink, opened
//! before any work. Figures are built, never written here: only the sweeps behind Figs.
//! 3.13 and 4.18 write their CSVs, into the [`Context`]'s data directory (the sweeps crate
//! streams them under its own lock).
//!
//! A figure that fails (or whose code panics) is one failed outcome; the others are still
//! built. Figures drawn from a model used outside its assumptions are built with a note in
//! their title and a [`Warning`] returned beside the outcomes.

use crate::catalog::{FigureSpec, FiguresRequest};
pub use crate::context::Context;
use crate::data::Drawn;
use crate::error::{FigureError, Result};
pub use crate::warning::Warning;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// The outcomes of [`build_figures`], in the order of the jobs, and the warnings.
#[derive(Debug)]
pub struct Built<R> {
    /// What `deliver` returned for each job.
    pub outcomes: Vec<R>,
    /// Figures drawn from a model used outside its assumptions.
    pub warnings: Vec<Warning>,
}

/// Builds the figures of `jobs` on the request's workers ([`FiguresRequest::workers`]),
/// the sweeps' CSVs in `data`. For each job, on a worker thread, `deliver` gets the figure's
/// entry, the job's own value (the front end's opened sink) and the figure's builder, which
/// it calls to build the figure (a panic of the figure's code becomes
/// [`FigureError::Panicked`]); a job whose sink did not open need not build anything.
///
/// ```
/// use tensegrity_figures::{build_figures, FiguresRequest};
/// let request = FiguresRequest { quick: true, only: vec!["5.1".into(), "4.2".into()], ..Default::default() };
/// let jobs = request.selected()?.into_iter().map(|f| (f, f.file_name("svg"))).collect();
/// let data = std::env::temp_dir();
/// let built = build_figures(&request, &data, jobs, |_, name, build| {
///     build().map(|drawn| (name, drawn.figure.panels.len()))
/// });
/// let outcomes: Vec<_> = built.outcomes.into_iter().collect::<Result<_, _>>()?;
/// assert_eq!(outcomes, [("fig_4_2.svg".to_string(), 1), ("fig_5_1.svg".to_string(), 2)]);
/// # Ok::<(), tensegrity_figures::FigureError>(())
/// ```
pub fn build_figures<T: Send, R: Send>(
    request: &FiguresRequest,
    data: &Path,
    jobs: Vec<(&'static FigureSpec, T)>,
    deliver: impl Fn(&'static FigureSpec, T, &dyn Fn() -> Result<Drawn>) -> R + Sync,
) -> Built<R> {
    let ctx = Context::new(request.quick, data);
    let count = jobs.len();
    let next = AtomicUsize::new(0);
    let jobs: Mutex<Vec<Option<(&'static FigureSpec, T)>>> =
        Mutex::new(jobs.into_iter().map(Some).collect());
    let slots: Mutex<Vec<Option<R>>> = Mutex::new((0..count).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..request.workers().min(count.max(1)) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= count {
                    break;
                }
                let job = jobs.lock().unwrap_or_else(|e| e.into_inner())[k].take();
                let Some((spec, value)) = job else { break };
                let build = || {
                    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| spec.build(&ctx)))
                        .unwrap_or(Err(FigureError::Panicked))
                };
                let outcome = deliver(spec, value, &build);
                slots.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(outcome);
            });
        }
    });
    let outcomes = slots
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .map(|o| o.expect("every job is taken by one worker"))
        .collect();
    Built {
        outcomes,
        warnings: ctx.into_warnings(),
    }
}
