//! Line figures on `plotters`: one or more panels side by side, each with a title, axis labels,
//! linear or logarithmic axes and labelled series of (x, y) points with a legend.
//!
//! [`Figure::save`] picks the format from the file extension: `.svg` (text stays text) or
//! `.png` (drawn with the embedded DejaVu Sans font through `ab_glyph`, encoded with `png`);
//! no system library or installed font is needed. On a log axis a value v is drawn at log₁₀ v
//! (non-positive values are left out) and the axis spans whole decades; a linear y axis gets
//! 5 % padding. Each series is one polyline (plus optional circle markers); the plot is framed
//! by a rectangle and legend entries are small filled bars, so an SVG holds exactly one
//! `<polyline>` per series.
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
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// DejaVu Sans (Bitstream Vera licence, see `assets/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");

/// The series colours, in order.
const COLORS: [RGBColor; 6] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x17, 0xbe, 0xcf),
];

/// Registers the embedded font as plotters' `sans-serif` once.
fn ensure_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, FONT).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(IoError::Drawing {
            message: "the embedded font could not be loaded".into(),
        })
    }
}

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
    /// Legend text (an empty label gets no legend entry).
    pub label: String,
    /// (x, y) points, joined in order.
    pub points: Vec<(f64, f64)>,
    /// Draw a circle at every point too.
    pub markers: bool,
    /// An RGB colour of its own (`None`: the next colour of the palette, by position).
    pub color: Option<(u8, u8, u8)>,
}

impl Series {
    /// A curve without markers.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            label: label.into(),
            points,
            markers: false,
            color: None,
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
}

/// One panel: title, axes and curves.
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
    /// The curves.
    pub series: Vec<Series>,
    /// Empty band above the data, as a fraction of the data's y span, where the legend sits
    /// (0: the legend may cover the data).
    pub legend_headroom: f64,
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
        }
    }

    /// Keeps an empty band of `fraction` of the y span above the data for the legend, so
    /// that it covers no curve (linear y axes).
    pub fn legend_above(mut self, fraction: f64) -> Self {
        self.legend_headroom = fraction.max(0.0);
        self
    }

    /// Logarithmic x and y axes.
    pub fn log_log(mut self) -> Self {
        self.x_scale = Scale::Log;
        self.y_scale = Scale::Log;
        self
    }

    /// Adds a curve.
    pub fn series(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// The points of every series in drawing coordinates (log₁₀ on log axes), finite only.
    fn drawn_points(&self) -> Vec<Vec<(f64, f64)>> {
        let map = |scale: Scale, v: f64| match scale {
            Scale::Linear => v,
            Scale::Log if v > 0.0 => v.log10(),
            Scale::Log => f64::NAN,
        };
        self.series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .map(|&(x, y)| (map(self.x_scale, x), map(self.y_scale, y)))
                    .filter(|(x, y)| x.is_finite() && y.is_finite())
                    .collect()
            })
            .collect()
    }
}

/// Range of one axis in drawing coordinates.
fn axis_range(values: impl Iterator<Item = f64>, scale: Scale, pad: f64) -> (f64, f64) {
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
                1e-12 * lo.abs().max(1.0)
            };
            (lo - pad * span, lo + span + pad * span)
        }
    }
}

/// Tick text: `1e-3` style on log axes (decades), short decimals on linear ones.
fn tick_label(v: f64, scale: Scale, span: f64) -> String {
    // a tick computed as lo + k·step lands on 0 only up to round-off
    let v = if scale == Scale::Linear && v.abs() < 1e-9 * span {
        0.0
    } else {
        v
    };
    match scale {
        Scale::Log if (v - v.round()).abs() < 1e-9 => format!("1e{}", v.round() as i64),
        Scale::Log => format!("{:.1e}", 10f64.powf(v)),
        Scale::Linear if v == 0.0 => "0".into(),
        Scale::Linear if (1e-3..1e4).contains(&v.abs()) => {
            let s = format!("{v:.4}");
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        }
        Scale::Linear => format!("{v:.1e}"),
    }
}

fn drawing_error(e: impl std::fmt::Display) -> IoError {
    IoError::Drawing {
        message: e.to_string(),
    }
}

/// A figure: panels side by side, each `panel_size` pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// The panels, left to right.
    pub panels: Vec<Panel>,
    /// Width and height of one panel (pixels; SVG user units).
    pub panel_size: (u32, u32),
}

impl Figure {
    /// A figure of `panels`, 540 × 400 pixels each.
    pub fn new(panels: Vec<Panel>) -> Self {
        Self {
            panels,
            panel_size: (540, 400),
        }
    }

    /// The same figure with another panel size (pixels).
    pub fn with_panel_size(mut self, width: u32, height: u32) -> Self {
        self.panel_size = (width, height);
        self
    }

    /// Width and height of the whole figure (pixels).
    pub fn size(&self) -> (u32, u32) {
        let (w, h) = self.panel_size;
        (w.saturating_mul(self.panels.len() as u32), h)
    }

    fn check(&self) -> Result<(u32, u32)> {
        if self.panels.is_empty() {
            return Err(IoError::InvalidFigure {
                reason: "a figure needs at least one panel",
            });
        }
        let (w, h) = self.size();
        let (pw, ph) = self.panel_size;
        if pw < 100 || ph < 100 || w > 20_000 || h > 20_000 {
            return Err(IoError::InvalidFigure {
                reason:
                    "panels must be at least 100 × 100 and the figure at most 20000 pixels a side",
            });
        }
        Ok((w, h))
    }

    /// The figure as SVG text.
    pub fn to_svg(&self) -> Result<String> {
        let size = self.check()?;
        ensure_font()?;
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            self.draw(&root)?;
        }
        Ok(text)
    }

    /// The figure as an RGB image (8 bits per channel, row-major), with its size.
    pub fn to_rgb(&self) -> Result<(Vec<u8>, (u32, u32))> {
        let (w, h) = self.check()?;
        ensure_font()?;
        let mut buffer = vec![0u8; w as usize * h as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (w, h)).into_drawing_area();
            self.draw(&root)?;
        }
        Ok((buffer, (w, h)))
    }

    /// Writes the figure to `path`: SVG for `.svg`, PNG for `.png` (case-insensitive), through
    /// a [`crate::sink::FigureSink`] (a command opens the sink before its work instead).
    ///
    /// ```
    /// use tensegrity_io::figure::{Figure, Panel, Series};
    /// let fig = Figure::new(vec![Panel::new("error", "time [s]", "error [m]")
    ///     .log_log()
    ///     .series(Series::new("rk4", vec![(1e-3, 1e-4), (1e-2, 1e-8)]).with_markers())]);
    /// let dir = std::env::temp_dir();
    /// let path = dir.join(format!("tensegrity-io-fig-{}.png", std::process::id()));
    /// fig.save(&path)?;
    /// assert!(std::fs::read(&path).unwrap().starts_with(b"\x89PNG"));
    /// # std::fs::remove_file(&path).unwrap();
    /// assert!(fig.save(&dir.join("figure.bmp")).is_err());
    /// # Ok::<(), tensegrity_io::IoError>(())
    /// ```
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::sink::FigureSink::open(path)?.finish(self)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        root.fill(&WHITE).map_err(drawing_error)?;
        let areas = root.split_evenly((1, self.panels.len()));
        for (area, panel) in areas.iter().zip(&self.panels) {
            draw_panel(area, panel)?;
        }
        root.present().map_err(drawing_error)
    }
}

/// Draws one panel into its area.
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Result<()> {
    let points = panel.drawn_points();
    let all = || points.iter().flatten();
    let (xs, ys) = (panel.x_scale, panel.y_scale);
    let x = axis_range(all().map(|p| p.0), panel.x_scale, 0.0);
    let mut y = axis_range(all().map(|p| p.1), panel.y_scale, 0.05);
    if panel.y_scale == Scale::Linear {
        y.1 += panel.legend_headroom * (y.1 - y.0) / 1.1;
    }
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(42)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(drawing_error)?;
    let (x_span, y_span) = ((x.1 - x.0).abs(), (y.1 - y.0).abs());
    let x_fmt = move |v: &f64| tick_label(*v, xs, x_span);
    let y_fmt = move |v: &f64| tick_label(*v, ys, y_span);
    // a log axis is labelled at its decades only
    let labels = |scale: Scale, (lo, hi): (f64, f64)| match scale {
        Scale::Log => ((hi - lo).round() as usize + 1).min(12),
        Scale::Linear => 10,
    };
    chart
        .configure_mesh()
        .x_labels(labels(xs, x))
        .y_labels(labels(ys, y))
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .max_light_lines(0)
        .bold_line_style(RGBColor(0xe5, 0xe5, 0xe5))
        // invisible axis lines and no tick marks (plotters draws them as polylines, and skips
        // transparent ones): a frame instead
        .axis_style(TRANSPARENT)
        .set_all_tick_mark_size(0)
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(drawing_error)?;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(x.0, y.0), (x.1, y.1)],
            BLACK.stroke_width(1),
        )))
        .map_err(drawing_error)?;
    for (k, (series, pts)) in panel.series.iter().zip(&points).enumerate() {
        let color = series
            .color
            .map_or(COLORS[k % COLORS.len()], |(r, g, b)| RGBColor(r, g, b));
        let drawn = chart
            .draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))
            .map_err(drawing_error)?;
        if !series.label.is_empty() {
            drawn.label(series.label.as_str()).legend(move |(x, y)| {
                Rectangle::new([(x, y - 2), (x + 18, y + 2)], color.filled())
            });
        }
        if series.markers {
            chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(drawing_error)?;
        }
    }
    if panel.series.iter().any(|s| !s.label.is_empty()) {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 12))
            .draw()
            .map_err(drawing_error)?;
    }
    Ok(())
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
    fn log_axes_span_whole_decades_and_label_them() {
        let (lo, hi) = axis_range([-3.2, -1.5].into_iter(), Scale::Log, 0.0);
        assert_eq!((lo, hi), (-4.0, -1.0));
        assert_eq!(tick_label(-3.0, Scale::Log, 4.0), "1e-3");
        assert_eq!(tick_label(0.25, Scale::Linear, 1.0), "0.25");
        assert_eq!(tick_label(2.0e-5, Scale::Linear, 1e-4), "2.0e-5");
        // round-off of lo + k·step near zero is labelled 0
        assert_eq!(tick_label(6.9e-18, Scale::Linear, 0.08), "0");
        let (lo, hi) = axis_range([0.0, 10.0].into_iter(), Scale::Linear, 0.05);
        assert!((lo + 0.5).abs() < 1e-12 && (hi - 10.5).abs() < 1e-12);
    }

    #[test]
    fn non_positive_values_are_left_out_on_log_axes() {
        let p = Panel::new("t", "x", "y")
            .log_log()
            .series(Series::new("a", vec![(1.0, 1.0), (0.0, 1.0), (10.0, -1.0)]));
        assert_eq!(p.drawn_points(), vec![vec![(0.0, 0.0)]]);
    }
}
