//! Structures drawn to scale, in one style: members projected onto a plane, one polyline per
//! member, on equal axes (the same pixels per metre in x and y, whatever the figure's size);
//! bars thick and dark, strings thin and drawn under the bars; optionally every member
//! coloured by its force or force density on a diverging map with a colour bar (tension
//! dashed, compression solid, so they differ in greyscale too); supports as triangles, loads
//! and reactions as arrows, node and member numbers.
//!
//! Projections (thesis frame ι̂₁ ι̂₂ ι̂₃ = x y z), each a linear map (u, v) = P p:
//! `Side` = `yz` (y, z) is the plane of the wheels and of the planar Michell truss; `Top`
//! (y, x); `Xy` (x, y); `Xz` (x, z); `Iso` the isometric view u = (y − x) cos 30°,
//! v = z − (x + y) sin 30°; `Orbit { azimuth a, elevation e }` the view from the direction
//! (cos e cos a, cos e sin a, sin e): u = −x sin a + y cos a,
//! v = −x sin e cos a − y sin e sin a + z cos e. All keep lengths along the screen axes, so a
//! drawing is to scale in the plane of a `Side`, `Top`, `Xy` or `Xz` view.
//!
//! Two entry points: [`structure_panel`] / [`structure_figure`] draw groups of members (the
//! figures: a group's colour picks its style — [`BLUE`] bars or compression thick and dark,
//! [`RED`] strings or tension thin, [`GREY`] thin), and [`drawing_panel`] /
//! [`drawing_figure_of`] draw a [`Drawing`] (nodes, bars, strings, member values, supports,
//! loads, reactions, a reference shape) in a [`Style`] (view, widths, colouring, labels).

use nalgebra::Vector3;
use std::str::FromStr;
use tensegrity_core::Structure;
use tensegrity_io::figure::{
    diverging_color, Arrow, ColorBar, Figure, Mark, MarkShape, Note, Panel, Series,
};

/// Red: strings, tension.
pub const RED: (u8, u8, u8) = (0xd6, 0x27, 0x28);
/// Blue: bars, compression (drawn in [`BAR_COLOR`]).
pub const BLUE: (u8, u8, u8) = (0x1f, 0x77, 0xb4);
/// Grey: the ground, members that carry nothing.
pub const GREY: (u8, u8, u8) = (0x80, 0x80, 0x80);
/// Bars: dark navy.
pub const BAR_COLOR: (u8, u8, u8) = (0x1b, 0x2a, 0x49);
/// Loads.
pub const LOAD_COLOR: (u8, u8, u8) = (0xe6, 0x7e, 0x00);
/// Reactions.
pub const REACTION_COLOR: (u8, u8, u8) = (0x2c, 0x8c, 0x2c);
/// Bar width (px).
pub const BAR_WIDTH: f64 = 3.0;
/// String width (px).
pub const STRING_WIDTH: f64 = 1.1;

/// A projection plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum View {
    /// (y, z), also written `yz`.
    Side,
    /// (y, x).
    Top,
    /// (x, y).
    Xy,
    /// (x, z).
    Xz,
    /// Isometric.
    Iso,
    /// Seen from azimuth and elevation (radians).
    Orbit {
        /// About z, from the x axis.
        azimuth: f64,
        /// Above the x–y plane.
        elevation: f64,
    },
}

impl View {
    /// The projected point.
    pub fn project(self, p: &Vector3<f64>) -> (f64, f64) {
        let (s, c) = std::f64::consts::FRAC_PI_6.sin_cos();
        match self {
            View::Side => (p.y, p.z),
            View::Top => (p.y, p.x),
            View::Xy => (p.x, p.y),
            View::Xz => (p.x, p.z),
            View::Iso => ((p.y - p.x) * c, p.z - (p.x + p.y) * s),
            View::Orbit { azimuth, elevation } => {
                let (sa, ca) = azimuth.sin_cos();
                let (se, ce) = elevation.sin_cos();
                (
                    -p.x * sa + p.y * ca,
                    -p.x * se * ca - p.y * se * sa + p.z * ce,
                )
            }
        }
    }

    /// Axis labels.
    pub fn labels(self) -> (String, String) {
        let pair = |a: &str, b: &str| (a.to_string(), b.to_string());
        match self {
            View::Side => pair("ι₂ [m]", "ι₃ [m]"),
            View::Top => pair("ι₂ [m]", "ι₁ [m]"),
            View::Xy => pair("ι₁ [m]", "ι₂ [m]"),
            View::Xz => pair("ι₁ [m]", "ι₃ [m]"),
            View::Iso => pair("isometric, across [m]", "isometric, up [m]"),
            View::Orbit { azimuth, elevation } => {
                let v = format!(
                    "azimuth {:.0}°, elevation {:.0}°",
                    azimuth.to_degrees(),
                    elevation.to_degrees()
                );
                (format!("{v}, across [m]"), "up [m]".to_string())
            }
        }
    }

    /// A short name: `yz`, `yx`, `xy`, `xz`, `iso` or `az 30°, el 20°`.
    pub fn name(self) -> String {
        match self {
            View::Side => "yz".into(),
            View::Top => "yx".into(),
            View::Xy => "xy".into(),
            View::Xz => "xz".into(),
            View::Iso => "iso".into(),
            View::Orbit { azimuth, elevation } => format!(
                "az {:.0}°, el {:.0}°",
                azimuth.to_degrees(),
                elevation.to_degrees()
            ),
        }
    }
}

/// The view that shows a planar structure flat: `yz` when every node has the same x, `xy`
/// the same z, `xz` the same y; `iso` otherwise.
pub fn default_view(nodes: &[Vector3<f64>]) -> View {
    let flat = |d: usize| {
        let (lo, hi) = nodes.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
            (lo.min(p[d]), hi.max(p[d]))
        });
        let size = nodes
            .iter()
            .map(|p| p.amax())
            .fold(0.0, f64::max)
            .max(1e-300);
        hi - lo <= 1e-12 * size
    };
    if flat(0) {
        View::Side
    } else if flat(2) {
        View::Xy
    } else if flat(1) {
        View::Xz
    } else {
        View::Iso
    }
}

impl FromStr for View {
    type Err = String;

    /// `iso`, `xy`, `yz` (or `side`), `xz`, `yx` (or `top`), or `AZIMUTH,ELEVATION` as
    /// angles (`30deg,20deg`, `pi/6,0.3`; a bare number is radians).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "iso" | "isometric" => Ok(View::Iso),
            "xy" => Ok(View::Xy),
            "yz" | "side" => Ok(View::Side),
            "xz" => Ok(View::Xz),
            "yx" | "top" => Ok(View::Top),
            other => {
                let (a, e) = other.split_once(',').ok_or_else(|| {
                    format!("unknown view \"{s}\": expected iso, xy, yz, xz or AZIMUTH,ELEVATION (e.g. 30deg,20deg)")
                })?;
                let azimuth = tensegrity_core::angle::parse_angle(a).map_err(|e| e.to_string())?;
                let elevation =
                    tensegrity_core::angle::parse_angle(e).map_err(|e| e.to_string())?;
                if elevation.abs() > std::f64::consts::FRAC_PI_2 + 1e-12 {
                    return Err(format!(
                        "view \"{s}\": the elevation must lie in [−90°, 90°]"
                    ));
                }
                Ok(View::Orbit { azimuth, elevation })
            }
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

/// The house style of a member of colour `color`: [`BLUE`] (bars, compression) thick in
/// [`BAR_COLOR`], [`RED`] (strings, tension) thin, anything else 1.4 px.
fn member_series(label: String, points: Vec<(f64, f64)>, color: (u8, u8, u8)) -> Series {
    match color {
        BLUE => Series::new(label, points)
            .with_color(BAR_COLOR)
            .with_width(BAR_WIDTH),
        RED => Series::new(label, points)
            .with_color(RED)
            .with_width(STRING_WIDTH),
        other => Series::new(label, points).with_color(other).with_width(1.4),
    }
}

/// A panel drawing `groups` of members between `nodes`, seen in `view`, to scale: one
/// two-point polyline per member (no joins, so no miter spikes where a walk would turn
/// back), thin members under thick ones.
pub fn structure_panel(
    title: impl Into<String>,
    view: View,
    nodes: &[Vector3<f64>],
    groups: &[Group],
) -> Panel {
    let projected: Vec<(f64, f64)> = nodes.iter().map(|p| view.project(p)).collect();
    let (x, y) = view.labels();
    let mut panel = Panel::new(title, x, y).with_equal_axes();
    for g in groups {
        for (i, &[a, b]) in g.edges.iter().enumerate() {
            let label = if i == 0 {
                g.label.clone()
            } else {
                String::new()
            };
            let points = vec![projected[a], projected[b]];
            panel = panel.series(member_series(label, points, g.color));
        }
    }
    panel.series.sort_by(|a, b| a.width.total_cmp(&b.width));
    panel
}

/// The series reordered (stably) by width: thin members under thick ones; in a drawing of
/// many members (over 400) every line is thinner by √(400/members), down to 0.4 of its
/// width, so that a dense wheel stays readable.
fn under_thick(mut panel: Panel) -> Panel {
    panel.series.sort_by(|a, b| a.width.total_cmp(&b.width));
    let n = panel.series.len() as f64;
    if n > 400.0 {
        let f = (400.0 / n).sqrt().max(0.4);
        panel.series.iter_mut().for_each(|s| s.width *= f);
    }
    panel
}

/// The panels side by side on equal axes, each sized to the aspect ratio of its drawing (the
/// widest extent 420 pixels); series in [`BLUE`] or [`RED`] get the bar or string style.
pub fn drawing_figure(panels: Vec<Panel>) -> Figure {
    let panels: Vec<Panel> = panels
        .into_iter()
        .map(|mut p| {
            p = p.with_equal_axes();
            for s in &mut p.series {
                if (s.width - 2.0).abs() < 1e-12 {
                    let styled = member_series(String::new(), Vec::new(), s.color.unwrap_or(GREY));
                    if matches!(s.color, Some(BLUE) | Some(RED)) {
                        s.color = styled.color;
                        s.width = styled.width;
                    }
                }
            }
            under_thick(p)
        })
        .collect();
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

/// A bar-and-string structure in two views, isometric and from above (x, y): bars thick and
/// dark, strings thin, to scale (a found form of `formfind`, a scene).
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

/// What colours the members of a [`Drawing`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ColorBy {
    /// Bars dark, strings red.
    #[default]
    Kind,
    /// The member force (N, tension positive).
    Force,
    /// The force density (N/m, tension positive).
    ForceDensity,
}

impl FromStr for ColorBy {
    type Err = String;

    /// `kind`, `force` or `force-density` (`q`).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "kind" | "none" => Ok(ColorBy::Kind),
            "force" => Ok(ColorBy::Force),
            "force-density" | "force_density" | "q" => Ok(ColorBy::ForceDensity),
            _ => Err(format!(
                "unknown colouring \"{s}\": expected kind, force or force-density"
            )),
        }
    }
}

/// How a [`Drawing`] is drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// The projection.
    pub view: View,
    /// Bar width (px).
    pub bar_width: f64,
    /// String width (px).
    pub string_width: f64,
    /// Member colours.
    pub color_by: ColorBy,
    /// Node numbers.
    pub node_labels: bool,
    /// Member numbers (`b0`, `s3`: bar 0, string 3).
    pub member_labels: bool,
}

impl Default for Style {
    fn default() -> Self {
        Self {
            view: View::Iso,
            bar_width: BAR_WIDTH,
            string_width: STRING_WIDTH,
            color_by: ColorBy::Kind,
            node_labels: false,
            member_labels: false,
        }
    }
}

/// A structure to draw: its members, and what to show on it.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Drawing {
    /// Node positions.
    pub nodes: Vec<Vector3<f64>>,
    /// Bars.
    pub bars: Vec<[usize; 2]>,
    /// Strings.
    pub strings: Vec<[usize; 2]>,
    /// Member forces (N), bars first then strings.
    pub force: Option<Vec<f64>>,
    /// Member force densities (N/m), bars first then strings.
    pub force_density: Option<Vec<f64>>,
    /// Supported nodes.
    pub supports: Vec<usize>,
    /// External loads (node, force in N).
    pub loads: Vec<(usize, Vector3<f64>)>,
    /// Support reactions (node, force in N).
    pub reactions: Vec<(usize, Vector3<f64>)>,
    /// A reference shape drawn thin and light under the structure (e.g. the undeformed
    /// structure under a mode shape).
    pub reference: Option<Vec<Vector3<f64>>>,
}

impl Drawing {
    /// The members, supports and loads of `structure`.
    pub fn of(structure: &Structure) -> Self {
        Self {
            nodes: structure.nodes().to_vec(),
            bars: structure.bars().iter().map(|b| b.nodes).collect(),
            // a clustered string is drawn as strings, segment by segment
            strings: (structure.strings().iter().map(|s| s.nodes))
                .chain(structure.clusters().iter().flat_map(|c| c.segments()))
                .collect(),
            supports: structure.supports().iter().map(|s| s.node).collect(),
            loads: structure
                .loads()
                .iter()
                .map(|l| (l.node, l.force))
                .collect(),
            ..Self::default()
        }
    }

    fn values(&self, by: ColorBy) -> Option<(&[f64], &'static str)> {
        match by {
            ColorBy::Kind => None,
            ColorBy::Force => self.force.as_deref().map(|v| (v, "member force [N]")),
            ColorBy::ForceDensity => self
                .force_density
                .as_deref()
                .map(|v| (v, "force density [N/m]")),
        }
    }

    /// The largest projected extent of the nodes.
    fn extent(&self, view: View) -> f64 {
        let pts: Vec<(f64, f64)> = self.nodes.iter().map(|p| view.project(p)).collect();
        let span = |f: fn(&(f64, f64)) -> f64| {
            let (lo, hi) = pts
                .iter()
                .map(f)
                .fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
            (hi - lo).max(0.0)
        };
        span(|p| p.0).max(span(|p| p.1)).max(1e-9)
    }
}

/// The members of `d` as series: strings under bars; coloured by value (tension dashed) or by
/// kind.
fn member_lines(d: &Drawing, style: &Style, p: &[(f64, f64)]) -> (Vec<Series>, Option<ColorBar>) {
    let values = d.values(style.color_by).filter(|(v, _)| {
        v.len() == d.bars.len() + d.strings.len() && v.iter().all(|x| x.is_finite())
    });
    let max_abs = values.map_or(0.0, |(v, _)| v.iter().fold(0.0f64, |m, x| m.max(x.abs())));
    let members = d
        .strings
        .iter()
        .enumerate()
        .map(|(i, e)| (d.bars.len() + i, e, false))
        .chain(d.bars.iter().enumerate().map(|(i, e)| (i, e, true)));
    let mut out = Vec::new();
    let mut seen = [false; 4];
    for (k, &[a, b], is_bar) in members {
        let width = if is_bar {
            style.bar_width
        } else {
            style.string_width
        };
        let pts = vec![p[a], p[b]];
        let s = match values {
            Some((v, _)) => {
                let x = v[k];
                let tiny = x.abs() <= 1e-9 * max_abs.max(f64::MIN_POSITIVE);
                let (slot, label) = match (tiny, x > 0.0) {
                    (true, _) => (2, "no force"),
                    (false, true) => (0, "tension (dashed)"),
                    (false, false) => (1, "compression (solid)"),
                };
                let label = if seen[slot] { "" } else { label };
                seen[slot] = true;
                let s = Series::new(label, pts)
                    .with_color(diverging_color(x, max_abs))
                    .with_width(width);
                if !tiny && x > 0.0 {
                    s.dashed()
                } else {
                    s
                }
            }
            None => {
                let (slot, label, color) = if is_bar {
                    (0, "bars", BAR_COLOR)
                } else {
                    (1, "strings", RED)
                };
                let label = if seen[slot] { "" } else { label };
                seen[slot] = true;
                Series::new(label, pts).with_color(color).with_width(width)
            }
        };
        out.push(s);
    }
    let bar = values.filter(|_| max_abs > 0.0).map(|(_, label)| ColorBar {
        label: label.to_string(),
        max_abs,
    });
    (out, bar)
}

/// A panel of `d` drawn in `style`, to scale: members (see the [module](self) docs), the
/// reference shape under them, supports, load and reaction arrows (the largest 15 % of the
/// drawing's extent, the head at the node), node and member numbers.
pub fn drawing_panel(title: impl Into<String>, d: &Drawing, style: &Style) -> Panel {
    let view = style.view;
    let p: Vec<(f64, f64)> = d.nodes.iter().map(|n| view.project(n)).collect();
    let (xl, yl) = view.labels();
    let mut panel = Panel::new(title, xl, yl).with_equal_axes();
    if let Some(reference) = &d.reference {
        let r: Vec<(f64, f64)> = reference.iter().map(|n| view.project(n)).collect();
        for (i, &[a, b]) in d.bars.iter().chain(&d.strings).enumerate() {
            let label = if i == 0 { "reference" } else { "" };
            panel.series.push(
                Series::new(label, vec![r[a], r[b]])
                    .with_color((0xb0, 0xb0, 0xb0))
                    .with_width(0.8)
                    .dashed(),
            );
        }
    }
    let (lines, bar) = member_lines(d, style, &p);
    panel.series.extend(lines);
    panel.colorbar = bar;
    for &n in &d.supports {
        panel.marks.push(Mark {
            label: "support".into(),
            at: p[n],
            shape: MarkShape::Support,
            color: (0x33, 0x33, 0x33),
        });
    }
    let largest = d
        .loads
        .iter()
        .chain(&d.reactions)
        .map(|(_, f)| f.norm())
        .fold(0.0f64, f64::max);
    let scale = if largest > 0.0 {
        0.15 * d.extent(view) / largest
    } else {
        0.0
    };
    let arrows = d
        .loads
        .iter()
        .map(|l| (l, "load", LOAD_COLOR))
        .chain(d.reactions.iter().map(|r| (r, "reaction", REACTION_COLOR)));
    for (&(n, f), label, color) in arrows {
        let tail = view.project(&(d.nodes[n] - f * scale));
        if f.norm() > 0.0 && (tail.0 - p[n].0).hypot(tail.1 - p[n].1) > 1e-12 {
            panel.arrows.push(Arrow {
                label: label.into(),
                from: tail,
                to: p[n],
                color,
            });
        }
    }
    if style.node_labels {
        for (i, &at) in p.iter().enumerate() {
            panel.notes.push(Note {
                at,
                text: i.to_string(),
                color: (0x00, 0x00, 0x00),
            });
        }
    }
    if style.member_labels {
        let named = d
            .bars
            .iter()
            .enumerate()
            .map(|(i, e)| (format!("b{i}"), e))
            .chain(
                d.strings
                    .iter()
                    .enumerate()
                    .map(|(i, e)| (format!("s{i}"), e)),
            );
        for (text, &[a, b]) in named {
            panel.notes.push(Note {
                at: (0.5 * (p[a].0 + p[b].0), 0.5 * (p[a].1 + p[b].1)),
                text,
                color: (0x55, 0x55, 0x55),
            });
        }
    }
    panel
}

/// A figure of `panels` (each drawn to scale), `width` pixels per panel and the height that
/// the tallest drawing needs.
pub fn drawing_figure_of(panels: Vec<Panel>, width: u32) -> Figure {
    let fig = drawing_figure(panels);
    let (_, h) = fig.panel_size;
    let w = width.max(200);
    let extra = if fig.panels.iter().any(|p| p.colorbar.is_some()) {
        90
    } else {
        0
    };
    let h = ((h as f64 - 80.0) * (w as f64 - 90.0) / 340.0 + 80.0).clamp(240.0, 900.0);
    fig.with_panel_size(w + extra, h as u32)
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
            Group::new("bars", BLUE, vec![[0, 2]]),
            Group::new("strings", RED, vec![[0, 1], [1, 2], [2, 3], [3, 0]]),
        ];
        let p = structure_panel("square", View::Side, &nodes, &groups);
        assert_eq!(p.series.len(), 5);
        // strings first (under), then the bar
        assert_eq!(p.series[1].points, vec![(1.0, 0.0), (1.0, 1.0)]);
        assert_eq!(p.series[4].points, vec![(0.0, 0.0), (1.0, 1.0)]);
        assert_eq!(
            (p.series[4].color, p.series[4].label.as_str()),
            (Some(BAR_COLOR), "bars")
        );
        assert!(p.series[4].width > 2.0 * p.series[0].width);
        assert_eq!(p.series[1].label, "");
        assert!(p.equal_axes);
        assert_eq!(drawing_figure(vec![p]).panel_size, (420, 420));
        // isometric: ι3 straight up, ι1 and ι2 at ∓30° below the horizontal
        let (u, v) = View::Iso.project(&Vector3::new(1.0, 0.0, 0.0));
        assert!((u + 0.75f64.sqrt()).abs() < 1e-15 && (v + 0.5).abs() < 1e-15);
    }

    #[test]
    fn views_parse_and_an_orbit_at_zero_elevation_from_x_is_the_side_view() {
        assert_eq!("yz".parse::<View>().unwrap(), View::Side);
        assert_eq!("XZ".parse::<View>().unwrap(), View::Xz);
        let v: View = "0deg,0deg".parse().unwrap();
        let p = Vector3::new(0.3, -1.2, 2.5);
        let (a, b) = (v.project(&p), View::Side.project(&p));
        assert!((a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15);
        // seen from straight above (elevation 90°, azimuth 0): up is −x
        let top: View = "0deg,90deg".parse().unwrap();
        let (u, w) = top.project(&Vector3::new(1.0, 2.0, 5.0));
        assert!((u - 2.0).abs() < 1e-12 && (w + 1.0).abs() < 1e-12);
        assert!("front".parse::<View>().unwrap_err().contains("front"));
        assert!("0,100deg".parse::<View>().is_err());
    }

    #[test]
    fn forces_colour_the_members_tension_dashed_with_a_colour_bar() {
        let d = Drawing {
            nodes: vec![
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(0.0, 1.0, 0.0),
                Vector3::new(0.0, 1.0, 1.0),
            ],
            bars: vec![[0, 2]],
            strings: vec![[0, 1], [1, 2]],
            force: Some(vec![-2.0, 1.0, 0.0]),
            supports: vec![0],
            loads: vec![(2, Vector3::new(0.0, 0.0, -10.0))],
            ..Drawing::default()
        };
        let style = Style {
            view: View::Side,
            color_by: ColorBy::Force,
            member_labels: true,
            ..Style::default()
        };
        let p = drawing_panel("t", &d, &style);
        assert_eq!(p.series.len(), 3);
        let bar = p.series.iter().find(|s| s.width == BAR_WIDTH).unwrap();
        assert!(!bar.dashed && bar.label.starts_with("compression"));
        assert!(p
            .series
            .iter()
            .any(|s| s.dashed && s.label.starts_with("tension")));
        assert_eq!(p.colorbar.as_ref().unwrap().max_abs, 2.0);
        // the load arrow ends at its node, 15 % of the extent long
        let a = &p.arrows[0];
        assert_eq!(a.to, (1.0, 1.0));
        assert!((a.from.1 - 1.15).abs() < 1e-12);
        assert_eq!(p.marks.len(), 1);
        assert_eq!(p.notes.len(), 3);
    }
}
