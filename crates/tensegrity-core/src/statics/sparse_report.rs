//! The statics report of a large structure from the sparse rank-revealing QR
//! ([`SparseStatics`]): the same fields as the dense report, `statics_method: "sparse_qr"`.

use super::report::{add_load_solve, add_modes, StaticsReport, StaticsRequest};
use super::{
    dense_statics_bytes, SparseStatics, StaticsMethod, StaticsSettings, DEFAULT_MEMORY_LIMIT,
    SPARSE_MIN_SIZE,
};
use crate::error::Result;
use crate::structure::Structure;

/// Whether `settings` send `structure` to the sparse path.
pub(super) fn wants_sparse(structure: &Structure, settings: &StaticsSettings) -> bool {
    match settings.method {
        StaticsMethod::Dense => false,
        StaticsMethod::Sparse => true,
        StaticsMethod::Auto => {
            let dofs = super::DofMap::of(structure).len();
            dofs.min(structure.n_members()) >= SPARSE_MIN_SIZE
        }
    }
}

/// The report from the sparse path; `None` when its rank decision is not certified and the
/// automatic method may fall back to the dense SVD.
pub(super) fn sparse_statics_report(
    structure: &Structure,
    request: &StaticsRequest,
) -> Result<Option<StaticsReport>> {
    let st = SparseStatics::with_settings(structure, request.settings)?;
    let mut warning = None;
    if !st.is_certified() {
        let (m, n) = (st.dofs().len(), structure.n_members());
        let limit = request
            .settings
            .memory_limit
            .unwrap_or(DEFAULT_MEMORY_LIMIT);
        if request.settings.method == StaticsMethod::Auto && dense_statics_bytes(m, n) <= limit {
            return Ok(None);
        }
        warning = Some(format!(
            "the sparse rank decision is not certified (rejected residual {:.3e}, σ_min(R) estimate {:.3e}, tolerance {:.3e}): rank and self-stress dimension may differ from the SVD's",
            st.factorization().rejected_residual(),
            st.sigma_min_r_estimate(),
            st.tolerance()
        ));
    }
    let mut report = base(structure, &st)?;
    report.statics_warning = warning;
    if structure.is_loaded() {
        add_load_solve(
            structure,
            st.solve_loads(),
            request.least_squares,
            &mut report,
        )?;
    }
    if let Some(k) = request.modes {
        add_modes(structure, k, request.mass, &mut report);
    }
    Ok(Some(report))
}

/// Counts, self-stress, prestressability and mechanisms.
fn base(structure: &Structure, st: &SparseStatics<'_>) -> Result<StaticsReport> {
    let pre = st.prestressability()?;
    let (internal, _) = st.internal_mechanisms()?;
    let prestress_stable = if pre.prestressable {
        Some(st.prestress_stability_on(&internal, &pre.stress)?.stable)
    } else {
        None
    };
    Ok(StaticsReport {
        nodes: structure.n_nodes(),
        bars: structure.n_bars(),
        strings: structure.n_strings(),
        rank: st.rank(),
        self_stress_dim: st.self_stress_dim(),
        mechanisms: st.mechanisms(),
        internal_mechanisms: internal.ncols(),
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
        prestress_stable,
        self_stress: st
            .self_stress_basis()
            .column_iter()
            .map(|c| c.iter().copied().collect())
            .collect(),
        prestress: pre
            .prestressable
            .then(|| pre.stress.iter().copied().collect()),
        smallest_singular_value: st.smallest_singular_value_estimate(),
        rank_tolerance: st.tolerance(),
        statics_method: Some("sparse_qr"),
        // the load solve, sizing and warnings are added by their own steps
        ..StaticsReport::default()
    })
}
