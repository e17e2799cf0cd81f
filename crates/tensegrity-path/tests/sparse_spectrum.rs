//! The spectrum of a sparse tangent (above `factor::DENSE_MAX` free coordinates, or forced
//! with `Factored::with_dense_max(…, 0)`): its eigenvalues of smallest magnitude and the mode,
//! by shift-invert subspace iteration with the factorisation, against the dense
//! eigendecomposition — for stable tangents (the sparse Cholesky) and unstable ones (the
//! sparse LU) — and on the points and folds of paths through the public API.

use crate::common;
use common::von_mises_row;

use nalgebra::{DMatrix, DVector, Vector3};
use tensegrity_path::dofs::Dofs;
use tensegrity_path::factor::{Factored, DENSE_MAX};
use tensegrity_path::forces::{member_states, MemberState};
use tensegrity_path::point::Event;
use tensegrity_path::stability::{Stability, SMALLEST};
use tensegrity_path::tangent::{tangent_stiffness, tangent_triplets};
use tensegrity_path::{
    follow, load_steps, ElasticMember, ElasticModel, MemberKind, PathSettings, Support,
};

/// A fixed pseudo-random sequence in [−1, 1).
fn jitter(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (s >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The triangulated truss tower of `scripts/truss-tower` (three nodes a layer, nine bars a
/// stage, the base pinned), stretched by 1.6 along x, its nodes moved by up to 5 cm and its
/// bars' EA varied by up to 20 %, so that no eigenvalue is repeated or nearly so.
fn tower(stages: usize) -> ElasticModel {
    let mut r = jitter(7);
    let mut nodes = Vec::new();
    for l in 0..=stages {
        for i in 0..3 {
            let a = ((120 * i + 60 * l) as f64).to_radians();
            let d = Vector3::new(r(), r(), r()) * 0.05;
            nodes.push(Vector3::new(1.6 * a.cos(), a.sin(), l as f64) + d);
        }
    }
    let ea = 206e9 * std::f64::consts::PI * 1e-4;
    let mut members = Vec::new();
    for l in 1..=stages {
        let (base, below) = (3 * l, 3 * (l - 1));
        for i in 0..3 {
            for (a, b) in [
                (base + i, base + (i + 1) % 3),
                (below + i, base + i),
                (below + i, base + (i + 2) % 3),
            ] {
                members.push(ElasticMember {
                    nodes: [a, b],
                    kind: MemberKind::Bar,
                    ea: ea * (1.0 + 0.2 * r()),
                    rest_length: (nodes[b] - nodes[a]).norm(),
                });
            }
        }
    }
    let force = 1e6 / (stages * stages) as f64;
    let mut load = vec![Vector3::zeros(); nodes.len()];
    for i in 0..3 {
        load[3 * stages + i] = Vector3::new(force, 0.0, -force);
    }
    ElasticModel {
        clusters: Vec::new(),
        supports: (0..3).map(Support::pinned).collect(),
        nodes,
        members,
        load,
        drivers: Default::default(),
    }
    .validated()
    .unwrap()
}

/// The dense eigenpairs of `k` of smallest magnitude: up to [`SMALLEST`] eigenvalues
/// ascending, and the unit eigenvector of the smallest in magnitude.
fn dense_smallest(k: &DMatrix<f64>) -> (Vec<f64>, DVector<f64>) {
    let eig = k.clone().symmetric_eigen();
    let mut order: Vec<usize> = (0..k.nrows()).collect();
    order.sort_by(|&a, &b| {
        eig.eigenvalues[a]
            .abs()
            .total_cmp(&eig.eigenvalues[b].abs())
    });
    let mut values: Vec<f64> = order
        .iter()
        .take(SMALLEST)
        .map(|&a| eig.eigenvalues[a])
        .collect();
    values.sort_by(f64::total_cmp);
    (values, eig.eigenvectors.column(order[0]).into_owned())
}

/// The sparse spectrum of `k` (factored as `factored`) against the dense one: eigenvalues to
/// 10⁻⁸ relative, the mode up to its sign to 10⁻⁶; returns the sparse eigenvalues.
fn agrees(k: &DMatrix<f64>, factored: &Factored, what: &str) -> Vec<f64> {
    let sparse = factored.spectrum();
    let (values, mode) = dense_smallest(k);
    assert_eq!(sparse.smallest.len(), values.len(), "{what}");
    for (s, d) in sparse.smallest.iter().zip(&values) {
        assert!(
            (s - d).abs() <= 1e-8 * d.abs(),
            "{what}: sparse {:?} against dense {values:?}",
            sparse.smallest
        );
    }
    assert_eq!(sparse.mode.len(), mode.len(), "{what}");
    let apart = (&sparse.mode - &mode)
        .norm()
        .min((&sparse.mode + &mode).norm());
    assert!(apart < 1e-6, "{what}: the modes differ by {apart:e}");
    println!(
        "{what}: {} coordinates, sparse {:?}, dense {values:?}, modes apart {apart:.1e}",
        k.nrows(),
        sparse.smallest
    );
    sparse.smallest
}

/// A stable tower of 25 stages (225 free coordinates): the sparse Cholesky's smallest
/// eigenvalues and mode are the dense eigendecomposition's, and so is the dense path's report.
#[test]
fn a_stable_sparse_tangent_reports_the_dense_smallest_eigenvalues_and_mode() {
    let model = tower(25);
    let dofs = Dofs::of(&model).unwrap();
    assert!(dofs.len() > DENSE_MAX);
    let states = member_states(&model, &model.nodes, 0.0);
    let sparse = Factored::of(&model, &dofs, &states).unwrap();
    assert!(matches!(sparse, Factored::Cholesky(_)), "{sparse:?}");
    let k = tangent_stiffness(&model, &dofs, &states);
    let values = agrees(&k, &sparse, "stable tower");
    assert!(values.iter().all(|&v| v > 0.0));
    let spectrum = sparse.spectrum();
    assert_eq!(
        (spectrum.stability, spectrum.negative, spectrum.below_zero),
        (Stability::Stable, 0, 0)
    );
    // the dense path at the same state: the same three values (all positive)
    let dense = Factored::with_dense_max(&model, &dofs, &states, usize::MAX).unwrap();
    for (s, d) in values.iter().zip(&dense.spectrum().smallest) {
        assert!((s - d).abs() <= 1e-8 * d, "{values:?}");
    }
    // repeatable: the start of the iteration is fixed
    assert_eq!(sparse.spectrum(), spectrum);
}

/// The same tower with every bar compressed (tension −c, geometry held): c between the first
/// and second critical values gives one negative eigenvalue, past the second two; the sparse
/// LU's eigenvalues of smallest magnitude (with their signs) and mode are the dense ones, and
/// the negative ones among them are counted.
#[test]
fn an_unstable_sparse_tangent_reports_its_smallest_eigenvalues_with_their_signs() {
    let model = tower(25);
    let dofs = Dofs::of(&model).unwrap();
    let at_rest = member_states(&model, &model.nodes, 0.0);
    let compressed = |c: f64| -> Vec<MemberState> {
        at_rest
            .iter()
            .map(|s| MemberState { tension: -c, ..*s })
            .collect()
    };
    // K(c) = K_m − c G: the critical c are the reciprocals of the eigenvalues of
    // L⁻¹ G L⁻ᵀ (K_m = L Lᵀ)
    let k_m = tangent_stiffness(&model, &dofs, &at_rest);
    let g = &k_m - tangent_stiffness(&model, &dofs, &compressed(1.0));
    let l = k_m.clone().cholesky().unwrap();
    let a = l.l().solve_lower_triangular(&g).unwrap();
    let a = l.l().solve_lower_triangular(&a.transpose()).unwrap();
    let mut mu: Vec<f64> = a.symmetric_eigen().eigenvalues.iter().copied().collect();
    mu.sort_by(|x, y| y.total_cmp(x));
    let (c1, c2, c3) = (1.0 / mu[0], 1.0 / mu[1], 1.0 / mu[2]);
    println!("critical compressions {c1:e} {c2:e} {c3:e} N");
    for (c, negative) in [(0.5 * (c1 + c2), 1), (0.5 * (c2 + c3), 2)] {
        let states = compressed(c);
        let sparse = Factored::of(&model, &dofs, &states).unwrap();
        assert!(matches!(sparse, Factored::Lu(_)), "{sparse:?}");
        let k = tangent_stiffness(&model, &dofs, &states);
        let values = agrees(&k, &sparse, &format!("tower compressed by {c:e} N"));
        let spectrum = sparse.spectrum();
        assert_eq!(spectrum.stability, Stability::Unstable);
        assert_eq!(values.iter().filter(|&&v| v < 0.0).count(), negative);
        assert_eq!(
            (spectrum.negative, spectrum.below_zero),
            (negative, negative)
        );
        if negative == 1 {
            // one negative, nearest zero: the dense path reports the same three and mode
            let dense = Factored::with_dense_max(&model, &dofs, &states, usize::MAX).unwrap();
            let d = dense.spectrum();
            for (s, e) in values.iter().zip(&d.smallest) {
                assert!(
                    (s - e).abs() <= 1e-8 * e.abs(),
                    "{values:?} {:?}",
                    d.smallest
                );
            }
            let apart = (&spectrum.mode - &d.mode)
                .norm()
                .min((&spectrum.mode + &d.mode).norm());
            assert!(apart < 1e-6, "{apart:e}");
            assert_eq!((d.negative, d.stability), (1, Stability::Unstable));
        }
    }
}

/// The two-bar truss past its fold (apex at 0.1 m, below w* = 0.278 m: one negative
/// eigenvalue), forced onto the sparse path: its two eigenvalues and the mode are the dense
/// ones; and a row of 101 such trusses (202 free coordinates, sparse by size), five shallow
/// ones (0.1 to 0.3 m high) and 96 of 0.5 m, the shallowest past its fold (apex at 0.03 m),
/// the others at rest.
#[test]
fn the_von_mises_truss_past_its_fold_on_the_sparse_path() {
    let model = von_mises_row(&[0.5]);
    let dofs = Dofs::of(&model).unwrap();
    let mut x = model.nodes.clone();
    x[2].y = 0.1;
    let states = member_states(&model, &x, 0.0);
    let sparse = Factored::with_dense_max(&model, &dofs, &states, 0).unwrap();
    assert!(matches!(sparse, Factored::Lu(_)), "{sparse:?}");
    let k = tangent_stiffness(&model, &dofs, &states);
    let values = agrees(&k, &sparse, "von Mises truss at w = 0.1 m");
    assert!(values[0] < 0.0 && values[1] > 0.0);
    let dense = Factored::with_dense_max(&model, &dofs, &states, usize::MAX).unwrap();
    assert_eq!(dense.spectrum().smallest.len(), 2);
    for (s, d) in values.iter().zip(&dense.spectrum().smallest) {
        assert!((s - d).abs() <= 1e-8 * d.abs(), "{values:?}");
    }
    // the mode is vertical: the apex snaps through
    let mode = sparse.spectrum().mode;
    assert!(
        mode[0].abs() < 1e-8 && (mode[1].abs() - 1.0).abs() < 1e-8,
        "{mode}"
    );

    let heights: Vec<f64> = (0..101)
        .map(|t| if t < 5 { 0.1 + 0.05 * t as f64 } else { 0.5 })
        .collect();
    let model = von_mises_row(&heights);
    let dofs = Dofs::of(&model).unwrap();
    assert!(dofs.len() > DENSE_MAX);
    let mut x = model.nodes.clone();
    x[2].y = 0.03;
    let states = member_states(&model, &x, 0.0);
    let sparse = Factored::of(&model, &dofs, &states).unwrap();
    assert!(matches!(sparse, Factored::Lu(_)), "{sparse:?}");
    let k = tangent_stiffness(&model, &dofs, &states);
    let values = agrees(&k, &sparse, "101 trusses, one past its fold");
    assert!(values[0] < 0.0 && values[1] > 0.0);
    let spectrum = sparse.spectrum();
    assert_eq!((spectrum.negative, spectrum.below_zero), (1, 1));
    // the mode is the first truss's apex alone, vertical
    assert!(
        (spectrum.mode[1].abs() - 1.0).abs() < 1e-8,
        "{}",
        spectrum.mode
    );
    // the triplets factored as a matrix give the same (the dynamics' route)
    let triplets = tangent_triplets(&model, &dofs, &states);
    let again = Factored::from_triplets(dofs.len(), &triplets, DENSE_MAX).unwrap();
    assert_eq!(again.spectrum(), spectrum);
}

/// Through the public API on sparse tangents: every point of a tower's load steps (225 free
/// coordinates) reports its three smallest eigenvalues, positive and at rest the dense ones;
/// the arc-length path of a row of 101 trusses (the first 0.45 m high, its fold at
/// λ = 0.291; the others 0.5 m, theirs at 0.384) to λ = 0.35 reports them too, and the first
/// truss's fold with its mode.
#[test]
fn paths_on_sparse_tangents_report_eigenvalues_and_modes() {
    let model = tower(25);
    let path = load_steps(&model, 4, 1.0).unwrap();
    assert_eq!(path.points.len(), 5);
    for p in &path.points {
        assert_eq!(p.smallest_eigenvalues.len(), SMALLEST, "{p:?}");
        assert!(p.smallest_eigenvalues.iter().all(|&v| v > 0.0));
        assert_eq!(p.stability, Stability::Stable);
    }
    let dofs = Dofs::of(&model).unwrap();
    let k = tangent_stiffness(&model, &dofs, &member_states(&model, &model.nodes, 0.0));
    let (values, _) = dense_smallest(&k);
    for (s, d) in path.points[0].smallest_eigenvalues.iter().zip(&values) {
        assert!((s - d).abs() <= 1e-8 * d, "{values:?}");
    }

    let heights: Vec<f64> = (0..101).map(|t| if t == 0 { 0.45 } else { 0.5 }).collect();
    let model = von_mises_row(&heights);
    // steps short enough to see the first truss snap (in the path's scaled coordinates its
    // motion is a hundredth of the row's)
    let path = follow(
        &model,
        &PathSettings {
            target: 0.35,
            initial_step: 0.02,
            max_step: 0.02,
            ..PathSettings::default()
        },
    )
    .unwrap();
    assert!(path
        .points
        .iter()
        .all(|p| p.smallest_eigenvalues.len() == SMALLEST));
    // the closed form of the first truss's folds: ±λ* at L*³ = L₀ (a = 1 m)
    let l0 = (1.0f64 + 0.45 * 0.45).sqrt();
    let l = l0.cbrt();
    let w = (l * l - 1.0).sqrt();
    let lambda_star = 2.0 * 1000.0 * w * (1.0 / l - 1.0 / l0) / 100.0;
    let folds: Vec<(f64, &Vec<[f64; 3]>)> = path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::LimitPoint { lambda, mode, .. } => Some((*lambda, mode)),
            _ => None,
        })
        .collect();
    assert_eq!(folds.len(), 2, "{:?}", path.events);
    for ((lambda, mode), sign) in folds.into_iter().zip([1.0, -1.0]) {
        println!(
            "fold of the row at λ = {lambda} (closed form {})",
            sign * lambda_star
        );
        assert!((lambda - sign * lambda_star).abs() < 1e-8 * lambda_star);
        assert_eq!(mode.len(), model.nodes.len());
        // unit largest component, at the apex of the first truss, vertical; nothing elsewhere
        assert!((mode[2][1].abs() - 1.0).abs() < 1e-9, "{:?}", mode[2]);
        let elsewhere = mode
            .iter()
            .enumerate()
            .filter(|&(i, _)| i != 2)
            .map(|(_, v)| v.iter().fold(0.0f64, |m, c| m.max(c.abs())))
            .fold(0.0, f64::max);
        assert!(elsewhere < 1e-6, "{elsewhere:e}");
    }
}
