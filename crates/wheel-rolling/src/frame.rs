//! A snapshot of a rolling wheel's nodes ([`WheelFrame`]), as both models give their node
//! frames (the full model from its state, the rigid model from its pose). A leaf of the
//! crate: it names nothing else of it.

use nalgebra::Vector3;

/// A snapshot of the wheel's nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct WheelFrame {
    /// Time (s).
    pub t: f64,
    /// Node positions (the structure's numbering) in slope coordinates: x along the axle,
    /// y = s along the slope (downhill, 0 at the starting downhill pair), z = h above it (m).
    pub nodes: Vec<Vector3<f64>>,
    /// Node velocities in the same coordinates (m/s); empty when the model has none to give.
    pub velocities: Vec<Vector3<f64>>,
    /// Axial member forces, bars then strings, tension positive (N); empty for the rigid
    /// model (a rigid body has no member forces).
    pub member_forces: Vec<f64>,
}
