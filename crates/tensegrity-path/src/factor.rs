//! The tangent stiffness factored for solves: dense (LU, and the symmetric eigendecomposition
//! for the verdict) up to [`DENSE_MAX`] free coordinates; above, sparse — the Cholesky
//! factorisation when the tangent is positive definite (stable), else the sparse LU — so that
//! a path costs about the band of the structure per factorisation, not m³.
//!
//! On the sparse path the spectrum is not computed: the verdict is `stable` when the Cholesky
//! factorisation succeeds and `unstable` when it does not (a negative or zero pivot), with one
//! negative eigenvalue counted, so a bifurcation is reported where the tangent stops (or
//! starts) being positive definite, not at later crossings.

use crate::dofs::Dofs;
use crate::forces::MemberState;
use crate::model::ElasticModel;
use crate::stability::{spectrum, Spectrum, Stability};
use crate::tangent::tangent_triplets;
use nalgebra::{DMatrix, DVector};
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
    /// Sparse Cholesky: positive definite.
    Cholesky(Box<SparseCholesky>),
    /// Sparse LU: not positive definite.
    Lu(Box<SparseLu>),
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
        let m = dofs.len();
        let triplets = tangent_triplets(model, dofs, states);
        if m <= dense_max {
            let mut k = DMatrix::zeros(m, m);
            for (r, c, v) in triplets {
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
                return Some(Factored::Cholesky(Box::new(chol)));
            }
        }
        let full = CscMatrix::from_triplets(m, m, &triplets).ok()?;
        SparseLu::new(&full)
            .ok()
            .map(|lu| Factored::Lu(Box::new(lu)))
    }

    /// Solves K x = b; `None` when the dense LU finds K singular or the result is not finite.
    pub fn solve(&mut self, b: &DVector<f64>) -> Option<DVector<f64>> {
        let x = match self {
            Factored::Dense(lu, _) => lu.solve(b)?,
            Factored::Cholesky(chol) => {
                let mut x = b.as_slice().to_vec();
                chol.solve_in_place(&mut x);
                DVector::from_vec(x)
            }
            Factored::Lu(lu) => {
                let mut x = b.as_slice().to_vec();
                lu.solve_in_place(&mut x);
                DVector::from_vec(x)
            }
        };
        x.iter().all(|v| v.is_finite()).then_some(x)
    }

    /// The spectrum (dense) or the verdict of the factorisation (sparse: module docs).
    pub fn spectrum(&self) -> Spectrum {
        match self {
            Factored::Dense(_, k) => spectrum(k),
            Factored::Cholesky(_) => Spectrum {
                smallest: Vec::new(),
                negative: 0,
                below_zero: 0,
                mode: DVector::zeros(0),
                stability: Stability::Stable,
            },
            Factored::Lu(_) => Spectrum {
                smallest: Vec::new(),
                negative: 1,
                below_zero: 1,
                mode: DVector::zeros(0),
                stability: Stability::Unstable,
            },
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
            }))
            .chain((2..=n).map(|i| Support {
                node: i,
                directions: vec![Vector3::z()],
            }))
            .collect();
        let mut load = vec![Vector3::zeros(); n + 1];
        load[n] = Vector3::new(10.0, -5.0, 0.0);
        ElasticModel {
            nodes,
            members,
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
