//! The mass price of the load envelope swept over the complexity q and δ (or ε): one complete
//! analysis ([`crate::report::tbar_report`]) per single tread with the rigid rim, its
//! [`MassComparison`] against the Michell truss ([`crate::mass`]) or why it has none.

use crate::mass::MassComparison;
use crate::params::{Layout, RimMode, TbarParams};
use crate::report::{tbar_report, TbarRequest};
use serde::Serialize;

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

/// The complexities q of a mass sweep unless told (`tbar --mass-sweep`, Python's
/// `tbar(mass_sweep=True)`).
pub const MASS_SWEEP_COMPLEXITIES: [usize; 3] = [1, 2, 3];

/// The offsets δ (or angles ε, radians) of a mass sweep unless told.
pub const MASS_SWEEP_OFFSETS: [f64; 5] = [0.05, 0.1, 0.25, 0.5, 1.0];

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
            let mut req = TbarRequest::new(params);
            req.load = load;
            req.ea = ea;
            req.material = material.to_string();
            let row = match tbar_report(&req) {
                Ok(r) => MassRow {
                    complexity: q,
                    delta,
                    min_prestress: r.min_prestress,
                    mass: r.mass,
                    note: r.warnings.first().map(ToString::to_string),
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
