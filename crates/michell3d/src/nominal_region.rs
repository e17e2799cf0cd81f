//! The nominal load region of complexity 1 and the smallest extra-string prestress that keeps
//! every other member's sign over all of it (§4.6–4.7).
//!
//! **The region.** The three tip members (node n₀₀₀₀ to level 1) carry f = T w for a tip
//! load w, T the 3×3 block of the unit tip responses (times the lengths). Their signs σ under
//! the nominal load w₀(−ι̂₃) define the nominal region of complexity 1 — the same for every q,
//! since the tip members are the complexity-1 truss —
//!
//! > C = { w : σᵢ (T w)ᵢ ≥ 0, i = 1, 2, 3 },
//!
//! a simplicial cone with inward facet normals gᵢ = σᵢ Tᵢ and extreme rays r_k = T⁻¹ σ_k e_k.
//! The prestress does not reach the tip members (node n₀₀₀₀ carries no string, so its three
//! members are in equilibrium with the load alone), so C does not depend on it.
//!
//! **Member forces.** Every other base member j carries f_j(w, t) = t P_j + b_j · w, with P_j
//! its force per newton of prestress in every extra string and b_j its force per unit tip
//! load; the extra strings carry t. Over the loads of magnitude w₀ in C, f_j ranges over
//! [t P_j + w₀ min_S b_j·ŵ, t P_j + w₀ max_S b_j·ŵ], S = C ∩ unit sphere.
//!
//! **Exact extremes over S.** The maximum of c·ŵ over S is attained at c/|c| if c ∈ C, else at
//! the normalised projection of c on a facet plane gᵢ·w = 0 when it lies in that facet, else
//! at an extreme ray; the largest of these candidates is the maximum ([`NominalCone::max_over`]).
//! This replaces a sampled sweep: the worst direction is exact.
//!
//! **Threshold.** Member j keeps one sign over C for every t ≥ t_j, where (with s = sign P_j)
//! t_j = max(0, w₀ max_S(−s b_j·ŵ) / |P_j|): the prestress sign then wins in every nominal
//! direction. The smallest prestress above which no member but the tip members changes sign
//! is t* = max_j t_j ([`min_extra_prestress`]); a member the prestress does not reach
//! (P_j = 0) whose load force changes sign over C makes the claim fail for every t, and is
//! reported ([`ExtraPrestress::unreachable`]).

use crate::error::{invalid, MichellError, Result};
use crate::extra_strings::{solve_prestressed, ExtraStrings};
use crate::loads::NodalLoads;
use crate::propagation::{unit_tip_responses, Method};
use crate::sizing::ZERO_FORCE_RTOL;
use crate::truss::MichellTruss;
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;

/// The nominal region of complexity 1 as a simplicial cone of load directions.
#[derive(Debug, Clone, PartialEq)]
pub struct NominalCone {
    /// Inward facet normals gᵢ = σᵢ Tᵢ.
    normals: [Vector3<f64>; 3],
    /// Unit extreme rays.
    rays: [Vector3<f64>; 3],
}

impl NominalCone {
    /// The region of the tip members of `truss` (3-D, q ≥ 1) around the nominal load −ι̂₃.
    pub fn of(truss: &MichellTruss, method: Method) -> Result<Self> {
        if truss.is_planar() {
            return Err(MichellError::NeedsThreeD {
                what: "the nominal load region",
            });
        }
        let [qx, qy, qz] = unit_tip_responses(truss, method)?;
        let members = truss.members();
        let t = Matrix3::from_fn(|i, a| [&qx, &qy, &qz][a][i] * members[i].length);
        let nominal = t * Vector3::new(0.0, 0.0, -1.0);
        let scale = nominal.amax();
        let mut signed = t;
        for i in 0..3 {
            if nominal[i].abs() <= 1e-9 * scale {
                return Err(invalid(
                    "polar",
                    std::f64::consts::PI,
                    format!("tip member {i} is unloaded under the nominal load: the region is degenerate"),
                ));
            }
            let s = nominal[i].signum();
            signed.row_mut(i).scale_mut(s);
        }
        let inverse = signed.try_inverse().ok_or(MichellError::SingularNode {
            node: vec![0, 0, 0, 0],
            relative_det: 0.0,
        })?;
        Ok(Self {
            normals: [0, 1, 2].map(|i| signed.row(i).transpose()),
            rays: [0, 1, 2].map(|k| inverse.column(k).normalize()),
        })
    }

    /// Whether the direction `w` lies in the region (to round-off).
    pub fn contains(&self, w: &Vector3<f64>) -> bool {
        let n = w.norm();
        self.normals
            .iter()
            .all(|g| g.dot(w) >= -1e-12 * g.norm() * n)
    }

    /// The unit extreme rays.
    pub fn rays(&self) -> &[Vector3<f64>; 3] {
        &self.rays
    }

    /// max over unit directions ŵ in the region of c·ŵ, and the maximiser.
    pub fn max_over(&self, c: &Vector3<f64>) -> (f64, Vector3<f64>) {
        let mut best = (f64::NEG_INFINITY, self.rays[0]);
        let mut offer = |w: Vector3<f64>| {
            let n = w.norm();
            if n > 0.0 && self.contains(&w) && c.dot(&w) / n > best.0 {
                best = (c.dot(&w) / n, w / n);
            }
        };
        offer(*c);
        for g in &self.normals {
            offer(c - g * (c.dot(g) / g.norm_squared()));
        }
        for r in self.rays {
            offer(r);
        }
        best
    }
}

/// The result of [`min_extra_prestress`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtraPrestress {
    /// t* (N): above it no member but the tip members changes sign over the region; `None`
    /// when some member cannot be held by any prestress (see `unreachable`).
    pub min_extra_prestress: Option<f64>,
    /// The member that sets t* (index among the base members).
    pub critical_member: Option<usize>,
    /// The load direction in which it reaches zero at t*: [azimuth, polar] (rad).
    pub worst_direction: Option<[f64; 2]>,
    /// Members that change sign over the region whatever the prestress.
    pub unreachable: Vec<usize>,
}

/// The base members' forces as linear functions of the prestress and the tip load:
/// f_j = t P_j + b_j · w.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearForces {
    /// P_j: force per newton of prestress (N/N).
    pub pre: Vec<f64>,
    /// b_j: force per unit tip load (N/N, per component).
    pub load: Vec<Vector3<f64>>,
}

impl LinearForces {
    /// Forces of every base member at prestress `t` (N) for the tip load `w` (N).
    pub fn forces(&self, w: &Vector3<f64>, t: f64) -> Vec<f64> {
        self.pre
            .iter()
            .zip(&self.load)
            .map(|(p, b)| t * p + b.dot(w))
            .collect()
    }
}

/// The [`LinearForces`] of `truss` with its extra strings.
pub fn member_data(
    truss: &MichellTruss,
    strings: &ExtraStrings,
    method: Method,
) -> Result<LinearForces> {
    let lengths = truss.lengths();
    let unit = solve_prestressed(truss, strings, &NodalLoads::new(), 1.0, method)?;
    let [qx, qy, qz] = unit_tip_responses(truss, method)?;
    Ok(LinearForces {
        pre: unit
            .base
            .force_density
            .iter()
            .zip(&lengths)
            .map(|(q, l)| q * l)
            .collect(),
        load: (0..lengths.len())
            .map(|j| lengths[j] * Vector3::new(qx[j], qy[j], qz[j]))
            .collect(),
    })
}

fn direction_angles(w: &Vector3<f64>) -> [f64; 2] {
    [w.y.atan2(w.x), w.z.clamp(-1.0, 1.0).acos()]
}

/// The smallest extra-string prestress t* for loads of magnitude `w0` (see the module docs).
pub fn min_extra_prestress(
    truss: &MichellTruss,
    strings: &ExtraStrings,
    w0: f64,
    method: Method,
) -> Result<ExtraPrestress> {
    let cone = NominalCone::of(truss, method)?;
    let data = member_data(truss, strings, method)?;
    let f_scale = data
        .load
        .iter()
        .map(|b| w0 * b.norm())
        .fold(0.0f64, f64::max);
    let tol = ZERO_FORCE_RTOL * f_scale;
    let mut out = ExtraPrestress {
        min_extra_prestress: Some(0.0),
        critical_member: None,
        worst_direction: None,
        unreachable: Vec::new(),
    };
    for j in 3..data.pre.len() {
        let (p, b) = (data.pre[j], data.load[j]);
        if p.abs() <= ZERO_FORCE_RTOL {
            let (hi, _) = cone.max_over(&b);
            let (lo, _) = cone.max_over(&-b);
            if w0 * hi > tol && w0 * lo > tol {
                out.unreachable.push(j);
            }
            continue;
        }
        let (m, w) = cone.max_over(&(-p.signum() * b));
        let t_j = (w0 * m / p.abs()).max(0.0);
        if out.min_extra_prestress.is_some_and(|t| t_j > t) {
            out.min_extra_prestress = Some(t_j);
            out.critical_member = Some(j);
            out.worst_direction = Some(direction_angles(&w));
        }
    }
    if !out.unreachable.is_empty() {
        out.min_extra_prestress = None;
    }
    Ok(out)
}

/// The base members other than the tip members that take both signs over the region at
/// prestress `prestress` (N) and load magnitude `w0`, from the exact extremes over the cone.
pub fn sign_changes(
    truss: &MichellTruss,
    strings: &ExtraStrings,
    w0: f64,
    prestress: f64,
    method: Method,
) -> Result<Vec<usize>> {
    let cone = NominalCone::of(truss, method)?;
    let data = member_data(truss, strings, method)?;
    let f_scale = data
        .load
        .iter()
        .zip(&data.pre)
        .map(|(b, p)| w0 * b.norm() + prestress * p.abs())
        .fold(0.0f64, f64::max);
    let tol = ZERO_FORCE_RTOL * f_scale;
    Ok((3..data.pre.len())
        .filter(|&j| {
            let base = prestress * data.pre[j];
            let hi = base + w0 * cone.max_over(&data.load[j]).0;
            let lo = base - w0 * cone.max_over(&-data.load[j]).0;
            hi > tol && lo < -tol
        })
        .collect())
}
