//! Structure drawings are to scale: in the SVG of every structure panel, the pixel coordinates
//! of the member polylines are an affine image of the drawing's own coordinates (the figure's
//! data: its series points) with the same scale in x and y, to 1e-6, at the figure's own size
//! and at sizes of other aspect ratios. The scale is fitted by least squares over every member
//! end, so the check reads it from the coordinates, not from the layout.

use tensegrity_figures::draw::{drawing_panel, Drawing, Style, View};
use tensegrity_figures::{Context, FIGURES};
use tensegrity_io::figure::{Figure, RenderOptions};

/// The points of every `<polyline>` of each `<g class="panel">`, in order.
fn panel_polylines(svg: &str) -> Vec<Vec<Vec<(f64, f64)>>> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.attribute("class") == Some("panel"))
        .map(|g| {
            g.descendants()
                .filter(|n| n.has_tag_name("polyline"))
                .map(|l| {
                    l.attribute("points")
                        .unwrap()
                        .split(' ')
                        .map(|p| {
                            let (x, y) = p.split_once(',').unwrap();
                            (x.parse().unwrap(), y.parse().unwrap())
                        })
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// Least-squares slope of `b` against `a` and the largest residual.
fn fit(a: &[f64], b: &[f64]) -> (f64, f64) {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let var: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let s = cov / var;
    let worst = a
        .iter()
        .zip(b)
        .map(|(x, y)| (mb + s * (x - ma) - y).abs())
        .fold(0.0, f64::max);
    (s, worst)
}

/// Checks every panel with equal axes: x and y scales equal to 1e-6, every point on the map.
fn assert_to_scale(fig: &Figure, options: &RenderOptions, what: &str) -> usize {
    let svg = fig.to_svg_with(options).unwrap();
    let drawn = panel_polylines(&svg);
    assert_eq!(drawn.len(), fig.panels.len(), "{what}");
    let mut checked = 0;
    for (k, (panel, lines)) in fig.panels.iter().zip(&drawn).enumerate() {
        if !panel.equal_axes {
            continue;
        }
        assert_eq!(lines.len(), panel.series.len(), "{what} panel {k}");
        let (mut x, mut y, mut px, mut py) = (vec![], vec![], vec![], vec![]);
        for (s, l) in panel.series.iter().zip(lines) {
            assert_eq!(s.points.len(), l.len());
            for (&(a, b), &(c, d)) in s.points.iter().zip(l) {
                x.push(a);
                y.push(b);
                px.push(c);
                py.push(d);
            }
        }
        let (sx, rx) = fit(&x, &px);
        let (sy, ry) = fit(&y, &py);
        // y grows upwards, pixels downwards
        assert!(
            (sx / -sy - 1.0).abs() < 1e-6,
            "{what} panel {k}: x scale {sx} px/m, y scale {} px/m",
            -sy
        );
        assert!(
            rx < 1e-4 && ry < 1e-4,
            "{what} panel {k}: residual {rx} {ry} px"
        );
        checked += 1;
    }
    checked
}

fn sizes() -> Vec<RenderOptions> {
    [None, Some("1600x400"), Some("5x9in")]
        .iter()
        .map(|s| RenderOptions::parse(*s, None).unwrap())
        .collect()
}

#[test]
fn a_toroid_drawing_has_one_scale_in_every_view_and_size() {
    let wheel = toroid::WheelSpec::default().build().unwrap();
    let d = Drawing::of(&wheel.structure);
    for view in [
        View::Side,
        View::Xy,
        View::Xz,
        View::Iso,
        "30deg,20deg".parse().unwrap(),
    ] {
        let style = Style {
            view,
            node_labels: true,
            ..Style::default()
        };
        let fig =
            tensegrity_figures::draw::drawing_figure_of(vec![drawing_panel("w", &d, &style)], 420);
        for o in sizes() {
            assert_eq!(assert_to_scale(&fig, &o, &view.name()), 1);
        }
    }
}

#[test]
fn the_catalogue_structure_figures_are_to_scale() {
    let ctx = Context::new(true, std::env::temp_dir());
    let mut panels = 0;
    for number in ["3.3", "3.9", "4.4", "4.7", "5.1", "5.3"] {
        let spec = FIGURES.iter().find(|f| f.number == number).unwrap();
        let fig = spec.build(&ctx).unwrap().figure;
        for o in sizes() {
            panels += assert_to_scale(&fig, &o, number);
        }
    }
    assert!(panels >= 3 * 10, "{panels} panels checked");
}
