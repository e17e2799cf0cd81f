//! Minimum mass for the load envelope, against the 3-D Michell truss (issue item 4).
//!
//! Over every load direction d on every tip, member k carries s_k + w₀ g_{k,T}·d, so its
//! largest tension is s_k + w₀ a_k and its largest compression −s_k + w₀ a_k (a_k = max_T ‖g‖,
//! see [`crate::envelope`]). Strings are sized for yield at the largest tension; the bar for
//! max(yield, Euler buckling) at the largest compression (core sizing: pinned–pinned solid
//! rods, eq. 4.54–4.59 with ERRATA 4.25). The 3-D Michell truss of the same (q, r₀, β, φ, δ/ε)
//! is sized by michell3d for its nominal load, w₀ along −ι̂₃ (ERRATA 4.5), with the same
//! material; the ratio of the two masses is the price of carrying w₀ from every direction
//! (per tread: a wheel's mass is divided by its number of treads).

use crate::envelope::LoadResponse;
use crate::error::Result;
use crate::params::{Layout, RimMode, TbarParams};
use michell3d::{analyse, AnalysisRequest};
use serde::Serialize;
use tensegrity_core::sizing::{size_bar, size_string};
use tensegrity_core::MaterialTable;

/// Default material of the sizing.
pub const DEFAULT_MATERIAL: &str = "steel";

/// The design forces over the envelope: the largest tension of every string and the largest
/// compression (negative) of every bar, for the prestress state `state` (N) and load `load`.
pub fn design_forces(response: &LoadResponse, state: &[f64], load: f64) -> Vec<f64> {
    response
        .worst_gains()
        .iter()
        .enumerate()
        .map(|(k, (a, _))| {
            if response.is_bar(k) {
                state[k] - load * a
            } else {
                state[k] + load * a
            }
        })
        .collect()
}

/// Masses of the T-bar structure and of the matching Michell truss.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassComparison {
    /// Material name (core table).
    pub material: String,
    /// T-bar mass, strings for yield and bars for max(yield, buckling) (kg).
    pub mass_kg: f64,
    /// T-bar mass with every member sized for yield only (kg).
    pub yield_mass_kg: f64,
    /// Mass of the 3-D Michell truss of the same parameters for its nominal load (kg).
    pub michell_mass_kg: f64,
    /// mass_kg / (treads × michell_mass_kg).
    pub mass_ratio: f64,
}

/// Sizes the T-bar members for `forces` (design forces, N) and the Michell truss of `params`
/// for `load`, both of `material`.
pub fn compare(
    params: &TbarParams,
    treads: usize,
    lengths: &[f64],
    n_bars: usize,
    forces: &[f64],
    load: f64,
    material: &str,
) -> Result<MassComparison> {
    let table = MaterialTable::builtin();
    let mat = table.lookup(material, "the T-bar members")?;
    let (mut mass, mut yield_mass) = (0.0, 0.0);
    for (k, (&l, &f)) in lengths.iter().zip(forces).enumerate() {
        let size = if k < n_bars {
            Some(size_bar(mat, f, l))
        } else {
            size_string(mat, f.max(0.0), l)
        };
        if let Some(s) = size {
            mass += s.mass;
            yield_mass += s.yield_mass;
        }
    }
    let mut req = AnalysisRequest::new(params.michell);
    req.load = load;
    req.material = material.to_string();
    let michell = analyse(&req)?.mass_kg.yield_buckling;
    Ok(MassComparison {
        material: material.to_string(),
        mass_kg: mass,
        yield_mass_kg: yield_mass,
        michell_mass_kg: michell,
        mass_ratio: mass / (treads as f64 * michell),
    })
}

/// One row of the mass sweep over q and δ.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassRow {
    /// Complexity q.
    pub complexity: usize,
    /// Out-of-plane parameter δ (or ε).
    pub delta: f64,
    /// Minimum prestress (N), when the tread has an envelope.
    pub min_prestress: Option<f64>,
    /// The masses, when the tread has an envelope.
    pub mass: Option<MassComparison>,
    /// Why there is no envelope (mechanism, not prestressable), if so.
    pub note: Option<String>,
}

/// The mass price of the envelope over complexities and δ (single treads with the rigid rim,
/// cylindrical with δ, or spherical with ε when `base` is spherical).
pub fn mass_sweep(
    base: &TbarParams,
    complexities: &[usize],
    deltas: &[f64],
    load: f64,
    ea: f64,
    material: &str,
) -> Vec<MassRow> {
    let mut rows = Vec::new();
    for &q in complexities {
        for &delta in deltas {
            let mut michell = base.michell.with_complexity(q);
            michell.geometry = match michell.geometry {
                michell3d::Geometry::Spherical { .. } => {
                    michell3d::Geometry::Spherical { epsilon: delta }
                }
                _ => michell3d::Geometry::Cylindrical { delta },
            };
            let params = TbarParams {
                michell,
                layout: Layout::Tread,
                rim: RimMode::Fixed,
                ..*base
            };
            let mut req = crate::report::TbarRequest::new(params);
            req.load = load;
            req.ea = ea;
            req.material = material.to_string();
            let row = match crate::report::tbar_report(&req) {
                Ok(r) => MassRow {
                    complexity: q,
                    delta,
                    min_prestress: r.min_prestress,
                    mass: r.mass,
                    note: r.warnings.first().cloned(),
                },
                Err(e) => MassRow {
                    complexity: q,
                    delta,
                    min_prestress: None,
                    mass: None,
                    note: Some(e.to_string()),
                },
            };
            rows.push(row);
        }
    }
    rows
}
