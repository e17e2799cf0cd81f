//! The symmetry-adapted (Fourier) blocks of the equilibrium matrix, one per irreducible
//! representation k = 0..n−1 of Cₙ (character λ = ωᵏ, ω = e^{2πi/n}).
//!
//! A vector in representation k satisfies g·v = λ v, where g acts on nodal vectors by
//! (g·u)_σ(i) = R uᵢ and on force densities by (g·q)_π(e) = q_e; A g = g A, so A maps
//! representation k of the members into representation k of the nodes. Unitary bases:
//!
//! - member orbit E of d members (rep e), present in block k iff k d ≡ 0 (mod n):
//!   q̂ = (√d / n) Σ_{p=0}^{n−1} λ^{−p} gᵖ δ_e, i.e. q̂ = λ^{−p}/√d on member πᵖ(e);
//! - node orbit of n nodes (rep r), one row per free direction t at r:
//!   û_t = (1/√n) λ^{−p} Rᵖ e_t at node σᵖ(r);
//! - node a on the axis, one row per unit eigenvector w of R with eigenvalue λ (free at a):
//!   the axis ι̂ (k = 0) and (e₁ ∓ i e₂)/√2 (k = 1 and k = n − 1, e₁ × e₂ = ι̂).
//!
//! With e = (i, j), m₀ = x_j − x_i and i = σ^{p_i}(r_i), j = σ^{p_j}(r_j), the block entry of
//! orbit E is the sum over its two ends (sign +1 at j, −1 at i) of
//! √(d/n) · sign · λ^{p} (R^{−p} m₀)_t   at a node orbit (p the end's phase), and
//! √d · sign · wᴴ m₀                      at an axis node.
//! The change of basis is unitary, so the singular values of the n blocks together are those
//! of A, and rank, self-stress dimension and mechanism counts add up over k.

use super::descriptor::CyclicSymmetry;
use nalgebra::{Complex, DMatrix, Vector3};
use tensegrity_core::structure::Structure;

/// A row of a block: a free direction of a node orbit's representative, or an eigenvector of
/// R at a node on the axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockRow {
    /// Direction `dir` (x, y, z) of node orbit `orbit`.
    Orbit {
        /// The node orbit.
        orbit: usize,
        /// The coordinate direction at the representative.
        dir: usize,
    },
    /// Eigenvector `eig` (0: the axis, 1: (e₁ − i e₂)/√2, 2: (e₁ + i e₂)/√2) at an axis node.
    Axis {
        /// The node.
        node: usize,
        /// Which eigenvector.
        eig: usize,
    },
}

/// Which rows and columns block k has (free and fixed rows both listed).
#[derive(Debug, Clone, PartialEq)]
pub struct BlockLayout {
    /// The representation index.
    pub k: usize,
    /// Rows, each with whether it is a free degree of freedom.
    pub rows: Vec<(BlockRow, bool)>,
    /// Member orbits (columns).
    pub cols: Vec<usize>,
}

impl BlockLayout {
    /// Number of free rows.
    pub fn free_rows(&self) -> usize {
        self.rows.iter().filter(|r| r.1).count()
    }
}

/// The unit eigenvectors of R (axis ι̂, (e₁ ∓ i e₂)/√2) and their representation indices.
pub(crate) fn axis_eigenvectors(sym: &CyclicSymmetry) -> [(Vector3<Complex<f64>>, usize); 3] {
    let a = sym.axis();
    let helper = if a.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let e1 = (helper - a * a.dot(&helper)).normalize();
    let e2 = a.cross(&e1);
    let c = |v: Vector3<f64>| v.map(|x| Complex::new(x, 0.0));
    let i = Complex::new(0.0, 1.0);
    let s = std::f64::consts::FRAC_1_SQRT_2;
    let n = sym.order();
    [
        (c(a), 0),
        ((c(e1) - c(e2) * i) * Complex::new(s, 0.0), 1 % n),
        ((c(e1) + c(e2) * i) * Complex::new(s, 0.0), n - 1),
    ]
}

/// λᵐ = e^{2πi m/n} for m = 0..n−1.
pub(crate) fn roots_of_unity(n: usize) -> Vec<Complex<f64>> {
    (0..n)
        .map(|m| {
            let t = 2.0 * std::f64::consts::PI * m as f64 / n as f64;
            Complex::new(t.cos(), t.sin())
        })
        .collect()
}

/// What every block needs from the structure, gathered once (O(nodes + members)) so that
/// each block costs only O(orbits).
#[derive(Debug, Clone)]
pub struct BlockContext<'a> {
    structure: &'a Structure,
    sym: &'a CyclicSymmetry,
    fixed: Vec<[bool; 3]>,
    ends: Vec<[usize; 2]>,
    roots: Vec<Complex<f64>>,
    eigs: [(Vector3<Complex<f64>>, usize); 3],
}

impl<'a> BlockContext<'a> {
    /// Gathers the supports, member ends, roots of unity and axis eigenvectors.
    pub fn new(structure: &'a Structure, sym: &'a CyclicSymmetry) -> Self {
        Self {
            structure,
            sym,
            fixed: structure.fixed_dofs(),
            ends: structure.member_nodes(),
            roots: roots_of_unity(sym.order()),
            eigs: axis_eigenvectors(sym),
        }
    }

    /// The rows and columns of block k.
    pub fn layout(&self, k: usize) -> BlockLayout {
        block_layout(self, k)
    }

    /// Block k on the free rows of `layout` (see the module docs).
    pub fn assemble(&self, layout: &BlockLayout) -> DMatrix<Complex<f64>> {
        assemble_block(self, layout)
    }
}

fn block_layout(ctx: &BlockContext<'_>, k: usize) -> BlockLayout {
    let (sym, fixed, eigs) = (ctx.sym, &ctx.fixed, &ctx.eigs);
    let mut rows = Vec::new();
    for (o, orbit) in sym.node_orbits().iter().enumerate() {
        let f = fixed[orbit.rep];
        if orbit.on_axis {
            for (j, (w, kw)) in eigs.iter().enumerate() {
                if *kw == k {
                    let in_fixed: f64 = (0..3).filter(|&d| f[d]).map(|d| w[d].norm_sqr()).sum();
                    let row = BlockRow::Axis {
                        node: orbit.rep,
                        eig: j,
                    };
                    rows.push((row, in_fixed < 0.5));
                }
            }
        } else {
            for (dir, &fx) in f.iter().enumerate() {
                rows.push((BlockRow::Orbit { orbit: o, dir }, !fx));
            }
        }
    }
    let n = sym.order();
    let cols = (0..sym.member_orbits().len())
        .filter(|&e| (k * sym.member_orbits()[e].size).is_multiple_of(n))
        .collect();
    BlockLayout { k, rows, cols }
}

/// R^{−p} v by Rodrigues' formula (angle −2πp/n about the axis), from the root table.
fn rotate_back(
    a: &Vector3<f64>,
    roots: &[Complex<f64>],
    p: usize,
    v: &Vector3<f64>,
) -> Vector3<f64> {
    let (c, s) = (roots[p].re, -roots[p].im);
    v * c + a.cross(v) * s + a * (a.dot(v) * (1.0 - c))
}

fn assemble_block(ctx: &BlockContext<'_>, layout: &BlockLayout) -> DMatrix<Complex<f64>> {
    let (sym, roots, eigs) = (ctx.sym, &ctx.roots, &ctx.eigs);
    let n = sym.order();
    let k = layout.k;
    // row index of (node orbit, dir) or (axis node, eig) among the free rows
    let mut orbit_row = vec![[usize::MAX; 3]; sym.node_orbits().len()];
    let mut free = 0;
    for (row, is_free) in &layout.rows {
        if !is_free {
            continue;
        }
        match *row {
            BlockRow::Orbit { orbit, dir } => orbit_row[orbit][dir] = free,
            BlockRow::Axis { node, eig } => orbit_row[sym.node_places()[node].orbit][eig] = free,
        }
        free += 1;
    }
    let a = sym.axis();
    let x = ctx.structure.nodes();
    let ends = &ctx.ends;
    let mut block = DMatrix::zeros(free, layout.cols.len());
    let sqrt_n = (n as f64).sqrt();
    for (c, &e) in layout.cols.iter().enumerate() {
        let orbit = sym.member_orbits()[e];
        let d = orbit.size as f64;
        let [i, j] = ends[orbit.rep];
        let m0 = x[j] - x[i];
        for (node, sign) in [(j, 1.0), (i, -1.0)] {
            let place = sym.node_places()[node];
            let rows = orbit_row[place.orbit];
            if sym.node_orbits()[place.orbit].on_axis {
                for (eig, (w, _)) in eigs.iter().enumerate() {
                    if rows[eig] != usize::MAX {
                        let wm: Complex<f64> = (0..3).map(|t| w[t].conj() * m0[t]).sum();
                        block[(rows[eig], c)] += wm * (sign * d.sqrt());
                    }
                }
            } else {
                let p = place.phase;
                let lam = roots[(k * p) % n] * (sign * d.sqrt() / sqrt_n);
                let v = rotate_back(&a, roots, p, &m0);
                for t in 0..3 {
                    if rows[t] != usize::MAX {
                        block[(rows[t], c)] += lam * v[t];
                    }
                }
            }
        }
    }
    block
}
