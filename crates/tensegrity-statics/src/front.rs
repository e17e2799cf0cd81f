//! One statics front: what every factorisation of the equilibrium matrix answers.
//!
//! The equilibrium matrix A (free dofs × members, A q = w, q tension-positive force
//! densities) is factored by one of three back-ends:
//!
//! | back-end | factorisation | [`Factorization`] |
//! |---|---|---|
//! | [`Statics`](crate::Statics) | dense SVD A = U Σ Vᵀ | `Svd` |
//! | [`SparseStatics`](crate::SparseStatics) | rank-revealing sparse QR along the band | `SparseQr` |
//! | [`CyclicStatics`](crate::symmetry::CyclicStatics) | one SVD per Fourier block of a Cₙ-symmetric structure | `Cyclic` |
//!
//! Each answers, through [`StaticsBackend`]: rank r, self-stress dimension members − r,
//! mechanisms dofs − r, the rigid-body motions the supports allow and the internal mechanisms
//! (mechanisms − rigid-body motions), the rank tolerance and the smallest singular value,
//! whether its rank decision is certified ([`Certification`]), a self-stress basis
//! ([`SelfStressBasis`]: the whole space, or only the fully symmetric states for the cyclic
//! back-end), the prestressability margin LP with any member signs, the prestress-stability
//! test and the minimal-norm load solve. What a back-end cannot compute is the typed error
//! [`CoreError::Unsupported`] (the cyclic back-end: prestress stability and load solves, whose
//! stresses and loads need not be symmetric), never a silent approximation.
//!
//! The statics report is built once over this trait ([`super::report::report_from`]); the
//! back-end is chosen in `select`.

use super::load::LoadSolution;
use super::prestress::{MemberSign, Prestressability};
use super::stability::PrestressStability;
use super::symmetry::CyclicSymmetry;
use super::SpectralGap;
use nalgebra::{DMatrix, DVector, Matrix3xX};
use serde::Serialize;
use tensegrity_core::error::{CoreError, Result};
use tensegrity_core::structure::Structure;

/// Which factorisation answered (serialised as the report's `statics_method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Factorization {
    /// The dense SVD ([`Statics`](crate::Statics)).
    #[serde(rename = "svd")]
    Svd,
    /// The sparse rank-revealing QR ([`SparseStatics`](crate::SparseStatics)).
    #[serde(rename = "sparse_qr")]
    SparseQr,
    /// The symmetry-adapted blocks of a cyclic structure ([`CyclicStatics`](crate::symmetry::CyclicStatics)).
    #[serde(rename = "cyclic")]
    Cyclic,
}

impl Factorization {
    /// A name for messages.
    pub fn describe(self) -> &'static str {
        match self {
            Factorization::Svd => "dense SVD",
            Factorization::SparseQr => "sparse rank-revealing QR",
            Factorization::Cyclic => "cyclic (symmetry-adapted blocks)",
        }
    }

    /// The error of a back-end asked for `analysis`, which it does not compute.
    pub fn unsupported(self, analysis: &'static str) -> CoreError {
        CoreError::Unsupported {
            analysis,
            backend: self.describe(),
        }
    }
}

/// Whether a back-end's rank decision is certified.
#[derive(Debug, Clone, PartialEq)]
pub enum Certification {
    /// The rank decision is the dense SVD's at the same tolerance.
    Certified,
    /// It may differ from the dense SVD's; `reason` says why (numbers included).
    NotCertified {
        /// Why, for the report's `statics_warning`.
        reason: String,
    },
}

impl Certification {
    /// Whether certified.
    pub fn is_certified(&self) -> bool {
        matches!(self, Certification::Certified)
    }
}

/// A self-stress basis as a back-end gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum SelfStressBasis {
    /// An orthonormal basis of the whole self-stress space (members × dimension, bars
    /// first), oriented so that a one-dimensional basis is unique.
    Full(DMatrix<f64>),
    /// The fully symmetric self-stresses only (members × d₀, orthonormal, constant on member
    /// orbits) of a cyclic structure whose whole space has dimension `dim`.
    Symmetric {
        /// The basis, members × d₀.
        basis: DMatrix<f64>,
        /// The dimension of the whole self-stress space.
        dim: usize,
    },
    /// Not listed: the orthonormal basis of a large self-stress space (members × `dim`
    /// numbers above [`SELF_STRESS_LIST_MAX`](crate::sparse::SELF_STRESS_LIST_MAX)) would
    /// cost O(members·dim²) to build and dominate the report; `basis` has no column.
    Omitted {
        /// Members × 0.
        basis: DMatrix<f64>,
        /// The dimension of the self-stress space.
        dim: usize,
    },
}

impl SelfStressBasis {
    /// The columns held (the whole basis, or the symmetric part).
    pub fn matrix(&self) -> &DMatrix<f64> {
        match self {
            SelfStressBasis::Full(b)
            | SelfStressBasis::Symmetric { basis: b, .. }
            | SelfStressBasis::Omitted { basis: b, .. } => b,
        }
    }
}

/// What every statics back-end answers (see the module documentation).
pub trait StaticsBackend {
    /// Which factorisation this is.
    fn kind(&self) -> Factorization;

    /// The analysed structure.
    fn structure(&self) -> &Structure;

    /// The cyclic symmetry the back-end exploits (`None` but for the cyclic back-end).
    fn symmetry(&self) -> Option<&CyclicSymmetry> {
        None
    }

    /// Free degrees of freedom (rows of A).
    fn free_dofs(&self) -> usize;

    /// Rank of A.
    fn rank(&self) -> usize;

    /// Dimension of the self-stress space, columns (members and clusters) − rank.
    fn self_stress_dim(&self) -> usize {
        crate::n_columns(self.structure()) - self.rank()
    }

    /// First-order mechanisms, free dofs − rank (rigid-body motions included).
    fn mechanisms(&self) -> usize {
        self.free_dofs() - self.rank()
    }

    /// Rigid-body motions the supports allow.
    fn rigid_body_motions(&self) -> Result<usize>;

    /// Mechanisms beyond the rigid-body motions.
    fn internal_mechanisms(&self) -> Result<usize> {
        Ok(self.mechanisms().saturating_sub(self.rigid_body_motions()?))
    }

    /// The absolute rank tolerance τ (σ ≤ τ counts as zero).
    fn tolerance(&self) -> f64;

    /// The smallest singular value of A (an estimate for the sparse QR: see
    /// [`SparseStatics::smallest_singular_value_estimate`](crate::SparseStatics::smallest_singular_value_estimate)).
    fn smallest_singular_value(&self) -> f64;

    /// The singular values on either side of the tolerance behind the rank decision (the
    /// cyclic back-end: of the block with the narrowest gap; the sparse QR: the σ_min(R)
    /// estimate above and the rejected residual below).
    fn spectral_gap(&self) -> SpectralGap;

    /// Whether the rank decision is certified.
    fn certification(&self) -> Certification;

    /// A self-stress basis (the whole space, or the symmetric part for the cyclic back-end).
    fn self_stress(&self) -> SelfStressBasis;

    /// The prestressability margin LP (bars compressed, strings in tension).
    fn prestressability(&self) -> Result<Prestressability> {
        self.prestressability_with(&MemberSign::standard(self.structure()))
    }

    /// The margin LP with the given member signs.
    fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability>;

    /// The prestress-stability test with force densities `q`.
    fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability>;

    /// The minimal-norm solution of A q = w for a 3 × nodes force matrix.
    fn solve_nodal_forces(&self, w_nodes: &Matrix3xX<f64>) -> Result<LoadSolution>;

    /// The minimal-norm solution for the structure's own loads (nodal loads and bar weights).
    fn solve_loads(&self) -> Result<LoadSolution> {
        self.solve_nodal_forces(&self.structure().W())
    }
}
