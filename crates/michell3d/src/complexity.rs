//! Mass against complexity (Fig. 4.18, with ERRATA 4.4, 4.5 and 4.24).
//!
//! For q ∈ 2..=35, r₀ = 1, β = π/6, φ = π/q and the tip load w = [0, 0, −w₀] (φ_w = 0, γ = π,
//! ERRATA 4.5), the planar truss and the cylindrical 3-D trusses with δ ∈ {0.1, 0.25, 0.5} are
//! solved and sized. Each row gives the normalised yield mass Σ|q|l²/(w₀r₀), the yield mass
//! and the yield + buckling mass for one material, and how many 3-D members have the sign opposite
//! to their planar counterpart (member (U,D,L,R) → child projected to n_UD → n_(U+1)D or
//! n_U(D+1)). For loads with w_x = 0 the 3-D force densities do not depend on δ (ERRATA 4.24).

use crate::error::{invalid, Result};
use crate::loads::{tip_load, NodalLoads};
use crate::nodes::NodeTuple;
use crate::params::{Geometry, MichellParams};
use crate::propagation::{propagate, ForceSolution, Method};
use crate::sizing::{normalized_yield_mass, size_members, MemberKind};
use crate::truss::MichellTruss;
use serde::Serialize;
use std::f64::consts::{FRAC_PI_6, PI};
use tensegrity_core::Material;

/// The δ values of Fig. 4.18.
pub const FIG_4_18_DELTAS: [f64; 3] = [0.1, 0.25, 0.5];

/// One row of the mass–complexity table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassRow {
    /// Complexity q.
    pub complexity: usize,
    /// δ (0 for the planar truss).
    pub delta: f64,
    /// Σ|q|l²/(w₀ r₀).
    pub normalized_yield_mass: f64,
    /// Yield-only mass (kg).
    pub yield_mass_kg: f64,
    /// Yield + buckling mass (kg).
    pub yield_buckling_mass_kg: f64,
    /// 3-D members whose sign differs from their planar counterpart (0 for planar rows).
    pub sign_changes_vs_planar: usize,
}

/// Fig. 4.18 parameters for complexity q: r₀ = 1, β = π/6, φ = π/q; `delta = None` is planar.
pub fn fig_4_18_params(q: usize, delta: Option<f64>) -> MichellParams {
    let phi = PI / q as f64;
    match delta {
        None => MichellParams::planar(q, 1.0, FRAC_PI_6, phi),
        Some(d) => MichellParams::cylindrical(q, 1.0, FRAC_PI_6, phi, d),
    }
}

/// Number of 3-D members whose kind (string/bar) is the opposite of that of the planar member
/// they project onto. Both solutions must be for the same in-plane load and complexity.
pub fn sign_changes_vs_planar(
    truss3d: &MichellTruss,
    sol3d: &ForceSolution,
    planar: &MichellTruss,
    sol2d: &ForceSolution,
) -> Result<usize> {
    let q = truss3d.params().complexity;
    if truss3d.is_planar() || !planar.is_planar() || planar.params().complexity != q {
        return Err(invalid(
            "complexity",
            planar.params().complexity as f64,
            format!("need a 3-D truss and a planar truss of the same complexity {q}"),
        ));
    }
    let f3 = sol3d.forces(truss3d);
    let f2 = sol2d.forces(planar);
    let max3 = f3.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let max2 = f2.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    let mut changes = 0;
    for (m, &f) in truss3d.members().iter().zip(&f3) {
        let p = truss3d.nodes()[m.parent].tuple;
        let c = truss3d.nodes()[m.child].tuple;
        // Every 3-D member projects onto the planar member n_UD → n_child(U, D).
        let Some(j2) =
            planar.find_member(&NodeTuple::planar(p.u, p.d), &NodeTuple::planar(c.u, c.d))
        else {
            continue;
        };
        let k3 = MemberKind::classify(f, max3);
        let k2 = MemberKind::classify(f2[j2], max2);
        if matches!(
            (k3, k2),
            (MemberKind::String, MemberKind::Bar) | (MemberKind::Bar, MemberKind::String)
        ) {
            changes += 1;
        }
    }
    Ok(changes)
}

/// The Fig. 4.18 table for complexities `qs`, planar plus each δ in `deltas`, load w₀ (N) along
/// −ι̂₃, bars and strings of `material`. Rows are ordered by q, planar first. Sequential: the
/// sweeps crate fans the complexities out over threads (`sweeps::grids::mass_vs_complexity`),
/// one [`mass_rows`] call each.
pub fn mass_vs_complexity(
    qs: &[usize],
    deltas: &[f64],
    w0: f64,
    material: &Material,
) -> Result<Vec<MassRow>> {
    let mut all = Vec::new();
    for &q in qs {
        all.extend(mass_rows(q, deltas, w0, material)?);
    }
    Ok(all)
}

/// The rows of one complexity q: planar first, then one per δ in `deltas`.
pub fn mass_rows(q: usize, deltas: &[f64], w0: f64, material: &Material) -> Result<Vec<MassRow>> {
    let w = tip_load(w0, 0.0, PI)?;
    let planar = MichellTruss::new(fig_4_18_params(q, None))?;
    let loads = NodalLoads::tip(w);
    let sol2 = propagate(&planar, &loads, Method::Recursive)?;
    let mut out = vec![row(&planar, &sol2, w0, material, 0)];
    for &d in deltas {
        let t = MichellTruss::new(fig_4_18_params(q, Some(d)))?;
        let s = propagate(&t, &loads, Method::Recursive)?;
        let changes = sign_changes_vs_planar(&t, &s, &planar, &sol2)?;
        out.push(row(&t, &s, w0, material, changes));
    }
    Ok(out)
}

fn row(
    t: &MichellTruss,
    s: &ForceSolution,
    w0: f64,
    material: &Material,
    changes: usize,
) -> MassRow {
    let lengths = t.lengths();
    let sizing = size_members(&lengths, &s.forces(t), material, material);
    MassRow {
        complexity: t.params().complexity,
        delta: match t.params().geometry {
            Geometry::Cylindrical { delta } => delta,
            _ => 0.0,
        },
        normalized_yield_mass: normalized_yield_mass(&lengths, &s.force_density, w0, t.params().r0),
        yield_mass_kg: sizing.yield_mass,
        yield_buckling_mass_kg: sizing.yield_buckling_mass,
        sign_changes_vs_planar: changes,
    }
}
