//! Adaptive force density: force densities found from the connectivity.
//!
//! A free-standing 3-D form needs D(q) = Cᵀ diag(q) C with rank deficiency d + 1 = 4, and a
//! super-stable one D positive semi-definite. Following the spectral iteration of Zhang and
//! Ohsaki (with the group equalities of Tibert and Pellegrino's symmetric formulation), the
//! force densities are parameterised q = G p (one parameter p_g per group, one per
//! ungrouped member) and iterated:
//!
//! 1. D(q) = Σ_i λ_i φ_i φ_iᵀ, eigenvalues ascending;
//! 2. the target D̄ = Σ_{i≥4} max(λ_i, 0) φ_i φ_iᵀ: the nearest positive semi-definite
//!    matrix of rank ≤ n − 4 (the four smallest eigenvalues set to zero, any other negative
//!    one too — a super-stable form has D ⪰ 0);
//! 3. the admissible q closest to it, min_p ‖D(G p) − D̄‖_F: the normal equations
//!    Gᵀ H G p = Gᵀ r with H_kl = (c_k · c_l)² (4 on the diagonal, 1 for members sharing a
//!    node) and r_k = c_kᵀ D̄ c_k;
//! 4. signs enforced (a string's parameter at least 10⁻³ of the mean |p|, a bar's at most
//!    minus that), and p rescaled to its initial norm (D and D̄ are homogeneous in q, and the
//!    iteration would otherwise creep towards q = 0).
//!
//! It stops when max_{i<4} |λ_i| ≤ tolerance · max|λ| ([`crate::Settings::tolerance`]) and
//! fails with [`FormFindError::NotConverged`] after `max_iterations`. The start is the given
//! force densities (member, else group), else 1/L for strings and −s/L for bars (L the
//! member's length at the initial nodes, averaged over a group: equal member forces; 1 when
//! there are no nodes), s found by
//! bisection where the fourth smallest eigenvalue of D reaches zero. Once that eigenvalue
//! is below 10⁻⁴ of the largest, Newton steps replace the projection (p projected onto the
//! null space of J = [vec(Φᵀ D_g Φ)]_g, Φ the four eigenvectors of the smallest eigenvalues),
//! and after the tolerance they continue while they gain a factor of ten, so the form is
//! exact to round-off (the statics' rank decision needs it). The geometry is
//! then the force density method's for the final q (the same normalisation), and q is scaled
//! so that the bars' force densities average −1 (the strings' +1 without bars). A result
//! with a string not in tension or a bar not in compression is refused
//! ([`FormFindError::NoPrestress`]).

use crate::error::{FormFindError, Result};
use crate::fdm;
use crate::method::Settings;
use crate::topology::Topology;
use nalgebra::{DMatrix, DVector, Vector3};
use std::collections::BTreeMap;

/// Largest topology (nodes) of the adaptive method, which takes a dense eigendecomposition
/// of D per iteration.
pub const MAX_NODES: usize = fdm::DENSE_MAX_NODES;

/// The force-density parameters: member k has q_k = p[param[k]].
struct Params {
    param: Vec<usize>,
    is_bar: Vec<bool>,
    start: Vec<f64>,
    given: bool,
}

fn params(topology: &Topology) -> Params {
    let given = topology.given_force_densities();
    let mut by_group: BTreeMap<&str, usize> = BTreeMap::new();
    let mut param = Vec::with_capacity(given.len());
    let mut sums: Vec<(f64, usize)> = Vec::new();
    let mut is_bar = Vec::new();
    for (k, m) in topology.members().enumerate() {
        let bar = topology.is_bar(k);
        let p = match m.group.as_deref() {
            Some(g) => *by_group.entry(g).or_insert_with(|| {
                sums.push((0.0, 0));
                is_bar.push(bar);
                sums.len() - 1
            }),
            None => {
                sums.push((0.0, 0));
                is_bar.push(bar);
                sums.len() - 1
            }
        };
        if let Some(q) = given[k] {
            sums[p].0 += q;
            sums[p].1 += 1;
        }
        param.push(p);
    }
    // Default magnitude per parameter: the mean of 1/L over its members at the initial
    // nodes (equal member forces), else 1.
    let mut inv_len = vec![(0.0, 0usize); sums.len()];
    if let Some(x) = topology.initial_nodes() {
        for (k, &[i, j]) in topology.member_nodes().iter().enumerate() {
            let l = (x[j] - x[i]).norm();
            if l > 0.0 {
                inv_len[param[k]].0 += 1.0 / l;
                inv_len[param[k]].1 += 1;
            }
        }
    }
    let start = sums
        .iter()
        .zip(&is_bar)
        .zip(&inv_len)
        .map(|((&(s, c), &bar), &(il, ic))| {
            let q = if c > 0 { s / c as f64 } else { 0.0 };
            let ok = if bar { q < 0.0 } else { q > 0.0 };
            let magnitude = if ic > 0 { il / ic as f64 } else { 1.0 };
            match (ok, bar) {
                (true, _) => q,
                (false, true) => -magnitude,
                (false, false) => magnitude,
            }
        })
        .collect();
    Params {
        param,
        is_bar,
        start,
        given: sums.iter().any(|&(_, c)| c > 0),
    }
}

/// Runs the iteration: nodes, force densities, iterations.
pub(crate) fn run(
    topology: &Topology,
    settings: &Settings,
) -> Result<(Vec<Vector3<f64>>, Vec<f64>, usize)> {
    if !topology.fixed.is_empty() {
        return Err(FormFindError::Unsupported {
            what: "the adaptive method with fixed nodes (give force densities and use the \
                   force density method)"
                .into(),
        });
    }
    if topology.n_nodes > MAX_NODES {
        return Err(FormFindError::Unsupported {
            what: format!(
                "the adaptive method on {} nodes (at most {MAX_NODES}: it takes a dense \
                 eigendecomposition per iteration); give force densities and use the force \
                 density method, which is sparse",
                topology.n_nodes
            ),
        });
    }
    let pr = params(topology);
    let pairs = topology.member_nodes();
    let n = topology.n_nodes;
    let g = pr.start.len();
    let gram = gram(n, &pairs, &pr.param, g);
    let chol = gram
        .clone()
        .cholesky()
        .ok_or_else(|| FormFindError::SingularSystem {
            hint: "the groups' force-density matrices are linearly dependent".into(),
        })?;
    let mut p = DVector::from_vec(pr.start.clone());
    // D and the iteration are homogeneous in p: start at unit scale, so force densities
    // near the largest double do not overflow the eigenvalues
    p /= p.amax().max(f64::MIN_POSITIVE);
    if !pr.given {
        scale_bars(&pairs, &pr, n, &mut p)?;
    }
    let norm0 = p.norm();
    let mut err = f64::INFINITY;
    // After convergence to the tolerance, Newton polishing steps continue while they gain a
    // factor of ten (at most POLISH of them), so the form is exact to round-off.
    let mut best: Option<(f64, DVector<f64>, usize)> = None;
    let mut polish = 0;
    for it in 1..=settings.max_iterations {
        let q: Vec<f64> = pr.param.iter().map(|&i| p[i]).collect();
        let d = fdm::dense_matrix(&pairs, &q, n);
        let (w, v) = tensegrity_linalg::symmetric_eigen(&d)?;
        let scale = w.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        err = w.iter().take(4).fold(0.0f64, |a, x| a.max(x.abs())) / scale;
        if let Some((e_best, p_best, it_best)) = &best {
            if err > 0.1 * e_best || polish >= POLISH {
                let (p_best, it_best) = (p_best.clone(), *it_best);
                return finish(topology, &pr, p_best, it_best);
            }
        }
        if err <= settings.tolerance {
            best = Some((err, p.clone(), it));
            polish += 1;
        }
        let next = if err <= NEWTON_SWITCH {
            newton_step(&pairs, &pr.param, &v, &p)
        } else {
            None
        };
        p = match next {
            Some(pn) => pn,
            None => spectral_step(&pairs, &pr.param, &d, &w, &v, &chol, g),
        };
        let mean = p.iter().map(|x| x.abs()).sum::<f64>() / g as f64;
        for (x, &bar) in p.iter_mut().zip(&pr.is_bar) {
            let floor = 1e-3 * mean;
            *x = if bar { x.min(-floor) } else { x.max(floor) };
        }
        let norm = p.norm();
        if !(norm.is_finite() && norm > 0.0) {
            break;
        }
        p *= norm0 / norm;
    }
    if let Some((_, p_best, it_best)) = best {
        return finish(topology, &pr, p_best, it_best);
    }
    if !err.is_finite() {
        return Err(FormFindError::NonFinite {
            method: "adaptive".into(),
            item: "the force densities".into(),
        });
    }
    Err(FormFindError::NotConverged {
        method: "adaptive".into(),
        iterations: settings.max_iterations,
        residual: err,
        tolerance: settings.tolerance,
    })
}

/// Scales the bars' parameters by the s at which the fourth smallest eigenvalue of D
/// reaches zero (bisection, 60 halvings), the start of the iteration when no force density
/// is given.
fn scale_bars(pairs: &[[usize; 2]], pr: &Params, n: usize, p: &mut DVector<f64>) -> Result<()> {
    let lambda3 = |s: f64| -> Result<f64> {
        let q: Vec<f64> = pr
            .param
            .iter()
            .map(|&i| if pr.is_bar[i] { s * p[i] } else { p[i] })
            .collect();
        let (w, _) = tensegrity_linalg::symmetric_eigen(&fdm::dense_matrix(pairs, &q, n))?;
        Ok(w.get(3).copied().unwrap_or(0.0))
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    let mut grow = 0;
    while lambda3(hi)? > 0.0 {
        lo = hi;
        hi *= 2.0;
        grow += 1;
        if grow > 60 {
            return Ok(());
        }
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if lambda3(mid)? > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    for (x, &bar) in p.iter_mut().zip(&pr.is_bar) {
        if bar {
            *x *= hi;
        }
    }
    Ok(())
}

/// Relative size of the four smallest eigenvalues below which Newton steps replace the
/// spectral projection.
const NEWTON_SWITCH: f64 = 1e-4;

/// Newton polishing steps after the tolerance is reached.
const POLISH: usize = 4;

/// One step of the spectral projection (module docs, steps 2 and 3).
fn spectral_step(
    pairs: &[[usize; 2]],
    param: &[usize],
    d: &DMatrix<f64>,
    w: &[f64],
    v: &DMatrix<f64>,
    chol: &nalgebra::Cholesky<f64, nalgebra::Dyn>,
    g: usize,
) -> DVector<f64> {
    let mut r = DVector::zeros(g);
    for (k, &[a, b]) in pairs.iter().enumerate() {
        let mut rk = d[(a, a)] + d[(b, b)] - 2.0 * d[(a, b)];
        for (i, &wi) in w.iter().enumerate() {
            if i >= 4 && wi >= 0.0 {
                break;
            }
            let dv = v[(a, i)] - v[(b, i)];
            rk -= wi * dv * dv;
        }
        r[param[k]] += rk;
    }
    chol.solve(&r)
}

/// A Newton (projection) step: with Φ the four eigenvectors of the smallest eigenvalues and
/// B_g = Φᵀ D_g Φ the parameters' blocks, the p' closest to p with Σ_g p'_g B_g = 0 (the
/// projection of p onto the null space of J = [vec B_g]); `None` when J has no null space.
fn newton_step(
    pairs: &[[usize; 2]],
    param: &[usize],
    v: &DMatrix<f64>,
    p: &DVector<f64>,
) -> Option<DVector<f64>> {
    let g = p.len();
    let mut j = DMatrix::zeros(10, g);
    for (k, &[a, b]) in pairs.iter().enumerate() {
        let dv: Vec<f64> = (0..4).map(|i| v[(a, i)] - v[(b, i)]).collect();
        let mut row = 0;
        for i in 0..4 {
            for l in i..4 {
                j[(row, param[k])] += dv[i] * dv[l];
                row += 1;
            }
        }
    }
    let svd = j.svd(false, true);
    let vt = svd.v_t?;
    let smax = svd.singular_values.max();
    let rank = svd
        .singular_values
        .iter()
        .filter(|&&s| s > 1e-10 * smax)
        .count();
    if rank >= g {
        return None;
    }
    // p' = p − Σ_{rank} (v_i · p) v_i over the row space of J.
    let mut out = p.clone();
    for (i, s) in svd.singular_values.iter().enumerate() {
        if *s > 1e-10 * smax {
            let vi = vt.row(i).transpose();
            out -= &vi * vi.dot(p);
        }
    }
    Some(out)
}

/// Gᵀ H G with H_kl = (c_k · c_l)².
fn gram(n: usize, pairs: &[[usize; 2]], param: &[usize], g: usize) -> DMatrix<f64> {
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (k, &[a, b]) in pairs.iter().enumerate() {
        at[a].push(k);
        at[b].push(k);
    }
    let mut m = DMatrix::zeros(g, g);
    for k in 0..pairs.len() {
        m[(param[k], param[k])] += 4.0;
    }
    for members in &at {
        for &k in members {
            for &l in members {
                if k != l {
                    m[(param[k], param[l])] += 1.0;
                }
            }
        }
    }
    m
}

/// The geometry of the converged q, its sign check and normalisation.
fn finish(
    topology: &Topology,
    pr: &Params,
    p: DVector<f64>,
    iterations: usize,
) -> Result<(Vec<Vector3<f64>>, Vec<f64>, usize)> {
    let mut q: Vec<f64> = pr.param.iter().map(|&i| p[i]).collect();
    if let Some(k) = (0..q.len()).find(|&k| {
        if pr.is_bar[pr.param[k]] {
            q[k] >= 0.0
        } else {
            q[k] <= 0.0
        }
    }) {
        return Err(FormFindError::NoPrestress {
            reason: format!(
                "the adaptive iteration converged with {} at force density {:.3e}, of the \
                 wrong sign",
                topology.member_name(k),
                q[k]
            ),
        });
    }
    let nb = topology.bars.len();
    let mean = if nb > 0 {
        -q[..nb].iter().sum::<f64>() / nb as f64
    } else {
        q.iter().sum::<f64>() / q.len() as f64
    };
    for x in q.iter_mut() {
        *x /= mean;
    }
    let nodes = fdm::geometry(topology, &q)?;
    Ok((nodes, q, iterations))
}
