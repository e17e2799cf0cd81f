//! A long step must not skip a fold: a row of two-bar (von Mises) trusses side by side, the
//! first lower (apex 0.45 m against 0.5 m) so that it folds first, followed with the default
//! settings (steps up to 0.25). In the path's scaled coordinates the low truss's snap is a
//! small part of the row's motion: a long step's corrector used to converge past both of its
//! folds (its apex inverted, λ rising again, no negative eigenvalue at either end) and the
//! path went on without a limit point. Both folds are found at the closed form ±λ*, on the
//! dense path (21 trusses, 42 free coordinates) and the sparse one (101 trusses, 202).

use crate::common;
use common::von_mises_row;

use tensegrity_path::dofs::Dofs;
use tensegrity_path::factor::DENSE_MAX;
use tensegrity_path::point::{Event, Stop};
use tensegrity_path::{follow, PathSettings};

/// The closed form of the low truss's folds: ±λ* at L*³ = L₀ (half-span a = 1 m).
fn lambda_star() -> f64 {
    let l0 = (1.0f64 + 0.45 * 0.45).sqrt();
    let l = l0.cbrt();
    let w = (l * l - 1.0).sqrt();
    2.0 * 1000.0 * w * (1.0 / l - 1.0 / l0) / 100.0
}

/// The row of `trusses` (the first 0.45 m high) followed with the default settings to
/// λ = 0.35 (below the other trusses' fold at 0.384): both folds of the first truss at ±λ*
/// to 10⁻⁸, their mode the first truss's apex alone, vertical; its apex inverted at the end.
fn finds_both_folds(trusses: usize, sparse: bool) {
    let heights: Vec<f64> = (0..trusses)
        .map(|t| if t == 0 { 0.45 } else { 0.5 })
        .collect();
    let model = von_mises_row(&heights);
    let dofs = Dofs::of(&model).unwrap();
    assert_eq!(dofs.len() > DENSE_MAX, sparse, "{} coordinates", dofs.len());
    let path = follow(
        &model,
        &PathSettings {
            target: 0.35,
            ..PathSettings::default()
        },
    )
    .unwrap();
    assert_eq!(path.stop, Stop::ReachedTarget, "{:?}", path.stop);
    let lambda_star = lambda_star();
    let folds: Vec<(f64, &Vec<[f64; 3]>)> = path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::LimitPoint { lambda, mode, .. } => Some((*lambda, mode)),
            _ => None,
        })
        .collect();
    println!(
        "{trusses} trusses: {} points, folds at {:?} (closed form ±{lambda_star})",
        path.points.len(),
        folds.iter().map(|f| f.0).collect::<Vec<_>>()
    );
    assert_eq!(folds.len(), 2, "{:?}", path.events);
    for ((lambda, mode), sign) in folds.into_iter().zip([1.0, -1.0]) {
        assert!(
            (lambda - sign * lambda_star).abs() < 1e-8 * lambda_star,
            "fold at {lambda} against {}",
            sign * lambda_star
        );
        assert_eq!(mode.len(), model.nodes.len());
        assert!((mode[2][1].abs() - 1.0).abs() < 1e-9, "{:?}", mode[2]);
        let elsewhere = mode
            .iter()
            .enumerate()
            .filter(|&(i, _)| i != 2)
            .map(|(_, v)| v.iter().fold(0.0f64, |m, c| m.max(c.abs())))
            .fold(0.0, f64::max);
        assert!(elsewhere < 1e-6, "{elsewhere:e}");
    }
    // no other event: the other trusses stay short of their fold
    assert_eq!(path.events.len(), 2, "{:?}", path.events);
    // between consecutive points the low truss's apex moves by less than its snap (it was
    // one jump from 0.33 m to −0.52 m)
    for w in path.points.windows(2) {
        let jump = (w[1].nodes[2][1] - w[0].nodes[2][1]).abs();
        assert!(jump < 0.5, "apex jumps by {jump} m after λ {}", w[0].lambda);
    }
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, 0.35);
    assert!(last.nodes[2][1] < 0.0, "{:?}", last.nodes[2]);
}

#[test]
fn the_default_steps_find_both_folds_of_the_low_truss_in_a_dense_row() {
    finds_both_folds(21, false);
}

#[test]
fn the_default_steps_find_both_folds_of_the_low_truss_in_a_sparse_row() {
    finds_both_folds(101, true);
}
