//! The linear elastic response of a Cₙ-symmetric structure to a load on one node, block by
//! block.
//!
//! With member k of axial stiffness k_e (N/m, e.g. EA/L) and length L_e, small displacements
//! u of the free dofs stretch member e by (Aᵀu)_e / L_e, so its force is
//! t = diag(k/L) Aᵀ u and the elastic stiffness is K = A diag(k/L²) Aᵀ. When k and L are
//! constant on member orbits, K commutes with the group like A does, and in the unitary
//! symmetry-adapted bases of [`super::blocks`] (nodal Û, member Q̂) it splits into
//! K_k = A_k diag(k_E/L_E²) A_kᴴ, one Hermitian block per representation k. A load f on one
//! node has the coefficients f̂_k = Û_kᴴ f:
//!
//! - node σᵖ(r) off the axis, row (r, t): (1/√n) λᵖ (Rᵖ e_t)·f;
//! - node a on the axis, row w (an eigenvector of R): wᴴ f.
//!
//! Each block gives û_k = K_k⁻¹ f̂_k (Cholesky) and the member coefficients
//! t̂_k = diag(k_E/L_E) A_kᴴ û_k; the force of member πᵖ(e) of orbit E (size d) is the inverse
//! transform t = (1/√d) Σ_k t̂_{k,E} λ_k^{−p} over the blocks holding E. Block n − k is the
//! conjugate of block k (A and f are real), so only k = 0..⌊n/2⌋ are solved and the sum
//! takes 2 Re(·) of the others. Cost: O(n·b³) for the blocks (b the orbits of one block)
//! and O(n·members) for the transform, written as a direct sum (no FFT).

use super::blocks::{roots_of_unity, BlockContext, BlockRow};
use super::descriptor::CyclicSymmetry;
use nalgebra::{Complex, DMatrix, Vector3};
use tensegrity_core::error::{CoreError, FactorizationFailure, ModelError, NumericsError, Result};
use tensegrity_core::structure::Structure;

/// Relative spread of the stiffness over an orbit above which it is not symmetric.
const ORBIT_TOLERANCE: f64 = 1e-9;

/// The member forces (N, members × 3; column d for a unit load along axis d) of the linear
/// elastic structure with axial stiffnesses `stiffness` (N/m per member, constant on member
/// orbits) under a unit load on `node`, which must be free in every direction (see the
/// module documentation). A singular block (a mechanism) is
/// [`tensegrity_core::error::NumericsError::Factorization`].
pub fn elastic_response(
    structure: &Structure,
    symmetry: &CyclicSymmetry,
    stiffness: &[f64],
    node: usize,
) -> Result<DMatrix<f64>> {
    crate::cluster_columns::refuse_clusters_in(structure, "cyclic-symmetry block")?;
    check_inputs(structure, symmetry, stiffness, node)?;
    let n = symmetry.order();
    let ctx = BlockContext::new(structure, symmetry);
    let lengths = structure.member_lengths();
    let orbits = symmetry.member_orbits();
    let member_at = members_by_place(symmetry);
    let roots = roots_of_unity(n);
    let mut out = DMatrix::zeros(structure.n_members(), 3);
    for k in 0..=n / 2 {
        let layout = ctx.layout(k);
        let a = ctx.assemble(&layout);
        let k_over_l: Vec<f64> = layout
            .cols
            .iter()
            .map(|&e| stiffness[orbits[e].rep] / lengths[orbits[e].rep])
            .collect();
        let f = load_coefficients(symmetry, &layout.rows, node, &roots, k);
        let t_hat = block_forces(&a, &layout.cols, &lengths, orbits, &k_over_l, &f)?;
        let weight = if k == 0 || 2 * k == n { 1.0 } else { 2.0 };
        for (c, &e) in layout.cols.iter().enumerate() {
            let d = orbits[e].size;
            let scale = weight / (d as f64).sqrt();
            let t = [0, 1, 2].map(|dir| t_hat[(c, dir)] * scale);
            // λ_k^{−p} by stepping the root index back by k (mod n)
            let mut index = 0;
            for &member in &member_at[e] {
                let phase = roots[index];
                for (dir, tc) in t.iter().enumerate() {
                    out[(member, dir)] += tc.re * phase.re - tc.im * phase.im;
                }
                index = (index + n - k % n) % n;
            }
        }
    }
    Ok(out)
}

/// û = K_k⁻¹ f̂ and t̂ = diag(k/L) A_kᴴ û for one block (columns: the three load directions).
fn block_forces(
    a: &DMatrix<Complex<f64>>,
    cols: &[usize],
    lengths: &[f64],
    orbits: &[super::MemberOrbit],
    k_over_l: &[f64],
    f: &DMatrix<Complex<f64>>,
) -> Result<DMatrix<Complex<f64>>> {
    if a.nrows() == 0 {
        return Ok(DMatrix::zeros(cols.len(), 3));
    }
    let mut b = a.clone();
    for (c, &e) in cols.iter().enumerate() {
        let w = (k_over_l[c] / lengths[orbits[e].rep]).sqrt();
        b.column_mut(c).scale_mut(w);
    }
    let stiffness = &b * b.adjoint();
    let dim = stiffness.nrows();
    let chol = stiffness.cholesky().ok_or(NumericsError::Factorization {
        operation: "Cholesky of a cyclic stiffness block",
        reason: FactorizationFailure::NonPositivePivot { pivot: 0, dim },
    })?;
    let u = chol.solve(f);
    let mut t = a.adjoint() * u;
    for (c, mut row) in t.row_iter_mut().enumerate() {
        row.scale_mut(k_over_l[c]);
    }
    Ok(t)
}

/// f̂_k for unit loads along x, y, z on `node` (free rows of block k in layout order).
fn load_coefficients(
    symmetry: &CyclicSymmetry,
    rows: &[(BlockRow, bool)],
    node: usize,
    roots: &[Complex<f64>],
    k: usize,
) -> DMatrix<Complex<f64>> {
    let n = symmetry.order();
    let place = symmetry.node_places()[node];
    let eigs = super::blocks::axis_eigenvectors(symmetry);
    let free: Vec<&BlockRow> = rows.iter().filter(|r| r.1).map(|r| &r.0).collect();
    let rp = symmetry.rotation(place.phase);
    let lambda = roots[(k * place.phase) % n] / (n as f64).sqrt();
    DMatrix::from_fn(free.len(), 3, |i, d| match *free[i] {
        BlockRow::Orbit { orbit, dir } if orbit == place.orbit => lambda * rp[(d, dir)],
        BlockRow::Axis { node: a, eig } if a == node => eigs[eig].0[d].conj(),
        _ => Complex::new(0.0, 0.0),
    })
}

/// The member at (orbit, phase): `member_at[orbit][phase]`.
pub(crate) fn members_by_place(symmetry: &CyclicSymmetry) -> Vec<Vec<usize>> {
    let mut at: Vec<Vec<usize>> = symmetry
        .member_orbits()
        .iter()
        .map(|o| vec![usize::MAX; o.size])
        .collect();
    for (e, place) in symmetry.member_places().iter().enumerate() {
        at[place.orbit][place.phase] = e;
    }
    at
}

/// The stiffness list, the node and the symmetry of the stiffness.
fn check_inputs(
    structure: &Structure,
    symmetry: &CyclicSymmetry,
    stiffness: &[f64],
    node: usize,
) -> Result<()> {
    if stiffness.len() != structure.n_members() {
        return Err(ModelError::LengthMismatch {
            what: "axial stiffness of the members".into(),
            expected: structure.n_members(),
            found: stiffness.len(),
        }
        .into());
    }
    if let Some(&k) = stiffness.iter().find(|k| !(k.is_finite() && **k > 0.0)) {
        return Err(CoreError::invalid_parameter(
            "stiffness",
            k,
            "every axial stiffness must be finite and > 0",
        ));
    }
    let orbits = symmetry.member_orbits();
    for (e, place) in symmetry.member_places().iter().enumerate() {
        let rep = stiffness[orbits[place.orbit].rep];
        if (stiffness[e] - rep).abs() > ORBIT_TOLERANCE * rep {
            return Err(CoreError::invalid_parameter(
                "stiffness",
                stiffness[e],
                "the axial stiffness must be the same on every member of an orbit",
            ));
        }
    }
    let free = structure
        .fixed_dofs()
        .get(node)
        .is_some_and(|f| f.iter().all(|x| !x));
    if !free {
        return Err(CoreError::invalid_parameter(
            "node",
            node as f64,
            "the loaded node must exist and be free in every direction",
        ));
    }
    Ok(())
}

/// The group action on members: πᵖ(e), and the rotation of a member response (member
/// πᵖ(e) under a load on σᵖ(i) carries Rᵖ times what e carries under the load on i), used to
/// expand one computed response to every node of its orbit.
#[derive(Debug, Clone)]
pub struct MemberRotations<'a> {
    symmetry: &'a CyclicSymmetry,
    at: Vec<Vec<usize>>,
}

impl<'a> MemberRotations<'a> {
    /// The member table of `symmetry` (O(members)).
    pub fn new(symmetry: &'a CyclicSymmetry) -> Self {
        Self {
            symmetry,
            at: members_by_place(symmetry),
        }
    }

    /// πᵖ(e).
    pub fn member(&self, e: usize, p: usize) -> usize {
        let place = self.symmetry.member_places()[e];
        let d = self.symmetry.member_orbits()[place.orbit].size;
        self.at[place.orbit][(place.phase + p) % d]
    }

    /// The members of the orbit of e, by phase.
    pub fn orbit_of(&self, e: usize) -> &[usize] {
        &self.at[self.symmetry.member_places()[e].orbit]
    }

    /// The response of every member under the load rotated by p: out\[πᵖ(e)\] = Rᵖ r\[e\].
    pub fn rotate(&self, response: &[Vector3<f64>], p: usize) -> Vec<Vector3<f64>> {
        let rp = self.symmetry.rotation(p);
        let mut out = vec![Vector3::zeros(); response.len()];
        for (e, r) in response.iter().enumerate() {
            out[self.member(e, p)] = rp * r;
        }
        out
    }
}
