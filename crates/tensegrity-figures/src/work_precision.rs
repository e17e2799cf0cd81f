//! The work–precision figure of the integrators ([`tensegrity_dynamics::work_precision`]:
//! every integrator on five scenes, two of them stiff): one log–log panel per scene, the
//! maximum node error (m) at the end time against the best-of-N wall time (s), one curve per
//! integrator (points with a zero error left out: nothing to draw on a log axis).

use tensegrity_dynamics::work_precision::Point;
use tensegrity_dynamics::IntegratorKind;
use tensegrity_io::figure::{Figure, Panel, Series};

/// One log–log panel per scene (in the order the points list them), one curve per
/// integrator with markers.
///
/// ```
/// use tensegrity_dynamics::work_precision::Point;
/// use tensegrity_dynamics::IntegratorKind;
/// let point = |scene, integrator, error, wall_time_s| Point {
///     scene, integrator, parameter: 1e-3, steps: 10, rhs_evals: 40, error, wall_time_s,
/// };
/// let f = tensegrity_figures::work_precision::figure(&[
///     point("dbar", IntegratorKind::Rk4, 1e-6, 1e-3),
///     point("dbar", IntegratorKind::Rk4, 1e-8, 1e-2),
///     point("dbar", IntegratorKind::Rk45, 0.0, 1e-3),
///     point("prism", IntegratorKind::Rk45, 1e-5, 2e-3),
/// ]);
/// assert_eq!(f.panels.len(), 2);
/// assert_eq!(f.panels[0].series.len(), 1); // rk45's only point has no error to draw
/// assert_eq!(f.panels[0].series[0].points, [(1e-3, 1e-6), (1e-2, 1e-8)]);
/// assert_eq!(f.panels[1].series[0].label, "rk45");
/// ```
pub fn figure(points: &[Point]) -> Figure {
    let mut scenes: Vec<&str> = points.iter().map(|p| p.scene).collect();
    scenes.dedup();
    let panels = scenes
        .iter()
        .map(|&scene| {
            let mut panel = Panel::new(scene, "wall time [s]", "max node error [m]").log_log();
            for kind in IntegratorKind::ALL {
                let curve: Vec<(f64, f64)> = points
                    .iter()
                    .filter(|p| p.scene == scene && p.integrator == kind && p.error > 0.0)
                    .map(|p| (p.wall_time_s, p.error))
                    .collect();
                if !curve.is_empty() {
                    panel = panel.series(Series::new(kind.to_string(), curve).with_markers());
                }
            }
            panel
        })
        .collect();
    Figure::new(panels)
}
