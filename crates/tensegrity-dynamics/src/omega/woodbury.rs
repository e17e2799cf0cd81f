//! The Ω system of a small structure as a low-rank update of a constant matrix (Woodbury).
//!
//! When every constraint row is ±e_d on one axis d (the rows of N P = D), the Ω system splits
//! into a constant part and one rank-one term per constrained bar:
//!
//! `A(b̂) = A₀ − Σ_k (3/m_k) u_k u_kᵀ`,  `u_k[r] = Σ_{e ∈ r on bar k} s_e σ_e b̂_k[d_r]`,
//!
//! where A₀ = G M⁻¹ Gᵀ (per bar M⁻¹ = [[4, −2], [−2, 4]]/m: the α weights of the parent
//! module), s_e = ±1 is the sign of the gradient ±e_d of entry e and σ_e = −1 at a bar's start,
//! +1 at its end (the β weights −3 σ_p σ_q). A₀ couples only rows of one axis: sorted by axis it
//! is block diagonal, A₀ = K_x ⊕ K_y ⊕ K_z. With C = diag(3/m_k) and U = [u_1 … u_β] the
//! Woodbury identity gives
//!
//! `A⁻¹ = A₀⁻¹ + A₀⁻¹ U S⁻¹ Uᵀ A₀⁻¹`,  `S = C⁻¹ − Uᵀ A₀⁻¹ U`  (β × β),
//!
//! S being SPD exactly when A is (both are Schur complements of [[A₀, U], [Uᵀ, C⁻¹]]). Since
//! u_k = Σ_d b̂_k[d] c_{k,d} with constant vectors c_{k,d} (nonzero on the axis-d rows only),
//! the blocks of A₀⁻¹, V_{k,d} = A₀⁻¹ c_{k,d} and T_{kl,d} = c_{k,d}ᵀ V_{l,d} are computed
//! once per set of masses; an evaluation forms `S_kl = δ_kl m_k/3 − Σ_d b̂_k[d] b̂_l[d] T_{kl,d}`
//! and its LDLᵀ factorisation (β³/3), and a solve is `z = A₀⁻¹ r` (block by block),
//! `g = Uᵀ z`, `S y = g`, `x = z + Σ_{k,d} y_k b̂_k[d] V_{k,d}`: about 2n²/3 + 4βn/3 + 2β²
//! flops for n rows and β bars (twice, with the refinement below), against n³/3 + 2n² for a
//! Cholesky of the assembled A (the MOTES D-bar: n = 15, β = 4, ≈ 1.1 k with the refinement and
//! the padding against ≈ 2 k with the assembly of A).
//!
//! Accuracy: every solve is refined once, x += A⁻¹(r − A x) with A x = A₀ x − Σ_k (3/m_k) u_k
//! (u_kᵀ x) (without it the D-bar's ‖N P − D‖ drifted ten times faster than with the direct
//! Cholesky; with it the drift is the direct path's). S is formed by cancellation (m_k/3
//! minus a positive part), which loses digits only when A is close to singular: an LDLᵀ pivot
//! below [`MIN_PIVOT_RATIO`] × m_k/3 (or NaN) makes the caller fall back to the direct
//! factorisation of A, which then decides (and reports a singular system exactly as before).

use super::{axis_of, AxisContribution, Row};
use nalgebra::Vector3;
use tensegrity_linalg::DenseCholesky;

/// Smallest LDLᵀ pivot of S, relative to its undepleted value m_k/3, accepted before falling
/// back to the direct factorisation.
pub(super) const MIN_PIVOT_RATIO: f64 = 1e-8;

/// One node entry of a constraint row in the low-rank form.
#[derive(Debug, Clone, Copy)]
struct Entry {
    /// Constraint row, in the internal (axis-sorted) order.
    row: usize,
    /// `3·k + d`: local bar k, axis d.
    kd: usize,
    /// s_e σ_e.
    coef: f64,
}

/// The blocks are padded to a multiple of this with zeros (the SSE2 width: the padded lanes
/// cost a little, a 4-wide padding of 5-row blocks cost 3/8 of the products).
const W: usize = 2;

/// When no axis has more than this many rows, every block is padded to exactly this many
/// (stride P): the block products and axpys then run on fixed-size arrays, unrolled and
/// without index checks (the MOTES D-bar's 5-row blocks). The zero padding adds exact zeros,
/// so the results are those of the unpadded sums.
const P: usize = 8;

/// The rows of one axis in the internal order, and where its blocks are stored.
#[derive(Debug, Clone, Copy, Default)]
struct Block {
    /// First internal position.
    start: usize,
    /// Number of rows.
    len: usize,
    /// len rounded up to a multiple of [`W`] (the stride of the stored blocks).
    lp: usize,
    /// Offset of the lp × lp blocks of A₀ and A₀⁻¹.
    off: usize,
}

/// `out = Σ_{j < len} x_j m_j` for the padded symmetric lp × lp block `m` (row j = column j),
/// accumulated row by row (each output summed in the order j = 0, 1, …: the same rounding
/// as a dot product per output, without per-element index checks).
#[inline]
fn block_product(m: &[f64], blk: &Block, x: &[f64], out: &mut [f64]) {
    if let (true, Ok(o)) = (blk.lp == P, <&mut [f64; P]>::try_from(&mut *out)) {
        // the accumulators in registers
        let mut acc = [0.0; P];
        // (all zero: a planar structure's out-of-plane block)
        if x.iter().any(|v| *v != 0.0) {
            let (rows, _) = m.as_chunks::<P>();
            for (xj, row) in x.iter().zip(rows).take(blk.len) {
                for i in 0..P {
                    acc[i] += xj * row[i];
                }
            }
        }
        *o = acc;
        return;
    }
    out.fill(0.0);
    if x.iter().all(|v| *v == 0.0) {
        return;
    }
    for (xj, row) in x.iter().zip(m.chunks_exact(blk.lp)).take(blk.len) {
        for (o, r) in out.iter_mut().zip(row) {
            *o += xj * r;
        }
    }
}

/// The constant parts (per set of masses) and the per-evaluation factor of the Woodbury form.
#[derive(Debug, Clone)]
pub(super) struct LowRank {
    /// Constraint row → internal (axis-sorted, padded) position.
    pos: Vec<usize>,
    blocks: [Block; 3],
    /// Global index of each constrained bar (local k → bar).
    bars: Vec<usize>,
    /// The entries, grouped by bar: those of bar k are `entries[bar_entries[k]..bar_entries[k + 1]]`.
    entries: Vec<Entry>,
    bar_entries: Vec<usize>,
    /// Internal row of every entry (the order of `entries`).
    erow: Vec<usize>,
    /// s_e σ_e b̂_k[d] of every entry at the last factorisation (the entries of U; s_e σ_e
    /// is ±1, so the products with it are exact and the rounding is the unweighted form's).
    ew: Vec<f64>,
    /// The blocks with rows, with their axis.
    active: Vec<(usize, Block)>,
    /// A₀'s terms: (internal i, j, bar, α weight with sign).
    a0_terms: Vec<(usize, usize, usize, f64)>,
    /// The inverse masses the constants below belong to (empty before the first build).
    key: Vec<f64>,
    /// Whether A₀ factored (else the caller always takes the direct path).
    ready: bool,
    /// The blocks of A₀⁻¹ (row j = column j), padded.
    a0inv: Vec<f64>,
    /// The blocks of A₀, padded, for the residual.
    a0: Vec<f64>,
    /// V_{k,d} = A₀⁻¹ c_{k,d} on the rows of block d, at `v_off[3k + d]` (block-major: those
    /// of block d start at `v_off[d]`, one after the other).
    v: Vec<f64>,
    v_off: Vec<usize>,
    /// T_{kl,d} = c_{k,d}ᵀ V_{l,d} at `(k·β + l)·3 + d`.
    t: Vec<f64>,
    /// m_k / 3.
    cinv: Vec<f64>,
    /// 3 / m_k.
    c: Vec<f64>,
    /// S, then its LDLᵀ factor (unit L in the strict lower triangle), β × β row-major.
    s: Vec<f64>,
    /// D_jj.
    dval: Vec<f64>,
    /// 1 / D_jj.
    dinv: Vec<f64>,
    /// b̂ of the constrained bars at the last factorisation (3β).
    bh: Vec<f64>,
    /// Whether some b̂_k[d] ≠ 0, per axis d (else the block is A₀'s alone).
    coupled: [bool; 3],
    /// Scratch (internal order): the solution.
    x: Vec<f64>,
    /// Scratch: the right-hand side, then the residual and the correction.
    r0: Vec<f64>,
    /// Scratch: z = A₀⁻¹ r, and A₀ x.
    z: Vec<f64>,
    /// Scratch: g = Uᵀ z, then y = S⁻¹ g.
    g: Vec<f64>,
}

impl LowRank {
    /// The low-rank form of the system with rows `rows` and axis contributions `axis`, or
    /// `None` if some row is not ±e_d on a single axis d.
    pub(super) fn new(rows: &[Row], axis: &[AxisContribution]) -> Option<Self> {
        let n = rows.len();
        let mut row_axis = Vec::with_capacity(n);
        for row in rows {
            let mut ax = None;
            for e in row.entries.iter().flatten() {
                let (d, _) = axis_of(&e.grad)?;
                if ax.is_some_and(|a| a != d) {
                    return None;
                }
                ax = Some(d);
            }
            row_axis.push(ax?);
        }
        let mut blocks = [Block::default(); 3];
        let (mut start, mut off) = (0, 0);
        let lens = [0, 1, 2].map(|d| row_axis.iter().filter(|&&a| a == d).count());
        let fixed = lens.iter().all(|&l| l <= P);
        for (d, b) in blocks.iter_mut().enumerate() {
            let len = lens[d];
            let lp = match (len, fixed) {
                (0, _) => 0,
                (_, true) => P,
                (_, false) => len.div_ceil(W) * W,
            };
            *b = Block {
                start,
                len,
                lp,
                off,
            };
            start += lp;
            off += lp * lp;
        }
        let np = start;
        let mut internal = vec![0; n];
        let mut next = blocks.map(|b| b.start);
        for (r, &d) in row_axis.iter().enumerate() {
            internal[r] = next[d];
            next[d] += 1;
        }
        let mut bars: Vec<usize> = rows
            .iter()
            .flat_map(|r| r.entries.iter().flatten().map(|e| e.node / 2))
            .collect();
        bars.sort_unstable();
        bars.dedup();
        let nb = bars.len();
        let mut entries = Vec::new();
        for (r, row) in rows.iter().enumerate() {
            for e in row.entries.iter().flatten() {
                let (d, s) = axis_of(&e.grad)?;
                let bar = bars.binary_search(&(e.node / 2)).ok()?;
                let sigma = if e.node % 2 == 1 { 1.0 } else { -1.0 };
                entries.push(Entry {
                    row: internal[r],
                    kd: 3 * bar + d,
                    coef: s * sigma,
                });
            }
        }
        entries.sort_by_key(|e| e.kd / 3);
        let mut bar_entries = vec![0; nb + 1];
        for e in &entries {
            bar_entries[e.kd / 3 + 1] += 1;
        }
        for k in 0..nb {
            bar_entries[k + 1] += bar_entries[k];
        }
        let a0_terms = axis
            .iter()
            .filter(|c| c.c0 != 0.0)
            .map(|c| (internal[c.dense / n], internal[c.dense % n], c.bar, c.c0))
            .collect();
        // block-major: the V_{k,d} of one block d are contiguous (k = 0, 1, …)
        let mut v_off = vec![0; 3 * nb];
        let mut vlen = 0;
        for (d, b) in blocks.iter().enumerate() {
            for k in 0..nb {
                v_off[3 * k + d] = vlen;
                vlen += b.lp;
            }
        }
        let erow = entries.iter().map(|e| e.row).collect();
        let ew = vec![0.0; entries.len()];
        let active = blocks
            .iter()
            .enumerate()
            .filter(|(_, b)| b.len > 0)
            .map(|(d, b)| (d, *b))
            .collect();
        Some(Self {
            pos: internal,
            blocks,
            erow,
            ew,
            active,
            entries,
            bar_entries,
            a0_terms,
            key: Vec::new(),
            ready: false,
            a0inv: vec![0.0; off],
            a0: vec![0.0; off],
            v: vec![0.0; vlen],
            v_off,
            t: vec![0.0; 3 * nb * nb],
            cinv: vec![0.0; nb],
            c: vec![0.0; nb],
            s: vec![0.0; nb * nb],
            dval: vec![0.0; nb],
            dinv: vec![0.0; nb],
            bh: vec![0.0; 3 * nb],
            coupled: [true; 3],
            x: vec![0.0; np],
            r0: vec![0.0; np],
            z: vec![0.0; np],
            g: vec![0.0; nb],
            bars,
        })
    }

    /// Number of constrained bars β.
    pub(super) fn rank(&self) -> usize {
        self.bars.len()
    }

    /// The blocks of A₀ and A₀⁻¹, V and T for the inverse masses `inv_mass`.
    fn build(&mut self, inv_mass: &[f64]) {
        self.key.clear();
        self.key.extend_from_slice(inv_mass);
        self.ready = false;
        self.a0.fill(0.0);
        self.a0inv.fill(0.0);
        for b in self.blocks.iter().filter(|b| b.len > 0) {
            let (st, len, lp) = (b.start, b.len, b.lp);
            let a0 = &mut self.a0[b.off..b.off + lp * lp];
            for &(i, j, bar, c0) in &self.a0_terms {
                if (st..st + len).contains(&i) {
                    let v = inv_mass[bar] * c0;
                    a0[(i - st) * lp + (j - st)] += v;
                    if i != j {
                        a0[(j - st) * lp + (i - st)] += v;
                    }
                }
            }
            let mut chol = DenseCholesky::new(len);
            let a = chol.zeroed();
            for i in 0..len {
                a[i * len..i * len + i + 1].copy_from_slice(&a0[i * lp..i * lp + i + 1]);
            }
            if chol.factor_filled().is_err() {
                return;
            }
            let inv = &mut self.a0inv[b.off..b.off + lp * lp];
            for (j, col) in inv.chunks_exact_mut(lp).take(len).enumerate() {
                col[j] = 1.0;
                chol.solve_in_place(&mut col[..len]);
            }
        }
        self.v.fill(0.0);
        for e in &self.entries {
            let b = self.blocks[e.kd % 3];
            let col = &self.a0inv[b.off + (e.row - b.start) * b.lp..][..b.lp];
            let vk = &mut self.v[self.v_off[e.kd]..][..b.lp];
            vk.iter_mut().zip(col).for_each(|(v, a)| *v += e.coef * a);
        }
        let nb = self.bars.len();
        self.t.fill(0.0);
        for e in &self.entries {
            let (k, d) = (e.kd / 3, e.kd % 3);
            let r = e.row - self.blocks[d].start;
            for l in 0..nb {
                self.t[(k * nb + l) * 3 + d] += e.coef * self.v[self.v_off[3 * l + d] + r];
            }
        }
        for (k, &bar) in self.bars.iter().enumerate() {
            self.c[k] = 3.0 * inv_mass[bar];
            self.cinv[k] = 1.0 / self.c[k];
        }
        self.ready = true;
    }

    /// Forms and factors S for the unit vectors `bhat` (all bars) and inverse masses
    /// `inv_mass`; `false` when the direct factorisation must decide (A₀ or S singular or
    /// too close to it, NaN).
    pub(super) fn factor(&mut self, bhat: &[Vector3<f64>], inv_mass: &[f64]) -> bool {
        if self.key.as_slice() != inv_mass {
            self.build(inv_mass);
        }
        if !self.ready {
            return false;
        }
        let mut coupled = [false; 3];
        for (b, &bar) in self.bh.chunks_exact_mut(3).zip(&self.bars) {
            let h = &bhat[bar];
            b.copy_from_slice(h.as_slice());
            coupled[0] |= h.x != 0.0;
            coupled[1] |= h.y != 0.0;
            coupled[2] |= h.z != 0.0;
        }
        self.coupled = coupled;
        for (w, e) in self.ew.iter_mut().zip(&self.entries) {
            *w = e.coef * self.bh[e.kd];
        }
        let nb = self.bars.len();
        // S_kl = δ_kl m_k/3 − Σ_d b̂_k[d] b̂_l[d] T_{kl,d} (lower triangle)
        for (k, (srow, bk)) in self
            .s
            .chunks_exact_mut(nb)
            .zip(self.bh.chunks_exact(3))
            .enumerate()
        {
            let trow = &self.t[3 * k * nb..3 * (k + 1) * nb];
            for (l, ((sv, bl), t)) in srow[..=k]
                .iter_mut()
                .zip(self.bh.chunks_exact(3))
                .zip(trow.chunks_exact(3))
                .enumerate()
            {
                let acc = bk[0] * bl[0] * t[0] + bk[1] * bl[1] * t[1] + bk[2] * bl[2] * t[2];
                let diag = if k == l { self.cinv[k] } else { 0.0 };
                *sv = diag - acc;
            }
        }
        // LDLᵀ, left-looking (β is small)
        let s = &mut self.s;
        for j in 0..nb {
            for i in j..nb {
                let (head, tail) = s.split_at_mut(i * nb);
                let ri = &mut tail[..nb];
                let sum = {
                    let rj = if i == j {
                        &ri[..j]
                    } else {
                        &head[j * nb..j * nb + j]
                    };
                    let mut sum = ri[j];
                    for ((a, b), d) in ri[..j].iter().zip(rj).zip(&self.dval[..j]) {
                        sum -= a * b * d;
                    }
                    sum
                };
                if i == j {
                    if sum.is_nan() || sum <= MIN_PIVOT_RATIO * self.cinv[j] {
                        return false;
                    }
                    self.dval[j] = sum;
                    self.dinv[j] = 1.0 / sum;
                } else {
                    ri[j] = sum * self.dinv[j];
                }
            }
        }
        true
    }

    /// Solves A x = rhs in place with the last successful [`factor`](Self::factor), refined
    /// once (x += A⁻¹(rhs − A x)).
    pub(super) fn solve_in_place(&mut self, rhs: &mut [f64]) {
        let mut x = std::mem::take(&mut self.x);
        let mut r = std::mem::take(&mut self.r0);
        for (&b, &p) in rhs.iter().zip(&self.pos) {
            x[p] = b;
        }
        self.solve_once(&mut x);
        // residual r − A x, with A x = A₀ x − Σ_k (3/m_k) u_k (u_kᵀ x)
        for (_, blk) in &self.active {
            let span = blk.start..blk.start + blk.lp;
            let a0 = &self.a0[blk.off..blk.off + blk.lp * blk.lp];
            block_product(a0, blk, &x[span.clone()], &mut r[span]);
        }
        for (&b, &p) in rhs.iter().zip(&self.pos) {
            r[p] = b - r[p];
        }
        for (k, c) in self.c.iter().enumerate() {
            let (lo, hi) = (self.bar_entries[k], self.bar_entries[k + 1]);
            let (ew, er) = (&self.ew[lo..hi], &self.erow[lo..hi]);
            let q: f64 = ew.iter().zip(er).map(|(w, &row)| w * x[row]).sum();
            let w = c * q;
            for (e, &row) in ew.iter().zip(er) {
                r[row] += w * e;
            }
        }
        self.solve_once(&mut r);
        for (b, &p) in rhs.iter_mut().zip(&self.pos) {
            *b = x[p] + r[p];
        }
        self.x = x;
        self.r0 = r;
    }

    /// One Woodbury solve of A x = b in place (internal order; the padding stays zero).
    fn solve_once(&mut self, b: &mut [f64]) {
        let nb = self.bars.len();
        // z = A₀⁻¹ b, block by block
        for (_, blk) in &self.active {
            let span = blk.start..blk.start + blk.lp;
            let inv = &self.a0inv[blk.off..blk.off + blk.lp * blk.lp];
            block_product(inv, blk, &b[span.clone()], &mut self.z[span]);
        }
        // g = Uᵀ z
        let z = &self.z;
        for (k, g) in self.g.iter_mut().enumerate() {
            let (lo, hi) = (self.bar_entries[k], self.bar_entries[k + 1]);
            *g = self.ew[lo..hi]
                .iter()
                .zip(&self.erow[lo..hi])
                .map(|(w, &row)| w * z[row])
                .sum();
        }
        // y = S⁻¹ g = L⁻ᵀ D⁻¹ L⁻¹ g
        let (s, g) = (&self.s, &mut self.g);
        for i in 0..nb {
            let li = &s[i * nb..i * nb + i];
            let sum: f64 = li.iter().zip(&g[..i]).map(|(l, g)| l * g).sum();
            g[i] -= sum;
        }
        for (g, d) in g.iter_mut().zip(&self.dinv) {
            *g *= d;
        }
        for i in (0..nb).rev() {
            let mut sum = 0.0;
            for p in i + 1..nb {
                sum += s[p * nb + i] * g[p];
            }
            g[i] -= sum;
        }
        // x = z + Σ_{k,d} y_k b̂_k[d] V_{k,d}, block by block (each entry summed in the
        // order k = 0, 1, …)
        for &(d, blk) in &self.active {
            let span = blk.start..blk.start + blk.lp;
            let out = &mut b[span.clone()];
            let zs = &self.z[span];
            if !self.coupled[d] {
                out.copy_from_slice(zs);
                continue;
            }
            let base = self.v_off[d];
            let vd = &self.v[base..base + nb * blk.lp];
            let bh = self.bh.chunks_exact(3);
            if let (Ok(o), Ok(z)) = (
                <&mut [f64; P]>::try_from(&mut *out),
                <&[f64; P]>::try_from(zs),
            ) {
                let mut acc = *z;
                for ((y, bk), v) in self.g.iter().zip(bh).zip(vd.as_chunks::<P>().0) {
                    let w = y * bk[d];
                    for i in 0..P {
                        acc[i] += w * v[i];
                    }
                }
                *o = acc;
                continue;
            }
            out.copy_from_slice(zs);
            for ((y, bk), v) in self.g.iter().zip(bh).zip(vd.chunks_exact(blk.lp)) {
                let w = y * bk[d];
                for (o, v) in out.iter_mut().zip(v) {
                    *o += w * v;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ConstraintMatrix;
    use crate::model::Model;
    use crate::test_models;
    use nalgebra::Vector3;
    use tensegrity_core::structure::Structure;

    /// The system of `s` twice: with the Woodbury form and with it removed (direct dense
    /// Cholesky of the assembled system).
    fn both(s: &Structure) -> (ConstraintMatrix, ConstraintMatrix, Vec<f64>) {
        let model = Model::new(s, None).unwrap();
        let rows: Vec<_> = model.linear_rows.iter().map(|r| r.row.clone()).collect();
        let lr = ConstraintMatrix::new(rows.clone(), true).unwrap();
        assert!(lr.low_rank.is_some(), "{} rows", rows.len());
        let mut direct = ConstraintMatrix::new(rows, true).unwrap();
        direct.low_rank = None;
        (lr, direct, model.inv_mass.clone())
    }

    /// Unit vectors out of the plane, different per bar (any directions give an SPD system
    /// when the constraints are independent).
    fn directions(nb: usize, seed: f64) -> Vec<Vector3<f64>> {
        (0..nb)
            .map(|k| {
                let a = seed + 1.3 * k as f64;
                Vector3::new(a.cos(), (2.1 * a).sin(), 0.4 * (0.7 * a).cos()).normalize()
            })
            .collect()
    }

    fn max_rel_diff(a: &[f64], b: &[f64]) -> f64 {
        let scale = a.iter().map(|v| v.abs()).fold(0.0, f64::max);
        assert!(scale > 1e-6);
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
            / scale
    }

    /// The Woodbury solve equals the Cholesky solve of the assembled Ω system (to round-off)
    /// on the MOTES D-bar (planar and tilted bars, changed masses), a partly supported D-bar
    /// and a two-D-bar chain.
    #[test]
    fn woodbury_matches_the_direct_solve() {
        let partial = test_models::partly_supported_dbar().unwrap();
        let cases = [
            test_models::motes_anchor_dbar().unwrap(),
            partial,
            test_models::dbar_chain(2).unwrap(),
        ];
        for (c, s) in cases.iter().enumerate() {
            let (mut lr, mut direct, inv_mass) = both(s);
            let n = lr.rows.len();
            for (trial, masses) in [inv_mass.clone(), inv_mass.iter().map(|m| 0.3 * m).collect()]
                .iter()
                .enumerate()
            {
                let bhat = directions(masses.len(), 0.2 + trial as f64 + c as f64);
                lr.assemble_and_factor(&bhat, masses).unwrap();
                assert!(lr.low_rank_active, "case {c}");
                direct.assemble_and_factor(&bhat, masses).unwrap();
                let rhs: Vec<f64> = (0..n).map(|i| (0.37 * i as f64 + 0.1).sin()).collect();
                let (mut x1, mut x2) = (rhs.clone(), rhs);
                lr.solve_in_place(&mut x1);
                direct.solve_in_place(&mut x2);
                let d = max_rel_diff(&x2, &x1);
                assert!(d < 1e-12, "case {c} trial {trial}: {d:e}");
            }
        }
    }

    /// 2000 RK4 steps of the MOTES anchor D-bar with the Woodbury path and with the Cholesky of
    /// the assembled system: the same trajectory to round-off, and N P = D kept as well.
    #[test]
    fn runs_agree_with_the_cholesky_path() {
        use crate::rk4::Rk4;
        use crate::Integrator;
        let s = test_models::motes_anchor_dbar().unwrap();
        let mut model = Model::new(&s, None).unwrap();
        // the Ω path (the joint-space form would replace it for this small structure)
        model.joint_space = None;
        let y0 = model.initial_state(&s).unwrap();
        let run = |woodbury: bool| {
            let mut ws = model.workspace().unwrap();
            if !woodbury {
                ws.omega.as_mut().unwrap().low_rank = None;
            }
            let mut rk = Rk4::new(y0.len());
            let mut y = y0.clone();
            let mut drift = 0.0_f64;
            for k in 0..2000 {
                rk.step(&model, &mut ws, k as f64 * 1e-3, &mut y, 1e-3)
                    .unwrap();
                drift = drift.max(model.constraint_error(&y));
            }
            let om = ws.omega.as_ref().unwrap();
            assert_eq!(om.low_rank_active, woodbury);
            (y, drift)
        };
        let (yw, dw) = run(true);
        let (yc, dc) = run(false);
        let d = max_rel_diff(&yc, &yw);
        assert!(d < 1e-10, "states differ by {d:e}");
        // the node has moved: the comparison is not between two resting states
        let moved = yw
            .iter()
            .zip(&y0)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(moved > 1e-2, "{moved}");
        assert!(
            dw < 1e-13 && dc < 1e-13,
            "‖NP − D‖ {dw:e} (Woodbury), {dc:e} (Cholesky)"
        );
    }

    /// A singular system (a bar pinned at both ends: S = m/3 − m/3 = 0) falls back to the
    /// direct factorisation, which reports it as before.
    #[test]
    fn singular_system_falls_back_to_the_direct_error() {
        let s = test_models::bar_pinned_at_both_ends().unwrap();
        let (mut lr, _, inv_mass) = both(&s);
        let bhat = [Vector3::x(), Vector3::y()];
        let e = lr.assemble_and_factor(&bhat, &inv_mass).unwrap_err();
        assert!(!lr.low_rank_active);
        assert!(
            matches!(
                e,
                tensegrity_core::error::CoreError::Dynamics(
                    tensegrity_core::error::DynamicsError::SingularConstraint { expected: 9, .. }
                )
            ),
            "{e:?}"
        );
    }
}
