//! The figure of chapter 2: the planar D-bar of §2.2.1 (Fig. 2.2), from its closed form,
//! eq. 2.8–2.10: nodes N = [0, L/2, L/2, L; 0, h/2, −h/2, 0], bars 1→2, 1→3, 2→4, 3→4 and
//! strings 1→4, 2→3 (rows of C_b and C_s, eq. 2.9, −1 at the start node as ERRATA 2.1), so
//! that B = N C_bᵀ has columns [L/2, ±h/2] and S = N C_sᵀ = [L, 0; 0, −h] (eq. 2.10).

use crate::context::Context as Ctx;
use crate::data::{no_forces, Drawn, StructureFigure};
use crate::draw::{Group, View, BLUE, RED};
use crate::error::Result;
use nalgebra::Vector3;

/// The span L and height h drawn (m).
pub const SPAN_HEIGHT: (f64, f64) = (2.0, 0.5);

/// Fig. 2.2: the planar D-bar, bars blue and strings red, in the (ι̂₁, ι̂₂) plane.
pub fn fig_2_2(_: &Ctx) -> Result<Drawn> {
    let (l, h) = SPAN_HEIGHT;
    let nodes = [
        Vector3::new(0.0, 0.0, 0.0),
        Vector3::new(l / 2.0, h / 2.0, 0.0),
        Vector3::new(l / 2.0, -h / 2.0, 0.0),
        Vector3::new(l, 0.0, 0.0),
    ];
    let groups = [
        Group::new("bars", BLUE, vec![[0, 1], [0, 2], [1, 3], [2, 3]]),
        Group::new("strings", RED, vec![[0, 3], [1, 2]]),
    ];
    let mut fig = StructureFigure::new(&[("span", "m"), ("height", "m")]);
    fig.node_labels = (1..=4).map(|i| format!("n{i}")).collect();
    let extra = vec![l.into(), h.into()];
    fig.add("planar D-bar", View::Xy, &nodes, &groups, &no_forces, extra);
    Ok(fig.finish())
}
