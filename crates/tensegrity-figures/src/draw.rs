//! Line drawings of structures for the io figure module: members projected onto a plane,
//! each group of members (bars, strings, tension, compression, …) in one colour, one
//! polyline per member.
//!
//! Projections (thesis frame ι̂₁ ι̂₂ ι̂₃ = x y z): `Side` (y, z) is the plane of the wheels
//! and of the planar Michell truss; `Top` (y, x); `Xy` (x, y); `Iso` the isometric view
//! u = (y − x) cos 30°, v = z − (x + y) sin 30°.

use nalgebra::Vector3;
use tensegrity_io::figure::{Figure, Panel, Series};

/// Red: strings, tension.
pub const RED: (u8, u8, u8) = (0xd6, 0x27, 0x28);
/// Blue: bars, compression.
pub const BLUE: (u8, u8, u8) = (0x1f, 0x77, 0xb4);
/// Grey: the ground, members that carry nothing.
pub const GREY: (u8, u8, u8) = (0x80, 0x80, 0x80);

/// A projection plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum View {
    /// (y, z).
    Side,
    /// (y, x).
    Top,
    /// (x, y).
    Xy,
    /// Isometric.
    Iso,
}

impl View {
    /// The projected point.
    pub fn project(self, p: &Vector3<f64>) -> (f64, f64) {
        let (s, c) = std::f64::consts::FRAC_PI_6.sin_cos();
        match self {
            View::Side => (p.y, p.z),
            View::Top => (p.y, p.x),
            View::Xy => (p.x, p.y),
            View::Iso => ((p.y - p.x) * c, p.z - (p.x + p.y) * s),
        }
    }

    /// Axis labels.
    pub fn labels(self) -> (&'static str, &'static str) {
        match self {
            View::Side => ("ι2 [m]", "ι3 [m]"),
            View::Top => ("ι2 [m]", "ι1 [m]"),
            View::Xy => ("ι1 [m]", "ι2 [m]"),
            View::Iso => ("isometric [m]", "isometric [m]"),
        }
    }
}

/// One group of members: a legend label, a colour and the node pairs.
pub struct Group {
    /// Legend text (on the first polyline only).
    pub label: String,
    /// RGB colour.
    pub color: (u8, u8, u8),
    /// Member end nodes.
    pub edges: Vec<[usize; 2]>,
}

impl Group {
    /// A group.
    pub fn new(label: impl Into<String>, color: (u8, u8, u8), edges: Vec<[usize; 2]>) -> Self {
        Self {
            label: label.into(),
            color,
            edges,
        }
    }
}

/// A panel drawing `groups` of members between `nodes`, seen in `view`: one two-point
/// polyline per member (no joins, so no miter spikes where a walk would turn back).
pub fn structure_panel(
    title: impl Into<String>,
    view: View,
    nodes: &[Vector3<f64>],
    groups: &[Group],
) -> Panel {
    let projected: Vec<(f64, f64)> = nodes.iter().map(|p| view.project(p)).collect();
    let (x, y) = view.labels();
    let mut panel = Panel::new(title, x, y);
    for g in groups {
        for (i, &[a, b]) in g.edges.iter().enumerate() {
            let label = if i == 0 {
                g.label.clone()
            } else {
                String::new()
            };
            let points = vec![projected[a], projected[b]];
            panel = panel.series(Series::new(label, points).with_color(g.color));
        }
    }
    panel
}

/// The panels side by side, each sized to the aspect ratio of its drawing (the widest
/// extent 420 pixels), so circles stay round.
pub fn drawing_figure(panels: Vec<Panel>) -> Figure {
    let aspect = panels
        .iter()
        .map(|p| {
            let pts = p.series.iter().flat_map(|s| s.points.iter());
            let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
            for &(x, y) in pts {
                (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
            }
            if x1 > x0 && y1 > y0 {
                (y1 - y0) / (x1 - x0)
            } else {
                1.0
            }
        })
        .fold(0.0f64, f64::max);
    // the plot area is the panel less about 80 px of labels each way
    let height = (80.0 + 340.0 * aspect).clamp(220.0, 760.0) as u32;
    Figure::new(panels).with_panel_size(420, height)
}

/// A bar-and-string structure in two views, isometric and from above (x, y): bars blue,
/// strings red, to scale (a found form of `formfind`, a scene).
pub fn structure_figure(
    title: &str,
    nodes: &[Vector3<f64>],
    bars: Vec<[usize; 2]>,
    strings: Vec<[usize; 2]>,
) -> Figure {
    let groups = [
        Group::new("bars", BLUE, bars),
        Group::new("strings", RED, strings),
    ];
    let panels = [(View::Iso, "isometric"), (View::Xy, "top (x, y)")]
        .map(|(view, name)| structure_panel(format!("{title}, {name}"), view, nodes, &groups));
    drawing_figure(panels.into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_with_a_diagonal_is_one_polyline_per_member_labelled_once() {
        let nodes = [
            Vector3::new(0.0, 0.0, 0.0),
            Vector3::new(0.0, 1.0, 0.0),
            Vector3::new(0.0, 1.0, 1.0),
            Vector3::new(0.0, 0.0, 1.0),
        ];
        let groups = [
            Group::new("strings", RED, vec![[0, 1], [1, 2], [2, 3], [3, 0]]),
            Group::new("bars", BLUE, vec![[0, 2]]),
        ];
        let p = structure_panel("square", View::Side, &nodes, &groups);
        assert_eq!(p.series.len(), 5);
        assert_eq!(p.series[1].points, vec![(1.0, 0.0), (1.0, 1.0)]);
        assert_eq!(p.series[4].points, vec![(0.0, 0.0), (1.0, 1.0)]);
        assert_eq!(
            (p.series[4].color, p.series[4].label.as_str()),
            (Some(BLUE), "bars")
        );
        assert_eq!(p.series[1].label, "");
        assert_eq!(drawing_figure(vec![p]).panel_size, (420, 420));
        // isometric: ι3 straight up, ι1 and ι2 at ∓30° below the horizontal
        let (u, v) = View::Iso.project(&Vector3::new(1.0, 0.0, 0.0));
        assert!((u + 0.75f64.sqrt()).abs() < 1e-15 && (v + 0.5).abs() < 1e-15);
    }
}
