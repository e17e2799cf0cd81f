//! Stage timings of the sparse statics on towers (diagnostic; `--ignored --nocapture`).
use std::time::Instant;
use tensegrity_core::{test_models, Structure};
use tensegrity_statics::nested::Orientation;
use tensegrity_statics::{NestedStatics, SparseStatics, StaticsBackend, StaticsSettings};

#[test]
#[ignore]
fn stage_timings() {
    let sizes: Vec<usize> = std::env::var("TOWERS")
        .unwrap_or("200,400,800".into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect();
    let grid = std::env::var("MODEL").is_ok_and(|m| m == "grid");
    for n in sizes {
        let s = if grid {
            test_models::double_layer_grid(n).unwrap()
        } else {
            test_models::snelson_tower_free(n).unwrap()
        };
        println!("members {} dofs {}", s.n_members(), 3 * s.n_nodes());
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
        let r = tensegrity_statics::report::statics_report(
            &s,
            &tensegrity_statics::report::StaticsRequest {
                settings: StaticsSettings::default()
                    .method(tensegrity_statics::StaticsMethod::Sparse),
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

/// Stage timings of the nested-dissection path on double-layer grids (`GRIDS=20,40`; the
/// QR of Aᵀ, `ORIENT=members` for the QR of A).
#[test]
#[ignore]
fn nested_timings() {
    for k in sizes("GRIDS", "20,40") {
        let s = test_models::double_layer_grid(k).unwrap();
        nested_stages(&format!("grid {k}"), &s, orientation("dofs"));
    }
}

/// Stage timings of the nested-dissection path on free towers (`TOWERS=800,3200`; the QR of
/// A, `ORIENT=dofs` for the QR of Aᵀ).
#[test]
#[ignore]
fn nested_tower_timings() {
    for n in sizes("TOWERS", "200,800") {
        let s = test_models::snelson_tower_free(n).unwrap();
        nested_stages(&format!("tower {n}"), &s, orientation("members"));
    }
}

/// The sizes listed in the environment variable `var` (comma-separated), else `default`.
fn sizes(var: &str, default: &str) -> Vec<usize> {
    std::env::var(var)
        .unwrap_or(default.into())
        .split(',')
        .map(|s| s.parse().unwrap())
        .collect()
}

/// `ORIENT` (`dofs` or `members`), else `default`.
fn orientation(default: &str) -> Orientation {
    match std::env::var("ORIENT").unwrap_or(default.into()).as_str() {
        "members" => Orientation::Members,
        _ => Orientation::Dofs,
    }
}

/// Factors `s` on the nested path in `orientation`, then the margin LP and the stability test
/// of its stress; prints the stages' times and the factorisation's numbers.
fn nested_stages(label: &str, s: &Structure, orientation: Orientation) {
    let t = Instant::now();
    let nd = match orientation {
        Orientation::Dofs => NestedStatics::with_settings(s, StaticsSettings::default()),
        Orientation::Members => NestedStatics::members_with_settings(s, StaticsSettings::default()),
    }
    .unwrap();
    let t1 = t.elapsed().as_secs_f64();
    if let Some(b) = nd.sparse_self_stress_basis() {
        let cp = b.pattern().col_ptr();
        let mut sizes: Vec<usize> = cp.windows(2).map(|w| w[1] - w[0]).collect();
        sizes.sort_unstable();
        if let Some(&max) = sizes.last() {
            println!(
                "  null vector entries: median {} max {max}",
                sizes[sizes.len() / 2]
            );
        }
    }
    let t = Instant::now();
    let pre = nd.prestressability();
    let t2 = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let stable = pre
        .as_ref()
        .ok()
        .map(|p| nd.prestress_stability(&p.stress).map(|s| s.stable));
    let t3 = t.elapsed().as_secs_f64();
    println!(
        "{label}: basis {:?} members {} rank {} s {} mech {} certified {} sigma_r {:.3e} E {:.3e} tol {:.3e} front {:?} entries {} | factor {t1:.3}s LP {t2:.3}s stability {t3:.3}s margin {:?} stable {:?}",
        nd.sparse_self_stress_basis().map(|b| b.pattern().nnz()),
        s.n_members(),
        nd.rank(),
        nd.self_stress_dim(),
        nd.mechanisms(),
        nd.is_certified(),
        nd.sigma_min_r_estimate(),
        nd.factorization().rejected_residual(),
        nd.tolerance(),
        nd.factorization().largest_front(),
        nd.factorization().stored_entries(),
        pre.as_ref().map(|p| p.margin).ok(),
        stable
    );
}
