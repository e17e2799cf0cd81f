//! One statics front ([`StaticsBackend`]): the dense SVD, the sparse QR and the cyclic
//! blocks give the same counts, margins and smallest singular value on the D-bar (no
//! symmetry), the Snelson prism (C₃) and a supported Snelson tower (C₃); the back-ends that
//! compute prestress stability and load solves agree, the cyclic one refuses them with a typed
//! error; the one report builder names the back-end; an uncertified cyclic rank decision falls
//! back to the SVD, or is reported when the SVD does not fit.

use nalgebra::Vector3;
use tensegrity_core::test_models::{self, snelson, snelson_twist};
use tensegrity_core::{CoreError, Structure};
use tensegrity_statics::report::{report_from, statics_report, StaticsRequest};
use tensegrity_statics::symmetry::{CyclicStatics, CyclicSymmetry};
use tensegrity_statics::Statics;
use tensegrity_statics::{
    cyclic_backend, Factorization, MemberSign, SelfStressBasis, SparseStatics, StaticsBackend,
    StaticsSettings,
};

fn prism() -> Structure {
    snelson(3, snelson_twist(3), 1.0, 1.0, 1.0).build().unwrap()
}

fn z_symmetry(s: &Structure) -> CyclicSymmetry {
    CyclicSymmetry::from_positions(s, 3, Vector3::z(), Vector3::zeros()).unwrap()
}

/// Every back-end of `s` (the cyclic one when `sym` is given).
fn backends<'a>(
    s: &'a Structure,
    sym: Option<&'a CyclicSymmetry>,
) -> Vec<Box<dyn StaticsBackend + 'a>> {
    let settings = StaticsSettings::default();
    let mut out: Vec<Box<dyn StaticsBackend + 'a>> = vec![
        Box::new(Statics::new(s).unwrap()),
        Box::new(SparseStatics::with_settings(s, settings).unwrap()),
    ];
    if let Some(sym) = sym {
        out.push(Box::new(CyclicStatics::new(s, sym).unwrap()));
    }
    out
}

/// Counts, rigid-body motions, margins (standard and with the bars sign-free) and the
/// smallest singular value agree with the dense SVD's; returns the dense margin.
fn same_answers(s: &Structure, sym: Option<&CyclicSymmetry>, what: &str) -> f64 {
    let all = backends(s, sym);
    let dense = &all[0];
    let free_bars: Vec<MemberSign> = MemberSign::standard(s)
        .into_iter()
        .map(|m| match m {
            MemberSign::Compression => MemberSign::Free,
            other => other,
        })
        .collect();
    let margin = dense.prestressability().unwrap().margin;
    let free_margin = dense.prestressability_with(&free_bars).unwrap().margin;
    let sigma_max = Statics::new(s).unwrap().singular_values()[0];
    for b in &all[1..] {
        let who = format!("{what}, {:?}", b.kind());
        assert!(b.certification().is_certified(), "{who}");
        assert_eq!(
            (b.free_dofs(), b.rank(), b.self_stress_dim(), b.mechanisms()),
            (
                dense.free_dofs(),
                dense.rank(),
                dense.self_stress_dim(),
                dense.mechanisms()
            ),
            "{who}"
        );
        assert_eq!(
            b.rigid_body_motions().unwrap(),
            dense.rigid_body_motions().unwrap(),
            "{who}"
        );
        assert_eq!(
            b.internal_mechanisms().unwrap(),
            dense.internal_mechanisms().unwrap(),
            "{who}"
        );
        let m = b.prestressability().unwrap().margin;
        assert!((m - margin).abs() < 1e-9, "{who}: margin {m} vs {margin}");
        let f = b.prestressability_with(&free_bars).unwrap().margin;
        assert!(
            (f - free_margin).abs() < 1e-9,
            "{who}: {f} vs {free_margin}"
        );
        // the sparse value is an estimate; the blocks' singular values are A's
        if b.kind() == Factorization::Cyclic {
            let (x, y) = (b.smallest_singular_value(), dense.smallest_singular_value());
            assert!((x - y).abs() < 1e-12 * sigma_max, "{who}: σ_min {x} vs {y}");
        }
    }
    margin
}

#[test]
fn every_backend_gives_the_dense_answers() {
    let dbar = test_models::loaded_dbar(2.0, 1e4).unwrap();
    assert_eq!(same_answers(&dbar, None, "loaded D-bar"), 0.0);
    let p = prism();
    let sym = z_symmetry(&p);
    let m = same_answers(&p, Some(&sym), "Snelson prism");
    assert!((m - 1.0 / 3f64.sqrt()).abs() < 1e-9, "ERRATA P.1: {m}");
    for stages in [1, 4, 12] {
        let t = test_models::snelson_tower(stages).unwrap();
        let sym = z_symmetry(&t);
        let m = same_answers(&t, Some(&sym), &format!("tower of {stages}"));
        assert!(
            (m - 1.0 / 3f64.sqrt()).abs() < 1e-9,
            "tower of {stages}: {m}"
        );
    }
}

#[test]
fn the_cyclic_backend_refuses_what_it_does_not_compute() {
    let t = test_models::snelson_tower(4).unwrap();
    let sym = z_symmetry(&t);
    let all = backends(&t, Some(&sym));
    let q = all[0].prestressability().unwrap().stress;
    let stable = all[0].prestress_stability(&q).unwrap().stable;
    assert_eq!(all[1].prestress_stability(&q).unwrap().stable, stable);
    let (dense, sparse) = (all[0].solve_loads().unwrap(), all[1].solve_loads().unwrap());
    assert!((&dense.member_force - &sparse.member_force).amax() < 1e-8);
    let cyclic = &all[2];
    for err in [
        cyclic.prestress_stability(&q).unwrap_err(),
        cyclic.solve_loads().unwrap_err(),
    ] {
        assert!(matches!(err, CoreError::Unsupported { .. }), "{err}");
        assert!(err.to_string().contains("cyclic"), "{err}");
    }
    // the symmetric basis: orthonormal self-stresses, constant on member orbits
    match cyclic.self_stress() {
        SelfStressBasis::Symmetric { basis, dim } => {
            assert_eq!(dim, all[0].self_stress_dim());
            assert!(basis.ncols() >= 1 && basis.ncols() <= dim);
            let dofs = tensegrity_statics::DofMap::of(&t);
            let a = tensegrity_statics::equilibrium_matrix(&t, &dofs);
            assert!((&a * &basis).amax() < 1e-10 * a.amax());
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn one_report_builder_for_every_backend() {
    let p = prism();
    let sym = z_symmetry(&p);
    let request = StaticsRequest::default();
    let all = backends(&p, Some(&sym));
    let dense = report_from(all[0].as_ref(), &request).unwrap();
    assert_eq!(dense, statics_report(&p, &request).unwrap());
    assert_eq!(dense.statics_method, None);
    let sparse = report_from(all[1].as_ref(), &request).unwrap();
    assert_eq!(sparse.statics_method, Some(Factorization::SparseQr));
    let cyclic = report_from(all[2].as_ref(), &request).unwrap();
    assert_eq!(cyclic.statics_method, Some(Factorization::Cyclic));
    for r in [&sparse, &cyclic] {
        assert_eq!(
            (
                r.rank,
                r.self_stress_dim,
                r.mechanisms,
                r.internal_mechanisms
            ),
            (
                dense.rank,
                dense.self_stress_dim,
                dense.mechanisms,
                dense.internal_mechanisms
            )
        );
        assert!((r.prestress_margin - dense.prestress_margin).abs() < 1e-9);
    }
    // one self-stress: the symmetric state is the whole space, the same oriented vector
    let (a, b) = (&dense.self_stress[0], &cyclic.self_stress[0]);
    assert!(a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9));
    assert_eq!(dense.prestress_stable, Some(true));
    assert_eq!(cyclic.prestress_stable, None);
    let note = cyclic.statics_warning.as_deref().unwrap();
    assert!(
        note.contains("prestress stability") && note.contains("fully symmetric"),
        "{note}"
    );
    let json = serde_json::to_value(&cyclic).unwrap();
    assert_eq!(json["statics_method"], "cyclic");
}

#[test]
fn an_uncertified_cyclic_rank_falls_back_to_the_svd_or_says_so() {
    // free and unloaded: the cyclic report has everything but the stability
    let t = test_models::snelson_tower_free(6).unwrap();
    let sym = z_symmetry(&t);
    let dense = Statics::new(&t).unwrap();
    let s = dense.singular_values();
    // a relative tolerance 3× the smallest non-zero singular value: it sits inside the
    // uncertain band of the block decision
    let smallest = s[..dense.rank()].last().copied().unwrap();
    let settings = StaticsSettings::default()
        .rank_tolerance(3.0 * smallest / s[0])
        .unwrap();
    let cyclic = CyclicStatics::with_settings(&t, &sym, settings).unwrap();
    assert!(!cyclic.is_certified());
    let chosen = cyclic_backend(&t, &sym, settings).unwrap();
    assert_eq!(chosen.kind(), Factorization::Svd, "falls back");
    let looser = Statics::with_settings(&t, settings).unwrap();
    assert_eq!(
        chosen.rank(),
        looser.rank(),
        "the SVD at the looser tolerance"
    );
    assert!(looser.rank() < dense.rank());
    let no_room = StaticsSettings {
        memory_limit: Some(0.0),
        ..settings
    };
    let kept = cyclic_backend(&t, &sym, no_room).unwrap();
    assert_eq!(kept.kind(), Factorization::Cyclic);
    let r = report_from(kept.as_ref(), &StaticsRequest::default()).unwrap();
    let w = r.statics_warning.unwrap();
    assert!(w.contains("not certified"), "{w}");
    // at the default tolerance the same tower is certified and answered by the blocks
    let default = cyclic_backend(&t, &sym, StaticsSettings::default()).unwrap();
    assert_eq!(default.kind(), Factorization::Cyclic);
    assert!(default.certification().is_certified());
}

/// Two bars from fixed ends to a free node offset `dy` from their line: A = [[1, −1],
/// [dy, dy], [0, 0]] on the free node's rows, singular values √2 and √2·dy.
fn kinked_pair(dy: f64) -> Structure {
    Structure::builder()
        .nodes([[0.0, 0.0, 0.0], [1.0, dy, 0.0], [2.0, 0.0, 0.0]])
        .bar(tensegrity_core::Bar::new(0, 1))
        .bar(tensegrity_core::Bar::new(1, 2))
        .support(tensegrity_core::Support::pinned(0))
        .support(tensegrity_core::Support::pinned(2))
        .build()
        .unwrap()
}

#[test]
fn a_dense_rank_decision_without_a_clear_gap_is_flagged() {
    let request = StaticsRequest::default();
    // clear: σ₂ = √2·0.1 lies 10¹⁴ above τ = 3·ε·√2
    let clear = statics_report(&kinked_pair(0.1), &request).unwrap();
    assert_eq!((clear.rank, clear.mechanisms), (2, 1));
    assert!(
        clear.statics_warning.is_none(),
        "{:?}",
        clear.statics_warning
    );
    let g = clear.spectral_gap;
    assert!((g.sigma_above.unwrap() - 0.1 * 2f64.sqrt()).abs() < 1e-12);
    assert_eq!((g.sigma_below, g.block), (None, None));
    assert!((g.tolerance - 3.0 * f64::EPSILON * 2f64.sqrt()).abs() < 1e-20);
    // near-degenerate: σ₂ = √2·2e-15 ≈ 3 τ. On the defaults the search above τ takes it as
    // zero (the gap above it, 5·10¹⁴, is clear; the bars are collinear to rounding): rank 1
    let searched = statics_report(&kinked_pair(2e-15), &request).unwrap();
    assert_eq!((searched.rank, searched.self_stress_dim), (1, 1));
    assert!(searched.statics_warning.is_none());
    let g = searched.spectral_gap;
    assert!(g.sigma_below.unwrap() < g.tolerance && g.tolerance < g.sigma_above.unwrap());
    // under a caller's tolerance (no search) at the arithmetic's τ, the value lies within the
    // factor 10 of the gap rule: flagged
    let request = StaticsRequest {
        settings: StaticsSettings::default()
            .rank_tolerance(3.0 * f64::EPSILON)
            .unwrap(),
        ..StaticsRequest::default()
    };
    let near = statics_report(&kinked_pair(2e-15), &request).unwrap();
    let w = near.statics_warning.as_deref().expect("flagged");
    assert!(
        w.contains("dense SVD") && w.contains("not certified"),
        "{w}"
    );
    let s2 = near.spectral_gap.sigma_above.unwrap();
    assert!(s2 > near.rank_tolerance && s2 < 10.0 * near.rank_tolerance);
    let json = serde_json::to_value(&near).unwrap();
    assert!(json["spectral_gap"]["sigma_above"].as_f64().unwrap() > 0.0);
    assert!(json["spectral_gap"]["ratio"].is_null());
}

#[test]
fn the_cyclic_gap_names_its_narrowest_block() {
    let t = test_models::snelson_tower_free(6).unwrap();
    let sym = z_symmetry(&t);
    let cyclic = CyclicStatics::new(&t, &sym).unwrap();
    let g = cyclic.spectral_gap();
    assert!(g.is_clear(), "{g:?}");
    let k = g.block.expect("a block index");
    assert!(k <= 1, "k = {k}"); // the rigid-body motions sit in blocks 0 and 1
                                // the rigid-body zeros of the free tower lie below the block tolerance, its smallest
                                // genuine value above, both by more than the factor 10
    assert!(g.sigma_below.unwrap() < g.tolerance / 10.0);
    assert!(g.sigma_above.unwrap() > 10.0 * g.tolerance);
}
