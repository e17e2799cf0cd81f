//! The one series style table of every line plot: a colour, a dash pattern and a marker per
//! series, so that curves differ in colour for a reader with normal colour vision, and in
//! dash and marker for everyone else (greyscale print, colour-blind readers).
//!
//! Colours ([`PALETTE`]): the seven of Okabe & Ito's colour-blind-safe set ("Color Universal
//! Design", Okabe and Ito 2002/2008: blue #0072B2, vermillion #D55E00, bluish green #009E73,
//! reddish purple #CC79A7, orange #E69F00, sky blue #56B4E9, black #000000; its yellow
//! #F0E442 left out, too light on white), then five of Paul Tol's colour-blind-safe "muted"
//! scheme (Tol, "Colour Schemes", SRON/EPS/TN/09-002, 2021: wine #882255, olive #999933,
//! indigo #332288, purple #AA4499, sand #DDCC77). Any two of the twelve are at least 22 apart
//! in CIELAB ΔE\*ab (`tests/figure_palette.rs`).
//!
//! Dash patterns ([`Dash`]): six, the first six styles one each; markers ([`Marker`]): six
//! shapes. Style k has dash k mod 6 and marker (k + ⌊k/6⌋) mod 6, so no two of the first
//! twelve share both their dash and their marker (and none their colour). A series drawn
//! with markers ([`super::Series::with_markers`]) has its style's marker at every point; a
//! plain line gets its marker every ~70 px along the curve when its panel holds more styled
//! series than there are dash patterns (beyond six, the dash alone no longer tells them
//! apart). A series with a colour of its own ([`super::Series::with_color`]: structure
//! drawings, force maps) keeps its colour, is solid (dashed with
//! [`super::Series::dashed`]) and has circles as markers.

/// The series colours, in order (see the [module](self) docs for their source).
pub const PALETTE: [(u8, u8, u8); 12] = [
    (0x00, 0x72, 0xb2), // Okabe–Ito blue
    (0xd5, 0x5e, 0x00), // Okabe–Ito vermillion
    (0x00, 0x9e, 0x73), // Okabe–Ito bluish green
    (0xcc, 0x79, 0xa7), // Okabe–Ito reddish purple
    (0xe6, 0x9f, 0x00), // Okabe–Ito orange
    (0x56, 0xb4, 0xe9), // Okabe–Ito sky blue
    (0x00, 0x00, 0x00), // Okabe–Ito black
    (0x88, 0x22, 0x55), // Tol muted wine
    (0x99, 0x99, 0x33), // Tol muted olive
    (0x33, 0x22, 0x88), // Tol muted indigo
    (0xaa, 0x44, 0x99), // Tol muted purple
    (0xdd, 0xcc, 0x77), // Tol muted sand
];

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dash {
    /// Solid.
    Solid,
    /// Dashes.
    Dashed,
    /// Dots.
    Dotted,
    /// Dash, dot.
    DashDot,
    /// Long dashes.
    LongDash,
    /// Dash, dot, dot.
    DashDotDot,
}

impl Dash {
    /// Every pattern, in the order of the style table.
    pub const ALL: [Dash; 6] = [
        Dash::Solid,
        Dash::Dashed,
        Dash::Dotted,
        Dash::DashDot,
        Dash::LongDash,
        Dash::DashDotDot,
    ];

    /// The SVG `stroke-dasharray` of a line `width` px wide (dash, gap, … in px; `None` for
    /// solid). Lengths scale with the width (at least 1.5 px); the caps are round, so a dash
    /// is drawn one width longer and a gap one width shorter than written.
    pub fn pattern(self, width: f64) -> Option<Vec<f64>> {
        let units: &[f64] = match self {
            Dash::Solid => return None,
            Dash::Dashed => &[3.0, 2.0],
            Dash::Dotted => &[0.01, 2.0],
            Dash::DashDot => &[3.5, 2.2, 0.01, 2.2],
            Dash::LongDash => &[8.0, 2.5],
            Dash::DashDotDot => &[3.5, 2.2, 0.01, 2.2, 0.01, 2.2],
        };
        let w = width.max(1.5);
        Some(units.iter().map(|u| u * w).collect())
    }
}

/// A marker's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle, point up.
    TriangleUp,
    /// A filled diamond.
    Diamond,
    /// A filled triangle, point down.
    TriangleDown,
    /// An open circle (white inside).
    Ring,
}

impl Marker {
    /// Every shape, in the order of the style table.
    pub const ALL: [Marker; 6] = [
        Marker::Circle,
        Marker::Square,
        Marker::TriangleUp,
        Marker::Diamond,
        Marker::TriangleDown,
        Marker::Ring,
    ];
}

/// How one series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SeriesStyle {
    /// RGB colour.
    pub color: (u8, u8, u8),
    /// Dash pattern.
    pub dash: Dash,
    /// Marker.
    pub marker: Marker,
}

/// Styles in the table before it repeats.
pub const STYLE_COUNT: usize = 12;

/// The style of the `k`-th styled series of a panel (repeating after [`STYLE_COUNT`]).
///
/// ```
/// use tensegrity_io::figure::style::{series_style, Dash, STYLE_COUNT};
/// assert_eq!(series_style(0).dash, Dash::Solid);
/// assert_eq!(series_style(STYLE_COUNT), series_style(0));
/// assert_ne!(series_style(6).color, series_style(0).color);
/// ```
pub fn series_style(k: usize) -> SeriesStyle {
    let k = k % STYLE_COUNT;
    SeriesStyle {
        color: PALETTE[k],
        dash: Dash::ALL[k % 6],
        marker: Marker::ALL[(k + k / 6) % 6],
    }
}
