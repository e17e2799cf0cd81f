//! Exact derivatives of the tangent stiffness's eigenvalues and of the natural frequencies
//! with respect to the force densities, the members' axial stiffnesses and the prestress
//! level (issue 47, item 3).
//!
//! The tangent stiffness ([`crate::stiffness`]) is K = Σ_k Bₖ ⊗ K_k on the free degrees of
//! freedom, K_k = a_k e_k e_kᵀ + q_k (I₃ − e_k e_kᵀ) for member k with axial stiffness a_k,
//! force density q_k and unit vector e_k, plus the springs of elastic supports. It is linear
//! in q and a, so for a member whose ends move by u_i and u_j under a vector of the free
//! degrees of freedom (expanded to the nodes, [`crate::DofMap::expand`]), d = u_j − u_i:
//!
//! > vᵀ (∂K/∂q_k) v = |d|² − (e_k · d)²,   vᵀ (∂K/∂a_k) v = (e_k · d)².
//!
//! **Node positions** enter through e_k = (x_j − x_i)/l_k alone at fixed q and a: member k's
//! share of the quadratic form, s_k = q_k |d|² + (a_k − q_k)(e_k · d)², has
//!
//! > ∂s_k/∂x_j = −∂s_k/∂x_i = 2 (a_k − q_k)(e_k · d)(d − (e_k · d) e_k) / l_k
//!
//! (a bar whose axial stiffness is E A / l changes a_k too: add ∂λ/∂a_k · ∂a_k/∂x, with
//! ∂a_k/∂x_j = −(a_k / l_k) e_k).
//!
//! **A simple eigenvalue** λ of K with unit eigenvector v (K v = λ v) has the derivative
//! dλ/dθ = vᵀ (∂K/∂θ) v; **a natural frequency** (K φ = ω² M φ, φ M-orthonormal, the lumped
//! mass of [`crate::stiffness::modal_analysis`], which q and a leave alone) dω²/dθ =
//! φᵀ (∂K/∂θ) φ and df/dθ = dω²/dθ / (8π² f) for f = ω / 2π. **The prestress level** α scales
//! the force densities, q = α q₀ at α = 1: dλ/dα = Σ_k q_k ∂λ/∂q_k.
//!
//! **Repeated eigenvalues** (within [`REPEATED_TOLERANCE`] of the largest |λ| of another) are
//! not differentiable — any combination of their eigenvectors is one, and the derivative
//! depends on the direction of the change: they are reported with their multiplicity and no
//! derivatives ([`EigenDerivative::multiplicity`]).
//!
//! **The prestress margin** is the value of a linear programme, a property of the geometry and
//! the member kinds: [`prestress_margin`] gives its derivative in the node positions by the
//! LP's multipliers where it has one (a unique, non-degenerate optimum whose self-stress
//! survives node moves), says why not where it has none, and gives zero for the prestress level
//! and the stiffnesses, which do not enter it ([`margin`]).
//!
//! Not covered yet: clustered strings (their blocks couple every node of the cluster); a
//! structure with clusters is refused by name.

pub mod margin;

pub use margin::{prestress_margin, MarginDerivative, MarginSmoothness};

use crate::stiffness::{axial_stiffness, lumped_masses, tangent_stiffness, ZERO_MODE_TOLERANCE};
use crate::DofMap;
use nalgebra::{DMatrix, DVector, Vector3};
use std::f64::consts::PI;
use tensegrity_core::error::{ModelError, Result};
use tensegrity_core::structure::Structure;
use tensegrity_linalg as linalg;

/// Two eigenvalues closer than this, relative to the largest |λ|, count as one repeated
/// eigenvalue (module docs).
pub const REPEATED_TOLERANCE: f64 = 1e-8;

/// An eigenvalue (or a natural frequency) and its derivatives (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct EigenDerivative {
    /// The eigenvalue λ (N/m), or the natural frequency f (Hz).
    pub value: f64,
    /// How many eigenvalues share it (module docs): 1 for a simple one, whose derivatives
    /// follow; more for a repeated one, which has none.
    pub multiplicity: usize,
    /// d value / d q_k, one per member (bars then strings); empty when repeated.
    pub force_densities: Vec<f64>,
    /// d value / d a_k, one per member's axial stiffness; empty when repeated.
    pub axial_stiffnesses: Vec<f64>,
    /// d value / d α for the force densities scaled by α at α = 1; `None` when repeated.
    pub prestress_level: Option<f64>,
    /// d value / d x_i of every node's position (held ones too: their members turn), at
    /// fixed force densities and axial stiffnesses; empty when repeated.
    pub nodes: Vec<Vector3<f64>>,
}

/// Refuses a structure with clusters, or `q` and `axial` of the wrong length.
fn check(structure: &Structure, q: &DVector<f64>, axial: &[f64]) -> Result<()> {
    let m = structure.n_members();
    if !structure.clusters().is_empty() {
        return Err(ModelError::ClustersNotModelled {
            cluster: 0,
            analysis: "the eigenvalue derivatives",
        }
        .into());
    }
    for (what, found) in [
        ("force densities", q.len()),
        ("axial stiffnesses", axial.len()),
    ] {
        if found != m {
            return Err(ModelError::LengthMismatch {
                what: what.to_string(),
                expected: m,
                found,
            }
            .into());
        }
    }
    Ok(())
}

/// The derivatives of a quadratic form: per q_k, per a_k, per α, per node.
type Quadratic = (Vec<f64>, Vec<f64>, f64, Vec<Vector3<f64>>);

/// The derivatives (module docs) of the quadratic form vᵀ K v along the free-dof vector `v`,
/// for axial stiffnesses `axial`, multiplied by `factor`.
fn quadratic(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    axial: &[f64],
    v: &[f64],
    factor: f64,
) -> Quadratic {
    let u = dofs.expand(v);
    let mut dq = Vec::with_capacity(q.len());
    let mut da = Vec::with_capacity(q.len());
    let mut dx = vec![Vector3::zeros(); structure.n_nodes()];
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.member_vector(k);
        let l = m.norm();
        let e = m / l;
        let d = u[j] - u[i];
        let ed = e.dot(&d);
        dq.push(factor * (d.norm_squared() - ed * ed));
        da.push(factor * ed * ed);
        let turn = (d - ed * e) * (2.0 * (axial[k] - q[k]) * ed / l * factor);
        dx[j] += turn;
        dx[i] -= turn;
    }
    let level = dq.iter().zip(q.iter()).map(|(g, q)| g * q).sum();
    (dq, da, level, dx)
}

/// How many of `values` (ascending) lie within [`REPEATED_TOLERANCE`] × max|λ| of `values[i]`.
fn multiplicity(values: &[f64], i: usize) -> usize {
    let top = values.iter().fold(0.0f64, |a, &w| a.max(w.abs()));
    let tol = REPEATED_TOLERANCE * top;
    values
        .iter()
        .filter(|&&w| (w - values[i]).abs() <= tol)
        .count()
}

/// The smallest nonzero eigenvalue of the tangent stiffness of `structure` (on the free
/// degrees of freedom of [`DofMap::stiffness_of`]: supports held, elastic ones as springs)
/// for force densities `q` and axial stiffnesses `axial` (one per member), with its
/// derivatives (module docs). "Nonzero": above [`ZERO_MODE_TOLERANCE`] × max|λ| in
/// magnitude (rigid-body motions the supports allow are zero; a negative eigenvalue, an
/// unstable direction, counts). `None` when every eigenvalue is zero.
///
/// ```
/// use nalgebra::DVector;
/// use tensegrity_core::{StringMember, Structure, Support};
/// use tensegrity_statics::sensitivity::smallest_stiffness_eigenvalue;
/// // a string of 100 N/m at q = 2 N/m from a pinned node to a free one: K = diag(100, 2, 2)
/// // on the free node, λ_min = q (repeated: y and z), then a
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .string(StringMember::new(0, 1).stiffness(100.0))
///     .support(Support::pinned(0))
///     .build()
///     .unwrap();
/// let q = DVector::from_element(1, 2.0);
/// let d = smallest_stiffness_eigenvalue(&s, &q, &[100.0]).unwrap().unwrap();
/// assert_eq!((d.value, d.multiplicity), (2.0, 2));
/// assert!(d.force_densities.is_empty());
/// ```
pub fn smallest_stiffness_eigenvalue(
    structure: &Structure,
    q: &DVector<f64>,
    axial: &[f64],
) -> Result<Option<EigenDerivative>> {
    check(structure, q, axial)?;
    let dofs = DofMap::stiffness_of(structure);
    let k = tangent_stiffness(structure, &dofs, q, axial);
    let (w, v) = linalg::symmetric_eigen(&k)?;
    let top = w.iter().fold(0.0f64, |a, &x| a.max(x.abs()));
    let Some(i) = (0..w.len()).find(|&i| w[i].abs() > ZERO_MODE_TOLERANCE * top) else {
        return Ok(None);
    };
    Ok(Some(derivative(
        structure, &dofs, q, axial, &w, &v, i, 1.0, w[i],
    )))
}

/// The derivative of eigenvalue `i` of `w` (eigenvectors `v`), each scaled by `factor` and
/// reported as `value` (module docs); none when it is repeated.
#[allow(clippy::too_many_arguments)]
fn derivative(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    axial: &[f64],
    w: &[f64],
    v: &DMatrix<f64>,
    i: usize,
    factor: f64,
    value: f64,
) -> EigenDerivative {
    let repeated = multiplicity(w, i);
    if repeated > 1 {
        return EigenDerivative {
            value,
            multiplicity: repeated,
            force_densities: Vec::new(),
            axial_stiffnesses: Vec::new(),
            prestress_level: None,
            nodes: Vec::new(),
        };
    }
    let column: Vec<f64> = v.column(i).iter().copied().collect();
    let (dq, da, level, dx) = quadratic(structure, dofs, q, axial, &column, factor);
    EigenDerivative {
        value,
        multiplicity: 1,
        force_densities: dq,
        axial_stiffnesses: da,
        prestress_level: Some(level),
        nodes: dx,
    }
}

/// The natural frequencies (Hz) of `structure` with force densities `q` and axial
/// stiffnesses `axial`, the lumped mass of [`crate::stiffness::modal_analysis`], ascending,
/// each with its derivatives (module docs; a zero or negative ω², a rigid-body motion or an
/// unstable mode, has frequency 0 and no derivatives, as does a repeated one). Every free
/// node needs mass.
///
/// ```
/// use nalgebra::DVector;
/// use tensegrity_core::{Bar, Material, Structure, Support};
/// use tensegrity_statics::sensitivity::natural_frequencies;
/// // a bar of axial stiffness a on a pinned node, 1 kg at each end: f = √(a / m_free) / 2π
/// // with m_free = 1 kg, and df/da = f / (2 a)
/// let s = Structure::builder()
///     .material("steel", Material::new(7800.0, 200e9, 500e6))
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(2.0).material("steel").radius(0.001))
///     .support(Support::pinned(0))
///     .support(Support::directions(1, [false, true, true]))
///     .build()
///     .unwrap();
/// let a = 1.0e4;
/// let f = natural_frequencies(&s, &DVector::zeros(1), &[a]).unwrap();
/// let expected = a.sqrt() / (2.0 * std::f64::consts::PI);
/// assert!((f[0].value - expected).abs() < 1e-12 * expected);
/// assert!((f[0].axial_stiffnesses[0] - expected / (2.0 * a)).abs() < 1e-12);
/// ```
pub fn natural_frequencies(
    structure: &Structure,
    q: &DVector<f64>,
    axial: &[f64],
) -> Result<Vec<EigenDerivative>> {
    check(structure, q, axial)?;
    let dofs = DofMap::stiffness_of(structure);
    let k = tangent_stiffness(structure, &dofs, q, axial);
    let masses = lumped_masses(structure);
    let mut scale = Vec::with_capacity(dofs.len());
    for &(node, _) in &dofs.free {
        if masses[node] <= 0.0 {
            return Err(ModelError::NoLumpedMass { node }.into());
        }
        scale.push(1.0 / masses[node].sqrt());
    }
    // M^(−½) K M^(−½) ψ = ω² ψ, φ = M^(−½) ψ (M-orthonormal)
    let n = dofs.len();
    let scaled = DMatrix::from_fn(n, n, |r, c| scale[r] * k[(r, c)] * scale[c]);
    let (w, psi) = linalg::symmetric_eigen(&scaled)?;
    let phi = DMatrix::from_fn(n, n, |r, c| scale[r] * psi[(r, c)]);
    let top = w.iter().fold(0.0f64, |a, &x| a.max(x.abs()));
    Ok((0..w.len())
        .map(|i| {
            if w[i] <= ZERO_MODE_TOLERANCE * top {
                // a rigid-body motion's ω² is round-off: its frequency is 0, as documented
                return EigenDerivative {
                    value: 0.0,
                    multiplicity: multiplicity(&w, i),
                    force_densities: Vec::new(),
                    axial_stiffnesses: Vec::new(),
                    prestress_level: None,
                    nodes: Vec::new(),
                };
            }
            let f = w[i].sqrt() / (2.0 * PI);
            // df = dω² / (8π² f)
            let factor = 1.0 / (8.0 * PI * PI * f);
            derivative(structure, &dofs, q, axial, &w, &phi, i, factor, f)
        })
        .collect())
}

/// A balance residual above this, relative to the largest member force or load, is a
/// state out of equilibrium ([`EquilibriumState::warning`]).
pub const EQUILIBRIUM_TOLERANCE: f64 = 1e-6;

/// The state the stiffness is differentiated about: the strings' force densities from their
/// rest lengths and stiffnesses, the bars' balancing them and the loads
/// ([`crate::stiffness::equilibrium_force_densities`]), the members' axial stiffnesses, and
/// how far from balance that leaves the nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct EquilibriumState {
    /// The force densities q (N/m), bars then strings.
    pub force_densities: DVector<f64>,
    /// The axial stiffnesses a (N/m).
    pub axial_stiffnesses: Vec<f64>,
    /// ‖A q − w‖ (N) on the free degrees of freedom.
    pub residual: f64,
    /// The residual relative to the largest member force |q_k| L_k or load.
    pub relative_residual: f64,
}

impl EquilibriumState {
    /// The state of `structure` (strings need rest lengths and stiffnesses; bars material
    /// and radius, or their errors name them).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Material, StringMember, Structure};
    /// use tensegrity_statics::sensitivity::EquilibriumState;
    /// // strings along a bar: 10 N/m in the strings, −5 N/m in the bar, balanced
    /// let build = |rest: f64| {
    ///     Structure::builder()
    ///         .material("steel", Material::new(7800.0, 200e9, 500e6))
    ///         .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///         .bar(Bar::new(0, 2).material("steel").radius(0.001))
    ///         .string(StringMember::new(0, 1).stiffness(100.0).rest_length(0.9))
    ///         .string(StringMember::new(1, 2).stiffness(100.0).rest_length(rest))
    ///         .build()
    ///         .unwrap()
    /// };
    /// let e = EquilibriumState::of(&build(0.9)).unwrap();
    /// assert!((e.force_densities[0] + 5.0).abs() < 1e-12 && e.warning().is_none());
    /// // unequal strings, 10 N and 20 N: the bar's best force, 15 N, leaves 5, 10 and 5 N
    /// // unbalanced at the three nodes
    /// let e = EquilibriumState::of(&build(0.8)).unwrap();
    /// assert!((e.residual - 150f64.sqrt()).abs() < 1e-9 && e.warning().is_some());
    /// ```
    pub fn of(structure: &Structure) -> Result<Self> {
        let (q, residual) = crate::stiffness::equilibrium_force_densities(structure)?;
        let axial = axial_stiffness(structure)?;
        let forces = (0..q.len()).map(|k| (q[k] * structure.member_vector(k).norm()).abs());
        let loads = structure
            .W()
            .column_iter()
            .map(|w| w.norm())
            .collect::<Vec<_>>();
        let scale = forces.chain(loads).fold(0.0f64, f64::max);
        let relative_residual = if scale > 0.0 {
            residual / scale
        } else {
            residual
        };
        Ok(Self {
            force_densities: q,
            axial_stiffnesses: axial,
            residual,
            relative_residual,
        })
    }

    /// Why derivatives about this state describe no equilibrium, when the relative residual
    /// passes [`EQUILIBRIUM_TOLERANCE`]: the rest lengths realise no self-stress the bars can
    /// balance (or the loads are not carried).
    pub fn warning(&self) -> Option<String> {
        (self.relative_residual > EQUILIBRIUM_TOLERANCE).then(|| {
            format!(
                "the strings' force densities from their rest lengths are not balanced by the bars and loads (residual {:.3e} N, {:.1e} of the largest force): the stiffness and its derivatives are those of a state out of equilibrium",
                self.residual, self.relative_residual
            )
        })
    }
}

/// [`smallest_stiffness_eigenvalue`] with the structure's own axial stiffnesses
/// ([`axial_stiffness`]: strings' k, bars' E·πr²/l).
pub fn smallest_stiffness_eigenvalue_of(
    structure: &Structure,
    q: &DVector<f64>,
) -> Result<Option<EigenDerivative>> {
    let axial = axial_stiffness(structure)?;
    smallest_stiffness_eigenvalue(structure, q, &axial)
}
