//! What a form-finding run returns.

use crate::method::Method;
use nalgebra::Vector3;
use serde::Serialize;

/// A found form: geometry, force densities and the statics of the self-stress.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FormFound {
    /// The method that found it.
    pub method: Method,
    /// One position per node (m).
    pub nodes: Vec<Vector3<f64>>,
    /// Force density per member (N/m, tension-positive), bars then strings in topology order,
    /// normalised as documented by the method.
    pub force_density: Vec<f64>,
    /// Dimension of the self-stress space of the found geometry.
    pub self_stress_dim: usize,
    /// Whether a self-stress with every string in tension and every bar in compression exists.
    pub prestressable: bool,
    /// Whether the prestressed structure is stable (positive-definite stiffness on the
    /// non-rigid motions).
    pub prestress_stable: bool,
    /// ‖A q‖ / ‖q‖ at the found geometry (A the equilibrium matrix, q the force densities).
    pub residual: f64,
    /// Iterations of the method (1 for a direct solve).
    pub iterations: usize,
}
