//! Stage timings of the sparse statics on towers (diagnostic; `--ignored --nocapture`).
use std::time::Instant;
use tensegrity_core::statics::{SparseStatics, StaticsSettings};
use tensegrity_core::test_models;

#[test]
#[ignore]
fn stage_timings() {
    let sizes: Vec<usize> = std::env::var("TOWERS")
        .unwrap_or("200,400,800".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    for n in sizes {
        let s = test_models::snelson_tower_free(n).unwrap();
        let t = Instant::now();
        let sp = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
        let t1 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let pre = sp.prestressability().unwrap();
        let t2 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let t3 = 0.0;
        let st = sp.prestress_stability(&pre.stress).unwrap();
        let t4 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let r = tensegrity_core::statics::report::statics_report(
            &s,
            &tensegrity_core::statics::report::StaticsRequest {
                settings: StaticsSettings::default()
                    .method(tensegrity_core::statics::StaticsMethod::Sparse),
                ..Default::default()
            },
        )
        .unwrap();
        println!(
            "  report {:.3}s sigma_r {:.3e} nnz(N) {} {:?}",
            t.elapsed().as_secs_f64(),
            sp.sigma_min_r_estimate(),
            sp.sparse_self_stress_basis().values().len(),
            r.statics_warning
        );
        println!(
            "tower {n}: factor+basis {t1:.3}s LP {t2:.3}s mechanisms {t3:.3}s stability {t4:.3}s (margin {} stable {})",
            pre.margin, st.stable
        );
    }
}

#[test]
#[ignore]
fn cholesky_vs_dense() {
    for n in [1, 2, 5, 30] {
        let s = test_models::snelson_tower_free(n).unwrap();
        let sp = SparseStatics::with_settings(&s, StaticsSettings::default()).unwrap();
        let pre = sp.prestressability().unwrap();
        let (phi, _) = sp.internal_mechanisms().unwrap();
        let st = sp.prestress_stability_on(&phi, &pre.stress).unwrap();
        println!(
            "tower {n}: dense eig {:?} stable {}; cholesky {} sigma_r {} qmax {}",
            &st.eigenvalues[..st.eigenvalues.len().min(3)],
            st.stable,
            sp.stable_by_cholesky(&pre.stress).unwrap().unwrap(),
            sp.sigma_min_r_estimate(),
            pre.stress.amax()
        );
    }
}
