//! The report of one simulation: what `tensegrity simulate --json` prints, built from a
//! [`SimulationResult`] (class-1 copies merged back into the file's node numbering).

use super::simulation::SimulationResult;
use serde::Serialize;
use tensegrity_core::warning::Warning;
use tensegrity_derive::Columns;

/// Summary of a run: final state, cost and drift of the invariants.
///
/// ```
/// use tensegrity_dynamics::{Simulation, SimulationReport, SimulationSettings};
/// use tensegrity_core::{Bar, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1).mass(1.0))
///     .build()
///     .unwrap();
/// let settings = SimulationSettings { t_end: 0.01, dt: 1e-3, ..Default::default() };
/// let r = Simulation::new(&s, settings).unwrap().run().unwrap();
/// let report = SimulationReport::from(&r);
/// assert_eq!(report.steps, 10);
/// assert_eq!(report.final_nodes[1], [1.0, 0.0, 0.0]); // no force, no motion
/// assert!(report.warnings.is_empty());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct SimulationReport {
    /// Final time reached (s).
    #[column(unit = "s")]
    pub t_end: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Right-hand-side (force) evaluations.
    pub rhs_evals: u64,
    /// Final node positions (m), file numbering.
    pub final_nodes: Vec<[f64; 3]>,
    /// Final node velocities (m/s), file numbering.
    pub final_velocities: Vec<[f64; 3]>,
    /// Max relative total-energy drift.
    pub energy_drift: f64,
    /// Max absolute bar-length error (m).
    #[column(unit = "m")]
    pub bar_length_drift: f64,
    /// Max absolute ‖N P − D‖ component (m).
    #[column(unit = "m")]
    pub constraint_drift: f64,
    /// Wall time of the integration alone (s).
    #[column(unit = "s")]
    pub wall_time_s: f64,
    /// Whether the run is valid: no warning (its invariants within their limits and, when
    /// checked, its final state converged), as every dynamic result states it.
    pub valid: bool,
    /// The invariants that drifted past their limits, each with its remedy (absent when the
    /// run is within them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<Warning>,
    /// The final state re-estimated at a refined resolution (set by the front end that ran
    /// the refined run; absent when not checked).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(nested)]
    pub convergence: Option<super::Convergence>,
}

impl From<&SimulationResult> for SimulationReport {
    fn from(r: &SimulationResult) -> Self {
        Self {
            t_end: r.t_end,
            steps: r.steps,
            rhs_evals: r.rhs_evals,
            final_nodes: r.final_nodes.iter().map(|v| [v.x, v.y, v.z]).collect(),
            final_velocities: r.final_velocities.iter().map(|v| [v.x, v.y, v.z]).collect(),
            energy_drift: r.energy_drift,
            bar_length_drift: r.bar_length_drift,
            constraint_drift: r.constraint_drift,
            wall_time_s: r.wall_time_s,
            valid: r.warnings.is_empty(),
            warnings: r.warnings.iter().map(|&w| w.into()).collect(),
            convergence: None,
        }
    }
}
