//! Actuation of the elastic dynamics ([`ElasticActuation`]): piecewise-linear time tables
//! (constant outside their times) that drive a string's or a cluster's rest length, or add
//! a load to a node — the scene's `[[actuation]]` tables, as the rigid-bar dynamics reads
//! them.
//!
//! A driven string or cluster keeps its EA (its material does not change as it is reeled; a
//! cluster's EA = k L₀ from its scene stiffness k and rest length L₀): t = EA (l − L₀(t))/L₀(t)
//! while l > L₀(t), else slack, a cluster's one tension along all its segments (l = L = Σ l_i),
//! so one actuator reels every segment. (The rigid-bar dynamics keeps a driven string's or
//! cluster's stiffness k instead, the thesis's string model; the two agree to first order in
//! the change of the rest length.) An actuator does work, so a driven run has no energy check (its `energy_drift`
//! includes the actuators' work). A cluster with pulley friction cannot be driven (where
//! its actuator takes in the material is not modelled): refused naming it.

use crate::error::{PathError, Result};
use crate::forces::MemberState;
use crate::model::{ElasticModel, MemberKind};
use nalgebra::Vector3;

/// What a rest-length table drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Driven {
    /// A member of the model (a string), by its index in the model.
    Member(usize),
    /// A cluster, by its index.
    Cluster(usize),
}

/// A rest-length table: `rest_lengths` (m) at increasing `times` (s).
#[derive(Debug, Clone, PartialEq)]
pub struct RestLengthTable {
    /// What it drives.
    pub driven: Driven,
    /// Increasing times (s).
    pub times: Vec<f64>,
    /// Rest lengths (m) at `times`.
    pub rest_lengths: Vec<f64>,
}

/// A load table: an extra load `forces` (N) on `node` at increasing `times` (s).
#[derive(Debug, Clone, PartialEq)]
pub struct LoadTable {
    /// The node.
    pub node: usize,
    /// Increasing times (s).
    pub times: Vec<f64>,
    /// Forces (N) at `times`.
    pub forces: Vec<Vector3<f64>>,
}

/// Every table of a run (module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ElasticActuation {
    /// The rest-length tables.
    pub rest_lengths: Vec<RestLengthTable>,
    /// The load tables.
    pub loads: Vec<LoadTable>,
}

/// The value of a piecewise-linear table at `t` (constant outside it).
///
/// ```
/// use tensegrity_path::actuation::table_at;
/// assert_eq!(table_at(&[0.0, 1.0], &[2.0, 4.0], 0.25, |a, b, w| a + (b - a) * w), 2.5);
/// assert_eq!(table_at(&[0.0, 1.0], &[2.0, 4.0], 7.0, |a, b, w| a + (b - a) * w), 4.0);
/// ```
pub fn table_at<T: Copy>(times: &[f64], values: &[T], t: f64, lerp: impl Fn(T, T, f64) -> T) -> T {
    let last = times.len() - 1;
    if t <= times[0] {
        return values[0];
    }
    if t >= times[last] {
        return values[last];
    }
    let j = times.partition_point(|&x| x <= t);
    let i = j - 1;
    lerp(values[i], values[j], (t - times[i]) / (times[j] - times[i]))
}

impl ElasticActuation {
    /// Whether nothing is driven.
    pub fn is_empty(&self) -> bool {
        self.rest_lengths.is_empty() && self.loads.is_empty()
    }

    /// Checks the tables against `model` (errors name `actuation k`, the tables numbered
    /// rest lengths first, then loads): a driven member a string, a driven cluster without
    /// friction, indices in range, at least one time, times finite and increasing, one
    /// value per time, rest lengths positive, forces finite.
    pub fn check(&self, model: &ElasticModel) -> Result<()> {
        let bad = |k: usize, why: String| PathError::model(format!("actuation {k}"), why);
        for (k, table) in self.rest_lengths.iter().enumerate() {
            match table.driven {
                Driven::Member(m) => match model.members.get(m) {
                    Some(member) if member.kind == MemberKind::String => {}
                    Some(_) => return Err(bad(k, format!("member {m} is a bar: only a string's or a cluster's rest length is driven"))),
                    None => return Err(bad(k, format!("member {m} does not exist ({} members)", model.members.len()))),
                },
                Driven::Cluster(c) => match model.clusters.get(c) {
                    Some(cl) if cl.friction.is_some() => return Err(bad(k, format!("cluster {c} has pulley friction: where its actuator takes in the material is not modelled; drive a frictionless cluster"))),
                    Some(_) => {}
                    None => return Err(bad(k, format!("cluster {c} does not exist ({} clusters)", model.clusters.len()))),
                },
            }
            check_times(&table.times, table.rest_lengths.len()).map_err(|why| bad(k, why))?;
            if let Some(v) = table
                .rest_lengths
                .iter()
                .find(|v| !(v.is_finite() && **v > 0.0))
            {
                return Err(bad(
                    k,
                    format!("rest length {v}: give positive, finite rest lengths (m)"),
                ));
            }
        }
        for (i, table) in self.loads.iter().enumerate() {
            let k = self.rest_lengths.len() + i;
            if table.node >= model.nodes.len() {
                return Err(bad(
                    k,
                    format!(
                        "node {} does not exist ({} nodes)",
                        table.node,
                        model.nodes.len()
                    ),
                ));
            }
            check_times(&table.times, table.forces.len()).map_err(|why| bad(k, why))?;
            if table
                .forces
                .iter()
                .any(|f| !f.iter().all(|c| c.is_finite()))
            {
                return Err(bad(k, "a force that is not finite".into()));
            }
        }
        Ok(())
    }

    /// Sets the driven members' and clusters' states at time `t` (module docs).
    pub fn apply(&self, model: &ElasticModel, t: f64, states: &mut [MemberState]) {
        for table in &self.rest_lengths {
            let rest = table_at(&table.times, &table.rest_lengths, t, |a, b, w| {
                a + (b - a) * w
            });
            match table.driven {
                Driven::Member(m) => {
                    let s = &mut states[m];
                    s.rest_length = rest;
                    s.slack = s.length <= rest;
                    s.tension = if s.slack {
                        0.0
                    } else {
                        model.members[m].ea * (s.length - rest) / rest
                    };
                }
                Driven::Cluster(c) => {
                    let range = model.cluster_states(c);
                    let length: f64 = states[range.clone()].iter().map(|s| s.length).sum();
                    let slack = length <= rest;
                    let tension = if slack {
                        0.0
                    } else {
                        model.clusters[c].stiffness_at(rest) * (length - rest)
                    };
                    for s in &mut states[range] {
                        s.rest_length = rest;
                        s.slack = slack;
                        s.tension = tension;
                    }
                }
            }
        }
    }

    /// A driven cluster's rest length at `t` (`None`: not driven).
    pub fn cluster_rest_length(&self, c: usize, t: f64) -> Option<f64> {
        self.rest_lengths
            .iter()
            .find(|table| table.driven == Driven::Cluster(c))
            .map(|table| {
                table_at(&table.times, &table.rest_lengths, t, |a, b, w| {
                    a + (b - a) * w
                })
            })
    }

    /// Adds the load tables' forces at `t` to `f` (one per node).
    pub fn add_loads(&self, t: f64, f: &mut [Vector3<f64>]) {
        for table in &self.loads {
            f[table.node] += table_at(&table.times, &table.forces, t, |a, b, w| a + (b - a) * w);
        }
    }
}

fn check_times(times: &[f64], values: usize) -> std::result::Result<(), String> {
    if times.is_empty() {
        return Err("no times: give at least one".into());
    }
    if values != times.len() {
        return Err(format!(
            "{values} value(s) for {} time(s): give one per time",
            times.len()
        ));
    }
    if !times.iter().all(|t| t.is_finite()) || times.windows(2).any(|w| w[1] <= w[0]) {
        return Err("times must be finite and increasing".into());
    }
    Ok(())
}
