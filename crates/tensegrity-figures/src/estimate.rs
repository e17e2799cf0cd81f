//! The work of `figures` before any figure is computed, for `--max-work`. The figures take no
//! parameter but `quick` and `only`, so each one's work is a constant, measured on the
//! project's 2-core VM (release, wall seconds) and rounded up: the four rolling runs shared by
//! Figs. 3.10 and 3.11 ([`ROLLING_SERIES_S`], counted once for both), Fig. 3.8's run of the
//! n = 8 wheel ([`FIG_3_8_S`]), Fig. 4.18's sweeps ([`FIG_4_18_S`]) and [`OTHER_FIGURE_S`]
//! for each other figure; with `quick` every figure is below 0.11 s ([`QUICK_FIGURE_S`]).
//! The figures run beside each other on the cores, so their sum bounds the wall time: all
//! 30 took 42.6 s against the estimate's 49.6 s.
//!
//! Measured (`tensegrity figures --only N --threads 1 --out DIR`, 2026-12-06): Figs. 3.10
//! and 3.11 36.8 s (60.6 s of CPU: the wheels and their convergence checks in parallel),
//! Fig. 3.8 4.4 s, Fig. 4.18 1.7 s, the other 26 together 1.4 s.

use crate::catalog::{FigureSpec, FiguresRequest};
use tensegrity_core::budget::Estimate;

/// The rolling runs of Figs. 3.10 and 3.11 (four wheels, 10 s, at half the full model's
/// default step, with their convergence checks) (s).
pub const ROLLING_SERIES_S: f64 = 40.0;
/// Fig. 3.8: the n = 8 wheel over 3 s with its check (s).
pub const FIG_3_8_S: f64 = 5.0;
/// Fig. 4.18: the Michell mass sweeps (s).
pub const FIG_4_18_S: f64 = 2.0;
/// Any other figure (s).
pub const OTHER_FIGURE_S: f64 = 0.1;
/// Any figure with `quick` (s).
pub const QUICK_FIGURE_S: f64 = 0.15;

/// The estimate of building `chosen` (module docs) with `request`'s `quick`; named
/// `only = …` (so that a refusal names `--only`).
///
/// ```
/// use tensegrity_figures::{estimate::figures, FiguresRequest};
/// let all = FiguresRequest::default();
/// let e = figures(&all, &all.selected().unwrap());
/// assert!((e.work_s - 49.6).abs() < 1e-9, "{}", e.work_s);
/// // Fig. 3.11 shares Fig. 3.10's runs
/// let both = FiguresRequest { only: vec!["3.10".into(), "3.11".into()], ..Default::default() };
/// assert_eq!(figures(&both, &both.selected().unwrap()).work_s, 40.0);
/// let quick = FiguresRequest { quick: true, ..Default::default() };
/// assert!(figures(&quick, &quick.selected().unwrap()).work_s < 5.0);
/// ```
pub fn figures(request: &FiguresRequest, chosen: &[&FigureSpec]) -> Estimate {
    let numbers: Vec<&str> = chosen.iter().map(|f| f.number).collect();
    let series = numbers.iter().any(|n| ["3.10", "3.11"].contains(n));
    let work: f64 = if request.quick {
        QUICK_FIGURE_S * numbers.len() as f64
    } else {
        let each = numbers.iter().map(|n| match *n {
            "3.10" | "3.11" => 0.0,
            "3.8" => FIG_3_8_S,
            "4.18" => FIG_4_18_S,
            _ => OTHER_FIGURE_S,
        });
        each.sum::<f64>() + if series { ROLLING_SERIES_S } else { 0.0 }
    };
    let what = format!(
        "{} figure(s){}{}",
        numbers.len(),
        if series && !request.quick {
            ", with the four 10 s rolling runs of Figs. 3.10 and 3.11"
        } else {
            ""
        },
        if request.quick { " (quick)" } else { "" }
    );
    Estimate::new(what, format!("only = {}", numbers.join(","))).work(work)
}
