//! `statics`: the statics of a scene ([`StaticsCommand`], a request named `statics`) — one
//! call of the core's statics front ([`tensegrity_statics::statics_report`]: rank, self-stress,
//! prestressability, mechanisms, the load solve and sizing, the modes on request) on the
//! scene's structure.
//!
//! Its resource estimate ([`estimate`]) is that of the dense SVD of the m × n equilibrium
//! matrix (m free degrees of freedom, n columns, members then clustered strings: O(m² + n²)
//! memory, O(max(m,n)² min(m,n)) work, [`budget::dense_statics`]) when the method takes the
//! dense path — `dense`, or `auto` below [`SPARSE_MIN_SIZE`] or with clustered strings, which
//! only the dense SVD models (the report names them `cluster 0`, … after the strings) — and otherwise that of the sparse QR, whose cost is linear in
//! the band of the structure: its memory is the QR's profile and the dense bases it reports
//! (mechanisms or self-stresses, at least the difference of dofs and members), so that a
//! structure too large for either is refused before it is read into a factorisation.
//!
//! ```
//! use tensegrity_core::request::Request;
//! use tensegrity_engine::statics::{statics, StaticsCommand};
//! let c = StaticsCommand::from_values([("scene", serde_json::json!("../../examples/prism.toml"))])?;
//! let r = statics(&c)?;
//! assert_eq!((r.self_stress_dim, r.prestressable), (1, true));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::context::Context;
use crate::scene::{required, SceneError, SceneSource};
use serde::{Deserialize, Serialize};
use tensegrity_core::budget::{self, Estimate, Limits};
use tensegrity_core::error::ModelError;
use tensegrity_core::request::{Categorized, Category, InvalidParameter, Request};
use tensegrity_core::{CoreError, Structure};
use tensegrity_derive::Params;
use tensegrity_io::scene::Scene;
use tensegrity_statics::stiffness::MassModel;
use tensegrity_statics::{
    n_columns, sparse_after_qr, DofMap, StaticsMethod, StaticsSettings, SPARSE_FLOP_RATE,
    SPARSE_MIN_SIZE,
};
use tensegrity_statics::{statics_report, StaticsReport, StaticsRequest};

/// The statics of a scene, as data (defaults: the SVD's own rank tolerance, the method
/// chosen by size, no modes, the lumped mass, a load that is not carried an error).
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct StaticsCommand {
    /// The scene: a TOML file, or its text (required).
    #[param(
        text,
        help = "The scene file (TOML), or the scene's TOML text (a value naming no file, with a line break or an `=`, and not one line ending in .toml)",
        required
    )]
    pub scene: Option<SceneSource>,
    /// Relative rank tolerance of the SVD, in (0, 1) (`None`: max(rows, cols) · ε).
    #[param(
        number,
        help = "Relative rank tolerance of the SVD, in (0, 1) (default: max(rows, cols) · machine epsilon)",
        positive,
        optional
    )]
    pub rank_tol: Option<f64>,
    /// Relative precision of the node coordinates (a fraction of the largest coordinate),
    /// in [0, 0.1): the rank decision discounts the singular values rounding of this size
    /// can create (`None`: judged from the coordinates' digits; 0: exact data).
    #[param(
        number,
        help = "Relative precision of the node coordinates, a fraction of the largest one, in [0, 0.1) (default: judged from their digits, e.g. 5e-10 for coordinates written to 9 significant digits; 0: exact); the rank decision discounts the singular values rounding of this size can create",
        optional
    )]
    pub input_precision: Option<f64>,
    /// Also report the k lowest natural frequencies.
    #[param(
        count,
        help = "Also report the K lowest natural frequencies about the current state (strings need stiffness and rest length, bars mass, material and radius)",
        optional
    )]
    pub modes: Option<usize>,
    /// The mass matrix of the modes.
    #[param(choice = ["lumped", "consistent"], help = "Mass matrix of the modes: lumped (half of each bar at each end) or consistent (the rigid-bar mass matrix of the dynamics)")]
    pub mass: MassModel,
    /// Report the least-squares force densities of a load that is not carried (marked
    /// `load_carried: false`, without sizing) instead of failing.
    #[param(
        flag,
        help = "When the loads cannot be carried (the structure is a mechanism for them), report the least-squares force densities marked `load_carried: false`, without sizing, instead of failing"
    )]
    pub least_squares: bool,
    /// Also report the linear response at the scene's geometry (small displacements under
    /// the loads; always computed when a support has a prescribed `displacement`).
    #[param(
        flag,
        help = "Also report the linear response at the scene's geometry: node displacements, member force changes and reactions under the loads, from the tangent stiffness (bars need material and radius, strings stiffness); computed whenever a support has a `displacement`"
    )]
    pub response: bool,
    /// The factorisation: by size, the dense SVD or the sparse QR.
    #[param(choice = ["auto", "dense", "sparse"], help = "Factorisation: auto (the dense SVD for small structures, the sparse rank-revealing QR from 50 dofs and members on, 300 for coordinates judged rounded), dense or sparse")]
    pub method: StaticsMethod,
}

impl Request for StaticsCommand {
    const NAME: &'static str = "statics";

    /// A relative rank tolerance lies strictly between 0 and 1, a relative input precision
    /// in [0, 0.1).
    fn check(&self) -> Result<(), InvalidParameter> {
        if let Some(tol) = self.rank_tol.filter(|&t| t >= 1.0) {
            return Err(InvalidParameter::new(
                "rank_tol",
                tol,
                "a relative tolerance must lie strictly between 0 and 1",
            ));
        }
        match self.input_precision {
            Some(p) if !(0.0..0.1).contains(&p) => Err(InvalidParameter::new(
                "input_precision",
                p,
                "a relative precision of the coordinates must lie in [0, 0.1)",
            )),
            _ => Ok(()),
        }
    }
}

impl StaticsCommand {
    /// The scene (required).
    pub fn source(&self) -> Result<&SceneSource, InvalidParameter> {
        required(&self.scene)
    }

    /// The core's request of this command.
    pub fn request(&self) -> StaticsRequest {
        self.request_within(None)
    }

    /// The core's request of this command under a front end's `limits` (memory and work: the
    /// sparse path checks them again once its rank is known).
    pub fn request_within(&self, limits: Option<&Limits>) -> StaticsRequest {
        StaticsRequest {
            settings: StaticsSettings {
                method: self.method,
                rank_tolerance: self.rank_tol,
                input_precision: self.input_precision,
                memory_limit: limits.map(|l| l.memory_bytes),
                work_limit: limits.map(|l| l.work_s),
                ..StaticsSettings::default()
            },
            modes: self.modes,
            mass: self.mass,
            least_squares: self.least_squares,
        }
    }

    /// The report of `structure` (the scene already read).
    pub fn report(&self, structure: &Structure) -> Result<StaticsReport, CoreError> {
        statics_report(structure, &self.request())
    }
}

/// Runs `statics`: reads the scene, one report (with the linear response when asked or
/// driven by a support's `displacement`, [`with_response`]).
pub fn statics(command: &StaticsCommand) -> Result<StaticsReport, SceneError> {
    let scene = command.source()?.load()?;
    refuse_unread_keys(&scene)?;
    let mut report = command.report(&scene.structure).map_err(refused)?;
    with_response(command, &scene, &mut report)?;
    Ok(report)
}

/// A statics error as the scene's: a clustered string the chosen back-end does not model
/// (`cluster 0: the sparse QR back-end …`) is bad input naming the cluster, as the
/// linear response's missing properties are ([`with_response`]); any other error keeps its
/// own category.
fn refused(e: CoreError) -> SceneError {
    match e {
        CoreError::Model(m @ ModelError::InvalidCluster { .. }) => {
            let item = m.item().unwrap_or_else(|| "scene".into());
            SceneError::InvalidParameter(InvalidParameter::text("scene", item, m.to_string()))
        }
        e => SceneError::Core(e),
    }
}

/// Refuses what `statics` does not read: a rest-length change (a load path's driver, `solve`
/// only) and the elastic models' keys.
fn refuse_unread_keys(scene: &Scene) -> Result<(), SceneError> {
    crate::scene::refuse_rest_length_changes(scene, "statics")?;
    crate::simulate::elastic::refuse_elastic_keys(scene, "statics")?;
    Ok(())
}

/// Whether the report carries the linear response: asked (`response`), or driven by a
/// support's prescribed `displacement`.
pub fn wants_response(command: &StaticsCommand, scene: &Scene) -> bool {
    command.response
        || scene
            .file
            .support_displacements()
            .iter()
            .any(Option::is_some)
}

/// Adds the linear response ([`tensegrity_statics::response::linear_response`]) to `report`
/// when [`wants_response`]: the supports' `displacement` prescribed. An error the core
/// files as bad input (a member without an axial stiffness, a displacement off the held
/// directions) is refused as the scene's, naming the item.
///
/// ```
/// use tensegrity_core::request::Request;
/// use tensegrity_engine::statics::{statics, StaticsCommand};
/// let c = StaticsCommand::from_values([("scene", serde_json::json!("../../examples/prescribed_displacement.toml"))])?;
/// let r = statics(&c)?.linear_response.unwrap();
/// // the top support raised 0.1 m: node 1 rises EA_b / (EA_a + EA_b) of it
/// assert!((r.displacements[1][2] - 0.075).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn with_response(
    command: &StaticsCommand,
    scene: &Scene,
    report: &mut StaticsReport,
) -> Result<(), SceneError> {
    if !wants_response(command, scene) {
        return Ok(());
    }
    let displacements: Vec<_> = (scene.file.support_displacements().into_iter())
        .map(|d| d.map(nalgebra::Vector3::from))
        .collect();
    let response = tensegrity_statics::response::linear_response(&scene.structure, &displacements)
        .map_err(|e| match e {
            CoreError::Model(m) if m.category() == Category::Input => {
                let item = match &m {
                    ModelError::MissingProperty { member, .. } => Some(member.to_string()),
                    other => other.item(),
                };
                let item = item.unwrap_or_else(|| "scene".into());
                SceneError::InvalidParameter(InvalidParameter::text("scene", item, m.to_string()))
            }
            e => SceneError::Core(e),
        })?;
    report.linear_response = Some(response);
    Ok(())
}

/// Runs `statics` in a sweep's (or another front end's) [`Context`]: as [`statics`], with the
/// context's limits checked again by the sparse path once its rank is known, so a case the
/// estimate before the run let through is refused before its bases are allocated.
pub fn statics_in(command: &StaticsCommand, ctx: &Context) -> Result<StaticsReport, SceneError> {
    let scene = command.source()?.load()?;
    refuse_unread_keys(&scene)?;
    let request = command.request_within(ctx.limits());
    let mut report = statics_report(&scene.structure, &request).map_err(refused)?;
    with_response(command, &scene, &mut report)?;
    Ok(report)
}

/// Runs `statics` under a front end's check of its estimate: reads the scene, hands the
/// estimate ([`estimate`]) to `admit` (a front end's limits: an error refuses the run, the
/// value it returns — a progress indicator — lives while the statics run), one report. The
/// scene comes back with the report (its member names label a readable report).
///
/// ```
/// use tensegrity_core::request::Request;
/// use tensegrity_engine::statics::{admitted, StaticsCommand};
/// use tensegrity_engine::SceneError;
/// let c = StaticsCommand::from_values([("scene", serde_json::json!("../../examples/prism.toml"))])?;
/// let (scene, r) = admitted(&c, None, |e| Ok::<_, SceneError>(assert!(e.unwrap().work_s < 1e-3)))?;
/// assert_eq!((scene.structure.n_bars(), r.self_stress_dim), (3, 1));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn admitted<G, E: From<SceneError>>(
    command: &StaticsCommand,
    limits: Option<&Limits>,
    admit: impl FnOnce(Option<Estimate>) -> Result<G, E>,
) -> Result<(Scene, StaticsReport), E> {
    let scene = command.source().map_err(SceneError::from)?;
    let scene = scene.load().map_err(SceneError::from)?;
    refuse_unread_keys(&scene)?;
    let asked = StaticsCommand {
        response: wants_response(command, &scene),
        ..command.clone()
    };
    let _admitted = admit(estimate(&scene.structure, &asked))?;
    let request = command.request_within(limits);
    let mut report = statics_report(&scene.structure, &request).map_err(refused)?;
    with_response(command, &scene, &mut report)?;
    Ok((scene, report))
}

/// The resource estimate of the statics of `structure` (module docs): the dense SVD when the
/// method takes the dense path, else the sparse QR's memory.
///
/// ```
/// use tensegrity_core::test_models::oscillating_prism;
/// use tensegrity_engine::statics::{estimate, StaticsCommand};
/// let e = estimate(&oscillating_prism().unwrap(), &StaticsCommand::default()).unwrap();
/// assert!(e.work_s < 1e-3 && e.parameters.to_string().starts_with("method = auto"));
/// ```
pub fn estimate(structure: &Structure, command: &StaticsCommand) -> Option<Estimate> {
    let statics = statics_estimate(structure, command);
    if !command.response {
        return statics;
    }
    let response = response_estimate(structure);
    Some(match statics {
        Some(s) => s.then(response),
        None => response,
    })
}

/// The estimate of the linear response ([`with_response`]): the dense tangent stiffness on
/// the m free coordinates and its symmetric eigendecomposition, 3 m² numbers held and about
/// 9 m³ flops at [`budget::DENSE_FLOP_RATE`].
///
/// ```
/// use tensegrity_core::test_models::oscillating_prism;
/// use tensegrity_engine::statics::response_estimate;
/// let e = response_estimate(&oscillating_prism().unwrap());
/// assert!(e.work_s < 1e-3 && e.what.contains("linear response"));
/// ```
pub fn response_estimate(structure: &Structure) -> Estimate {
    let m = DofMap::stiffness_of(structure).len();
    let mf = m as f64;
    Estimate::new(
        format!("the linear response (the eigendecomposition of the {m} × {m} tangent stiffness)"),
        format!("response ({} nodes)", structure.n_nodes()),
    )
    .memory(24.0 * mf * mf)
    .work(budget::DENSE_OVERHEAD * 9.0 * mf * mf * mf / budget::DENSE_FLOP_RATE)
}

/// The estimate of the statics without the linear response (module docs).
fn statics_estimate(structure: &Structure, command: &StaticsCommand) -> Option<Estimate> {
    // the columns of the equilibrium matrix: members, then clustered strings
    let (dofs, members) = (DofMap::of(structure).len(), n_columns(structure));
    let dense = match command.method {
        StaticsMethod::Dense => true,
        StaticsMethod::Sparse => false,
        StaticsMethod::Auto => dofs.min(members) < SPARSE_MIN_SIZE,
    };
    let method = serde_json::to_value(command.method).unwrap_or_default();
    let parameter = format!(
        "method = {} ({} nodes, {members} members)",
        method.as_str().unwrap_or("auto"),
        structure.n_nodes()
    );
    if dense {
        return Some(budget::dense_statics(dofs, members, parameter));
    }
    // a wide unloaded structure (a lattice) takes the nested-dissection path (never one with
    // clusters, which the nested dissection does not model)
    let nested = command.method == StaticsMethod::Auto && !structure.has_clusters();
    if nested && tensegrity_statics::nested::prefers_nested(structure) {
        return tensegrity_statics::nested::nested_estimate(structure, parameter).ok();
    }
    // a large unloaded structure of narrow band (a tower) takes the nested dissection of A
    // itself first; the banded QR it may still choose checks its own bound and budget
    if nested && tensegrity_statics::nested::prefers_nested_members(structure) {
        return tensegrity_statics::nested::nested_members_estimate(structure, parameter).ok();
    }
    // the sparse QR within its profile (a bound of what the factorisation stores), its work
    // (QR_FLOPS_PER_ENTRY a profile entry), then the stages after it at the generic rank
    // min(dofs, members); a structure with more self-stresses is checked again by the core
    // once its rank is known (`StaticsSettings::work_limit`, the memory limit)
    let profile = tensegrity_statics::sparse_statics_bytes(structure).unwrap_or(0.0);
    let after = sparse_after_qr(dofs, members, dofs.min(members), 0);
    let qr_work = QR_FLOPS_PER_ENTRY * (profile / 8.0) / SPARSE_FLOP_RATE;
    Some(
        Estimate::new(
            format!("the sparse statics (QR of the {dofs} × {members} equilibrium matrix)"),
            parameter,
        )
        .memory(profile + after.memory_bytes)
        .work(qr_work + after.work_s),
    )
}

/// Flops of the sparse QR per entry of its profile (the column updates by the reflectors that
/// reach it), calibrated on chains of 3,000 and 6,000 nodes (0.48 s and 0.94 s measured,
/// test profile: 26 and 13 flops an entry at [`SPARSE_FLOP_RATE`]).
pub const QR_FLOPS_PER_ENTRY: f64 = 40.0;

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    #[test]
    fn the_request_describes_its_fields_and_refuses_a_tolerance_of_one() {
        check_description::<StaticsCommand>().unwrap();
        let c = StaticsCommand::from_values([
            ("scene", json!("a.toml")),
            ("method", json!("sparse")),
            ("mass", json!("consistent")),
            ("modes", json!(3)),
        ])
        .unwrap();
        assert_eq!(c.method, StaticsMethod::Sparse);
        assert_eq!((c.mass, c.modes), (MassModel::Consistent, Some(3)));
        assert_eq!(c.source().unwrap(), &SceneSource::Path("a.toml".into()));
        let scene = ("scene", json!("a.toml"));
        let e = StaticsCommand::from_values([scene.clone(), ("rank_tol", json!(1.0))]);
        assert_eq!(e.unwrap_err().name, "rank_tol");
        let e = StaticsCommand::from_values([scene, ("method", json!("qr"))]).unwrap_err();
        assert_eq!(e.name, "method");
        // the scene is required
        assert!(StaticsCommand::default().validate().is_err());
    }

    #[test]
    fn the_dense_estimate_follows_the_method() {
        let s = tensegrity_core::test_models::oscillating_prism().unwrap();
        let auto = StaticsCommand::default();
        // the dense SVD of the free dofs × members, its memory
        let e = estimate(&s, &auto).unwrap();
        let m = DofMap::of(&s).len();
        assert_eq!(
            e.memory_bytes,
            tensegrity_statics::dense_statics_bytes(m, s.n_members())
        );
        let sparse = StaticsCommand {
            method: StaticsMethod::Sparse,
            ..auto
        };
        let e = estimate(&s, &sparse).unwrap();
        assert!(e.memory_bytes > 0.0 && e.what.contains("sparse"), "{e:?}");
    }
}
