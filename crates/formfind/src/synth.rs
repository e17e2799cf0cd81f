//! Rest-length synthesis: from a found form (nodes, force densities q) to a structure in
//! equilibrium at t = 0.
//!
//! The self-stress is scaled by α = P / max_s(q_s L_s) so that the largest string tension is
//! the prestress level P (N); member k then carries T_k = α q_k L_k. With axial stiffness
//! EA_k (N) the rest length solving T = EA (L − s0)/s0 is
//!
//! s0 = L / (1 + T / EA),
//!
//! and the core's string law γ = k (1 − s0/‖s‖) with the spring constant k = EA / s0 (N/m)
//! gives γ = T / L = α q at t = 0, exactly the scaled force density. Bars are rigid in the
//! core's dynamics: they keep their found length and carry mass `bar_mass`; their rest
//! length s0 (for an elastic bar, or dynamic relaxation) is reported by [`rest_lengths`].

use crate::error::{FormFindError, Result};
use crate::method::Synthesis;
use crate::result::FormFound;
use crate::topology::Topology;
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::{Bar, StringMember, Structure, Support};

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
}

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
    let mut max_tension = 0.0f64;
    for k in nb..pairs.len() {
        let q = found.force_density[k];
        if q.is_nan() || q <= 0.0 {
            return Err(FormFindError::NoPrestress {
                reason: format!(
                    "{} has force density {q}: a string must be in tension",
                    topology.member_name(k)
                ),
            });
        }
        max_tension = max_tension.max(q * lengths[k]);
    }
    if max_tension <= 0.0 {
        return Err(FormFindError::NoPrestress {
            reason: "no string carries tension".into(),
        });
    }
    let scale = synthesis.prestress / max_tension;
    let mut out = RestLengths {
        scale,
        tension: Vec::with_capacity(pairs.len()),
        stiffness: Vec::with_capacity(pairs.len()),
        rest_length: Vec::with_capacity(pairs.len()),
    };
    for (k, m) in topology.members().enumerate() {
        let t = scale * found.force_density[k] * lengths[k];
        let ea = m.stiffness.unwrap_or(synthesis.stiffness);
        if t <= -ea {
            return Err(FormFindError::InvalidParameter(InvalidParameter::new(
                "prestress",
                synthesis.prestress,
                format!(
                    "{} would carry a compression of {:.3e} N, beyond its stiffness EA = \
                     {ea:.3e} N",
                    topology.member_name(k),
                    -t
                ),
            )));
        }
        out.tension.push(t);
        out.stiffness.push(ea);
        out.rest_length.push(lengths[k] / (1.0 + t / ea));
    }
    Ok(out)
}

/// The structure realising `found` (see the module docs): nodes at the found positions,
/// bars of mass `bar_mass`, strings with rest length s0 and spring constant EA/s0, fixed
/// nodes pinned.
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
    for f in &topology.fixed {
        b = b.support(Support::pinned(f.node));
    }
    Ok(b.build()?)
}
