//! The Michell-truss figures of chapter 4 (r₀ = 1, β = π/6, a 1 kN tip load along −ι̂₃,
//! steel), each with its data ([`crate::data`]):
//!
//! - Figs. 4.1–4.2: the Michell spirals from their closed form (eq. 4.1–4.7):
//!   n_ik = r_(i+k) e^(j(i−k)φ) in the (ι̂₂, ι̂₃) plane, r_m = r₀ aᵐ, a = sin β / sin(β + φ);
//!   every member m_ik = n_ik − n_i(k+1) has length c r_(i+k), c = sin φ / sin(β + φ), and
//!   meets the radius of its outer node at β. 4.1: the spiral of complexity 4 with its radii;
//!   4.2: the spirals of order 4, 3, 2, 1 and 0 (φ = π/8);
//! - Fig. 4.3: the planar topology of complexity 4 (the m_ik and their conjugates);
//! - Fig. 4.4: its force regions: the U spiral red, the D spiral blue, and the two regions of
//!   the load direction θ₀₀ (from ι̂₂ towards ι̂₃) in which the truss is a tensegrity —
//!   [π + β, 2π − β] (blue members compressed, red in tension) and [β, π − β] (the
//!   reverse), exact for every q (ERRATA 4.2) — drawn as fans at the tip;
//! - drawings of the 3-D trusses, members in tension red, in compression blue, unloaded grey
//!   ([`michell3d::MichellAnalysis::run`]): Figs. 4.6–4.7 (cylindrical q = 4, δ = 0.25),
//!   4.8, 4.10–4.12 (spherical, ε = π/12), 4.13 (cylindrical q = 1: the three tip members,
//!   eq. 4.18–4.20), 4.19 (the extra strings of §4.6, [`ExtraStrings`]);
//! - Fig. 4.9: the spherical q = 2 truss from above, nodes and members coloured by their
//!   height class Z = U − D (the thesis's colours);
//! - Figs. 4.14–4.16: the sign of the tip members' force densities λ₁₀₁₀, λ₁₀₀₁, λ₀₁₀₀ over
//!   the load direction (azimuth φ, polar angle γ) on the q = 1 cylindrical truss
//!   ([`sweeps::grids::sign_maps`]), drawn as vertical runs of one sign per azimuth; the
//!   data is the grid;
//! - Fig. 4.18: the yield + buckling mass against complexity q (φ = π/q), planar and
//!   δ = 0.1, 0.25, 0.5: two `michell` sweeps, their CSVs kept; [`mass_table_figure`] draws
//!   the same curves from the rows of [`michell3d::mass_vs_complexity`] (the
//!   `michell_table` request);
//! - Fig. 4.20: the force densities of the members of the q = 2 cylindrical truss over
//!   γ ∈ [0, 2π] with 10 N and 5 kN in the extra strings
//!   ([`michell3d::extra_strings::gamma_sweep`]).

use crate::context::Context as Ctx;
use crate::data::{no_forces, Drawn, StructureFigure};
use crate::draw::{Group, View, BLUE, GREY, RED};
use crate::error::Result;
use michell3d::extra_strings::{gamma_sweep, ExtraStrings};
use michell3d::signmap::{AngleGrid, SignMap};
use michell3d::{AnalysisRequest, Branch, MemberKind, Method, MichellAnalysis, MichellParams};
use nalgebra::Vector3;
use std::collections::HashMap;
use std::f64::consts::{FRAC_PI_6, PI};
use tensegrity_io::figure::{diverging_color, Figure, Panel, Series};
use tensegrity_io::figure_data::{FigureData, Value};

const BETA: f64 = FRAC_PI_6;

/// The analysed truss (1 kN tip load along −ι̂₃, steel).
fn analysed(params: MichellParams) -> Result<MichellAnalysis> {
    Ok(MichellAnalysis::run(&AnalysisRequest::new(params))?)
}

/// Members in tension red, in compression blue, unloaded grey.
fn force_groups(a: &MichellAnalysis) -> Vec<Group> {
    let members = a.truss.members();
    let of = |kind: MemberKind| -> Vec<[usize; 2]> {
        a.report
            .members
            .iter()
            .zip(members)
            .filter(|(r, _)| r.kind == kind)
            .map(|(_, m)| [m.parent, m.child])
            .collect()
    };
    vec![
        Group::new("tension", RED, of(MemberKind::String)),
        Group::new("compression", BLUE, of(MemberKind::Bar)),
        Group::new("zero force", GREY, of(MemberKind::None)),
    ]
}

fn positions(a: &MichellAnalysis) -> Vec<Vector3<f64>> {
    a.truss.nodes().iter().map(|n| n.position).collect()
}

/// The axial force of every member by its end nodes (parent, child), from the analysis.
fn forces_of(a: &MichellAnalysis) -> HashMap<[usize; 2], f64> {
    a.truss
        .members()
        .iter()
        .zip(&a.report.members)
        .map(|(m, r)| ([m.parent, m.child], r.force))
        .collect()
}

/// The data columns of an analysed truss.
const TRUSS_COLUMNS: [(&str, &str); 3] = [("complexity", ""), ("phi", "rad"), ("load", "N")];

fn truss_extra(a: &MichellAnalysis) -> Vec<Value> {
    let p = &a.report.params;
    vec![
        p.complexity.into(),
        p.phi.into(),
        Vector3::from(a.report.load).norm().into(),
    ]
}

/// Adds one analysed truss as panels in `views`, members coloured by force sign.
fn add_truss(fig: &mut StructureFigure, a: &MichellAnalysis, views: &[(View, &str)]) {
    let (nodes, groups, forces) = (positions(a), force_groups(a), forces_of(a));
    for &(view, title) in views {
        let force = |_: usize, _: usize, e: [usize; 2]| forces.get(&e).copied();
        fig.add(title, view, &nodes, &groups, &force, truss_extra(a));
    }
}

/// Panels of one truss in several views.
fn truss_figure(params: MichellParams, views: &[(View, &str)]) -> Result<Drawn> {
    let a = analysed(params)?;
    let mut fig = StructureFigure::new(&TRUSS_COLUMNS);
    add_truss(&mut fig, &a, views);
    Ok(fig.finish())
}

/// Node n_ik of the planar spiral (eq. 4.7): radius r_(i+k) = r₀ a^(i+k), phase (i − k)φ,
/// in the (ι̂₂, ι̂₃) plane.
pub fn spiral_node(i: usize, k: usize, r0: f64, beta: f64, phi: f64) -> Vector3<f64> {
    let a = beta.sin() / (beta + phi).sin();
    let r = r0 * a.powi((i + k) as i32);
    let phase = (i as f64 - k as f64) * phi;
    Vector3::new(0.0, r * phase.cos(), r * phase.sin())
}

/// The nodes of a spiral drawing, their names and their numbers by (i, k).
type Spiral = (
    Vec<Vector3<f64>>,
    Vec<String>,
    HashMap<(usize, usize), usize>,
);

/// The nodes n_ik, i + k ≤ q, numbered row by row (i, then k), and their names.
fn spiral_nodes(q: usize, phi: f64) -> Spiral {
    let (mut nodes, mut names, mut index) = (Vec::new(), Vec::new(), HashMap::new());
    for i in 0..=q {
        for k in 0..=(q - i) {
            index.insert((i, k), nodes.len());
            nodes.push(spiral_node(i, k, 1.0, BETA, phi));
            names.push(format!("n{i}{k}"));
        }
    }
    (nodes, names, index)
}

/// The spiral of order `q − i`: members n_ik → n_i(k+1), k < q − i.
fn spiral_members(q: usize, i: usize, index: &HashMap<(usize, usize), usize>) -> Vec<[usize; 2]> {
    (0..q - i)
        .map(|k| [index[&(i, k)], index[&(i, k + 1)]])
        .collect()
}

/// The spiral colours, order 4 first.
const SPIRAL_COLORS: [(u8, u8, u8); 5] = [
    BLUE,
    RED,
    (0x2c, 0xa0, 0x2c),
    (0x94, 0x67, 0xbd),
    (0xff, 0x7f, 0x0e),
];

/// Fig. 4.1: the Michell spiral of complexity 4 (φ = π/8, β = π/6): n₀₀ … n₀₄ and the
/// radii from the origin to each node.
pub fn fig_4_1(_: &Ctx) -> Result<Drawn> {
    let q = 4;
    let (mut nodes, mut names, index) = spiral_nodes(q, PI / 8.0);
    let spiral = spiral_members(q, 0, &index);
    let origin = nodes.len();
    nodes.push(Vector3::zeros());
    names.push("origin".into());
    let radii = (0..=q).map(|k| [origin, index[&(0, k)]]).collect();
    let groups = [
        Group::new("spiral n00 … n04", BLUE, spiral),
        Group::new("radii r0 … r4", GREY, radii),
    ];
    let mut fig = StructureFigure::new(&[("beta", "rad"), ("phi", "rad")]);
    fig.node_labels = names;
    let extra = vec![BETA.into(), (PI / 8.0).into()];
    fig.add(
        "Michell spiral, q = 4, φ = π/8, β = π/6",
        View::Side,
        &nodes,
        &groups,
        &no_forces,
        extra,
    );
    Ok(fig.finish())
}

/// Fig. 4.2: the Michell spirals of order 4, 3, 2, 1 and 0 (φ = π/8, β = π/6): the spiral of
/// order q − i joins n_i0 … n_i(q−i); order 0 is the node n₄₀ alone.
pub fn fig_4_2(_: &Ctx) -> Result<Drawn> {
    let q = 4;
    let (nodes, names, index) = spiral_nodes(q, PI / 8.0);
    let groups: Vec<Group> = (0..q)
        .map(|i| {
            let label = format!("order {} (n{i}0 …)", q - i);
            Group::new(label, SPIRAL_COLORS[i], spiral_members(q, i, &index))
        })
        .collect();
    let mut fig = StructureFigure::new(&[("beta", "rad"), ("phi", "rad")]);
    fig.node_labels = names;
    let extra = vec![BETA.into(), (PI / 8.0).into()];
    let title = "Michell spirals of order 0–4, φ = π/8, β = π/6";
    fig.add(title, View::Side, &nodes, &groups, &no_forces, extra);
    let tip = View::Side.project(&nodes[index[&(q, 0)]]);
    let panel = fig.panels.last_mut().expect("just added");
    panel.series.push(
        Series::new(format!("order 0 (n{q}0)"), vec![tip, tip])
            .with_markers()
            .with_color(SPIRAL_COLORS[q]),
    );
    Ok(fig.finish())
}

/// The planar truss of complexity 4 (φ = π/8), analysed under the tip load at direction
/// `theta` from ι̂₂ towards ι̂₃ in the (ι̂₂, ι̂₃) plane.
pub fn planar_under(theta: f64) -> Result<MichellAnalysis> {
    let mut req = AnalysisRequest::new(MichellParams::planar(4, 1.0, BETA, PI / 8.0));
    let theta = theta.rem_euclid(2.0 * PI);
    // w = w₀ [cos φ sin γ, sin φ sin γ, cos γ] = w₀ [0, cos θ, sin θ]
    (req.azimuth, req.polar) = if theta <= 0.5 * PI {
        (0.5 * PI, 0.5 * PI - theta)
    } else if theta <= 1.5 * PI {
        (-0.5 * PI, theta - 0.5 * PI)
    } else {
        (0.5 * PI, 2.5 * PI - theta)
    };
    Ok(MichellAnalysis::run(&req)?)
}

/// The members of the U spiral (n_ik → n_(i+1)k) and of the D spiral (n_ik → n_i(k+1)).
fn families(a: &MichellAnalysis) -> [Vec<[usize; 2]>; 2] {
    let (mut up, mut down) = (Vec::new(), Vec::new());
    for m in a.truss.members() {
        match m.branch {
            Branch::Down => down.push([m.parent, m.child]),
            _ => up.push([m.parent, m.child]),
        }
    }
    [up, down]
}

/// Fig. 4.3: the Michell topology of complexity 4 (φ = π/8, β = π/6): the m_ik and their
/// conjugates.
pub fn fig_4_3(_: &Ctx) -> Result<Drawn> {
    let a = planar_under(1.5 * PI)?;
    let [up, down] = families(&a);
    let members = up.into_iter().chain(down).collect();
    let groups = [Group::new("members", (0x30, 0x30, 0x30), members)];
    let mut fig = StructureFigure::new(&TRUSS_COLUMNS);
    let title = "Michell topology, q = 4, φ = π/8, β = π/6";
    fig.add(
        title,
        View::Side,
        &positions(&a),
        &groups,
        &no_forces,
        truss_extra(&a),
    );
    Ok(fig.finish())
}

/// The regions of Fig. 4.4 (rad, from ι̂₂ towards ι̂₃): the blue one [π + β, 2π − β] (D spiral
/// compressed, U in tension) and the red one [β, π − β] (the reverse).
pub fn force_regions(beta: f64) -> [(f64, f64); 2] {
    [(PI + beta, 2.0 * PI - beta), (beta, PI - beta)]
}

/// A fan of directions [from, to] of radius `r` at `tip`.
fn fan(tip: (f64, f64), (from, to): (f64, f64), r: f64) -> Vec<(f64, f64)> {
    let mut pts = vec![tip];
    pts.extend((0..=24).map(|k| {
        let t = from + (to - from) * k as f64 / 24.0;
        (tip.0 + r * t.cos(), tip.1 + r * t.sin())
    }));
    pts.push(tip);
    pts
}

/// Fig. 4.4: the force regions of the planar truss of complexity 4: the U spiral red, the D
/// spiral blue, the regions of the load direction as fans at the tip; the data holds each
/// member's force under the load along −ι̂₃ (θ = 3π/2, in the blue region) and the regions.
pub fn fig_4_4(_: &Ctx) -> Result<Drawn> {
    let a = planar_under(1.5 * PI)?;
    let [up, down] = families(&a);
    let groups = [
        Group::new("U spiral (red members)", RED, up),
        Group::new("D spiral (blue members)", BLUE, down),
    ];
    let [blue, red] = force_regions(BETA);
    let mut fig = StructureFigure::new(&[
        ("load_direction", "rad"),
        ("blue_region_from", "rad"),
        ("blue_region_to", "rad"),
        ("red_region_from", "rad"),
        ("red_region_to", "rad"),
    ]);
    let extra = vec![
        (1.5 * PI).into(),
        blue.0.into(),
        blue.1.into(),
        red.0.into(),
        red.1.into(),
    ];
    let forces = forces_of(&a);
    let force = |_: usize, _: usize, e: [usize; 2]| forces.get(&e).copied();
    let nodes = positions(&a);
    fig.add(
        "q = 4: force regions of the tip load θ₀₀",
        View::Side,
        &nodes,
        &groups,
        &force,
        extra,
    );
    let tip = View::Side.project(&nodes[0]);
    let panel = fig.panels.last_mut().expect("just added");
    let (light_blue, light_red) = ((0x7f, 0xb2, 0xe0), (0xf0, 0x90, 0x90));
    panel
        .series
        .push(Series::new("blue region [π+β, 2π−β]", fan(tip, blue, 0.3)).with_color(light_blue));
    panel.series.push(
        Series::new("red region [β, π−β] (dashed)", fan(tip, red, 0.3))
            .with_color(light_red)
            .dashed(),
    );
    Ok(fig.finish())
}

/// Figs. 4.6–4.7: the cylindrical truss of complexity 4, δ = r₀/4, φ = π/8.
pub fn fig_4_6(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::cylindrical(4, 1.0, BETA, PI / 8.0, 0.25);
    truss_figure(p, &[(View::Side, "side (y–z)"), (View::Top, "top (y–x)")])
}

/// Fig. 4.7: isometric view of Fig. 4.6's truss.
pub fn fig_4_7(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::cylindrical(4, 1.0, BETA, PI / 8.0, 0.25);
    truss_figure(p, &[(View::Iso, "q = 4, δ = 0.25, isometric")])
}

/// Fig. 4.8: the segmentation angle ε on the spherical truss of complexity 1 (ε = π/12).
pub fn fig_4_8(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::spherical(1, 1.0, BETA, PI / 16.0, PI / 12.0);
    truss_figure(
        p,
        &[
            (View::Xy, "q = 1, ε = π/12 (x–y)"),
            (View::Iso, "isometric"),
        ],
    )
}

/// The colour of height class Z (or of a member between classes, its mean).
fn height_color(z: f64) -> (u8, u8, u8) {
    if z <= -1.5 {
        (0x08, 0x30, 0x8c)
    } else if z < 0.0 {
        (0x6b, 0xae, 0xd6)
    } else if z == 0.0 {
        (0x40, 0x40, 0x40)
    } else if z < 1.5 {
        (0xfd, 0x8d, 0x3c)
    } else {
        (0xbd, 0x00, 0x26)
    }
}

/// Fig. 4.9: the spherical truss of complexity 2 (φ = π/16, ε = π/12) from above (x–y),
/// coloured by height: each node by its class Z = U − D (its height above the ι̂₁ι̂₂ plane
/// grows with Z), each member by the mean Z of its ends.
pub fn fig_4_9(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::spherical(2, 1.0, BETA, PI / 16.0, PI / 12.0);
    let a = analysed(p)?;
    let z_of: Vec<i64> = a
        .report
        .nodes
        .iter()
        .map(|n| n.index[0] as i64 - n.index[1] as i64)
        .collect();
    let mut by_mean: std::collections::BTreeMap<i64, Vec<[usize; 2]>> = Default::default();
    for m in a.truss.members() {
        by_mean
            .entry(z_of[m.parent] + z_of[m.child])
            .or_default()
            .push([m.parent, m.child]);
    }
    let groups: Vec<Group> = by_mean
        .into_iter()
        .map(|(twice, edges)| {
            let mean = twice as f64 / 2.0;
            Group::new(
                format!("members, mean Z = {mean}"),
                height_color(mean),
                edges,
            )
        })
        .collect();
    let mut fig = StructureFigure::new(&TRUSS_COLUMNS);
    fig.node_labels = z_of.iter().map(|z| format!("Z = {z}")).collect();
    let forces = forces_of(&a);
    let force = |_: usize, _: usize, e: [usize; 2]| forces.get(&e).copied();
    let nodes = positions(&a);
    fig.add(
        "q = 2, ε = π/12 (x–y), coloured by height class Z",
        View::Xy,
        &nodes,
        &groups,
        &force,
        truss_extra(&a),
    );
    let panel = fig.panels.last_mut().expect("just added");
    let mut classes: Vec<i64> = z_of.clone();
    classes.sort_unstable();
    classes.dedup();
    // one marker per node (a polyline of one point twice: no line), labelled once a class
    for z in classes {
        let members = nodes.iter().zip(&z_of).filter(|&(_, &c)| c == z);
        for (k, (n, _)) in members.enumerate() {
            let p = View::Xy.project(n);
            let label = if k == 0 {
                format!("nodes, Z = {z}")
            } else {
                String::new()
            };
            let marker = Series::new(label, vec![p, p]).with_markers();
            panel.series.push(marker.with_color(height_color(z as f64)));
        }
    }
    Ok(fig.finish())
}

/// Fig. 4.10: isometric view of Fig. 4.9's truss.
pub fn fig_4_10(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::spherical(2, 1.0, BETA, PI / 16.0, PI / 12.0);
    truss_figure(p, &[(View::Iso, "q = 2, ε = π/12, isometric")])
}

/// Fig. 4.11: y–z and x–y views of the spherical truss of complexity 4, φ = π/10, ε = π/12.
pub fn fig_4_11(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::spherical(4, 1.0, BETA, PI / 10.0, PI / 12.0);
    truss_figure(p, &[(View::Side, "y–z"), (View::Xy, "x–y")])
}

/// Fig. 4.12: isometric view of Fig. 4.11's truss.
pub fn fig_4_12(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::spherical(4, 1.0, BETA, PI / 10.0, PI / 12.0);
    truss_figure(p, &[(View::Iso, "q = 4, ε = π/12, isometric")])
}

/// Fig. 4.13: the cylindrical truss of complexity 1 (δ = 0.25, φ = π/8) under the tip load
/// along −ι̂₃: m₁₀₁₀ and m₁₀₀₁ in tension (red), m₀₁₀₀ in compression (blue), eq. 4.18–4.20.
pub fn fig_4_13(_: &Ctx) -> Result<Drawn> {
    let p = MichellParams::cylindrical(1, 1.0, BETA, PI / 8.0, 0.25);
    truss_figure(
        p,
        &[
            (View::Iso, "q = 1, red tension, blue compression"),
            (View::Side, "side (y–z)"),
        ],
    )
}

/// The q = 1 cylindrical truss of §4.4.1 (δ = 0.25, φ = π/8) whose tip members m₁₀₁₀,
/// m₁₀₀₁, m₀₁₀₀ (members 0, 1, 2) are mapped.
fn sign_map(ctx: &Ctx, member: usize) -> Result<SignMap> {
    let truss =
        michell3d::MichellTruss::new(MichellParams::cylindrical(1, 1.0, BETA, PI / 8.0, 0.25))?;
    let (na, np) = if ctx.quick() { (73, 37) } else { (361, 181) };
    let maps = sweeps::grids::sign_maps(
        &truss,
        &[member],
        1000.0,
        AngleGrid::new(0.0, 2.0 * PI, na),
        AngleGrid::new(0.0, PI, np),
        Method::Recursive,
    )?;
    Ok(maps.into_iter().next().expect("one member asked, one map"))
}

/// A sign map drawn as vertical runs: for every azimuth column, each run of polar angles of
/// one sign is a segment, red for tension and blue for compression.
fn sign_map_panel(map: &SignMap, name: &str) -> Panel {
    let mut panel = Panel::new(
        format!("sign of $λ{name}$ (red tension, blue compression)"),
        "load azimuth φ [rad]",
        "load polar angle γ [rad]",
    );
    let mut labelled = [false; 2];
    let half = 0.5 * (map.polar.end - map.polar.start) / (map.polar.n.max(2) - 1) as f64;
    for ia in 0..map.azimuth.n {
        let x = map.azimuth.at(ia);
        let mut ip = 0;
        while ip < map.polar.n {
            let sign = map.sign(ip, ia);
            let start = ip;
            while ip < map.polar.n && map.sign(ip, ia) == sign {
                ip += 1;
            }
            if sign == 0 {
                continue;
            }
            // each grid point stands for half a cell either side
            let (lo, hi) = (
                (map.polar.at(start) - half).max(map.polar.start),
                (map.polar.at(ip - 1) + half).min(map.polar.end),
            );
            let slot = usize::from(sign < 0);
            let label = match (labelled[slot], sign > 0) {
                (true, _) => "",
                (false, true) => "tension",
                (false, false) => "compression",
            };
            labelled[slot] = true;
            // the diverging map's ends: they differ in lightness, so the signs differ in print
            let color = diverging_color(f64::from(sign), 1.0);
            panel = panel.series(Series::new(label, vec![(x, lo), (x, hi)]).with_color(color));
        }
    }
    panel
}

/// A sign map drawn, its data the grid: azimuth, polar angle and the sign (+1 tension, −1
/// compression, 0 none).
fn sign_map_figure(ctx: &Ctx, member: usize, name: &str) -> Result<Drawn> {
    let map = sign_map(ctx, member)?;
    let mut data = FigureData::new(&[("azimuth", "rad"), ("polar", "rad"), ("sign", "")]);
    for ia in 0..map.azimuth.n {
        for ip in 0..map.polar.n {
            data.push(vec![
                map.azimuth.at(ia).into(),
                map.polar.at(ip).into(),
                Value::Integer(map.sign(ip, ia).into()),
            ]);
        }
    }
    Ok(Drawn::new(
        Figure::new(vec![sign_map_panel(&map, name)]),
        data,
    ))
}

/// Figs. 4.14–4.16: the sign of λ₁₀₁₀, λ₁₀₀₁, λ₀₁₀₀ over the load direction.
pub fn fig_4_14(ctx: &Ctx) -> Result<Drawn> {
    sign_map_figure(ctx, 0, "1010")
}

/// Fig. 4.15: λ₁₀₀₁.
pub fn fig_4_15(ctx: &Ctx) -> Result<Drawn> {
    sign_map_figure(ctx, 1, "1001")
}

/// Fig. 4.16: λ₀₁₀₀.
pub fn fig_4_16(ctx: &Ctx) -> Result<Drawn> {
    sign_map_figure(ctx, 2, "0100")
}

/// Fig. 4.18: yield + buckling mass against complexity, planar and δ = 0.1, 0.25, 0.5 — two
/// `michell` sweeps (r₀ = 1, β = π/6, φ = π/q, 1 kN along −ι̂₃, steel), CSVs kept.
pub fn fig_4_18(ctx: &Ctx) -> Result<Drawn> {
    let max_q = if ctx.quick() { 8 } else { 35 };
    let common = "study = \"michell\"\n[derived]\nphi = \"pi / complexity\"\n\
         [output]\ncolumns = [\"mass_kg.yield_buckling\", \"normalized_yield_mass\"]\n";
    let axis = format!("complexity = {{ from = 2, to = {max_q}, step = 1 }}\n");
    let planar = format!("{common}[fixed]\nbeta = \"pi/6\"\nplanar = true\n[axes]\n{axis}");
    let cyl =
        format!("{common}[fixed]\nbeta = \"pi/6\"\n[axes]\ncylindrical = [0.1, 0.25, 0.5]\n{axis}");
    let y = "mass_kg.yield_buckling";
    let mut curves = ctx.sweep("fig_4_18_planar", &planar, "complexity", y, "")?;
    curves.extend(ctx.sweep("fig_4_18", &cyl, "complexity", y, "cylindrical")?);
    let mut panel = Panel::new(
        "steel yield + buckling mass, w0 = 1 kN (Fig. 4.18)",
        "complexity q [–]",
        "mass [kg]",
    );
    for (group, pts) in curves {
        let label = if group.is_empty() {
            "planar".to_string()
        } else {
            format!("δ = {group}")
        };
        panel = panel.series(Series::new(label, pts).with_markers());
    }
    Ok(Drawn::plot(
        Figure::new(vec![panel]),
        ("complexity", ""),
        ("mass", "kg"),
    ))
}

/// Fig. 4.19: the extra strings of §4.6 on the cylindrical trusses of complexity 2 and 3.
pub fn fig_4_19(_: &Ctx) -> Result<Drawn> {
    let mut fig = StructureFigure::new(&[("complexity", "")]);
    for q in [2, 3] {
        let params = MichellParams::cylindrical(q, 1.0, BETA, PI / 8.0, 0.25);
        let truss = michell3d::MichellTruss::new(params)?;
        let extra = ExtraStrings::new(&truss)?;
        let nodes: Vec<Vector3<f64>> = truss.nodes().iter().map(|n| n.position).collect();
        let members = truss
            .members()
            .iter()
            .map(|m| [m.parent, m.child])
            .collect();
        let groups = [
            Group::new("truss members", BLUE, members),
            Group::new("extra strings", RED, extra.pairs().to_vec()),
        ];
        let title = format!("q = {q}");
        fig.add(
            &title,
            View::Iso,
            &nodes,
            &groups,
            &no_forces,
            vec![q.into()],
        );
    }
    Ok(fig.finish())
}

/// Fig. 4.20: the force densities of the members of the q = 2 cylindrical truss over
/// γ ∈ [0, 2π] with 10 N (low) and 5 kN (high) in the extra strings: the thesis plots force
/// density, q = force / length (N/m, tension positive).
pub fn fig_4_20(ctx: &Ctx) -> Result<Drawn> {
    let truss =
        michell3d::MichellTruss::new(MichellParams::cylindrical(2, 1.0, BETA, PI / 8.0, 0.25))?;
    let extra = ExtraStrings::new(&truss)?;
    let base_len = truss.lengths();
    let nodes = truss.nodes();
    let extra_len: Vec<f64> = extra
        .pairs()
        .iter()
        .map(|&[a, b]| (nodes[b].position - nodes[a].position).norm())
        .collect();
    let n = if ctx.quick() { 73 } else { 721 };
    let mut panels = Vec::new();
    for (prestress, name) in [(10.0, "low"), (5000.0, "high")] {
        let grid = AngleGrid::new(0.0, 2.0 * PI, n);
        let sweep = gamma_sweep(
            &truss,
            &extra,
            1000.0,
            0.0,
            grid,
            prestress,
            Method::Recursive,
        )?;
        let mut panel = Panel::new(
            format!("{name} prestress: {prestress} N per extra string"),
            "load polar angle γ [rad]",
            "force density q [N/m]",
        );
        let curves = [
            (&sweep.base_force, &base_len, "", None),
            (&sweep.extra_force, &extra_len, "extra strings", Some(GREY)),
        ];
        for (forces, lengths, label, color) in curves {
            for (j, l) in lengths.iter().enumerate() {
                let pts = sweep
                    .polar
                    .iter()
                    .zip(forces.iter())
                    .map(|(&g, f)| (g, f[j] / l));
                // each truss member its own style (colour, dash, marker) and legend entry
                let label = match color {
                    None => format!("member {}", j + 1),
                    Some(_) if j == 0 => label.to_string(),
                    Some(_) => String::new(),
                };
                let s = Series::new(label, pts.collect());
                panel = panel.series(match color {
                    Some(c) => s.with_color(c),
                    None => s,
                });
            }
        }
        panels.push(panel);
    }
    Ok(Drawn::plot(
        Figure::new(panels),
        ("gamma", "rad"),
        ("force_density", "N/m"),
    ))
}

/// Fig. 4.18 from the rows of the Michell mass table ([`michell3d::mass_vs_complexity`], the
/// `michell_table` request): yield + buckling mass against complexity, planar and one curve
/// per δ of [`michell3d::complexity::FIG_4_18_DELTAS`].
pub fn mass_table_figure(
    request: &michell3d::MichellTableRequest,
    rows: &[michell3d::MassRow],
) -> Figure {
    let series = |delta: f64, label: String| {
        let points = rows
            .iter()
            .filter(|r| r.delta == delta)
            .map(|r| (r.complexity as f64, r.yield_buckling_mass_kg))
            .collect();
        Series::new(label, points)
    };
    let mut all = vec![series(0.0, "planar".into())];
    all.extend(
        michell3d::complexity::FIG_4_18_DELTAS
            .iter()
            .map(|&d| series(d, format!("δ = {d}"))),
    );
    let mut panel = Panel::new(
        format!(
            "{} yield + buckling mass, w0 = {} N (Fig. 4.18)",
            request.material, request.load
        ),
        "complexity q [–]",
        "mass [kg]",
    );
    panel.series = all;
    Figure::new(vec![panel])
}
