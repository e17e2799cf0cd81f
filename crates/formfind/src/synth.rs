//! Rest-length synthesis: from a found form (nodes, force densities q) to a structure in
//! equilibrium at t = 0.
//!
//! The self-stress is scaled by α = P / max_s(q_s L_s) so that the largest string tension is
//! the prestress level P (N); member k then carries T_k = α q_k L_k. A loaded form (point
//! loads or weights, the `fdm` module) is not scaled: its force densities balance loads given
//! in N, so T_k = q_k L_k and the prestress level is not applied (the largest string tension
//! follows from the loads); its structure carries the loads (point loads plus the lumped
//! self-weight) on its nodes, so the written scene is in equilibrium under them. With axial stiffness
//! EA_k (N) the rest length solving T = EA (L − s0)/s0 is
//!
//! s0 = L / (1 + T / EA),
//!
//! and the core's string law γ = k (1 − s0/‖s‖) with the spring constant k = EA / s0 (N/m)
//! gives γ = T / L = α q at t = 0, exactly the scaled force density. Bars are rigid in the
//! core's dynamics: they keep their found length and carry mass `bar_mass`; their rest
//! length s0 (for an elastic bar, or dynamic relaxation) is reported by [`rest_lengths`].
//!
//! A clustered string (the `cluster` module) carries α t (t its prescribed tension, counted
//! among the string tensions for α) along its whole length L = Σ l_i; with axial stiffness EA
//! its whole rest length is L₀ = L / (1 + α t / EA) and the core's cluster is written with
//! rest length L₀ and stiffness k = EA / L₀ (N/m), so that k (L − L₀) = α t at t = 0
//! ([`ClusterRest`]).
//!
//! **Precision.** A string's tension in the written structure is k (L − s0) with
//! L − s0 = L · (T/EA)/(1 + T/EA), a difference of two lengths that double precision holds
//! to about ε L: the tension keeps a relative accuracy of about ε / (T/EA). A string whose
//! strain T/EA is below [`MIN_STRAIN`] (10⁻⁴ of its tension lost to rounding; EA/T above
//! about 4.5·10¹¹) is refused naming it and the stiffness, and so is a prestress or stiffness
//! whose numbers overflow; nothing non-finite is ever returned. The scale α is computed for
//! q / max|q| (the same α q), so force densities near the largest double do not overflow it.

use crate::error::{FormFindError, Result};
use crate::method::Synthesis;
use crate::result::FormFound;
use crate::topology::Topology;
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::{Bar, Cluster, StringMember, Structure, Support};

/// The rest lengths realising a found form at a prestress level (bars then strings).
#[derive(Debug, Clone, PartialEq)]
pub struct RestLengths {
    /// The scale α applied to the force densities (1/m · m = N per unit q·L).
    pub scale: f64,
    /// Member tension T = α q L (N; negative in bars).
    pub tension: Vec<f64>,
    /// Axial stiffness EA of each member (N).
    pub stiffness: Vec<f64>,
    /// Rest length s0 = L / (1 + T/EA) of each member (m).
    pub rest_length: Vec<f64>,
    /// Each cluster's (the `cluster` module): its tension, stiffness and whole rest length.
    pub clusters: Vec<ClusterRest>,
}

/// The rest length of a clustered string realising its tension (the `cluster` module docs).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ClusterRest {
    /// Its tension at the prestress level, α t (N).
    pub tension: f64,
    /// Its length L = Σ l_i in the found form (m).
    pub length: f64,
    /// Its axial stiffness EA (N).
    pub axial_stiffness: f64,
    /// Its stiffness k = EA / L₀ as a whole (N/m): the written scene's `stiffness`.
    pub stiffness: f64,
    /// Its whole rest length L₀ = L / (1 + α t / EA) = L − α t / k (m).
    pub rest_length: f64,
}

/// The smallest strain T/EA of a synthesised string: below it rounding loses more than 10⁻⁴
/// of its tension (ε / 10⁻⁴; module docs).
pub const MIN_STRAIN: f64 = f64::EPSILON * 1e4;

fn check(name: &'static str, v: f64) -> Result<()> {
    if !(v.is_finite() && v > 0.0) {
        return Err(InvalidParameter::new(name, v, "must be finite and positive").into());
    }
    Ok(())
}

/// The rest lengths of every member for `found` at the prestress and stiffness of
/// `synthesis` (a member's own `stiffness` wins over `synthesis.stiffness`).
pub fn rest_lengths(
    topology: &Topology,
    found: &FormFound,
    synthesis: &Synthesis,
) -> Result<RestLengths> {
    check("prestress", synthesis.prestress)?;
    check("stiffness", synthesis.stiffness)?;
    if found.nodes.len() != topology.n_nodes || found.force_density.len() != topology.n_members() {
        return Err(FormFindError::InvalidTopology {
            item: "form".into(),
            reason: "the found form does not belong to this topology".into(),
        });
    }
    let pairs = topology.member_nodes();
    let lengths: Vec<f64> = pairs
        .iter()
        .map(|&[i, j]| (found.nodes[j] - found.nodes[i]).norm())
        .collect();
    let nb = topology.bars.len();
    if found.clusters.len() != topology.clusters.len() {
        return Err(FormFindError::InvalidTopology {
            item: "form".into(),
            reason: "the found form does not belong to this topology (its clusters)".into(),
        });
    }
    let segment_q = found.clusters.iter().flat_map(|c| &c.segment_force_density);
    let qmax = found
        .force_density
        .iter()
        .chain(segment_q)
        .fold(0.0f64, |a, q| a.max(q.abs()));
    let q: Vec<f64> = found
        .force_density
        .iter()
        .map(|x| x / qmax.max(f64::MIN_POSITIVE))
        .collect();
    let loaded = topology.is_loaded();
    let mut max_tension = 0.0f64;
    for k in nb..pairs.len() {
        if q[k].is_nan() || q[k] <= 0.0 {
            return Err(FormFindError::NoPrestress {
                reason: format!(
                    "{} has force density {}: a string must be in tension",
                    topology.member_name(k),
                    found.force_density[k]
                ),
            });
        }
        max_tension = max_tension.max(q[k] * lengths[k]);
    }
    // a cluster's tension, in the units of q / max|q| as the members' q L
    let unit = |t: f64| t / qmax.max(f64::MIN_POSITIVE);
    for c in &found.clusters {
        max_tension = max_tension.max(unit(c.tension));
    }
    if max_tension <= 0.0 && !loaded {
        return Err(FormFindError::NoPrestress {
            reason: "no string carries tension".into(),
        });
    }
    // the loads fix the forces: T = q L in N (the prestress level is not applied)
    let scale = if loaded {
        qmax
    } else {
        synthesis.prestress / max_tension
    };
    let mut out = RestLengths {
        scale: scale / qmax,
        tension: Vec::with_capacity(pairs.len()),
        stiffness: Vec::with_capacity(pairs.len()),
        rest_length: Vec::with_capacity(pairs.len()),
        clusters: Vec::with_capacity(found.clusters.len()),
    };
    for (k, m) in topology.members().enumerate() {
        let t = scale * q[k] * lengths[k];
        let ea = m.stiffness.unwrap_or(synthesis.stiffness);
        let s0 = lengths[k] / (1.0 + t / ea);
        check_member(topology, k, synthesis, (t, ea, s0))?;
        out.tension.push(t);
        out.stiffness.push(ea);
        out.rest_length.push(s0);
    }
    for (c, (spec, state)) in topology.clusters.iter().zip(&found.clusters).enumerate() {
        let t = scale * unit(state.tension);
        let ea = spec.axial_stiffness(synthesis.stiffness);
        let l0 = state.length / (1.0 + t / ea);
        check_cluster(c, spec, synthesis, (t, ea, l0))?;
        out.clusters.push(ClusterRest {
            tension: t,
            length: state.length,
            axial_stiffness: ea,
            stiffness: ea / l0,
            rest_length: l0,
        });
    }
    Ok(out)
}

/// Cluster c's tension `t`, stiffness `ea` and rest length `l0` in range, as
/// [`check_member`] checks a string's: the error names the prestress or the stiffness (the
/// cluster's own, else the synthesis').
fn check_cluster(
    c: usize,
    spec: &crate::ClusterString,
    synthesis: &Synthesis,
    (t, ea, l0): (f64, f64, f64),
) -> Result<()> {
    let name = format!("clusters[{c}]");
    let stiffness = |reason: String| -> FormFindError {
        match (spec.stiffness, spec.area) {
            (Some(v), _) => FormFindError::InvalidTopology {
                item: format!("{name}.stiffness"),
                reason: format!("{v:e} N: {reason}"),
            },
            (None, Some(a)) => FormFindError::InvalidTopology {
                item: format!("{name}.area"),
                reason: format!("{a:e} m² (EA = {ea:e} N): {reason}"),
            },
            _ => InvalidParameter::new("stiffness", synthesis.stiffness, reason).into(),
        }
    };
    if !t.is_finite() {
        let reason = format!("{name}'s tension overflows (lower the prestress)");
        return Err(InvalidParameter::new("prestress", synthesis.prestress, reason).into());
    }
    if t / ea < MIN_STRAIN {
        return Err(stiffness(format!(
            "{name} would stretch by T/EA = {:.2e} under its {t:.3e} N, below the \
             {MIN_STRAIN:.1e} double precision keeps its tension to 10⁻⁴ with: lower the \
             stiffness (at most {:.3e} N) or raise the prestress",
            t / ea,
            t / MIN_STRAIN
        )));
    }
    if !(l0.is_finite() && l0 > 0.0 && (ea / l0).is_finite()) {
        return Err(stiffness(format!(
            "{name}'s rest length {l0:e} m or stiffness EA/L₀ is out of the range of a double"
        )));
    }
    Ok(())
}

/// Member k's tension `t`, stiffness `ea` and rest length `s0` in range (module docs): the
/// error names the prestress or the stiffness (the member's own, else the synthesis') and
/// the member.
fn check_member(
    topology: &Topology,
    k: usize,
    synthesis: &Synthesis,
    (t, ea, s0): (f64, f64, f64),
) -> Result<()> {
    let name = topology.member_name(k);
    let stiffness = |reason: String| -> FormFindError {
        let own = topology.members().nth(k).and_then(|m| m.stiffness);
        match own {
            Some(v) => FormFindError::InvalidTopology {
                item: format!("{name}.stiffness"),
                reason: format!("{v:e} N: {reason}"),
            },
            None => InvalidParameter::new("stiffness", synthesis.stiffness, reason).into(),
        }
    };
    if !t.is_finite() {
        let reason = format!("{name}'s tension overflows (lower the prestress)");
        return Err(InvalidParameter::new("prestress", synthesis.prestress, reason).into());
    }
    if t <= -ea {
        return Err(FormFindError::InvalidParameter(InvalidParameter::new(
            "prestress",
            synthesis.prestress,
            format!(
                "{name} would carry a compression of {:.3e} N, beyond its stiffness EA = \
                 {ea:.3e} N",
                -t
            ),
        )));
    }
    if !topology.is_bar(k) && t / ea < MIN_STRAIN {
        return Err(stiffness(format!(
            "{name} would stretch by T/EA = {:.2e} under its {t:.3e} N, below the {MIN_STRAIN:.1e} \
             double precision keeps its tension to 10⁻⁴ with: lower the stiffness (at most \
             {:.3e} N) or raise the prestress",
            t / ea,
            t / MIN_STRAIN
        )));
    }
    if !(s0.is_finite() && s0 > 0.0 && (ea / s0).is_finite()) {
        return Err(stiffness(format!(
            "{name}'s rest length {s0:e} m or spring constant EA/s0 is out of the range of a \
             double"
        )));
    }
    Ok(())
}

/// The structure realising `found` (see the module docs): nodes at the found positions,
/// bars of mass `bar_mass`, strings with rest length s0 and spring constant EA/s0, fixed
/// nodes pinned, the form's loads (if any) on their nodes.
pub fn synthesize(
    topology: &Topology,
    found: &FormFound,
    synthesis: &Synthesis,
) -> Result<Structure> {
    check("bar_mass", synthesis.bar_mass)?;
    let r = rest_lengths(topology, found, synthesis)?;
    synthesize_with(topology, found, synthesis, &r)
}

/// [`synthesize`] from rest lengths already computed by [`rest_lengths`] for the same
/// topology, form and synthesis (a caller that reports them computes them once).
pub fn synthesize_with(
    topology: &Topology,
    found: &FormFound,
    synthesis: &Synthesis,
    r: &RestLengths,
) -> Result<Structure> {
    check("bar_mass", synthesis.bar_mass)?;
    let nb = topology.bars.len();
    let mut b = Structure::builder()
        .allow_isolated_nodes(!topology.fixed.is_empty())
        .nodes(found.nodes.iter().map(|p| [p.x, p.y, p.z]));
    for m in &topology.bars {
        b = b.bar(Bar::new(m.nodes[0], m.nodes[1]).mass(synthesis.bar_mass));
    }
    for (j, m) in topology.strings.iter().enumerate() {
        let (s0, ea) = (r.rest_length[nb + j], r.stiffness[nb + j]);
        b = b.string(
            StringMember::new(m.nodes[0], m.nodes[1])
                .rest_length(s0)
                .stiffness(ea / s0),
        );
    }
    for (spec, rest) in topology.clusters.iter().zip(&r.clusters) {
        let mut c = Cluster::new(spec.nodes.iter().copied())
            .rest_length(rest.rest_length)
            .stiffness(rest.stiffness);
        if let Some(m) = &spec.material {
            c = c.material(m);
        }
        b = b.cluster(c);
    }
    for f in &topology.fixed {
        b = b.support(Support::pinned(f.node));
    }
    for l in &found.loads {
        b = b.load(l.node, l.force);
    }
    Ok(b.build()?)
}
