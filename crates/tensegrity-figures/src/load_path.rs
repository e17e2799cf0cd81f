//! The load–displacement figure of a load path (`solve`): the load factor λ against the
//! largest node displacement at every point, the limit points marked (dark red dots), the
//! stable stretches solid blue and the unstable ones dashed red.

use tensegrity_io::figure::{Figure, Mark, MarkShape, Panel, Series};

/// One point of the curve: largest displacement (m), load factor, and whether it is stable.
pub type CurvePoint = (f64, f64, bool);

/// The figure of a path's `points` with its limit points `folds` (displacement, λ).
///
/// ```
/// use tensegrity_figures::load_path::figure;
/// let f = figure(&[(0.0, 0.0, true), (0.1, 1.0, true), (0.2, 0.8, false)], &[(0.12, 1.05)]);
/// let panel = &f.panels[0];
/// assert_eq!(panel.series.len(), 2); // a stable stretch and an unstable one
/// assert_eq!(panel.marks.len(), 1);
/// ```
pub fn figure(points: &[CurvePoint], folds: &[(f64, f64)]) -> Figure {
    let mut panel = Panel::new(
        "load path",
        "largest node displacement [m]",
        "load factor λ",
    );
    // consecutive points of one verdict make a stretch; a stretch shares its first point with
    // the end of the one before, so the curve stays connected
    let mut start = 0;
    for i in 1..=points.len() {
        let ends = i == points.len() || points[i].2 != points[start].2;
        if ends && i > start {
            let from = start.saturating_sub(usize::from(start > 0));
            let (label, color, dashed) = if points[start].2 {
                ("stable", (31, 119, 180), false)
            } else {
                ("unstable", (214, 39, 40), true)
            };
            let pts = points[from..i].iter().map(|&(x, y, _)| (x, y)).collect();
            let mut curve = Series::new(label, pts).with_color(color);
            curve.dashed = dashed;
            panel = panel.series(curve);
            start = i;
        }
    }
    panel.marks = folds
        .iter()
        .map(|&at| Mark {
            label: "limit point".into(),
            at,
            shape: MarkShape::Dot,
            color: (120, 0, 0),
        })
        .collect();
    Figure::new(vec![panel])
}
