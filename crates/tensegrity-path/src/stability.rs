//! The stability verdict of an equilibrium from the eigenvalues of its tangent stiffness on
//! the free coordinates (crate docs): all above the zero tolerance, stable; one below minus
//! it, unstable (its eigenvector the mode); else neutral (a mechanism, to first order).
//!
//! Dense tangents are decomposed whole ([`spectrum`]); a large sparse one gives its
//! eigenvalues of smallest magnitude to [`smallest_by_inverse_iteration`], shift-invert
//! subspace iteration with its factorisation ([`crate::factor`]).

use nalgebra::{DMatrix, DVector};
use serde::Serialize;

/// Eigenvalues within this fraction of the largest count as zero.
pub const ZERO_EIGENVALUE: f64 = 1e-10;

/// Free coordinates above which the eigenvalues are not computed (dense O(m³)).
pub const MAX_DENSE_EIGEN: usize = 3000;

/// How many of the smallest eigenvalues a spectrum reports.
pub const SMALLEST: usize = 3;

/// The block of [`smallest_by_inverse_iteration`]: the [`SMALLEST`] wanted and as many guard
/// vectors, so that the wanted ones converge by the ratio of the third smallest eigenvalue to
/// the seventh per iteration.
pub const SUBSPACE: usize = 2 * SMALLEST;

/// The most iterations of [`smallest_by_inverse_iteration`].
pub const MAX_SUBSPACE_ITERATIONS: usize = 50;

/// The residual ‖K x − θ x‖ (x of unit length) at which a Ritz pair (θ, x) of
/// [`smallest_by_inverse_iteration`] has converged, relative to |θ|: θ is then within about
/// the square of this (times |θ|/gap) of an eigenvalue, x within this (times |θ|/gap) of its
/// eigenvector.
pub const RITZ_TOLERANCE: f64 = 1e-10;

/// The floor of that residual, relative to ‖K‖∞: where round-off in K x stops it (an
/// eigenvalue near zero, as at a fold).
pub const RITZ_FLOOR: f64 = 1e-13;

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
    /// Up to [`SMALLEST`] smallest eigenvalues, ascending (N/m): of a dense tangent the
    /// algebraically smallest, of a sparse one those of smallest magnitude
    /// ([`smallest_by_inverse_iteration`]; the same unless a negative eigenvalue lies farther
    /// from zero than the third positive one).
    pub smallest: Vec<f64>,
    /// How many are negative (below the zero tolerance); of a sparse tangent, how many of
    /// those found (none under its Cholesky factorisation, at least one under its LU).
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
    // a tangent that overflowed (a stiffness near the largest double) has no verdict
    let stability = if eig.eigenvalues.iter().any(|v| !v.is_finite()) {
        Stability::Unknown
    } else if negative > 0 {
        Stability::Unstable
    } else if eig.eigenvalues[order[0]] <= zero {
        Stability::Neutral
    } else {
        Stability::Stable
    };
    Spectrum {
        smallest: order
            .iter()
            .take(SMALLEST)
            .map(|&a| eig.eigenvalues[a])
            .collect(),
        negative,
        below_zero,
        mode: eig.eigenvectors.column(softest).into_owned(),
        stability,
    }
}

/// The eigenpairs of smallest magnitude of a large symmetric matrix
/// ([`smallest_by_inverse_iteration`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SmallestEigen {
    /// Up to [`SMALLEST`] eigenvalues of smallest magnitude, ascending (with their signs).
    pub values: Vec<f64>,
    /// The unit eigenvector of the one of smallest magnitude.
    pub mode: DVector<f64>,
    /// The iterations made (each [`SUBSPACE`] solves and products).
    pub iterations: usize,
    /// Whether every reported pair reached [`RITZ_TOLERANCE`] (else the iterations ran out
    /// and the values are the last Ritz values).
    pub converged: bool,
}

/// The [`SMALLEST`] eigenvalues of smallest magnitude of the symmetric m × m matrix K, and
/// the eigenvector of the smallest, by shift-invert subspace (block inverse) iteration:
/// X ← K⁻¹ X, orthonormalised (QR), then Rayleigh–Ritz — the eigenpairs of the small
/// XᵀKX, ordered by magnitude — until every wanted Ritz pair's residual is within
/// [`RITZ_TOLERANCE`] of its value (or [`RITZ_FLOOR`] of ‖K‖∞), at most
/// [`MAX_SUBSPACE_ITERATIONS`] times. K is given by its product `apply(x, y)` (y = K x), its
/// solve `solve(b)` (b ← K⁻¹ b, with a factorisation made anyway) and `norm`, its ∞-norm.
/// The start is a fixed pseudo-random block, so results repeat. K may be indefinite (the
/// ones nearest zero, either sign). `None` when a solve is not finite (K singular).
///
/// ```
/// use nalgebra::{dvector, DMatrix};
/// use tensegrity_path::stability::smallest_by_inverse_iteration;
/// let k = DMatrix::from_diagonal(&dvector![5.0, -0.5, 2.0, 40.0, 7.0, 9.0, 11.0, 13.0]);
/// let inv = k.clone().try_inverse().unwrap();
/// let found = smallest_by_inverse_iteration(
///     8,
///     40.0,
///     |x, y| y.copy_from_slice((&k * nalgebra::DVector::from_column_slice(x)).as_slice()),
///     |b| {
///         let x = &inv * nalgebra::DVector::from_column_slice(b);
///         b.copy_from_slice(x.as_slice())
///     },
/// )
/// .unwrap();
/// assert!(found.converged);
/// assert!((found.values[0] + 0.5).abs() < 1e-12 && (found.values[2] - 5.0).abs() < 1e-12);
/// assert!((found.mode[1].abs() - 1.0).abs() < 1e-12);
/// ```
pub fn smallest_by_inverse_iteration(
    m: usize,
    norm: f64,
    mut apply: impl FnMut(&[f64], &mut [f64]),
    mut solve: impl FnMut(&mut [f64]),
) -> Option<SmallestEigen> {
    let (b, wanted) = (SUBSPACE.min(m), SMALLEST.min(m));
    if m == 0 {
        return Some(SmallestEigen {
            values: Vec::new(),
            mode: DVector::zeros(0),
            iterations: 0,
            converged: true,
        });
    }
    // a fixed pseudo-random start (xorshift64*), uniform in [−1, 1)
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut x = DMatrix::from_fn(m, b, |_, _| {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        let r = seed.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        r as f64 / (1u64 << 52) as f64 - 1.0
    });
    let mut kq = DMatrix::zeros(m, b);
    let floor = RITZ_FLOOR * norm;
    let mut iteration = 0;
    loop {
        iteration += 1;
        for mut column in x.column_iter_mut() {
            solve(column.as_mut_slice());
        }
        if !x.iter().all(|v| v.is_finite()) {
            return None;
        }
        let q = x.clone().qr().q();
        for (column, mut image) in q.column_iter().zip(kq.column_iter_mut()) {
            apply(column.as_slice(), image.as_mut_slice());
        }
        let h = q.tr_mul(&kq);
        let eig = ((&h + h.transpose()) * 0.5).symmetric_eigen();
        let mut order: Vec<usize> = (0..b).collect();
        order.sort_by(|&i, &j| {
            eig.eigenvalues[i]
                .abs()
                .total_cmp(&eig.eigenvalues[j].abs())
        });
        let s = DMatrix::from_fn(b, b, |r, c| eig.eigenvectors[(r, order[c])]);
        x = &q * &s;
        let kx = &kq * &s;
        let values: Vec<f64> = order.iter().map(|&i| eig.eigenvalues[i]).collect();
        let converged = (0..wanted).all(|i| {
            let theta = values[i];
            let residual = (kx.column(i) - x.column(i) * theta).norm();
            residual <= RITZ_TOLERANCE * theta.abs() + floor
        });
        if converged || iteration >= MAX_SUBSPACE_ITERATIONS {
            let mut smallest = values[..wanted].to_vec();
            smallest.sort_by(f64::total_cmp);
            return Some(SmallestEigen {
                values: smallest,
                mode: x.column(0).into_owned(),
                iterations: iteration,
                converged,
            });
        }
    }
}
