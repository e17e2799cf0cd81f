//! Where everything of a panel goes, in CSS pixels: the plot area inside the margins that the
//! title, tick labels, axis labels, colour bar and an outside legend need; the axis ranges
//! (equal scales for [`Panel::equal_axes`]: the range of one axis widened until
//! (x₁ − x₀)/w = (y₁ − y₀)/h); the ticks and their labels; the legend box in the emptiest
//! place.
//!
//! Ticks of a linear axis are at multiples of a step 1, 2 or 5 × 10ᵏ chosen so that labels are
//! at least ~60 px (x) or ~36 px (y) apart; every label of an axis has the same number of
//! decimals, and when the largest |tick| is ≥ 10⁴ or < 10⁻² the values are divided by a
//! common 10ᵉ shown once at the axis end (×10ᵉ). A log axis is labelled 10ⁿ at its decades
//! (every second or more when there are many).

use super::fit::{fit_at_least, Fitted};
use super::style::{series_style, Dash, Marker};
use super::text::{self, superscript};
use super::{Panel, Scale};

/// Font sizes (px).
pub const TITLE_SIZE: f64 = 14.0;
/// Axis labels.
pub const LABEL_SIZE: f64 = 12.5;
/// Tick labels, legend, colour bar.
pub const TICK_SIZE: f64 = 11.0;
/// A legend row's height.
const ROW: f64 = 16.0;
/// The smallest [`text_scale`]: 8 px tick labels (6 pt), 9 px axis labels, 10 px titles.
pub const MIN_TEXT: f64 = 0.72;

/// The size of a figure's text and of the gaps around it, relative to the usual, for panels
/// of `w` × `h` px each: 1 where each is at least 105 px wide and 190 px high (a journal's
/// column, 8.5 × 6 cm, and larger), in proportion below that, down to [`MIN_TEXT`] (a
/// 6 × 4 cm figure: about 0.8 for one or two panels, 0.72 for three side by side), so a small
/// page keeps room for its drawings.
///
/// ```
/// use tensegrity_io::figure::layout::{text_scale, MIN_TEXT};
/// assert_eq!(text_scale(321.0, 227.0), 1.0);
/// assert!((text_scale(227.0, 151.0) - 151.0 / 190.0).abs() < 1e-12);
/// assert_eq!(text_scale(75.0, 151.0), MIN_TEXT);
/// ```
pub fn text_scale(w: f64, h: f64) -> f64 {
    (w / 105.0).min(h / 190.0).clamp(MIN_TEXT, 1.0)
}

/// The smallest a title or label is fitted at on a page of text scale `k` (px): on a small
/// page the smallest tick label's size (7.92 px, 6 pt), so what does not fit is cut rather
/// than set tinier; elsewhere no floor but [`fit_at_least`]'s own.
pub(crate) fn smallest_text(k: f64) -> f64 {
    if k < 1.0 {
        MIN_TEXT * TICK_SIZE
    } else {
        0.0
    }
}

/// The size of a colour bar's `tension` and `compression` at text scale `k` (px).
pub(crate) fn colorbar_note_size(k: f64) -> f64 {
    (9.0 * k).max(smallest_text(k))
}

/// A rectangle: left, top, width, height.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rect {
    /// Left.
    pub x: f64,
    /// Top.
    pub y: f64,
    /// Width.
    pub w: f64,
    /// Height.
    pub h: f64,
}

impl Rect {
    fn contains(&self, (x, y): (f64, f64)) -> bool {
        x >= self.x && x <= self.x + self.w && y >= self.y && y <= self.y + self.h
    }
}

/// One axis: its range in drawing coordinates, its ticks and their labels.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Lower end.
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// The scale.
    pub scale: Scale,
    /// Tick positions (drawing coordinates) and labels.
    pub ticks: Vec<(f64, String)>,
    /// A common factor 10ᵉ of the labels, shown once.
    pub factor: Option<i32>,
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Glyph {
    /// A line sample (optionally with a marker).
    Line {
        /// Colour.
        color: (u8, u8, u8),
        /// Width (px).
        width: f64,
        /// Dash pattern.
        dash: Dash,
        /// With this marker.
        marker: Option<Marker>,
    },
    /// An arrow.
    Arrow((u8, u8, u8)),
    /// A mark.
    Mark(super::MarkShape, (u8, u8, u8)),
}

/// The legend: its box and entries, in `columns` columns filled row by row (one column:
/// the usual stacked legend; several: a legend row under the panel or the figure).
#[derive(Debug, Clone, PartialEq)]
pub struct Legend {
    /// The box.
    pub rect: Rect,
    /// Entries: glyph and text.
    pub entries: Vec<(Glyph, String)>,
    /// Columns (≥ 1).
    pub columns: usize,
    /// The size of its text, rows and samples relative to the usual (1, or down to
    /// [`super::fit::MIN_SCALE`] for a legend that would take too much of a small figure).
    pub scale: f64,
    /// Its rows and gaps at scale 1 ([`LEGEND`]; [`COMPACT_LEGEND`] on a small page).
    pub geometry: LegendGeometry,
}

/// The rows and gaps of a legend at scale 1 (px): padding above the first row and below the
/// last, a row's height, and across a column the gap before the sample, the sample's length,
/// the gap before the text and the gap after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LegendGeometry {
    /// Above the first row.
    pub top: f64,
    /// A row's height.
    pub row: f64,
    /// Below the last row.
    pub bottom: f64,
    /// Before the sample.
    pub left: f64,
    /// The sample's length.
    pub sample: f64,
    /// Between the sample and the text.
    pub gap: f64,
    /// After the text.
    pub right: f64,
}

/// The usual legend.
pub const LEGEND: LegendGeometry = LegendGeometry {
    top: 6.0,
    row: ROW,
    bottom: 2.0,
    left: 8.0,
    sample: 24.0,
    gap: 6.0,
    right: 8.0,
};

/// A legend on a small page ([`text_scale`] < 1): shorter samples, tighter rows and gaps.
pub const COMPACT_LEGEND: LegendGeometry = LegendGeometry {
    top: 3.0,
    row: 13.5,
    bottom: 3.0,
    left: 5.0,
    sample: 18.0,
    gap: 4.0,
    right: 5.0,
};

/// The legend geometry on a page of text scale `text`.
pub(crate) fn legend_geometry(text: f64) -> LegendGeometry {
    if text < 1.0 {
        COMPACT_LEGEND
    } else {
        LEGEND
    }
}

/// A text placed: its fitted lines and size, anchored in the middle at `at` (the first
/// line's baseline; a y-axis label is turned by −90° about it).
#[derive(Debug, Clone, PartialEq)]
pub struct Placed {
    /// The text.
    pub text: Fitted,
    /// Anchor point (px).
    pub at: (f64, f64),
}

/// How [`place_with`] lays a panel out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaceOptions {
    /// For a panel with equal axes, the scale (px per drawing unit) to draw it at, at most
    /// its own: the figure's one scale across its structure panels ([`super::arrange`]).
    pub scale: Option<f64>,
    /// The legend is the figure's (drawn once for all panels): none in the panel.
    pub shared_legend: bool,
    /// The size of the text and of the gaps around it relative to the usual ([`text_scale`];
    /// 1 by default).
    pub text: f64,
    /// The y-axis label is left out (a narrow panel right of one with the same label).
    pub no_y_label: bool,
}

impl Default for PlaceOptions {
    fn default() -> Self {
        Self {
            scale: None,
            shared_legend: false,
            text: 1.0,
            no_y_label: false,
        }
    }
}

/// Everything placed of one panel.
#[derive(Debug, Clone, PartialEq)]
pub struct PanelLayout {
    /// The panel's area in the figure.
    pub area: Rect,
    /// The plot area (inside the frame).
    pub plot: Rect,
    /// The x axis.
    pub x: Axis,
    /// The y axis.
    pub y: Axis,
    /// The legend, if any entry.
    pub legend: Option<Legend>,
    /// The colour bar's rectangle, if any.
    pub colorbar: Option<Rect>,
    /// The title (up to two lines).
    pub title: Placed,
    /// The x-axis label.
    pub x_label: Placed,
    /// The y-axis label (turned by −90°).
    pub y_label: Placed,
    /// For equal axes, the scale the panel is drawn at (px per drawing unit); `None` for
    /// other panels.
    pub equal_scale: Option<f64>,
    /// The size of the tick labels, the colour bar's text and the gaps relative to the usual
    /// ([`PlaceOptions::text`]).
    pub text: f64,
}

impl PanelLayout {
    /// The size of the tick labels and the colour bar's text (px).
    pub fn tick_size(&self) -> f64 {
        TICK_SIZE * self.text
    }
}

impl PanelLayout {
    /// Pixels per drawing unit along x and y (equal for equal axes).
    pub fn scales(&self) -> (f64, f64) {
        (
            self.plot.w / (self.x.hi - self.x.lo),
            self.plot.h / (self.y.hi - self.y.lo),
        )
    }

    /// A point in drawing coordinates → pixels.
    pub fn px(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let (sx, sy) = self.scales();
        (
            self.plot.x + (x - self.x.lo) * sx,
            self.plot.y + self.plot.h - (y - self.y.lo) * sy,
        )
    }
}

/// Where a series' markers go.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Markers {
    /// None.
    None,
    /// At every point ([`super::Series::markers`]).
    Every,
    /// Every ~70 px along the curve (a plain line in a panel of more styled series than
    /// dash patterns).
    Spaced,
}

/// How one series is drawn: colour, dash, marker and where its markers go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    /// RGB colour.
    pub color: (u8, u8, u8),
    /// Dash pattern.
    pub dash: Dash,
    /// Marker shape.
    pub marker: Marker,
    /// Where the markers go.
    pub markers: Markers,
}

/// The stroke of every series of `panel`, in order: a series without a colour of its own
/// takes the next style of [`super::style::series_style`] (counted over such series only);
/// one with its own colour is solid (dashed if asked) with circles.
pub fn strokes(panel: &Panel) -> Vec<Stroke> {
    let styled = panel.series.iter().filter(|s| s.color.is_none()).count();
    let mut k = 0;
    panel
        .series
        .iter()
        .map(|s| {
            let (color, dash, marker, spaced) = match s.color {
                Some(c) => (c, Dash::Solid, Marker::Circle, false),
                None => {
                    let style = series_style(k);
                    k += 1;
                    (style.color, style.dash, style.marker, styled > 6)
                }
            };
            let markers = match (s.markers, spaced) {
                (true, _) => Markers::Every,
                (false, true) => Markers::Spaced,
                (false, false) => Markers::None,
            };
            let dash = if s.dashed { Dash::Dashed } else { dash };
            Stroke {
                color,
                dash,
                marker,
                markers,
            }
        })
        .collect()
}

/// A step 1, 2 or 5 × 10ᵏ with at most `max_ticks` ticks over `span`.
fn nice_step(span: f64, max_ticks: f64) -> f64 {
    let raw = span / max_ticks.max(1.0);
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * base)
        .find(|&s| s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * base)
}

/// Writes `v` with `decimals` decimals and a true minus sign.
fn decimal(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    let zero = s
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.');
    if zero {
        s.trim_start_matches('-').to_string()
    } else {
        s.replace('-', "−")
    }
}

/// 10ⁿ with a superscript exponent.
pub fn power_of_ten(n: i32) -> String {
    let e: String = n.to_string().chars().map(superscript).collect();
    format!("10{e}")
}

/// The ticks of a linear axis over [lo, hi] with labels at least `spacing` px apart on
/// `length` px.
pub fn linear_ticks(
    lo: f64,
    hi: f64,
    length: f64,
    spacing: f64,
) -> (Vec<(f64, String)>, Option<i32>) {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return (vec![(lo, decimal(lo, 2))], None);
    }
    let step = nice_step(span, (length / spacing).floor().max(2.0));
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    let values: Vec<f64> = (first..=last).map(|k| k as f64 * step).collect();
    let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let e = if largest > 0.0 {
        largest.log10().floor() as i32
    } else {
        0
    };
    let factor = (e >= 4 || e <= -3).then_some(e);
    let unit = 10f64.powi(factor.unwrap_or(0));
    let decimals = (-(step / unit).log10() - 1e-9).ceil().clamp(0.0, 8.0) as usize;
    let ticks = values
        .into_iter()
        .map(|v| (v, decimal(v / unit, decimals)))
        .collect();
    (ticks, factor)
}

/// The ticks of a colour bar over ±`max_abs` on a bar `h` px tall, their labels at `k` of the
/// usual size, and their common factor 10ᵉ.
pub(crate) fn colorbar_ticks(max_abs: f64, h: f64, k: f64) -> (Vec<(f64, String)>, Option<i32>) {
    linear_ticks(-max_abs, max_abs, h, 30.0 * k)
}

/// How far right of a colour bar's left edge its texts reach (px) — the bar (12 px), its tick
/// labels `ticks_w` px wide, `tension` and `compression` above and below it (9 px) — at
/// text scale `k`: its label goes right of them.
pub(crate) fn colorbar_texts_w(ticks_w: f64, k: f64) -> f64 {
    ((12.0 + 5.0) * k + ticks_w).max(text::width("compression", colorbar_note_size(k)))
}

/// The widest of `ticks` at `size` px.
pub(crate) fn widest_label(ticks: &[(f64, String)], size: f64) -> f64 {
    widest(ticks, size)
}

/// The decades of a log axis over [lo, hi] (exponents), every k-th when there are many.
fn log_ticks(lo: f64, hi: f64, length: f64) -> Vec<(f64, String)> {
    let (a, b) = (lo.ceil() as i32, hi.floor() as i32);
    let count = (b - a + 1).max(1) as f64;
    let every = ((count * 28.0 / length).ceil() as i32).max(1);
    (a..=b)
        .filter(|k| (k - a) % every == 0)
        .map(|k| (k as f64, power_of_ten(k)))
        .collect()
}

/// The range of drawing coordinates of `values` (with `pad` of the span on a linear axis,
/// whole decades on a log axis).
pub fn axis_range(values: impl Iterator<Item = f64>, scale: Scale, pad: f64) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    if lo > hi {
        return (0.0, 1.0);
    }
    match scale {
        Scale::Log => {
            let (lo, hi) = (lo.floor(), hi.ceil());
            (lo, hi.max(lo + 1.0))
        }
        Scale::Linear => {
            let span = hi - lo;
            let span = if span > 0.0 {
                span
            } else {
                1e-3 * lo.abs().max(1.0)
            };
            (lo - pad * span, hi + pad * span)
        }
    }
}

/// Every point of the panel's drawing in drawing coordinates: series, arrows, marks, notes.
fn drawn_extent(panel: &Panel) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = panel.drawn_points().into_iter().flatten().collect();
    for a in &panel.arrows {
        pts.extend(
            [a.from, a.to]
                .into_iter()
                .filter_map(|p| panel.to_drawing(p)),
        );
    }
    pts.extend(panel.marks.iter().filter_map(|m| panel.to_drawing(m.at)));
    pts.extend(panel.notes.iter().filter_map(|n| panel.to_drawing(n.at)));
    pts
}

/// The legend entries of a panel: labelled series, arrows and marks, each label once.
pub(crate) fn legend_entries(panel: &Panel) -> Vec<(Glyph, String)> {
    let mut out: Vec<(Glyph, String)> = Vec::new();
    let mut add = |glyph: Glyph, label: &str| {
        if !label.is_empty() && !out.iter().any(|(_, l)| l == label) {
            out.push((glyph, label.to_string()));
        }
    };
    for (s, st) in panel.series.iter().zip(strokes(panel)) {
        let glyph = Glyph::Line {
            color: st.color,
            width: s.width,
            dash: st.dash,
            marker: (st.markers != Markers::None).then_some(st.marker),
        };
        add(glyph, &s.label);
    }
    for a in &panel.arrows {
        add(Glyph::Arrow(a.color), &a.label);
    }
    for m in &panel.marks {
        add(Glyph::Mark(m.shape, m.color), &m.label);
    }
    out
}

/// The legend scales tried, largest first.
pub(crate) const LEGEND_SCALES: [f64; 3] = [1.0, 0.85, super::fit::MIN_SCALE];

/// The legend scales tried on a page of text scale `text`: none larger than it.
pub(crate) fn legend_scales(text: f64) -> [f64; 3] {
    LEGEND_SCALES.map(|s| s.min(text))
}

/// The width of one legend column at `scale`: sample, gap, the widest text, padding (px).
fn legend_column(entries: &[(Glyph, String)], scale: f64, g: LegendGeometry) -> f64 {
    let text = entries
        .iter()
        .map(|(_, t)| text::width(t, TICK_SIZE))
        .fold(0.0, f64::max);
    scale * (g.left + g.sample + g.gap + text + g.right)
}

/// The size of a legend of `entries` in `columns` columns at `scale` (px).
pub(crate) fn legend_size(
    entries: &[(Glyph, String)],
    columns: usize,
    scale: f64,
    g: LegendGeometry,
) -> (f64, f64) {
    let columns = columns.clamp(1, entries.len().max(1));
    let rows = entries.len().div_ceil(columns);
    (
        legend_column(entries, scale, g) * columns as f64,
        scale * (g.top + g.row * rows as f64 + g.bottom),
    )
}

/// The columns of a legend of `entries` at `scale` that fit `room_w` px (at least one).
pub(crate) fn legend_columns(
    entries: &[(Glyph, String)],
    room_w: f64,
    scale: f64,
    g: LegendGeometry,
) -> usize {
    ((room_w / legend_column(entries, scale, g)).floor() as usize).clamp(1, entries.len().max(1))
}

/// A legend of `entries` in rows across `room_w` px, at the largest scale up to `text`
/// whose height is at most `max_h` px (else the smallest): its columns, scale and size.
pub(crate) fn legend_rows(
    entries: &[(Glyph, String)],
    room_w: f64,
    max_h: f64,
    text: f64,
) -> (usize, f64, (f64, f64)) {
    let g = legend_geometry(text);
    let mut best = (1, 1.0, (0.0, 0.0));
    for scale in legend_scales(text) {
        let columns = legend_columns(entries, room_w, scale, g);
        best = (columns, scale, legend_size(entries, columns, scale, g));
        if best.2 .1 <= max_h {
            break;
        }
    }
    best
}

/// The widest tick label of an axis, at `size` px.
fn widest(ticks: &[(f64, String)], size: f64) -> f64 {
    ticks
        .iter()
        .map(|(_, t)| text::width(t, size))
        .fold(0.0, f64::max)
}

/// The axes over the data ranges for a plot of `w` × `h` px (ranges widened for equal axes),
/// their labels at `k` of the usual size (and spacing).
fn axes(panel: &Panel, x: (f64, f64), y: (f64, f64), w: f64, h: f64, k: f64) -> (Axis, Axis) {
    let (mut x, mut y) = (x, y);
    if panel.equal_axes {
        let s = ((x.1 - x.0) / w).max((y.1 - y.0) / h);
        let (cx, cy) = (0.5 * (x.0 + x.1), 0.5 * (y.0 + y.1));
        x = (cx - 0.5 * s * w, cx + 0.5 * s * w);
        y = (cy - 0.5 * s * h, cy + 0.5 * s * h);
    }
    let axis = |(lo, hi): (f64, f64), scale: Scale, length: f64, spacing: f64| {
        let (ticks, factor) = match scale {
            Scale::Linear => linear_ticks(lo, hi, length, spacing),
            Scale::Log => (log_ticks(lo, hi, length), None),
        };
        Axis {
            lo,
            hi,
            scale,
            ticks,
            factor,
        }
    };
    (
        axis(x, panel.x_scale, w, 52.0 * k),
        axis(y, panel.y_scale, h, 36.0 * k),
    )
}

/// Places `panel` in `area` on its own (its own scale and legend).
pub fn place(panel: &Panel, area: Rect) -> PanelLayout {
    place_with(panel, area, PlaceOptions::default())
}

/// The data ranges of a panel before any layout: the drawing's extent, padded (5 % on a
/// linear y axis; 4 % of the larger span on every side for equal axes) and with the legend's
/// headroom.
fn data_ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let pts = drawn_extent(panel);
    let equal = panel.equal_axes;
    let pad = if equal { 0.0 } else { 0.05 };
    let mut x = axis_range(pts.iter().map(|p| p.0), panel.x_scale, 0.0);
    let mut y = axis_range(pts.iter().map(|p| p.1), panel.y_scale, pad);
    if equal {
        let m = 0.04 * (x.1 - x.0).max(y.1 - y.0);
        x = (x.0 - m, x.1 + m);
        y = (y.0 - m, y.1 + m);
    }
    if panel.y_scale == Scale::Linear && panel.legend_headroom > 0.0 {
        y.1 += panel.legend_headroom * (y.1 - y.0) / 1.1;
    }
    (x, y)
}

/// The smallest side of an equal-axes plot (px): a flat structure seen edge on still gets a
/// readable strip.
const MIN_SIDE: f64 = 24.0;

/// `range` widened about its middle to `span`, if shorter.
fn widened((lo, hi): (f64, f64), span: f64) -> (f64, f64) {
    if hi - lo >= span {
        return (lo, hi);
    }
    let c = 0.5 * (lo + hi);
    (c - 0.5 * span, c + 0.5 * span)
}

/// Places `panel` in `area` under `options`.
///
/// Margins come from the measured text: the title (fitted to the area's width, up to two
/// lines, [`super::fit::fit`]), the x tick labels and label below, the y tick labels (the widest of them)
/// and label to the left, the colour bar to the right. A panel with equal axes gets a plot
/// box of its data's own aspect, centred in the room left (so the structure fills its axes at
/// any size), at the scale of `options` or the largest that fits. The legend goes inside the
/// plot where it covers no data, else to the right of it when that takes at most ~35 % of the
/// area's width, else in rows under the panel. On a small page (`options.text` < 1: text,
/// gaps and legend rows smaller, titles and labels cut rather than set under 6 pt) a legend
/// that does not fit inside goes right of the plot or under the panel, whichever leaves the
/// plot the larger smaller side.
pub fn place_with(panel: &Panel, area: Rect, options: PlaceOptions) -> PanelLayout {
    let (x, y) = data_ranges(panel);
    let equal = panel.equal_axes;
    // text and gaps at `k` of their usual size on a small page
    let k = options.text;
    let tick = TICK_SIZE * k;
    let entries = if options.shared_legend {
        Vec::new()
    } else {
        legend_entries(panel)
    };
    let title = fit_at_least(
        &panel.title,
        TITLE_SIZE * k,
        smallest_text(k),
        area.w - 8.0 * k,
        2,
    );
    // a common factor ×10ᵉ of the y labels sits above the plot, under the title
    // (probed on the area's height: at least the ticks the plot will have)
    let factor = axes(panel, x, y, area.w, area.h, k).1.factor.is_some();
    let top = match title.lines.len() {
        0 => 16.0 * k,
        n => 8.0 * k + title.size + (n - 1) as f64 * title.line_height() + 8.0 * k,
    } + if factor { tick + 2.0 * k } else { 0.0 };
    let bottom = (8.0 + 6.0 + 8.0 + LABEL_SIZE) * k + tick;
    // the colour bar's column: bar, tick labels and its label turned (on a small page as
    // wide as they need)
    let colorbar_w = match &panel.colorbar {
        None => 0.0,
        Some(_) if k >= 1.0 => 86.0,
        Some(bar) => {
            let probe = colorbar_ticks(bar.max_abs, area.h - top - bottom, k).0;
            16.0 * k + colorbar_texts_w(widest(&probe, tick), k) + 10.0 * k + tick
        }
    };
    // the y-axis label's column, left of the tick labels
    let y_label_w = if options.no_y_label {
        0.0
    } else {
        (LABEL_SIZE + 8.0) * k
    };
    let margin = |ticks: &[(f64, String)]| (8.0 + 6.0) * k + y_label_w + widest(ticks, tick);
    // the layout with `outside` px right of the plot and `below` px under the panel taken
    // (by a legend), at the scale `fixed` for equal axes or the largest that fits
    let build = |outside: f64, below: f64, fixed: Option<f64>| {
        let right = 14.0 * k + colorbar_w + outside;
        // the y tick labels' width depends on the ticks, which depend on the height only
        let h = (area.h - top - bottom - below).max(20.0);
        let (_, probe) = axes(panel, x, y, (area.w - 90.0 * k - right).max(20.0), h, k);
        let mut left = margin(&probe.ticks);
        let mut w = (area.w - left - right).max(20.0);
        let (mut plot, xr, yr, mut equal_scale) = (
            Rect {
                x: area.x + left,
                y: area.y + top,
                w,
                h,
            },
            x,
            y,
            None,
        );
        let (mut xa, mut ya) = axes(panel, xr, yr, w, h, k);
        if equal {
            // the data's own aspect, at the figure's scale or the largest that fits a room
            // `w` wide: the scale, the ranges, the box and its axes
            // (a drawing of one point has no extent: a floor keeps the scale finite)
            let span = |(lo, hi): (f64, f64)| (hi - lo).max(1e-9 * lo.abs().max(hi.abs()).max(1.0));
            let at = |w: f64| {
                let fits = (w / span(x)).min(h / span(y));
                let s = fixed.map_or(fits, |s| s.min(fits));
                let min_side = MIN_SIDE * k;
                let (xr, yr) = (widened(x, min_side / s), widened(y, min_side / s));
                let (pw, ph) = (((xr.1 - xr.0) * s).min(w), ((yr.1 - yr.0) * s).min(h));
                let (xr, yr) = (widened(xr, pw / s), widened(yr, ph / s));
                let (xa, ya) = axes(panel, xr, yr, pw, ph, k);
                (s, xr, yr, pw, ph, xa, ya)
            };
            let (mut s, mut pw, mut ph);
            (s, _, _, pw, ph, xa, ya) = at(w);
            // the y tick labels of the box's own range may be wider than the probe's: a
            // wider margin, and the box fitted again to the narrower room
            let needed = margin(&ya.ticks);
            if needed > left {
                left = needed;
                w = (area.w - left - right).max(20.0);
                (s, _, _, pw, ph, xa, ya) = at(w);
            }
            plot = Rect {
                x: area.x + left + 0.5 * (w - pw).max(0.0),
                y: area.y + top + 0.5 * (h - ph).max(0.0),
                w: pw,
                h: ph,
            };
            equal_scale = Some(s);
        } else {
            let needed = margin(&ya.ticks);
            if needed > left {
                left = needed;
                w = (area.w - left - right).max(20.0);
                (xa, ya) = axes(panel, xr, yr, w, h, k);
                plot.x = area.x + left;
                plot.w = w;
            }
        }
        // the colour bar leaves room above and below it for its `tension` and
        // `compression`, inside the plot's height (clear of the title and the x labels)
        let colorbar = panel.colorbar.as_ref().map(|_| {
            let inset = (0.1 * plot.h).max(14.0 * k);
            Rect {
                x: plot.x + plot.w + 16.0 * k + outside,
                y: plot.y + inset,
                w: 12.0 * k,
                h: (plot.h - 2.0 * inset).max(4.0),
            }
        });
        // (on a small page a legend right of the plot may run down beside the x label)
        let (title, x_label, y_label) = texts(
            panel,
            area,
            plot,
            &title,
            widest(&ya.ticks, tick),
            k,
            !options.no_y_label,
            if k < 1.0 { outside } else { 0.0 },
        );
        PanelLayout {
            area,
            plot,
            x: xa,
            y: ya,
            legend: None,
            colorbar,
            title,
            x_label,
            y_label,
            equal_scale,
            text: k,
        }
    };
    let mut layout = build(0.0, 0.0, options.scale);
    if entries.is_empty() {
        return layout;
    }
    let g = legend_geometry(k);
    let legend = |rect: Rect, entries: Vec<(Glyph, String)>, columns: usize, scale: f64| Legend {
        rect,
        entries,
        columns,
        scale,
        geometry: g,
    };
    let (lw, lh) = legend_size(&entries, 1, k, g);
    if let Some(rect) = best_place(panel, &layout, (lw, lh), k) {
        layout.legend = Some(legend(rect, entries, 1, k));
        return layout;
    }
    let room_h = area.h - top - bottom;
    // where a legend goes: to the right of the plot (`outside` its width) or in rows under
    // the panel, at a scale, in columns
    let right = |scale: f64, layout: PanelLayout| {
        let (lw, lh) = legend_size(&entries, 1, scale, g);
        // beside the plot's top (a small page: its middle, not above the title's room)
        // (a small page: beside its middle, from under the title down to the page's foot,
        // clear of the last x tick label where it runs down past the plot)
        let p = layout.plot;
        let (mut x, mut y) = (p.x + p.w + 8.0 * k, p.y);
        if k < 1.0 {
            y = (p.y + 0.5 * (p.h - lh))
                .min(area.y + area.h - 4.0 * k - lh)
                .max(area.y + top);
            if y + lh > p.y + p.h {
                x += 0.5 * widest(&layout.x.ticks, tick);
            }
        }
        let rect = Rect { x, y, w: lw, h: lh };
        PanelLayout {
            legend: Some(legend(rect, entries.clone(), 1, scale)),
            ..layout
        }
    };
    let under = |columns: usize, scale: f64, layout: PanelLayout| {
        let (lw, lh) = legend_size(&entries, columns, scale, g);
        let rect = Rect {
            x: area.x + 0.5 * (area.w - lw).max(0.0),
            y: area.y + area.h - lh - 4.0 * k,
            w: lw,
            h: lh,
        };
        PanelLayout {
            legend: Some(legend(rect, entries.clone(), columns, scale)),
            ..layout
        }
    };
    if k < 1.0 {
        // a small page: of the places right of the plot and under the panel, at each scale,
        // the one that leaves the plot the most room (its smaller side, each at its own
        // scale, so every panel of a figure chooses as it did alone)
        let mut best: Option<(f64, f64, usize, f64)> = None;
        for scale in legend_scales(k) {
            let (lw, lh) = legend_size(&entries, 1, scale, g);
            let mut tries = Vec::new();
            if lh <= area.h - top - 4.0 * k {
                let outside = lw + 10.0 * k;
                let probe = build(outside, 0.0, None);
                tries.push((outside + 0.5 * widest(&probe.x.ticks, tick), 0.0, 0));
            }
            let columns = legend_columns(&entries, area.w - 16.0 * k, scale, g);
            tries.push((
                0.0,
                legend_size(&entries, columns, scale, g).1 + 6.0 * k,
                columns,
            ));
            for (outside, below, columns) in tries {
                let l = build(outside, below, None);
                let room = l.plot.w.min(l.plot.h);
                if best.is_none_or(|b| room > b.0 + 1e-9) {
                    best = Some((room, scale, columns, outside.max(below)));
                }
            }
        }
        let (_, scale, columns, taken) = best.expect("a legend place");
        return if columns == 0 {
            right(scale, build(taken, 0.0, options.scale))
        } else {
            under(columns, scale, build(0.0, taken, options.scale))
        };
    }
    for scale in legend_scales(k) {
        let (lw, lh) = legend_size(&entries, 1, scale, g);
        if lw + 10.0 * k <= 0.35 * area.w && lh <= room_h {
            return right(scale, build(lw + 10.0 * k, 0.0, options.scale));
        }
    }
    let (columns, scale, (_, lh)) = legend_rows(&entries, area.w - 16.0 * k, 0.3 * area.h, k);
    under(columns, scale, build(0.0, lh + 6.0 * k, options.scale))
}

/// The title, x label and y label (none unless `y_label`) of a panel whose plot is `plot`
/// (`tick_w`: the widest y tick label), at `k` of their usual size, each fitted to its room
/// in `area` and kept inside it (the x label left of the `right` px a legend takes).
#[allow(clippy::too_many_arguments)]
fn texts(
    panel: &Panel,
    area: Rect,
    plot: Rect,
    title: &Fitted,
    tick_w: f64,
    k: f64,
    y_label: bool,
    right: f64,
) -> (Placed, Placed, Placed) {
    // a centre that keeps a text of width `w` within [lo, hi]
    let centre = |c: f64, w: f64, lo: f64, hi: f64| c.min(hi - 0.5 * w).max(lo + 0.5 * w);
    let title = Placed {
        at: (
            centre(
                plot.x + 0.5 * plot.w,
                title.width(),
                area.x + 4.0 * k,
                area.x + area.w - 4.0 * k,
            ),
            area.y + 8.0 * k + title.size,
        ),
        text: title.clone(),
    };
    let xl = fit_at_least(
        &panel.x_label,
        LABEL_SIZE * k,
        smallest_text(k),
        area.w - 8.0 * k - right,
        1,
    );
    let x_label = Placed {
        at: (
            centre(
                plot.x + 0.5 * plot.w,
                xl.width(),
                area.x + 4.0 * k,
                area.x + area.w - 4.0 * k - right,
            ),
            plot.y + plot.h + (6.0 + 6.0) * k + TICK_SIZE * k + LABEL_SIZE * k,
        ),
        text: xl,
    };
    // beside the plot, below the title: it may run down past the plot to the x tick labels,
    // not up into the title nor down to the x label
    let (lo, hi) = (
        plot.y,
        (plot.y + plot.h + 20.0 * k).min(area.y + area.h - 4.0 * k),
    );
    let yl = fit_at_least(
        if y_label { &panel.y_label } else { "" },
        LABEL_SIZE * k,
        smallest_text(k),
        hi - lo,
        1,
    );
    let y_label = Placed {
        at: (
            (plot.x - tick_w - 14.0 * k).max(area.x + 4.0 * k + yl.size),
            centre(plot.y + 0.5 * plot.h, yl.width(), lo, hi),
        ),
        text: yl,
    };
    (title, x_label, y_label)
}

/// Points along everything drawn in a panel, in pixels, ~3 px apart.
fn sampled(panel: &Panel, layout: &PanelLayout) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut segment = |a: (f64, f64), b: (f64, f64)| {
        let (pa, pb) = (layout.px(a), layout.px(b));
        let n = ((pb.0 - pa.0).hypot(pb.1 - pa.1) / 3.0)
            .ceil()
            .clamp(1.0, 2000.0) as usize;
        for k in 0..=n {
            let t = k as f64 / n as f64;
            out.push((pa.0 + t * (pb.0 - pa.0), pa.1 + t * (pb.1 - pa.1)));
        }
    };
    for pts in panel.drawn_points() {
        if pts.len() == 1 {
            segment(pts[0], pts[0]);
        }
        for w in pts.windows(2) {
            segment(w[0], w[1]);
        }
    }
    for a in &panel.arrows {
        if let (Some(p), Some(q)) = (panel.to_drawing(a.from), panel.to_drawing(a.to)) {
            segment(p, q);
        }
    }
    for m in panel.marks.iter().filter_map(|m| panel.to_drawing(m.at)) {
        segment(m, m);
    }
    for n in panel.notes.iter().filter_map(|n| panel.to_drawing(n.at)) {
        segment(n, n);
    }
    out
}

/// The legend box (`k`: the text scale) inside the plot covering no sampled point, in order of preference (upper
/// right, upper left, lower right, lower left, top and bottom centre, centre right and left);
/// `None` when every place covers some.
fn best_place(panel: &Panel, layout: &PanelLayout, (w, h): (f64, f64), k: f64) -> Option<Rect> {
    let p = layout.plot;
    let gap = 6.0 * k;
    if w + 2.0 * gap > p.w || h + 2.0 * gap > p.h {
        return None;
    }
    let (l, r) = (p.x + gap, p.x + p.w - gap - w);
    let (t, b) = (p.y + gap, p.y + p.h - gap - h);
    let (cx, cy) = (p.x + 0.5 * (p.w - w), p.y + 0.5 * (p.h - h));
    let candidates = [
        (r, t),
        (l, t),
        (r, b),
        (l, b),
        (cx, t),
        (cx, b),
        (r, cy),
        (l, cy),
    ];
    let pts = sampled(panel, layout);
    candidates
        .iter()
        .map(|&(x, y)| Rect { x, y, w, h })
        .find(|rect| {
            let grown = Rect {
                x: rect.x - 3.0,
                y: rect.y - 3.0,
                w: rect.w + 6.0,
                h: rect.h + 6.0,
            };
            !pts.iter().any(|&q| grown.contains(q))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::Series;

    #[test]
    fn linear_ticks_share_their_decimals_and_factor_out_large_powers() {
        let (t, f) = linear_ticks(0.0, 1.0, 400.0, 64.0);
        let labels: Vec<&str> = t.iter().map(|(_, s)| s.as_str()).collect();
        assert_eq!(labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0"]);
        assert_eq!(f, None);
        let (t, f) = linear_ticks(0.0, 25_000.0, 400.0, 64.0);
        assert_eq!(f, Some(4));
        assert_eq!(t[1].1, "0.5");
        let (t, _) = linear_ticks(-3.0, 3.0, 400.0, 64.0);
        assert_eq!(t[0].1, "−3");
        assert_eq!(power_of_ten(-3), "10⁻³");
        let (lo, hi) = axis_range([-3.2, -1.5].into_iter(), Scale::Log, 0.0);
        assert_eq!((lo, hi), (-4.0, -1.0));
    }

    #[test]
    fn a_structure_of_one_point_or_none_gets_a_finite_box() {
        let area = Rect {
            x: 0.0,
            y: 0.0,
            w: 300.0,
            h: 200.0,
        };
        for pts in [vec![(1.0, 2.0)], vec![]] {
            let panel = Panel::new("t", "y [m]", "z [m]")
                .with_equal_axes()
                .series(Series::new("bar", pts));
            let l = place(&panel, area);
            let p = l.plot;
            assert!([p.x, p.y, p.w, p.h, l.x.lo, l.x.hi, l.y.lo, l.y.hi]
                .iter()
                .all(|v| v.is_finite()));
            assert!(p.w >= MIN_SIDE - 1e-9 && p.h >= MIN_SIDE - 1e-9, "{p:?}");
            assert!(p.x + p.w <= area.w && p.y + p.h <= area.h);
        }
    }

    #[test]
    fn equal_axes_have_one_scale_and_the_legend_avoids_the_data() {
        let panel = Panel::new("t", "y [m]", "z [m]")
            .with_equal_axes()
            .series(Series::new("bar", vec![(0.0, 0.0), (3.0, 1.0)]));
        let l = place(
            &panel,
            Rect {
                x: 0.0,
                y: 0.0,
                w: 500.0,
                h: 400.0,
            },
        );
        let (sx, sy) = l.scales();
        assert!((sx / sy - 1.0).abs() < 1e-12);
        let legend = l.legend.clone().expect("one entry");
        for p in sampled(&panel, &l) {
            assert!(!legend.rect.contains(p));
        }
        // a curve over the whole plot area pushes the legend outside
        let zigzag: Vec<(f64, f64)> = (0..200).map(|k| (k as f64, (k % 2) as f64)).collect();
        let full = Panel::new("t", "x", "y").series(Series::new("zigzag", zigzag));
        let l = place(
            &full,
            Rect {
                x: 0.0,
                y: 0.0,
                w: 500.0,
                h: 400.0,
            },
        );
        assert!(l.legend.unwrap().rect.x > l.plot.x + l.plot.w);
    }
}
