//! One complete analysis, as the CLI prints it (text or JSON); the truss is built once and
//! returned with the report ([`MichellAnalysis`]).
//!
//! Build the truss, apply the tip load w₀[cos φ_w sin γ, sin φ_w sin γ, cos γ], propagate the
//! forces (recursive or global), optionally add prestressed extra strings, classify and size
//! every member for one material, and collect the masses.

use crate::error::Result;
use crate::extra_strings::{solve_prestressed, ExtraStrings};
use crate::loads::{tip_load, NodalLoads};
use crate::params::MichellParams;
use crate::propagation::{propagate, Method};
use crate::sizing::{normalized_yield_mass, size_members, MemberKind, TrussSizing};
use crate::truss::MichellTruss;
use serde::Serialize;
use tensegrity_core::MaterialTable;
use tensegrity_derive::Columns;
use tensegrity_statics::sizing::Governing;

/// Everything one analysis needs.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalysisRequest {
    /// Truss parameters.
    pub params: MichellParams,
    /// Tip load magnitude w₀ (N).
    pub load: f64,
    /// Load azimuth φ_w (rad).
    pub azimuth: f64,
    /// Load polar angle γ (rad).
    pub polar: f64,
    /// Material of bars and strings (a `tensegrity_core` built-in name, e.g. `steel`).
    pub material: String,
    /// Extra strings with this prestress (N), if any.
    pub extra_strings: Option<f64>,
    /// Solver.
    pub method: Method,
}

impl AnalysisRequest {
    /// A request with the defaults: w₀ = 1000 N along −ι̂₃ (φ_w = 0, γ = π), steel, recursive,
    /// no extra strings.
    pub fn new(params: MichellParams) -> Self {
        Self {
            params,
            load: 1000.0,
            azimuth: 0.0,
            polar: std::f64::consts::PI,
            material: "steel".to_string(),
            extra_strings: None,
            method: Method::Recursive,
        }
    }
}

/// A node in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NodeReport {
    /// `[U, D, L, R]`, or `[i, k]` for a planar truss.
    pub index: Vec<usize>,
    /// Position (m).
    pub position: [f64; 3],
    /// Whether it is a (level-q) support.
    pub support: bool,
}

/// A member in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MemberReport {
    /// Parent tuple (for an extra string: its first node).
    pub parent: Vec<usize>,
    /// Child tuple (for an extra string: its second node).
    pub child: Vec<usize>,
    /// Length (m).
    pub length: f64,
    /// Tension-positive force density q (N/m).
    pub force_density: f64,
    /// Axial force q·l (N, tension positive).
    pub force: f64,
    /// `"string"`, `"bar"` or `"none"`.
    pub kind: MemberKind,
    /// Sizing radius (m); 0 for `none`.
    pub radius: f64,
    /// Sized mass (kg): yield for strings, max(yield, buckling) for bars.
    pub mass: f64,
    /// What sets the size: `"yield"`, `"buckling"` or `"unloaded"`.
    #[serde(serialize_with = "serialize_governing")]
    pub governing: Governing,
}

/// Total masses (kg).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns)]
pub struct MassReport {
    /// Every member sized for yield only.
    #[serde(rename = "yield")]
    #[column(unit = "kg")]
    pub yield_only: f64,
    /// Strings for yield, bars for max(yield, buckling).
    #[column(unit = "kg")]
    pub yield_buckling: f64,
}

/// The result of [`analyse`]; serialises to the JSON of the `michell` subcommand.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct MichellReport {
    /// Parameters used.
    #[column(nested)]
    pub params: MichellParams,
    /// Solver used.
    pub method: Method,
    /// Material name.
    pub material: String,
    /// Tip load vector w (N).
    pub load: [f64; 3],
    /// Nodes in numbering order.
    pub nodes: Vec<NodeReport>,
    /// Members, numbered by parent then child slot.
    pub members: Vec<MemberReport>,
    /// Extra strings (empty without `--extra-strings`).
    pub extra_strings: Vec<MemberReport>,
    /// Prestress of the extra strings (N), if any.
    #[column(unit = "N")]
    pub prestress: Option<f64>,
    /// Total masses (kg), extra strings included.
    #[column(nested)]
    pub mass_kg: MassReport,
    /// Σ|q|·l²/(w₀ r₀) over all members (extra strings included).
    pub normalized_yield_mass: f64,
    /// Indices into `members` (then `extra_strings`, offset by `members.len()`) of the
    /// buckling-governed bars.
    pub buckling_governed: Vec<usize>,
    /// Support reactions (N), in support-node order.
    pub reactions: Vec<[f64; 3]>,
}

/// One analysis together with the truss it was computed on, so that callers that go on with
/// the same truss (sign maps, γ sweeps) need not build it again.
#[derive(Debug, Clone)]
pub struct MichellAnalysis {
    /// The truss built from the request's parameters.
    pub truss: MichellTruss,
    /// The report.
    pub report: MichellReport,
}

impl MichellAnalysis {
    /// Builds the truss of `req` and analyses it.
    ///
    /// ```
    /// use michell3d::{AnalysisRequest, MichellAnalysis, MichellParams};
    /// let p = MichellParams::cylindrical(3, 1.0, std::f64::consts::FRAC_PI_6, 0.4, 0.25);
    /// let a = MichellAnalysis::run(&AnalysisRequest::new(p)).unwrap();
    /// assert_eq!(a.truss.members().len(), a.report.members.len());
    /// ```
    pub fn run(req: &AnalysisRequest) -> Result<Self> {
        let truss = MichellTruss::new(req.params)?;
        let report = analyse_truss(&truss, req)?;
        Ok(Self { truss, report })
    }
}

/// Runs one analysis (builds the truss; [`MichellAnalysis::run`] also returns it).
///
/// ```
/// use michell3d::{analyse, AnalysisRequest, MichellParams};
/// let p = MichellParams::planar(2, 1.0, std::f64::consts::FRAC_PI_6, std::f64::consts::FRAC_PI_2);
/// let r = analyse(&AnalysisRequest::new(p)).unwrap();
/// assert_eq!(r.members.len(), 6);
/// assert!((r.normalized_yield_mass - 4.618802153517).abs() < 1e-9); // ERRATA 4.4: 4.62
/// ```
pub fn analyse(req: &AnalysisRequest) -> Result<MichellReport> {
    Ok(MichellAnalysis::run(req)?.report)
}

/// The member forces of one analysis: base members then extra strings.
struct MemberForces {
    /// Lengths (m).
    lengths: Vec<f64>,
    /// Tension-positive force densities (N/m).
    q: Vec<f64>,
    /// (parent, child) node indices; an extra string's two ends.
    ends: Vec<(usize, usize)>,
    /// Support reactions (N).
    reactions: Vec<[f64; 3]>,
}

/// Propagates the load (with prestressed extra strings when asked) and collects the forces.
fn member_forces(
    truss: &MichellTruss,
    req: &AnalysisRequest,
    loads: &NodalLoads,
) -> Result<MemberForces> {
    let (base, strings, extra_q) = match req.extra_strings {
        Some(t) => {
            let strings = ExtraStrings::new(truss)?;
            let sol = solve_prestressed(truss, &strings, loads, t, req.method)?;
            (sol.base, Some(strings), sol.extra_force_density)
        }
        None => (propagate(truss, loads, req.method)?, None, Vec::new()),
    };
    let mut out = MemberForces {
        lengths: truss.lengths(),
        q: base.force_density.clone(),
        ends: truss
            .members()
            .iter()
            .map(|m| (m.parent, m.child))
            .collect(),
        reactions: base.reactions.iter().map(|r| (*r).into()).collect(),
    };
    if let Some(s) = &strings {
        out.lengths.extend_from_slice(s.lengths());
        out.q.extend_from_slice(&extra_q);
        out.ends.extend(s.pairs().iter().map(|&[a, b]| (a, b)));
    }
    Ok(out)
}

/// The name of a governing failure mode in the report: `yield`, `buckling`, `unloaded`.
pub fn governing_name(g: Governing) -> &'static str {
    match g {
        Governing::Yield => "yield",
        Governing::Buckling => "buckling",
        Governing::Unloaded => "unloaded",
    }
}

fn serialize_governing<S: serde::Serializer>(
    g: &Governing,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    s.serialize_str(governing_name(*g))
}

/// One report row per member of `f`, sized by `sizing`.
fn member_rows(truss: &MichellTruss, f: &MemberForces, sizing: &TrussSizing) -> Vec<MemberReport> {
    (0..f.q.len())
        .map(|j| {
            let s = sizing.members[j];
            let (radius, mass, governing) = match s.size {
                Some(sz) => (sz.radius, sz.mass, sz.governing),
                None => (0.0, 0.0, Governing::Unloaded),
            };
            MemberReport {
                parent: truss.label(f.ends[j].0),
                child: truss.label(f.ends[j].1),
                length: f.lengths[j],
                force_density: f.q[j],
                force: f.q[j] * f.lengths[j],
                kind: s.kind,
                radius,
                mass,
                governing,
            }
        })
        .collect()
}

/// The report rows of the nodes.
fn node_rows(truss: &MichellTruss) -> Vec<NodeReport> {
    truss
        .nodes()
        .iter()
        .enumerate()
        .map(|(i, n)| NodeReport {
            index: truss.label(i),
            position: n.position.into(),
            support: truss.is_support(i),
        })
        .collect()
}

/// Analyses an already built truss (its parameters must be `req.params`).
fn analyse_truss(truss: &MichellTruss, req: &AnalysisRequest) -> Result<MichellReport> {
    let material = *MaterialTable::builtin().lookup(&req.material, "michell truss")?;
    let mut w = tip_load(req.load, req.azimuth, req.polar)?;
    let loads = NodalLoads::tip(w);
    // A planar truss keeps only the in-plane part (NodalLoads rejects a real w_x).
    loads.dense(truss)?;
    if truss.is_planar() {
        w.x = 0.0;
    }
    let f = member_forces(truss, req, &loads)?;
    let forces: Vec<f64> = f.q.iter().zip(&f.lengths).map(|(q, l)| q * l).collect();
    let sizing = size_members(&f.lengths, &forces, &material, &material);
    let mut members = member_rows(truss, &f, &sizing);
    let extra_strings = members.split_off(truss.members().len());
    Ok(MichellReport {
        params: req.params,
        method: req.method,
        material: req.material.clone(),
        load: w.into(),
        nodes: node_rows(truss),
        members,
        extra_strings,
        prestress: req.extra_strings,
        mass_kg: MassReport {
            yield_only: sizing.yield_mass,
            yield_buckling: sizing.yield_buckling_mass,
        },
        normalized_yield_mass: normalized_yield_mass(&f.lengths, &f.q, req.load, req.params.r0),
        buckling_governed: sizing.buckling_governed,
        reactions: f.reactions,
    })
}
