//! The report of a form-finding run ([`find`]): the form found by [`form_find`], the statics
//! of its self-stress, and the structure that realises it at a prestress level
//! ([`synthesize_with`], from the string rest lengths computed once).
//!
//! At the prestress level P (the largest string tension) the member forces are
//! T_k = α q_k L_k with α = P / max_strings(q_k L_k), and each string's rest length is
//! s0 = L / (1 + T / EA) (see [`rest_lengths`]). The report also holds the equilibrium
//! residual ‖A q + p‖ / ‖q‖ of the found geometry (p the loads), its height (the z extent of
//! the nodes the method placed) and the longest bar; with fixed nodes the reactions and the
//! relative equilibrium residual of the free nodes, with loads the loads carried
//! ([`Loading`]). The statics of the self-stress (self-stress dimension, prestressability,
//! prestress stability) are in it only where [`Settings::analyse`] asks for them (`null`
//! otherwise, and then no warning about them); the synthesis needs none of them. A loaded form is not scaled to a prestress level: its force densities
//! balance loads in N, so T_k = q_k L_k (the `synth` module).

use crate::synth::{rest_lengths, synthesize_with, RestLengths};
use crate::{
    form_find, FormFindError, FormFound, Method, NodeForce, Result, Settings, Synthesis, Topology,
};
use serde::Serialize;
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::Structure;
use tensegrity_core::Warning;
use tensegrity_derive::Columns;

/// The report of a form-finding run (module docs). Member lists are bars then strings, in topology
/// order.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct FormfindReport {
    /// The built-in's name, the topology file, or `topology text`.
    pub source: String,
    /// Nodes.
    pub n_nodes: usize,
    /// Bars.
    pub n_bars: usize,
    /// Strings.
    pub n_strings: usize,
    /// The method that found the form.
    pub method: Method,
    /// One [x, y, z] per node (m).
    pub nodes: Vec<[f64; 3]>,
    /// Force density q per member (N/m, tension-positive), normalised by the method.
    pub force_density: Vec<f64>,
    /// Dimension of the self-stress space of the found geometry (`null` unless the form was
    /// analysed: `analyse`).
    pub self_stress_dim: Option<usize>,
    /// Whether a self-stress with strings in tension and bars in compression exists (for a
    /// loaded form: besides the stress that carries the loads, which a loaded form needs
    /// instead; no warning when it is false there; `null` unless analysed).
    pub prestressable: Option<bool>,
    /// Whether the prestressed structure is stable (`null` unless analysed).
    pub prestress_stable: Option<bool>,
    /// ‖A q + p‖ / ‖q‖ at the found geometry (p the loads, zero without; m).
    pub residual: f64,
    /// Iterations of the method (1 for a direct solve).
    pub iterations: usize,
    /// The convergence tolerance the iterative method stopped at (null for a direct solve;
    /// for dynamic relaxation at least the floor double precision reaches at the members'
    /// stiffness, see the `dr` module).
    pub tolerance: Option<f64>,
    /// The extent along z of the nodes the method placed (every node of a free-standing
    /// form, the free ones where nodes are held) (m).
    #[column(unit = "m")]
    pub height: f64,
    /// The longest bar (m; 0 without bars).
    #[column(unit = "m")]
    pub max_bar_length: f64,
    /// The prestress level of the exported structure: the largest string tension (N). For a
    /// loaded form the loads set the member forces (q L) and this is their largest string
    /// tension; the requested level is not applied.
    #[column(unit = "N")]
    pub prestress: f64,
    /// Member forces at that level (N, tension-positive), `null` where there is no scene.
    pub member_force: Option<Vec<f64>>,
    /// Rest length of each string of the exported structure (m), `null` where there is no
    /// scene.
    pub rest_length: Option<Vec<f64>>,
    /// The loads, the reactions, the equilibrium residual and the clusters, as top-level keys
    /// (`loads`, `reactions`, `equilibrium_residual`, `clusters`), each present only where it
    /// applies.
    #[serde(flatten)]
    #[column(skip)]
    pub loading: Loading,
    /// What the caller should know (a form that is not prestress-stable, no scene, …).
    pub warnings: Vec<Warning>,
}

/// One clustered string in a [`FormfindReport`] (the `cluster` and `synth` modules).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClusterReport {
    /// The nodes it passes through, in order.
    pub nodes: Vec<usize>,
    /// Its prescribed tension t (N), the same on every segment.
    pub force: f64,
    /// Its length L = Σ l_i in the found form (m).
    pub length: f64,
    /// The length l_i of each segment (m).
    pub segment_length: Vec<f64>,
    /// The force density t / l_i of each segment (N/m).
    pub segment_force_density: Vec<f64>,
    /// Its tension at the prestress level, α t (N; t for a loaded form), `null` where there
    /// is no scene.
    pub tension: Option<f64>,
    /// Its axial stiffness EA (N), `null` where there is no scene.
    pub axial_stiffness: Option<f64>,
    /// Its stiffness k = EA / L₀ (N/m, the scene's), `null` where there is no scene.
    pub stiffness: Option<f64>,
    /// Its whole rest length L₀ = L / (1 + α t / EA) = L − α t / k (m), `null` where there
    /// is no scene.
    pub rest_length: Option<f64>,
}

/// The loads a form carries, the reactions that balance them and its clustered strings (keys
/// of [`FormfindReport`], flattened into it; each present only where it applies).
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Loading {
    /// The loads on the nodes (N), one per loaded node in node order: point loads summed per
    /// node plus the lumped self-weight at the found lengths; absent without loads.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<NodeForce>,
    /// The reaction at each fixed node, r_i = (D X)_i − p_i (N, in the `fixed` order), so
    /// that Σ r + Σ p = 0; absent without fixed nodes. In the units of `force_density` × m:
    /// physical where the force densities are (the force density method), relative where a
    /// method normalises them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub reactions: Vec<NodeForce>,
    /// ‖(D X)_f − P_f‖ / ‖F_f‖ at the free nodes, F_i = Σ_k∋i |q_k| L_k + ‖p_i‖ (relative);
    /// absent without fixed nodes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equilibrium_residual: Option<f64>,
    /// Each clustered string (absent without): its prescribed tension, the found lengths and
    /// segment force densities, and its rest length at the prestress level.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub clusters: Vec<ClusterReport>,
}

/// Everything a `formfind` run makes: the topology, the found form, the structure realising
/// its prestress (when it can be synthesised) and the report.
#[derive(Debug, Clone)]
pub struct Formfound {
    /// The topology found.
    pub topology: Topology,
    /// The library's result.
    pub found: FormFound,
    /// The prestressed structure (`None` where the synthesis failed: the report says why).
    pub structure: Option<Structure>,
    /// The report.
    pub report: FormfindReport,
}

/// Finds the form of `topology` (`source`: its label in the report) and synthesises the
/// prestressed structure; a synthesis that fails for the form (no string in tension) leaves
/// `structure` unset and says why in the report's warnings, one that fails for a prestress
/// or stiffness out of range (an overflow, a strain below precision) is the error.
pub fn find(
    topology: Topology,
    source: String,
    settings: &Settings,
    synthesis: &Synthesis,
) -> Result<Formfound> {
    let found = form_find(&topology, settings)?;
    let mut warnings: Vec<Warning> = found
        .choice
        .iter()
        .map(|reason| Warning::MethodChosen {
            reason: reason.clone(),
        })
        .collect();
    // a loaded form is stressed by its loads and needs no self-stress; nothing is said of a
    // form that was not analysed (the statics were not asked for)
    if found.prestressable == Some(false) && !topology.is_loaded() {
        warnings.push(Warning::NotPrestressable);
    } else if found.prestress_stable == Some(false) {
        warnings.push(Warning::NotPrestressStable);
    }
    // the rest lengths once: the structure is built from them
    let synthesised = rest_lengths(&topology, &found, synthesis)
        .and_then(|r| Ok((synthesize_with(&topology, &found, synthesis, &r)?, r)));
    let (structure, rest) = match synthesised {
        Ok((s, r)) => (Some(s), Some(r)),
        // a prestress or stiffness out of range (an overflow, a strain below precision) is
        // the caller's input, refused; a form that cannot be prestressed is reported
        Err(e @ (FormFindError::InvalidParameter(_) | FormFindError::InvalidTopology { .. })) => {
            return Err(e)
        }
        Err(e) => {
            warnings.push(Warning::NoPrestressedStructure {
                reason: e.to_string(),
            });
            (None, None)
        }
    };
    let report = FormfindReport {
        source,
        n_nodes: topology.n_nodes,
        n_bars: topology.bars.len(),
        n_strings: topology.strings.len(),
        method: found.method,
        nodes: found.node_rows(),
        force_density: found.force_density.clone(),
        self_stress_dim: found.self_stress_dim,
        prestressable: found.prestressable,
        prestress_stable: found.prestress_stable,
        residual: found.residual,
        iterations: found.iterations,
        tolerance: found.tolerance,
        height: extent_z(&topology, &found),
        max_bar_length: topology
            .bars
            .iter()
            .map(|b| (found.nodes[b.nodes[1]] - found.nodes[b.nodes[0]]).norm())
            .fold(0.0, f64::max),
        prestress: if topology.is_loaded() {
            loaded_prestress(&topology, &found)
        } else {
            synthesis.prestress
        },
        member_force: rest.as_ref().map(|r| r.tension.clone()),
        rest_length: rest.as_ref().map(|r| r.rest_length.clone()),
        loading: Loading {
            loads: found.loads.clone(),
            reactions: found.reactions.clone(),
            equilibrium_residual: found.equilibrium_residual,
            clusters: cluster_reports(&found, rest.as_ref()),
        },
        warnings,
    };
    Ok(Formfound {
        topology,
        found,
        structure,
        report,
    })
}

/// Multiplies the force density of group `name` (the group's own and its members') by
/// `ratio`; an unknown group, or one without a force density, is refused naming `group`.
pub fn scale_group(
    topology: &mut Topology,
    name: &str,
    ratio: f64,
) -> Result<(), InvalidParameter> {
    let Some(group) = topology.groups.get_mut(name) else {
        let known: Vec<&str> = topology.groups.keys().map(String::as_str).collect();
        let reason = format!(
            "no such group in the topology (groups: {})",
            known.join(", ")
        );
        return Err(InvalidParameter::text("group", name, reason));
    };
    let mut scaled = false;
    if let Some(q) = &mut group.force_density {
        *q *= ratio;
        scaled = true;
    }
    for m in topology.bars.iter_mut().chain(topology.strings.iter_mut()) {
        if let (Some(q), Some(g)) = (&mut m.force_density, &m.group) {
            if g == name {
                *q *= ratio;
                scaled = true;
            }
        }
    }
    if !scaled {
        let reason = "the group has no force density to scale";
        return Err(InvalidParameter::text("group", name, reason));
    }
    Ok(())
}

/// The largest string tension q L of a loaded form, a cluster's tension included (N; 0
/// without strings): the loads set it.
fn loaded_prestress(topology: &Topology, found: &FormFound) -> f64 {
    let nb = topology.bars.len();
    topology
        .strings
        .iter()
        .zip(&found.force_density[nb..])
        .map(|(m, q)| q * (found.nodes[m.nodes[1]] - found.nodes[m.nodes[0]]).norm())
        .chain(found.clusters.iter().map(|c| c.tension))
        .fold(0.0, f64::max)
}

/// The report's clusters: the found state, with the rest lengths where there is a scene.
fn cluster_reports(found: &FormFound, rest: Option<&RestLengths>) -> Vec<ClusterReport> {
    let rest = |c: usize| rest.and_then(|r| r.clusters.get(c));
    let report = |(c, s): (usize, &crate::ClusterState)| ClusterReport {
        nodes: s.nodes.clone(),
        force: s.tension,
        length: s.length,
        segment_length: s.segment_length.clone(),
        segment_force_density: s.segment_force_density.clone(),
        tension: rest(c).map(|r| r.tension),
        axial_stiffness: rest(c).map(|r| r.axial_stiffness),
        stiffness: rest(c).map(|r| r.stiffness),
        rest_length: rest(c).map(|r| r.rest_length),
    };
    found.clusters.iter().enumerate().map(report).collect()
}

/// The extent along z of the nodes that are not held.
fn extent_z(topology: &Topology, found: &FormFound) -> f64 {
    let mut held = vec![false; found.nodes.len()];
    for f in &topology.fixed {
        held[f.node] = true;
    }
    let z = (0..found.nodes.len())
        .filter(|&i| !held[i])
        .map(|i| found.nodes[i].z);
    z.clone().fold(f64::NEG_INFINITY, f64::max) - z.fold(f64::INFINITY, f64::min)
}
