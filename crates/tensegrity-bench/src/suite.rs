//! `bench anchors`: the anchor scenes ([`Anchor`]) and the scaling series ([`SeriesKind`])
//! measured in one run ([`AnchorsRequest`] → [`bench_anchors`] → [`AnchorsReport`]).
//!
//! Per anchor: the best wall time of the integration alone over `repeats` runs (as
//! `simulate`'s `wall_time_s`: the monitors included, the scene's reading and setup not),
//! per step, the final nodes and their distance to the independent reference, the reference
//! code's time and the ratio to it (labelled: measured on that machine, [`MEASURED_ON`]); with
//! `instructions` and an [`InstructionCounter`] (the command line's: the binary itself under
//! callgrind), the instructions per step: (I(k) − I(1)) / (k − 1) from two whole-process
//! counts of k and 1 steps, so that process start, reading and setup cancel; and the
//! instructions of every scaling series point with their own fitted exponent
//! ([`super::count`]).

use crate::anchors::{Anchor, ReferenceTime, MEASURED_ON};
use crate::count;
pub use crate::count::{CountedRun, InstructionCounter};
use crate::series::{self, Series, SeriesKind};
use crate::BenchError;
use serde::{Deserialize, Serialize};
use tensegrity_core::request::Request;
use tensegrity_derive::Params;

/// The note of a report without an instruction counter.
const NO_COUNTER: &str = "no instruction counter (valgrind) available";

/// Repeats per measurement by default (the best is kept).
pub const DEFAULT_REPEATS: usize = 5;

/// Steps of the instruction counts when `quick` (the scene's own steps otherwise).
pub const QUICK_COUNT_STEPS: u64 = 200;

/// The benchmark, as data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct AnchorsRequest {
    /// The small size set of every series (for a smoke test); the anchors run whole.
    #[param(
        flag,
        help = "The small size set of every scaling series (a smoke test); the anchors run whole"
    )]
    pub quick: bool,
    /// Runs per measurement; the best is reported.
    #[param(count, help = "Runs per measurement (the best is reported)", rule = AtLeast(1.0))]
    pub repeats: usize,
    /// Count instructions (per anchor step, per series point) where a counter is available
    /// (callgrind).
    #[param(
        flag,
        help = "Count instructions (per step of each anchor, per point of each scaling series) under callgrind when valgrind is installed"
    )]
    pub instructions: bool,
}

impl Default for AnchorsRequest {
    /// The full size sets, [`DEFAULT_REPEATS`], instructions counted.
    fn default() -> Self {
        Self {
            quick: false,
            repeats: DEFAULT_REPEATS,
            instructions: true,
        }
    }
}

impl Request for AnchorsRequest {
    const NAME: &'static str = "bench_anchors";
}

/// One anchor's measurement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AnchorResult {
    /// Which anchor.
    pub anchor: Anchor,
    /// Its scene file.
    pub scene: String,
    /// RK4 steps of the run.
    pub steps: u64,
    /// Best wall time of the integration over the repeats (s).
    pub best_s: f64,
    /// `best_s` per step (s).
    pub per_step_s: f64,
    /// Instructions per step (callgrind), when counted.
    pub instructions_per_step: Option<f64>,
    /// Final node positions (m).
    pub final_nodes: Vec<[f64; 3]>,
    /// Largest coordinate difference to the independent reference's final nodes (m).
    pub final_error_m: f64,
    /// What that difference may be: the RK4 error at the scene's step (m).
    pub final_tolerance_m: f64,
    /// The reference code and its stored time, with when and where it was measured.
    pub reference: ReferenceTime,
    /// The reference time over `best_s`, only for a reference measured in the same run:
    /// never for the stored times ([`crate::anchors::MEASURED_ON`]), so always absent
    /// (`null`) today.
    pub ratio: Option<f64>,
}

/// What `bench anchors` measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AnchorsReport {
    /// The request.
    pub request: AnchorsRequest,
    /// The anchors.
    pub anchors: Vec<AnchorResult>,
    /// The label of every reference time.
    pub reference_note: &'static str,
    /// Why instructions were not counted (absent when they were, or not asked for).
    pub instructions_note: Option<String>,
    /// The scaling series.
    pub series: Vec<Series>,
}

/// One CSV row: an anchor, or a point of a series (`exponent`: the series' fit).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BenchRow {
    /// `anchor` or `series`.
    pub group: &'static str,
    /// The anchor's or the series' name.
    pub name: &'static str,
    /// The series' size (empty for an anchor).
    pub size: Option<usize>,
    /// Members, where known.
    pub members: Option<usize>,
    /// Steps of a time integration.
    pub steps: Option<u64>,
    /// Best time (s).
    pub best_s: f64,
    /// Best time per step (s).
    pub per_step_s: Option<f64>,
    /// Instructions per step (callgrind).
    pub instructions_per_step: Option<f64>,
    /// Reference code (anchors).
    pub reference_code: Option<&'static str>,
    /// Its stored time (s), measured on [`crate::anchors::REFERENCE_MEASURED`].
    pub reference_s: Option<f64>,
    /// Reference time over ours, for a reference measured in the same run (none today).
    pub ratio: Option<f64>,
    /// The series' fitted cost exponent.
    pub exponent: Option<f64>,
    /// Instructions of the series point's call (callgrind; start-up and setup removed).
    pub instructions: Option<f64>,
    /// The exponent fitted to the series' instructions.
    pub instructions_exponent: Option<f64>,
}

impl AnchorsReport {
    /// The report as CSV rows: the anchors, then every point of every series.
    pub fn rows(&self) -> Vec<BenchRow> {
        let anchors = self.anchors.iter().map(|a| BenchRow {
            group: "anchor",
            name: a.anchor.name(),
            size: None,
            members: None,
            steps: Some(a.steps),
            best_s: a.best_s,
            per_step_s: Some(a.per_step_s),
            instructions_per_step: a.instructions_per_step,
            reference_code: Some(a.reference.code),
            reference_s: Some(a.reference.seconds),
            ratio: a.ratio,
            exponent: None,
            instructions: None,
            instructions_exponent: None,
        });
        let points = self.series.iter().flat_map(|s| {
            s.points.iter().map(|p| BenchRow {
                group: "series",
                name: s.series.name(),
                size: Some(p.size),
                members: p.members,
                steps: p.steps,
                best_s: p.best_s,
                per_step_s: p.per_step_s,
                instructions_per_step: p.instructions_per_step,
                reference_code: None,
                reference_s: None,
                ratio: None,
                exponent: s.fit.map(|f| f.exponent),
                instructions: p.instructions,
                instructions_exponent: s.instructions_fit.map(|f| f.exponent),
            })
        });
        anchors.chain(points).collect()
    }
}

/// Runs the benchmark (module docs); `counter` counts instructions when the request asks for
/// them (none given: the note says so).
pub fn bench_anchors(
    request: &AnchorsRequest,
    counter: Option<&dyn InstructionCounter>,
) -> Result<AnchorsReport, BenchError> {
    let repeats = request.repeats.max(1);
    let mut anchors = Vec::new();
    for anchor in Anchor::ALL {
        anchors.push(measure_anchor(anchor, repeats)?);
    }
    let mut instructions_note = None;
    if request.instructions {
        match counter {
            None => instructions_note = Some(NO_COUNTER.into()),
            Some(c) => {
                let steps = request.quick.then_some(QUICK_COUNT_STEPS);
                if let Err(why) = count_all(&mut anchors, c, steps) {
                    instructions_note = Some(why);
                }
            }
        }
    }
    let mut series: Vec<Series> = SeriesKind::ALL
        .into_iter()
        .map(|kind| series::measure(kind, request.quick, repeats))
        .collect::<Result<_, _>>()?;
    match (request.instructions, counter) {
        (false, _) => count::not_counted(&mut series, "instructions not requested"),
        (true, None) => count::not_counted(&mut series, NO_COUNTER),
        (true, Some(c)) => count::count_series(&mut series, c, request.quick),
    }
    Ok(AnchorsReport {
        request: request.clone(),
        anchors,
        reference_note: MEASURED_ON,
        instructions_note,
        series,
    })
}

/// The best of `repeats` runs of one anchor.
fn measure_anchor(anchor: Anchor, repeats: usize) -> Result<AnchorResult, BenchError> {
    let mut best = anchor.run(None)?;
    for _ in 1..repeats {
        let r = anchor.run(None)?;
        if r.wall_time_s < best.wall_time_s {
            best = r;
        }
    }
    let final_nodes: Vec<[f64; 3]> = best.final_nodes.iter().map(|p| [p.x, p.y, p.z]).collect();
    let final_error_m = final_nodes
        .iter()
        .zip(anchor.reference_final_nodes())
        .flat_map(|(p, q)| (0..3).map(move |d| (p[d] - q[d]).abs()))
        .fold(0.0, f64::max);
    let reference = anchor.reference();
    Ok(AnchorResult {
        anchor,
        scene: anchor.path(),
        steps: best.steps,
        best_s: best.wall_time_s,
        per_step_s: best.wall_time_s / best.steps.max(1) as f64,
        instructions_per_step: None,
        final_nodes,
        final_error_m,
        final_tolerance_m: anchor.tolerance(),
        reference,
        // the stored reference was not measured in this run: no ratio to it
        ratio: None,
    })
}

/// Instructions per step of every anchor: (I(k) − I(1)) / (k − 1), k the run's steps or
/// `steps`.
fn count_all(
    anchors: &mut [AnchorResult],
    counter: &dyn InstructionCounter,
    steps: Option<u64>,
) -> Result<(), String> {
    let ks: Vec<u64> = anchors
        .iter()
        .map(|a| steps.unwrap_or(a.steps).min(a.steps).max(2))
        .collect();
    let runs: Vec<CountedRun> = anchors
        .iter()
        .zip(&ks)
        .flat_map(|(a, &k)| {
            [k, 1].map(|steps| CountedRun::Anchor {
                anchor: a.anchor,
                steps,
            })
        })
        .collect();
    let mut counts = counter.count_batch(&runs).into_iter();
    for (a, k) in anchors.iter_mut().zip(ks) {
        let whole = counts
            .next()
            .ok_or("the counter returned too few counts")??;
        let one = counts
            .next()
            .ok_or("the counter returned too few counts")??;
        a.instructions_per_step = Some(whole.saturating_sub(one) as f64 / (k - 1) as f64);
    }
    Ok(())
}
