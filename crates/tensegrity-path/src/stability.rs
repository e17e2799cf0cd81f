//! The stability verdict of an equilibrium from the eigenvalues of its tangent stiffness on
//! the free coordinates (crate docs): all above the zero tolerance, stable; one below minus
//! it, unstable (its eigenvector the mode); else neutral (a mechanism, to first order).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Eigenvalues within this fraction of the largest count as zero.
pub const ZERO_EIGENVALUE: f64 = 1e-10;

/// Free coordinates above which the eigenvalues are not computed (dense O(m³)).
pub const MAX_DENSE_EIGEN: usize = 3000;

/// The verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Stability {
    /// Every eigenvalue positive.
    Stable,
    /// A negative eigenvalue.
    Unstable,
    /// No negative eigenvalue, one near zero: a mechanism to first order.
    Neutral,
    /// Not computed (too many free coordinates).
    Unknown,
}

/// The tangent's spectrum at a point: its smallest eigenvalues, the number of negative ones,
/// the mode of the smallest, the verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Up to three smallest eigenvalues, ascending (N/m).
    pub smallest: Vec<f64>,
    /// How many are negative (below the zero tolerance).
    pub negative: usize,
    /// How many are below zero itself (no tolerance): where a crossing is located, to the
    /// round-off of the eigenvalues (≈ ε × the largest).
    pub below_zero: usize,
    /// The eigenvector of the eigenvalue of smallest magnitude (reduced coordinates).
    pub mode: DVector<f64>,
    /// The verdict.
    pub stability: Stability,
}

/// The spectrum of the symmetric tangent `k`; [`Stability::Unknown`] past
/// [`MAX_DENSE_EIGEN`] coordinates.
///
/// ```
/// use nalgebra::DMatrix;
/// use tensegrity_path::stability::{spectrum, Stability};
/// let s = spectrum(&DMatrix::from_diagonal(&nalgebra::dvector![3.0, -1.0, 2.0]));
/// assert_eq!((s.negative, s.stability), (1, Stability::Unstable));
/// assert_eq!(s.smallest, vec![-1.0, 2.0, 3.0]);
/// ```
pub fn spectrum(k: &DMatrix<f64>) -> Spectrum {
    let m = k.nrows();
    if m == 0 || m > MAX_DENSE_EIGEN {
        return Spectrum {
            smallest: Vec::new(),
            negative: 0,
            below_zero: 0,
            mode: DVector::zeros(m),
            stability: if m == 0 {
                Stability::Stable
            } else {
                Stability::Unknown
            },
        };
    }
    let sym = (k + k.transpose()) * 0.5;
    let eig = sym.symmetric_eigen();
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let largest = eig.eigenvalues.amax();
    let zero = ZERO_EIGENVALUE * largest;
    let negative = eig.eigenvalues.iter().filter(|&&v| v < -zero).count();
    let below_zero = eig.eigenvalues.iter().filter(|&&v| v < 0.0).count();
    let softest = (0..m)
        .min_by(|&a, &b| {
            eig.eigenvalues[a]
                .abs()
                .total_cmp(&eig.eigenvalues[b].abs())
        })
        .unwrap_or(0);
    let stability = if negative > 0 {
        Stability::Unstable
    } else if eig.eigenvalues[order[0]] <= zero {
        Stability::Neutral
    } else {
        Stability::Stable
    };
    Spectrum {
        smallest: order.iter().take(3).map(|&a| eig.eigenvalues[a]).collect(),
        negative,
        below_zero,
        mode: eig.eigenvectors.column(softest).into_owned(),
        stability,
    }
}
