//! A PDF's colour bar paints the diverging map where the SVG and the PNG do: the colour the
//! PDF's axial shading gives at 0, ½ and 1 of the bar's height is that of −max, 0 and +max.
//!
//! The colour is found as a PDF viewer finds it (PDF 32000-1 §8.7.3, §8.7.4.5.3, §7.10): a
//! point of the page's default space is taken into pattern space by the inverse of the
//! pattern's `/Matrix`, projected on the shading's `/Coords` axis (t clamped to [0, 1] by
//! `/Extend`), and t is evaluated by the stitching function (`/Bounds`, `/Encode`) of linear
//! (`/N 1`) pieces from `/C0` to `/C1`. The bar's place on the page comes from the SVG (its
//! pixels × 0.75, y measured from the page's bottom). svg2pdf 0.13 at 96 dpi wrote the
//! pattern's matrix in pixels while the page is in points: zero then sat 74 % up the bar and
//! its top was pale pink (issue 46).

use tensegrity_io::figure::{diverging_color, ColorBar, Figure, Panel, RenderOptions, Series};

/// The text of object `id` (between `id 0 obj` and `endobj`).
fn object(pdf: &str, id: usize) -> &str {
    let head = format!("\n{id} 0 obj");
    let start = pdf.find(&head).unwrap_or_else(|| panic!("no object {id}")) + head.len();
    let end = start + pdf[start..].find("endobj").unwrap();
    &pdf[start..end]
}

/// The objects whose text holds `key`.
fn objects_with<'a>(pdf: &'a str, key: &str) -> Vec<&'a str> {
    pdf.match_indices(" 0 obj")
        .map(|(at, _)| {
            let start = pdf[..at].rfind('\n').unwrap() + 1;
            object(pdf, pdf[start..at].parse().unwrap())
        })
        .filter(|o| o.contains(key))
        .collect()
}

/// The tokens of the array after `key`.
fn array<'a>(dict: &'a str, key: &str) -> Vec<&'a str> {
    let at = dict
        .find(&format!("{key} ["))
        .unwrap_or_else(|| panic!("no {key} in {dict}"));
    let rest = &dict[at..];
    let (open, close) = (rest.find('[').unwrap(), rest.find(']').unwrap());
    rest[open + 1..close].split_whitespace().collect()
}

fn numbers(dict: &str, key: &str) -> Vec<f64> {
    array(dict, key)
        .iter()
        .map(|t| t.parse().unwrap())
        .collect()
}

/// The object number of the reference after `key` (`/Key 12 0 R`).
fn reference(dict: &str, key: &str) -> usize {
    let at = dict.find(&format!("{key} ")).unwrap() + key.len() + 1;
    dict[at..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// The colour of the stitching function `f` (or a single linear piece) at t ∈ [0, 1].
fn evaluate(pdf: &str, f: &str, t: f64) -> [f64; 3] {
    if f.contains("/FunctionType 2") {
        let (c0, c1) = (numbers(f, "/C0"), numbers(f, "/C1"));
        assert!(f.contains("/N 1"), "a linear piece: {f}");
        return [0, 1, 2].map(|i| c0[i] + t * (c1[i] - c0[i]));
    }
    assert!(f.contains("/FunctionType 3"), "{f}");
    let bounds = numbers(f, "/Bounds");
    let encode = numbers(f, "/Encode");
    let domain = numbers(f, "/Domain");
    let pieces: Vec<usize> = array(f, "/Functions")
        .chunks(3)
        .map(|r| r[0].parse().unwrap())
        .collect();
    let k = bounds
        .iter()
        .filter(|&&b| t >= b)
        .count()
        .min(pieces.len() - 1);
    let lo = if k == 0 { domain[0] } else { bounds[k - 1] };
    let hi = if k == bounds.len() {
        domain[1]
    } else {
        bounds[k]
    };
    let (e0, e1) = (encode[2 * k], encode[2 * k + 1]);
    let u = e0 + (t - lo) / (hi - lo) * (e1 - e0);
    evaluate(pdf, object(pdf, pieces[k]), u)
}

/// The colour (0–255) the PDF's one shading pattern paints at `(x, y)` of the page's default
/// space (points).
fn painted(pdf: &str, (x, y): (f64, f64)) -> [f64; 3] {
    let patterns = objects_with(pdf, "/PatternType 2");
    assert_eq!(patterns.len(), 1, "one colour bar, one shading pattern");
    let m = numbers(patterns[0], "/Matrix");
    let shading = object(pdf, reference(patterns[0], "/Shading"));
    assert!(shading.contains("/ShadingType 2"), "an axial shading");
    let c = numbers(shading, "/Coords");
    // the page point in pattern space: p = M⁻¹ (x − e, y − f)
    let det = m[0] * m[3] - m[1] * m[2];
    let (dx, dy) = (x - m[4], y - m[5]);
    let p = (
        (m[3] * dx - m[2] * dy) / det,
        (-m[1] * dx + m[0] * dy) / det,
    );
    let axis = (c[2] - c[0], c[3] - c[1]);
    let t = ((p.0 - c[0]) * axis.0 + (p.1 - c[1]) * axis.1) / (axis.0.powi(2) + axis.1.powi(2));
    let f = object(pdf, reference(shading, "/Function"));
    evaluate(pdf, f, t.clamp(0.0, 1.0)).map(|v| 255.0 * v)
}

/// The colour bar's rectangle in the SVG: x, y, width, height (pixels, y down).
fn bar_rect(svg: &str) -> [f64; 4] {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let rect = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("colorbar"))
        .expect("a colour bar");
    ["x", "y", "width", "height"].map(|a| rect.attribute(a).unwrap().parse().unwrap())
}

fn figure(max_abs: f64) -> Figure {
    let mut panel = Panel::new("members", "x [m]", "y [m]")
        .with_equal_axes()
        .series(Series::new("", vec![(0.0, 0.0), (1.0, 1.0)]).with_color((0xa5, 0x0f, 0x15)));
    panel.colorbar = Some(ColorBar {
        label: "force [N]".into(),
        max_abs,
    });
    Figure::new(vec![panel])
}

#[test]
fn a_pdf_colour_bar_paints_the_map_at_its_bottom_middle_and_top() {
    // the figure's own size and two journal sizes (one column, two columns)
    for size in [None, Some("8.5x6cm"), Some("17.8x8cm")] {
        let options = RenderOptions::parse(size, None).unwrap();
        let max_abs = 250.0;
        let fig = figure(max_abs);
        let svg = fig.to_svg_with(&options).unwrap();
        let pdf = fig.to_pdf_with(&options).unwrap();
        let pdf = String::from_utf8_lossy(&pdf);
        let page_h = numbers(&pdf, "/MediaBox")[3];
        let (_, h_px) = fig.page_px(&options).unwrap();
        assert!((page_h - 0.75 * h_px).abs() < 1e-3, "{size:?}: {page_h}");
        let [x, y, w, h] = bar_rect(&svg);
        for (fraction, value) in [(0.0, -max_abs), (0.5, 0.0), (1.0, max_abs)] {
            // a hair inside the bar's bottom and top edges
            let f = 0.002 + 0.996 * fraction;
            let at_px = (x + 0.5 * w, y + h * (1.0 - f));
            let at = (0.75 * at_px.0, page_h - 0.75 * at_px.1);
            let got = painted(&pdf, at);
            let want = diverging_color(value, max_abs);
            let want = [want.0, want.1, want.2].map(f64::from);
            let off = (0..3).map(|i| (got[i] - want[i]).abs()).fold(0.0, f64::max);
            assert!(
                off < 2.0,
                "{size:?}: at {fraction} of the bar the PDF paints {got:?}, the map is {want:?}"
            );
        }
    }
}
