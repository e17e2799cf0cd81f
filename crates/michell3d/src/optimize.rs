//! Michell optima in Skelton's setting (thesis §4.1 and the results it builds on): the tip
//! point and the support circle are given, i.e. the radius ratio ρ = r_q / r₀ ∈ (0, 1) is
//! fixed, so a = ρ^(1/q) and the departure angle follows the segmentation angle through
//! sin β / sin(β + φ) = a:
//!
//! > tan β = a sin φ / (1 − a cos φ).
//!
//! **Planar truss, yield mass** (ERRATA 4.3). With sin(β+φ) = sin β / a the normalised yield
//! mass q sin φ / (sin β sin(β+φ)) becomes f(φ) = q (1 + a² − 2a cos φ) / (a sin φ), whose
//! only stationary point in (0, π) is
//!
//! > cos φ* = 2a / (1 + a²),  tan β* = a,  f* = q (1/a − a) = 2q sinh(ln(1/ρ)/q),
//!
//! decreasing in q towards Michell's continuum 2 ln(1/ρ) ([`continuum_normalized`]). The
//! mass in kilograms is (ϱ/σ) w₀ r₀ f for a material of density ϱ and yield strength σ.
//!
//! **Joint mass.** Each node (supports included) costs `joint_mass` kilograms, so the total
//! m(q) = m_members(q) + m_j N(q) with N(q) = (q+1)(q+2)/2 nodes in the plane and
//! Σ_{l≤q} (l+1)² … (merged tuples, counted from the built truss) in 3-D. Without a joint
//! mass the member mass decreases with q for ever (towards the continuum), so an optimal q
//! exists only with `joint_mass > 0`: the search runs q = 1, 2, … and stops as soon as the
//! joints alone of the next q weigh more than the best design so far (no larger q can win).
//!
//! **3-D trusses** (cylindrical δ, spherical ε): no closed form; the member mass with bars
//! sized for max(yield, buckling) and strings for yield (§4.5) is minimised over φ by a grid
//! scan of (0, π) followed by golden-section refinement of the best bracket, each evaluation
//! a full force propagation and sizing. The mass penalty of the spatial truss is the optimal
//! 3-D mass over the optimal planar mass at the same q, ρ, material and load, the planar
//! optimum found the same way with the same (yield + buckling) sizing, so that the ratio
//! compares like with like.

use crate::error::{invalid, Result};
use crate::params::{Geometry, MichellParams};
use crate::report::{analyse, AnalysisRequest};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_derive::Columns;

/// Grid points of the φ scan before golden-section refinement.
const PHI_GRID: usize = 48;
/// Golden-section tolerance on φ (rad).
const PHI_TOL: f64 = 1e-9;

/// What [`optimize`] minimises.
#[derive(Debug, Clone, PartialEq)]
pub struct OptimizeRequest {
    /// Planar, or the 3-D family with its δ or ε.
    pub geometry: Geometry,
    /// ρ = r_q / r₀, in (0, 1).
    pub radius_ratio: f64,
    /// The complexity q; `None` optimises it (needs `joint_mass > 0`).
    pub complexity: Option<usize>,
    /// Mass of one joint (kg), added per node.
    pub joint_mass: f64,
    /// Material of bars and strings (a built-in name).
    pub material: String,
    /// Tip load w₀ (N), along −ι̂₃ (perpendicular to the tip radius, in the plane).
    pub load: f64,
    /// Initial radius r₀ (m).
    pub r0: f64,
    /// Largest q the complexity search tries.
    pub max_complexity: usize,
}

impl OptimizeRequest {
    /// A request with w₀ = 1000 N, r₀ = 1 m, steel, no joint mass, q to be given.
    ///
    /// ```
    /// use michell3d::optimize::OptimizeRequest;
    /// use michell3d::Geometry;
    /// let r = OptimizeRequest::new(Geometry::Planar, 0.25);
    /// assert_eq!((r.load, r.r0, r.joint_mass), (1000.0, 1.0, 0.0));
    /// ```
    pub fn new(geometry: Geometry, radius_ratio: f64) -> Self {
        Self {
            geometry,
            radius_ratio,
            complexity: None,
            joint_mass: 0.0,
            material: "steel".to_string(),
            load: 1000.0,
            r0: 1.0,
            max_complexity: 60,
        }
    }

    fn validate(&self) -> Result<()> {
        let rho = self.radius_ratio;
        if !(rho.is_finite() && rho > 0.0 && rho < 1.0) {
            return Err(invalid(
                "radius_ratio",
                rho,
                "must lie in (0, 1): the supports are inside the tip radius",
            ));
        }
        if !(self.joint_mass.is_finite() && self.joint_mass >= 0.0) {
            return Err(invalid(
                "joint_mass",
                self.joint_mass,
                "must be finite and ≥ 0",
            ));
        }
        for (name, v) in [("load", self.load), ("r0", self.r0)] {
            if !(v.is_finite() && v > 0.0) {
                return Err(invalid(name, v, "must be finite and > 0"));
            }
        }
        match self.complexity {
            Some(0) => Err(invalid("complexity", 0.0, "must be at least 1")),
            None if self.joint_mass == 0.0 => Err(invalid(
                "joint_mass",
                0.0,
                "an optimal complexity needs a joint mass > 0 (without one the mass decreases \
                 with q towards Michell's continuum): give complexity or joint_mass",
            )),
            None if self.max_complexity == 0 => {
                Err(invalid("max_complexity", 0.0, "must be at least 1"))
            }
            _ => Ok(()),
        }
    }
}

/// The optimal design of [`optimize`]; serialises to the JSON of `michell optimize`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct Optimum {
    /// `planar`, `cylindrical` or `spherical`.
    #[column(nested)]
    pub geometry: Geometry,
    /// ρ = r_q / r₀.
    pub radius_ratio: f64,
    /// Departure angle β (rad).
    #[column(unit = "rad")]
    pub beta: f64,
    /// Segmentation angle φ (rad).
    #[column(unit = "rad")]
    pub phi: f64,
    /// Complexity q (optimised when not given).
    pub complexity: usize,
    /// Members plus joints (kg): yield sizing in the plane, yield + buckling in 3-D.
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// Members only (kg).
    #[column(unit = "kg")]
    pub member_mass_kg: f64,
    /// Joints only (kg).
    #[column(unit = "kg")]
    pub joint_mass_kg: f64,
    /// Number of joints (nodes, supports included).
    pub joints: usize,
    /// Σ|q|l²/(w₀ r₀) of the optimal design.
    pub normalized_yield_mass: f64,
    /// Michell's continuum 2 ln(1/ρ), the q → ∞ limit of the planar optimum.
    pub continuum_normalized_mass: f64,
    /// 3-D only: the optimal planar mass (yield + buckling, joints) at the same q.
    #[column(unit = "kg")]
    pub planar_mass_kg: Option<f64>,
    /// 3-D only: `mass_kg / planar_mass_kg`, the mass penalty of the spatial truss.
    pub mass_penalty: Option<f64>,
    /// The largest q the complexity search evaluated (= `complexity` when q was given).
    pub searched_to: usize,
}

/// β from φ at radius ratio a: tan β = a sin φ / (1 − a cos φ), so sin β / sin(β+φ) = a.
///
/// ```
/// use michell3d::optimize::beta_for;
/// let (a, phi) = (0.8_f64, 0.5_f64);
/// let b = beta_for(a, phi);
/// assert!((b.sin() / (b + phi).sin() - a).abs() < 1e-15);
/// ```
pub fn beta_for(a: f64, phi: f64) -> f64 {
    (a * phi.sin()).atan2(1.0 - a * phi.cos())
}

/// The planar yield-mass optimum at ratio a = ρ^(1/q): (β*, φ*, f*) with cos φ* = 2a/(1+a²),
/// tan β* = a and f* = q (1/a − a).
///
/// ```
/// use michell3d::optimize::planar_yield_optimum;
/// let (beta, phi, f) = planar_yield_optimum(4, 0.25);
/// let a = 0.25_f64.powf(0.25);
/// assert!((beta - a.atan()).abs() < 1e-15);
/// assert!((f - 4.0 * (1.0 / a - a)).abs() < 1e-12);
/// assert!(phi > 0.0 && phi < std::f64::consts::FRAC_PI_2);
/// ```
pub fn planar_yield_optimum(complexity: usize, radius_ratio: f64) -> (f64, f64, f64) {
    let q = complexity as f64;
    let a = radius_ratio.powf(1.0 / q);
    let phi = ((1.0 - a * a) / (1.0 + a * a)).atan2(2.0 * a / (1.0 + a * a));
    (a.atan(), phi, q * (1.0 / a - a))
}

/// Michell's continuum mass, normalised: 2 ln(1/ρ).
pub fn continuum_normalized(radius_ratio: f64) -> f64 {
    2.0 * (1.0 / radius_ratio).ln()
}

/// The optimum of `req` (see the module docs).
///
/// ```
/// use michell3d::optimize::{optimize, OptimizeRequest};
/// use michell3d::Geometry;
/// let req = OptimizeRequest { complexity: Some(3), ..OptimizeRequest::new(Geometry::Planar, 0.3) };
/// let o = optimize(&req).unwrap();
/// let a = 0.3_f64.powf(1.0 / 3.0);
/// assert!((o.normalized_yield_mass - 3.0 * (1.0 / a - a)).abs() < 1e-9);
/// ```
pub fn optimize(req: &OptimizeRequest) -> Result<Optimum> {
    req.validate()?;
    match req.complexity {
        Some(q) => optimum_at(req, q),
        None => {
            let mut best = optimum_at(req, 1)?;
            for q in 2..=req.max_complexity {
                if req.joint_mass * joint_count(req.geometry, q) as f64 >= best.mass_kg {
                    break;
                }
                // a family that cannot be built at this q (e.g. q|ε| ≥ π/2) ends the search
                let Ok(candidate) = optimum_at(req, q) else {
                    break;
                };
                best.searched_to = q;
                if candidate.mass_kg < best.mass_kg {
                    best = Optimum {
                        searched_to: q,
                        ..candidate
                    };
                }
            }
            Ok(best)
        }
    }
}

/// Analyses of one complexity in the search: the φ grid, the golden section down to its
/// tolerance (≤ 40 steps) and the final design, twice in 3-D (the family and its planar
/// comparison at the same q). A front end's work estimate multiplies it by the joints.
pub fn analyses_per_complexity(geometry: Geometry) -> usize {
    let one = PHI_GRID + 2 + 40 + 1;
    if geometry.is_planar() {
        one
    } else {
        2 * one
    }
}

/// The largest complexity the search may analyse: `complexity` when it is given; else the
/// first q whose joints alone weigh as much as the q = 1 optimum (the search stops there at
/// the latest, since its best design never weighs more), at most `max_complexity`. One
/// analysis at q = 1 (milliseconds).
///
/// ```
/// use michell3d::optimize::{search_bound, OptimizeRequest};
/// use michell3d::Geometry;
/// let heavy = OptimizeRequest { joint_mass: 10.0, ..OptimizeRequest::new(Geometry::Planar, 0.3) };
/// assert!(search_bound(&heavy).unwrap() < 5);
/// let light = OptimizeRequest { joint_mass: 1e-9, max_complexity: 40, ..heavy };
/// assert_eq!(search_bound(&light).unwrap(), 40);
/// ```
pub fn search_bound(req: &OptimizeRequest) -> Result<usize> {
    req.validate()?;
    if let Some(q) = req.complexity {
        return Ok(q);
    }
    let first = optimum_at(req, 1)?.mass_kg;
    Ok((2..=req.max_complexity)
        .find(|&q| req.joint_mass * joint_count(req.geometry, q) as f64 >= first)
        .unwrap_or(req.max_complexity.max(1))
        .min(match req.geometry {
            Geometry::Planar => crate::params::MAX_COMPLEXITY_PLANAR,
            _ => crate::params::MAX_COMPLEXITY_3D,
        }))
}

/// Number of joints (nodes with merged tuples, supports included) at complexity q:
/// (q+1)(q+2)/2 in the plane, (q+1)(q+2)(q+3)/6 in 3-D.
pub fn joint_count(geometry: Geometry, q: usize) -> usize {
    match geometry {
        Geometry::Planar => (q + 1) * (q + 2) / 2,
        _ => (q + 1) * (q + 2) * (q + 3) / 6,
    }
}

/// One evaluated design.
#[derive(Debug, Clone, Copy)]
struct Design {
    phi: f64,
    member_mass: f64,
    normalized: f64,
    joints: usize,
}

fn optimum_at(req: &OptimizeRequest, q: usize) -> Result<Optimum> {
    let a = req.radius_ratio.powf(1.0 / q as f64);
    let design = match req.geometry {
        Geometry::Planar => {
            let (_, phi, _) = planar_yield_optimum(q, req.radius_ratio);
            let r = evaluate(req, q, a, phi)?;
            Design {
                member_mass: r.yield_mass,
                ..r.design
            }
        }
        _ => minimise_over_phi(req, q, a)?,
    };
    let planar_mass = match req.geometry {
        Geometry::Planar => None,
        _ => {
            let planar = OptimizeRequest {
                geometry: Geometry::Planar,
                ..req.clone()
            };
            let p = minimise_over_phi(&planar, q, a)?;
            Some(p.member_mass + req.joint_mass * p.joints as f64)
        }
    };
    let joint_mass_kg = req.joint_mass * design.joints as f64;
    let mass_kg = design.member_mass + joint_mass_kg;
    Ok(Optimum {
        geometry: req.geometry,
        radius_ratio: req.radius_ratio,
        beta: beta_for(a, design.phi),
        phi: design.phi,
        complexity: q,
        mass_kg,
        member_mass_kg: design.member_mass,
        joint_mass_kg,
        joints: design.joints,
        normalized_yield_mass: design.normalized,
        continuum_normalized_mass: continuum_normalized(req.radius_ratio),
        planar_mass_kg: planar_mass,
        mass_penalty: planar_mass.map(|p| mass_kg / p),
        searched_to: q,
    })
}

struct Evaluation {
    design: Design,
    yield_mass: f64,
}

/// Force propagation and sizing of the design (q, φ) with β from the radius ratio.
fn evaluate(req: &OptimizeRequest, q: usize, a: f64, phi: f64) -> Result<Evaluation> {
    let params = MichellParams {
        complexity: q,
        r0: req.r0,
        beta: beta_for(a, phi),
        phi,
        geometry: req.geometry,
    };
    let report = analyse(&AnalysisRequest {
        load: req.load,
        material: req.material.clone(),
        ..AnalysisRequest::new(params)
    })?;
    Ok(Evaluation {
        design: Design {
            phi,
            member_mass: report.mass_kg.yield_buckling,
            normalized: report.normalized_yield_mass,
            joints: report.nodes.len(),
        },
        yield_mass: report.mass_kg.yield_only,
    })
}

/// Yield + buckling member mass minimised over φ ∈ (0, π): grid, then golden section.
fn minimise_over_phi(req: &OptimizeRequest, q: usize, a: f64) -> Result<Design> {
    let step = PI / (PHI_GRID + 1) as f64;
    let grid: Vec<Option<Design>> = (1..=PHI_GRID)
        .map(|i| evaluate(req, q, a, i as f64 * step).ok().map(|e| e.design))
        .collect();
    let (i_best, best) = grid
        .iter()
        .enumerate()
        .filter_map(|(i, d)| d.map(|d| (i, d)))
        .filter(|(_, d)| d.member_mass.is_finite())
        .min_by(|x, y| x.1.member_mass.total_cmp(&y.1.member_mass))
        .ok_or_else(|| {
            invalid(
                "complexity",
                q as f64,
                "no segmentation angle in (0, π) gives a valid truss at this complexity"
                    .to_string(),
            )
        })?;
    let mass = |phi: f64| {
        evaluate(req, q, a, phi)
            .map(|e| e.design.member_mass)
            .unwrap_or(f64::INFINITY)
    };
    let (mut lo, mut hi) = ((i_best as f64) * step, (i_best as f64 + 2.0) * step);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (mass(x1), mass(x2));
    while hi - lo > PHI_TOL {
        if f1 <= f2 {
            (hi, x2, f2) = (x2, x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = mass(x1);
        } else {
            (lo, x1, f1) = (x1, x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = mass(x2);
        }
    }
    let phi = 0.5 * (lo + hi);
    match evaluate(req, q, a, phi) {
        Ok(e) if e.design.member_mass <= best.member_mass => Ok(e.design),
        _ => Ok(best),
    }
}
