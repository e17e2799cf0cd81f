//! A small SVG line plotter (linear axes, several panels side by side) for the figures the
//! CLI writes; no system libraries or fonts needed.

use std::fmt::Write;

/// One curve.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// (x, y) points, drawn in order.
    pub points: Vec<(f64, f64)>,
}

/// One panel with its axes.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// The curves.
    pub series: Vec<Series>,
}

const COLORS: [&str; 6] = [
    "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf",
];

/// Tick positions: about five "nice" values (1, 2 or 5 × 10ᵏ apart) covering [lo, hi].
fn ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = (hi - lo).max(f64::MIN_POSITIVE);
    let raw = span / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| span / s <= 6.0)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

fn bounds(series: &[Series]) -> (f64, f64, f64, f64) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in series.iter().flat_map(|s| s.points.iter()) {
        if x.is_finite() && y.is_finite() {
            x0 = x0.min(*x);
            x1 = x1.max(*x);
            y0 = y0.min(*y);
            y1 = y1.max(*y);
        }
    }
    if x0 > x1 {
        return (0.0, 1.0, 0.0, 1.0);
    }
    let pad = 0.05 * (y1 - y0).max(1e-12 * y1.abs().max(1.0));
    (x0, x1.max(x0 + 1e-12), y0 - pad, y1 + pad)
}

/// Renders the panels side by side.
pub fn svg(panels: &[Panel]) -> String {
    let (pw, ph, margin) = (460.0, 300.0, 70.0);
    let width = panels.len() as f64 * (pw + margin) + margin;
    let height = ph + 2.0 * margin;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (pi, panel) in panels.iter().enumerate() {
        let (x0, x1, y0, y1) = bounds(&panel.series);
        let ox = margin + pi as f64 * (pw + margin);
        let oy = margin - 20.0;
        let px = |x: f64| ox + (x - x0) / (x1 - x0) * pw;
        let py = |y: f64| oy + ph - (y - y0) / (y1 - y0) * ph;
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="14">{}</text>"#,
            ox + pw / 2.0,
            oy - 8.0,
            panel.title
        );
        for t in ticks(x0, x1) {
            let x = px(t);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.2}" y1="{oy}" x2="{x:.2}" y2="{}" stroke="#e5e5e5"/><text x="{x:.2}" y="{}" text-anchor="middle">{}</text>"##,
                oy + ph,
                oy + ph + 16.0,
                format_tick(t)
            );
        }
        for t in ticks(y0, y1) {
            let y = py(t);
            let _ = writeln!(
                s,
                r##"<line x1="{ox}" y1="{y:.2}" x2="{}" y2="{y:.2}" stroke="#e5e5e5"/><text x="{}" y="{:.2}" text-anchor="end">{}</text>"##,
                ox + pw,
                ox - 5.0,
                y + 4.0,
                format_tick(t)
            );
        }
        let _ = writeln!(
            s,
            r#"<rect x="{ox}" y="{oy}" width="{pw}" height="{ph}" fill="none" stroke="black"/>"#
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#,
            ox + pw / 2.0,
            oy + ph + 36.0,
            panel.x_label
        );
        let (lx, ly) = (ox - 52.0, oy + ph / 2.0);
        let _ = writeln!(
            s,
            r#"<text x="{lx}" y="{ly}" text-anchor="middle" transform="rotate(-90 {lx} {ly})">{}</text>"#,
            panel.y_label
        );
        for (k, series) in panel.series.iter().enumerate() {
            let color = COLORS[k % COLORS.len()];
            let path: Vec<String> = series
                .points
                .iter()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .map(|&(x, y)| format!("{:.2},{:.2}", px(x), py(y)))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline fill="none" stroke="{color}" stroke-width="1.2" points="{}"/>"#,
                path.join(" ")
            );
            let ly = oy + 16.0 + 16.0 * k as f64;
            let lx = ox + pw - 110.0;
            let _ = writeln!(
                s,
                r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{color}" stroke-width="2"/><text x="{}" y="{}">{}</text>"#,
                lx + 20.0,
                lx + 25.0,
                ly + 4.0,
                series.label
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

fn format_tick(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if (1e-3..1e4).contains(&a) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_nice_and_cover_the_range() {
        assert_eq!(ticks(0.0, 10.0), vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]);
        let t = ticks(-0.013, 0.041);
        assert!(t.first().unwrap() >= &-0.013 && t.last().unwrap() <= &0.041 && t.len() >= 3);
        assert_eq!(format_tick(0.25), "0.25");
        assert_eq!(format_tick(2.0e-5), "2.0e-5");
    }

    #[test]
    fn svg_has_one_polyline_per_series() {
        let panel = Panel {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series: vec![
                Series {
                    label: "a".into(),
                    points: vec![(0.0, 0.0), (1.0, 1.0)],
                },
                Series {
                    label: "b".into(),
                    points: vec![(0.0, 1.0), (1.0, 0.0)],
                },
            ],
        };
        let s = svg(&[panel.clone(), panel]);
        assert_eq!(s.matches("<polyline").count(), 4);
        assert!(s.starts_with("<svg") && s.trim_end().ends_with("</svg>"));
    }
}
