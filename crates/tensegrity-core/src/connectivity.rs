//! Connectivity matrices C_b (β×n), C_s (α×n), C_r = ½|C_b| and the member matrices
//! B = N C_bᵀ, S = N C_sᵀ, R = N C_rᵀ.
//!
//! Convention (thesis eq. 2.3–2.4 with ERRATA 2.1–2.2): row k of C has −1 in the column of the
//! member's start node and +1 in the column of its end node, so column k of N Cᵀ is
//! `n_end − n_start`. Every row has exactly two non-zeros, so [`Incidence`] stores the pairs
//! and multiplies in O(members); dense matrices are available for inspection and tests.

use crate::structure::Structure;
use nalgebra::{DMatrix, Matrix3xX};

/// A sparse incidence matrix: row k is −1 at `pairs[k][0]`, +1 at `pairs[k][1]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Incidence {
    /// `[start, end]` of each row.
    pub pairs: Vec<[usize; 2]>,
    /// Number of columns (nodes).
    pub n_nodes: usize,
}

impl Incidence {
    /// The dense matrix (rows × nodes) with entries in {−1, 0, 1}.
    pub fn to_dense(&self) -> DMatrix<f64> {
        let mut c = DMatrix::zeros(self.pairs.len(), self.n_nodes);
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            c[(k, i)] = -1.0;
            c[(k, j)] = 1.0;
        }
        c
    }

    /// The dense ½|C| (bar centres R = N C_rᵀ).
    pub fn half_abs_dense(&self) -> DMatrix<f64> {
        let mut c = DMatrix::zeros(self.pairs.len(), self.n_nodes);
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            c[(k, i)] = 0.5;
            c[(k, j)] = 0.5;
        }
        c
    }

    /// N Cᵀ: column k is `n_end − n_start`.
    #[allow(non_snake_case)]
    pub fn member_vectors(&self, N: &Matrix3xX<f64>) -> Matrix3xX<f64> {
        let mut b = Matrix3xX::zeros(self.pairs.len());
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            b.set_column(k, &(N.column(j) - N.column(i)));
        }
        b
    }

    /// N C_rᵀ: column k is the midpoint of row k's two nodes.
    #[allow(non_snake_case)]
    pub fn midpoints(&self, N: &Matrix3xX<f64>) -> Matrix3xX<f64> {
        let mut r = Matrix3xX::zeros(self.pairs.len());
        for (k, &[i, j]) in self.pairs.iter().enumerate() {
            r.set_column(k, &(0.5 * (N.column(i) + N.column(j))));
        }
        r
    }
}

/// Bar and string incidence of a structure.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Connectivity {
    /// C_b (β×n).
    pub bars: Incidence,
    /// C_s (α×n).
    pub strings: Incidence,
}

impl Connectivity {
    /// Builds C_b and C_s from a structure.
    ///
    /// ```
    /// use tensegrity_core::{Bar, Connectivity, Structure};
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 1.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .build()
    ///     .unwrap();
    /// let c = Connectivity::of(&s);
    /// let b = c.B(&s.N());
    /// assert_eq!((b[(0, 0)], b[(1, 0)]), (2.0, 1.0));
    /// ```
    pub fn of(structure: &Structure) -> Self {
        let n = structure.n_nodes();
        Self {
            bars: Incidence {
                pairs: structure.bars().iter().map(|b| b.nodes).collect(),
                n_nodes: n,
            },
            strings: Incidence {
                pairs: structure.strings().iter().map(|s| s.nodes).collect(),
                n_nodes: n,
            },
        }
    }

    /// Dense C_b.
    #[allow(non_snake_case)]
    pub fn C_b(&self) -> DMatrix<f64> {
        self.bars.to_dense()
    }

    /// Dense C_s.
    #[allow(non_snake_case)]
    pub fn C_s(&self) -> DMatrix<f64> {
        self.strings.to_dense()
    }

    /// Dense C_r = ½|C_b|.
    #[allow(non_snake_case)]
    pub fn C_r(&self) -> DMatrix<f64> {
        self.bars.half_abs_dense()
    }

    /// Bar matrix B = N C_bᵀ.
    #[allow(non_snake_case)]
    pub fn B(&self, N: &Matrix3xX<f64>) -> Matrix3xX<f64> {
        self.bars.member_vectors(N)
    }

    /// String matrix S = N C_sᵀ.
    #[allow(non_snake_case)]
    pub fn S(&self, N: &Matrix3xX<f64>) -> Matrix3xX<f64> {
        self.strings.member_vectors(N)
    }

    /// Bar centres R = N C_rᵀ.
    #[allow(non_snake_case)]
    pub fn R(&self, N: &Matrix3xX<f64>) -> Matrix3xX<f64> {
        self.bars.midpoints(N)
    }
}
