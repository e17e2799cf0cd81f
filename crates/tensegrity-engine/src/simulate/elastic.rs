//! Elastic scenes in `simulate`: a scene with `[simulation] bars = "elastic"` (or some bar
//! `elastic = true`), or a net of strings with point masses and no bar (`[[masses]]`), runs
//! the elastic dynamics of `tensegrity_path::transient` instead of the rigid-bar model —
//! every member an axial spring (a bar EA = E π r² from its material and radius, its rest
//! length its `rest_length` or its length in the scene; a string its stiffness k, EA = k L₀,
//! tension only), the mass at the nodes: each bar's `mass` (or ρ π r² L), each string's
//! `mass` (default massless), every `[[masses]]` point mass, distributed by
//! `[simulation] mass_matrix` (lumped, the default, or consistent), the strings' `damping`
//! as axial dashpots, the scene's loads from t = 0 and the weights under `[gravity]`; supports
//! along any direction (`along`) and on springs (`stiffness`) as in `solve`; `[[clusters]]`
//! (clustered strings, massless: `tensegrity_path::clusters`) with their `stiffness`,
//! `rest_length`, `damping` and pulley `friction`.
//!
//! The same request ([`SimulateCommand`]) and report ([`SimulationReport`]: its constraint
//! drift is zero, the supports holding exactly, and its bar-length drift that of the rigid
//! bars of a mixed scene, below) as a rigid run; the integrators are rk4 (its step refused
//! above the stability limit of the stiffest axial mode, and by default half that limit when
//! below 1 ms), rk45 and newmark (implicit: stable at any step). The convergence check reruns
//! the scene at the refined resolution ([`SimulateCommand::refine`]) and compares the final
//! states as for a rigid run. `[[actuation]]` drives strings' and clusters' rest lengths
//! and node loads (`tensegrity_path::actuation`; no energy check then); `[ground]` is refused
//! (not modelled for elastic members).
//!
//! **Mixed scenes.** A bar's `elastic = true | false` overrides `[simulation] bars` for it;
//! a scene with some elastic bar runs this model with its rigid bars as length constraints
//! (`tensegrity_path::rigid_bars`: no radius nor material needed, their mass always
//! consistent, their force −μ L in the member forces, the largest length error the
//! report's `bar_length_drift`); a scene whose bars are all rigid runs the rigid-bar
//! dynamics. A rigid bar here takes no `rest_length` (it keeps its length in the scene).

use super::companion::{self, Refined};
use super::{Checked, CompanionRun, Scales, SimulateCommand};
use crate::scene::SceneError;
use nalgebra::Vector3;
use tensegrity_core::budget::{Estimate, Parameters};
use tensegrity_core::request::InvalidParameter;
use tensegrity_dynamics::recorder::SampleSink;
use tensegrity_dynamics::{IntegratorKind, SimulationReport, SimulationSettings};
use tensegrity_io::scene::{MassMatrixKind, Scene};
use tensegrity_path::actuation::{Driven, ElasticActuation, LoadTable, RestLengthTable};
use tensegrity_path::transient::RK4_STABILITY;
use tensegrity_path::{ElasticDynamics, ElasticModel, MassDistribution, Masses, PathError};

/// An elastic scene set up for its run: the model and the settings under the request.
#[derive(Debug)]
pub struct ElasticRun {
    /// The elastic dynamics of the scene.
    pub dynamics: ElasticDynamics,
    /// The run's settings (the scene's `[simulation]` under the request's overrides).
    pub settings: SimulationSettings,
}

/// Whether `simulate` runs `scene` as an elastic model (module docs).
pub fn is_elastic(scene: &Scene) -> bool {
    scene.file.is_elastic()
}

/// Refuses the keys only the elastic dynamics reads (a string's `mass`, `[[masses]]`) and
/// the bars' `elastic` (read by `simulate` alone) in a scene that `command` runs otherwise,
/// naming the first.
pub fn refuse_elastic_keys(scene: &Scene, command: &str) -> Result<(), InvalidParameter> {
    if let Some(key) = scene.file.bar_model_keys().first() {
        return Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by `simulate` only (a bar elastic or rigid in the dynamics); `{command}` would ignore it: remove it"),
        ));
    }
    refuse_elastic_keys_of_rigid_run(scene, command)
}

/// [`refuse_elastic_keys`] for the rigid-bar dynamics, which reads the bars' `elastic`
/// (every one false there: a scene with an elastic bar runs the elastic dynamics).
pub fn refuse_elastic_keys_of_rigid_run(
    scene: &Scene,
    command: &str,
) -> Result<(), InvalidParameter> {
    match scene.file.elastic_keys().first() {
        None => Ok(()),
        Some(key) => Err(InvalidParameter::text(
            "scene",
            key,
            format!("{key} is read by the elastic dynamics only (`[simulation] bars = \"elastic\"`, or strings with point masses and no bar); `{command}` would ignore it: remove it, or give the scene elastic bars"),
        )),
    }
}

/// The elastic dynamics of `scene` (module docs); errors name the item.
pub fn dynamics_of(scene: &Scene) -> Result<ElasticDynamics, SceneError> {
    crate::scene::refuse_driver_keys(scene, "simulate")?;
    let file = &scene.file;
    if file.ground.is_some() {
        return Err(InvalidParameter::text(
            "scene",
            "[ground]",
            "[ground] is not modelled for elastic members: remove it, or run the scene with rigid bars",
        )
        .into());
    }
    let s = &scene.structure;
    let rigid = rigid_bars(scene)?;
    let mut model = ElasticModel::from_structure_mixed(s, &rigid)?;
    for (member, (l0, &r)) in model
        .members
        .iter_mut()
        .zip(file.bar_rest_lengths().into_iter().zip(&rigid))
    {
        if let (Some(l0), false) = (l0, r) {
            member.rest_length = l0;
        }
    }
    // the bar's mass, or ρ π r² L from its material and radius (as the rigid model)
    let bars = (0..s.n_bars()).map(|k| s.bar_mass(k).unwrap_or(0.0));
    let strings = file
        .strings
        .iter()
        .map(|st| st.get_ref().mass.unwrap_or(0.0));
    let nodes = point_masses(scene)?;
    let distribution = match file.simulation.as_ref().map(|sim| sim.mass_matrix) {
        Some(MassMatrixKind::Consistent) => MassDistribution::Consistent,
        _ => MassDistribution::Lumped,
    };
    let masses = Masses {
        members: bars.chain(strings).collect(),
        nodes,
        distribution,
    };
    let damping: Vec<f64> = std::iter::repeat_n(0.0, s.n_bars())
        .chain(s.strings().iter().map(|st| st.damping))
        .collect();
    let damping = if damping.iter().all(|&c| c == 0.0) {
        Vec::new()
    } else {
        damping
    };
    let velocities = s.velocities().unwrap_or_default();
    let rigid: Vec<usize> = (0..rigid.len()).filter(|&k| rigid[k]).collect();
    Ok(
        ElasticDynamics::new(model, masses, damping, s.gravity(), velocities)?
            .with_rigid_bars(&rigid)?
            .with_actuation(actuation_of(scene)?)?,
    )
}

/// The scene's `[[actuation]]` tables for the elastic model (strings after the bars):
/// a string's or a cluster's rest length, a node's extra load (`tensegrity_path::actuation`);
/// a cluster with pulley friction is not driven (an error naming the table).
fn actuation_of(scene: &Scene) -> Result<ElasticActuation, SceneError> {
    let n_bars = scene.structure.n_bars();
    let mut out = ElasticActuation::default();
    for (i, a) in scene.file.actuation.iter().map(|a| a.get_ref()).enumerate() {
        let driven = match (a.string, a.cluster) {
            (Some(k), _) => Some(Driven::Member(n_bars + k)),
            (None, Some(c)) => Some(Driven::Cluster(c)),
            _ => None,
        };
        if let Some(c) = a.cluster {
            if scene
                .structure
                .clusters()
                .get(c)
                .is_some_and(|cl| !cl.is_frictionless())
            {
                return Err(PathError::model(
                    format!("actuation {i}"),
                    format!("cluster {c} has pulley friction: where its actuator takes in the material is not modelled; drive a frictionless cluster"),
                )
                .into());
            }
        }
        if let (Some(driven), Some(rest)) = (driven, &a.rest_lengths) {
            out.rest_lengths.push(RestLengthTable {
                driven,
                times: a.times.clone(),
                rest_lengths: rest.clone(),
            });
        }
        if let (Some(node), Some(forces)) = (a.node, &a.forces) {
            out.loads.push(LoadTable {
                node,
                times: a.times.clone(),
                forces: forces.iter().map(|&f| f.into()).collect(),
            });
        }
    }
    Ok(out)
}

/// Which bars of an elastic scene are rigid (their `elastic = false`, or `[simulation]
/// bars` rigid where not given); a rigid bar with a `rest_length` is an error naming it.
fn rigid_bars(scene: &Scene) -> Result<Vec<bool>, SceneError> {
    let rigid: Vec<bool> = scene.file.elastic_bars().iter().map(|e| !e).collect();
    let lengths = scene.file.bar_rest_lengths();
    if let Some(k) = (0..rigid.len()).find(|&k| rigid[k] && lengths[k].is_some()) {
        return Err(PathError::model(
            format!("bar {k}"),
            "a rigid bar keeps its length in the scene: remove its `rest_length`, or make it elastic (`elastic = true`)",
        )
        .into());
    }
    Ok(rigid)
}

/// Sets the bars' rest lengths of `model` (built from `scene`'s structure: bars first) to the
/// scene's `rest_length` where given (a prestressed elastic bar).
pub fn with_bar_rest_lengths(model: &mut ElasticModel, scene: &Scene) {
    for (member, l0) in model.members.iter_mut().zip(scene.file.bar_rest_lengths()) {
        if let Some(l0) = l0 {
            member.rest_length = l0;
        }
    }
}

/// Adds to `model`'s dead load (built from `scene`'s structure: the bars' weight) the weight
/// of the strings' `mass` (half at each end) and of the `[[masses]]` point masses under the
/// scene's `[gravity]` (nothing without it): the self-weight a load path carries from λ = 0.
/// A point mass at a node that does not exist, or a mass not finite and ≥ 0, is an error
/// naming its entry.
pub fn with_string_and_point_weights(
    model: &mut ElasticModel,
    scene: &Scene,
) -> Result<(), SceneError> {
    let nodes = point_masses(scene)?;
    let Some(g) = scene.structure.gravity() else {
        return Ok(());
    };
    let n = model.nodes.len();
    let mut weight = vec![Vector3::zeros(); n];
    for (i, m) in nodes.iter().enumerate() {
        weight[i] += g * *m;
    }
    for (k, st) in scene.file.strings.iter().enumerate() {
        let m = st.get_ref().mass.unwrap_or(0.0);
        if !(m.is_finite() && m >= 0.0) {
            return Err(PathError::model(
                format!("string {k}"),
                format!("mass {m}: give a finite mass ≥ 0 (kg)"),
            )
            .into());
        }
        for i in scene.structure.strings()[k].nodes {
            weight[i] += g * (0.5 * m);
        }
    }
    if weight.iter().all(|w| w.norm() == 0.0) {
        return Ok(());
    }
    if model.drivers.dead_load.is_empty() {
        model.drivers.dead_load = vec![Vector3::zeros(); n];
    }
    for (d, w) in model.drivers.dead_load.iter_mut().zip(weight) {
        *d += w;
    }
    Ok(())
}

/// Each node's point mass from `[[masses]]` (kg), every entry checked (module docs).
fn point_masses(scene: &Scene) -> Result<Vec<f64>, SceneError> {
    let n = scene.structure.n_nodes();
    let mut nodes = vec![0.0; n];
    for (k, (node, mass)) in scene.file.point_masses().into_iter().enumerate() {
        if node >= n {
            return Err(PathError::model(
                format!("point mass {k}"),
                format!("node {node} does not exist ({n} nodes)"),
            )
            .into());
        }
        if !(mass.is_finite() && mass >= 0.0) {
            return Err(PathError::model(
                format!("point mass {k}"),
                format!("mass {mass}: give a finite mass ≥ 0 (kg)"),
            )
            .into());
        }
        nodes[node] += mass;
    }
    Ok(nodes)
}

impl SimulateCommand {
    /// The elastic run of `scene` under this request (`written`: samples are written); with
    /// no step given, rk4 takes the smaller of its default and half its stability limit.
    pub fn elastic(&self, scene: &Scene, written: bool) -> Result<ElasticRun, SceneError> {
        let dynamics = dynamics_of(scene)?;
        let spec = scene.file.simulation.as_ref();
        let mut settings = spec.map(|s| s.to_settings()).unwrap_or_default();
        self.apply(&mut settings, spec, written)?;
        let given = self.dt.is_some() || spec.is_some_and(|s| s.dt.is_some());
        if !given && settings.integrator == IntegratorKind::Rk4 {
            let half_limit = 0.5 * RK4_STABILITY / dynamics.highest_frequency();
            settings.dt = settings.dt.min(half_limit);
        }
        Ok(ElasticRun { dynamics, settings })
    }
}

impl ElasticRun {
    /// The run into `sink` and, with the request's convergence check, the refined run after
    /// it: the report with its `convergence` (a warning per unconverged quantity).
    pub fn run_checked(
        &self,
        command: &SimulateCommand,
        scene: &Scene,
        sink: &mut dyn SampleSink,
    ) -> Result<SimulationReport, SceneError> {
        Ok(self.run_beside(command, scene, sink).report()?)
    }

    /// The run into `sink` and, with the request's convergence check, its refined companion
    /// after it (not after a failed run), as [`SimulateCommand::run_beside`] gives them.
    pub fn run_beside(
        &self,
        command: &SimulateCommand,
        scene: &Scene,
        sink: &mut dyn SampleSink,
    ) -> Checked {
        let main = self.dynamics.run(&self.settings, sink);
        let companion = match (&main, command.convergence_check) {
            (Ok(_), true) => {
                let mut fine = SimulationSettings {
                    output_times: Vec::new(),
                    output_interval: None,
                    quantities: Default::default(),
                    ..self.settings.clone()
                };
                let what = SimulateCommand::refine(&mut fine);
                let why = if fine.integrator.is_adaptive() {
                    Refined::Adaptive
                } else {
                    Refined::Refused("an elastic model")
                };
                Some(CompanionRun {
                    convergence: companion::refined(what, 1.0, why),
                    result: self.dynamics.run(&fine, &mut super::Discard),
                })
            }
            _ => None,
        };
        Checked {
            main,
            companion,
            scales: Scales::of(scene),
        }
    }

    /// The resource estimate: the run and its refined companion (twice its work) when
    /// checked, at the measured cost of one force evaluation per member (`csv`, `vtk`:
    /// samples written).
    pub fn estimate(&self, checked: bool, csv: bool, vtk: bool) -> Result<Estimate, SceneError> {
        self.settings.validate()?;
        let s = &self.settings;
        let steps = (s.t_end / s.dt).ceil();
        let members = self.dynamics.model().members.len().max(1) as f64;
        let n = self.dynamics.n_free() as f64;
        let per_step = match s.integrator {
            IntegratorKind::Rk4 => 4.0 * members * SECONDS_PER_MEMBER_EVALUATION,
            IntegratorKind::Rk45 => 6.0 * members * SECONDS_PER_MEMBER_EVALUATION,
            // a few Newton iterations, each a force evaluation, an assembly and a
            // factorisation: sparse (measured, module docs) or dense LU (n³/3 flops each)
            _ if n > tensegrity_path::factor::DENSE_MAX as f64 => {
                members * NEWMARK_SECONDS_PER_MEMBER
            }
            _ => members * NEWMARK_SECONDS_PER_MEMBER + 3.0 * n.powi(3) / 3.0 * 1e-9,
        };
        let work = steps * per_step * if checked { 3.0 } else { 1.0 };
        let samples = s
            .output_interval
            .map_or(s.output_times.len() as f64, |d| (s.t_end / d).ceil() + 1.0);
        let nodes = self.dynamics.model().nodes.len() as f64;
        let bytes = samples
            * 3.0
            * nodes
            * (25.0 * f64::from(u8::from(csv)) + 40.0 * f64::from(u8::from(vtk)));
        let memory = 8.0 * (self.dynamics.n_free() as f64).powi(2).min(1e9) + 1e6;
        Ok(Estimate::new(
            format!(
                "the elastic dynamics ({} members, {} free coordinates, {steps} steps of {})",
                members,
                self.dynamics.n_free(),
                s.integrator
            ),
            Parameters::default().and("t_end", s.t_end).and("dt", s.dt),
        )
        .memory(memory)
        .work(work)
        .output(bytes))
    }
}

/// The cost of one member's force in one evaluation (s; measured on the T-bar anchor: 8013
/// RK4 steps of 6 members in 15–33 ms of a release build on 2 loaded cores, 0.08 µs a member
/// and evaluation, rounded up to cover a debug build's).
pub const SECONDS_PER_MEMBER_EVALUATION: f64 = 2e-7;

/// The cost of one Newmark step per member on the sparse path (s; measured on the truss
/// towers of docs/notes/PERFORMANCE.md: 3.5 ms a step at 999 members, 125 ms at 29,997, about
/// 4 µs a member, release build).
pub const NEWMARK_SECONDS_PER_MEMBER: f64 = 5e-6;
