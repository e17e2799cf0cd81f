//! The constrained accelerations of a small jointed structure in joint space: N P = D
//! eliminated exactly instead of through Ω.
//!
//! The rows of N P = D tie the class-1 copies of a file node together and hold supported
//! directions. Their null space has a 0/1 basis Z: a free coordinate q_{i,d} (file node i, axis
//! d) moves every copy of node i along d, a held one nothing. With x = Z q + x_held, the
//! consistent mass of a rigid bar (kinetic energy ½m‖ṙ‖² + ½(m/12)‖ḃ‖²), (m/6)[[2, 1], [1, 2]]
//! ⊗ I₃ per bar, assembled over the constrained bars gives the constant H = Zᵀ M Z, block
//! diagonal by axis (H = H_x ⊕ H_y ⊕ H_z: the mass couples equal axes only). The bars keep
//! their lengths through multipliers λ on b_kᵀb̈_k = −‖ḃ_k‖² (b_k = x_end − x_start):
//!
//! H q̈ = Zᵀ F + Eᵀ λ,   E q̈ = −c,   E_k = Σ_d b_{k,d} δ_{k,d}ᵀ,   c_k = ‖ḃ_k‖²,
//!
//! with δ_{k,d} = e_{q(end,d)} − e_{q(start,d)} (a held end contributes nothing). Hence
//! q̈₀ = H⁻¹ Zᵀ F, (E H⁻¹ Eᵀ) λ = −c − E q̈₀ and q̈ = q̈₀ + H⁻¹ Eᵀ λ. The constants
//! V_{k,d} = H_d⁻¹ δ_{k,d} and T_{kl,d} = δ_{k,d}ᵀ V_{l,d} are computed once (the masses do not
//! change); an evaluation forms K_kl = Σ_d b_{k,d} b_{l,d} T_{kl,d} (β × β, SPD when the bar
//! constraints are independent), factors it (LDLᵀ), and updates
//! q̈_d = q̈₀_d + Σ_k λ_k b_{k,d} V_{k,d}; every copy of node i then gets q̈_{i,d}, a held
//! direction 0.
//!
//! This is the same linear system as the Ω closed form of `model` (the KKT system
//! M ẍ = F + Gᵀω + Bᵀλ, G ẍ = 0, B ẍ = −c; there λ is eliminated bar by bar and ω solved
//! for, here ω is eliminated by the null space and λ solved for), so the two agree to
//! round-off; this one takes ≈ 400 flops for the MOTES D-bar (β = 4 bars, three free nodes)
//! against ≈ 2,300 for the refined Woodbury solve of its 15 Ω rows, and it keeps the copies
//! of a node bitwise equal and held directions exactly held (N P = D exactly, not to
//! round-off). It is used for at most [`BMAX`] constrained bars and [`QMAX`] free coordinates
//! per axis; an evaluation whose K has a pivot below [`MIN_PIVOT_RATIO`] of its diagonal (or
//! NaN) is left to the Ω path, which then decides (and reports a singular constraint set
//! exactly as before).

use nalgebra::Vector3;
use tensegrity_linalg::DenseCholesky;

/// Largest number of constrained bars β of the joint-space form.
pub(crate) const BMAX: usize = 8;
/// Largest number of free coordinates per axis.
pub(crate) const QMAX: usize = 16;
/// The slot of a held coordinate: always 0 in the padded per-axis vectors.
const HELD: usize = QMAX;
/// A per-axis vector, padded with the held slot.
type QVec = [f64; QMAX + 1];
/// Smallest LDLᵀ pivot of K relative to its diagonal entry before the Ω path decides.
pub(crate) const MIN_PIVOT_RATIO: f64 = 1e-10;

/// One constrained bar: its class-1 nodes and its ends' coordinates per axis.
#[derive(Debug, Clone, Copy)]
struct JointBar {
    /// Bar index in the model (class-1 nodes 2k, 2k + 1).
    bar: usize,
    /// Per axis d: the free coordinate of the start and of the end (or [`HELD`]).
    q: [[usize; 2]; 3],
}

/// The constants of the joint-space form of one model.
#[derive(Debug, Clone)]
pub(crate) struct JointSpace {
    /// Free coordinates per axis.
    nq: [usize; 3],
    /// H_d⁻¹, row i at `hinv[d][i]` (symmetric; padding and the held slot zero).
    hinv: Box<[[QVec; QMAX]; 3]>,
    /// Per axis: (coordinate, class-1 node) for every copy of a free coordinate, sorted by
    /// coordinate (Zᵀ F).
    gather: [Vec<(usize, usize)>; 3],
    /// The constrained bars (local index k).
    bars: Vec<JointBar>,
    /// V_{k,d} at `v[d][k]`.
    v: Box<[[QVec; BMAX]; 3]>,
    /// T_{kl,d} at `t[k][l][d]` (k ≥ l).
    t: Box<[[[f64; 3]; BMAX]; BMAX]>,
}

/// Per-evaluation scratch of [`JointSpace::accelerations`].
#[derive(Debug, Clone)]
pub(crate) struct JointScratch {
    /// Zᵀ F, then q̈ (per axis, the held slot zero).
    q: [QVec; 3],
    /// b_k of the constrained bars.
    b: [[f64; 3]; BMAX],
    /// K, then its LDLᵀ factor (unit L strictly below the diagonal), row-major.
    k: [[f64; BMAX]; BMAX],
    /// D_jj.
    dval: [f64; BMAX],
    /// 1 / D_jj.
    dinv: [f64; BMAX],
    /// −c − E q̈₀, then λ.
    lambda: [f64; BMAX],
}

impl Default for JointScratch {
    fn default() -> Self {
        Self {
            q: [[0.0; QMAX + 1]; 3],
            b: [[0.0; 3]; BMAX],
            k: [[0.0; BMAX]; BMAX],
            dval: [0.0; BMAX],
            dinv: [0.0; BMAX],
            lambda: [0.0; BMAX],
        }
    }
}

impl JointSpace {
    /// The joint-space form for the bars `constrained` (model indices, sorted) with masses
    /// `mass`, where `node_of[c]` is the file node of class-1 node c, `copies[i]` the class-1
    /// copies of file node i and `fixed[i]` its held directions; `None` when the sizes
    /// exceed [`BMAX`] or [`QMAX`] or a mass block does not factor.
    pub(crate) fn new(
        constrained: &[usize],
        mass: &[f64],
        node_of: &[usize],
        copies: &[Vec<usize>],
        fixed: &[[bool; 3]],
    ) -> Option<Self> {
        if constrained.is_empty() || constrained.len() > BMAX {
            return None;
        }
        // the file nodes of the constrained bars, in order of first appearance
        let mut nodes: Vec<usize> = Vec::new();
        for &k in constrained {
            for c in [2 * k, 2 * k + 1] {
                if !nodes.contains(&node_of[c]) {
                    nodes.push(node_of[c]);
                }
            }
        }
        let mut coord = vec![[HELD; 3]; nodes.len()];
        let mut nq = [0; 3];
        let mut gather: [Vec<(usize, usize)>; 3] = Default::default();
        for (j, &i) in nodes.iter().enumerate() {
            for d in 0..3 {
                if !fixed[i][d] {
                    coord[j][d] = nq[d];
                    gather[d].extend(copies[i].iter().map(|&c| (nq[d], c)));
                    nq[d] += 1;
                }
            }
        }
        if nq.iter().any(|&n| n > QMAX) {
            return None;
        }
        let local = |c: usize| nodes.iter().position(|&i| i == node_of[c]).unwrap_or(0);
        let bars: Vec<JointBar> = constrained
            .iter()
            .map(|&k| {
                let (a, b) = (local(2 * k), local(2 * k + 1));
                JointBar {
                    bar: k,
                    q: [0, 1, 2].map(|d| [coord[a][d], coord[b][d]]),
                }
            })
            .collect();
        let mut hinv = Box::new([[[0.0; QMAX + 1]; QMAX]; 3]);
        for d in 0..3 {
            let n = nq[d];
            if n == 0 {
                continue;
            }
            // H_d = Σ_k (m_k/6)[[2, 1], [1, 2]] over the free ends (lower triangle)
            let mut chol = DenseCholesky::new(n);
            let h = chol.zeroed();
            for jb in &bars {
                let m6 = mass[jb.bar] / 6.0;
                let [qa, qb] = jb.q[d];
                for (p, r, w) in [(qa, qa, 2.0), (qb, qb, 2.0), (qa.max(qb), qa.min(qb), 1.0)] {
                    if p != HELD && r != HELD {
                        h[p * n + r] += w * m6;
                    }
                }
            }
            chol.factor_filled().ok()?;
            for j in 0..n {
                let mut col = vec![0.0; n];
                col[j] = 1.0;
                chol.solve_in_place(&mut col);
                for (i, c) in col.iter().enumerate() {
                    hinv[d][i][j] = *c;
                }
            }
        }
        let mut v = Box::new([[[0.0; QMAX + 1]; BMAX]; 3]);
        for d in 0..3 {
            for (k, jb) in bars.iter().enumerate() {
                let [qa, qb] = jb.q[d];
                for i in 0..nq[d] {
                    let row = &hinv[d][i];
                    v[d][k][i] = row[qb] - row[qa];
                }
            }
        }
        let mut t = Box::new([[[0.0; 3]; BMAX]; BMAX]);
        for (k, jk) in bars.iter().enumerate() {
            for l in 0..=k {
                for d in 0..3 {
                    let [qa, qb] = jk.q[d];
                    t[k][l][d] = v[d][l][qb] - v[d][l][qa];
                }
            }
        }
        Some(Self {
            nq,
            hinv,
            gather,
            bars,
            v,
            t,
        })
    }

    /// The accelerations of the constrained bars' class-1 nodes into `dv` (a velocity half of
    /// the state), from positions `x`, velocities `v` and applied forces `f` (class-1 nodes);
    /// `false` (with `dv` partly written) when K is singular or nearly so, or not finite.
    pub(crate) fn accelerations(
        &self,
        x: &[f64],
        v: &[f64],
        f: &[Vector3<f64>],
        dv: &mut [f64],
        s: &mut JointScratch,
    ) -> bool {
        let nb = self.bars.len();
        // Zᵀ F per axis (each coordinate summed over its copies in order)
        for (d, (q, gather)) in s.q.iter_mut().zip(&self.gather).enumerate() {
            q.fill(0.0);
            for &(i, c) in gather {
                q[i] += f[c][d];
            }
        }
        // q̈₀ = H⁻¹ Zᵀ F; the held slot stays 0
        for (d, q) in s.q.iter_mut().enumerate() {
            let n = self.nq[d];
            let r = *q;
            for (qi, row) in q.iter_mut().zip(self.hinv[d].iter()).take(n) {
                let mut acc = 0.0;
                for (h, rj) in row.iter().zip(&r).take(n) {
                    acc += h * rj;
                }
                *qi = acc;
            }
        }
        // b_k, and −c_k − E_k q̈₀ = −‖ḃ_k‖² − Σ_d b_{k,d} (q̈₀[end] − q̈₀[start])
        for ((jb, b), rhs) in self
            .bars
            .iter()
            .zip(s.b.iter_mut())
            .zip(s.lambda.iter_mut())
        {
            let (i, j) = (6 * jb.bar, 6 * jb.bar + 3);
            let (xa, xb) = (&x[i..i + 3], &x[j..j + 3]);
            let (va, vb) = (&v[i..i + 3], &v[j..j + 3]);
            let mut c = 0.0;
            let mut e = 0.0;
            for d in 0..3 {
                b[d] = xb[d] - xa[d];
                let bd = vb[d] - va[d];
                c += bd * bd;
                let [qa, qb] = jb.q[d];
                e += b[d] * (s.q[d][qb] - s.q[d][qa]);
            }
            *rhs = -c - e;
        }
        // K = Σ_d (b_d b_dᵀ) ∘ T_d and its LDLᵀ (left-looking, row by row)
        for k in 0..nb {
            for l in 0..=k {
                let (bk, bl, t) = (&s.b[k], &s.b[l], &self.t[k][l]);
                let mut sum = bk[0] * bl[0] * t[0] + bk[1] * bl[1] * t[1] + bk[2] * bl[2] * t[2];
                let diag = sum;
                for p in 0..l {
                    sum -= s.k[k][p] * s.k[l][p] * s.dval[p];
                }
                if l < k {
                    s.k[k][l] = sum * s.dinv[l];
                } else {
                    if sum.is_nan() || sum <= MIN_PIVOT_RATIO * diag {
                        return false;
                    }
                    s.dval[k] = sum;
                    s.dinv[k] = 1.0 / sum;
                }
            }
        }
        // K λ = rhs
        let lam = &mut s.lambda;
        for i in 0..nb {
            let mut sum = lam[i];
            for p in 0..i {
                sum -= s.k[i][p] * lam[p];
            }
            lam[i] = sum;
        }
        for i in 0..nb {
            lam[i] *= s.dinv[i];
        }
        for i in (0..nb).rev() {
            let mut sum = lam[i];
            for p in i + 1..nb {
                sum -= s.k[p][i] * lam[p];
            }
            lam[i] = sum;
        }
        // q̈_d = q̈₀_d + Σ_k λ_k b_{k,d} V_{k,d}
        for (d, q) in s.q.iter_mut().enumerate() {
            let n = self.nq[d];
            for ((lk, bk), vk) in lam.iter().zip(&s.b).zip(self.v[d].iter()).take(nb) {
                let w = lk * bk[d];
                for (qi, vi) in q.iter_mut().zip(vk).take(n) {
                    *qi += w * vi;
                }
            }
        }
        // every copy gets its node's acceleration
        for jb in &self.bars {
            let out = &mut dv[6 * jb.bar..6 * jb.bar + 6];
            for d in 0..3 {
                let [qa, qb] = jb.q[d];
                out[d] = s.q[d][qa];
                out[3 + d] = s.q[d][qb];
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use crate::model::Model;
    use crate::test_models;
    use tensegrity_core::structure::{Bar, StringMember, Structure, Support};

    /// A state near the structure's nodes: positions moved, velocities arbitrary (the two
    /// paths solve the same linear system for any state; copies may even differ).
    fn state(model: &Model, s: &Structure, seed: f64) -> Vec<f64> {
        let mut y = model.initial_state(s).unwrap();
        let n3 = y.len() / 2;
        for (i, v) in y.iter_mut().enumerate() {
            let w = (seed + 0.731 * i as f64).sin();
            *v += if i < n3 { 0.01 * w } else { 0.7 * w };
        }
        y
    }

    /// dv of the joint-space path and of the Ω path (the same model, the same state).
    fn both(model: &Model, y: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut ws = model.workspace().unwrap();
        let mut a = vec![0.0; y.len()];
        let mut b = vec![0.0; y.len()];
        model.rhs_with(0.3, y, &mut a, &mut ws, true).unwrap();
        model.rhs_with(0.3, y, &mut b, &mut ws, false).unwrap();
        (a, b)
    }

    /// A hub of three bars (one class-3 joint) with a free class-1 bar beside it, strings
    /// between them, one tip pinned and another held in z only.
    fn hub_with_free_bar() -> Structure {
        Structure::builder()
            .nodes([
                [0.0, 0.0, 0.0],
                [1.0, 0.1, 0.0],
                [-0.2, 1.0, 0.3],
                [0.1, -0.3, 1.0],
            ])
            .nodes([[2.0, 2.0, 0.5], [2.5, 1.0, 1.5]])
            .bar(Bar::new(0, 1).mass(1.0))
            .bar(Bar::new(2, 0).mass(2.0))
            .bar(Bar::new(0, 3).mass(0.5))
            .bar(Bar::new(4, 5).mass(1.5))
            .string(StringMember::new(1, 4).stiffness(50.0).rest_length(0.5))
            .string(StringMember::new(2, 5).stiffness(80.0).rest_length(0.5))
            .string(StringMember::new(3, 4).stiffness(30.0).rest_length(0.5))
            .support(Support::pinned(1))
            .support(Support::directions(3, [false, false, true]))
            .gravity([0.0, 0.0, -9.81])
            .build()
            .unwrap()
    }

    /// The joint-space accelerations equal the Ω closed form's to round-off: the MOTES
    /// D-bar, a partly supported D-bar, a two-D-bar chain (8 bars), the double pendulum and a
    /// hub with a free bar beside it (the free bar's closed form is the same code).
    #[test]
    fn joint_space_matches_the_omega_path() {
        let partial = test_models::partly_supported_dbar().unwrap();
        let cases = [
            test_models::motes_anchor_dbar().unwrap(),
            partial,
            test_models::dbar_chain(2).unwrap(),
            test_models::double_pendulum(0.7).unwrap(),
            hub_with_free_bar(),
        ];
        for (c, s) in cases.iter().enumerate() {
            let model = Model::new(s, None).unwrap();
            assert!(model.joint_space.is_some(), "case {c}");
            for seed in [0.1, 2.3] {
                let y = state(&model, s, seed);
                let (a, b) = both(&model, &y);
                let scale = b.iter().map(|v| v.abs()).fold(0.0, f64::max);
                assert!(scale > 1e-3, "case {c}");
                let d = a
                    .iter()
                    .zip(&b)
                    .map(|(p, q)| (p - q).abs())
                    .fold(0.0, f64::max);
                assert!(
                    d < 1e-12 * scale,
                    "case {c} seed {seed}: {d:e} of {scale:e}"
                );
            }
        }
    }

    /// 2000 RK4 steps of the MOTES D-bar: the copies of every joint stay bitwise equal and
    /// the pinned node does not move at all (‖N P − D‖ = 0 exactly), the mirror symmetry of
    /// the scene (y → −y, nodes 1 ↔ 3) holds to 1e-13 m, and the run agrees with the Ω path
    /// to 1e-9 m (round-off amplified by the dynamics, see docs/notes/PERFORMANCE.md).
    #[test]
    fn joint_space_run_keeps_the_joints_exactly() {
        use crate::rk4::Rk4;
        use crate::Integrator;
        let s = test_models::motes_anchor_dbar().unwrap();
        let joint = Model::new(&s, None).unwrap();
        let mut omega = Model::new(&s, None).unwrap();
        omega.joint_space = None;
        let run = |model: &Model| {
            let mut ws = model.workspace().unwrap();
            let mut y = model.initial_state(&s).unwrap();
            let mut rk = Rk4::new(y.len());
            let mut drift = 0.0_f64;
            for k in 0..2000 {
                rk.step(model, &mut ws, k as f64 * 1e-3, &mut y, 1e-3)
                    .unwrap();
                drift = drift.max(model.constraint_error(&y));
            }
            (y, drift)
        };
        let (yj, dj) = run(&joint);
        let (yo, _) = run(&omega);
        assert_eq!(dj, 0.0);
        let nodes = joint.nodes_of(&yj);
        assert!((nodes[1].x - nodes[3].x).abs() < 1e-13, "{nodes:?}");
        assert!((nodes[1].y + nodes[3].y).abs() < 1e-13, "{nodes:?}");
        assert!(nodes[2].y.abs() < 1e-13, "{nodes:?}");
        let d = yj
            .iter()
            .zip(&yo)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(d < 1e-9, "{d:e}");
        let moved = (nodes[2] - s.nodes()[2]).norm();
        assert!(moved > 0.1, "{moved}");
    }

    /// A bar pinned at both ends makes K singular: the Ω path decides and reports the
    /// singular constraint set as before.
    #[test]
    fn a_singular_system_is_left_to_the_omega_path() {
        let s = test_models::bar_pinned_at_both_ends().unwrap();
        let model = Model::new(&s, None).unwrap();
        assert!(model.joint_space.is_some());
        let y = model.initial_state(&s).unwrap();
        let mut ws = model.workspace().unwrap();
        let mut dy = vec![0.0; y.len()];
        let e = model.rhs(0.0, &y, &mut dy, &mut ws).unwrap_err();
        assert!(
            matches!(
                e,
                tensegrity_core::error::CoreError::Dynamics(
                    tensegrity_core::error::DynamicsError::SingularConstraint { .. }
                )
            ),
            "{e:?}"
        );
    }

    /// More bars than [`super::BMAX`] keep the Ω path.
    #[test]
    fn large_structures_keep_the_omega_path() {
        let s = test_models::dbar_chain(3).unwrap();
        assert!(Model::new(&s, None).unwrap().joint_space.is_none());
    }
}
