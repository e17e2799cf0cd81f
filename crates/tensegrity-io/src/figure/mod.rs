//! Figures for a paper: one or more panels side by side, each with a title, axis labels,
//! linear or logarithmic axes, labelled series of (x, y) points, and for structure drawings
//! equal axes, arrows (loads, reactions), marks (supports, nodes), text notes and a colour bar.
//!
//! The SVG is written here from the panel model ([`layout`] places everything, [`svg`] writes
//! it) with coordinates to 1/10⁵ of a pixel, so curves have no staircases and a structure
//! drawing's scale can be read back from its coordinates. PNG and PDF are rendered from that
//! same SVG ([`render`]: resvg for PNG, svg2pdf for PDF, both with the embedded DejaVu Sans —
//! no system library or installed font is needed). [`Figure::save`] picks the format from the
//! file extension: `.svg`, `.png` or `.pdf`.
//!
//! Size: a figure is laid out in CSS pixels (1 px = 1/96 in); its physical size is
//! [`Figure::size`] pixels, or a [`PageSize`] given in `px`, `in`, `cm`, `mm` or `pt`
//! ([`RenderOptions`]). An SVG carries that size in its `width`/`height`; a PDF's MediaBox is
//! the size in points (72 per inch); a PNG has size × dpi / 96 pixels (96 dpi by default).
//!
//! Axes: on a log axis a value v is drawn at log₁₀ v (non-positive values are left out) and
//! the axis spans whole decades labelled 10ⁿ; a linear axis gets ticks at 1, 2 or 5 × 10ᵏ, all
//! written with the same number of decimals, and a common factor ×10ᵉ when |values| ≥ 10⁴ or
//! < 10⁻²; a linear y axis gets 5 % padding. A panel with [`Panel::equal_axes`] has the same
//! scale (pixels per unit) in x and y: the data range is widened along one axis until
//! (x₁ − x₀)/w = (y₁ − y₀)/h for the plot area w × h. Text is drawn as written (`mean_speed`
//! keeps its underscore) except between a pair of `$`, which marks math: there `_x` or
//! `_{xy}` is a subscript, `^x` or `^{xy}` a superscript, and digits right after a Greek
//! letter become subscripts (`$ι2$` → ι₂); [`literal`] makes any text plain (its dollars
//! escaped), for text from a user or a file.
//!
//! Layout ([`layout`], [`arrange`], [`fit`]) is measured, not fixed: titles and labels are
//! measured on the font and broken into lines or set smaller when wider than their room, a
//! structure panel's plot box takes its drawing's aspect so the drawing fills its axes at any
//! size, the structure panels of a figure share one scale, and a figure of several panels
//! has one legend under them.
//!
//! The legend of a single panel goes where it covers no data: the corner or edge of the plot area whose box
//! covers the fewest sampled points of the curves, marks and arrows, or, when every place
//! inside covers some, outside to the right of the plot (in rows under the panel when that
//! would take more than ~35 % of its width). Each series is one `<polyline>`, so
//! an SVG holds exactly one polyline per series (markers are circles, squares, triangles or
//! diamonds, each with a `data-marker` naming its shape). Every series without a colour of its
//! own takes the next of 12 styles (colour, dash, marker: [`style`], colour-blind- and
//! greyscale-safe). A figure of a run that is not valid carries a red `NOT VALID: reason`
//! above its panels ([`Figure::mark_invalid`]).
//!
//! ```
//! use tensegrity_io::figure::{Figure, Panel, Series};
//! let panel = Panel::new("drop", "time [s]", "height [m]")
//!     .series(Series::new("z", vec![(0.0, 1.0), (0.5, 0.6), (1.0, 0.0)]));
//! let svg = Figure::new(vec![panel]).to_svg()?;
//! assert_eq!(svg.matches("<polyline").count(), 1);
//! assert!(svg.contains("height [m]"));
//! # Ok::<(), tensegrity_io::IoError>(())
//! ```

use crate::error::{IoError, Result};

pub mod arrange;
pub mod fit;
pub mod layout;
pub mod render;
mod save;
mod size;
pub mod style;
pub mod svg;
mod text;

pub use size::{PageSize, RenderOptions, Unit};
pub use text::{literal, plain as plain_text};

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVuSans-LICENSE.txt`).
pub(crate) static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// The font family name of [`FONT`], as the SVG names it.
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// The series colours, in order: [`style::PALETTE`] (Okabe–Ito and Paul Tol's "muted",
/// colour-blind-safe); each series also has a dash pattern and a marker of its own
/// ([`style::series_style`]).
pub const COLORS: [(u8, u8, u8); 12] = style::PALETTE;

/// The scale of an axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Scale {
    /// Linear.
    #[default]
    Linear,
    /// Base-10 logarithmic.
    Log,
}

/// One curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text (an empty label gets no legend entry; a label met again is listed once).
    pub label: String,
    /// (x, y) points, joined in order.
    pub points: Vec<(f64, f64)>,
    /// Draw a circle at every point too.
    pub markers: bool,
    /// An RGB colour of its own (`None`: the next colour of the palette, by position).
    pub color: Option<(u8, u8, u8)>,
    /// Line width in pixels (CSS px).
    pub width: f64,
    /// Dashed instead of solid.
    pub dashed: bool,
}

impl Series {
    /// A curve without markers, 2 px wide.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            markers: false,
            color: None,
            width: 2.0,
            dashed: false,
        }
    }

    /// The same curve in an RGB colour of its own (e.g. red for tension, blue for
    /// compression in a structure drawing), whatever its position in the panel.
    pub fn with_color(mut self, rgb: (u8, u8, u8)) -> Self {
        self.color = Some(rgb);
        self
    }

    /// The same curve with a circle at every point.
    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }

    /// The same curve `width` pixels wide.
    pub fn with_width(mut self, width: f64) -> Self {
        self.width = width;
        self
    }

    /// The same curve dashed.
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// An arrow from `from` to `to` (data coordinates; the head at `to`): a load or a reaction.
#[derive(Debug, Clone, PartialEq)]
pub struct Arrow {
    /// Legend text (listed once per label; empty: none).
    pub label: String,
    /// Tail.
    pub from: (f64, f64),
    /// Head.
    pub to: (f64, f64),
    /// RGB colour.
    pub color: (u8, u8, u8),
}

/// The shape of a [`Mark`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkShape {
    /// A support: a triangle under the point.
    Support,
    /// A node: a small filled circle.
    Dot,
}

/// A symbol at a point (data coordinates).
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// Legend text (listed once per label; empty: none).
    pub label: String,
    /// Where.
    pub at: (f64, f64),
    /// Shape.
    pub shape: MarkShape,
    /// RGB colour.
    pub color: (u8, u8, u8),
}

/// A short text at a point (data coordinates), e.g. a node or member number.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// Where (the text's lower-left corner, offset by 2 px).
    pub at: (f64, f64),
    /// The text (markup as for labels).
    pub text: String,
    /// RGB colour.
    pub color: (u8, u8, u8),
}

/// A colour bar beside the plot: the diverging map of [`diverging_color`] over
/// [−`max_abs`, `max_abs`].
#[derive(Debug, Clone, PartialEq)]
pub struct ColorBar {
    /// The quantity and its unit, e.g. `force [N]`.
    pub label: String,
    /// The largest magnitude of the map (> 0).
    pub max_abs: f64,
}

/// The diverging colour of `value` on [−`max_abs`, `max_abs`]: compression (negative) from
/// light grey to dark navy (#08306b, the darkest of ColorBrewer's "Blues", CIELAB L\* 21),
/// tension (positive) from light grey to red (#e34a33, of ColorBrewer's "OrRd", L\* 53), 0
/// light grey (#c8c8c8, L\* 81). The lightness falls with the magnitude on both sides, and the
/// two ends differ in lightness by 32 (greyscale-safe: at full magnitude compression prints
/// near black, tension mid grey); a structure drawing also dashes tension, so any two members
/// of opposite sign differ in greyscale.
pub fn diverging_color(value: f64, max_abs: f64) -> (u8, u8, u8) {
    let t = if max_abs > 0.0 && value.is_finite() {
        (value.abs() / max_abs).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let grey = (0xc8 as f64, 0xc8 as f64, 0xc8 as f64);
    let end = if value >= 0.0 {
        (0xe3 as f64, 0x4a as f64, 0x33 as f64)
    } else {
        (0x08 as f64, 0x30 as f64, 0x6b as f64)
    };
    let mix = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
    (mix(grey.0, end.0), mix(grey.1, end.1), mix(grey.2, end.2))
}

/// One panel: title, axes and what is drawn in it.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// x-axis scale.
    pub x_scale: Scale,
    /// y-axis scale.
    pub y_scale: Scale,
    /// The curves, drawn in order (later ones on top).
    pub series: Vec<Series>,
    /// Empty band above the data, as a fraction of the data's y span (linear y axes), which
    /// the legend placement may then choose.
    pub legend_headroom: f64,
    /// The same scale in x and y (structure drawings).
    pub equal_axes: bool,
    /// Arrows, drawn over the curves.
    pub arrows: Vec<Arrow>,
    /// Symbols, drawn over the curves.
    pub marks: Vec<Mark>,
    /// Texts, drawn last.
    pub notes: Vec<Note>,
    /// A colour bar to the right of the plot.
    pub colorbar: Option<ColorBar>,
    /// Grid lines at the ticks (default on; off for structure drawings).
    pub grid: bool,
}

impl Panel {
    /// An empty panel with linear axes.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            series: Vec::new(),
            legend_headroom: 0.0,
            equal_axes: false,
            arrows: Vec::new(),
            marks: Vec::new(),
            notes: Vec::new(),
            colorbar: None,
            grid: true,
        }
    }

    /// Keeps an empty band of `fraction` of the y span above the data (linear y axes), where
    /// the legend then usually goes.
    pub fn legend_above(mut self, fraction: f64) -> Self {
        self.legend_headroom = if fraction.is_finite() {
            fraction.max(0.0)
        } else {
            0.0
        };
        self
    }

    /// Logarithmic x and y axes.
    pub fn log_log(mut self) -> Self {
        self.x_scale = Scale::Log;
        self.y_scale = Scale::Log;
        self
    }

    /// The same scale in x and y, no grid (a structure drawn to scale).
    pub fn with_equal_axes(mut self) -> Self {
        self.equal_axes = true;
        self.grid = false;
        self
    }

    /// Adds a curve.
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// The points of every series in drawing coordinates (log₁₀ on log axes), finite only.
    pub(crate) fn drawn_points(&self) -> Vec<Vec<(f64, f64)>> {
        self.series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .filter_map(|&p| self.to_drawing(p))
                    .collect()
            })
            .collect()
    }

    /// A data point in drawing coordinates (log₁₀ on log axes), if it can be drawn.
    pub(crate) fn to_drawing(&self, (x, y): (f64, f64)) -> Option<(f64, f64)> {
        let map = |scale: Scale, v: f64| match scale {
            Scale::Linear => v,
            Scale::Log if v > 0.0 => v.log10(),
            Scale::Log => f64::NAN,
        };
        let p = (map(self.x_scale, x), map(self.y_scale, y));
        (p.0.is_finite() && p.1.is_finite()).then_some(p)
    }
}

/// The smallest side of a panel (px, 0.75 in): [`Figure::page_px`] refuses a page that
/// leaves a panel less.
pub const MIN_PANEL_PX: f64 = 72.0;

/// A figure: panels side by side, each `panel_size` pixels unless a size is given.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// The panels, left to right.
    pub panels: Vec<Panel>,
    /// Width and height of one panel (CSS pixels; SVG user units).
    pub panel_size: (u32, u32),
    /// Why the run the figure shows is not valid ([`Figure::mark_invalid`]): drawn in red,
    /// `NOT VALID: reason`, in a band along the figure's top left, above the panels.
    pub invalid: Option<String>,
    /// Each structure panel drawn at its own largest scale, not at one scale across the
    /// figure ([`arrange`]); a figure that sets this says so in its titles.
    pub independent_scales: bool,
}

impl Figure {
    /// A figure of `panels`, 540 × 400 pixels each.
    pub fn new(panels: Vec<Panel>) -> Self {
        Self {
            panels,
            panel_size: (540, 400),
            invalid: None,
            independent_scales: false,
        }
    }

    /// The same figure with each structure panel at its own scale (a detail beside an
    /// overview), where by default all are drawn at one scale.
    ///
    /// ```
    /// use tensegrity_io::figure::{arrange::arrange, Figure, Panel, Series};
    /// let bar = |len: f64| {
    ///     Panel::new("bar", "x [m]", "z [m]")
    ///         .with_equal_axes()
    ///         .series(Series::new("", vec![(0.0, 0.0), (len, 0.5 * len)]))
    /// };
    /// let fig = Figure::new(vec![bar(1.0), bar(2.0)]).with_independent_scales();
    /// let a = arrange(&fig, (800.0, 300.0), 0.0);
    /// // each fills its panel: the short bar at about twice the scale
    /// let (s0, s1) = (a.panels[0].scales().0, a.panels[1].scales().0);
    /// assert!((s0 / s1 - 2.0).abs() < 0.05);
    /// ```
    pub fn with_independent_scales(mut self) -> Self {
        self.independent_scales = true;
        self
    }

    /// The same figure marked as showing a run that is not valid, `reason` (e.g. the first
    /// warning's kind): the writer draws `NOT VALID: reason` in red (an SVG `<text
    /// class="invalid">`, so in the PNG and PDF too) in a band of its own along the top of the
    /// figure, the panels below it, so the mark never covers a panel. The text is plain (no
    /// math); a reason wider than the figure is cut with `…`.
    ///
    /// ```
    /// use tensegrity_io::figure::{Figure, Panel, Series};
    /// let panel = Panel::new("run", "t [s]", "h [m]").series(Series::new("h", vec![(0.0, 1.0), (1.0, 0.5)]));
    /// let fig = Figure::new(vec![panel]);
    /// assert!(!fig.to_svg()?.contains("NOT VALID"));
    /// let svg = fig.mark_invalid("not_converged").to_svg()?;
    /// assert!(svg.contains("NOT VALID: not_converged"));
    /// # Ok::<(), tensegrity_io::IoError>(())
    /// ```
    pub fn mark_invalid(mut self, reason: impl Into<String>) -> Self {
        self.invalid = Some(reason.into());
        self
    }

    /// The same figure with another panel size (pixels).
    pub fn with_panel_size(mut self, width: u32, height: u32) -> Self {
        self.panel_size = (width, height);
        self
    }

    /// Width and height of the whole figure at its own panel size (pixels).
    pub fn size(&self) -> (u32, u32) {
        let (w, h) = self.panel_size;
        (w.saturating_mul(self.panels.len() as u32), h)
    }

    /// The figure's size in CSS pixels under `options` (its own size unless one is given),
    /// checked: at least one panel, each at least [`MIN_PANEL_PX`] px a side (three panels
    /// side by side on a 6 cm wide page), the figure at most 20000 px a side.
    pub fn page_px(&self, options: &RenderOptions) -> Result<(f64, f64)> {
        if self.panels.is_empty() {
            return Err(IoError::InvalidFigure {
                reason: "a figure needs at least one panel",
            });
        }
        let (w, h) = match options.size {
            Some(size) => size.px(),
            None => {
                let (w, h) = self.size();
                (w as f64, h as f64)
            }
        };
        let pw = w / self.panels.len() as f64;
        if pw < MIN_PANEL_PX || h < MIN_PANEL_PX || w > 20_000.0 || h > 20_000.0 {
            return Err(IoError::InvalidFigure {
                reason: "each panel must be at least 72 × 72 px (0.75 in) and the figure at most 20000 px a side",
            });
        }
        Ok((w, h))
    }

    /// The figure as SVG text at its own size.
    pub fn to_svg(&self) -> Result<String> {
        self.to_svg_with(&RenderOptions::default())
    }

    /// The figure as SVG text under `options` (the size; the dpi does not change an SVG).
    pub fn to_svg_with(&self, options: &RenderOptions) -> Result<String> {
        let size = self.page_px(options)?;
        Ok(svg::write(self, size, options.size.map(|s| s.unit)))
    }

    /// The figure as an RGB image (8 bits per channel, row-major) at its own size and 96 dpi
    /// (one pixel per CSS pixel), with its size in pixels.
    pub fn to_rgb(&self) -> Result<(Vec<u8>, (u32, u32))> {
        self.to_rgb_with(&RenderOptions::default())
    }

    /// The figure as an RGB image under `options`: size × dpi / 96 pixels.
    pub fn to_rgb_with(&self, options: &RenderOptions) -> Result<(Vec<u8>, (u32, u32))> {
        let text = self.to_svg_with(options)?;
        render::rgb(&text, options.dpi)
    }

    /// The figure as PNG bytes under `options`.
    pub fn to_png_with(&self, options: &RenderOptions) -> Result<Vec<u8>> {
        let (rgb, size) = self.to_rgb_with(options)?;
        let mut out = Vec::new();
        encode_png(&mut out, &rgb, size)?;
        Ok(out)
    }

    /// The figure as a one-page PDF under `options`: the page is the size in points.
    pub fn to_pdf_with(&self, options: &RenderOptions) -> Result<Vec<u8>> {
        let size = self.page_px(options)?;
        render::pdf(&svg::write_points(self, size))
    }
}

/// Encodes an RGB buffer as PNG.
pub(crate) fn encode_png(
    w: &mut dyn std::io::Write,
    rgb: &[u8],
    (width, height): (u32, u32),
) -> Result<()> {
    let mut encoder = png::Encoder::new(w, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let to_io = |e: png::EncodingError| IoError::Stream {
        what: "PNG figure",
        source: match e {
            png::EncodingError::IoError(io) => io,
            other => std::io::Error::other(other.to_string()),
        },
    };
    let mut writer = encoder.write_header().map_err(to_io)?;
    writer.write_image_data(rgb).map_err(to_io)?;
    writer.finish().map_err(to_io)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_positive_values_are_left_out_on_log_axes() {
        let p = Panel::new("t", "x", "y")
            .log_log()
            .series(Series::new("a", vec![(1.0, 1.0), (0.0, 1.0), (10.0, -1.0)]));
        assert_eq!(p.drawn_points(), vec![vec![(0.0, 0.0)]]);
    }

    #[test]
    fn the_diverging_map_is_grey_at_zero_and_darker_with_magnitude() {
        assert_eq!(diverging_color(0.0, 1.0), (0xc8, 0xc8, 0xc8));
        assert_eq!(diverging_color(2.0, 1.0), (0xe3, 0x4a, 0x33));
        assert_eq!(diverging_color(-1.0, 1.0), (0x08, 0x30, 0x6b));
        let lum = |(r, g, b): (u8, u8, u8)| 0.3 * r as f64 + 0.59 * g as f64 + 0.11 * b as f64;
        assert!(lum(diverging_color(0.5, 1.0)) > lum(diverging_color(0.9, 1.0)));
        assert!(lum(diverging_color(-0.5, 1.0)) > lum(diverging_color(-0.9, 1.0)));
    }
}
