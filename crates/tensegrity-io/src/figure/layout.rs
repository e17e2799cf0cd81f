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

use super::fit::{fit, Fitted};
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
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlaceOptions {
    /// For a panel with equal axes, the scale (px per drawing unit) to draw it at, at most
    /// its own: the figure's one scale across its structure panels ([`super::arrange`]).
    pub scale: Option<f64>,
    /// The legend is the figure's (drawn once for all panels): none in the panel.
    pub shared_legend: bool,
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

/// The width of one legend column at `scale`: sample, gap, the widest text, padding (px).
fn legend_column(entries: &[(Glyph, String)], scale: f64) -> f64 {
    let text = entries
        .iter()
        .map(|(_, t)| text::width(t, TICK_SIZE))
        .fold(0.0, f64::max);
    scale * (8.0 + 24.0 + 6.0 + text + 8.0)
}

/// The size of a legend of `entries` in `columns` columns at `scale` (px).
pub(crate) fn legend_size(entries: &[(Glyph, String)], columns: usize, scale: f64) -> (f64, f64) {
    let columns = columns.clamp(1, entries.len().max(1));
    let rows = entries.len().div_ceil(columns);
    (
        legend_column(entries, scale) * columns as f64,
        scale * (6.0 + ROW * rows as f64 + 2.0),
    )
}

/// A legend of `entries` in rows across `room_w` px, at the largest scale whose height is at
/// most `max_h` px (else the smallest): its columns, scale and size.
pub(crate) fn legend_rows(
    entries: &[(Glyph, String)],
    room_w: f64,
    max_h: f64,
) -> (usize, f64, (f64, f64)) {
    let mut best = (1, 1.0, (0.0, 0.0));
    for scale in LEGEND_SCALES {
        let columns = ((room_w / legend_column(entries, scale)).floor() as usize)
            .clamp(1, entries.len().max(1));
        best = (columns, scale, legend_size(entries, columns, scale));
        if best.2 .1 <= max_h {
            break;
        }
    }
    best
}

/// The widest tick label of an axis.
fn widest(ticks: &[(f64, String)]) -> f64 {
    ticks
        .iter()
        .map(|(_, t)| text::width(t, TICK_SIZE))
        .fold(0.0, f64::max)
}

/// The axes over the data ranges for a plot of `w` × `h` px (ranges widened for equal axes).
fn axes(panel: &Panel, x: (f64, f64), y: (f64, f64), w: f64, h: f64) -> (Axis, Axis) {
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
        axis(x, panel.x_scale, w, 52.0),
        axis(y, panel.y_scale, h, 36.0),
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
/// lines, [`fit`]), the x tick labels and label below, the y tick labels (the widest of them)
/// and label to the left, the colour bar to the right. A panel with equal axes gets a plot
/// box of its data's own aspect, centred in the room left (so the structure fills its axes at
/// any size), at the scale of `options` or the largest that fits. The legend goes inside the
/// plot where it covers no data, else to the right of it when that takes at most ~35 % of the
/// area's width, else in rows under the panel.
pub fn place_with(panel: &Panel, area: Rect, options: PlaceOptions) -> PanelLayout {
    let (x, y) = data_ranges(panel);
    let equal = panel.equal_axes;
    let entries = if options.shared_legend {
        Vec::new()
    } else {
        legend_entries(panel)
    };
    let title = fit(&panel.title, TITLE_SIZE, area.w - 8.0, 2);
    // a common factor ×10ᵉ of the y labels sits above the plot, under the title
    // (probed on the area's height: at least the ticks the plot will have)
    let factor = axes(panel, x, y, area.w, area.h).1.factor.is_some();
    let top = match title.lines.len() {
        0 => 16.0,
        n => 8.0 + title.size + (n - 1) as f64 * title.line_height() + 8.0,
    } + if factor { TICK_SIZE + 2.0 } else { 0.0 };
    let bottom = 8.0 + TICK_SIZE + 6.0 + LABEL_SIZE + 8.0;
    let colorbar_w = if panel.colorbar.is_some() { 86.0 } else { 0.0 };
    let build = |outside: f64, below: f64| {
        let right = 14.0 + colorbar_w + outside;
        // the y tick labels' width depends on the ticks, which depend on the height only
        let h = (area.h - top - bottom - below).max(20.0);
        let (_, probe) = axes(panel, x, y, (area.w - 90.0 - right).max(20.0), h);
        let mut left = 8.0 + LABEL_SIZE + 8.0 + widest(&probe.ticks) + 6.0;
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
        let (mut xa, mut ya) = axes(panel, xr, yr, w, h);
        if equal {
            // the data's own aspect, at the figure's scale or the largest that fits a room
            // `w` wide: the scale, the ranges, the box and its axes
            // (a drawing of one point has no extent: a floor keeps the scale finite)
            let span = |(lo, hi): (f64, f64)| (hi - lo).max(1e-9 * lo.abs().max(hi.abs()).max(1.0));
            let at = |w: f64| {
                let fits = (w / span(x)).min(h / span(y));
                let s = options.scale.map_or(fits, |s| s.min(fits));
                let (xr, yr) = (widened(x, MIN_SIDE / s), widened(y, MIN_SIDE / s));
                let (pw, ph) = (((xr.1 - xr.0) * s).min(w), ((yr.1 - yr.0) * s).min(h));
                let (xr, yr) = (widened(xr, pw / s), widened(yr, ph / s));
                let (xa, ya) = axes(panel, xr, yr, pw, ph);
                (s, xr, yr, pw, ph, xa, ya)
            };
            let (mut s, mut pw, mut ph);
            (s, _, _, pw, ph, xa, ya) = at(w);
            // the y tick labels of the box's own range may be wider than the probe's: a
            // wider margin, and the box fitted again to the narrower room
            let needed = 8.0 + LABEL_SIZE + 8.0 + widest(&ya.ticks) + 6.0;
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
            let needed = 8.0 + LABEL_SIZE + 8.0 + widest(&ya.ticks) + 6.0;
            if needed > left {
                left = needed;
                w = (area.w - left - right).max(20.0);
                (xa, ya) = axes(panel, xr, yr, w, h);
                plot.x = area.x + left;
                plot.w = w;
            }
        }
        let colorbar = panel.colorbar.as_ref().map(|_| Rect {
            x: plot.x + plot.w + 16.0 + outside,
            y: plot.y + 0.1 * plot.h,
            w: 12.0,
            h: 0.8 * plot.h,
        });
        let (title, x_label, y_label) = texts(panel, area, plot, &title, widest(&ya.ticks));
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
        }
    };
    let mut layout = build(0.0, 0.0);
    if entries.is_empty() {
        return layout;
    }
    let (lw, lh) = legend_size(&entries, 1, 1.0);
    if let Some(rect) = best_place(panel, &layout, (lw, lh)) {
        layout.legend = Some(Legend {
            rect,
            entries,
            columns: 1,
            scale: 1.0,
        });
        return layout;
    }
    let room_h = area.h - top - bottom;
    for scale in LEGEND_SCALES {
        let (lw, lh) = legend_size(&entries, 1, scale);
        if lw + 10.0 <= 0.35 * area.w && lh <= room_h {
            layout = build(lw + 10.0, 0.0);
            let rect = Rect {
                x: layout.plot.x + layout.plot.w + 8.0,
                y: layout.plot.y,
                w: lw,
                h: lh,
            };
            layout.legend = Some(Legend {
                rect,
                entries,
                columns: 1,
                scale,
            });
            return layout;
        }
    }
    let (columns, scale, (lw, lh)) = legend_rows(&entries, area.w - 16.0, 0.3 * area.h);
    layout = build(0.0, lh + 6.0);
    let rect = Rect {
        x: area.x + 0.5 * (area.w - lw).max(0.0),
        y: area.y + area.h - lh - 4.0,
        w: lw,
        h: lh,
    };
    layout.legend = Some(Legend {
        rect,
        entries,
        columns,
        scale,
    });
    layout
}

/// The title, x label and y label of a panel whose plot is `plot` (`tick_w`: the widest y
/// tick label), each fitted to its room in `area` and kept inside it.
fn texts(
    panel: &Panel,
    area: Rect,
    plot: Rect,
    title: &Fitted,
    tick_w: f64,
) -> (Placed, Placed, Placed) {
    // a centre that keeps a text of width `w` within [lo, hi]
    let centre = |c: f64, w: f64, lo: f64, hi: f64| c.min(hi - 0.5 * w).max(lo + 0.5 * w);
    let title = Placed {
        at: (
            centre(
                plot.x + 0.5 * plot.w,
                title.width(),
                area.x + 4.0,
                area.x + area.w - 4.0,
            ),
            area.y + 8.0 + title.size,
        ),
        text: title.clone(),
    };
    let xl = fit(&panel.x_label, LABEL_SIZE, area.w - 8.0, 1);
    let x_label = Placed {
        at: (
            centre(
                plot.x + 0.5 * plot.w,
                xl.width(),
                area.x + 4.0,
                area.x + area.w - 4.0,
            ),
            plot.y + plot.h + 6.0 + TICK_SIZE + 6.0 + LABEL_SIZE,
        ),
        text: xl,
    };
    // beside the plot, below the title: it may run down past the plot to the x tick labels,
    // not up into the title nor down to the x label
    let (lo, hi) = (plot.y, (plot.y + plot.h + 20.0).min(area.y + area.h - 4.0));
    let yl = fit(&panel.y_label, LABEL_SIZE, hi - lo, 1);
    let y_label = Placed {
        at: (
            (plot.x - tick_w - 14.0).max(area.x + 4.0 + yl.size),
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

/// The legend box inside the plot covering no sampled point, in order of preference (upper
/// right, upper left, lower right, lower left, top and bottom centre, centre right and left);
/// `None` when every place covers some.
fn best_place(panel: &Panel, layout: &PanelLayout, (w, h): (f64, f64)) -> Option<Rect> {
    let p = layout.plot;
    if w + 12.0 > p.w || h + 12.0 > p.h {
        return None;
    }
    let (l, r) = (p.x + 6.0, p.x + p.w - 6.0 - w);
    let (t, b) = (p.y + 6.0, p.y + p.h - 6.0 - h);
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
