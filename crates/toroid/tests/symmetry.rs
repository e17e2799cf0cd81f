//! The symmetry-adapted statics of the toroid against the dense path: rank, self-stress
//! dimension, internal mechanisms and prestress margin for every stabilising option set.
//! The quick sizes run by default; the full list n ∈ {3..12, 24, 50, 100} with
//! `cargo test -p toroid --test integration symmetry:: -- --ignored` (12 min on the loaded 2-core machine,
//! most of it the dense SVDs and LPs at n = 50 and 100).

use toroid::*;

const OPTION_SETS: [&str; 8] = [
    "none",
    "spokes",
    "inner",
    "outer",
    "spokes,inner",
    "spokes,outer",
    "inner,outer",
    "spokes,inner,outer",
];

fn compare(n: usize, o: &str) {
    let p = ToroidParams::default().sides(n);
    let t = build(&p, o.parse().unwrap(), 1.0).unwrap();
    let sym = analyse(&t).unwrap();
    let dense = analyse_dense(&t).unwrap();
    let what = format!("n = {n}, {o}");
    assert_eq!(sym.rank, dense.rank, "rank, {what}");
    assert_eq!(
        sym.self_stress_dim, dense.self_stress_dim,
        "self-stress, {what}"
    );
    assert_eq!(
        sym.internal_mechanisms, dense.internal_mechanisms,
        "mechanisms, {what}"
    );
    assert_eq!(sym.prestressable, dense.prestressable, "{what}");
    assert!(
        (sym.prestress_margin - dense.prestress_margin).abs() < 1e-9,
        "margin {} vs {}, {what}",
        sym.prestress_margin,
        dense.prestress_margin
    );
    // the per-representation counts add up to the totals
    let reps = &sym.representations;
    assert_eq!(reps.len(), n);
    assert_eq!(reps.iter().map(|r| r.rank).sum::<usize>(), sym.rank);
    assert_eq!(
        reps.iter().map(|r| r.self_stress).sum::<usize>(),
        sym.self_stress_dim
    );
    assert_eq!(
        reps.iter().map(|r| r.internal_mechanisms).sum::<usize>(),
        sym.internal_mechanisms
    );
    assert_eq!(
        reps.iter().map(|r| r.columns).sum::<usize>(),
        t.structure.n_members()
    );
    assert_eq!(
        reps.iter().map(|r| r.rows).sum::<usize>(),
        3 * t.structure.n_nodes()
    );
    assert_eq!(reps.iter().map(|r| r.rigid_body).sum::<usize>(), 6);
    // the symmetric stress is a self-stress: A q = 0, and it carries the margin
    if let Some(q) = &sym.prestress {
        let a = tensegrity_statics::equilibrium_matrix_full(&t.structure);
        assert!((a * q).amax() < 1e-9, "A q = 0, {what}");
        let nb = t.structure.n_bars();
        let worst = (0..q.len())
            .map(|k| if k < nb { -q[k] } else { q[k] })
            .fold(f64::INFINITY, f64::min);
        assert!((worst - sym.prestress_margin).abs() < 1e-12);
    }
}

#[test]
fn symmetric_equals_dense_quick() {
    for n in [3, 4, 5, 8] {
        for o in OPTION_SETS {
            compare(n, o);
        }
    }
}

#[test]
#[ignore = "minutes (the dense path at n = 100): cargo test -p toroid --test integration symmetry:: -- --ignored"]
fn symmetric_equals_dense_every_size() {
    for n in (3..=12).chain([24, 50, 100]) {
        for o in OPTION_SETS {
            compare(n, o);
        }
    }
}

#[test]
fn spokes_and_inner_carry_4n_plus_1_self_stresses() {
    for n in [8, 16, 1000] {
        let t = build(
            &ToroidParams::default().sides(n),
            "spokes,inner".parse().unwrap(),
            1.0,
        )
        .unwrap();
        let a = analyse(&t).unwrap();
        assert_eq!(a.self_stress_dim, 4 * n + 1, "n = {n}");
        assert_eq!(a.internal_mechanisms, 0, "n = {n}");
        // the reference geometry stays prestressable up to n ≈ 30 (the dense path agrees:
        // margin 0.00484 at n = 30, none at n = 40)
        assert_eq!(a.prestressable, n < 30, "n = {n}");
    }
}

#[test]
fn symmetric_equals_dense_off_the_reference_geometry() {
    let geometries = [
        // no tread offset (a more degenerate wheel), a wide inner tread, a rim near the window
        ToroidParams::default().offset(0.0),
        ToroidParams {
            inner_tread: 0.5,
            inner_radius: 0.4,
            ..ToroidParams::default()
        },
        ToroidParams::default().rim_radius(0.69),
    ];
    for p in geometries {
        for n in [6, 7] {
            for o in OPTION_SETS {
                let p = p.sides(n);
                let t = build(&p, o.parse().unwrap(), 1.0).unwrap();
                let (a, b) = (analyse(&t).unwrap(), analyse_dense(&t).unwrap());
                let what = format!("{p:?}, {o}");
                assert_eq!(
                    (
                        a.rank,
                        a.self_stress_dim,
                        a.internal_mechanisms,
                        a.prestressable
                    ),
                    (
                        b.rank,
                        b.self_stress_dim,
                        b.internal_mechanisms,
                        b.prestressable
                    ),
                    "{what}"
                );
                assert!(
                    (a.prestress_margin - b.prestress_margin).abs() < 1e-9,
                    "{what}"
                );
            }
        }
    }
}

/// The toroid through each statics back-end of the core's front (dense SVD, sparse QR,
/// cyclic blocks): the same counts and margin.
#[test]
fn every_statics_backend_analyses_the_toroid_alike() {
    use tensegrity_statics::symmetry::CyclicStatics;
    use tensegrity_statics::Statics;
    use tensegrity_statics::{SparseStatics, StaticsSettings};
    for (n, o) in [
        (5, "spokes,inner"),
        (8, "inner,outer"),
        (6, "spokes,inner,outer"),
    ] {
        let t = build(&ToroidParams::default().sides(n), o.parse().unwrap(), 1.0).unwrap();
        let s = &t.structure;
        let sym = toroid_symmetry(&t).unwrap();
        let dense = analysis_from(&t, &Statics::new(s).unwrap(), Vec::new()).unwrap();
        let sparse = SparseStatics::with_settings(s, StaticsSettings::default()).unwrap();
        let sparse = analysis_from(&t, &sparse, Vec::new()).unwrap();
        let cyclic = analysis_from(&t, &CyclicStatics::new(s, &sym).unwrap(), Vec::new()).unwrap();
        for (a, who) in [(&sparse, "sparse"), (&cyclic, "cyclic")] {
            let what = format!("n = {n}, {o}, {who}");
            assert_eq!(
                (a.rank, a.self_stress_dim, a.internal_mechanisms),
                (dense.rank, dense.self_stress_dim, dense.internal_mechanisms),
                "{what}"
            );
            assert_eq!(a.prestressable, dense.prestressable, "{what}");
            assert!(
                (a.prestress_margin - dense.prestress_margin).abs() < 1e-9,
                "{what}: {} vs {}",
                a.prestress_margin,
                dense.prestress_margin
            );
        }
    }
}
