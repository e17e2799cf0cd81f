//! The Michell-truss figures of chapter 4 (r₀ = 1, β = π/6, a 1 kN tip load along −ι̂₃,
//! steel):
//!
//! - drawings of the planar and 3-D trusses, members in tension red, in compression blue,
//!   unloaded grey ([`michell3d::MichellAnalysis::run`]): Fig. 4.2 (planar spirals q = 1…4,
//!   φ = π/8), 4.4 (planar q = 4), 4.6–4.7 (cylindrical q = 4, δ = 0.25), 4.8–4.12
//!   (spherical, ε = π/12), 4.19 (the extra strings of §4.6, [`ExtraStrings`]);
//! - Figs. 4.14–4.16: the sign of the tip members' force densities λ₁₀₁₀, λ₁₀₀₁, λ₀₁₀₀ over
//!   the load direction (azimuth φ, polar angle γ) on the q = 1 cylindrical truss
//!   ([`sweeps::grids::sign_maps`]), drawn as vertical runs of one sign per azimuth;
//! - Fig. 4.18: the yield + buckling mass against complexity q (φ = π/q), planar and
//!   δ = 0.1, 0.25, 0.5: two `michell` sweeps, their CSVs kept; [`mass_table_figure`] draws
//!   the same curves from the rows of [`michell3d::mass_vs_complexity`] (the
//!   `michell_table` request);
//! - Fig. 4.20: the member forces of the q = 2 cylindrical truss over γ ∈ [0, 2π] with 10 N
//!   and 5 kN in the extra strings ([`michell3d::extra_strings::gamma_sweep`]).

use crate::draw::{drawing_figure, structure_panel, Group, View, BLUE, GREY, RED};
use crate::driver::Context as Ctx;
use crate::error::Result;
use michell3d::extra_strings::{gamma_sweep, ExtraStrings};
use michell3d::signmap::{AngleGrid, SignMap};
use michell3d::{AnalysisRequest, MemberKind, Method, MichellAnalysis, MichellParams};
use nalgebra::Vector3;
use std::f64::consts::{FRAC_PI_6, PI};
use tensegrity_io::figure::{Figure, Panel, Series};

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

/// Panels of one truss in several views.
fn truss_figure(params: MichellParams, views: &[(View, &str)]) -> Result<Figure> {
    let a = analysed(params)?;
    let (nodes, groups) = (positions(&a), force_groups(&a));
    let panels = views
        .iter()
        .map(|&(view, title)| structure_panel(title, view, &nodes, &groups))
        .collect();
    Ok(drawing_figure(panels))
}

/// Fig. 4.2: planar Michell spirals of complexity 1 to 4, φ = π/8, β = π/6.
pub fn fig_4_2(_: &Ctx) -> Result<Figure> {
    let panels = (1..=4)
        .map(|q| {
            let a = analysed(MichellParams::planar(q, 1.0, BETA, PI / 8.0))?;
            let title = format!("q = {q}");
            Ok(structure_panel(
                title,
                View::Side,
                &positions(&a),
                &force_groups(&a),
            ))
        })
        .collect::<Result<Vec<Panel>>>()?;
    Ok(drawing_figure(panels))
}

/// Fig. 4.4: the planar truss of complexity 4 under the tip load, tension and compression.
pub fn fig_4_4(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::planar(4, 1.0, BETA, PI / 8.0);
    truss_figure(p, &[(View::Side, "q = 4, load −ι3: force regions")])
}

/// Figs. 4.6–4.7: the cylindrical truss of complexity 4, δ = r₀/4, φ = π/8.
pub fn fig_4_6(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::cylindrical(4, 1.0, BETA, PI / 8.0, 0.25);
    truss_figure(p, &[(View::Side, "side (y–z)"), (View::Top, "top (y–x)")])
}

/// Fig. 4.7: isometric view of Fig. 4.6's truss.
pub fn fig_4_7(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::cylindrical(4, 1.0, BETA, PI / 8.0, 0.25);
    truss_figure(p, &[(View::Iso, "q = 4, δ = 0.25, isometric")])
}

/// Fig. 4.8: the segmentation angle ε on the spherical truss of complexity 1 (ε = π/12).
pub fn fig_4_8(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::spherical(1, 1.0, BETA, PI / 16.0, PI / 12.0);
    truss_figure(
        p,
        &[
            (View::Xy, "q = 1, ε = π/12 (x–y)"),
            (View::Iso, "isometric"),
        ],
    )
}

/// Fig. 4.9: x–y view of the spherical truss of complexity 2, φ = π/16, ε = π/12.
pub fn fig_4_9(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::spherical(2, 1.0, BETA, PI / 16.0, PI / 12.0);
    truss_figure(p, &[(View::Xy, "q = 2, ε = π/12 (x–y)")])
}

/// Fig. 4.10: isometric view of Fig. 4.9's truss.
pub fn fig_4_10(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::spherical(2, 1.0, BETA, PI / 16.0, PI / 12.0);
    truss_figure(p, &[(View::Iso, "q = 2, ε = π/12, isometric")])
}

/// Fig. 4.11: y–z and x–y views of the spherical truss of complexity 4, φ = π/10, ε = π/12.
pub fn fig_4_11(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::spherical(4, 1.0, BETA, PI / 10.0, PI / 12.0);
    truss_figure(p, &[(View::Side, "y–z"), (View::Xy, "x–y")])
}

/// Fig. 4.12: isometric view of Fig. 4.11's truss.
pub fn fig_4_12(_: &Ctx) -> Result<Figure> {
    let p = MichellParams::spherical(4, 1.0, BETA, PI / 10.0, PI / 12.0);
    truss_figure(p, &[(View::Iso, "q = 4, ε = π/12, isometric")])
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
        format!("sign of λ{name} (red tension, blue compression)"),
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
            let color = if sign > 0 { RED } else { BLUE };
            panel = panel.series(Series::new(label, vec![(x, lo), (x, hi)]).with_color(color));
        }
    }
    panel
}

/// Figs. 4.14–4.16: the sign of λ₁₀₁₀, λ₁₀₀₁, λ₀₁₀₀ over the load direction.
pub fn fig_4_14(ctx: &Ctx) -> Result<Figure> {
    Ok(Figure::new(vec![sign_map_panel(
        &sign_map(ctx, 0)?,
        "1010",
    )]))
}

/// Fig. 4.15: λ₁₀₀₁.
pub fn fig_4_15(ctx: &Ctx) -> Result<Figure> {
    Ok(Figure::new(vec![sign_map_panel(
        &sign_map(ctx, 1)?,
        "1001",
    )]))
}

/// Fig. 4.16: λ₀₁₀₀.
pub fn fig_4_16(ctx: &Ctx) -> Result<Figure> {
    Ok(Figure::new(vec![sign_map_panel(
        &sign_map(ctx, 2)?,
        "0100",
    )]))
}

/// Fig. 4.18: yield + buckling mass against complexity, planar and δ = 0.1, 0.25, 0.5 — two
/// `michell` sweeps (r₀ = 1, β = π/6, φ = π/q, 1 kN along −ι̂₃, steel), CSVs kept.
pub fn fig_4_18(ctx: &Ctx) -> Result<Figure> {
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
        "complexity q",
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
    Ok(Figure::new(vec![panel]))
}

/// Fig. 4.19: the extra strings of §4.6 on the cylindrical trusses of complexity 2 and 3.
pub fn fig_4_19(_: &Ctx) -> Result<Figure> {
    let panels = [2, 3]
        .iter()
        .map(|&q| {
            let truss = michell3d::MichellTruss::new(MichellParams::cylindrical(
                q,
                1.0,
                BETA,
                PI / 8.0,
                0.25,
            ))?;
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
            Ok(structure_panel(
                format!("q = {q}"),
                View::Iso,
                &nodes,
                &groups,
            ))
        })
        .collect::<Result<Vec<Panel>>>()?;
    Ok(drawing_figure(panels))
}

/// Fig. 4.20: member forces of the q = 2 cylindrical truss over γ ∈ [0, 2π] with 10 N (low)
/// and 5 kN (high) in the extra strings.
pub fn fig_4_20(ctx: &Ctx) -> Result<Figure> {
    let truss =
        michell3d::MichellTruss::new(MichellParams::cylindrical(2, 1.0, BETA, PI / 8.0, 0.25))?;
    let extra = ExtraStrings::new(&truss)?;
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
            "member force [N]",
        );
        for j in 0..sweep.base_keeps_sign.len() {
            let pts = sweep
                .polar
                .iter()
                .zip(&sweep.base_force)
                .map(|(&g, f)| (g, f[j]));
            let label = if j == 0 { "truss members" } else { "" };
            panel = panel.series(Series::new(label, pts.collect()));
        }
        for j in 0..sweep.extra_keeps_sign.len() {
            let pts = sweep
                .polar
                .iter()
                .zip(&sweep.extra_force)
                .map(|(&g, f)| (g, f[j]));
            let label = if j == 0 { "extra strings" } else { "" };
            panel = panel.series(Series::new(label, pts.collect()).with_color(GREY));
        }
        panels.push(panel);
    }
    Ok(Figure::new(panels))
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
        "complexity q",
        "mass [kg]",
    );
    panel.series = all;
    Figure::new(vec![panel])
}
