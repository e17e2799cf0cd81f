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
pub use crate::mass_sweep::{mass_sweep, MassRow};
use crate::params::TbarParams;
use michell3d::{analyse, AnalysisRequest};
use serde::Serialize;
use tensegrity_core::MaterialTable;
use tensegrity_derive::Columns;
use tensegrity_statics::sizing::{size_bar, size_string};

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
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct MassComparison {
    /// Material name (core table).
    pub material: String,
    /// T-bar mass, strings for yield and bars for max(yield, buckling) (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// T-bar mass with every member sized for yield only (kg).
    #[column(unit = "kg")]
    pub yield_mass_kg: f64,
    /// Mass of the 3-D Michell truss of the same parameters for its nominal load (kg).
    #[column(unit = "kg")]
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
