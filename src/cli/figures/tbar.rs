//! The T-bar figures of chapter 5: a single tread (Fig. 5.1), the wheel (Fig. 5.2) and the
//! extended wheel (Fig. 5.3), drawn from [`tbar_wheel::drawing::polylines`] (the drawing of
//! `tensegrity tbar --svg`), on the cylindrical q = 2 truss (β = π/6, φ = π/8, δ = 0.25).

use super::draw::{drawing_figure, BLUE, RED};
use super::Ctx;
use anyhow::Result;
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

fn figure(layout: Layout, views: &[(View, &str)]) -> Result<Figure> {
    let michell = MichellParams::cylindrical(2, 1.0, FRAC_PI_6, PI / 8.0, 0.25);
    let g = TbarGeometry::new(TbarParams::tread(michell).with_layout(layout))?;
    let panels = views.iter().map(|&(v, t)| panel(&g, v, t)).collect();
    Ok(drawing_figure(panels))
}

/// Fig. 5.1: one tread.
pub fn fig_5_1(_: &Ctx) -> Result<Figure> {
    figure(
        Layout::Tread,
        &[(View::Side, "T-bar tread, side"), (View::Top, "top")],
    )
}

/// Fig. 5.2: the wheel.
pub fn fig_5_2(_: &Ctx) -> Result<Figure> {
    figure(Layout::Wheel, &[(View::Side, "T-bar wheel, side")])
}

/// Fig. 5.3: the extended wheel (a copy 0.5 m along ι̂₁).
pub fn fig_5_3(_: &Ctx) -> Result<Figure> {
    figure(
        Layout::Extended { offset: 0.5 },
        &[
            (View::Side, "extended T-bar wheel, side"),
            (View::Top, "top"),
        ],
    )
}
