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
use crate::linalg::DenseCholesky;
use nalgebra::Vector3;

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

/// Width of the register accumulators of the block products; blocks are padded to a multiple
/// of it with zeros, so the inner loops have no remainder.
const W: usize = 4;

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
/// with the accumulators in registers.
#[inline]
fn block_product(m: &[f64], blk: &Block, x: &[f64], out: &mut [f64]) {
    if x.iter().all(|v| *v == 0.0) {
        // a planar structure's out-of-plane block
        out.fill(0.0);
        return;
    }
    for (c, o) in out.chunks_exact_mut(W).enumerate() {
        let mut acc = [0.0; W];
        for (xj, row) in x.iter().zip(m.chunks_exact(blk.lp)).take(blk.len) {
            for (a, r) in acc.iter_mut().zip(&row[c * W..c * W + W]) {
                *a += xj * r;
            }
        }
        o.copy_from_slice(&acc);
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
    /// V_{k,d} = A₀⁻¹ c_{k,d} on the rows of block d, at `v_off[3k + d]`.
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
        for (d, b) in blocks.iter_mut().enumerate() {
            let len = row_axis.iter().filter(|&&a| a == d).count();
            let lp = len.div_ceil(W) * W;
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
        let mut v_off = Vec::with_capacity(3 * nb);
        let mut vlen = 0;
        for _ in 0..nb {
            for b in &blocks {
                v_off.push(vlen);
                vlen += b.lp;
            }
        }
        Some(Self {
            pos: internal,
            blocks,
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
        self.coupled = [false; 3];
        for (b, &bar) in self.bh.chunks_exact_mut(3).zip(&self.bars) {
            b.copy_from_slice(bhat[bar].as_slice());
            for (c, v) in self.coupled.iter_mut().zip(b.iter()) {
                *c |= *v != 0.0;
            }
        }
        let nb = self.bars.len();
        // S_kl = δ_kl m_k/3 − Σ_d b̂_k[d] b̂_l[d] T_{kl,d} (lower triangle)
        for k in 0..nb {
            let bk = &self.bh[3 * k..3 * k + 3];
            for l in 0..=k {
                let bl = &self.bh[3 * l..3 * l + 3];
                let t = &self.t[(k * nb + l) * 3..][..3];
                let acc = bk[0] * bl[0] * t[0] + bk[1] * bl[1] * t[1] + bk[2] * bl[2] * t[2];
                let diag = if k == l { self.cinv[k] } else { 0.0 };
                self.s[k * nb + l] = diag - acc;
            }
        }
        // LDLᵀ, left-looking (β is small)
        for j in 0..nb {
            for i in j..nb {
                let mut sum = self.s[i * nb + j];
                for p in 0..j {
                    sum -= self.s[i * nb + p] * self.s[j * nb + p] * self.dval[p];
                }
                if i == j {
                    if sum.is_nan() || sum <= MIN_PIVOT_RATIO * self.cinv[j] {
                        return false;
                    }
                    self.dval[j] = sum;
                    self.dinv[j] = 1.0 / sum;
                } else {
                    self.s[i * nb + j] = sum * self.dinv[j];
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
        for blk in self.blocks.iter().filter(|b| b.len > 0) {
            let span = blk.start..blk.start + blk.lp;
            let a0 = &self.a0[blk.off..blk.off + blk.lp * blk.lp];
            block_product(a0, blk, &x[span.clone()], &mut r[span]);
        }
        for (&b, &p) in rhs.iter().zip(&self.pos) {
            r[p] = b - r[p];
        }
        for (k, c) in self.c.iter().enumerate() {
            let ents = &self.entries[self.bar_entries[k]..self.bar_entries[k + 1]];
            let q: f64 = ents.iter().map(|e| e.coef * self.bh[e.kd] * x[e.row]).sum();
            let w = c * q;
            for e in ents {
                r[e.row] += w * e.coef * self.bh[e.kd];
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
        for blk in self.blocks.iter().filter(|b| b.len > 0) {
            let span = blk.start..blk.start + blk.lp;
            let inv = &self.a0inv[blk.off..blk.off + blk.lp * blk.lp];
            block_product(inv, blk, &b[span.clone()], &mut self.z[span]);
        }
        // g = Uᵀ z
        for (k, g) in self.g.iter_mut().enumerate() {
            let ents = &self.entries[self.bar_entries[k]..self.bar_entries[k + 1]];
            *g = ents
                .iter()
                .map(|e| e.coef * self.bh[e.kd] * self.z[e.row])
                .sum();
        }
        // y = S⁻¹ g = L⁻ᵀ D⁻¹ L⁻¹ g
        for i in 0..nb {
            let li = &self.s[i * nb..i * nb + i];
            let sum: f64 = li.iter().zip(&self.g[..i]).map(|(l, g)| l * g).sum();
            self.g[i] -= sum;
        }
        for (g, d) in self.g.iter_mut().zip(&self.dinv) {
            *g *= d;
        }
        for i in (0..nb).rev() {
            let mut sum = 0.0;
            for p in i + 1..nb {
                sum += self.s[p * nb + i] * self.g[p];
            }
            self.g[i] -= sum;
        }
        // x = z + Σ_{k,d} y_k b̂_k[d] V_{k,d}, block by block in register accumulators
        for (d, blk) in self.blocks.iter().enumerate().filter(|(_, b)| b.len > 0) {
            if !self.coupled[d] {
                // x = z on this block
                b[blk.start..blk.start + blk.lp]
                    .copy_from_slice(&self.z[blk.start..blk.start + blk.lp]);
                continue;
            }
            let span = blk.start..blk.start + blk.lp;
            for (c, (o, z)) in b[span.clone()]
                .chunks_exact_mut(W)
                .zip(self.z[span].chunks_exact(W))
                .enumerate()
            {
                let mut acc = [0.0; W];
                acc.copy_from_slice(z);
                for (k, y) in self.g.iter().enumerate() {
                    let w = y * self.bh[3 * k + d];
                    let v = &self.v[self.v_off[3 * k + d] + c * W..][..W];
                    for (a, v) in acc.iter_mut().zip(v) {
                        *a += w * v;
                    }
                }
                o.copy_from_slice(&acc);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ConstraintMatrix;
    use crate::dynamics::model::Model;
    use crate::structure::{Bar, Structure, Support};
    use crate::test_models;
    use nalgebra::Vector3;

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
        let mut partial = test_models::dbar(2.0, 0.5, 1.5, 1000.0, 0.05).unwrap();
        let fixed = partial.nodes().len() - 1;
        partial = partial
            .to_builder()
            .support(Support::directions(0, [true, false, true]))
            .support(Support::directions(fixed, [false, true, false]))
            .build()
            .unwrap();
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
        use crate::dynamics::rk4::Rk4;
        use crate::dynamics::Integrator;
        let s = test_models::motes_anchor_dbar().unwrap();
        let model = Model::new(&s, None).unwrap();
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
        let s = Structure::builder()
            .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]])
            .bar(Bar::new(0, 1).mass(1.0))
            .bar(Bar::new(1, 2).mass(2.0))
            .support(Support::pinned(0))
            .support(Support::pinned(1))
            .build()
            .unwrap();
        let (mut lr, _, inv_mass) = both(&s);
        let bhat = [Vector3::x(), Vector3::y()];
        let e = lr.assemble_and_factor(&bhat, &inv_mass).unwrap_err();
        assert!(!lr.low_rank_active);
        assert!(
            matches!(
                e,
                crate::error::CoreError::Dynamics(
                    crate::error::DynamicsError::SingularConstraint { expected: 9, .. }
                )
            ),
            "{e:?}"
        );
    }
}
