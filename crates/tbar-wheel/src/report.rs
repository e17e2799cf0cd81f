//! One complete analysis of a T-bar tread or wheel, as the CLI prints it (text or JSON):
//! geometry → statics → load envelope (minimum prestress, critical member; slack map for a
//! given prestress) → mass against the Michell truss.
//!
//! When the envelope does not exist (the elastic stiffness has a mechanism, or no prestress
//! is admissible) its fields are `null` and the reason is in `warnings`; the geometry and the
//! statics are still reported.
//!
//! A `prestress` (the slack map's bar compression, and the state the mass is sized for)
//! below the minimum prestress is analysed as asked, but the envelope is not carried: strings
//! slacken under some of its loads, so the mass is not a sizing for it. The report says so
//! (`envelope_carried: false` and the warning `prestress_below_minimum`, with the minimum
//! and the slack fraction).

use crate::envelope::{
    self, min_prestress, scaled_state, slack_map, CriticalMember, LoadResponse, SlackPoint,
};
use crate::error::{invalid, Result};
use crate::geometry::TbarGeometry;
use crate::mass::{self, MassComparison};
use crate::params::{RimMode, TbarParams};
use crate::statics::{backend, summarise};
use serde::Serialize;
use tensegrity_core::Structure;
use tensegrity_core::Warning;
use tensegrity_derive::Columns;
use tensegrity_statics::{Certification, Factorization, SpectralGap, StaticsBackend};

/// Everything one analysis needs.
#[derive(Debug, Clone, PartialEq)]
pub struct TbarRequest {
    /// Geometry.
    pub params: TbarParams,
    /// Tip load magnitude w₀ (N).
    pub load: f64,
    /// Axial stiffness EA of every member (N).
    pub ea: f64,
    /// Bar compression of the slack map (N), if any.
    pub prestress: Option<f64>,
    /// Directions of the slack map (quasi-uniform sphere).
    pub directions: usize,
    /// Material of the sizing (core table name).
    pub material: String,
}

impl TbarRequest {
    /// A request with the defaults: w₀ = 1 N, EA = 1 MN, no slack map, 2000 directions, steel.
    pub fn new(params: TbarParams) -> Self {
        Self {
            params,
            load: envelope::DEFAULT_LOAD,
            ea: envelope::DEFAULT_EA,
            prestress: None,
            directions: envelope::DEFAULT_DIRECTIONS,
            material: mass::DEFAULT_MATERIAL.to_string(),
        }
    }

    fn validate(&self) -> Result<()> {
        if !(self.load.is_finite() && self.load > 0.0) {
            return Err(invalid("load", self.load, "must be finite and > 0"));
        }
        // a subnormal load sizes every member to a mass that underflows to 0 (ratio 0/0)
        if self.load < f64::MIN_POSITIVE / f64::EPSILON {
            return Err(invalid(
                "load",
                self.load,
                "is below the range where the member masses stay representable (at least 1e-292 N)",
            ));
        }
        if !(self.ea.is_finite() && self.ea > 0.0) {
            return Err(invalid("ea", self.ea, "must be finite and > 0"));
        }
        if let Some(p) = self.prestress {
            if !(p.is_finite() && p > 0.0) {
                return Err(invalid("prestress", p, "must be finite and > 0"));
            }
        }
        if self.directions == 0 || self.directions > envelope::MAX_DIRECTIONS {
            return Err(invalid(
                "directions",
                self.directions as f64,
                format!("must lie in 1..={}", envelope::MAX_DIRECTIONS),
            ));
        }
        Ok(())
    }
}

/// The report of one analysis (the JSON contract of `tensegrity tbar --json`).
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct TbarReport {
    /// The parameters.
    #[column(nested)]
    pub params: TbarParams,
    /// Number of nodes.
    pub nodes: usize,
    /// Number of bars (the treads' and, with a rim body, the rim body's).
    pub bars: usize,
    /// The rim model: `fixed` (rigid rim, supports) or `body` (free rim body of bars).
    pub rim: RimMode,
    /// Bars of the rim body (0 with the rigid rim).
    pub rim_bars: usize,
    /// Number of strings.
    pub strings: usize,
    /// Number of treads (both wheels of an extended wheel).
    pub treads: usize,
    /// Lattice nodes per level of one tread, (l+1)².
    pub level_sizes: Vec<usize>,
    /// Node labels (tread 0: `tip`, `bar_base`, tuples such as `1010`).
    pub node_labels: Vec<String>,
    /// Node coordinates (m), same order as the labels.
    pub node_coordinates: Vec<[f64; 3]>,
    /// Whether each node is a rim support.
    pub supported: Vec<bool>,
    /// Bars as [start, end] node indices: the treads' [base, tip], then the rim body's.
    pub bar_nodes: Vec<[usize; 2]>,
    /// Strings as [parent, child] node indices.
    pub string_nodes: Vec<[usize; 2]>,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Self-stress dimension.
    pub self_stress_dim: usize,
    /// First-order mechanisms.
    pub mechanisms: usize,
    /// Internal mechanisms (beyond the rigid-body motions the supports allow).
    pub internal_mechanisms: usize,
    /// The statics back-end that answered: `cyclic` (a wheel: the symmetry-adapted blocks)
    /// or `svd` (a tread, or the dense fallback).
    pub statics_method: Factorization,
    /// Whether a self-stress with taut strings and compressed bars exists.
    pub prestressable: bool,
    /// The core's prestressability margin.
    pub prestress_margin: f64,
    /// Tip load w₀ (N).
    #[column(unit = "N")]
    pub load: f64,
    /// Axial stiffness EA (N).
    #[column(unit = "N")]
    pub ea: f64,
    /// Minimum bar compression (N) carrying w₀ from every direction.
    #[column(unit = "N")]
    pub min_prestress: Option<f64>,
    /// The binding member and its worst direction.
    #[column(nested)]
    pub critical_member: Option<CriticalMember>,
    /// Every binding member (indices, bars first).
    pub active_members: Vec<usize>,
    /// Member forces (N, bars first) of the minimum-prestress state.
    pub prestress_force: Option<Vec<f64>>,
    /// The bar compression of the slack map (N).
    #[column(unit = "N")]
    pub prestress: Option<f64>,
    /// Fraction of the sampled directions that slacken a string or put a bar in tension.
    pub slack_fraction: Option<f64>,
    /// Whether the bar stays in compression for every sampled direction.
    pub bar_always_compressed: Option<bool>,
    /// Fewest strings whose force a sampled load changes.
    pub min_strings_carrying: Option<usize>,
    /// Whether the bar's force changes for every sampled load.
    pub bar_always_carries: Option<bool>,
    /// The slack map over (azimuth, polar).
    pub slack_map: Option<Vec<SlackPoint>>,
    /// Mass of the T-bar structure sized for the envelope (kg).
    #[column(unit = "kg")]
    pub mass_kg: Option<f64>,
    /// Masses against the Michell truss.
    #[column(nested)]
    pub mass: Option<MassComparison>,
    /// Whether the prestress of the sizing carries the load envelope: `true` at the minimum
    /// prestress or a `prestress` at least that, `false` for a `prestress` below it (the
    /// mass is then that of a structure whose strings slacken under some loads of the
    /// envelope: not a valid sizing, warning `prestress_below_minimum`); `null` without an
    /// envelope.
    pub envelope_carried: Option<bool>,
    /// Everything the analysis could not do, and why.
    pub warnings: Vec<Warning>,
    /// The singular values on either side of the rank tolerance behind the counts (the
    /// narrowest block's for a wheel).
    #[column(nested)]
    pub spectral_gap: SpectralGap,
    /// Set (else `null`) when the rank decision has no clear gap (a singular value within a
    /// factor 10 of the tolerance); also listed in `warnings`.
    pub statics_warning: Option<String>,
}

/// Runs one analysis.
///
/// ```
/// use michell3d::MichellParams;
/// use tbar_wheel::{tbar_report, TbarParams, TbarRequest};
/// let m = MichellParams::cylindrical(1, 1.0, 0.5, std::f64::consts::PI / 8.0, 0.25);
/// let r = tbar_report(&TbarRequest::new(TbarParams::tread(m))).unwrap();
/// assert_eq!((r.nodes, r.self_stress_dim), (6, 2));
/// assert!(r.min_prestress.unwrap() > 0.0);
/// ```
pub fn tbar_report(req: &TbarRequest) -> Result<TbarReport> {
    report_with(req, true)
}

/// [`tbar_report`] through the dense SVD for every layout (O(n³) for a wheel of n treads):
/// the cross-check of the cyclic path.
pub fn tbar_report_dense(req: &TbarRequest) -> Result<TbarReport> {
    report_with(req, false)
}

fn report_with(req: &TbarRequest, cyclic: bool) -> Result<TbarReport> {
    req.validate()?;
    let geometry = TbarGeometry::new(req.params)?;
    let structure = geometry.structure()?;
    let mut warnings = Vec::new();
    let symmetry = cyclic
        .then(|| crate::symmetry::find_symmetry(&geometry, &structure, &mut warnings))
        .flatten();
    let statics = backend(&structure, symmetry.as_ref())?;
    let statics_warning = match statics.certification() {
        Certification::Certified => None,
        Certification::NotCertified { reason } => Some(reason),
    };
    warnings.extend(
        statics_warning
            .clone()
            .map(|reason| Warning::StaticsNotCertified { reason }),
    );
    let summary = summarise(statics.as_ref())?;
    let mut report = base_report(req, &geometry, &structure);
    report.warnings = warnings;
    report.statics_warning = statics_warning;
    report.spectral_gap = statics.spectral_gap();
    report.statics_method = statics.kind();
    report.rank = summary.rank;
    report.self_stress_dim = summary.self_stress_dim;
    report.mechanisms = summary.mechanisms;
    report.internal_mechanisms = summary.internal_mechanisms;
    report.prestressable = summary.prestressable;
    report.prestress_margin = summary.prestress_margin;
    if let Some(rim) = &geometry.rim {
        // rim-body bars carry either sign: only the treads' members need the right one
        let margin =
            crate::rim::prestressability(statics.as_ref(), geometry.bars.len(), rim.bars.len())?;
        report.prestress_margin = margin;
        report.prestressable = margin > tensegrity_statics::PRESTRESS_TOLERANCE;
        report.warnings.push(Warning::RimFreeBody);
        return Ok(report);
    }
    if let Err(e) = add_envelope(req, &geometry, statics.as_ref(), &mut report) {
        report.warnings.push(Warning::NoLoadEnvelope {
            reason: e.to_string(),
        });
    }
    Ok(report)
}

fn base_report(req: &TbarRequest, g: &TbarGeometry, s: &Structure) -> TbarReport {
    TbarReport {
        params: req.params,
        nodes: s.n_nodes(),
        bars: s.n_bars(),
        rim: req.params.rim,
        rim_bars: g.rim.as_ref().map_or(0, |r| r.bars.len()),
        strings: s.n_strings(),
        treads: g.treads(),
        level_sizes: g.level_sizes.clone(),
        node_labels: g.labels.clone(),
        node_coordinates: g.nodes.iter().map(|p| [p.x, p.y, p.z]).collect(),
        supported: g.supported.clone(),
        bar_nodes: g.all_bars(),
        string_nodes: g.strings.clone(),
        rank: 0,
        self_stress_dim: 0,
        mechanisms: 0,
        internal_mechanisms: 0,
        statics_method: Factorization::Svd,
        prestressable: false,
        prestress_margin: 0.0,
        load: req.load,
        ea: req.ea,
        min_prestress: None,
        critical_member: None,
        active_members: Vec::new(),
        prestress_force: None,
        prestress: req.prestress,
        slack_fraction: None,
        bar_always_compressed: None,
        min_strings_carrying: None,
        bar_always_carries: None,
        slack_map: None,
        mass_kg: None,
        mass: None,
        envelope_carried: None,
        warnings: Vec::new(),
        spectral_gap: SpectralGap::default(),
        statics_warning: None,
    }
}

/// Relative margin under the minimum prestress within which a `prestress` counts as the
/// minimum (the minimum written to 9 digits and given back).
const AT_MINIMUM: f64 = 1e-9;

/// Whether the `prestress` of the slack map and the sizing carries the envelope of minimum
/// `minimum`; below it, the [`Warning::PrestressBelowMinimum`] with the slack fraction of
/// the map.
fn below_minimum(prestress: f64, minimum: f64, load: f64, slack: f64, report: &mut TbarReport) {
    let carried = prestress >= minimum * (1.0 - AT_MINIMUM);
    report.envelope_carried = Some(carried);
    if !carried {
        report.warnings.push(Warning::PrestressBelowMinimum {
            prestress,
            minimum,
            load,
            slack_fraction: slack,
        });
    }
}

/// Minimum prestress, slack map and mass.
fn add_envelope(
    req: &TbarRequest,
    g: &TbarGeometry,
    statics: &dyn StaticsBackend,
    report: &mut TbarReport,
) -> Result<()> {
    let what = req.params.layout.name();
    let response = LoadResponse::new(statics, &g.tips, req.ea, what)?;
    let sol = min_prestress(statics, &response, req.load, &g.labels, what)?;
    let state = match req.prestress {
        Some(p) => {
            let state = scaled_state(&sol, p)?;
            let dirs = envelope::sphere_directions(req.directions);
            let map = slack_map(&response, &state, req.load, &dirs);
            report.slack_fraction = Some(map.slack_fraction);
            report.bar_always_compressed = Some(map.bar_always_compressed);
            report.min_strings_carrying = Some(map.min_strings_carrying);
            report.bar_always_carries = Some(map.bar_always_carries);
            report.slack_map = Some(map.points);
            below_minimum(p, sol.min_prestress, req.load, map.slack_fraction, report);
            state
        }
        None => {
            report.envelope_carried = Some(true);
            sol.prestress_force.clone()
        }
    };
    report.min_prestress = Some(sol.min_prestress);
    report.critical_member = Some(sol.critical_member.clone());
    report.active_members = sol.active_members.clone();
    report.prestress_force = Some(sol.prestress_force.clone());
    let forces = mass::design_forces(&response, &state, req.load);
    let m = mass::compare(
        &req.params,
        g.treads(),
        &response.lengths,
        response.n_bars,
        &forces,
        req.load,
        &req.material,
    )?;
    report.mass_kg = Some(m.mass_kg);
    report.mass = Some(m);
    Ok(())
}
