//! `bench anchors` as library data (issue 25, item 4): the report's structure, the anchors'
//! final states against the independent references of `tests/anchors.rs`, the instruction
//! differencing, the rows, and the exponent fit against synthetic power laws. Run with the
//! quick size set and one repeat; no timing is asserted.

use tensegrity_bench::fit::power_law;
use tensegrity_bench::series::{run_counted, SeriesKind};
use tensegrity_bench::{bench_anchors, Anchor, AnchorsRequest, InstructionCounter};

/// A counter whose whole-process count is a fixed start-up cost plus a known cost per step,
/// different per anchor; for a series point, start-up + a setup growing with the size +
/// `reps` calls of cost 500 · size^p, p = 1, 2, 3, 1.5 for toroid, towers, Michell, rolling
/// (per step).
struct Linear;

/// The exponents of [`Linear`]'s series.
const EXPONENTS: [f64; 4] = [1.0, 2.0, 3.0, 1.5];

impl InstructionCounter for Linear {
    fn count(&self, anchor: Anchor, steps: u64) -> Result<u64, String> {
        let per_step = 1000 * (1 + Anchor::ALL.iter().position(|&a| a == anchor).unwrap() as u64);
        Ok(3_000_000 + per_step * steps)
    }

    fn count_series(&self, kind: SeriesKind, size: usize, reps: u64) -> Result<u64, String> {
        let p = EXPONENTS[SeriesKind::ALL.iter().position(|&k| k == kind).unwrap()];
        let call = (500.0 * (size as f64).powf(p)).round() as u64;
        Ok(3_000_000 + 70_000 * size as u64 + reps * call)
    }
}

/// A counter that counts the anchors only (the trait's default for the series).
struct AnchorsOnly;

impl InstructionCounter for AnchorsOnly {
    fn count(&self, _: Anchor, steps: u64) -> Result<u64, String> {
        Ok(1_000_000 + 10 * steps)
    }
}

/// A counter that is not there.
struct Broken;

impl InstructionCounter for Broken {
    fn count(&self, _: Anchor, _: u64) -> Result<u64, String> {
        Err("valgrind: not found".into())
    }

    fn count_series(&self, _: SeriesKind, _: usize, _: u64) -> Result<u64, String> {
        Err("valgrind: not found".into())
    }
}

fn quick(instructions: bool) -> AnchorsRequest {
    AnchorsRequest {
        quick: true,
        repeats: 1,
        instructions,
    }
}

#[test]
fn the_report_holds_every_anchor_and_series_with_the_reference_final_states() {
    let r = bench_anchors(&quick(true), Some(&Linear)).unwrap();
    assert_eq!(r.anchors.len(), 4);
    assert!(r.instructions_note.is_none());
    for (a, (anchor, steps, per_step)) in r.anchors.iter().zip([
        (Anchor::MotesDbar, 5000, 1000.0),
        (Anchor::MotesPrism, 5000, 2000.0),
        (Anchor::TsgfemTbar, 2000, 3000.0),
        (Anchor::DoublePendulum, 5000, 4000.0),
    ]) {
        assert_eq!(a.anchor, anchor);
        assert_eq!(a.steps, steps);
        assert_eq!(a.scene, format!("examples/anchors/{}.toml", anchor.name()));
        // (I(k) − I(1)) / (k − 1): the start-up cost cancels
        assert_eq!(a.instructions_per_step, Some(per_step));
        // the final state is the independent integrator's within the RK4 error at dt
        let reference = anchor.reference_final_nodes();
        assert_eq!(a.final_nodes.len(), reference.len());
        assert!(
            a.final_error_m < anchor.tolerance(),
            "{anchor}: {}",
            a.final_error_m
        );
        let diff = a
            .final_nodes
            .iter()
            .zip(reference)
            .flat_map(|(p, q)| (0..3).map(move |d| (p[d] - q[d]).abs()))
            .fold(0.0, f64::max);
        assert_eq!(diff, a.final_error_m);
        assert!(a.best_s > 0.0 && (a.per_step_s * steps as f64 - a.best_s).abs() < 1e-15);
        // a stored reference time gives no ratio; it carries its date and machine
        assert_eq!(a.ratio, None);
        assert!(a.reference.measured.starts_with("2026-11-28"));
    }
    let refs: Vec<(&str, f64)> = r
        .anchors
        .iter()
        .map(|a| (a.reference.code, a.reference.seconds))
        .collect();
    assert_eq!(
        refs,
        [
            ("MOTES", 54.3),
            ("MOTES", 12.3),
            ("TsgFEM", 2.75),
            ("MOTES", 35.1)
        ]
    );
    assert!(r.reference_note.contains("not in this run"));
    assert!(r.rows().iter().all(|row| row.ratio.is_none()));
    assert!(r.reference_note.contains("GNU Octave 7.3"));

    let kinds: Vec<SeriesKind> = r.series.iter().map(|s| s.series).collect();
    assert_eq!(kinds, SeriesKind::ALL);
    for s in &r.series {
        let sizes: Vec<usize> = s.points.iter().map(|p| p.size).collect();
        assert_eq!(sizes, s.series.sizes(true));
        assert!(s.fit.is_some_and(|f| f.exponent.is_finite()));
        let timed = s.series == SeriesKind::Rolling;
        assert!(s.points.iter().all(|p| p.per_step_s.is_some() == timed));
    }
    // members where the call reports them: 3n + 1 bars and 16n strings (spokes + inner);
    // 9N + 3 for the towers
    let members =
        |k: usize| -> Vec<Option<usize>> { r.series[k].points.iter().map(|p| p.members).collect() };
    assert_eq!(members(0), [100, 200, 400].map(|n| Some(19 * n + 1)));
    assert_eq!(members(1), [5, 10, 20].map(|n| Some(9 * n + 3)));
    assert!(r.series[3].points.iter().all(|p| p.steps == Some(20)));
    // the Michell truss reports its members too: more with each complexity
    let michell = members(2);
    assert!(michell.iter().all(Option::is_some) && michell.windows(2).all(|w| w[0] < w[1]));
    // the instructions: start-up and setup removed, the call's (per step for rolling) left,
    // and the power law fitted to them exactly
    for (s, p) in r.series.iter().zip(EXPONENTS) {
        assert!(s.instructions_note.is_none(), "{:?}", s.instructions_note);
        for point in &s.points {
            let call = (500.0 * (point.size as f64).powf(p)).round();
            match point.steps {
                Some(k) => {
                    assert_eq!(point.instructions_per_step, Some(call));
                    assert_eq!(point.instructions, Some(call * k as f64));
                }
                None => {
                    assert_eq!(point.instructions, Some(call));
                    assert!(point.instructions_per_step.is_none());
                }
            }
        }
        let fit = s.instructions_fit.unwrap();
        assert!((fit.exponent - p).abs() < 1e-3, "{:?}: {fit:?}", s.series);
    }

    let rows = r.rows();
    assert_eq!(rows.len(), 4 + 3 + 3 + 3 + 2);
    assert_eq!(rows[0].name, "motes_dbar");
    assert_eq!(rows[0].reference_s, Some(54.3));
    assert_eq!(rows[0].instructions_per_step, Some(1000.0));
    assert!(rows[0].instructions.is_none() && rows[0].instructions_exponent.is_none());
    assert_eq!(rows[4].group, "series");
    assert_eq!(rows[4].exponent, r.series[0].fit.map(|f| f.exponent));
    assert_eq!(rows[4].instructions, r.series[0].points[0].instructions);
    let exponent = r.series[0].instructions_fit.map(|f| f.exponent);
    assert_eq!(rows[4].instructions_exponent, exponent);
    let last = rows.last().unwrap();
    assert_eq!(
        last.instructions_per_step,
        Some((500.0 * 8f64.powf(1.5)).round())
    );
}

#[test]
fn without_a_counter_the_report_says_why() {
    let no_instructions = |r: &tensegrity_bench::AnchorsReport, note: &str| {
        for s in &r.series {
            assert_eq!(s.instructions_note.as_deref(), Some(note));
            assert!(s.instructions_fit.is_none());
            let counted = |p: &tensegrity_bench::series::SeriesPoint| {
                p.instructions.is_some() || p.instructions_per_step.is_some()
            };
            assert!(!s.points.iter().any(counted));
        }
        assert!(r.rows().iter().all(|row| row.instructions.is_none()
            && row.instructions_exponent.is_none()
            && row.instructions_per_step.is_none()));
    };
    let r = bench_anchors(&quick(true), None).unwrap();
    assert!(r.instructions_note.as_ref().unwrap().contains("valgrind"));
    assert!(r.anchors.iter().all(|a| a.instructions_per_step.is_none()));
    no_instructions(&r, "no instruction counter (valgrind) available");
    let r = bench_anchors(&quick(true), Some(&Broken)).unwrap();
    assert_eq!(r.instructions_note.as_deref(), Some("valgrind: not found"));
    no_instructions(&r, "valgrind: not found");
    let r = bench_anchors(&quick(false), Some(&Broken)).unwrap();
    assert!(r.instructions_note.is_none());
    no_instructions(&r, "instructions not requested");
    // a counter of the anchors alone: the anchors counted, the series say why not
    let r = bench_anchors(&quick(true), Some(&AnchorsOnly)).unwrap();
    assert!(r.instructions_note.is_none());
    assert!(r
        .anchors
        .iter()
        .all(|a| a.instructions_per_step == Some(10.0)));
    assert!(r.series.iter().all(|s| s.instructions_note.as_deref()
        == Some("this instruction counter counts the anchors only")));
}

#[test]
fn a_counted_series_run_is_the_timed_call() {
    // the hidden run's setup alone and its calls succeed at the quick sizes (what callgrind
    // counts); a bad size is an error, not a panic
    for kind in SeriesKind::ALL {
        let size = kind.sizes(true)[0];
        run_counted(kind, size, 0).unwrap();
        run_counted(kind, size, 2).unwrap();
    }
    assert!(run_counted(SeriesKind::Toroid, 1, 1).is_err());
}

#[test]
fn the_request_describes_its_fields() {
    tensegrity_core::request::check_description::<AnchorsRequest>().unwrap();
    use tensegrity_core::request::Request;
    let r = AnchorsRequest::from_values([("repeats", serde_json::json!(3))]).unwrap();
    assert_eq!((r.repeats, r.quick, r.instructions), (3, false, true));
    assert!(AnchorsRequest::from_values([("repeats", serde_json::json!(0))]).is_err());
}

#[test]
fn a_run_of_k_steps_is_the_start_of_the_whole_run() {
    let whole = Anchor::MotesDbar.run(None).unwrap();
    assert_eq!(whole.steps, 5000);
    let part = Anchor::MotesDbar.run(Some(7)).unwrap();
    assert_eq!(part.steps, 7);
    assert!("nope".parse::<Anchor>().unwrap_err().contains("motes_dbar"));
    assert_eq!("tsgfem_tbar".parse::<Anchor>(), Ok(Anchor::TsgfemTbar));
}

#[test]
fn the_fit_recovers_a_synthetic_power_law() {
    for (p, c) in [(0.97, 2.3e-5), (2.37, 1.1e-7), (1.0, 1.0), (-0.5, 4.0)] {
        let points: Vec<(f64, f64)> = [8.0, 31.0, 100.0, 316.0, 1000.0]
            .iter()
            .map(|&n: &f64| (n, c * n.powf(p)))
            .collect();
        let fit = power_law(&points).unwrap();
        assert!((fit.exponent - p).abs() < 1e-12, "{fit:?}");
        assert!((fit.prefactor / c - 1.0).abs() < 1e-10, "{fit:?}");
        assert!(fit.max_log_residual < 1e-10);
    }
    // symmetric ±10 % noise on alternate points: the slope moves, the residual shows it
    let noisy: Vec<(f64, f64)> = [10.0, 20.0, 40.0, 80.0]
        .iter()
        .enumerate()
        .map(|(i, &n): (usize, &f64)| (n, n * n * if i % 2 == 0 { 1.1 } else { 0.9 }))
        .collect();
    let fit = power_law(&noisy).unwrap();
    assert!((fit.exponent - 2.0).abs() < 0.1 && fit.max_log_residual > 0.05);
    assert!(power_law(&[(10.0, 1.0)]).is_none());
    assert!(power_law(&[(10.0, 1.0), (10.0, 2.0)]).is_none());
    assert!(power_law(&[(10.0, 1.0), (20.0, 0.0)]).is_none());
}
