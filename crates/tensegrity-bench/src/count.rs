//! Instruction counts of `bench anchors` (callgrind: a count that does not depend on the
//! machine's load). An [`InstructionCounter`] runs whole processes ([`CountedRun`]: the
//! command line's binary in a hidden mode under `valgrind --tool=callgrind`) and returns their
//! total instructions I; differences of two such counts remove process start, reading and
//! setup:
//!
//! - an anchor, per step: (I(k steps) − I(1 step)) / (k − 1);
//! - a scaling series point of a single call (toroid, towers, Michell):
//!   I_call = I(setup + 1 call) − I(setup alone), the setup being what the timed point does
//!   before its clock starts (the request, the tower);
//! - a point of the rolling series, per step: I_step = (I(k) − I(1)) / (k − 1), k its steps
//!   (`instructions` = k · I_step, as `best_s` is the k steps' time).
//!
//! Each series then gets the least-squares power law I ≈ c · sᵖ of its instructions against
//! size ([`super::fit`]), beside the one of its times. A count that fails leaves the
//! instruction fields `null` and says why in the series' `instructions_note`.

use crate::anchors::Anchor;
use crate::fit::power_law;
use crate::series::{Series, SeriesKind};

/// One whole process an [`InstructionCounter`] counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CountedRun {
    /// `anchor` run for `steps` steps.
    Anchor {
        /// Which anchor.
        anchor: Anchor,
        /// Steps of the run.
        steps: u64,
    },
    /// A series point's input at `size`, then `reps` calls ([`super::series::run_counted`];
    /// the rolling series: one run of `reps` steps).
    Series {
        /// Which series.
        kind: SeriesKind,
        /// The size.
        size: usize,
        /// Calls (steps for the rolling series).
        reps: u64,
    },
}

/// Counts the instructions of whole runs (the command line: its own binary's hidden
/// `bench anchor-run` and `bench series-run` modes under callgrind).
pub trait InstructionCounter {
    /// Instructions of one whole process running `anchor` for `steps` steps, or why none.
    fn count(&self, anchor: Anchor, steps: u64) -> Result<u64, String>;

    /// Instructions of one whole process of [`super::series::run_counted`]`(kind, size, reps)`,
    /// or why none (by default: this counter counts anchors only).
    fn count_series(&self, kind: SeriesKind, size: usize, reps: u64) -> Result<u64, String> {
        let _ = (kind, size, reps);
        Err("this instruction counter counts the anchors only".into())
    }

    /// Every run of `runs`, in order (by default one after the other; a counter may run them
    /// side by side).
    fn count_batch(&self, runs: &[CountedRun]) -> Vec<Result<u64, String>> {
        runs.iter().map(|&run| self.count_run(run)).collect()
    }

    /// One run: [`InstructionCounter::count`] or [`InstructionCounter::count_series`].
    fn count_run(&self, run: CountedRun) -> Result<u64, String> {
        match run {
            CountedRun::Anchor { anchor, steps } => self.count(anchor, steps),
            CountedRun::Series { kind, size, reps } => self.count_series(kind, size, reps),
        }
    }
}

/// The two runs whose difference is a series point's instructions: (more, less, divisor).
fn pair(kind: SeriesKind, size: usize, steps: Option<u64>) -> (CountedRun, CountedRun, u64) {
    let run = |reps| CountedRun::Series { kind, size, reps };
    match steps {
        Some(k) => {
            let k = k.max(2);
            (run(k), run(1), k - 1)
        }
        None => (run(1), run(0), 1),
    }
}

/// Fills the instruction fields of every series (module docs): one batch of counts.
pub fn count_series(series: &mut [Series], counter: &dyn InstructionCounter, quick: bool) {
    let pairs: Vec<Vec<_>> = series
        .iter()
        .map(|s| {
            let steps = s.series.steps(quick);
            s.points
                .iter()
                .map(|p| pair(s.series, p.size, p.steps.or(steps)))
                .collect()
        })
        .collect();
    let runs: Vec<CountedRun> = pairs
        .iter()
        .flatten()
        .flat_map(|&(more, less, _)| [more, less])
        .collect();
    let mut counts = counter.count_batch(&runs).into_iter();
    for (s, pairs) in series.iter_mut().zip(pairs) {
        let mut failure = None;
        for (p, (_, _, divisor)) in s.points.iter_mut().zip(pairs) {
            let (more, less) = (counts.next(), counts.next());
            match (more, less) {
                (Some(Ok(more)), Some(Ok(less))) => {
                    let per = more.saturating_sub(less) as f64 / divisor as f64;
                    match p.steps {
                        Some(k) => {
                            p.instructions_per_step = Some(per);
                            p.instructions = Some(per * k as f64);
                        }
                        None => p.instructions = Some(per),
                    }
                }
                (Some(Err(why)), _) | (_, Some(Err(why))) => {
                    failure.get_or_insert(why);
                }
                _ => {
                    failure.get_or_insert_with(|| "the counter returned too few counts".into());
                }
            }
        }
        finish(s, failure);
    }
}

/// The instruction fit of a series, or the note of why its instructions are absent.
fn finish(s: &mut Series, failure: Option<String>) {
    if let Some(why) = failure {
        for p in &mut s.points {
            p.instructions = None;
            p.instructions_per_step = None;
        }
        s.instructions_note = Some(why);
        return;
    }
    let xy: Vec<(f64, f64)> = s
        .points
        .iter()
        .filter_map(|p| Some((p.size as f64, p.instructions_per_step.or(p.instructions)?)))
        .collect();
    s.instructions_fit = power_law(&xy);
}

/// Leaves the instruction fields of every series empty, with `note` saying why.
pub fn not_counted(series: &mut [Series], note: &str) {
    for s in series {
        s.instructions_note = Some(note.to_string());
    }
}
