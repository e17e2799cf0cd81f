//! The derivative of the prestress margin ([`Statics::prestressability`]) with respect to the node
//! positions, where it exists, and why it does not where it does not.
//!
//! The margin is the value of the linear programme
//!
//! > t*(x) = max t  s.t.  A(x) q = 0,  σ_k q_k ≥ t (every member),  |q_k| ≤ 1,
//!
//! over force densities q, with A(x) the equilibrium matrix of the free degrees of freedom at
//! node positions x and σ_k = +1 for a string, −1 for a bar. It is a property of the geometry
//! and the member kinds alone: **the prestress level and the members' stiffnesses do not enter
//! it**, so its derivatives with respect to them are exactly zero.
//!
//! **Node positions.** At an optimal vertex (q*, t*) with the members T whose σ_k q_k = t*
//! ("at the margin") and the members U whose |q_k| = 1 ("at the bound"), the Lagrangian
//!
//! > L = t + μᵀ A(x) q + Σ_T λ_k (σ_k q_k − t) + Σ_U ν_k (1 − s_k q_k),   s_k = sign q*_k,
//!
//! is stationary: Σ_T λ_k = 1 and Aᵀ μ = −g with g = Σ_T λ_k σ_k e_k − Σ_U ν_k s_k e_k. In
//! the coordinates z = (x, t) of an orthonormal self-stress basis V (q = V x) the active
//! constraints are G z = b, G the rows (σ_k V_k, −1) for T and (−s_k V_k, 0) for U, b = (0,
//! −1), and the multipliers solve Gᵀ (λ, ν) = (0, −1); μ is the least-squares solution of
//! Aᵀ μ = −g. By the envelope theorem
//!
//! > dt*/dx = ∂(μᵀ A(x) q*)/∂x,   μᵀ A q = Σ_k q_k (m_j − m_i) · (x_j − x_i),
//!
//! with m the nodal vectors of μ ([`crate::DofMap::expand`], zero at held directions), so
//! member k from node i to node j adds q*_k (m_j − m_i) to node j's gradient and its negative
//! to node i's (a held node's gradient is the effect of moving its support).
//!
//! **Where it exists.** The envelope formula is the derivative when the multipliers are unique
//! and positive, the slope is the same at every optimum, and the self-stress persists under
//! every node move:
//!
//! - G has full row rank (at most dim V + 1 active members) and every multiplier is positive.
//!   Symmetric structures tie: more members reach the margin (or the bound) at once than there
//!   are unknowns, and the margin is a minimum of several smooth functions, with a kink;
//!   [`MarginSmoothness::Tie`].
//! - Fewer active members than unknowns leave a face of optima (e.g. a bar held at each end by
//!   strings: the end that does not limit the margin may share its strings' forces in many
//!   ways). The margin is still differentiable when its slope is the same all over the face,
//!   ∂(μᵀ A q')/∂x = 0 for every direction q' of the face (null(G) with δt = 0, q'_k = 0 on
//!   the active members), else [`MarginSmoothness::NotUnique`].
//! - No mechanism m (left null vector of A) couples with the self-stress:
//!   ∂(mᵀ A q*)/∂x = 0 ([`COUPLING_TOLERANCE`]). A classic tensegrity (the Snelson prism, the
//!   expanded octahedron) holds its self-stress only on a special geometry, where a mechanism
//!   and the self-stress come together: a generic node move destroys it (the margin drops to
//!   0 once the move passes the rank tolerance), so it has no derivative at all
//!   ([`MarginSmoothness::SpecialGeometry`]). Rigid-body motions never couple. An overbraced
//!   structure (more members than the rank needs) keeps its self-stresses.
//! - t* > 0: at t* = 0 the constraint t ≥ 0 is active ([`MarginSmoothness::AtZero`]); a
//!   structure with no self-stress keeps none under small moves, and its margin is 0 with zero
//!   derivatives ([`MarginSmoothness::NoSelfStress`]).
//!
//! The optimum is polished from the interior-point solution ([`Statics::prestressability`]) by
//! projecting it on its active constraints G z = b, so the margin reported here agrees with
//! the LP's to its tolerance (1e-10) and is exact to round-off where it is differentiable
//! (central differences of it agree with the gradient to 2e-10 on the five structures of
//! `tests/margin.rs`).

use crate::{MemberSign, Statics, PRESTRESS_TOLERANCE};
use nalgebra::{DMatrix, DVector, Vector3};
use tensegrity_core::error::{ModelError, Result};
use tensegrity_core::structure::Structure;

/// A member counts as at the margin (or at the bound |q| = 1) within this distance.
pub const ACTIVE_TOLERANCE: f64 = 1e-7;

/// A multiplier at or below this counts as zero (a degenerate vertex).
pub const DEGENERATE_TOLERANCE: f64 = 1e-9;

/// A mechanism whose coupling with the self-stress (|∂(mᵀ A q*)/∂x| for a unit m and
/// max|q*| = 1, a singular value of the coupling matrix) is above this couples (module docs).
pub const COUPLING_TOLERANCE: f64 = 1e-6;

/// Whether the prestress margin is differentiable in the node positions, and why not when it
/// is not (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum MarginSmoothness {
    /// A unique, non-degenerate optimal self-stress that persists under node moves:
    /// [`MarginDerivative::nodes`] is the gradient.
    Differentiable,
    /// No self-stress: the margin is 0 near this geometry, with zero derivatives.
    NoSelfStress,
    /// A self-stress exists but no sign-consistent one: the margin sits at 0, where t ≥ 0 is
    /// active; it is not differentiable.
    AtZero,
    /// The multipliers are not unique or not positive: `at_margin` + `at_bound` active members
    /// for `unknowns` = dim V + 1 unknowns (more: a tie, typical of symmetric structures), or
    /// a zero multiplier. The margin has a kink here.
    Tie {
        /// How many members are at the margin.
        at_margin: usize,
        /// How many members are at the bound |q| = 1.
        at_bound: usize,
        /// dim V + 1.
        unknowns: usize,
    },
    /// The optimal self-stress is not unique (a face of optima, not a vertex) and the margin's
    /// slope differs along `directions` of the face: it has a kink here.
    NotUnique {
        /// How many directions of the optimal face change the slope.
        directions: usize,
    },
    /// The self-stress exists only on a special geometry: `mechanisms` mechanisms couple with
    /// it (the largest coupling `coupling`, relative), and a generic node move destroys it.
    SpecialGeometry {
        /// How many mechanisms couple.
        mechanisms: usize,
        /// The largest |∂(mᵀ A q*)/∂x| over unit mechanisms m, with max|q*| = 1.
        coupling: f64,
    },
}

/// The prestress margin with its derivatives (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct MarginDerivative {
    /// The margin t* ∈ [0, 1] (polished: exact at a vertex).
    pub margin: f64,
    /// The optimal self-stress q* (force densities, bars then strings), max|q*| = 1.
    pub stress: DVector<f64>,
    /// Whether [`Self::nodes`] is a derivative, and why not.
    pub smoothness: MarginSmoothness,
    /// The members at the margin (σ_k q*_k = t*): those that limit it.
    pub at_margin: Vec<usize>,
    /// The members at the bound |q*_k| = 1.
    pub at_bound: Vec<usize>,
    /// dt*/dx_i for every node (held ones too: moving a support); empty when not
    /// differentiable, zeros when there is no self-stress.
    pub nodes: Vec<Vector3<f64>>,
    /// dt*/dα for force densities scaled by a prestress level α: 0 (module docs).
    pub prestress_level: f64,
    /// dt*/da_k for each member's axial stiffness: 0 (module docs).
    pub axial_stiffnesses: Vec<f64>,
}

/// The prestress margin of `structure` (bars compressed, strings in tension) and its
/// derivatives with respect to the node positions, the prestress level and the members'
/// stiffnesses (module docs). Clusters are refused by name.
///
/// ```
/// use tensegrity_core::{Bar, StringMember, Structure, Support};
/// use tensegrity_statics::sensitivity::{prestress_margin, MarginSmoothness};
/// // a bar held at each end by three strings to pinned anchors towards its middle: seven
/// // members on six free dofs, one self-stress
/// let s = Structure::builder()
///     .nodes([
///         [0.0, 0.0, 0.0], [1.0, 0.1, 0.0],
///         [0.4, 1.0, 0.2], [0.45, -0.9, 0.5], [0.35, 0.1, -1.0],
///         [0.6, 1.1, -0.3], [0.55, -1.0, -0.4], [0.65, 0.2, 0.9],
///     ])
///     .bar(Bar::new(0, 1))
///     .string(StringMember::new(0, 2)).string(StringMember::new(0, 3))
///     .string(StringMember::new(0, 4)).string(StringMember::new(1, 5))
///     .string(StringMember::new(1, 6)).string(StringMember::new(1, 7))
///     .support(Support::pinned(2)).support(Support::pinned(3)).support(Support::pinned(4))
///     .support(Support::pinned(5)).support(Support::pinned(6)).support(Support::pinned(7))
///     .build()
///     .unwrap();
/// let d = prestress_margin(&s).unwrap();
/// assert_eq!(d.smoothness, MarginSmoothness::Differentiable);
/// assert!(d.margin > 0.0 && d.prestress_level == 0.0);
/// // moving everything together changes nothing: the gradients sum to zero
/// let total: nalgebra::Vector3<f64> = d.nodes.iter().sum();
/// assert!(total.norm() < 1e-12);
/// ```
pub fn prestress_margin(structure: &Structure) -> Result<MarginDerivative> {
    if !structure.clusters().is_empty() {
        return Err(ModelError::ClustersNotModelled {
            cluster: 0,
            analysis: "the prestress margin's derivative",
        }
        .into());
    }
    let m = structure.n_members();
    let statics = Statics::new(structure)?;
    let basis = statics.self_stress_basis();
    let d = basis.ncols();
    let mut out = MarginDerivative {
        margin: 0.0,
        stress: DVector::zeros(m),
        smoothness: MarginSmoothness::NoSelfStress,
        at_margin: Vec::new(),
        at_bound: Vec::new(),
        nodes: Vec::new(),
        prestress_level: 0.0,
        axial_stiffnesses: vec![0.0; m],
    };
    if d == 0 {
        out.nodes = vec![Vector3::zeros(); structure.n_nodes()];
        return Ok(out);
    }
    let sigma: Vec<f64> = MemberSign::standard(structure)
        .iter()
        .map(|s| s.sigma().unwrap_or(1.0))
        .collect();
    let lp = statics.prestressability()?;
    out.margin = lp.margin;
    out.stress = lp.stress.clone();
    if lp.margin <= PRESTRESS_TOLERANCE {
        out.smoothness = MarginSmoothness::AtZero;
        return Ok(out);
    }
    let q = &lp.stress;
    out.at_margin = (0..m)
        .filter(|&k| sigma[k] * q[k] <= lp.margin + ACTIVE_TOLERANCE)
        .collect();
    out.at_bound = (0..m)
        .filter(|&k| q[k].abs() >= 1.0 - ACTIVE_TOLERANCE)
        .collect();
    let coupled = coupling(&statics, q)?;
    if coupled.0 > 0 {
        out.smoothness = MarginSmoothness::SpecialGeometry {
            mechanisms: coupled.0,
            coupling: coupled.1,
        };
        return Ok(out);
    }
    let tie = MarginSmoothness::Tie {
        at_margin: out.at_margin.len(),
        at_bound: out.at_bound.len(),
        unknowns: d + 1,
    };
    let Some(opt) = optimum(&basis, &sigma, q, lp.margin, &out.at_margin, &out.at_bound)? else {
        out.smoothness = tie;
        return Ok(out);
    };
    out.margin = opt.t;
    // g = Σ_T λ σ e − Σ_U ν s e; Aᵀ μ = −g by the SVD of A
    let mut g = DVector::zeros(m);
    for (&k, l) in out.at_margin.iter().zip(&opt.lambda) {
        g[k] += l * sigma[k];
    }
    for (&k, v) in out.at_bound.iter().zip(&opt.nu) {
        g[k] -= v * opt.q[k].signum();
    }
    let mu = adjoint_multiplier(&statics, &(-g));
    // along the optimal face the slope must not change (module docs)
    let varying = opt
        .face
        .iter()
        .filter(|dq| {
            let grad = envelope_gradient(structure, &statics, dq, &mu);
            grad.iter().any(|v| v.amax() > COUPLING_TOLERANCE)
        })
        .count();
    out.stress = opt.q;
    if varying > 0 {
        out.smoothness = MarginSmoothness::NotUnique {
            directions: varying,
        };
        return Ok(out);
    }
    out.nodes = envelope_gradient(structure, &statics, &out.stress, &mu);
    out.smoothness = MarginSmoothness::Differentiable;
    Ok(out)
}

/// The optimum polished on its active constraints (module docs).
struct Optimum {
    /// A point of the optimal face (the interior-point solution projected on it), max|q| = 1.
    q: DVector<f64>,
    /// The margin.
    t: f64,
    /// The multipliers of the members at the margin.
    lambda: Vec<f64>,
    /// The multipliers of the members at the bound.
    nu: Vec<f64>,
    /// A basis of the optimal face's directions (force densities, q_k = 0 on every active
    /// member); empty at a vertex.
    face: Vec<DVector<f64>>,
}

/// The optimum of the margin LP on the active members (in the coordinates z = (x, t), q = V x,
/// the rows G: (σ_k V_k, −1) at the margin, (−s_k V_k, 0) at the bound, G z = (0, −1)): the
/// interior-point solution `q0`, `t0` projected on G z = b, the multipliers y from Gᵀ y = (0,
/// −1) and the face's directions, null(G) with δt = 0. `None` (a tie) when G is not of full
/// row rank (the multipliers are not unique), the projection moves far, the multipliers do not
/// solve Gᵀ y = (0, −1) or one is ≤ 0.
fn optimum(
    basis: &DMatrix<f64>,
    sigma: &[f64],
    q0: &DVector<f64>,
    t0: f64,
    at_margin: &[usize],
    at_bound: &[usize],
) -> Result<Option<Optimum>> {
    let d = basis.ncols();
    let n = d + 1;
    let r = at_margin.len() + at_bound.len();
    if r > n || at_margin.is_empty() {
        return Ok(None);
    }
    let mut g = DMatrix::zeros(r, n);
    let mut b = DVector::zeros(r);
    for (i, &k) in at_margin.iter().enumerate() {
        for j in 0..d {
            g[(i, j)] = sigma[k] * basis[(k, j)];
        }
        g[(i, d)] = -1.0;
    }
    for (i, &k) in at_bound.iter().enumerate() {
        let row = at_margin.len() + i;
        for j in 0..d {
            g[(row, j)] = -q0[k].signum() * basis[(k, j)];
        }
        b[row] = -1.0;
    }
    let svd = tensegrity_linalg::svd(&g)?;
    let top = svd.s.first().copied().unwrap_or(0.0);
    if svd.s.len() < r || svd.s[r - 1] <= 1e-10 * top {
        return Ok(None);
    }
    // G = U S Wᵀ (W: svd.v); G⁺ y = W_r S⁻¹ U_rᵀ y; the multipliers y = U S⁻¹ W_rᵀ c
    let pinv = |rhs: &DVector<f64>| {
        let mut z = DVector::zeros(n);
        for i in 0..r {
            z.axpy(svd.u.column(i).dot(rhs) / svd.s[i], &svd.v.column(i), 1.0);
        }
        z
    };
    let mut z0 = basis.transpose() * q0;
    z0 = z0.push(t0);
    let z = &z0 + pinv(&(&b - &g * &z0));
    let mut c = DVector::zeros(n);
    c[d] = -1.0;
    let mut y = DVector::zeros(r);
    for i in 0..r {
        y.axpy(svd.v.column(i).dot(&c) / svd.s[i], &svd.u.column(i), 1.0);
    }
    let q = basis * z.rows(0, d);
    let consistent = (g.transpose() * &y - &c).amax() <= 1e-8;
    let close = (&q - q0).amax() <= 1e3 * ACTIVE_TOLERANCE && z.iter().all(|v| v.is_finite());
    if !consistent || !close || y.iter().any(|&v| v.is_nan() || v <= DEGENERATE_TOLERANCE) {
        return Ok(None);
    }
    // the face: null([G; e_t])
    let mut stacked = g.clone().insert_row(r, 0.0);
    stacked[(r, d)] = 1.0;
    let face_svd = tensegrity_linalg::svd(&stacked)?;
    let tol = 1e-10 * face_svd.s.first().copied().unwrap_or(0.0);
    let rank = face_svd.s.iter().filter(|&&v| v > tol).count();
    let face = (rank..n)
        .map(|i| basis * face_svd.v.column(i).rows(0, d))
        .collect();
    let y: Vec<f64> = y.iter().copied().collect();
    Ok(Some(Optimum {
        q,
        t: z[d],
        lambda: y[..at_margin.len()].to_vec(),
        nu: y[at_margin.len()..].to_vec(),
        face,
    }))
}

/// The least-squares μ of Aᵀ μ = `rhs` by the SVD of A (A = U S Vᵀ: μ = Σ u_i (v_iᵀ rhs) / s_i
/// over the rank).
fn adjoint_multiplier(statics: &Statics<'_>, rhs: &DVector<f64>) -> DVector<f64> {
    let svd = &statics.svd;
    let mut mu = DVector::zeros(statics.a.nrows());
    for i in 0..statics.rank {
        let c = svd.v.column(i).dot(rhs) / svd.s[i];
        mu.axpy(c, &svd.u.column(i), 1.0);
    }
    mu
}

/// The gradient over the nodes of μᵀ A(x) q at fixed μ and q (module docs).
fn envelope_gradient(
    structure: &Structure,
    statics: &Statics<'_>,
    q: &DVector<f64>,
    mu: &DVector<f64>,
) -> Vec<Vector3<f64>> {
    let m_nodes = statics.dofs.expand(mu.as_slice());
    let mut grad = vec![Vector3::zeros(); structure.n_nodes()];
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let f = (m_nodes[j] - m_nodes[i]) * q[k];
        grad[j] += f;
        grad[i] -= f;
    }
    grad
}

/// How many independent mechanisms (left null vectors of A) couple with the self-stress `q`:
/// the rank of the coupling matrix whose row for the unit mechanism m is ∂(mᵀ A q)/∂x, and
/// its largest singular value (module docs).
fn coupling(statics: &Statics<'_>, q: &DVector<f64>) -> Result<(usize, f64)> {
    let motions = statics.motion_basis();
    if motions.ncols() == 0 {
        return Ok((0, 0.0));
    }
    let n = statics.structure.n_nodes();
    let mut c = DMatrix::zeros(motions.ncols(), 3 * n);
    for (r, w) in motions.column_iter().enumerate() {
        let grad = envelope_gradient(statics.structure, statics, q, &w.into_owned());
        for (i, g) in grad.iter().enumerate() {
            for a in 0..3 {
                c[(r, 3 * i + a)] = g[a];
            }
        }
    }
    let s = tensegrity_linalg::svd(&c)?.s;
    let coupled = s.iter().filter(|&&v| v > COUPLING_TOLERANCE).count();
    Ok((coupled, s.first().copied().unwrap_or(0.0)))
}
