//! The SVG text of a figure, written from the panel model and its [`layout`]: coordinates to
//! 10⁻⁵ px (no whole-pixel staircases; a structure drawing's scale can be read back), one
//! `<polyline>` per series, text as `<text>` with `<tspan>`s for sub- and superscripts.
//!
//! Each panel is a `<g class="panel">` whose `data-plot` (left top width height, px),
//! `data-x-range` and `data-y-range` (drawing coordinates) give the map from data to pixels:
//! x_px = left + (x − x₀)·width/(x₁ − x₀), y_px = top + height − (y − y₀)·height/(y₁ − y₀).

use super::arrange;
use super::layout::{self, Glyph, Markers, PanelLayout, Rect, TICK_SIZE};
use super::style::{Dash, Marker};
use super::text::{self, Shift, SCRIPT_SCALE};
use super::{diverging_color, Figure, MarkShape, Panel, Unit, FONT_FAMILY};
use std::fmt::Write;

/// A number with at most 5 decimals, trailing zeros dropped.
pub fn num(v: f64) -> String {
    let s = format!("{v:.5}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn rgb((r, g, b): (u8, u8, u8)) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// Text with its markup as `<text>` at (x, y); `anchor` start, middle or end; `rotate` −90
/// for a y-axis label.
fn label(out: &mut String, t: &str, (x, y): (f64, f64), size: f64, anchor: &str, rotate: bool) {
    let transform = if rotate {
        format!(" transform=\"rotate(-90 {} {})\"", num(x), num(y))
    } else {
        String::new()
    };
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"{anchor}\"{transform}>",
        num(x),
        num(y),
        num(size)
    );
    let runs = text::runs(t);
    if let [(run, Shift::Normal)] = runs.as_slice() {
        out.push_str(&escape(run));
        out.push_str("</text>\n");
        return;
    }
    let mut offset = 0.0;
    for (run, shift) in runs {
        let (target, s) = match shift {
            Shift::Normal => (0.0, size),
            Shift::Sub => (0.28 * size, size * SCRIPT_SCALE),
            Shift::Sup => (-0.42 * size, size * SCRIPT_SCALE),
        };
        let dy = target - offset;
        offset = target;
        let dy = if dy == 0.0 {
            String::new()
        } else {
            format!(" dy=\"{}\"", num(dy))
        };
        let _ = write!(
            out,
            "<tspan font-size=\"{}\"{dy}>{}</tspan>",
            num(s),
            escape(&run)
        );
    }
    out.push_str("</text>\n");
}

/// A placed text, each line centred on its anchor, the lines `line_height` apart (a y-axis
/// label, one line, turned by −90°).
fn placed(out: &mut String, p: &layout::Placed, rotate: bool) {
    for (i, line) in p.text.lines.iter().enumerate() {
        let y = p.at.1 + i as f64 * p.text.line_height();
        label(out, line, (p.at.0, y), p.text.size, "middle", rotate);
    }
}

/// The SVG of `figure` laid out on `size` CSS pixels; `unit` the unit of its `width` and
/// `height` attributes (pixels when `None`).
pub fn write(figure: &Figure, (w, h): (f64, f64), unit: Option<Unit>) -> String {
    let unit = unit.unwrap_or_default();
    let (pw, ph) = (w / unit.px(), h / unit.px());
    let width = format!("{}{}", num(pw), unit.suffix());
    let height = format!("{}{}", num(ph), unit.suffix());
    write_with_size(figure, (w, h), (&width, &height))
}

/// The SVG of `figure` laid out on `size` CSS pixels, its `width` and `height` the page's
/// size in points written as user units (0.75 of the pixels), what [`super::render::pdf`]
/// takes: the 96 → 72 scale then lies in the SVG's own `viewBox`, inside the drawing, where
/// svg2pdf places gradients with it (svg2pdf 0.13 leaves its own dpi scale out of a
/// gradient's pattern matrix: a colour bar converted at 96 dpi has its stops 4/3 too far
/// apart, zero 74 % up the bar).
pub fn write_points(figure: &Figure, (w, h): (f64, f64)) -> String {
    let (width, height) = (num(0.75 * w), num(0.75 * h));
    write_with_size(figure, (w, h), (&width, &height))
}

/// The SVG of `figure` laid out on `size` CSS pixels with these `width` and `height`
/// attributes.
fn write_with_size(figure: &Figure, (w, h): (f64, f64), (width, height): (&str, &str)) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" viewBox=\"0 0 {} {}\" font-family=\"{FONT_FAMILY}, sans-serif\">",
        num(w),
        num(h)
    );
    out.push_str("<rect x=\"0\" y=\"0\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n");
    let band = match &figure.invalid {
        Some(reason) => invalid_mark(&mut out, reason, w),
        None => 0.0,
    };
    let arranged = arrange::arrange(figure, (w, h), band);
    for (k, (panel, l)) in figure.panels.iter().zip(&arranged.panels).enumerate() {
        write_panel(&mut out, panel, l, k);
    }
    if let Some(legend) = &arranged.legend {
        write_legend(&mut out, legend);
    }
    out.push_str("</svg>\n");
    out
}

/// The red `NOT VALID: reason` of [`Figure::mark_invalid`] at the figure's top left, plain
/// text cut with `…` to the figure's width `w`; the height of its band (px), which the panels
/// are laid out below.
fn invalid_mark(out: &mut String, reason: &str, w: f64) -> f64 {
    const SIZE: f64 = 11.0;
    let mut t = format!("NOT VALID: {}", text::literal(reason));
    while text::width(&t, SIZE) > w - 12.0 && t.chars().count() > 12 {
        t = t.trim_end_matches('…').to_string();
        t.pop();
        t.push('…');
    }
    let _ = write!(out, "<g class=\"invalid\" fill=\"#d00000\">");
    label(out, &t, (6.0, 4.0 + SIZE), SIZE, "start", false);
    out.push_str("</g>\n");
    SIZE + 8.0
}

fn write_panel(out: &mut String, panel: &Panel, l: &PanelLayout, k: usize) {
    let p = l.plot;
    let _ = writeln!(
        out,
        "<g class=\"panel\" data-plot=\"{} {} {} {}\" data-x-range=\"{} {}\" data-y-range=\"{} {}\">",
        num(p.x),
        num(p.y),
        num(p.w),
        num(p.h),
        l.x.lo,
        l.x.hi,
        l.y.lo,
        l.y.hi
    );
    placed(out, &l.title, false);
    write_axes(out, panel, l);
    // the data clipped to the plot box only where it reaches the box's edge: a clip costs
    // the rasteriser a layer of the whole page (a fifth of an animation frame's time)
    let mut data = String::new();
    if write_data(&mut data, panel, l) {
        let _ = writeln!(
            out,
            "<clipPath id=\"plot{k}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath>\n<g class=\"data\" clip-path=\"url(#plot{k})\">",
            num(p.x),
            num(p.y),
            num(p.w),
            num(p.h)
        );
    } else {
        out.push_str("<g class=\"data\">\n");
    }
    out.push_str(&data);
    out.push_str("</g>\n");
    let _ = writeln!(
        out,
        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#000000\" stroke-width=\"0.8\"/>",
        num(p.x),
        num(p.y),
        num(p.w),
        num(p.h)
    );
    if let Some(legend) = &l.legend {
        write_legend(out, legend);
    }
    if let (Some(bar), Some(rect)) = (&panel.colorbar, l.colorbar) {
        write_colorbar(out, bar, rect, k, l);
    }
    out.push_str("</g>\n");
}

fn write_axes(out: &mut String, panel: &Panel, l: &PanelLayout) {
    let p = l.plot;
    let grid = |out: &mut String, a: (f64, f64), b: (f64, f64)| {
        let _ = writeln!(
            out,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#e3e3e3\" stroke-width=\"0.7\"/>",
            num(a.0),
            num(a.1),
            num(b.0),
            num(b.1)
        );
    };
    let tick = |out: &mut String, a: (f64, f64), b: (f64, f64)| {
        let _ = writeln!(
            out,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#000000\" stroke-width=\"0.8\"/>",
            num(a.0),
            num(a.1),
            num(b.0),
            num(b.1)
        );
    };
    let bottom = p.y + p.h;
    // tick labels and gaps at the layout's text scale (smaller on a small page)
    let (size, k) = (l.tick_size(), l.text);
    for (v, t) in &l.x.ticks {
        let x = l.px((*v, l.y.lo)).0;
        if panel.grid {
            grid(out, (x, p.y), (x, bottom));
        }
        tick(out, (x, bottom), (x, bottom + 4.0 * k));
        label(out, t, (x, bottom + 6.0 * k + size), size, "middle", false);
    }
    for (v, t) in &l.y.ticks {
        let y = l.px((l.x.lo, *v)).1;
        if panel.grid {
            grid(out, (p.x, y), (p.x + p.w, y));
        }
        tick(out, (p.x - 4.0 * k, y), (p.x, y));
        label(out, t, (p.x - 6.0 * k, y + 0.35 * size), size, "end", false);
    }
    placed(out, &l.x_label, false);
    placed(out, &l.y_label, true);
    let x_label_y = l.x_label.at.1;
    if let Some(e) = l.x.factor {
        let t = format!("×{}", layout::power_of_ten(e));
        label(out, &t, (p.x + p.w, x_label_y), size, "end", false);
    }
    if let Some(e) = l.y.factor {
        let t = format!("×{}", layout::power_of_ten(e));
        label(out, &t, (p.x, p.y - 4.0 * k), size, "start", false);
    }
}

/// The `stroke-dasharray` attribute of `dash` on a line `width` px wide (empty if solid).
fn dasharray(dash: Dash, width: f64) -> String {
    match dash.pattern(width) {
        Some(p) => {
            let p: Vec<String> = p.iter().map(|&v| num(v)).collect();
            format!(" stroke-dasharray=\"{}\"", p.join(" "))
        }
        None => String::new(),
    }
}

fn polyline(out: &mut String, pts: &[(f64, f64)], color: (u8, u8, u8), width: f64, dash: Dash) {
    let points: Vec<String> = pts
        .iter()
        .map(|&(x, y)| format!("{},{}", num(x), num(y)))
        .collect();
    let dash = dasharray(dash, width);
    let _ = writeln!(
        out,
        "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\" stroke-linecap=\"round\"{dash}/>",
        points.join(" "),
        rgb(color),
        num(width)
    );
}

/// A series marker of `shape` centred at (x, y), about 6 px across, with a thin white edge
/// so that overlapping markers stay apart (`data-marker` names the shape).
fn marker(out: &mut String, shape: Marker, (x, y): (f64, f64), color: (u8, u8, u8)) {
    let c = rgb(color);
    let edge = "stroke=\"#ffffff\" stroke-width=\"0.6\"";
    let poly = |pts: &[(f64, f64)]| -> String {
        let p: Vec<String> = pts
            .iter()
            .map(|&(dx, dy)| format!("{},{}", num(x + dx), num(y + dy)))
            .collect();
        p.join(" ")
    };
    let _ = match shape {
        Marker::Circle => writeln!(
            out,
            "<circle data-marker=\"circle\" cx=\"{}\" cy=\"{}\" r=\"3.2\" fill=\"{c}\" {edge}/>",
            num(x),
            num(y)
        ),
        Marker::Ring => writeln!(
            out,
            "<circle data-marker=\"ring\" cx=\"{}\" cy=\"{}\" r=\"3\" fill=\"#ffffff\" stroke=\"{c}\" stroke-width=\"1.5\"/>",
            num(x),
            num(y)
        ),
        Marker::Square => writeln!(
            out,
            "<rect data-marker=\"square\" x=\"{}\" y=\"{}\" width=\"5.6\" height=\"5.6\" fill=\"{c}\" {edge}/>",
            num(x - 2.8),
            num(y - 2.8)
        ),
        Marker::TriangleUp => writeln!(
            out,
            "<polygon data-marker=\"triangle-up\" points=\"{}\" fill=\"{c}\" {edge}/>",
            poly(&[(0.0, -4.0), (3.6, 2.6), (-3.6, 2.6)])
        ),
        Marker::TriangleDown => writeln!(
            out,
            "<polygon data-marker=\"triangle-down\" points=\"{}\" fill=\"{c}\" {edge}/>",
            poly(&[(0.0, 4.0), (3.6, -2.6), (-3.6, -2.6)])
        ),
        Marker::Diamond => writeln!(
            out,
            "<polygon data-marker=\"diamond\" points=\"{}\" fill=\"{c}\" {edge}/>",
            poly(&[(0.0, -4.0), (3.4, 0.0), (0.0, 4.0), (-3.4, 0.0)])
        ),
    };
}

/// Points every `step` px along the polyline `px`, the first `offset` px from its start.
fn spaced(px: &[(f64, f64)], step: f64, offset: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut next = offset;
    let mut walked = 0.0;
    for w in px.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        while len > 0.0 && next <= walked + len {
            let f = (next - walked) / len;
            out.push((a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)));
            next += step;
        }
        walked += len;
    }
    out
}

/// A straight stroke as `<line>` (legend samples, arrow shafts: not a series, so no
/// `<polyline>`).
fn segment(
    out: &mut String,
    a: (f64, f64),
    b: (f64, f64),
    color: (u8, u8, u8),
    width: f64,
    dash: Dash,
) {
    let dash = dasharray(dash, width);
    let _ = writeln!(
        out,
        "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"{}\"{dash}/>",
        num(a.0),
        num(a.1),
        num(b.0),
        num(b.1),
        rgb(color),
        num(width)
    );
}

fn arrow(out: &mut String, from: (f64, f64), to: (f64, f64), color: (u8, u8, u8)) {
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = dx.hypot(dy);
    if len < 1e-9 {
        return;
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = 8.0f64.min(0.6 * len);
    let base = (to.0 - head * ux, to.1 - head * uy);
    segment(out, from, base, color, 1.6, Dash::Solid);
    let (nx, ny) = (-uy * 0.4 * head, ux * 0.4 * head);
    let _ = writeln!(
        out,
        "<polygon points=\"{},{} {},{} {},{}\" fill=\"{}\"/>",
        num(to.0),
        num(to.1),
        num(base.0 + nx),
        num(base.1 + ny),
        num(base.0 - nx),
        num(base.1 - ny),
        rgb(color)
    );
}

fn mark(out: &mut String, shape: MarkShape, (x, y): (f64, f64), color: (u8, u8, u8)) {
    match shape {
        MarkShape::Dot => {
            let _ = writeln!(
                out,
                "<circle cx=\"{}\" cy=\"{}\" r=\"2.5\" fill=\"{}\"/>",
                num(x),
                num(y),
                rgb(color)
            );
        }
        MarkShape::Support => {
            let _ = writeln!(
                out,
                "<polygon points=\"{},{} {},{} {},{}\" fill=\"#ffffff\" stroke=\"{}\" stroke-width=\"1.2\"/>",
                num(x),
                num(y),
                num(x - 6.0),
                num(y + 10.0),
                num(x + 6.0),
                num(y + 10.0),
                rgb(color)
            );
            segment(
                out,
                (x - 8.0, y + 12.0),
                (x + 8.0, y + 12.0),
                color,
                1.2,
                Dash::Solid,
            );
        }
    }
}

/// Writes the panel's data (series, arrows, marks, notes); whether any of it reaches within
/// its own reach (half a line's width, a marker, an arrow head, any note) of the plot box's
/// edge, so that it needs the clip.
fn write_data(out: &mut String, panel: &Panel, l: &PanelLayout) -> bool {
    let p = l.plot;
    let near_edge = |(x, y): (f64, f64), reach: f64| {
        !(x - reach > p.x && x + reach < p.x + p.w && y - reach > p.y && y + reach < p.y + p.h)
    };
    let mut clip = !panel.notes.is_empty();
    let strokes = layout::strokes(panel);
    let lines = panel.series.iter().zip(panel.drawn_points()).zip(&strokes);
    for (k, ((s, pts), st)) in lines.enumerate() {
        let px: Vec<(f64, f64)> = pts.iter().map(|&p| l.px(p)).collect();
        let reach = match st.markers {
            Markers::None => 0.5 * s.width + 1.0,
            _ => 0.5 * s.width + 6.0,
        };
        clip = clip || px.iter().any(|&q| near_edge(q, reach));
        polyline(out, &px, st.color, s.width, st.dash);
        let at = match st.markers {
            Markers::None => Vec::new(),
            Markers::Every => px,
            // staggered by series, so that curves that coincide show each marker
            Markers::Spaced => spaced(&px, 70.0, 12.0 + 4.7 * (k % 12) as f64),
        };
        for p in at {
            marker(out, st.marker, p, st.color);
        }
    }
    for a in &panel.arrows {
        if let (Some(p), Some(q)) = (panel.to_drawing(a.from), panel.to_drawing(a.to)) {
            let (p, q) = (l.px(p), l.px(q));
            clip = clip || near_edge(p, 8.0) || near_edge(q, 8.0);
            arrow(out, p, q, a.color);
        }
    }
    for m in &panel.marks {
        if let Some(p) = panel.to_drawing(m.at) {
            clip = clip || near_edge(l.px(p), 8.0);
            mark(out, m.shape, l.px(p), m.color);
        }
    }
    for n in &panel.notes {
        if let Some(p) = panel.to_drawing(n.at) {
            let (x, y) = l.px(p);
            let _ = write!(out, "<g fill=\"{}\">", rgb(n.color));
            label(out, &n.text, (x + 2.5, y - 2.5), 9.0, "start", false);
            out.push_str("</g>\n");
        }
    }
    clip
}

fn write_legend(out: &mut String, legend: &layout::Legend) {
    let r = legend.rect;
    let _ = writeln!(
        out,
        "<rect class=\"legend\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" fill-opacity=\"0.9\" stroke=\"#666666\" stroke-width=\"0.6\"/>",
        num(r.x),
        num(r.y),
        num(r.w),
        num(r.h)
    );
    let column_w = r.w / legend.columns.max(1) as f64;
    let (k, g) = (legend.scale, legend.geometry);
    for (i, (glyph, t)) in legend.entries.iter().enumerate() {
        let (row, column) = (i / legend.columns.max(1), i % legend.columns.max(1));
        let y = r.y + k * (g.top + g.row * row as f64 + 0.5 * g.row);
        let x = r.x + column_w * column as f64;
        let (x0, x1) = (x + g.left * k, x + (g.left + g.sample) * k);
        match *glyph {
            Glyph::Line {
                color,
                width,
                dash,
                marker: shape,
            } => {
                segment(out, (x0, y), (x1, y), color, width.min(4.0), dash);
                if let Some(shape) = shape {
                    marker(out, shape, (0.5 * (x0 + x1), y), color);
                }
            }
            Glyph::Arrow(color) => arrow(out, (x0, y), (x1, y), color),
            Glyph::Mark(shape, color) => {
                let at = match shape {
                    MarkShape::Support => (0.5 * (x0 + x1), y - 6.0),
                    MarkShape::Dot => (0.5 * (x0 + x1), y),
                };
                mark(out, shape, at, color)
            }
        }
        label(
            out,
            t,
            (x1 + g.gap * k, y + 0.35 * TICK_SIZE * k),
            TICK_SIZE * k,
            "start",
            false,
        );
    }
}

fn write_colorbar(out: &mut String, bar: &super::ColorBar, r: Rect, k: usize, l: &PanelLayout) {
    let _ = write!(
        out,
        "<linearGradient id=\"cbar{k}\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">"
    );
    for i in 0..=10 {
        let t = i as f64 / 10.0;
        let v = (2.0 * t - 1.0) * bar.max_abs;
        let _ = write!(
            out,
            "<stop offset=\"{}\" stop-color=\"{}\"/>",
            num(t),
            rgb(diverging_color(v, bar.max_abs))
        );
    }
    out.push_str("</linearGradient>\n");
    let _ = writeln!(
        out,
        "<rect class=\"colorbar\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"url(#cbar{k})\" stroke=\"#444444\" stroke-width=\"0.6\"/>",
        num(r.x),
        num(r.y),
        num(r.w),
        num(r.h)
    );
    // its text and gaps at the layout's text scale (smaller on a small page)
    let (size, k) = (l.tick_size(), l.text);
    let (ticks, factor) = layout::colorbar_ticks(bar.max_abs, r.h, k);
    let ticks_w = layout::widest_label(&ticks, size);
    for (v, t) in ticks {
        let y = r.y + r.h * (1.0 - (v / bar.max_abs + 1.0) / 2.0);
        let _ = writeln!(
            out,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#000000\" stroke-width=\"0.8\"/>",
            num(r.x + r.w),
            num(y),
            num(r.x + r.w + 3.0 * k),
            num(y)
        );
        label(
            out,
            &t,
            (r.x + r.w + 5.0 * k, y + 0.35 * size),
            size,
            "start",
            false,
        );
    }
    let mut title = bar.label.clone();
    if let Some(e) = factor {
        title = format!("{title} ×{}", layout::power_of_ten(e));
    }
    // turned, beside the bar: fitted to the panel's height below its title
    // (and above a legend under the panel)
    let mut hi = l.area.y + l.area.h - 4.0 * k;
    if let Some(legend) = l.legend.as_ref().filter(|g| g.rect.y > l.plot.y + l.plot.h) {
        hi = hi.min(legend.rect.y - 2.0 * k);
    }
    let lo = l.plot.y;
    let fitted = super::fit::fit_at_least(&title, size, layout::smallest_text(k), hi - lo, 1);
    let half = 0.5 * fitted.width();
    let y = (r.y + 0.5 * r.h).min(hi - half).max(lo + half);
    // its baseline right of the tick labels (on a small page just clear of them)
    let x = if k < 1.0 {
        r.x + layout::colorbar_texts_w(ticks_w, k) + 4.0 * k + 0.8 * fitted.size
    } else {
        r.x + r.w + 56.0
    };
    for line in &fitted.lines {
        label(out, line, (x, y), fitted.size, "middle", true);
    }
    // above and below the bar, in the room the layout leaves inside the plot's height
    let note = layout::colorbar_note_size(k);
    label(out, "tension", (r.x, r.y - 5.0 * k), note, "start", false);
    label(
        out,
        "compression",
        (r.x, r.y + r.h + 12.0 * k),
        note,
        "start",
        false,
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_keep_five_decimals_at_most() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.234567), "1.23457");
        assert_eq!(num(-0.000001), "0");
        assert_eq!(num(-2.5), "-2.5");
    }
}
