//! [`Anchor`]: the point where a contact node of the stick ground ([`crate::stick`]) is
//! held on the plane, and whether it slid at the last update; the state the model keeps per
//! contact node.

use nalgebra::Vector3;

/// The anchor of a contact node on the plane (the stick ground of [`crate::stick`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchor {
    /// Point on the plane where the tangential spring is attached (m).
    pub point: Vector3<f64>,
    /// Whether the anchor slid at the last update (the cap is then μ_k f_n, else μ_s f_n).
    pub sliding: bool,
}
