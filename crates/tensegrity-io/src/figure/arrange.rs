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

use super::layout::{
    legend_entries, legend_rows, place_with, Glyph, Legend, PanelLayout, PlaceOptions, Rect,
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
    let legend = shared.map(|entries| {
        let (columns, scale, (lw, lh)) = legend_rows(&entries, w - 16.0, 0.25 * (h - band));
        Legend {
            rect: Rect {
                x: 0.5 * (w - lw).max(0.0),
                y: h - lh - 4.0,
                w: lw,
                h: lh,
            },
            entries,
            columns,
            scale,
        }
    });
    let below = legend.as_ref().map_or(0.0, |l| l.rect.h + 6.0);
    let panel_w = w / n as f64;
    let areas: Vec<Rect> = (0..figure.panels.len())
        .map(|k| Rect {
            x: k as f64 * panel_w,
            y: band,
            w: panel_w,
            h: h - band - below,
        })
        .collect();
    let options = PlaceOptions {
        scale: None,
        shared_legend: legend.is_some(),
    };
    let mut panels: Vec<PanelLayout> = figure
        .panels
        .iter()
        .zip(&areas)
        .map(|(p, &a)| place_with(p, a, options))
        .collect();
    let scales: Vec<f64> = panels.iter().filter_map(|l| l.equal_scale).collect();
    if scales.len() > 1 && !figure.independent_scales {
        let s = scales.iter().copied().fold(f64::INFINITY, f64::min);
        for ((layout, panel), &area) in panels.iter_mut().zip(&figure.panels).zip(&areas) {
            if layout.equal_scale.is_some() {
                *layout = place_with(
                    panel,
                    area,
                    PlaceOptions {
                        scale: Some(s),
                        ..options
                    },
                );
            }
        }
    }
    Arranged { panels, legend }
}
