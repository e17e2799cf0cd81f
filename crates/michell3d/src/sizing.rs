//! Member types and minimum mass (§4.5, eq. 4.54–4.61 with the lengths of ERRATA 4.26–4.29).
//!
//! The member type follows the sign of the force density: tension → string, compression → bar,
//! |f| ≤ [`ZERO_FORCE_RTOL`]·max|f| → no member. Strings are sized for yield,
//! m = (ρ_s/σ_s) |f| l; bars for yield and Euler buckling (pinned–pinned solid rod),
//! r = max(r_Y, r_B), via `tensegrity_statics::sizing`. Two totals are reported:
//!
//! - `yield_mass`: every member sized for yield only, Σ (ρ/σ)|q| l²;
//! - `yield_buckling_mass`: strings for yield, bars for max(yield, buckling).
//!
//! The material-independent figure of merit is the normalised yield mass
//! Σ |q_j| l_j² / (w₀ r₀) (so yield mass = (ρ/σ) w₀ r₀ × normalised mass).
//!
//! For the q = 1 truss under w = [0, 0, −w₀] the bar m₀₁₀₀ (length r₀c, ERRATA 4.27) buckles
//! before it yields iff r₀² c² sin β > π w₀ E / (8 σ²) (eq. 4.65 as corrected by ERRATA 4.28);
//! see [`q1_bar_buckling_governs`].

use crate::params::MichellParams;
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::Material;
use tensegrity_statics::sizing::{size_bar, size_string, Governing, MemberSize};

/// Forces with |f| ≤ this × max|f| count as zero ("none" members).
pub const ZERO_FORCE_RTOL: f64 = 1e-9;

/// The member type implied by the sign of its force.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MemberKind {
    /// Tension.
    String,
    /// Compression.
    Bar,
    /// (Numerically) zero force: no member needed.
    None,
}

impl MemberKind {
    /// Classifies a force `f` against the largest force magnitude `f_max` of the truss.
    pub fn classify(f: f64, f_max: f64) -> Self {
        if f.abs() <= ZERO_FORCE_RTOL * f_max {
            MemberKind::None
        } else if f > 0.0 {
            MemberKind::String
        } else {
            MemberKind::Bar
        }
    }

    /// `"string"`, `"bar"` or `"none"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            MemberKind::String => "string",
            MemberKind::Bar => "bar",
            MemberKind::None => "none",
        }
    }
}

/// The sizing of one member.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MemberSizing {
    /// String, bar or none.
    pub kind: MemberKind,
    /// The size (radius, masses, governing mode); `None` for [`MemberKind::None`].
    pub size: Option<MemberSize>,
}

/// Sizes and masses of all members.
#[derive(Debug, Clone, PartialEq)]
pub struct TrussSizing {
    /// One entry per member (same order as the forces given).
    pub members: Vec<MemberSizing>,
    /// Total mass with every member sized for yield only (kg).
    pub yield_mass: f64,
    /// Total mass with bars sized for max(yield, buckling) (kg).
    pub yield_buckling_mass: f64,
    /// Indices of the bars whose size is set by buckling.
    pub buckling_governed: Vec<usize>,
}

/// Sizes members with axial forces `forces` (N, tension positive) and lengths `lengths` (m):
/// strings of `string_material`, bars of `bar_material`.
pub fn size_members(
    lengths: &[f64],
    forces: &[f64],
    bar_material: &Material,
    string_material: &Material,
) -> TrussSizing {
    let f_max = forces.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let mut out = TrussSizing {
        members: Vec::with_capacity(forces.len()),
        yield_mass: 0.0,
        yield_buckling_mass: 0.0,
        buckling_governed: Vec::new(),
    };
    for (j, (&l, &f)) in lengths.iter().zip(forces).enumerate() {
        let kind = MemberKind::classify(f, f_max);
        let size = match kind {
            MemberKind::None => None,
            MemberKind::String => size_string(string_material, f, l),
            MemberKind::Bar => Some(size_bar(bar_material, f, l)),
        };
        if let Some(s) = size {
            out.yield_mass += s.yield_mass;
            out.yield_buckling_mass += s.mass;
            if s.governing == Governing::Buckling {
                out.buckling_governed.push(j);
            }
        }
        out.members.push(MemberSizing { kind, size });
    }
    out
}

/// Normalised yield mass Σ |q_j| l_j² / (w₀ r₀) (material independent).
pub fn normalized_yield_mass(lengths: &[f64], force_density: &[f64], w0: f64, r0: f64) -> f64 {
    lengths
        .iter()
        .zip(force_density)
        .map(|(l, q)| q.abs() * l * l)
        .sum::<f64>()
        / (w0 * r0)
}

/// Corrected eq. 4.65 (ERRATA 4.28): for q = 1 under w = [0, 0, −w₀], the bar m₀₁₀₀ is
/// buckling-governed iff r₀² c² sin β > π w₀ E / (8 σ²).
pub fn q1_bar_buckling_governs(params: &MichellParams, w0: f64, bar_material: &Material) -> bool {
    let c = params.c();
    params.r0 * params.r0 * c * c * params.beta.sin()
        > PI * w0 * bar_material.youngs_modulus / (8.0 * bar_material.yield_strength.powi(2))
}
