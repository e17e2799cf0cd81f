//! The sparse rank-revealing QR path of the statics gives the dense SVD path's rank,
//! self-stress space, mechanisms, prestressability margin, prestress stability and
//! minimal-norm load solution: on stacked-prism towers, random structures (supported and
//! free, loaded) and a planar truss in 3-D (many out-of-plane mechanisms).
use nalgebra::DMatrix;
use tensegrity_core::{test_models, Bar, StringMember, Structure, Support};
use tensegrity_statics::report::{statics_report, StaticsReport, StaticsRequest};
use tensegrity_statics::Statics;
use tensegrity_statics::{SparseStatics, StaticsMethod, StaticsSettings};

fn report(s: &Structure, method: StaticsMethod) -> StaticsReport {
    let request = StaticsRequest {
        settings: StaticsSettings::default().method(method),
        least_squares: true,
        ..Default::default()
    };
    statics_report(s, &request).unwrap()
}

/// ‖P_a − P_b‖_max for the orthogonal projectors on two orthonormal bases.
fn projector_distance(a: &DMatrix<f64>, b: &DMatrix<f64>) -> f64 {
    (a * a.transpose() - b * b.transpose()).amax()
}

fn basis(r: &StaticsReport) -> DMatrix<f64> {
    let n = r.bars + r.strings;
    let cols: Vec<f64> = r.self_stress.iter().flatten().copied().collect();
    DMatrix::from_column_slice(n, r.self_stress.len(), &cols)
}

fn assert_same(dense: &StaticsReport, sparse: &StaticsReport, what: &str) {
    assert_eq!(
        sparse.statics_method,
        Some(tensegrity_statics::Factorization::SparseQr),
        "{what}"
    );
    assert_eq!(dense.statics_method, None, "{what}");
    assert!(
        sparse.statics_warning.is_none(),
        "{what}: {:?}",
        sparse.statics_warning
    );
    assert_eq!(
        (dense.rank, dense.self_stress_dim, dense.mechanisms),
        (sparse.rank, sparse.self_stress_dim, sparse.mechanisms),
        "{what}"
    );
    assert_eq!(
        dense.internal_mechanisms, sparse.internal_mechanisms,
        "{what}"
    );
    assert_eq!(dense.prestressable, sparse.prestressable, "{what}");
    assert!(
        (dense.prestress_margin - sparse.prestress_margin).abs() < 1e-9,
        "{what}: margin {} vs {}",
        dense.prestress_margin,
        sparse.prestress_margin
    );
    assert_eq!(dense.prestress_stable, sparse.prestress_stable, "{what}");
    // (a basis above SELF_STRESS_LIST_MAX numbers is not listed: its callers compare the
    // sparse path's own orthonormal basis)
    if sparse.self_stress_omitted.is_none() {
        let d = projector_distance(&basis(dense), &basis(sparse));
        assert!(d < 1e-9, "{what}: self-stress spaces differ by {d:e}");
    }
    if let (Some(a), Some(b)) = (&dense.force_density, &sparse.force_density) {
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (x, y) in a.iter().zip(b) {
            assert!(
                (x - y).abs() < 1e-9 * scale,
                "{what}: load solve {x} vs {y}"
            );
        }
        assert_eq!(dense.load_carried, sparse.load_carried, "{what}");
    }
}

#[test]
fn towers_match_the_dense_path() {
    for stages in [1, 2, 5, 12, 30] {
        let s = test_models::snelson_tower_free(stages).unwrap();
        let dense = report(&s, StaticsMethod::Dense);
        let sparse = report(&s, StaticsMethod::Sparse);
        assert_same(&dense, &sparse, &format!("tower of {stages}"));
        // one self-stress per prism, one internal mechanism per prism, prestressable
        assert_eq!(sparse.self_stress_dim, stages, "tower of {stages}");
        assert_eq!(sparse.internal_mechanisms, stages, "tower of {stages}");
        assert!(sparse.prestressable && sparse.prestress_margin > 0.01);
    }
}

#[test]
fn a_supported_loaded_tower_gives_the_dense_load_solution() {
    let s = test_models::snelson_tower(20).unwrap();
    let dense = report(&s, StaticsMethod::Dense);
    let sparse = report(&s, StaticsMethod::Sparse);
    assert!(sparse.force_density.is_some());
    assert_same(&dense, &sparse, "pinned, loaded tower of 20");
    let (ra, rb) = (dense.residual.unwrap(), sparse.residual.unwrap());
    assert!(
        (ra - rb).abs() < 1e-9 * ra.max(1.0),
        "residual {ra} vs {rb}"
    );
    let (a, b) = (dense.reactions.unwrap(), sparse.reactions.unwrap());
    for (ra, rb) in a.iter().zip(&b) {
        for d in 0..3 {
            assert!((ra.force[d] - rb.force[d]).abs() < 1e-7, "{ra:?} vs {rb:?}");
        }
    }
}

/// A deterministic value in [0, 1).
fn hash(i: usize, salt: usize) -> f64 {
    let x = ((i * 7919 + salt * 104_729 + 13) as f64 * 0.618_033_988_7).sin() * 43_758.545_3;
    x - x.floor()
}

/// A random structure: `n` nodes in a long box, each joined to its nearest neighbours along
/// the box (a banded graph), every third member a bar; optional supports and loads.
fn random_structure(n: usize, neighbours: usize, salt: usize, supported: bool) -> Structure {
    let mut b = Structure::builder();
    for i in 0..n {
        b = b.node([
            hash(i, salt),
            hash(i, salt + 1),
            i as f64 * 0.3 + hash(i, salt + 2),
        ]);
    }
    let mut k = 0;
    for i in 0..n {
        for j in i + 1..(i + 1 + neighbours).min(n) {
            if hash(k, salt + 3) < 0.8 {
                b = if k % 3 == 0 {
                    b.bar(Bar::new(i, j))
                } else {
                    b.string(StringMember::new(i, j))
                };
            }
            k += 1;
        }
    }
    if supported {
        b = b.support(Support::pinned(0)).support(Support::pinned(1));
        b = b.load(n - 1, [1.0, -2.0, 0.5]);
    }
    b.build().unwrap()
}

#[test]
fn random_structures_match_the_dense_path() {
    let mut certified = 0;
    for (n, nb, salt, supported) in [
        (40, 3, 1, false), // sparse: many mechanisms, few self-stresses
        (40, 6, 2, false), // dense graph: many self-stresses
        (60, 5, 3, true),
        (80, 4, 4, true),
        (70, 7, 5, false),
        (90, 5, 6, true),
    ] {
        let s = random_structure(n, nb, salt, supported);
        let what = format!("random n = {n}, {nb} neighbours");
        let dense = report(&s, StaticsMethod::Dense);
        let sparse = report(&s, StaticsMethod::Sparse);
        if sparse.statics_warning.is_none() {
            assert_same(&dense, &sparse, &what);
            certified += 1;
        } else {
            // the greedy column order picked an ill-conditioned set of members: the report
            // says so, and the automatic method falls back to the SVD
            let auto = report(&s, StaticsMethod::Auto);
            assert_eq!(auto, dense, "{what}");
        }
    }
    assert!(
        certified >= 2,
        "{certified} of 4 random structures certified"
    );
}

#[test]
fn a_planar_truss_in_space_has_its_out_of_plane_mechanisms() {
    // a triangulated strip in the plane z = 0: every node can move out of the plane
    let n = 30;
    let mut b = Structure::builder();
    for i in 0..n {
        b = b.node([i as f64 * 0.5, (i % 2) as f64, 0.0]);
    }
    for i in 0..n - 1 {
        b = b.bar(Bar::new(i, i + 1));
        if i + 2 < n {
            b = b.string(StringMember::new(i, i + 2));
        }
    }
    let s = b.build().unwrap();
    let dense = report(&s, StaticsMethod::Dense);
    let sparse = report(&s, StaticsMethod::Sparse);
    assert_same(&dense, &sparse, "planar strip");
    // rigid in its plane (2n − 3 members, independent), n out-of-plane flexes
    assert_eq!(sparse.rank, 2 * n - 3);
    assert_eq!(sparse.mechanisms, 3 * n - (2 * n - 3));
}

#[test]
fn the_sparse_statics_api_answers_like_the_dense_one() {
    let s = test_models::snelson_tower_free(8).unwrap();
    let dense = Statics::new(&s).unwrap();
    let sparse = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
    assert!(sparse.is_certified());
    assert_eq!(dense.rank(), sparse.rank());
    let rel = (dense.tolerance() - sparse.tolerance()).abs() / dense.tolerance();
    assert!(rel < 1e-4, "σ_max by the power method: {rel:e}");
    let q = sparse.self_stress_basis();
    let aq = dense.matrix() * q;
    assert!(
        aq.amax() < 1e-12,
        "A times the sparse self-stress basis: {}",
        aq.amax()
    );
    let gram = q.transpose() * q;
    assert!((gram - DMatrix::identity(8, 8)).amax() < 1e-12);
}

/// Issue 25: the near-linear path (local sparse null vectors, the margin LP over them, the
/// sparse flex test of stability) answers like the dense SVD on towers and on a double-layer
/// lattice small enough for it: rank, self-stress dimension, mechanisms, margin, stability.
#[test]
fn towers_and_a_lattice_match_the_dense_path_on_the_near_linear_path() {
    let cases = [
        ("tower of 40", test_models::snelson_tower_free(40).unwrap()),
        ("tower of 64", test_models::snelson_tower_free(64).unwrap()),
        ("lattice 4 × 4", test_models::double_layer_grid(4).unwrap()),
        ("lattice 6 × 6", test_models::double_layer_grid(6).unwrap()),
    ];
    for (what, s) in &cases {
        let dense = report(s, StaticsMethod::Dense);
        let sparse = report(s, StaticsMethod::Sparse);
        assert_same(&dense, &sparse, what);
        assert!(sparse.prestressable, "{what}");
        // the sparse stability test (used beyond the dense test's size) agrees as well
        let st = SparseStatics::with_settings(s, StaticsSettings::default()).unwrap();
        let q = nalgebra::DVector::from_column_slice(sparse.prestress.as_ref().unwrap());
        assert_eq!(
            st.stable_by_cholesky(&q).unwrap(),
            dense.prestress_stable,
            "{what}"
        );
        // and so does the flex test alone (the penalised matrix certifies these first)
        assert_eq!(
            st.stable_by_flexes(&q).unwrap(),
            dense.prestress_stable,
            "{what}"
        );
        // the sparse path's orthonormal basis spans the dense path's self-stress space
        let d = projector_distance(&basis(&dense), st.self_stress_basis());
        assert!(d < 1e-9, "{what}: self-stress spaces differ by {d:e}");
        // the sparse self-stress basis spans the null space: A N = 0 to round-off
        let n = st.sparse_self_stress_basis();
        assert_eq!(n.pattern().ncols(), dense.self_stress_dim, "{what}");
        let a = st.matrix();
        for c in 0..n.pattern().ncols() {
            let mut x = vec![0.0; n.pattern().nrows()];
            let (cp, ri, v) = (n.pattern().col_ptr(), n.pattern().row_idx(), n.values());
            for slot in cp[c]..cp[c + 1] {
                x[ri[slot]] = v[slot];
            }
            let ax = a.mul_vec(&x);
            assert!(ax.iter().all(|y| y.abs() < 1e-10), "{what}: column {c}");
        }
    }
}

/// The tower's null vectors are local (one prism each: 12 members), so the sparse basis
/// grows linearly with the tower.
#[test]
fn a_towers_self_stresses_are_local() {
    for stages in [50, 200] {
        let s = test_models::snelson_tower_free(stages).unwrap();
        let st = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
        let n = st.sparse_self_stress_basis();
        assert_eq!(n.pattern().ncols(), stages);
        assert!(n.pattern().nnz() <= 12 * stages, "{}", n.pattern().nnz());
    }
}

/// A self-stress basis above `SELF_STRESS_LIST_MAX` numbers is not listed (its dimension is,
/// with the reason); margin and stability are still computed (the sparse flex test).
#[test]
fn a_large_self_stress_basis_is_not_listed() {
    let s = test_models::snelson_tower_free(350).unwrap();
    let r = report(&s, StaticsMethod::Auto);
    assert_eq!((r.self_stress_dim, r.internal_mechanisms), (350, 350));
    assert!(r.self_stress.is_empty());
    let why = r.self_stress_omitted.as_deref().unwrap();
    assert!(why.contains("350-dimensional"), "{why}");
    assert!((r.prestress_margin - 1.0 / 3f64.sqrt()).abs() < 1e-9);
    assert_eq!(r.prestress_stable, Some(true), "{:?}", r.statics_warning);
    assert!(r.statics_warning.is_none(), "{:?}", r.statics_warning);
}

/// The two sparse stability tests against the eigenvalue test on an orthonormal basis of
/// the internal mechanisms (one prism's self-stress: unstable, the other prisms'
/// mechanisms unstiffened; all prisms' self-stresses, bars compressed: stable). The
/// penalised stress matrix, which `stable_by_cholesky` tries first, certifies the stable
/// one and gives no decision — never "stable" — on the unstable one. At 400 prisms (factor
/// below `FLEX_QR_ENTRIES_PER_DOF`) the local-flex Cholesky (`stable_by_flexes`) decides
/// both, so `stable_by_cholesky` does too; at 500 (fill past the guard, flexes not local)
/// the flex test gives no decision, and the report says "stable" with no warning.
#[test]
fn the_sparse_stability_tests_agree_with_the_eigen_test_beyond_the_flex_guard() {
    for stages in [400, 500] {
        let s = test_models::snelson_tower_free(stages).unwrap();
        let st = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
        let q = st.sparse_self_stress_basis();
        let (cp, ri, v) = (q.pattern().col_ptr(), q.pattern().row_idx(), q.values());
        let mut q0 = nalgebra::DVector::zeros(s.n_members());
        for slot in cp[0]..cp[1] {
            q0[ri[slot]] = v[slot];
        }
        let mut qs = nalgebra::DVector::zeros(s.n_members());
        for c in 0..q.pattern().ncols() {
            let sign = (cp[c]..cp[c + 1]).map(|slot| v[slot]).sum::<f64>().signum();
            for slot in cp[c]..cp[c + 1] {
                qs[ri[slot]] += sign * v[slot];
            }
        }
        let (phi, _) = st.internal_mechanisms().unwrap();
        for (what, q, stable) in [
            ("one prism's stress", &q0, false),
            ("all prisms' stresses", &qs, true),
        ] {
            let dense = st.prestress_stability_on(&phi, q).unwrap().stable;
            assert_eq!(dense, stable, "{stages}: {what}");
            let sparse = st.stable_by_cholesky(q).unwrap();
            let flexes = st.stable_by_flexes(q).unwrap();
            if stages == 400 {
                assert_eq!(sparse, Some(dense), "{stages}: {what}");
                assert_eq!(flexes, Some(dense), "{stages}: {what}");
            } else {
                assert_eq!(sparse, dense.then_some(true), "{stages}: {what}");
                assert_eq!(flexes, None, "{stages}: {what}");
            }
        }
    }
    let r = report(
        &test_models::snelson_tower_free(500).unwrap(),
        StaticsMethod::Auto,
    );
    assert_eq!((r.self_stress_dim, r.internal_mechanisms), (500, 500));
    assert_eq!(r.prestress_stable, Some(true), "{:?}", r.statics_warning);
    assert!(r.statics_warning.is_none(), "{:?}", r.statics_warning);
}

/// The margin LP's method by the fill of the sparse self-stress basis N: on a lattice whose N
/// has filled in (more than `NULL_BASIS_FILL_MAX` times A's entries) the interior point on
/// A D⁻¹ Aᵀ answers, on a tower whose N is local the LP over N; both give the dense path's
/// margin, and a stress that is a self-stress.
#[test]
fn the_margin_lp_runs_on_the_smaller_formulation_and_agrees_with_the_dense_path() {
    use tensegrity_statics::sparse::{equilibrium_matrix_sparse, NULL_BASIS_FILL_MAX};
    let cases = [
        (
            test_models::double_layer_grid(8).unwrap(),
            "8 × 8 lattice",
            true,
        ),
        (
            test_models::snelson_tower(40).unwrap(),
            "tower of 40",
            false,
        ),
    ];
    for (s, what, fills) in cases {
        let sparse = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
        let dense = Statics::with_settings(&s, StaticsSettings::default()).unwrap();
        let a = equilibrium_matrix_sparse(&s, dense.dofs()).unwrap();
        let fill =
            sparse.sparse_self_stress_basis().values().len() as f64 / a.values().len() as f64;
        assert_eq!(
            fill > NULL_BASIS_FILL_MAX,
            fills,
            "{what}: N is {fill:.1} × A"
        );
        let (p, q) = (
            dense.prestressability().unwrap(),
            sparse.prestressability().unwrap(),
        );
        assert!(p.prestressable && q.prestressable, "{what}");
        assert!(
            (p.margin - q.margin).abs() < 1e-9,
            "{what}: margin {} (dense) vs {} (sparse)",
            p.margin,
            q.margin
        );
        let aq = a.mul_vec(q.stress.as_slice());
        let worst = aq.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(worst < 1e-8, "{what}: |A q| = {worst:e}");
    }
}

/// The margin LP runs on A (the interior point imposes A q = 0 exactly) only where the
/// sparse basis holds exact self-stresses. A lattice of 4 × 4 prisms, whose basis fills in
/// past `NULL_BASIS_FILL_MAX`, beside a generic affine image of a Snelson prism with its
/// coordinates rounded to five decimals (its self-stress holds to about 10⁻⁵, counted at
/// `input_precision` 10⁻⁵): the LP stays on the basis and gives the dense path's margin,
/// the prism's 1/√3 to the rounding. On A (measured without the exactness test) the
/// interior point converged to a margin of 1.5·10⁻¹¹: the rounded prism has no exact
/// self-stress, so its bars got no compression.
#[test]
fn a_rounded_self_stress_keeps_the_margin_lp_on_the_basis() {
    use tensegrity_statics::sparse::{equilibrium_matrix_sparse, NULL_BASIS_FILL_MAX};
    let lattice = test_models::double_layer_grid(4).unwrap();
    let s = crate::common::lattice_beside_rounded_prism(&lattice, 1e5);
    let settings = StaticsSettings::default().input_precision(1e-5).unwrap();
    let dense = Statics::with_settings(&s, settings).unwrap();
    let sparse = SparseStatics::with_settings(&s, settings).unwrap();
    let lattice_only = Statics::with_settings(&lattice, StaticsSettings::default()).unwrap();
    // the prism's self-stress is counted on both paths, and the basis has filled in
    assert_eq!(dense.self_stress_dim(), lattice_only.self_stress_dim() + 1);
    assert_eq!(sparse.self_stress_dim(), dense.self_stress_dim());
    let a = equilibrium_matrix_sparse(&s, dense.dofs()).unwrap();
    let fill = sparse.sparse_self_stress_basis().values().len() as f64 / a.values().len() as f64;
    assert!(fill > NULL_BASIS_FILL_MAX, "N is {fill:.2} × A");
    let (p, q) = (
        dense.prestressability().unwrap(),
        sparse.prestressability().unwrap(),
    );
    assert!((p.margin - 1.0 / 3f64.sqrt()).abs() < 1e-3, "{}", p.margin);
    assert!(
        (p.margin - q.margin).abs() < 1e-9,
        "margin {} (dense) vs {} (sparse)",
        p.margin,
        q.margin
    );
}

/// A coarse input precision rejects no member the arithmetic keeps: on a 6 m double-layer
/// grid given to 10⁻⁴ and 10⁻³ of its size (e = 0.6 and 6 mm), the banded QR (forced)
/// counts the exact data's rank and self-stresses, as the SVD does. It rejected columns at
/// 10³ e before (the factor meant for its own round-off), every member shorter than 6 m at
/// 10⁻³: rank 0, every member a self-stress, and certified (`statics` of `grid:10` at
/// `--input-precision 1e-3` reported 1,420 self-stresses and 795 mechanisms, no warning).
/// A rank of 0 is now certified only where σ_max(A) is within the rejection level.
#[test]
fn a_coarse_input_precision_rejects_no_member() {
    use tensegrity_statics::rank::DATA_REJECT_FACTOR;
    let grid = test_models::double_layer_grid(6).unwrap();
    let exact = Statics::with_settings(&grid, StaticsSettings::default()).unwrap();
    assert!(exact.self_stress_dim() > 0);
    let size = grid
        .nodes()
        .iter()
        .flat_map(|p| [p.x.abs(), p.y.abs(), p.z.abs()])
        .fold(0.0, f64::max);
    for precision in [1e-4, 1e-3] {
        let settings = StaticsSettings::default()
            .input_precision(precision)
            .unwrap();
        let dense = Statics::with_settings(&grid, settings).unwrap();
        let sparse = SparseStatics::with_settings(&grid, settings).unwrap();
        println!(
            "{precision:e}: rank {} (SVD {}, exact {}), certified {}",
            sparse.rank(),
            dense.rank(),
            exact.rank(),
            sparse.is_certified()
        );
        assert_eq!(dense.rank(), exact.rank());
        assert_eq!(sparse.rank(), exact.rank());
        assert_eq!(sparse.self_stress_dim(), exact.self_stress_dim());
        // the rejection level stays below the shortest member (1 m)
        assert!(DATA_REJECT_FACTOR * precision * size < 1.0);
    }
}
