//! The tangent stiffness factored for solves: dense (LU, and the symmetric eigendecomposition
//! for the verdict) up to [`DENSE_MAX`] free coordinates; above, sparse — the Cholesky
//! factorisation when the tangent is positive definite (stable), else the sparse LU — so that
//! a path costs about the band of the structure per factorisation, not m³.
//!
//! On the sparse path the verdict is that of the factorisation: `stable` when the Cholesky
//! factorisation succeeds, `unstable` when it does not (a negative or zero pivot). The
//! spectrum beside it — the [`SMALLEST`] eigenvalues of smallest magnitude, with their signs,
//! and the eigenvector of the smallest, the mode — comes from shift-invert subspace iteration
//! with that factorisation ([`smallest_by_inverse_iteration`]: blocks of [`SUBSPACE`] solves
//! and products, to a relative residual of [`RITZ_TOLERANCE`]). On the LU the negative ones
//! among them are counted (at least one), so a second eigenvalue crossing zero is seen —
//! it crosses among the smallest in magnitude — but a count of two or more may also drop
//! where a negative eigenvalue grows past the [`SMALLEST`] nearest zero. The zero tolerance
//! of that count is [`ZERO_EIGENVALUE`] of ‖K‖∞ (an upper bound of the largest eigenvalue,
//! of which the dense path takes it); `neutral` is not reported. Limit points and
//! bifurcations on sparse tangents carry the mode as on dense ones ([`crate::arclength`]).
//!
//! Cost, measured (release build, two shared cores; `tensegrity solve t.toml --load-steps
//! 10` on the towers of `scripts/truss-tower`, 11 spectra): 999 free coordinates (111
//! stages), 5 iterations a point, 1.7 ms a spectrum, about 17 % of the whole run (0.10–0.15 s,
//! 0.09–0.16 s before); 9,999 (1111 stages), 3 iterations, 11–14 ms a spectrum, about 10 %
//! (1.3–1.4 s, 1.2–1.9 s before: within the noise). The arc-length path costs alike per
//! point. A clustered spectrum — the third eigenvalue nearest zero close to the seventh —
//! converges slowly, up to [`MAX_SUBSPACE_ITERATIONS`] (18 on a row of 101 two-bar trusses of
//! six heights, 12–43 along the path of a row of 100 alike and one lower,
//! `tests/sparse_spectrum.rs`); past them the values reached are reported.

use crate::dofs::Dofs;
use crate::forces::MemberState;
use crate::model::ElasticModel;
use crate::stability::{
    smallest_by_inverse_iteration, spectrum, Spectrum, Stability, ZERO_EIGENVALUE,
};
#[cfg(doc)]
use crate::stability::{MAX_SUBSPACE_ITERATIONS, RITZ_TOLERANCE, SMALLEST, SUBSPACE};
use crate::tangent::tangent_triplets;
use nalgebra::{DMatrix, DVector};
use std::sync::{Mutex, PoisonError};
use tensegrity_linalg::{CscMatrix, SparseCholesky, SparseLu};

/// Free coordinates above which the tangent is sparse.
pub const DENSE_MAX: usize = 200;

/// A factored tangent.
pub enum Factored {
    /// Dense LU (and the matrix, for the spectrum).
    Dense(
        nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
        DMatrix<f64>,
    ),
    /// Sparse Cholesky: positive definite (beside it the matrix's lower triangle).
    Cholesky(Box<Sparse<SparseCholesky>>),
    /// Sparse LU: not positive definite (beside it the whole matrix).
    Lu(Box<Sparse<SparseLu>>),
}

/// A sparse factorisation beside the matrix it factors, whose products the spectrum needs
/// ([`Factored::spectrum`]); the factorisation's solves need its workspace, held in a lock so
/// that the spectrum can be taken from a shared reference.
pub struct Sparse<F> {
    factor: Mutex<F>,
    matrix: CscMatrix,
}

impl<F> Sparse<F> {
    /// The matrix: its lower triangle under a Cholesky factorisation, all of it under an LU.
    pub fn matrix(&self) -> &CscMatrix {
        &self.matrix
    }
}

/// The solve of a sparse factorisation.
trait SolveInPlace {
    fn solve_in_place(&mut self, b: &mut [f64]);
}

impl SolveInPlace for SparseCholesky {
    fn solve_in_place(&mut self, b: &mut [f64]) {
        SparseCholesky::solve_in_place(self, b)
    }
}

impl SolveInPlace for SparseLu {
    fn solve_in_place(&mut self, b: &mut [f64]) {
        SparseLu::solve_in_place(self, b)
    }
}

/// Solves K x = b with a sparse factorisation.
fn sparse_solve<F: SolveInPlace>(sparse: &mut Sparse<F>, b: &DVector<f64>) -> DVector<f64> {
    let mut x = b.as_slice().to_vec();
    sparse
        .factor
        .get_mut()
        .unwrap_or_else(PoisonError::into_inner)
        .solve_in_place(&mut x);
    DVector::from_vec(x)
}

/// The eigenvalues of smallest magnitude and the mode, by shift-invert subspace iteration
/// with the factorisation (module docs); `definite` under a Cholesky factorisation.
fn sparse_spectrum<F: SolveInPlace>(sparse: &Sparse<F>, definite: bool) -> Spectrum {
    let lower = definite;
    let norm = infinity_norm(&sparse.matrix, lower);
    let mut factor = sparse.factor.lock().unwrap_or_else(PoisonError::into_inner);
    let found = smallest_by_inverse_iteration(
        sparse.matrix.pattern().ncols(),
        norm,
        |x, y| multiply(&sparse.matrix, lower, x, y),
        |b| factor.solve_in_place(b),
    );
    let (smallest, mode) = found.map_or_else(
        || (Vec::new(), DVector::zeros(0)),
        |found| (found.values, found.mode),
    );
    if definite {
        return Spectrum {
            smallest,
            negative: 0,
            below_zero: 0,
            mode,
            stability: Stability::Stable,
        };
    }
    let zero = ZERO_EIGENVALUE * norm;
    Spectrum {
        negative: smallest.iter().filter(|&&v| v < -zero).count().max(1),
        below_zero: smallest.iter().filter(|&&v| v < 0.0).count().max(1),
        smallest,
        mode,
        stability: Stability::Unstable,
    }
}

/// y = K x for the symmetric K stored whole, or (`lower`) by its lower triangle.
fn multiply(k: &CscMatrix, lower: bool, x: &[f64], y: &mut [f64]) {
    y.fill(0.0);
    let (ptr, rows, values) = (k.pattern().col_ptr(), k.pattern().row_idx(), k.values());
    for (j, &xj) in x.iter().enumerate() {
        for slot in ptr[j]..ptr[j + 1] {
            let (i, v) = (rows[slot], values[slot]);
            y[i] += v * xj;
            if lower && i != j {
                y[j] += v * x[i];
            }
        }
    }
}

/// max_i Σ_j |K_ij| of the symmetric K stored whole, or (`lower`) by its lower triangle: an
/// upper bound of its largest eigenvalue's magnitude.
fn infinity_norm(k: &CscMatrix, lower: bool) -> f64 {
    let mut sums = vec![0.0; k.pattern().nrows()];
    let (ptr, rows, values) = (k.pattern().col_ptr(), k.pattern().row_idx(), k.values());
    for j in 0..k.pattern().ncols() {
        for slot in ptr[j]..ptr[j + 1] {
            let (i, v) = (rows[slot], values[slot].abs());
            sums[i] += v;
            if lower && i != j {
                sums[j] += v;
            }
        }
    }
    sums.into_iter().fold(0.0, f64::max)
}

impl std::fmt::Debug for Factored {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let kind = match self {
            Factored::Dense(..) => "dense",
            Factored::Cholesky(_) => "sparse Cholesky",
            Factored::Lu(_) => "sparse LU",
        };
        f.write_str(kind)
    }
}

impl Factored {
    /// The tangent of `states` on the free coordinates of `dofs`, factored; `None` when it is
    /// singular (a sparse LU that fails).
    pub fn of(model: &ElasticModel, dofs: &Dofs, states: &[MemberState]) -> Option<Self> {
        Self::with_dense_max(model, dofs, states, DENSE_MAX)
    }

    /// [`Factored::of`] with the dense path up to `dense_max` free coordinates.
    pub fn with_dense_max(
        model: &ElasticModel,
        dofs: &Dofs,
        states: &[MemberState],
        dense_max: usize,
    ) -> Option<Self> {
        Self::from_triplets(
            dofs.len(),
            &tangent_triplets(model, dofs, states),
            dense_max,
        )
    }

    /// A symmetric m × m matrix given as (row, column, value) triplets (both triangles,
    /// repeated entries summed), factored as [`Factored::of`] factors the tangent: dense up
    /// to `dense_max`, else sparse Cholesky, or sparse LU when it is not positive definite
    /// (the implicit dynamics' K + (4/h²) M, [`crate::newmark`]).
    pub fn from_triplets(
        m: usize,
        triplets: &[(usize, usize, f64)],
        dense_max: usize,
    ) -> Option<Self> {
        if m <= dense_max {
            let mut k = DMatrix::zeros(m, m);
            for &(r, c, v) in triplets {
                k[(r, c)] += v;
            }
            return Some(Factored::Dense(k.clone().lu(), k));
        }
        let lower: Vec<(usize, usize, f64)> = triplets
            .iter()
            .copied()
            .filter(|&(r, c, _)| r >= c)
            .collect();
        let lower = CscMatrix::from_triplets(m, m, &lower).ok()?;
        if let Ok(mut chol) = SparseCholesky::new(lower.pattern()) {
            if chol.factor(lower.values()).is_ok() {
                return Some(Factored::Cholesky(Box::new(Sparse {
                    factor: Mutex::new(chol),
                    matrix: lower,
                })));
            }
        }
        let full = CscMatrix::from_triplets(m, m, triplets).ok()?;
        let lu = SparseLu::new(&full).ok()?;
        Some(Factored::Lu(Box::new(Sparse {
            factor: Mutex::new(lu),
            matrix: full,
        })))
    }

    /// Solves K x = b; `None` when the dense LU finds K singular or the result is not finite.
    pub fn solve(&mut self, b: &DVector<f64>) -> Option<DVector<f64>> {
        let x = match self {
            Factored::Dense(lu, _) => lu.solve(b)?,
            Factored::Cholesky(chol) => sparse_solve(chol, b),
            Factored::Lu(lu) => sparse_solve(lu, b),
        };
        x.iter().all(|v| v.is_finite()).then_some(x)
    }

    /// The spectrum: dense, all eigenvalues; sparse, the verdict of the factorisation and
    /// the eigenvalues of smallest magnitude by shift-invert iteration with it (module docs).
    pub fn spectrum(&self) -> Spectrum {
        match self {
            Factored::Dense(_, k) => spectrum(k),
            Factored::Cholesky(chol) => sparse_spectrum(chol, true),
            Factored::Lu(lu) => sparse_spectrum(lu, false),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::forces::member_states;
    use crate::model::{ElasticMember, MemberKind, Support};
    use nalgebra::Vector3;

    /// A chain of `n` bars zig-zagging in the plane z = 0 (held in z), pinned at its first node,
    /// pulled at its last: a tangent of 2n free coordinates, positive definite.
    fn chain(n: usize) -> ElasticModel {
        let nodes: Vec<Vector3<f64>> = (0..=n)
            .map(|i| Vector3::new(i as f64, (i % 2) as f64 * 0.5, 0.0))
            .collect();
        let mut members: Vec<ElasticMember> = (0..n)
            .map(|i| ElasticMember {
                nodes: [i, i + 1],
                kind: MemberKind::Bar,
                ea: 1e4 * (1.0 + i as f64 * 0.01),
                rest_length: (nodes[i + 1] - nodes[i]).norm(),
            })
            .collect();
        // braces two apart make it a truss
        members.extend((0..n - 1).map(|i| ElasticMember {
            nodes: [i, i + 2],
            kind: MemberKind::Bar,
            ea: 5e3,
            rest_length: (nodes[i + 2] - nodes[i]).norm(),
        }));
        let supports = std::iter::once(Support::pinned(0))
            .chain(std::iter::once(Support {
                node: 1,
                directions: vec![Vector3::y(), Vector3::z()],
                stiffness: None,
            }))
            .chain((2..=n).map(|i| Support {
                node: i,
                directions: vec![Vector3::z()],
                stiffness: None,
            }))
            .collect();
        let mut load = vec![Vector3::zeros(); n + 1];
        load[n] = Vector3::new(10.0, -5.0, 0.0);
        ElasticModel {
            nodes,
            members,
            clusters: Vec::new(),
            supports,
            load,
            drivers: Default::default(),
        }
        .validated()
        .unwrap()
    }

    /// The sparse Cholesky and LU solve the system as the dense LU does (backward error at
    /// round-off: this slender chain's tangent is ill-conditioned, so solutions are compared
    /// by their residuals), and the Cholesky's verdict is the spectrum's: positive definite
    /// at rest, not once every bar is compressed past buckling.
    #[test]
    fn the_sparse_factorisations_agree_with_the_dense_one() {
        let model = chain(150);
        let dofs = Dofs::of(&model).unwrap();
        let states = member_states(&model, &model.nodes, 0.0);
        let b = dofs.reduce(&model.load);
        let mut dense = Factored::with_dense_max(&model, &dofs, &states, usize::MAX).unwrap();
        let mut sparse = Factored::with_dense_max(&model, &dofs, &states, 0).unwrap();
        assert!(matches!(sparse, Factored::Cholesky(_)), "{sparse:?}");
        let k = crate::tangent::tangent_stiffness(&model, &dofs, &states);
        let backward = |x: &DVector<f64>| (&k * x - &b).amax() / (k.amax() * x.amax());
        let (x, y) = (dense.solve(&b).unwrap(), sparse.solve(&b).unwrap());
        assert!(
            backward(&x) < 1e-14 && backward(&y) < 1e-14,
            "{} {}",
            backward(&x),
            backward(&y)
        );
        assert_eq!(dense.spectrum().stability, Stability::Stable);
        assert_eq!(sparse.spectrum().stability, Stability::Stable);
        // and its spectrum beside the verdict: three eigenvalues and the mode
        let (d, e) = (dense.spectrum(), sparse.spectrum());
        assert_eq!((e.smallest.len(), e.mode.len()), (3, dofs.len()));
        for (a, b) in d.smallest.iter().zip(&e.smallest) {
            assert!(
                (a - b).abs() < 1e-6 * b,
                "{:?} {:?}",
                d.smallest,
                e.smallest
            );
        }
        // a compressed state whose geometric stiffness wins: tensions −10⁶ N on every member
        let squeezed: Vec<MemberState> = states
            .iter()
            .map(|s| MemberState {
                tension: -1e6,
                ..*s
            })
            .collect();
        let mut dense = Factored::with_dense_max(&model, &dofs, &squeezed, usize::MAX).unwrap();
        let mut sparse = Factored::with_dense_max(&model, &dofs, &squeezed, 0).unwrap();
        assert_eq!(dense.spectrum().stability, Stability::Unstable);
        assert!(matches!(sparse, Factored::Lu(_)), "{sparse:?}");
        assert_eq!(sparse.spectrum().stability, Stability::Unstable);
        assert!(sparse.spectrum().negative >= 1);
        let k = crate::tangent::tangent_stiffness(&model, &dofs, &squeezed);
        let backward = |x: &DVector<f64>| (&k * x - &b).amax() / (k.amax() * x.amax());
        let (x, y) = (dense.solve(&b).unwrap(), sparse.solve(&b).unwrap());
        assert!(
            backward(&x) < 1e-13 && backward(&y) < 1e-13,
            "{} {}",
            backward(&x),
            backward(&y)
        );
    }
}
