//! The force density method.
//!
//! With force densities q (tension-positive, one per member, bars then strings) and the
//! incidence matrix C (row k: −1 at the member's start node, +1 at its end node) the force
//! density matrix is D = Cᵀ diag(q) C (n × n, symmetric, rows summing to zero). Nodal
//! equilibrium without loads reads D X = 0 for the n × 3 coordinate matrix X = Nᵀ.
//!
//! **Free-standing** (no fixed nodes): X lies in the null space of D. The constant vector is
//! always in it; a 3-D geometry needs rank deficiency ≥ d + 1 = 4 (rank deficiency 3 gives a
//! planar form, like the X-module, in the plane z = 0 of the canonical normalisation; less
//! is [`FormFindError::RankDeficiency`]). Any affine image of an
//! equilibrium is again one, so the geometry is fixed by a normalisation:
//!
//! - with initial `nodes`, the null-space geometry closest to them in least squares:
//!   X = Φ Φᵀ X₀ for an orthonormal null-space basis Φ (dense path). When the null space is
//!   exactly 4-dimensional this is the affine image of any equilibrium closest to X₀, which is
//!   also what the sparse path computes (below);
//! - without them (or when that projection is flat), the canonical form: centroid at the
//!   origin, the three (two for a planar form) non-constant null-space directions with the
//!   largest spread, taken
//!   orthonormal (equal second moments), rotated to the principal axes of the bar vectors
//!   (Σ b bᵀ, largest first) with the first significant coordinate of each axis positive,
//!   scaled to a mean bar length of 1, and mirrored in z if needed so that the first four
//!   affinely independent nodes (in index order) form a positively oriented tetrahedron.
//!
//! The null space of a topology of up to [`DENSE_MAX_NODES`] nodes comes from the symmetric
//! eigendecomposition of D: eigenvalues |λ| ≤ [`NULL_SPACE_TOLERANCE`] · max|λ| count as zero.
//! Larger topologies never form D densely: four affinely independent anchor nodes are held at
//! their initial positions, the sparse system D_ff X_f = −D_fa X_a is solved by sparse LU, the
//! anchors' own rows of D X are checked to vanish (which proves rank deficiency ≥ 4), and the
//! affine map closest in least squares to the initial nodes is applied.
//!
//! **Fixed nodes**: the free coordinates solve D_ff X_f = −D_fx X_x: by sparse Cholesky
//! (AMD ordering) where D_ff is positive definite — every force density positive, or bars
//! braced by enough strings, as in the built-in grid — else by sparse LU (D_ff indefinite).
//!
//! **Loads** (fixed nodes only; a free-standing topology with loads is refused, see
//! [`crate::Topology`]): with point loads P (one row per node, summed over the `loads` on it)
//! the equilibrium of node i is Σ_j q_ij (x_j − x_i) + p_i + r_i = 0, r_i the reaction, zero
//! at a free node. The free coordinates solve
//!
//! D_ff X_f = P_f − D_fx X_x,
//!
//! and the reaction at a held node is r_i = (D X)_i − p_i (a load on a held node goes straight
//! into its reaction). The force densities are physical here (N/m, loads in N): the form
//! changes when q is scaled, unlike the unloaded one. q and P are divided by max|q| for the
//! solve (the same X), so force densities near the largest double do not overflow D.
//!
//! **Self-weight**: a member of weight w per length (N/m, its own `weight` or its group's)
//! adds w L / 2 along −z at each end node, L its length in the found form. The loads then
//! depend on X, so X is the fixed point of X ↦ solve(P(X)), started from the form under the
//! point loads alone, with D_ff factored once: it stops when the largest change of a node
//! coordinate is at most `tolerance` (the settings', default 10⁻¹²) times the form's size (the
//! diagonal of its bounding box), and fails with [`FormFindError::NotConverged`] after
//! `max_iterations`. The map contracts when the weights' change with the geometry is small
//! against the force densities (a light net, taut strings); a net whose weight dominates its
//! force densities may not converge — raise the force densities. The reported loads are
//! P(X) at the returned X.

use crate::error::{FormFindError, Result};
use crate::method::Settings;
use crate::topology::Topology;
use nalgebra::{DMatrix, Matrix3, Matrix4, Vector3, Vector4};
use tensegrity_linalg::{self as linalg, CscMatrix, SparseCholesky, SparseLu};

/// Relative tolerance of the null space of D: |λ| ≤ tol · max|λ| counts as zero.
pub const NULL_SPACE_TOLERANCE: f64 = 1e-9;

/// Free-standing topologies up to this many nodes take the dense eigendecomposition of D;
/// larger ones the sparse anchored solve.
pub const DENSE_MAX_NODES: usize = 1200;

/// Largest error of the test solve D_ff y = D_ff z (|z| ≤ 1) before D_ff counts as singular.
pub(crate) const SINGULARITY_TOLERANCE: f64 = 1e-6;

/// Relative tolerance of a linear solve's residual, ‖D X‖ ≤ tol · ‖D‖ · ‖X‖.
pub(crate) const SOLVE_TOLERANCE: f64 = 1e-8;

/// The force density matrix D = Cᵀ diag(q) C of `topology` (n × n, both triangles stored),
/// for force densities `q` (bars then strings).
///
/// ```
/// use formfind::{force_density_matrix, Member, Topology};
/// let t = Topology {
///     n_nodes: 2,
///     strings: vec![Member::new(0, 1)],
///     ..Default::default()
/// };
/// let d = force_density_matrix(&t, &[2.0]).unwrap();
/// assert_eq!(d.mul_vec(&[1.0, 0.0]), vec![2.0, -2.0]);
/// ```
pub fn force_density_matrix(topology: &Topology, q: &[f64]) -> Result<CscMatrix> {
    if q.len() != topology.n_members() {
        return Err(FormFindError::InvalidTopology {
            item: "force_density".into(),
            reason: format!(
                "{} force densities for {} members",
                q.len(),
                topology.n_members()
            ),
        });
    }
    let mut t = Vec::with_capacity(4 * q.len());
    for (&[i, j], &qk) in topology.member_nodes().iter().zip(q) {
        t.extend_from_slice(&[(i, i, qk), (j, j, qk), (i, j, -qk), (j, i, -qk)]);
    }
    Ok(CscMatrix::from_triplets(
        topology.n_nodes,
        topology.n_nodes,
        &t,
    )?)
}

/// D as a dense matrix (small topologies only).
pub(crate) fn dense_matrix(pairs: &[[usize; 2]], q: &[f64], n: usize) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(n, n);
    for (&[i, j], &qk) in pairs.iter().zip(q) {
        d[(i, i)] += qk;
        d[(j, j)] += qk;
        d[(i, j)] -= qk;
        d[(j, i)] -= qk;
    }
    d
}

/// The geometry of the force density method for force densities `q`. The geometry does not
/// change when q is scaled, so it is found for q / max|q|: force densities near the largest
/// double do not overflow D.
pub(crate) fn geometry(topology: &Topology, q: &[f64]) -> Result<Vec<Vector3<f64>>> {
    let scale = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let unit: Vec<f64> = q.iter().map(|x| x / scale.max(f64::MIN_POSITIVE)).collect();
    let q = unit.as_slice();
    if !topology.fixed.is_empty() {
        return fixed_solve(topology, q, &held_positions(topology));
    }
    if topology.n_nodes <= DENSE_MAX_NODES {
        let d = dense_matrix(&topology.member_nodes(), q, topology.n_nodes);
        let phi = null_space(&d)?;
        return Ok(normalise(topology, &phi));
    }
    anchored(topology, q)
}

/// An orthonormal basis of the null space of D (n × k), or the rank-deficiency error.
pub(crate) fn null_space(d: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let (w, v) = linalg::symmetric_eigen(d)?;
    let scale = w.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let tol = NULL_SPACE_TOLERANCE * scale;
    let null: Vec<usize> = (0..w.len()).filter(|&i| w[i].abs() <= tol).collect();
    if null.len() < 3 {
        let mut by_size: Vec<f64> = w
            .iter()
            .map(|x| x.abs() / scale.max(f64::MIN_POSITIVE))
            .collect();
        by_size.sort_by(f64::total_cmp);
        let shown: Vec<String> = by_size.iter().take(5).map(|x| format!("{x:.2e}")).collect();
        return Err(FormFindError::RankDeficiency {
            found: null.len(),
            required: 4,
            hint: format!(
                "the smallest |eigenvalues| of D relative to the largest are [{}] (zero below \
                 {NULL_SPACE_TOLERANCE:e}); change the force-density ratios (e.g. scale the \
                 bars' group) or let the adaptive method find admissible ones (`method = \
                 adaptive`, started from these, which it replaces)",
                shown.join(", ")
            ),
        });
    }
    Ok(v.select_columns(&null))
}

/// Rows of an n × 3 matrix as points.
fn points(x: &DMatrix<f64>) -> Vec<Vector3<f64>> {
    (0..x.nrows())
        .map(|i| Vector3::new(x[(i, 0)], x[(i, 1)], x[(i, 2)]))
        .collect()
}

/// The number of dimensions the points span (principal spreads above 1e-6 of the largest).
pub(crate) fn spanned_dimensions(p: &[Vector3<f64>]) -> usize {
    let c = centroid(p);
    let mut m = Matrix3::zeros();
    for x in p {
        let d = x - c;
        m += d * d.transpose();
    }
    let e = m.symmetric_eigenvalues();
    let hi = e.max();
    if hi.is_nan() || hi <= 0.0 {
        return 0;
    }
    e.iter().filter(|&&x| x > 1e-12 * hi).count()
}

/// The centroid of the points.
pub(crate) fn centroid(p: &[Vector3<f64>]) -> Vector3<f64> {
    p.iter().sum::<Vector3<f64>>() / p.len().max(1) as f64
}

/// The normalised geometry of a null-space basis (see the module docs).
pub(crate) fn normalise(topology: &Topology, phi: &DMatrix<f64>) -> Vec<Vector3<f64>> {
    if let Some(x0) = &topology.nodes {
        let x0 = DMatrix::from_fn(x0.len(), 3, |i, j| x0[i][j]);
        let x = phi * (phi.transpose() * &x0);
        let p = points(&x);
        if spanned_dimensions(&p) >= (phi.ncols() - 1).min(3) {
            return p;
        }
    }
    canonical(topology, phi)
}

/// The canonical geometry of a null-space basis (module docs).
fn canonical(topology: &Topology, phi: &DMatrix<f64>) -> Vec<Vector3<f64>> {
    let n = phi.nrows();
    let mut c = phi.clone();
    for mut col in c.column_iter_mut() {
        let mean = col.sum() / n as f64;
        col.add_scalar_mut(-mean);
    }
    // The three directions of largest spread of the centred null space, orthonormal.
    let (u, _) = match linalg::svd(&c) {
        Ok(s) => (s.u, s.s),
        Err(_) => return vec![Vector3::zeros(); n],
    };
    let dim = (phi.ncols() - 1).min(3);
    let mut x = DMatrix::zeros(n, 3);
    x.columns_mut(0, dim).copy_from(&u.columns(0, dim));
    let p = points(&x);
    right_handed(orient_and_scale(topology, p))
}

/// Mirrors the last axis when the first four affinely independent nodes (in index order)
/// form a negatively oriented tetrahedron: the canonical form's handedness convention
/// (for `prism:N` it puts the bottom ring counter-clockwise about the axis towards the top,
/// so the top is twisted by +(π/2 + π/N)).
fn right_handed(mut p: Vec<Vector3<f64>>) -> Vec<Vector3<f64>> {
    let size = p
        .iter()
        .fold(0.0f64, |a, x| a.max(x.amax()))
        .max(f64::MIN_POSITIVE);
    let Some(&p0) = p.first() else {
        return p;
    };
    let e1 = p.iter().map(|x| x - p0).find(|d| d.norm() > 1e-9 * size);
    let Some(e1) = e1 else {
        return p;
    };
    let e2 = p
        .iter()
        .map(|x| x - p0)
        .find(|d| e1.cross(d).norm() > 1e-9 * size * e1.norm());
    let Some(e2) = e2 else {
        return p;
    };
    let normal = e1.cross(&e2);
    let volume = p
        .iter()
        .map(|x| normal.dot(&(x - p0)))
        .find(|v| v.abs() > 1e-9 * size * normal.norm());
    if volume.is_some_and(|v| v < 0.0) {
        for x in p.iter_mut() {
            x.z = -x.z;
        }
    }
    p
}

/// Rotates to the principal axes of the bar vectors and scales to a mean bar length of 1.
pub(crate) fn orient_and_scale(topology: &Topology, mut p: Vec<Vector3<f64>>) -> Vec<Vector3<f64>> {
    let pairs = topology.member_nodes();
    let used: Vec<[usize; 2]> = if topology.bars.is_empty() {
        pairs
    } else {
        pairs[..topology.bars.len()].to_vec()
    };
    let mut m = Matrix3::zeros();
    let mut mean = 0.0;
    for &[i, j] in &used {
        let b = p[j] - p[i];
        m += b * b.transpose();
        mean += b.norm();
    }
    mean /= used.len().max(1) as f64;
    let eig = m.symmetric_eigen();
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| eig.eigenvalues[b].total_cmp(&eig.eigenvalues[a]));
    let mut r = Matrix3::zeros();
    for (col, &k) in order.iter().enumerate() {
        r.set_column(col, &eig.eigenvectors.column(k));
    }
    let scale = if mean > 0.0 { 1.0 / mean } else { 1.0 };
    for x in p.iter_mut() {
        *x = r.transpose() * *x * scale;
    }
    let size = p.iter().fold(0.0f64, |a, x| a.max(x.amax()));
    for axis in 0..3 {
        let first = p.iter().map(|x| x[axis]).find(|v| v.abs() > 1e-6 * size);
        if first.is_some_and(|v| v < 0.0) {
            for x in p.iter_mut() {
                x[axis] = -x[axis];
            }
        }
    }
    p
}

/// The free coordinates with `fixed` nodes held: D_ff X_f = −D_fx X_x by sparse Cholesky
/// (D_ff positive definite) or LU.
pub(crate) fn fixed_solve(
    topology: &Topology,
    q: &[f64],
    fixed: &[(usize, Vector3<f64>)],
) -> Result<Vec<Vector3<f64>>> {
    FixedSystem::new(topology, q, fixed)?.solve(&[])
}

/// The factors of D_ff: a sparse Cholesky (AMD ordering) where D_ff is positive definite
/// (every force density positive, or bars braced enough: the usual held form), else a sparse
/// LU (D_ff indefinite, bars present).
enum Factors {
    Cholesky(SparseCholesky),
    Lu(SparseLu),
}

impl Factors {
    /// Cholesky when it succeeds, else LU; a failing LU is the error (`nf` free nodes).
    fn new(a: &CscMatrix, nf: usize) -> Result<Self> {
        if let Some(c) = cholesky(a) {
            return Ok(Factors::Cholesky(c));
        }
        let lu = SparseLu::new(a).map_err(|e| singular(nf, e.to_string()))?;
        Ok(Factors::Lu(lu))
    }

    fn solve_in_place(&mut self, b: &mut [f64]) {
        match self {
            Factors::Cholesky(c) => c.solve_in_place(b),
            Factors::Lu(lu) => lu.solve_in_place(b),
        }
    }
}

/// The sparse Cholesky factors of the symmetric `a` (both triangles stored) from its lower
/// triangle, `None` where it is not (numerically) positive definite.
fn cholesky(a: &CscMatrix) -> Option<SparseCholesky> {
    let p = a.pattern();
    let n = p.ncols();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut rows = Vec::with_capacity(p.nnz() / 2 + n);
    let mut values = Vec::with_capacity(p.nnz() / 2 + n);
    col_ptr.push(0);
    for c in 0..n {
        for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
            if p.row_idx()[s] >= c {
                rows.push(p.row_idx()[s]);
                values.push(a.values()[s]);
            }
        }
        col_ptr.push(rows.len());
    }
    let lower = linalg::CscPattern::new(n, col_ptr, rows).ok()?;
    let mut chol = SparseCholesky::new(&lower).ok()?;
    chol.factor(&values).ok()?;
    Some(chol)
}

/// D_ff factored once for held nodes: the solves of D_ff X_f = P_f − D_fx X_x for any loads
/// P (the self-weight iteration solves it once per iteration).
pub(crate) struct FixedSystem {
    /// The position of every held node, `None` for a free one.
    position: Vec<Option<Vector3<f64>>>,
    /// The free nodes, in index order.
    free: Vec<usize>,
    /// D_ff.
    a: CscMatrix,
    /// Its factors (`None` without free nodes).
    lu: Option<Factors>,
    /// −D_fx X_x, one row per free node.
    rhs: Vec<Vector3<f64>>,
    /// max |q|.
    dmax: f64,
}

impl FixedSystem {
    /// Assembles and factors D_ff; a numerically singular one is the error.
    pub(crate) fn new(
        topology: &Topology,
        q: &[f64],
        fixed: &[(usize, Vector3<f64>)],
    ) -> Result<Self> {
        let n = topology.n_nodes;
        let mut position: Vec<Option<Vector3<f64>>> = vec![None; n];
        for &(i, x) in fixed {
            position[i] = Some(x);
        }
        let mut free_index = vec![usize::MAX; n];
        let mut free = Vec::new();
        for i in 0..n {
            if position[i].is_none() {
                free_index[i] = free.len();
                free.push(i);
            }
        }
        let nf = free.len();
        let mut t = Vec::new();
        let mut rhs = vec![Vector3::zeros(); nf];
        let mut dmax = 0.0f64;
        for (&[i, j], &qk) in topology.force_pairs().iter().zip(q) {
            dmax = dmax.max(qk.abs());
            for (a, b) in [(i, j), (j, i)] {
                if position[a].is_some() {
                    continue;
                }
                let fa = free_index[a];
                t.push((fa, fa, qk));
                match position[b] {
                    Some(xb) => rhs[fa] += qk * xb,
                    None => t.push((fa, free_index[b], -qk)),
                }
            }
        }
        let a = CscMatrix::from_triplets(nf, nf, &t)?;
        let lu = if nf == 0 {
            None
        } else {
            let mut lu = Factors::new(&a, nf)?;
            // A numerically singular D_ff factors without complaint: solve D_ff y = D_ff z
            // for a fixed pseudo-random z and require y = z.
            let z: Vec<f64> = (0..nf).map(|i| (0.7 + 1.3 * i as f64).sin()).collect();
            let mut y = a.mul_vec(&z);
            lu.solve_in_place(&mut y);
            let dev = y
                .iter()
                .zip(&z)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            if dev.is_nan() || dev > SINGULARITY_TOLERANCE {
                return Err(singular(
                    nf,
                    format!(
                        "a test solve is off by {dev:.1e}: D has null vectors that vanish at \
                         the held nodes"
                    ),
                ));
            }
            Some(lu)
        };
        Ok(FixedSystem {
            position,
            free,
            a,
            lu,
            rhs,
            dmax,
        })
    }

    /// The free nodes, in index order (the rows of D_ff).
    pub(crate) fn free(&self) -> &[usize] {
        &self.free
    }

    /// Solves D_ff y = b for one column `b` (one entry per free node), in place, with the
    /// factors of D_ff (nothing to do without free nodes).
    pub(crate) fn solve_free_in_place(&mut self, b: &mut [f64]) {
        if let Some(lu) = &mut self.lu {
            lu.solve_in_place(b);
        }
    }

    /// Every node's position under the loads `p` (one per node, or none: unloaded); the
    /// solve's residual is checked.
    pub(crate) fn solve(&mut self, p: &[Vector3<f64>]) -> Result<Vec<Vector3<f64>>> {
        let nf = self.free.len();
        let mut position = self.position.clone();
        if let Some(lu) = &mut self.lu {
            let rhs: Vec<Vector3<f64>> = self
                .free
                .iter()
                .zip(&self.rhs)
                .map(|(&i, r)| r + p.get(i).copied().unwrap_or_default())
                .collect();
            let mut x = vec![Vector3::zeros(); nf];
            for axis in 0..3 {
                let mut b: Vec<f64> = rhs.iter().map(|r| r[axis]).collect();
                lu.solve_in_place(&mut b);
                for (xi, bi) in x.iter_mut().zip(&b) {
                    xi[axis] = *bi;
                }
            }
            // Residual of the solve, against the size of its terms.
            let size = x
                .iter()
                .chain(self.position.iter().flatten())
                .fold(0.0f64, |a, p| a.max(p.amax()));
            let pmax = p.iter().fold(0.0f64, |a, f| a.max(f.amax()));
            let mut res = 0.0f64;
            for axis in 0..3 {
                let xa: Vec<f64> = x.iter().map(|p| p[axis]).collect();
                let ax = self.a.mul_vec(&xa);
                for (k, v) in ax.iter().enumerate() {
                    res = res.max((v - rhs[k][axis]).abs());
                }
            }
            let scale = self.dmax * size.max(1e-300) + pmax;
            if !size.is_finite() || !res.is_finite() || res > SOLVE_TOLERANCE * scale {
                return Err(singular(nf, format!("solve residual {res:.2e}")));
            }
            for (k, &i) in self.free.iter().enumerate() {
                position[i] = Some(x[k]);
            }
        }
        Ok(position
            .into_iter()
            .map(|p| p.unwrap_or_default())
            .collect())
    }
}

/// D_ff of `nf` free nodes is singular (`detail`: how it showed).
fn singular(nf: usize, detail: String) -> FormFindError {
    FormFindError::SingularSystem {
        hint: format!(
            "D_ff of the {nf} free nodes is singular ({detail}): the fixed nodes do not \
             determine the free ones with these force densities; fix more nodes or change \
             the force densities"
        ),
    }
}

/// A loaded form: the nodes, the load on every node (N) and the iterations.
pub(crate) type Loaded = (Vec<Vector3<f64>>, Vec<Vector3<f64>>, usize);

/// The loaded form (module docs, **Loads**): the nodes, the loads each node carries at them
/// (point loads plus the lumped self-weight; N, in the units of `q`) and the iterations of the
/// self-weight's fixed point (1 without weights). `q` and the loads are scaled together by
/// 1 / max|q| for the solve.
pub(crate) fn loaded(topology: &Topology, q: &[f64], settings: &Settings) -> Result<Loaded> {
    let scale = q
        .iter()
        .fold(0.0f64, |a, x| a.max(x.abs()))
        .max(f64::MIN_POSITIVE);
    let unit: Vec<f64> = q.iter().map(|x| x / scale).collect();
    let fixed = held_positions(topology);
    let mut system = FixedSystem::new(topology, &unit, &fixed)?;
    let point = point_loads(topology);
    let weights = member_weights(topology);
    let weighted = weights.iter().any(|&w| w > 0.0);
    let scaled =
        |p: &[Vector3<f64>]| -> Vec<Vector3<f64>> { p.iter().map(|f| f / scale).collect() };
    let mut nodes = system.solve(&scaled(&point))?;
    if !weighted {
        return Ok((nodes, point, 1));
    }
    // The self-weight's fixed point: P(X) = P_point + lumped w L(X), solved until the
    // largest change of a node is at most the tolerance times the form's size.
    let (mut change, mut done) = (f64::INFINITY, 0);
    for iteration in 1..=settings.max_iterations {
        done = iteration;
        let p = with_weight(topology, &point, &weights, &nodes);
        let next = system.solve(&scaled(&p))?;
        change = next
            .iter()
            .zip(&nodes)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).amax()));
        let size = crate::analysis::size(&next).max(f64::MIN_POSITIVE);
        nodes = next;
        if !change.is_finite() {
            break;
        }
        if change <= settings.tolerance * size {
            let p = with_weight(topology, &point, &weights, &nodes);
            return Ok((nodes, p, iteration));
        }
        change /= size;
    }
    Err(FormFindError::NotConverged {
        method: "fdm (the self-weight's fixed point X = solve(P(X)))".into(),
        iterations: done,
        residual: change,
        tolerance: settings.tolerance,
    })
}

/// The held nodes with their positions.
pub(crate) fn held_positions(topology: &Topology) -> Vec<(usize, Vector3<f64>)> {
    topology
        .fixed
        .iter()
        .map(|f| (f.node, Vector3::from(f.position)))
        .collect()
}

/// Each member's weight per length (N/m; 0 where not given).
pub(crate) fn member_weights(topology: &Topology) -> Vec<f64> {
    topology
        .given_weights()
        .iter()
        .map(|w| w.unwrap_or(0.0))
        .collect()
}

/// The point loads summed per node (N).
pub(crate) fn point_loads(topology: &Topology) -> Vec<Vector3<f64>> {
    let mut p = vec![Vector3::zeros(); topology.n_nodes];
    for l in &topology.loads {
        p[l.node] += Vector3::from(l.force);
    }
    p
}

/// The point loads plus each member's weight w L at `nodes`, half at each end, along −z.
pub(crate) fn with_weight(
    topology: &Topology,
    point: &[Vector3<f64>],
    weights: &[f64],
    nodes: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let mut p = point.to_vec();
    for (&[i, j], &w) in topology.member_nodes().iter().zip(weights) {
        if w > 0.0 {
            let half = 0.5 * w * (nodes[j] - nodes[i]).norm();
            p[i].z -= half;
            p[j].z -= half;
        }
    }
    p
}

/// Four affinely independent nodes, well spread: the farthest from the centroid, the
/// farthest from it, the farthest from their line, the farthest from their plane.
pub(crate) fn anchors(p: &[Vector3<f64>]) -> Option<[usize; 4]> {
    let c = centroid(p);
    let argmax = |f: &dyn Fn(&Vector3<f64>) -> f64| {
        (0..p.len())
            .max_by(|&a, &b| f(&p[a]).total_cmp(&f(&p[b])))
            .unwrap_or(0)
    };
    let a0 = argmax(&|x| (x - c).norm());
    let a1 = argmax(&|x| (x - p[a0]).norm());
    let e = (p[a1] - p[a0]).normalize();
    let a2 = argmax(&|x| {
        let d = x - p[a0];
        (d - e * e.dot(&d)).norm()
    });
    let nrm = (p[a1] - p[a0]).cross(&(p[a2] - p[a0]));
    if nrm.norm() == 0.0 {
        return None;
    }
    let nrm = nrm.normalize();
    let a3 = argmax(&|x| (x - p[a0]).dot(&nrm).abs());
    let size = (p[a1] - p[a0]).norm();
    if (p[a3] - p[a0]).dot(&nrm).abs() <= 1e-9 * size {
        return None;
    }
    Some([a0, a1, a2, a3])
}

/// The sparse free-standing path (module docs).
fn anchored(topology: &Topology, q: &[f64]) -> Result<Vec<Vector3<f64>>> {
    let x0 = topology
        .initial_nodes()
        .ok_or_else(|| FormFindError::Unsupported {
            what: format!(
                "a free-standing topology of {} nodes (over {DENSE_MAX_NODES}) without initial \
             nodes: give `nodes` as a guess, so the sparse path can anchor the affine freedom",
                topology.n_nodes
            ),
        })?;
    let a = anchors(&x0).ok_or_else(|| FormFindError::InvalidTopology {
        item: "nodes".into(),
        reason: "the initial nodes are coplanar; a 3-D guess is needed".into(),
    })?;
    let fixed: Vec<(usize, Vector3<f64>)> = a.iter().map(|&i| (i, x0[i])).collect();
    let x = fixed_solve(topology, q, &fixed).map_err(|e| match e {
        FormFindError::SingularSystem { hint } => FormFindError::RankDeficiency {
            found: 5,
            required: 4,
            hint: format!(
                "with four anchor nodes held, {hint}; the sparse path of topologies over \
                 {DENSE_MAX_NODES} nodes needs rank deficiency exactly 4 (a null space \
                 beyond the affine maps, e.g. folds along the planar rings of stacked \
                 stages, needs held nodes)"
            ),
        },
        e => e,
    })?;
    // The anchors' own rows must vanish too: then D X = 0 everywhere.
    let mut f = vec![Vector3::zeros(); topology.n_nodes];
    let mut qmax = 0.0f64;
    for (&[i, j], &qk) in topology.member_nodes().iter().zip(q) {
        let m = qk * (x[j] - x[i]);
        f[i] += m;
        f[j] -= m;
        qmax = qmax.max(qk.abs());
    }
    let size = x.iter().fold(0.0f64, |s, p| s.max(p.amax()));
    let res = a.iter().fold(0.0f64, |s, &i| s.max(f[i].amax()));
    if res > SOLVE_TOLERANCE * qmax * size {
        return Err(FormFindError::RankDeficiency {
            found: 3,
            required: 4,
            hint: format!(
                "with four nodes anchored the anchors stay out of balance (residual \
                 {:.2e} relative): the force densities admit no free-standing 3-D form; \
                 change their ratios (the adaptive method, `method = adaptive`, takes at \
                 most {} nodes)",
                res / (qmax * size),
                // the adaptive method's bound is its dense eigensolver's, this one
                DENSE_MAX_NODES
            ),
        });
    }
    Ok(affine_fit(&x, &x0))
}

/// The affine image of `x` closest to `x0` in least squares.
pub(crate) fn affine_fit(x: &[Vector3<f64>], x0: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let c = centroid(x);
    let mut g = Matrix4::zeros();
    let mut r = nalgebra::Matrix4x3::zeros();
    for (p, t) in x.iter().zip(x0) {
        let d = p - c;
        let y = Vector4::new(d.x, d.y, d.z, 1.0);
        g += y * y.transpose();
        r += y * t.transpose();
    }
    let Some(chol) = g.cholesky() else {
        return x.to_vec();
    };
    let m = chol.solve(&r);
    x.iter()
        .map(|p| {
            let d = p - c;
            let y = Vector4::new(d.x, d.y, d.z, 1.0);
            m.transpose() * y
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// D_ff of the held grid is positive definite: the Cholesky runs, and its form is the LU's
    /// to round-off. A free node between a bar and a weaker string (D_ff = q_b + q_s < 0) is
    /// indefinite: the LU runs, and places the node where the closed form does.
    #[test]
    fn the_cholesky_runs_where_d_ff_is_positive_definite_and_the_lu_elsewhere() {
        let t = crate::builtin("grid:4").unwrap();
        let q = t.force_densities().unwrap();
        let held = held_positions(&t);
        let system = FixedSystem::new(&t, &q, &held).unwrap();
        assert!(matches!(system.lu, Some(Factors::Cholesky(_))));
        let mut cholesky = FixedSystem::new(&t, &q, &held).unwrap();
        let mut lu = FixedSystem::new(&t, &q, &held).unwrap();
        lu.lu = Some(Factors::Lu(SparseLu::new(&lu.a).unwrap()));
        let (a, b) = (cholesky.solve(&[]).unwrap(), lu.solve(&[]).unwrap());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).amax() < 1e-12, "{x} vs {y}");
        }
        // node 1 between node 0 (a bar, q = −2) and node 2 (a string, q = 1), both held
        let line = Topology {
            n_nodes: 3,
            bars: vec![crate::Member::new(0, 1).force_density(-2.0)],
            strings: vec![crate::Member::new(1, 2).force_density(1.0)],
            fixed: vec![
                crate::FixedNode {
                    node: 0,
                    position: [0.0, 0.0, 0.0],
                },
                crate::FixedNode {
                    node: 2,
                    position: [1.0, 0.0, 0.0],
                },
            ],
            ..Topology::default()
        };
        let q = line.force_densities().unwrap();
        let mut system = FixedSystem::new(&line, &q, &held_positions(&line)).unwrap();
        assert!(matches!(system.lu, Some(Factors::Lu(_))));
        // −2 (x₀ − x₁) + 1 (x₂ − x₁) = 0 → x₁ = −1
        let x = system.solve(&[]).unwrap();
        assert!(
            (x[1] - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-15,
            "{}",
            x[1]
        );
    }
}
