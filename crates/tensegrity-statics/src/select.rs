//! Which back-end answers a statics question ([`StaticsBackend`]).
//!
//! - [`backend`] (general structures, [`StaticsMethod`]): the dense SVD below
//!   [`SPARSE_MIN_SIZE`] free dofs or members (below [`ROUNDED_SPARSE_MIN_SIZE`] for
//!   coordinates judged rounded, whose rank decision reads the SVD's spectral gap), the
//!   sparse rank-revealing QR from there on
//!   (automatic method: along the band, or along a nested dissection for an unloaded
//!   structure whose band is wide, a lattice: [`prefers_nested`](super::nested::prefers_nested);
//!   for a large unloaded structure of narrow band, a tower, along a nested dissection of A
//!   itself: [`prefers_nested_members`](super::nested::prefers_nested_members));
//!   an uncertified sparse rank decision falls back to the SVD when the method is automatic
//!   and the SVD fits the memory budget and the default work limit, and is otherwise
//!   returned as is (its
//!   [`Certification`](super::Certification) says so).
//! - [`cyclic_backend`] (structures with a validated Cₙ descriptor): the symmetry-adapted
//!   blocks ([`CyclicStatics`]); an uncertified block rank decision falls back to the dense
//!   SVD when it fits the memory budget and the work limit, and is otherwise returned as is.
//!   `method = Dense` or `Sparse` forces that back-end; a structure with a support along
//!   directions of any orientation (`along`, which the blocks do not know) takes [`backend`].
//! - A structure with clustered strings takes the dense SVD or the banded sparse QR, the
//!   back-ends that model them ([`crate::cluster_columns`]: one column per cluster), by the
//!   same rule as above (the nested dissection, which does not, is never chosen); the cyclic
//!   blocks do not model them either, and a symmetric structure with clusters takes this
//!   general choice.

use super::front::Factorization;
use super::symmetry::{CyclicStatics, CyclicSymmetry};
use super::{
    dense_statics_bytes, DofMap, SparseStatics, Statics, StaticsBackend, StaticsMethod,
    StaticsSettings, DEFAULT_MEMORY_LIMIT, SPARSE_MIN_SIZE,
};
use tensegrity_core::error::{CoreError, Result};
use tensegrity_core::structure::Structure;

/// Whether the dense SVD of `structure` fits the memory budget of `settings` and its
/// estimated work the work limit of `settings` (the front end's `--max-work`; without one
/// the default, [`tensegrity_core::budget::DEFAULT_MAX_WORK_S`]): a fallback beyond it would
/// run for minutes unannounced, so the uncertified decision is returned (flagged) instead.
fn dense_fits(structure: &Structure, settings: &StaticsSettings) -> bool {
    let (m, n) = (DofMap::of(structure).len(), super::n_columns(structure));
    let limit = settings.memory_limit.unwrap_or(DEFAULT_MEMORY_LIMIT);
    let work = dense_work_s(structure);
    let work_limit = (settings.work_limit).unwrap_or(tensegrity_core::budget::DEFAULT_MAX_WORK_S);
    dense_statics_bytes(m, n) <= limit && work <= work_limit
}

/// The dense SVD's estimated work on `structure` (s).
pub(crate) fn dense_work_s(structure: &Structure) -> f64 {
    let (m, n) = (DofMap::of(structure).len(), super::n_columns(structure));
    tensegrity_core::budget::dense_statics(m, n, "").work_s
}

/// Whether a sparse result that failed its check may be answered by the dense SVD: the
/// automatic method, and the SVD within the limits ([`dense_fits`]).
pub(crate) fn dense_fallback(structure: &Structure, settings: &StaticsSettings) -> bool {
    settings.method == StaticsMethod::Auto && dense_fits(structure, settings)
}

/// Whether `settings` send `structure` to the sparse QR.
/// [`StaticsMethod::Auto`] keeps the dense SVD below this many free dofs or members (rather
/// than [`SPARSE_MIN_SIZE`]) for coordinates judged rounded: the rank decision on rounded
/// data reads the gap of the singular values (the report's `spectral_gap`), which the
/// sparse QR only bounds. At this size the SVD still costs a few tens of milliseconds.
pub const ROUNDED_SPARSE_MIN_SIZE: usize = 300;

fn wants_sparse(structure: &Structure, settings: &StaticsSettings) -> bool {
    match settings.method {
        StaticsMethod::Dense => false,
        StaticsMethod::Sparse => true,
        StaticsMethod::Auto => {
            let size = DofMap::of(structure).len().min(crate::n_columns(structure));
            if size < SPARSE_MIN_SIZE {
                return false;
            }
            // rounded coordinates (judged from their digits, or the user's precision) keep
            // the SVD's spectrum a little longer: its gap is what tells a self-stress the
            // rounding hid from a mechanism (crate::rank)
            let rounded = settings.rank_tolerance.is_none()
                && crate::rank::input_rounding(structure, settings.input_precision) > 0.0;
            !rounded || size >= ROUNDED_SPARSE_MIN_SIZE
        }
    }
}

/// The back-end [`StaticsMethod`] chooses for a general structure (see the module docs).
///
/// ```
/// use tensegrity_statics::{backend, Factorization, StaticsBackend, StaticsSettings};
/// use tensegrity_core::{Bar, StringMember, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.5, 0.0], [1.0, -0.5, 0.0], [2.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1)).bar(Bar::new(0, 2)).bar(Bar::new(1, 3)).bar(Bar::new(2, 3))
///     .string(StringMember::new(0, 3)).string(StringMember::new(1, 2))
///     .build()
///     .unwrap();
/// let b = backend(&s, StaticsSettings::default()).unwrap();
/// assert_eq!((b.kind(), b.self_stress_dim()), (Factorization::Svd, 1));
/// ```
pub fn backend<'a>(
    structure: &'a Structure,
    settings: StaticsSettings,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    if structure.has_clusters() {
        return clustered(structure, settings);
    }
    if wants_sparse(structure, &settings) {
        let fallback = settings.method == StaticsMethod::Auto && dense_fits(structure, &settings);
        if settings.method == StaticsMethod::Auto && super::nested::prefers_nested(structure) {
            let nested = super::NestedStatics::with_settings(structure, settings)?;
            if nested.is_certified() || !fallback {
                return Ok(Box::new(nested));
            }
            return Ok(Box::new(Statics::with_settings(structure, settings)?));
        }
        if settings.method == StaticsMethod::Auto
            && super::nested::prefers_nested_members(structure)
        {
            return long_structure(structure, settings, fallback);
        }
        let sparse = SparseStatics::with_settings(structure, settings)?;
        if sparse.is_certified() || !fallback {
            return Ok(Box::new(sparse));
        }
    }
    Ok(Box::new(Statics::with_settings(structure, settings)?))
}

/// The name of the path a back-end of `kind` built for `structure` takes, as the benches and
/// the scaling example label it: `svd`, `cyclic`, and for the sparse QR `nested` (a wide
/// lattice), `nested_members` (a long structure) or `sparse_qr` (the banded QR), by the
/// automatic method's rules.
///
/// ```
/// use tensegrity_core::test_models::snelson_tower_free;
/// use tensegrity_statics::{backend, backend_path, StaticsSettings};
/// let tower = snelson_tower_free(20).unwrap();
/// let b = backend(&tower, StaticsSettings::default()).unwrap();
/// assert_eq!(backend_path(&tower, b.kind()), "sparse_qr");
/// ```
pub fn backend_path(structure: &Structure, kind: Factorization) -> &'static str {
    match kind {
        Factorization::Svd => "svd",
        Factorization::Cyclic => "cyclic",
        Factorization::SparseQr if super::nested::prefers_nested(structure) => "nested",
        Factorization::SparseQr if super::nested::prefers_nested_members(structure) => {
            "nested_members"
        }
        Factorization::SparseQr => "sparse_qr",
    }
}

/// A structure with clusters: the dense SVD or the banded sparse QR, the back-ends that
/// model them (a cluster is one column of A over all its nodes); the nested dissection does
/// not, and the automatic method takes the sparse QR where [`wants_sparse`] would, falling
/// back to the SVD when its rank is not certified and the SVD fits.
fn clustered<'a>(
    structure: &'a Structure,
    settings: StaticsSettings,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    let sparse = match settings.method {
        StaticsMethod::Sparse => true,
        StaticsMethod::Auto => wants_sparse(structure, &settings),
        _ => false,
    };
    if sparse {
        let fallback = settings.method == StaticsMethod::Auto && dense_fits(structure, &settings);
        let sparse = SparseStatics::with_settings(structure, settings)?;
        if sparse.is_certified() || !fallback {
            return Ok(Box::new(sparse));
        }
    }
    Ok(Box::new(Statics::with_settings(structure, settings)?))
}

/// A large unloaded structure of narrow band (a tower): the nested-dissection QR of A
/// itself ([`NestedStatics::members_with_settings`], linear), kept when certified unless the
/// report would list its self-stress basis (0 < members × self-stresses ≤
/// [`SELF_STRESS_LIST_MAX`](super::sparse::SELF_STRESS_LIST_MAX)), which the banded QR
/// builds; the banded QR otherwise (with the SVD as its fallback), and the nested result
/// again where the banded QR exceeds its memory bound or budget.
fn long_structure<'a>(
    structure: &'a Structure,
    settings: StaticsSettings,
    fallback: bool,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    // should the nested factorisation fail, the banded QR answers as it did before
    let Ok(nested) = super::NestedStatics::members_with_settings(structure, settings) else {
        let sparse = SparseStatics::with_settings(structure, settings)?;
        if sparse.is_certified() || !fallback {
            return Ok(Box::new(sparse));
        }
        return Ok(Box::new(Statics::with_settings(structure, settings)?));
    };
    let s = nested.self_stress_dim();
    let listed =
        s > 0 && structure.n_members().saturating_mul(s) <= super::sparse::SELF_STRESS_LIST_MAX;
    if nested.is_certified() && !listed {
        return Ok(Box::new(nested));
    }
    match SparseStatics::with_settings(structure, settings) {
        Ok(sparse) if sparse.is_certified() || !fallback => Ok(Box::new(sparse)),
        Ok(_) => Ok(Box::new(Statics::with_settings(structure, settings)?)),
        Err(CoreError::TooLarge { .. } | CoreError::OverBudget(_)) => {
            if nested.is_certified() || !fallback {
                Ok(Box::new(nested))
            } else {
                Ok(Box::new(Statics::with_settings(structure, settings)?))
            }
        }
        Err(e) => Err(e),
    }
}

/// The back-end of a structure with a validated cyclic symmetry (see the module docs).
pub fn cyclic_backend<'a>(
    structure: &'a Structure,
    symmetry: &'a CyclicSymmetry,
    settings: StaticsSettings,
) -> Result<Box<dyn StaticsBackend + 'a>> {
    if structure.has_clusters() {
        return clustered(structure, settings);
    }
    match settings.method {
        StaticsMethod::Dense => return Ok(Box::new(Statics::with_settings(structure, settings)?)),
        StaticsMethod::Sparse => {
            return Ok(Box::new(SparseStatics::with_settings(structure, settings)?))
        }
        // the blocks know supports along x, y, z only: any other orientation takes the
        // general path
        StaticsMethod::Auto if structure.supports().iter().any(|s| !s.along.is_empty()) => {
            return backend(structure, settings);
        }
        StaticsMethod::Auto => {}
    }
    let cyclic = CyclicStatics::with_settings(structure, symmetry, settings)?;
    if cyclic.is_certified() || !dense_fits(structure, &settings) {
        return Ok(Box::new(cyclic));
    }
    Ok(Box::new(Statics::with_settings(structure, settings)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::{Cluster, StringMember};

    /// The dense fit follows the given work limit (a raised `--max-work` admits the SVD),
    /// not the default; a small clustered structure takes the SVD as any small structure,
    /// and the sparse QR where the method names it (it models clusters).
    #[test]
    fn the_dense_fit_follows_the_given_work_limit() {
        let s = Structure::builder()
            .nodes([
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 1.0],
                [2.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
            ])
            .string(StringMember::new(0, 3))
            .cluster(Cluster::new([0, 1, 2]))
            .build()
            .unwrap();
        let tiny = StaticsSettings {
            work_limit: Some(1e-15),
            ..StaticsSettings::default()
        };
        assert!(dense_fits(&s, &StaticsSettings::default()));
        assert!(!dense_fits(&s, &tiny));
        let sparse = StaticsSettings::default().method(StaticsMethod::Sparse);
        assert_eq!(
            backend(&s, sparse).unwrap().kind(),
            crate::Factorization::SparseQr
        );
        assert_eq!(
            backend(&s, StaticsSettings::default()).unwrap().kind(),
            crate::Factorization::Svd
        );
    }
}
