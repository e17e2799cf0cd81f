//! A point of a load path, the events between points, and the path's report.

use crate::stability::Stability;
use serde::Serialize;

/// One equilibrium of the path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathPoint {
    /// Its index on the path (0: the unloaded state).
    pub step: usize,
    /// The load factor λ (the load is λ P).
    pub lambda: f64,
    /// Node positions (m).
    pub nodes: Vec<[f64; 3]>,
    /// Each node's displacement from the reference state (m).
    pub displacements: Vec<[f64; 3]>,
    /// The largest node displacement (m).
    pub max_displacement: f64,
    /// Each member's tension (N, compression negative), then each cluster's (index
    /// `members + c` is cluster c: [`crate::clusters`]).
    pub tensions: Vec<f64>,
    /// The slack strings and clusters (indices as in `tensions`).
    pub slack: Vec<usize>,
    /// Each cluster's segment tensions in order along it (N; one value repeated on
    /// frictionless pulleys, the cluster's entry in `tensions` is their largest); absent
    /// without clusters.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub segment_tensions: Vec<Vec<f64>>,
    /// Each cluster's pulleys after the step: `stick`, `slip_forward` (material passed to
    /// the next segment: t_{j+1} = e^{μθ} t_j) or `slip_backward` (t_j = e^{μθ} t_{j+1});
    /// an empty list for a frictionless cluster; absent without pulley friction.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub pulleys: Vec<Vec<&'static str>>,
    /// The reactions: node, the held direction, the force along it (N).
    pub reactions: Vec<Reaction>,
    /// Up to three smallest eigenvalues of the tangent stiffness (N/m).
    pub smallest_eigenvalues: Vec<f64>,
    /// The stability verdict.
    pub stability: Stability,
    /// The largest residual force left (N).
    pub residual: f64,
}

/// A support's reaction along one held direction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Reaction {
    /// The node.
    pub node: usize,
    /// The unit direction.
    pub direction: [f64; 3],
    /// The force the support applies along it (N).
    pub force: f64,
}

/// What happened between two points.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Event {
    /// A limit point (fold): λ reaches an extremum along the path; located by bisection.
    LimitPoint {
        /// The load factor there.
        lambda: f64,
        /// The point's index after which it lies.
        after_step: usize,
        /// The largest node displacement there (m).
        max_displacement: f64,
        /// The buckling mode (node displacements, unit largest component).
        mode: Vec<[f64; 3]>,
    },
    /// The number of negative eigenvalues changed without a limit point: a bifurcation.
    Bifurcation {
        /// The load factor there.
        lambda: f64,
        /// The point's index after which it lies.
        after_step: usize,
        /// The mode (node displacements, unit largest component; dense and sparse tangents
        /// alike, empty only where a sparse tangent's shift-invert iteration found none).
        mode: Vec<[f64; 3]>,
        /// Whether the path left here along the mode (`switch_branch`).
        switched: bool,
    },
    /// Load control jumped between two load steps: the equilibrium found moved far more than
    /// the tangent predicts (more than [`crate::load_steps::JUMP_RATIO`] times), as past a
    /// limit point where the structure snaps to another branch; the arc-length path shows
    /// what lies between.
    Jump {
        /// The load factor before the jump.
        from_lambda: f64,
        /// The load factor after it.
        to_lambda: f64,
        /// The displacement increment against the tangent's prediction.
        ratio: f64,
    },
    /// Strings went slack: λ where the first of them reaches zero tension on the path with
    /// the slack set held (the others within the residual tolerance of zero there go with it;
    /// [`crate::arclength`]).
    Slackened {
        /// Their indices (as in [`PathPoint::tensions`]: clusters after the members).
        members: Vec<usize>,
        /// The load factor where the set of slack strings changed.
        lambda: f64,
        /// The point's index at which they are first slack.
        at_step: usize,
    },
    /// Slack strings took tension again; located alike.
    Retensioned {
        /// Their indices (as in [`PathPoint::tensions`]: clusters after the members).
        members: Vec<usize>,
        /// The load factor where the set of slack strings changed.
        lambda: f64,
        /// The point's index at which they are first taut.
        at_step: usize,
    },
}

/// Why the path stopped.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Stop {
    /// It reached the target load factor.
    ReachedTarget,
    /// It made the largest number of steps.
    MaxSteps,
    /// The path could not go on: every step down to the smallest size failed (no
    /// equilibrium, a residual that left double precision, a singular tangent). The points
    /// so far are kept.
    StepTooSmall {
        /// Why, with the load factor of the last point and the last step's error.
        message: String,
    },
    /// It spent its work limit ([`crate::PathSettings::max_seconds`]) before its target.
    /// The points so far are kept.
    WorkLimit {
        /// The limit (s of wall time).
        seconds: f64,
    },
}

/// A load path: its points, its events and why it stopped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathReport {
    /// The equilibria, in path order.
    pub points: Vec<PathPoint>,
    /// Limit points, bifurcations and slack changes, in path order.
    pub events: Vec<Event>,
    /// Why it stopped.
    pub stop: Stop,
}
