//! The panels of a figure placed together: side by side on the page below the NOT VALID
//! band, with one scale across their structure drawings and one legend for all.
//!
//! - **One scale.** Every panel with equal axes is first placed alone, which gives the largest
//!   scale s_k (px per drawing unit) at which its drawing fits its room; all are then drawn at
//!   s = min_k s_k, so a metre is as long in every panel and a picture can be compared with
//!   its neighbour (unless the figure says otherwise, [`Figure::independent_scales`]).
//! - **One legend.** When a figure has several panels and no label stands for two different
//!   glyphs, the legend is the union of the panels' entries, drawn once in rows under the
//!   panels (as many columns as fit the page's width), instead of once per panel, where at a
//!   journal's column width it would take the room of the drawings.
//! - **A small page** ([`text_scale`] < 1: a 6 × 4 cm figure) has its text and gaps set
//!   smaller, the same in every panel; its legend goes in rows under the panels or in a
//!   column right of them, whichever leaves the plots the most room; a y-axis label that the
//!   panel to the left already shows is left out.

use super::layout::{
    legend_columns, legend_entries, legend_geometry, legend_rows, legend_scales, legend_size,
    place_with, text_scale, Glyph, Legend, PanelLayout, PlaceOptions, Rect,
};
use super::Figure;

/// A figure placed: each panel's layout, and the figure's legend if it has one of its own.
#[derive(Debug, Clone, PartialEq)]
pub struct Arranged {
    /// The panels' layouts, in order.
    pub panels: Vec<PanelLayout>,
    /// The figure's legend (under the panels), when shared.
    pub legend: Option<Legend>,
}

/// The union of the panels' legend entries, or `None` when a label stands for two different
/// glyphs (then each panel keeps its own).
fn shared_entries(figure: &Figure) -> Option<Vec<(Glyph, String)>> {
    let mut out: Vec<(Glyph, String)> = Vec::new();
    for panel in &figure.panels {
        for (glyph, label) in legend_entries(panel) {
            match out.iter().find(|(_, l)| *l == label) {
                Some((g, _)) if *g != glyph => return None,
                Some(_) => {}
                None => out.push((glyph, label)),
            }
        }
    }
    Some(out)
}

/// Places `figure` on a page of `size` CSS pixels whose top `band` px are taken (the NOT
/// VALID mark).
///
/// ```
/// use tensegrity_io::figure::{arrange::arrange, Figure, Panel, Series};
/// let bar = |len: f64| {
///     Panel::new("bar", "x [m]", "z [m]")
///         .with_equal_axes()
///         .series(Series::new("bars", vec![(0.0, 0.0), (len, 0.5 * len)]))
/// };
/// let a = arrange(&Figure::new(vec![bar(1.0), bar(2.0)]), (800.0, 300.0), 0.0);
/// // one scale: the longer bar's panel is twice as wide
/// let (s0, s1) = (a.panels[0].scales().0, a.panels[1].scales().0);
/// assert!((s0 / s1 - 1.0).abs() < 1e-9);
/// // one legend, under the panels
/// assert!(a.panels.iter().all(|p| p.legend.is_none()));
/// assert!(a.legend.unwrap().rect.y > a.panels[0].plot.y + a.panels[0].plot.h);
/// ```
pub fn arrange(figure: &Figure, (w, h): (f64, f64), band: f64) -> Arranged {
    let n = figure.panels.len().max(1);
    let shared = if n > 1 {
        shared_entries(figure).filter(|e| !e.is_empty())
    } else {
        None
    };
    // a small page sets its text and gaps smaller (the same in every panel)
    let k = text_scale(w / n as f64, h - band);
    let Some(entries) = shared else {
        return Arranged {
            panels: place_panels(figure, (0.0, w), (band, h), false, k),
            legend: None,
        };
    };
    let g = legend_geometry(k);
    // the legend in rows under the panels, `columns` across, at `scale`
    let under = |columns: usize, scale: f64| {
        let (lw, lh) = legend_size(&entries, columns, scale, g);
        let legend = Legend {
            rect: Rect {
                x: 0.5 * (w - lw).max(0.0),
                y: h - lh - 4.0 * k,
                w: lw,
                h: lh,
            },
            entries: entries.clone(),
            columns,
            scale,
            geometry: g,
        };
        let panels = place_panels(figure, (0.0, w), (band, h - lh - 6.0 * k), true, k);
        Arranged {
            panels,
            legend: Some(legend),
        }
    };
    if k >= 1.0 {
        let (columns, scale, _) = legend_rows(&entries, w - 16.0 * k, 0.25 * (h - band), k);
        return under(columns, scale);
    }
    // a small page: in rows under the panels or in a column right of them, at each scale,
    // whichever leaves the panels' plots the most room (the sum of their smaller sides)
    let room = |a: &Arranged| -> f64 { a.panels.iter().map(|p| p.plot.w.min(p.plot.h)).sum() };
    let mut best: Option<(f64, Arranged)> = None;
    let mut consider = |a: Arranged| {
        let r = room(&a);
        if best.as_ref().is_none_or(|b| r > b.0 + 1e-9) {
            best = Some((r, a));
        }
    };
    for scale in legend_scales(k) {
        consider(under(
            legend_columns(&entries, w - 16.0 * k, scale, g),
            scale,
        ));
        let (lw, lh) = legend_size(&entries, 1, scale, g);
        if lh <= h - band - 8.0 * k {
            let legend = Legend {
                rect: Rect {
                    x: w - lw - 4.0 * k,
                    y: band + 0.5 * (h - band - lh),
                    w: lw,
                    h: lh,
                },
                entries: entries.clone(),
                columns: 1,
                scale,
                geometry: g,
            };
            let panels = place_panels(figure, (0.0, w - lw - 8.0 * k), (band, h), true, k);
            consider(Arranged {
                panels,
                legend: Some(legend),
            });
        }
    }
    best.expect("a legend place").1
}

/// The panels of `figure` side by side across `x0..x1` and `y0..y1` px (with the figure's
/// legend elsewhere if `shared_legend`), at text scale `k`, their structure drawings at one
/// scale (unless the figure says otherwise).
fn place_panels(
    figure: &Figure,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    shared_legend: bool,
    k: f64,
) -> Vec<PanelLayout> {
    let panel_w = (x1 - x0) / figure.panels.len().max(1) as f64;
    let areas: Vec<Rect> = (0..figure.panels.len())
        .map(|i| Rect {
            x: x0 + i as f64 * panel_w,
            y: y0,
            w: panel_w,
            h: y1 - y0,
        })
        .collect();
    // on a small page, a y-axis label the panel to the left has already is left out
    let options: Vec<PlaceOptions> = (0..figure.panels.len())
        .map(|i| PlaceOptions {
            scale: None,
            shared_legend,
            text: k,
            no_y_label: k < 1.0
                && i > 0
                && !figure.panels[i].y_label.is_empty()
                && figure.panels[i].y_label == figure.panels[i - 1].y_label,
        })
        .collect();
    let mut panels: Vec<PanelLayout> = figure
        .panels
        .iter()
        .zip(&areas)
        .zip(&options)
        .map(|((p, &a), &o)| place_with(p, a, o))
        .collect();
    let scales: Vec<f64> = panels.iter().filter_map(|l| l.equal_scale).collect();
    if scales.len() > 1 && !figure.independent_scales {
        let s = scales.iter().copied().fold(f64::INFINITY, f64::min);
        let each = panels
            .iter_mut()
            .zip(&figure.panels)
            .zip(&areas)
            .zip(&options);
        for (((layout, panel), &area), &o) in each {
            if layout.equal_scale.is_some() {
                *layout = place_with(
                    panel,
                    area,
                    PlaceOptions {
                        scale: Some(s),
                        ..o
                    },
                );
            }
        }
    }
    panels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::layout::MIN_TEXT;
    use crate::figure::{Panel, RenderOptions, Series};

    /// Three wheels side by side on a 6 × 4 cm page: drawn (not refused), each plot box in
    /// its panel, one scale, text at its smallest, one y label, the legend clear of the plots.
    #[test]
    fn three_structure_panels_fit_a_six_by_four_cm_page() {
        let wheel = |r: f64| {
            let rim = (0..=24)
                .map(|i| {
                    let t = i as f64 * std::f64::consts::TAU / 24.0;
                    (r * t.cos(), r * t.sin())
                })
                .collect();
            Panel::new("wheel", "y [m]", "z [m]")
                .with_equal_axes()
                .series(Series::new("bars", rim))
        };
        let figure = Figure::new(vec![wheel(1.0), wheel(1.0), wheel(0.5)]);
        let options = RenderOptions::parse(Some("6x4cm"), None).unwrap();
        let (w, h) = figure.page_px(&options).unwrap();
        let a = arrange(&figure, (w, h), 0.0);
        let legend = a.legend.expect("one legend").rect;
        assert!(legend.x >= 0.0 && legend.x + legend.w <= w && legend.y + legend.h <= h);
        let s0 = a.panels[0].scales().0;
        for (i, p) in a.panels.iter().enumerate() {
            assert_eq!(p.text, MIN_TEXT);
            let (b, area) = (p.plot, p.area);
            assert!(
                b.x >= area.x && b.x + b.w <= area.x + area.w,
                "{b:?} in {area:?}"
            );
            assert!(
                b.y >= area.y && b.y + b.h <= area.y + area.h,
                "{b:?} in {area:?}"
            );
            // the half-size wheel at the same scale: half as wide
            assert!(b.w >= if i < 2 { 30.0 } else { 15.0 }, "{b:?}");
            assert!((p.scales().0 / s0 - 1.0).abs() < 1e-9);
            assert_eq!(p.y_label.text.lines.is_empty(), i > 0);
            let apart = legend.y >= b.y + b.h || legend.x >= b.x + b.w;
            assert!(apart, "legend {legend:?} over plot {b:?}");
        }
    }
}
