//! The resource estimate of `bench anchors` ([`estimate`]), before anything runs: the suite
//! is a fixed set of computations (the anchors, the series' sizes of the full or `quick`
//! set), each estimated by the library that runs it, then repeated and counted:
//!
//! - an anchor: its scene's run ([`tensegrity_dynamics::estimate::simulation`]: its RK4
//!   steps by the right-hand side's flops);
//! - a series point: the toroid's symmetry-adapted statics ([`toroid::budget::statics`]),
//!   the tower's statics ([`tensegrity_engine::statics::estimate`]), the Michell truss's
//!   global analysis (its joints at [`tensegrity_engine::estimate::MICHELL_TABLE_S_PER_JOINT`])
//!   and the rolling run ([`toroid::budget::roll`]);
//! - the work: `repeats` times the whole set, and with instructions counted (callgrind) the
//!   counted processes ([`super::count`]: two per anchor and per point) side by side on
//!   `workers` cores, each [`VALGRIND_START_S`] to start and [`CALLGRIND_SLOWDOWN`] times the
//!   native work of its call;
//! - the memory: the largest single computation (the measurements run one at a time);
//! - the output: [`CSV_ROW_BYTES`] a row of the CSV when one is written.
//!
//! The libraries' estimates are conservative here (one pass over the full sizes: 3.2 s
//! estimated, 2.1 s measured on the project's 2-core VM, optimised build). The default suite
//! (full sizes, 5 repeats, instructions counted on 2 cores) is estimated at 2.6 min and took
//! 4 min 27 s wall beside other work; `--quick --repeats 1 --no-instructions` is estimated
//! at 0.3 s and took 0.06–0.16 s.

use crate::anchors::Anchor;
use crate::series::{self, SeriesKind};
use crate::suite::AnchorsRequest;
use crate::BenchError;
use tensegrity_core::budget::{Estimate, Parameters};
use tensegrity_engine::scene::SceneError;

/// Wall seconds valgrind takes to start one counted process (a one-step anchor run: 0.8 s
/// of CPU, 1.8 s wall beside other runs).
pub const VALGRIND_START_S: f64 = 2.0;

/// Callgrind's slowdown of a counted process's own work (50× measured on the MOTES D-bar
/// anchor: 0.7 s of CPU under callgrind for 13 ms natively; rounded up).
pub const CALLGRIND_SLOWDOWN: f64 = 60.0;

/// Bytes of one row of the CSV (`--csv`).
pub const CSV_ROW_BYTES: f64 = 256.0;

/// The native estimate of one pass over the suite: its work summed, its memory the largest,
/// and the number of anchors and points.
fn one_pass(quick: bool) -> Result<(Estimate, usize), BenchError> {
    let mut all = Estimate::new("", "");
    let mut items = 0;
    for anchor in Anchor::ALL {
        let simulation = anchor.scene()?.simulation().map_err(SceneError::from)?;
        let e = tensegrity_dynamics::estimate::simulation(&simulation, true, false, 0.0, "");
        all = add(all, &e);
        items += 1;
    }
    for kind in SeriesKind::ALL {
        for &size in kind.sizes(quick) {
            all = add(all, &series::estimate_point(kind, size, quick)?);
            items += 1;
        }
    }
    Ok((all, items))
}

/// `total` with `e`'s work added and its memory taken in.
fn add(total: Estimate, e: &Estimate) -> Estimate {
    Estimate {
        memory_bytes: total.memory_bytes.max(e.memory_bytes),
        work_s: total.work_s + e.work_s,
        ..total
    }
}

/// The estimate of `request` (module docs): `counted` when instructions will be counted (an
/// instruction counter is available and the request asks for them), on `workers` cores;
/// `csv` when the rows are written. Named by its parameters (`repeats = 5`) and notes.
///
/// ```
/// use tensegrity_bench::{estimate::estimate, AnchorsRequest};
/// let quick = AnchorsRequest { quick: true, repeats: 1, instructions: false };
/// let small = estimate(&quick, false, 2, false).unwrap();
/// assert!(small.work_s < 5.0, "{small:?}");
/// let full = estimate(&AnchorsRequest::default(), true, 2, true).unwrap();
/// assert!(full.work_s > 60.0 && full.output_bytes > 0.0, "{full:?}");
/// ```
pub fn estimate(
    request: &AnchorsRequest,
    counted: bool,
    workers: usize,
    csv: bool,
) -> Result<Estimate, BenchError> {
    let (pass, items) = one_pass(request.quick)?;
    let repeats = request.repeats.max(1) as f64;
    let mut work = repeats * pass.work_s;
    let mut parameters = Parameters::default().and("repeats", request.repeats.max(1));
    if request.quick {
        parameters = parameters.and("", "the quick size sets");
    }
    let mut what = format!("{items} benchmark measurements, best of {repeats}");
    if counted {
        let processes = 2.0 * items as f64;
        let counting = CALLGRIND_SLOWDOWN * pass.work_s + VALGRIND_START_S * processes;
        work += counting / workers.max(1) as f64;
        parameters = parameters.and("", "instructions counted under callgrind");
        what.push_str(&format!(", {processes} callgrind processes"));
    }
    let output = if csv {
        CSV_ROW_BYTES * items as f64
    } else {
        0.0
    };
    Ok(Estimate {
        what,
        parameters,
        memory_bytes: pass.memory_bytes,
        work_s: work,
        output_bytes: output,
    })
}
