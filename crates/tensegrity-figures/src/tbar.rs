//! The T-bar figures of chapter 5: a single tread (Fig. 5.1), the wheel (Fig. 5.2) and the
//! extended wheel (Fig. 5.3, a copy 0.5 m along ι̂₁) on the cylindrical truss of complexity
//! [`FIGURE_COMPLEXITY`] = 1 (β = π/6, φ = π/8, δ = 0.25), strings red and bars blue, and
//! [`side_and_top`], the side and top views of any T-bar geometry (the drawing of the `tbar`
//! command). Each is drawn from the projected line segments of
//! [`tbar_wheel::drawing::polylines`]: side (ι̂₂, ι̂₃) and top (ι̂₂, ι̂₁).
//!
//! The thesis draws q = 2, but with every lattice member a string only q = 1 treads are
//! prestressable (`tbar --complexity 2 --beta pi/6 --phi pi/8 --cylindrical 0.25` reports
//! `prestressable: no`, and so does every q from 2 to 5 for β ∈ {π/12 … π/3}, δ ∈
//! {0.05 … 1}, either bar base, and the spherical ε ∈ {π/48, π/24, π/12}): the figures draw
//! the smallest prestressable tread, q = 1, the structure `tbar` analyses.

use crate::context::Context as Ctx;
use crate::data::{no_forces, Drawn, PanelData, StructureData};
use crate::draw::{drawing_figure, Group, BLUE, RED};
use crate::error::Result;
use michell3d::MichellParams;
use std::f64::consts::{FRAC_PI_6, PI};
use tbar_wheel::drawing::{polylines, View};
use tbar_wheel::{Layout, TbarGeometry, TbarParams};
use tensegrity_io::figure::{Figure, Panel, Series};

fn panel(g: &TbarGeometry, view: View, title: &str) -> Panel {
    let y = match view {
        View::Side => "ι₃ [m]",
        View::Top => "ι₁ [m]",
    };
    let mut p = Panel::new(title, "ι₂ [m]", y);
    let mut colour = RED;
    for line in polylines(g, view) {
        // the strings come first, then the bars (labelled "bars")
        if line.label.contains("bar") {
            colour = BLUE;
        }
        p = p.series(Series::new(line.label, line.points).with_color(colour));
    }
    p
}

/// The complexity of the treads of Figs. 5.1–5.3: the smallest (and only) prestressable one
/// (module docs).
pub const FIGURE_COMPLEXITY: usize = 1;

/// The T-bar of Figs. 5.1–5.3 in `layout`: the cylindrical truss of complexity
/// [`FIGURE_COMPLEXITY`], β = π/6, φ = π/8, δ = 0.25, r₀ = 1.
pub fn figure_params(layout: Layout) -> TbarParams {
    let michell = MichellParams::cylindrical(FIGURE_COMPLEXITY, 1.0, FRAC_PI_6, PI / 8.0, 0.25);
    TbarParams::tread(michell).with_layout(layout)
}

/// The drawing of `layout` in `views`; its data the geometry's nodes (labelled by their
/// tuples), bars and strings per panel (no forces: the drawing shows the geometry).
fn figure(layout: Layout, views: &[(View, &str)]) -> Result<Drawn> {
    let g = TbarGeometry::new(figure_params(layout))?;
    let panels = views.iter().map(|&(v, t)| panel(&g, v, t)).collect();
    let groups = [
        Group::new("bars", BLUE, g.bars.clone()),
        Group::new("strings", RED, g.strings.clone()),
    ];
    let mut data = StructureData::new(&[]);
    for (k, &(view, title)) in views.iter().enumerate() {
        let view = match view {
            View::Side => crate::draw::View::Side,
            View::Top => crate::draw::View::Top,
        };
        let p = PanelData {
            panel: (k, title),
            view,
            nodes: &g.nodes,
            groups: &groups,
            extra: vec![],
            node_labels: &g.labels,
        };
        data.panel(p, &no_forces);
    }
    Ok(Drawn::new(drawing_figure(panels), data.finish()))
}

/// Fig. 5.1: one tread.
pub fn fig_5_1(_: &Ctx) -> Result<Drawn> {
    figure(
        Layout::Tread,
        &[(View::Side, "T-bar tread, side"), (View::Top, "top")],
    )
}

/// Fig. 5.2: the wheel.
pub fn fig_5_2(_: &Ctx) -> Result<Drawn> {
    figure(Layout::Wheel, &[(View::Side, "T-bar wheel, side")])
}

/// Fig. 5.3: the extended wheel (a copy 0.5 m along ι̂₁).
pub fn fig_5_3(_: &Ctx) -> Result<Drawn> {
    figure(
        Layout::Extended { offset: 0.5 },
        &[
            (View::Side, "extended T-bar wheel, side"),
            (View::Top, "top"),
        ],
    )
}

/// The side and top views of a T-bar tread or wheel, one default-coloured series per
/// polyline of [`polylines`].
pub fn side_and_top(g: &TbarGeometry) -> Figure {
    let panel = |view: View, title: &str, y: &str| {
        polylines(g, view)
            .into_iter()
            .fold(Panel::new(title, "ι₂ [m]", y), |p, l| {
                p.series(Series::new(l.label, l.points))
            })
    };
    Figure::new(vec![
        panel(View::Side, "T-bar, side view", "ι₃ [m]"),
        panel(View::Top, "T-bar, top view", "ι₁ [m]"),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use tbar_wheel::{tbar_report, TbarRequest};

    /// Figs. 5.1–5.3 draw a structure that `tbar` reports prestressable (with the margin and
    /// minimum prestress of `tbar --beta pi/6 --phi pi/8 --cylindrical 0.25`), and one with
    /// the nodes the figures' data list.
    #[test]
    fn the_figures_draw_prestressable_treads() {
        for (number, layout, nodes) in [
            ("5.1", Layout::Tread, 6),
            ("5.2", Layout::Wheel, 32),
            ("5.3", Layout::Extended { offset: 0.5 }, 64),
        ] {
            let p = figure_params(layout);
            let r = tbar_report(&TbarRequest::new(p)).unwrap();
            assert!(r.prestressable, "Fig. {number}: {:?}", r.warnings);
            assert!(
                (r.prestress_margin - 0.221289).abs() < 1e-6,
                "Fig. {number}"
            );
            let min = r.min_prestress.unwrap();
            assert!((min - 3.235768601).abs() < 1e-8, "Fig. {number}: {min}");
            assert_eq!(r.nodes, nodes, "Fig. {number}");
            assert_eq!(TbarGeometry::new(p).unwrap().nodes.len(), nodes);
        }
        // the thesis's q = 2 tread is not prestressable: the reason the figures draw q = 1
        let mut q2 = figure_params(Layout::Tread);
        q2.michell.complexity = 2;
        assert!(!tbar_report(&TbarRequest::new(q2)).unwrap().prestressable);
    }
}
