//! The T-bar figures of chapter 5: a single tread (Fig. 5.1), the wheel (Fig. 5.2) and the
//! extended wheel (Fig. 5.3, a copy 0.5 m along ι̂₁) on the cylindrical q = 2 truss
//! (β = π/6, φ = π/8, δ = 0.25), strings red and bars blue, and [`side_and_top`], the side
//! and top views of any T-bar geometry (the drawing of the `tbar` command). Each is drawn
//! from the projected line segments of [`tbar_wheel::drawing::polylines`]: side (ι̂₂, ι̂₃)
//! and top (ι̂₂, ι̂₁).

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
        View::Side => "ι3 [m]",
        View::Top => "ι1 [m]",
    };
    let mut p = Panel::new(title, "ι2 [m]", y);
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

/// The drawing of `layout` in `views`; its data the geometry's nodes (labelled by their
/// tuples), bars and strings per panel (no forces: the drawing shows the geometry).
fn figure(layout: Layout, views: &[(View, &str)]) -> Result<Drawn> {
    let michell = MichellParams::cylindrical(2, 1.0, FRAC_PI_6, PI / 8.0, 0.25);
    let g = TbarGeometry::new(TbarParams::tread(michell).with_layout(layout))?;
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
            .fold(Panel::new(title, "ι2 [m]", y), |p, l| {
                p.series(Series::new(l.label, l.points))
            })
    };
    Figure::new(vec![
        panel(View::Side, "T-bar, side view", "ι3 [m]"),
        panel(View::Top, "T-bar, top view", "ι1 [m]"),
    ])
}
