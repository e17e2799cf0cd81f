//! Scene-file tables of the dynamics (serde, `deny_unknown_fields`), and the function that
//! turns a [`Structure`] plus these tables into a runnable [`Simulation`] through the core's
//! own API ([`Simulation::new`], [`Ground::new`], [`Model::set_ground`] and the rest-length and
//! load schedules of [`Model`]).
//!
//! Checked against each other and the structure ([`build_simulation`], and the scene reader
//! with the line of the item): μ_k ≤ μ_s, no node that can touch the ground starting more than
//! [`GROUND_START_TOLERANCE`] below it, at most one rest-length table per string (load tables
//! of one node add).
//!
//! Actuation tables are piecewise linear in time and constant outside their range:
//! v(t) = v_i (1 − w) + v_{i+1} w with w = (t − t_i)/(t_{i+1} − t_i) for t_i ≤ t < t_{i+1}.
//!
//! ```toml
//! [simulation]
//! t_end = 2.0
//! integrator = "rk45"          # rk4 (default) | rk45 | rattle
//! dt = 1e-3                    # fixed step (rk4, rattle) / maximum step (rk45, default t_end)
//! rtol = 1e-8
//! atol = 1e-10
//! output_interval = 0.01       # and/or output_times = [0.5, 1.0]
//! record = ["nodes", "energy"] # nodes, velocities, member_forces, energy, contact_forces
//! project = false              # project rk4/rk45 states onto the constraints
//! bars = "elastic"             # rigid (default) | elastic: every member an axial spring,
//!                              # the mass at the nodes; integrator rk4, rk45 or newmark
//! mass_matrix = "consistent"   # elastic: lumped (default) | consistent
//!
//! [ground]
//! point = [0, 0, 0]
//! normal = [0, 0, 1]
//! model = "penalty"            # or "thesis"
//! stiffness = 1e5              # penalty: N/m
//! damping = 50                 # penalty: N·s/m normal; thesis: N·s/m on contact velocities
//! mu_static = 0.8
//! mu_kinetic = 0.6
//! regularization_velocity = 1e-3
//! stribeck_velocity = 1e-2
//! nodes = [0, 1, 2]            # default: every node
//!
//! [[actuation]]                # piecewise linear in time, constant outside the table
//! string = 3
//! times = [0.0, 1.0]
//! rest_lengths = [0.9, 0.8]
//!
//! [[actuation]]                # a clustered string's whole rest length: all its segments
//! cluster = 0
//! times = [0.0, 2.0]
//! rest_lengths = [5.1, 4.6]
//!
//! [[actuation]]
//! node = 5
//! times = [0.0, 0.5]
//! forces = [[0, 0, 0], [0, 0, -10]]
//! ```

use crate::error::{IoError, Result};
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use tensegrity_core::Structure;
use tensegrity_dynamics::{
    Ground, GroundModel, IntegratorKind, Model, Quantities, Simulation, SimulationSettings,
};

/// The `[simulation]` table.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SimulationSpec {
    /// End time (s).
    pub t_end: f64,
    /// Integrator (default rk4).
    #[serde(default)]
    #[schemars(schema_with = "integrator_schema")]
    pub integrator: IntegratorKind,
    /// Fixed step (rk4, rattle; default 1e-3 s) or maximum step (rk45; default t_end).
    pub dt: Option<f64>,
    /// RK45 relative tolerance, default 1e-8.
    pub rtol: Option<f64>,
    /// RK45 absolute tolerance, default 1e-10.
    pub atol: Option<f64>,
    /// Explicit output times (s).
    #[serde(default)]
    pub output_times: Vec<f64>,
    /// Regular output interval (s), from 0 to t_end.
    pub output_interval: Option<f64>,
    /// Quantities to record.
    #[serde(default)]
    pub record: Vec<RecordQuantity>,
    /// Project RK states onto the constraints after every step.
    #[serde(default)]
    pub project: bool,
    /// The bars: rigid (the default: the rigid-bar dynamics) or elastic (every member an
    /// axial spring, the mass at the nodes: `tensegrity_path::transient`); a bar's own
    /// `elastic` key overrides it, and a scene with rigid and elastic bars runs the node-mass
    /// model with its rigid bars as length constraints (`tensegrity_path::rigid_bars`).
    #[serde(default, skip_serializing_if = "BarModel::is_rigid")]
    pub bars: BarModel,
    /// How an elastic model's member masses are distributed onto its nodes: `lumped` (the
    /// default: half at each end) or `consistent` (TsgFEM's `lumped = 0`).
    #[serde(default, skip_serializing_if = "MassMatrixKind::is_lumped")]
    pub mass_matrix: MassMatrixKind,
}

/// The JSON Schema of an integrator's name: one of [`IntegratorKind::NAMES`].
fn integrator_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
    schemars::json_schema!({
        "type": "string",
        "enum": IntegratorKind::NAMES,
        "default": "rk4",
    })
}

/// Rigid or elastic bars (`[simulation] bars`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum BarModel {
    /// Rigid bars with their length constraint (the thesis' dynamics).
    #[default]
    Rigid,
    /// Elastic bars: axial springs EA = E π r² with their mass at their ends.
    Elastic,
}

impl BarModel {
    fn is_rigid(&self) -> bool {
        *self == Self::Rigid
    }
}

/// The mass distribution of an elastic model (`[simulation] mass_matrix`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum MassMatrixKind {
    /// Half of a member's mass at each end.
    #[default]
    Lumped,
    /// (m/6) [[2, 1], [1, 2]] per member.
    Consistent,
}

impl MassMatrixKind {
    fn is_lumped(&self) -> bool {
        *self == Self::Lumped
    }
}

/// A recordable quantity name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum RecordQuantity {
    /// Node positions.
    Nodes,
    /// Node velocities.
    Velocities,
    /// Axial member forces.
    MemberForces,
    /// Kinetic and total energy.
    Energy,
    /// Ground contact forces.
    ContactForces,
}

/// The ground reaction model name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum GroundModelKind {
    /// Penalty spring–damper with regularised Coulomb friction.
    #[default]
    Penalty,
    /// Thesis §3.2.2 model.
    Thesis,
}

fn up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

/// The `[ground]` table.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GroundSpec {
    /// A point of the plane (default origin).
    #[serde(default)]
    pub point: [f64; 3],
    /// Outward normal (default +z).
    #[serde(default = "up")]
    pub normal: [f64; 3],
    /// Reaction model (default penalty).
    #[serde(default)]
    pub model: GroundModelKind,
    /// Penalty stiffness (N/m), required for the penalty model.
    pub stiffness: Option<f64>,
    /// Normal damping (penalty) or contact-velocity damping (thesis), N·s/m; default 0.
    pub damping: Option<f64>,
    /// Static friction coefficient (default 0).
    pub mu_static: Option<f64>,
    /// Kinetic friction coefficient (default μ_s).
    pub mu_kinetic: Option<f64>,
    /// Friction regularisation velocity (m/s), default 1e-3.
    pub regularization_velocity: Option<f64>,
    /// Stribeck velocity (m/s), default 1e-2.
    pub stribeck_velocity: Option<f64>,
    /// Contact distance of the thesis model (m), default 1e-6.
    pub tolerance: Option<f64>,
    /// Nodes that can touch the ground (default all).
    pub nodes: Option<Vec<usize>>,
}

/// One `[[actuation]]` table: a piecewise-linear time table for one string's or one
/// cluster's rest length, or one node's extra load.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ActuationSpec {
    /// The string whose rest length is driven.
    pub string: Option<usize>,
    /// The clustered string whose (whole) rest length is driven: one actuator for all its
    /// segments.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cluster: Option<usize>,
    /// The node that gets the extra load.
    pub node: Option<usize>,
    /// Increasing times (s).
    pub times: Vec<f64>,
    /// Rest lengths (m) at `times` (with `string`).
    pub rest_lengths: Option<Vec<f64>>,
    /// Forces (N) at `times` (with `node`).
    pub forces: Option<Vec<[f64; 3]>>,
}

/// Piecewise-linear interpolation, constant outside the table.
fn interp(times: &[f64], t: f64) -> (usize, usize, f64) {
    if t <= times[0] {
        return (0, 0, 0.0);
    }
    let last = times.len() - 1;
    if t >= times[last] {
        return (last, last, 0.0);
    }
    let j = times.partition_point(|&x| x <= t);
    let i = j - 1;
    (i, j, (t - times[i]) / (times[j] - times[i]))
}

fn invalid(table: impl Into<String>, reason: &'static str) -> IoError {
    IoError::InvalidTable {
        table: table.into(),
        reason,
    }
}

fn nonneg(table: &str, name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(IoError::NegativeValue {
            table: table.into(),
            name,
            value,
        })
    }
}

/// How far below the ground plane (m) a node that can touch it may start: a structure
/// resting on a penalty ground sinks in by its weight over the stiffness, so a restart from a
/// resting state is accepted, but a structure starting inside the ground is refused.
pub const GROUND_START_TOLERANCE: f64 = 1e-3;

/// The item a failed check of [`check_tables`] concerns (for the line of its error).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Culprit {
    /// A node.
    Node(usize),
    /// The `[ground]` table.
    Ground,
    /// An `[[actuation]]` table.
    Actuation(usize),
}

/// The checks of the dynamics tables against each other and the structure that
/// [`build_simulation`] and the scene reader share: μ_k ≤ μ_s, no node that can touch the
/// ground starting more than [`GROUND_START_TOLERANCE`] below it, one rest-length table per
/// string.
pub(crate) fn check_tables(
    structure: &Structure,
    ground: Option<&GroundSpec>,
    actuation: &[ActuationSpec],
) -> std::result::Result<(), Box<(IoError, Culprit)>> {
    if let Some(g) = ground {
        g.check_friction()
            .map_err(|e| Box::new((e, Culprit::Ground)))?;
        if let Some((node, depth)) = g.deepest_node(structure) {
            if depth > GROUND_START_TOLERANCE {
                let e = IoError::BelowGround {
                    node,
                    depth,
                    tolerance: GROUND_START_TOLERANCE,
                };
                return Err(Box::new((e, Culprit::Node(node))));
            }
        }
    }
    let mut driven: Vec<Option<usize>> = vec![None; structure.n_strings()];
    for (k, a) in actuation.iter().enumerate() {
        let Some(slot) = a.string.and_then(|s| driven.get_mut(s)) else {
            continue;
        };
        if let Some(first) = *slot {
            let e = IoError::DuplicateActuation {
                table: format!("actuation {k}"),
                string: a.string.unwrap_or_default(),
                first: format!("actuation {first}"),
            };
            return Err(Box::new((e, Culprit::Actuation(k))));
        }
        *slot = Some(k);
    }
    let mut clusters: Vec<Option<usize>> = vec![None; structure.clusters().len()];
    for (k, a) in actuation.iter().enumerate() {
        let Some(slot) = a.cluster.and_then(|c| clusters.get_mut(c)) else {
            continue;
        };
        if slot.is_some() {
            let e = invalid(
                format!("actuation {k}"),
                "its cluster already has a rest-length table: give one table per cluster",
            );
            return Err(Box::new((e, Culprit::Actuation(k))));
        }
        *slot = Some(k);
    }
    Ok(())
}

impl GroundSpec {
    /// μ_k ≤ μ_s (μ_k defaults to μ_s).
    fn check_friction(&self) -> Result<()> {
        // a key the chosen model does not read would be ignored silently
        let penalty_only = [
            ("stiffness", self.stiffness.is_some()),
            ("mu_static", self.mu_static.is_some()),
            ("mu_kinetic", self.mu_kinetic.is_some()),
            (
                "regularization_velocity",
                self.regularization_velocity.is_some(),
            ),
            ("stribeck_velocity", self.stribeck_velocity.is_some()),
        ];
        let ignored = match self.model {
            GroundModelKind::Thesis => penalty_only.iter().find(|(_, given)| *given),
            GroundModelKind::Penalty => None,
        };
        if let Some((key, _)) = ignored {
            return Err(IoError::IgnoredKey {
                table: "ground".into(),
                key,
                model: "thesis",
            });
        }
        if self.model == GroundModelKind::Penalty && self.tolerance.is_some() {
            return Err(IoError::IgnoredKey {
                table: "ground".into(),
                key: "tolerance",
                model: "penalty",
            });
        }
        if let (Some(mu_static), Some(mu_kinetic)) = (self.mu_static, self.mu_kinetic) {
            if mu_kinetic > mu_static {
                return Err(IoError::FrictionOrder {
                    mu_static,
                    mu_kinetic,
                });
            }
        }
        Ok(())
    }

    /// The node (of those that can touch the ground) deepest below the plane, and its depth
    /// (m; negative when every node is above). `None` for a degenerate normal or no node.
    fn deepest_node(&self, structure: &Structure) -> Option<(usize, f64)> {
        let n = Vector3::from(self.normal);
        let n = n.try_normalize(0.0)?;
        let p = Vector3::from(self.point);
        let depth = |i: usize| structure.nodes().get(i).map(|x| -(x - p).dot(&n));
        let all: Vec<usize>;
        let nodes = match &self.nodes {
            Some(list) => list.as_slice(),
            None => {
                all = (0..structure.n_nodes()).collect();
                &all
            }
        };
        nodes
            .iter()
            .filter_map(|&i| Some((i, depth(i)?)))
            .filter(|(_, d)| d.is_finite())
            .max_by(|a, b| a.1.total_cmp(&b.1))
    }

    /// The [`Ground`] this table describes.
    pub fn to_ground(&self) -> Result<Ground> {
        self.check_friction()?;
        let n = Vector3::from(self.normal);
        if !(n.iter().all(|v| v.is_finite()) && n.norm() > 0.0) {
            return Err(invalid("ground", "normal must be a non-zero vector"));
        }
        let damping = nonneg("ground", "damping", self.damping.unwrap_or(0.0))?;
        let model = match self.model {
            GroundModelKind::Penalty => {
                let stiffness = self
                    .stiffness
                    .ok_or_else(|| invalid("ground", "the penalty model needs a stiffness"))?;
                if !(stiffness.is_finite() && stiffness > 0.0) {
                    return Err(invalid("ground", "stiffness must be positive"));
                }
                let mu_static = nonneg("ground", "mu_static", self.mu_static.unwrap_or(0.0))?;
                let mu_kinetic =
                    nonneg("ground", "mu_kinetic", self.mu_kinetic.unwrap_or(mu_static))?;
                let v_reg = self.regularization_velocity.unwrap_or(1e-3);
                let v_s = self.stribeck_velocity.unwrap_or(1e-2);
                if !(v_reg > 0.0 && v_s > 0.0 && v_reg.is_finite() && v_s.is_finite()) {
                    return Err(invalid(
                        "ground",
                        "regularization_velocity and stribeck_velocity must be positive",
                    ));
                }
                GroundModel::Penalty {
                    stiffness,
                    damping,
                    mu_static,
                    mu_kinetic,
                    regularization_velocity: v_reg,
                    stribeck_velocity: v_s,
                }
            }
            GroundModelKind::Thesis => GroundModel::Thesis {
                damping,
                tolerance: nonneg("ground", "tolerance", self.tolerance.unwrap_or(1e-6))?,
            },
        };
        let mut g = Ground::new(Vector3::from(self.point), n, model);
        g.nodes = self.nodes.clone();
        Ok(g)
    }
}

impl SimulationSpec {
    /// Settings from this table (defaults: dt 1e-3 s, or t_end for rk45; rtol 1e-8;
    /// atol 1e-10).
    pub fn to_settings(&self) -> SimulationSettings {
        let mut q = Quantities::default();
        for r in &self.record {
            match r {
                RecordQuantity::Nodes => q.nodes = true,
                RecordQuantity::Velocities => q.velocities = true,
                RecordQuantity::MemberForces => q.member_forces = true,
                RecordQuantity::Energy => q.energy = true,
                RecordQuantity::ContactForces => q.contact_forces = true,
            }
        }
        let d = SimulationSettings::default();
        SimulationSettings {
            t_end: self.t_end,
            integrator: self.integrator,
            dt: self.dt.unwrap_or(match self.integrator {
                IntegratorKind::Rk45 => self.t_end,
                _ => d.dt,
            }),
            rtol: self.rtol.unwrap_or(d.rtol),
            atol: self.atol.unwrap_or(d.atol),
            output_times: self.output_times.clone(),
            output_interval: self.output_interval,
            quantities: q,
            project: self.project,
            ..d
        }
    }
}

/// One validated actuation table: the string or node it drives, its times and values.
type Table<T> = (usize, Vec<f64>, Vec<T>);

/// Turns a structure plus the optional `[simulation]`, `[ground]` and `[[actuation]]` tables
/// into a runnable [`Simulation`] (settings default to [`SimulationSettings::default`] when
/// `sim` is `None`; a caller may still override `simulation.settings`).
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_io::scene::{build_simulation, GroundSpec};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.1], [1.0, 0.0, 0.1]])
///     .bar(Bar::new(0, 1).mass(1.0))
///     .build()
///     .unwrap();
/// let ground: GroundSpec = toml::from_str("stiffness = 1e4").unwrap();
/// let sim = build_simulation(&s, None, Some(&ground), &[]).unwrap();
/// assert!(sim.model.ground().is_some());
/// ```
pub fn build_simulation(
    structure: &Structure,
    sim: Option<&SimulationSpec>,
    ground: Option<&GroundSpec>,
    actuation: &[ActuationSpec],
) -> Result<Simulation> {
    check_tables(structure, ground, actuation).map_err(|b| b.0)?;
    let ground = ground.map(GroundSpec::to_ground).transpose()?;
    let settings = sim.map(SimulationSpec::to_settings).unwrap_or_default();
    let mut simulation = Simulation::new(structure, settings)?;
    if let Some(g) = ground {
        simulation.model.set_ground(g)?;
    }
    let mut rest_tables: Vec<Table<f64>> = Vec::new();
    let mut load_tables: Vec<Table<Vector3<f64>>> = Vec::new();
    for (k, a) in actuation.iter().enumerate() {
        match a.validate(&format!("actuation {k}"), structure)? {
            Actuation::RestLength(t) => rest_tables.push(t),
            Actuation::Load(t) => load_tables.push(t),
        }
    }
    set_schedules(&mut simulation.model, rest_tables, load_tables);
    Ok(simulation)
}

/// A validated actuation table.
enum Actuation {
    RestLength(Table<f64>),
    Load(Table<Vector3<f64>>),
}

impl ActuationSpec {
    /// Checks the table against the structure; `table` names it in errors.
    fn validate(&self, table: &str, structure: &Structure) -> Result<Actuation> {
        let increasing = self
            .times
            .windows(2)
            .all(|w| w[1].partial_cmp(&w[0]) == Some(std::cmp::Ordering::Greater));
        if self.times.is_empty() || !increasing {
            return Err(invalid(
                table,
                "times must be non-empty and strictly increasing",
            ));
        }
        if self.times.iter().any(|t| !t.is_finite()) {
            return Err(invalid(table, "times must be finite"));
        }
        let unknown = |kind, index, count| IoError::UnknownIndex {
            table: table.into(),
            kind,
            index,
            count,
        };
        if let Some(c) = self.cluster {
            let (Some(r), None, None, None) =
                (&self.rest_lengths, &self.forces, self.string, self.node)
            else {
                return Err(invalid(
                    table,
                    "give `cluster` with `rest_lengths` only (no `string`, `node` or `forces`)",
                ));
            };
            let count = structure.clusters().len();
            if c >= count {
                return Err(unknown("cluster", c, count));
            }
            if r.len() != self.times.len() {
                return Err(invalid(table, "rest_lengths and times differ in length"));
            }
            if r.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(invalid(table, "rest lengths must be positive"));
            }
            // the schedule's slots: the strings', then the clusters'
            let slot = structure.n_strings() + c;
            return Ok(Actuation::RestLength((slot, self.times.clone(), r.clone())));
        }
        match (self.string, self.node, &self.rest_lengths, &self.forces) {
            (Some(s), None, Some(r), None) => {
                if s >= structure.n_strings() {
                    return Err(unknown("string", s, structure.n_strings()));
                }
                if r.len() != self.times.len() {
                    return Err(invalid(table, "rest_lengths and times differ in length"));
                }
                if r.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                    return Err(invalid(table, "rest lengths must be positive"));
                }
                Ok(Actuation::RestLength((s, self.times.clone(), r.clone())))
            }
            (None, Some(n), None, Some(f)) => {
                if n >= structure.n_nodes() {
                    return Err(unknown("node", n, structure.n_nodes()));
                }
                if f.len() != self.times.len() {
                    return Err(invalid(table, "forces and times differ in length"));
                }
                if f.iter().flatten().any(|v| !v.is_finite()) {
                    return Err(invalid(table, "forces must be finite"));
                }
                let forces = f.iter().map(|&v| v.into()).collect();
                Ok(Actuation::Load((n, self.times.clone(), forces)))
            }
            _ => Err(invalid(
                table,
                "give either `string` (or `cluster`) with `rest_lengths` or `node` with `forces`",
            )),
        }
    }
}

/// Installs the interpolated tables as the model's rest-length and load schedules.
fn set_schedules(
    model: &mut Model,
    rest_tables: Vec<Table<f64>>,
    load_tables: Vec<Table<Vector3<f64>>>,
) {
    if !rest_tables.is_empty() {
        model.set_rest_length_schedule(Box::new(move |t, rest| {
            for (s, times, values) in &rest_tables {
                let (i, j, w) = interp(times, t);
                rest[*s] = values[i] * (1.0 - w) + values[j] * w;
            }
        }));
    }
    if !load_tables.is_empty() {
        model.set_load_schedule(Box::new(move |t, loads| {
            for (n, times, values) in &load_tables {
                let (i, j, w) = interp(times, t);
                loads[*n] += values[i] * (1.0 - w) + values[j] * w;
            }
        }));
    }
}
