//! The description of a design problem as data: which force densities vary and within which
//! bounds ([`ParameterSpec`]), the terms of the objective ([`TermSpec`]), each a kind of error
//! over goals ([`GoalSpec`]), and the optimiser's stopping rules ([`OptimizerSpec`]). A front
//! end reads it from the `[design]` table of a topology file (`tensegrity_io::design`).

use super::lbfgsb::LbfgsbSettings;
use serde::{Deserialize, Serialize};

/// A design problem on a topology (module docs).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DesignSpec {
    /// The force densities that vary (none given: every member's, a group's members sharing
    /// one).
    #[serde(default)]
    pub parameters: Vec<ParameterSpec>,
    /// The terms of the objective, summed (at least one).
    #[serde(default)]
    pub terms: Vec<TermSpec>,
    /// The optimiser's stopping rules.
    #[serde(default)]
    pub optimizer: OptimizerSpec,
}

/// Which members a parameter selects.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Selection {
    /// Every member.
    All,
    /// Every bar.
    Bars,
    /// Every string.
    Strings,
}

/// Force densities that vary: the members of a `group` (one shared value), a list of
/// `members` (each its own value, or one shared with `shared`) or a `select`ion (each its own
/// value); exactly one of the three. Bounds keep the member's sign (a bar's
/// q ≤ −[`super::SIGN_FLOOR`], a string's q ≥ [`super::SIGN_FLOOR`]); `lower` and `upper` narrow
/// them. With `sign = "free"` only `lower` and `upper` bound it (jax-fdm's edges have no
/// kind): a member whose designed q changes sign becomes the other kind in the designed
/// topology ([`super::Designed::changed_kind`]).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterSpec {
    /// Member indices, bars then strings.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub members: Vec<usize>,
    /// A group of the topology: one force density for all its members.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<String>,
    /// A selection of members, each its own force density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub select: Option<Selection>,
    /// The listed `members` share one force density (the first member's is the start).
    #[serde(default)]
    pub shared: bool,
    /// Lower bound (N/m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lower: Option<f64>,
    /// Upper bound (N/m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub upper: Option<f64>,
    /// `"member"` (the default: the member's sign kept) or `"free"` (either sign).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sign: Option<String>,
}

/// How a term measures its goals' predictions p against their targets t (w a goal's weight,
/// n the number of goals in the term: one per node or member).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// Σ w ‖p − t‖².
    #[default]
    Squared,
    /// Σ w ‖p − t‖² / n.
    MeanSquared,
    /// √(Σ w ‖p − t‖² / n).
    RootMeanSquared,
    /// Σ w ‖p − t‖₁.
    Absolute,
    /// Σ w ‖p − t‖₁ / n.
    MeanAbsolute,
    /// Σ w Σ p: the prediction itself (a load path to minimise).
    Prediction,
    /// Σ w Σ p / n.
    MeanPrediction,
}

impl ErrorKind {
    /// Its name in a design file (`mean_squared`).
    ///
    /// ```
    /// use formfind::design::ErrorKind;
    /// assert_eq!(ErrorKind::MeanSquared.name(), "mean_squared");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            ErrorKind::Squared => "squared",
            ErrorKind::MeanSquared => "mean_squared",
            ErrorKind::RootMeanSquared => "root_mean_squared",
            ErrorKind::Absolute => "absolute",
            ErrorKind::MeanAbsolute => "mean_absolute",
            ErrorKind::Prediction => "prediction",
            ErrorKind::MeanPrediction => "mean_prediction",
        }
    }
}

/// One term of the objective: `weight` times its error over its goals (default: no name,
/// squared error, weight 1, no goals).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TermSpec {
    /// Its name in the report and the history (default `term N`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The error (default `squared`).
    #[serde(default)]
    pub error: ErrorKind,
    /// The factor on the term (default 1).
    #[serde(default = "one")]
    pub weight: f64,
    /// Its goals (at least one).
    #[serde(default)]
    pub goals: Vec<GoalSpec>,
}

impl Default for TermSpec {
    fn default() -> Self {
        Self {
            name: None,
            error: ErrorKind::default(),
            weight: 1.0,
            goals: Vec::new(),
        }
    }
}

fn one() -> f64 {
    1.0
}

/// A goal: a prediction of the form per node or member, its target and weight. `nodes`
/// default to the free nodes (the held ones for reactions), `members` to every member (or
/// the members of `group`); `target` is one value for all, `targets` one per node or member.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum GoalSpec {
    /// A node's position x_i; without a target, the topology's own `nodes` (shape matching).
    Position {
        /// The nodes.
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// One target position for every node (m).
        #[serde(default)]
        target: Option<[f64; 3]>,
        /// A target position per node (m).
        #[serde(default)]
        targets: Option<Vec<[f64; 3]>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// One coordinate of a node's position (m): `axis` 0, 1, 2 for x, y, z (a height goal).
    Coordinate {
        /// The nodes.
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// The coordinate: 0, 1 or 2.
        axis: usize,
        /// One target (m).
        #[serde(default)]
        target: Option<f64>,
        /// A target per node (m).
        #[serde(default)]
        targets: Option<Vec<f64>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A node's signed distance (x − p) · n̂ to a plane through `point` with normal `normal`
    /// (m), target 0: with a squared error, jax-fdm's plane goal.
    Plane {
        /// The nodes.
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// A point of the plane (m).
        point: [f64; 3],
        /// Its normal (made unit).
        normal: [f64; 3],
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A node's offset (I − ûûᵀ)(x − p) from a line through `point` along `direction` (m),
    /// target 0: with a squared error, jax-fdm's line goal.
    Line {
        /// The nodes.
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// A point of the line (m).
        point: [f64; 3],
        /// Its direction (made unit).
        direction: [f64; 3],
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A member's force density q_k (N/m), target default 0: with a squared error and the
    /// term's weight α, jax-fdm's L2 regulariser α Σ q².
    ForceDensity {
        /// The members.
        #[serde(default)]
        members: Option<Vec<usize>>,
        /// A group's members instead.
        #[serde(default)]
        group: Option<String>,
        /// One target (N/m; default 0).
        #[serde(default)]
        target: Option<f64>,
        /// A target per member (N/m).
        #[serde(default)]
        targets: Option<Vec<f64>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A member's length L_k (m).
    Length {
        /// The members.
        #[serde(default)]
        members: Option<Vec<usize>>,
        /// A group's members instead.
        #[serde(default)]
        group: Option<String>,
        /// One target (m).
        #[serde(default)]
        target: Option<f64>,
        /// A target per member (m).
        #[serde(default)]
        targets: Option<Vec<f64>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A member's force F_k = q_k L_k (N, tension positive).
    Force {
        /// The members.
        #[serde(default)]
        members: Option<Vec<usize>>,
        /// A group's members instead.
        #[serde(default)]
        group: Option<String>,
        /// One target (N).
        #[serde(default)]
        target: Option<f64>,
        /// A target per member (N).
        #[serde(default)]
        targets: Option<Vec<f64>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A member's unit direction (x_end − x_start) / L_k against a target direction (made
    /// unit).
    Direction {
        /// The members.
        #[serde(default)]
        members: Option<Vec<usize>>,
        /// A group's members instead.
        #[serde(default)]
        group: Option<String>,
        /// One target direction.
        #[serde(default)]
        target: Option<[f64; 3]>,
        /// A target direction per member.
        #[serde(default)]
        targets: Option<Vec<[f64; 3]>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A held node's reaction r_h (N), the force its support exerts on it.
    Reaction {
        /// The held nodes (default: all).
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// One target reaction (N).
        #[serde(default)]
        target: Option<[f64; 3]>,
        /// A target reaction per node (N).
        #[serde(default)]
        targets: Option<Vec<[f64; 3]>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// The magnitude ‖r_h‖ of a held node's reaction (N; jax-fdm's residual force goal).
    ReactionForce {
        /// The held nodes (default: all).
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// One target (N).
        #[serde(default)]
        target: Option<f64>,
        /// A target per node (N).
        #[serde(default)]
        targets: Option<Vec<f64>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// A reaction limit: the excess max(0, ‖r_h‖ − limit) of a held node's reaction, target 0.
    ReactionLimit {
        /// The held nodes (default: all).
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// The largest reaction magnitude (N).
        limit: f64,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// The load path Σ_k |F_k| L_k = Σ_k |q_k| L_k² over the members (one goal; target 0):
    /// with error `prediction`, minimised.
    LoadPath {
        /// The members.
        #[serde(default)]
        members: Option<Vec<usize>>,
        /// The target (default 0).
        #[serde(default)]
        target: Option<f64>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
    /// Smoothness (fairness): x_i minus the mean of its neighbours' positions, target 0.
    Smoothness {
        /// The nodes (default: the free nodes).
        #[serde(default)]
        nodes: Option<Vec<usize>>,
        /// The weight w (default 1).
        #[serde(default = "one")]
        weight: f64,
    },
}

/// The optimiser's stopping rules (defaults: 1000 iterations, scipy's tolerances).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OptimizerSpec {
    /// Iterations at most.
    pub max_iterations: usize,
    /// Relative decrease of the objective below which it stops (scipy's `ftol`).
    pub ftol: f64,
    /// Largest projected-gradient component below which it stops (scipy's `gtol`).
    pub gtol: f64,
    /// Pairs of the limited-memory Hessian (L-BFGS-B).
    pub memory: usize,
    /// The method (default L-BFGS-B).
    pub method: OptimizerMethod,
}

/// The optimiser of a design problem (the file's `[design.optimizer] method`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OptimizerMethod {
    /// `lbfgsb`: the bound-constrained quasi-Newton method ([`super::lbfgsb`]), for any
    /// objective (jax-fdm's default).
    #[default]
    Lbfgsb,
    /// `levenberg_marquardt`: the projected Levenberg–Marquardt method on the residuals'
    /// exact Jacobian ([`super::levenberg_marquardt`]), for problems whose every term is a
    /// squared or mean-squared error: Gauss–Newton's fast convergence where L-BFGS crawls
    /// along a flat valley.
    LevenbergMarquardt,
}

impl OptimizerMethod {
    /// Its name in a design file (`levenberg_marquardt`).
    ///
    /// ```
    /// use formfind::design::OptimizerMethod;
    /// assert_eq!(OptimizerMethod::LevenbergMarquardt.name(), "levenberg_marquardt");
    /// ```
    pub fn name(self) -> &'static str {
        match self {
            OptimizerMethod::Lbfgsb => "lbfgsb",
            OptimizerMethod::LevenbergMarquardt => "levenberg_marquardt",
        }
    }
}

impl Default for OptimizerSpec {
    fn default() -> Self {
        let s = LbfgsbSettings::default();
        Self {
            max_iterations: s.max_iterations,
            ftol: s.ftol,
            gtol: s.gtol,
            memory: s.memory,
            method: OptimizerMethod::default(),
        }
    }
}

impl OptimizerSpec {
    /// The optimiser's settings.
    pub fn settings(&self) -> LbfgsbSettings {
        LbfgsbSettings {
            max_iterations: self.max_iterations,
            max_evaluations: 15 * self.max_iterations.max(1000),
            memory: self.memory,
            ftol: self.ftol,
            gtol: self.gtol,
        }
    }
}
