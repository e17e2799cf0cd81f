//! The T-bar wheel as a free, prestressed, massive structure for the full tensegrity rolling
//! model (issue item 5, "rolling … with the rolling models (rigid unilateral and full)").
//!
//! This module builds the structure and names its parts; wheel-rolling's full model
//! integrates it ([`FullWheel`] is a [`wheel_rolling::Wheel`]: its polygon and its
//! [`WheelScene`]). [`full_wheel`] returns:
//!
//! - **the structure**: the wheel (or extended wheel) with its rim body ([`crate::rim`]: hub,
//!   spokes, ring; class-k joints, no support, so a free body); every bar is a uniform rigid
//!   rod of mass ρL (treads' bars at the bar density ρ_b, rim-body bars at the rim density
//!   ρ_r); every string is linear elastic, t = k (L − L₀) for L > L₀ (slack below), with the
//!   rest length L₀ = L − t₀/k that realises the prestress t₀ at the built length L;
//! - **the prestress**: every tread carries the load envelope's optimal self-stress
//!   ([`crate::envelope::min_prestress`] of the rim-supported tread for a unit tip load:
//!   treads' bar −P*, strings s_k ≥ ‖g_k‖), scaled by λ. The scaled state keeps every string
//!   taut and the bar compressed under a tip load of magnitude up to w = λ · 1 N from any
//!   direction (small displacements, one EA): the **tip-load capacity**. [`PrestressLevel`]
//!   sets λ: from the smallest string tension t_min (λ = t_min / s_min), or (the default) a
//!   capacity of twice the wheel's weight per tip of a contact group, λ = 2 m g / c (see
//!   [`FullWheel::warnings`] for a capacity below the weight). The treads' members forces sum to a
//!   self-equilibrated set on the rim points, which the rim body (rigid: its only first-order
//!   mechanisms are the six rigid-body motions) balances with bar forces: the built shape is
//!   an equilibrium, and the rigid bars' forces are the dynamics' constraint forces;
//! - **an isostatic rim body**: the dynamics' bars are rigid, so a set of bars with a
//!   bar-only self-stress (a statically indeterminate rim) leaves its constraint forces
//!   undetermined — the core refuses the singular constraint system. The rim body keeps a
//!   maximal independent subset of its bars ([`independent_bars`]: greedy in the order ring,
//!   spokes, axle, a bar kept when its row of the bar-only rigidity matrix is independent of
//!   the rows kept), which has the same rank, hence the same first-order motions (the six
//!   rigid ones): the rim is as rigid as before, only its mass is that of the bars kept
//!   (3|R| = 3(|R| + 2) − 6 bars on |R| + 2 nodes). The ring goes first because every spoke adds
//!   coincidence rows at a hub: keeping the ring and as few spokes as the rank needs cut the
//!   cost of a step of the n = 8 extended wheel eightfold (96 → 33 spokes, when the core still
//!   tied every copy at a joint to the first one; the single loop keeps every ring bar, 5|R|/3
//!   spokes and no axle bar);
//! - **the starting pose**: turned about ι̂₁ by −π/2 − π/n, so that the tips of treads 0 and 1
//!   (at angles 2kφ from ι̂₂ in the built frame) lie at (∓r₀ sin(π/n), −r₀ cos(π/n)): the
//!   contact polygon (n = π/φ sides, circumradius r₀) standing on its side 0–1, tread 1
//!   downhill (+y);
//! - **contact groups**: group k = the tips of tread k of every copy (one node for the single
//!   loop, two for the extended wheel): the nodes that can touch the slope, in rolling order;
//! - **rim points and hubs**: ω is their mean spin about the hub (the hubs' midpoint);
//! - **mass properties** ([`crate::rolling::MassProperties`]): every bar, rim body included.

use crate::envelope::{min_prestress, LoadResponse};
use crate::error::{invalid, Result, TbarError};
use crate::geometry::TbarGeometry;
use crate::params::{Layout, RimMode, TbarParams};
use crate::rolling::{mass_properties_with, MassProperties};
use nalgebra::{Rotation3, Vector3};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::budget::Estimate;
use tensegrity_core::{Bar, StringMember, Structure};
use tensegrity_statics::Statics;
use wheel_rolling::estimate::{FullSizes, RunSize};
use wheel_rolling::{Polygon, WheelScene};

/// What the full model's structure is built with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FullWheelRequest {
    /// Linear density of the treads' bars ρ_b (kg/m).
    pub bar_density: f64,
    /// Linear density of the rim body's bars ρ_r (kg/m).
    pub rim_density: f64,
    /// Stiffness of every string k (N/m).
    pub string_stiffness: f64,
    /// The level of the prestress.
    pub prestress: PrestressLevel,
}

/// How large the prestress is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PrestressLevel {
    /// The smallest string tension t_min (N).
    MinTension(f64),
    /// A tip-load capacity of `factor` × the wheel's weight per tip of a contact group,
    /// m g / c (c = 1 for the single loop, 2 for the extended wheel): the whole weight landing
    /// on one group, with a margin for the dynamic loads.
    Weight {
        /// The factor on m g / c.
        factor: f64,
        /// g (m/s²).
        gravity: f64,
    },
}

/// Default factor of [`PrestressLevel::Weight`].
pub const DEFAULT_CAPACITY_FACTOR: f64 = 2.0;

impl Default for FullWheelRequest {
    /// Bars and rim at 1 kg/m (the toroid crate's bar density), strings 2·10⁴ N/m (its
    /// rolling default), prestress of twice the weight per landing tip under g = 9.81 m/s².
    fn default() -> Self {
        Self {
            bar_density: crate::rolling::DEFAULT_BAR_DENSITY,
            rim_density: crate::rolling::DEFAULT_BAR_DENSITY,
            string_stiffness: 2e4,
            prestress: PrestressLevel::Weight {
                factor: DEFAULT_CAPACITY_FACTOR,
                gravity: 9.81,
            },
        }
    }
}

/// The prestress the structure is built with.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FullPrestress {
    /// Compression of every tread's bar (N).
    pub bar_compression: f64,
    /// Smallest string tension (N): t_min.
    pub min_string_tension: f64,
    /// Largest string tension (N).
    pub max_string_tension: f64,
    /// Tip load (N) the state carries from every direction with every string taut and the
    /// bar compressed (the envelope: small displacements, one EA, rigid rim).
    pub tip_load_capacity: f64,
    /// Smallest rest length over the string's length, L₀/L.
    pub min_rest_ratio: f64,
}

/// The T-bar wheel ready for the full rolling model.
#[derive(Debug, Clone)]
pub struct FullWheel {
    /// The geometry with its rim body, in the built frame.
    pub geometry: TbarGeometry,
    /// The prestressed structure in the starting pose (no gravity, no support).
    pub structure: Structure,
    /// Contact groups in rolling order: the tips of tread k of every copy.
    pub contact_groups: Vec<Vec<usize>>,
    /// The rim points (ω is their mean spin about the hub).
    pub rim_points: Vec<usize>,
    /// The two hub nodes on the axle.
    pub hubs: [usize; 2],
    /// Circumradius of the contact polygon r₀ (m).
    pub outer_radius: f64,
    /// Mass and I₁ of every bar (rim body included).
    pub mass: MassProperties,
    /// The prestress.
    pub prestress: FullPrestress,
    /// Rim-body bars left out to make the rim isostatic (see the module docs).
    pub redundant_rim_bars: usize,
}

impl FullWheel {
    /// The assumptions a run of this structure under gravity `gravity` leaves: a tip load
    /// beyond the prestress's capacity (the wheel's weight m g on one tip, as when it lands on
    /// a single contact group) may slacken strings, which the model allows but the envelope
    /// does not cover.
    pub fn warnings(&self, gravity: f64) -> Vec<tensegrity_core::Warning> {
        let weight = self.mass.mass * gravity;
        let tips = self.contact_groups.first().map_or(1, Vec::len).max(1);
        let per_tip = weight / tips as f64;
        let mut out = Vec::new();
        let p = &self.prestress;
        if per_tip > p.tip_load_capacity {
            out.push(tensegrity_core::Warning::SlackInContact {
                min_tension: p.min_string_tension,
                capacity: p.tip_load_capacity,
                tips,
                per_tip,
                suggested_min_tension: p.min_string_tension * per_tip / p.tip_load_capacity,
            });
        }
        out
    }
}

impl FullWheel {
    /// The wheel as the full model runs it: the prestressed structure in its starting pose,
    /// the tip groups, ω from the rim points about the hubs, r₀, m and I₁.
    pub fn scene(&self) -> WheelScene {
        WheelScene {
            structure: self.structure.clone(),
            contact_groups: self.contact_groups.clone(),
            rim: self.rim_points.clone(),
            axle: Some(self.hubs),
            outer_radius: self.outer_radius,
            mass: self.mass.mass,
            i1: self.mass.i1,
        }
    }
}

impl wheel_rolling::Wheel for FullWheel {
    type Error = TbarError;

    fn polygon(&self) -> Polygon {
        self.mass.polygon()
    }

    /// The structure's nodes (built in the starting pose), for `auto` runs the policy hands
    /// to the rigid model.
    fn start_pose(&self) -> Vec<nalgebra::Vector3<f64>> {
        self.structure.nodes().to_vec()
    }

    fn scene(&self) -> Result<WheelScene> {
        Ok(FullWheel::scene(self))
    }
}

/// Builds the T-bar wheel of `params` (a wheel or an extended wheel; its rim is replaced by
/// the rim body) for the full model (see the module docs).
///
/// ```
/// use michell3d::MichellParams;
/// use tbar_wheel::rolling_full::{full_wheel, FullWheelRequest};
/// use tbar_wheel::{Layout, TbarParams};
/// use std::f64::consts::{FRAC_PI_4, FRAC_PI_6};
/// let m = MichellParams::cylindrical(1, 1.0, FRAC_PI_6, FRAC_PI_4, 0.25);
/// let p = TbarParams::tread(m).with_layout(Layout::Wheel);
/// let w = full_wheel(&p, &FullWheelRequest::default()).unwrap();
/// // 4 treads: the polygon stands on the tips of treads 0 and 1
/// assert_eq!(w.contact_groups.len(), 4);
/// let z = -(std::f64::consts::PI / 4.0).cos();
/// assert!((w.structure.nodes()[w.contact_groups[1][0]].z - z).abs() < 1e-12);
/// // the default prestress carries twice the weight on one tip from every direction
/// assert!((w.prestress.tip_load_capacity - 2.0 * w.mass.mass * 9.81).abs() < 1e-9);
/// ```
pub fn full_wheel(params: &TbarParams, req: &FullWheelRequest) -> Result<FullWheel> {
    check_request(req)?;
    if params.layout == Layout::Tread {
        return Err(invalid(
            "layout",
            1.0,
            "a single tread does not roll: use a wheel or an extended wheel",
        ));
    }
    let tread = tread_state(params)?;
    let mut g = TbarGeometry::new(params.with_rim(RimMode::Body))?;
    let redundant_rim_bars = make_isostatic(&mut g);
    let n = g.params.treads_per_wheel()?;
    let forces = wheel_forces(&g, &tread)?;
    let mass = mass_properties_with(&g, req.bar_density, req.rim_density)?;
    let copies = g.params.copies();
    // the state carries a tip load of λ · 1 N; its smallest string tension is λ s_min
    let lambda = match req.prestress {
        PrestressLevel::MinTension(t) => t / tread.min_string,
        PrestressLevel::Weight { factor, gravity } => factor * mass.mass * gravity / copies as f64,
    };
    let structure = build_structure(&g, req, &forces, lambda, n)?;
    let rim = g
        .rim
        .as_ref()
        .ok_or_else(|| invalid("rim", 0.0, "the rim body was not attached"))?;
    let (rim_points, hubs) = (rim.rim_points.clone(), rim.hubs);
    let contact_groups = (0..n)
        .map(|k| (0..copies).map(|c| g.tips[c * n + k]).collect())
        .collect();
    let strings = &forces[g.bars.len()..];
    let min_rest_ratio = strings
        .iter()
        .zip(&g.strings)
        .map(|(t, &[a, b])| {
            let l = (g.nodes[b] - g.nodes[a]).norm();
            1.0 - lambda * t / (req.string_stiffness * l)
        })
        .fold(f64::INFINITY, f64::min);
    let prestress = FullPrestress {
        bar_compression: -lambda * tread.bar_force,
        min_string_tension: lambda * tread.min_string,
        max_string_tension: lambda * strings.iter().copied().fold(0.0, f64::max),
        tip_load_capacity: lambda,
        min_rest_ratio,
    };
    Ok(FullWheel {
        redundant_rim_bars,
        outer_radius: g.params.michell.r0,
        geometry: g,
        structure,
        contact_groups,
        rim_points,
        hubs,
        mass,
        prestress,
    })
}

/// Keeps a maximal independent subset of the rim body's bars (in `g.rim`); returns how many
/// were left out.
fn make_isostatic(g: &mut TbarGeometry) -> usize {
    let Some(rim) = g.rim.as_mut() else {
        return 0;
    };
    // ring first, then spokes, then the axle: the fewer spokes, the smaller the hub joints
    let first_ring = 1 + rim.spokes;
    let order: Vec<usize> = (first_ring..rim.bars.len())
        .chain(1..first_ring)
        .chain(std::iter::once(0))
        .collect();
    let ordered: Vec<[usize; 2]> = order.iter().map(|&k| rim.bars[k]).collect();
    let mut keep: Vec<usize> = independent_bars(&g.nodes, &ordered)
        .into_iter()
        .map(|i| order[i])
        .collect();
    keep.sort_unstable();
    let spokes = keep
        .iter()
        .filter(|&&k| (1..first_ring).contains(&k))
        .count();
    let ring = keep.iter().filter(|&&k| k >= first_ring).count();
    let before = rim.bars.len();
    rim.bars = keep.iter().map(|&k| rim.bars[k]).collect();
    (rim.spokes, rim.ring) = (spokes, ring);
    before - rim.bars.len()
}

/// Indices of a maximal independent subset of `bars` (rows of the rigidity matrix, unit
/// direction ∓d at the two ends), chosen greedily in order: a bar is kept when its row keeps
/// more than 10⁻⁸ of its norm after the projection out of the rows kept (modified
/// Gram–Schmidt, applied twice).
///
/// ```
/// use nalgebra::Vector3;
/// use tbar_wheel::rolling_full::independent_bars;
/// // a triangle with a doubled side: the repeat is dependent
/// let x = [Vector3::zeros(), Vector3::x(), Vector3::y()];
/// assert_eq!(independent_bars(&x, &[[0, 1], [1, 2], [2, 0], [1, 0]]), [0, 1, 2]);
/// ```
pub fn independent_bars(nodes: &[Vector3<f64>], bars: &[[usize; 2]]) -> Vec<usize> {
    let dim = 3 * nodes.len();
    let mut basis: Vec<Vec<f64>> = Vec::new();
    let mut keep = Vec::new();
    for (k, &[a, b]) in bars.iter().enumerate() {
        let d = (nodes[b] - nodes[a]).normalize();
        let mut row = vec![0.0; dim];
        for i in 0..3 {
            row[3 * a + i] = -d[i];
            row[3 * b + i] = d[i];
        }
        for _ in 0..2 {
            for q in &basis {
                let c: f64 = q.iter().zip(&row).map(|(x, y)| x * y).sum();
                row.iter_mut().zip(q).for_each(|(r, x)| *r -= c * x);
            }
        }
        // the row's norm before the projection is √2
        let norm = row.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm > 1e-8 * 2f64.sqrt() {
            row.iter_mut().for_each(|v| *v /= norm);
            basis.push(row);
            keep.push(k);
        }
    }
    keep
}

fn check_request(req: &FullWheelRequest) -> Result<()> {
    let (level_name, level) = match req.prestress {
        PrestressLevel::MinTension(t) => ("min_tension", t),
        PrestressLevel::Weight { factor, gravity } => {
            if !(gravity.is_finite() && gravity > 0.0) {
                return Err(invalid("gravity", gravity, "must be finite and > 0"));
            }
            ("prestress_factor", factor)
        }
    };
    for (name, v) in [
        ("bar_density", req.bar_density),
        ("rim_density", req.rim_density),
        ("string_stiffness", req.string_stiffness),
        (level_name, level),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, "must be finite and > 0"));
        }
    }
    Ok(())
}

/// One rim-supported tread's optimal envelope state for a unit tip load.
struct TreadState {
    /// Member forces (N), the bar first, then the strings in the tread's order.
    forces: Vec<f64>,
    /// Force of the bar (N, negative).
    bar_force: f64,
    /// Smallest string tension (N).
    min_string: f64,
    /// String lengths (m), to match the wheel's strings.
    lengths: Vec<f64>,
}

fn tread_state(params: &TbarParams) -> Result<TreadState> {
    let tread = TbarGeometry::new(params.with_layout(Layout::Tread).with_rim(RimMode::Fixed))?;
    let s = tread.structure()?;
    let statics = Statics::new(&s)?;
    let response = LoadResponse::new(&statics, &tread.tips, 1.0, "tread")?;
    let sol = min_prestress(&statics, &response, 1.0, &tread.labels, "tread")?;
    let nb = tread.bars.len();
    let min_string = sol.prestress_force[nb..]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    if nb != 1 || min_string.is_nan() || min_string <= 0.0 {
        return Err(TbarError::NotPrestressable {
            structure: "tread",
            self_stress_dim: statics.self_stress_dim(),
        });
    }
    let lengths = s.member_lengths()[nb..].to_vec();
    Ok(TreadState {
        bar_force: sol.prestress_force[0],
        forces: sol.prestress_force,
        min_string,
        lengths,
    })
}

/// The tread state on every tread of the wheel: member forces (N, unit tip load) in the
/// wheel's order, the treads' bars first, then the strings (the rim body's bars carry none
/// of the prescribed prestress: theirs are constraint forces).
fn wheel_forces(g: &TbarGeometry, tread: &TreadState) -> Result<Vec<f64>> {
    let per = tread.lengths.len();
    let treads = g.tips.len();
    if g.strings.len() != treads * per || g.bars.len() != treads {
        return Err(invalid(
            "complexity",
            g.params.complexity() as f64,
            format!(
                "neighbouring treads share strings ({} strings for {treads} treads of {per}): the per-tread prestress does not apply",
                g.strings.len()
            ),
        ));
    }
    let mut out = vec![tread.bar_force; treads];
    for (i, &[a, b]) in g.strings.iter().enumerate() {
        let j = i % per;
        let l = (g.nodes[b] - g.nodes[a]).norm();
        if (l - tread.lengths[j]).abs() > 1e-9 * l.max(1.0) {
            return Err(invalid(
                "string",
                i as f64,
                format!(
                    "string {i} ({l} m) does not match the tread's string {j} ({} m)",
                    tread.lengths[j]
                ),
            ));
        }
        out.push(tread.forces[1 + j]);
    }
    Ok(out)
}

/// Bars with mass, strings with rest lengths, nodes turned onto the starting side.
fn build_structure(
    g: &TbarGeometry,
    req: &FullWheelRequest,
    forces: &[f64],
    lambda: f64,
    n: usize,
) -> Result<Structure> {
    let turn = Rotation3::from_axis_angle(&Vector3::x_axis(), -0.5 * PI - PI / n as f64);
    let nodes = g.nodes.iter().map(|p| turn * p);
    let mut b = Structure::builder().nodes(nodes.map(|p| [p.x, p.y, p.z]));
    let length = |[s, e]: [usize; 2]| (g.nodes[e] - g.nodes[s]).norm();
    for &bar in &g.bars {
        b = b.bar(Bar::new(bar[0], bar[1]).mass(req.bar_density * length(bar)));
    }
    for &bar in g.rim.iter().flat_map(|r| &r.bars) {
        b = b.bar(Bar::new(bar[0], bar[1]).mass(req.rim_density * length(bar)));
    }
    let k = req.string_stiffness;
    for (i, &s) in g.strings.iter().enumerate() {
        let (l, t) = (length(s), lambda * forces[g.bars.len() + i]);
        if t >= k * l {
            return Err(invalid(
                "string_stiffness",
                k,
                format!(
                    "string {i} needs a tension of {t:.6} N, which a stiffness of {k} N/m cannot give at its length {l:.6} m (rest length ≤ 0)"
                ),
            ));
        }
        b = b.string(
            StringMember::new(s[0], s[1])
                .stiffness(k)
                .rest_length(l - t / k),
        );
    }
    Ok(b.build()?)
}

/// The sizes of the full model of `params` (the isostatic structure): the class-1 model has
/// two nodes per bar and 3 (copies − 1) coincidence rows per node, tied in a chain (so a
/// hub's rows form a banded block of the sparse Ω system): ~1500 flops a bar on top of the
/// core's per-member cost; a step is four right-hand sides and a projection (counted as two
/// more). Calibrated on the default full roll (n = 8 loop, 1 s at 0.1 ms: 3.8 s of CPU
/// against 10.2 s estimated; it was 4000 flops a bar, 5.8× over).
pub fn full_sizes(params: &TbarParams) -> Result<FullSizes> {
    let mut g = TbarGeometry::new(params.with_rim(RimMode::Body))?;
    make_isostatic(&mut g);
    let bars = g.all_bars().len();
    Ok(FullSizes {
        nodes: g.nodes.len(),
        bars,
        strings: g.strings.len(),
        constraint_rows: 3 * (2 * bars).saturating_sub(g.nodes.len()),
        rhs_per_step: 6.0,
        extra_flops: 1500.0 * bars as f64,
    })
}

/// Estimate of a full rolling run of `params` for `t_end` s at step `dt` (RK4 with the
/// projection onto the bar lengths and joints after every step), from the isostatic
/// structure's sizes ([`full_sizes`], estimated by [`wheel_rolling::estimate::full`]).
/// Checked against runs of 0.05 s on a shared 2-core machine (n = 6…24, loop and extended;
/// conservative by 3–6× with 4000 flops a bar, so by about 1.2–2.7× now) and the default 1 s
/// roll (2.7×). One 1 ms sample is kept per millisecond.
pub fn full_roll_estimate(params: &TbarParams, t_end: f64, dt: f64) -> Result<Estimate> {
    let sizes = full_sizes(params)?;
    let n = params.treads_per_wheel()?;
    let mut size = RunSize::new(t_end, dt, n);
    size.parameter = format!(
        "t_end = {t_end}, dt = {dt}, treads = {n} ({} bars with the isostatic rim body)",
        sizes.bars
    );
    Ok(wheel_rolling::estimate::full(&size, &sizes))
}
