//! Figures: the SVG is XML with one polyline per series and its labels, coordinates with
//! decimals; the PNG decodes at the requested size (and size × dpi) and is not blank; the PDF's
//! page is the requested size (and, where `pdftoppm` is installed, renders at it); the file type
//! follows the extension; equal axes have one scale; the legend covers no data.

use tensegrity_io::figure::{Figure, Panel, RenderOptions, Scale, Series};

fn figure() -> Figure {
    let t: Vec<f64> = (0..50).map(|i| i as f64 * 0.02).collect();
    let time_series = Panel::new("axle height", "time [s]", "height [m]")
        .series(Series::new(
            "n = 8",
            t.iter().map(|&t| (t, 0.5 + 0.1 * t.sin())).collect(),
        ))
        .series(Series::new(
            "n = 16",
            t.iter().map(|&t| (t, 0.5 - 0.1 * t)).collect(),
        ));
    let work_precision = Panel::new("prism", "wall time [s]", "error [m]")
        .log_log()
        .series(Series::new("rk4", vec![(1e-4, 1e-3), (1e-3, 1e-7), (1e-2, 1e-11)]).with_markers())
        .series(Series::new("rk45", vec![(2e-4, 1e-5), (3e-3, 1e-10)]).with_markers())
        .series(Series::new(
            "rattle",
            vec![(1e-4, 1e-2), (1e-3, 1e-4), (0.0, 1.0)],
        ));
    Figure::new(vec![time_series, work_precision]).with_panel_size(400, 300)
}

#[test]
fn the_svg_is_xml_with_one_polyline_per_series_and_the_labels() {
    let fig = figure();
    let svg = fig.to_svg().unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.attribute("width"), Some("800"));
    assert_eq!(root.attribute("height"), Some("300"));
    let polylines = doc
        .descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .count();
    assert_eq!(polylines, 5);
    let texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for label in [
        "axle height",
        "time [s]",
        "height [m]",
        "n = 8",
        "n = 16",
        "prism",
        "wall time [s]",
        "error [m]",
        "rk4",
        "rk45",
        "rattle",
        "10⁻³",
    ] {
        assert!(texts.contains(&label), "{label} missing from {texts:?}");
    }
    // markers on the two marked series only (5 points), and on their 2 legend samples: the
    // first style's circles and the second's squares (issue 46: one style table)
    let shapes: Vec<&str> = doc
        .descendants()
        .filter_map(|n| n.attribute("data-marker"))
        .collect();
    assert_eq!(shapes.len(), 7);
    assert_eq!(shapes.iter().filter(|&&s| s == "circle").count(), 4);
    assert_eq!(shapes.iter().filter(|&&s| s == "square").count(), 3);
}

#[test]
fn the_png_decodes_at_the_requested_size_and_is_not_blank() {
    let path =
        std::env::temp_dir().join(format!("tensegrity-io-figure-{}.png", std::process::id()));
    figure().save(&path).unwrap();
    let decoder = png::Decoder::new(std::fs::File::open(&path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!((info.width, info.height), (800, 300));
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let pixels = &buf[..info.buffer_size()];
    let white = pixels.chunks(3).filter(|p| p == &[255, 255, 255]).count();
    let total = pixels.len() / 3;
    // mostly background, but axes, text and curves draw a real share of the pixels
    assert!(
        white < total && white > total / 2,
        "{white} of {total} white"
    );
    let colored = pixels
        .chunks(3)
        .filter(|p| {
            let c = tensegrity_io::figure::style::PALETTE[1];
            p == &[c.0, c.1, c.2]
        })
        .count();
    assert!(
        colored > 100,
        "the second series is drawn ({colored} pixels)"
    );
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn the_format_follows_the_extension() {
    let dir = std::env::temp_dir();
    let svg = dir.join(format!("tensegrity-io-figure-{}.SVG", std::process::id()));
    figure().save(&svg).unwrap();
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    std::fs::remove_file(&svg).unwrap();
    let e = figure()
        .save(&dir.join("figure.bmp"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("figure.bmp") && e.contains("svg, png, pdf"),
        "{e}"
    );
    let e = Figure::new(vec![]).to_svg().unwrap_err().to_string();
    assert!(e.contains("at least one panel"), "{e}");
    assert_eq!(Panel::new("a", "b", "c").x_scale, Scale::Linear);
}

/// The numbers of every `points` attribute and `x`/`y` coordinate attribute of an SVG.
fn coordinates(svg: &str) -> Vec<String> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let mut out = Vec::new();
    for n in doc.descendants() {
        if let Some(p) = n.attribute("points") {
            out.extend(
                p.split([' ', ','])
                    .filter(|s| !s.is_empty())
                    .map(String::from),
            );
        }
        for a in ["x1", "y1", "x2", "y2", "cx", "cy"] {
            out.extend(n.attribute(a).map(String::from));
        }
    }
    out
}

#[test]
fn svg_coordinates_carry_decimals() {
    let svg = figure().to_svg().unwrap();
    let numbers = coordinates(&svg);
    assert!(numbers.len() > 200);
    let with_decimals = numbers.iter().filter(|s| s.contains('.')).count();
    // whole pixels would make every one an integer; sub-pixel vector coordinates make almost
    // none integral
    assert!(
        with_decimals * 10 > numbers.len() * 9,
        "{with_decimals} of {} have decimals",
        numbers.len()
    );
    for n in &numbers {
        let v: f64 = n.parse().unwrap();
        assert!(v.is_finite() && (-1.0..=801.0).contains(&v), "{n}");
    }
}

fn png_size(bytes: &[u8]) -> (u32, u32) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    (info.width, info.height)
}

#[test]
fn a_png_at_a_size_and_dpi_has_size_times_dpi_pixels() {
    let fig = figure();
    let opts = RenderOptions::parse(Some("3x2in"), Some(150.0)).unwrap();
    assert_eq!(png_size(&fig.to_png_with(&opts).unwrap()), (450, 300));
    let opts = RenderOptions::parse(Some("16x10cm"), Some(300.0)).unwrap();
    // 16 cm = 6.299 in → 1890 px, 10 cm → 1181 px
    assert_eq!(png_size(&fig.to_png_with(&opts).unwrap()), (1890, 1181));
    let opts = RenderOptions::parse(None, Some(192.0)).unwrap();
    assert_eq!(png_size(&fig.to_png_with(&opts).unwrap()), (1600, 600));
    // the SVG carries the size in its unit
    let opts = RenderOptions::parse(Some("16x10cm"), None).unwrap();
    let svg = fig.to_svg_with(&opts).unwrap();
    assert!(
        svg.contains("width=\"16cm\" height=\"10cm\""),
        "{}",
        &svg[..200]
    );
    // too small a panel, too many pixels, a bad dpi: refused with a reason
    let small = RenderOptions::parse(Some("1x1in"), None).unwrap();
    assert!(fig.to_svg_with(&small).is_err());
    let huge = RenderOptions::parse(Some("100x100in"), Some(1200.0)).unwrap();
    assert!(fig
        .to_png_with(&huge)
        .unwrap_err()
        .to_string()
        .contains("pixels"));
    assert!(RenderOptions::parse(None, Some(5000.0)).is_err());
}

/// The MediaBox of a one-page PDF (the first one written).
fn media_box(pdf: &[u8]) -> [f64; 4] {
    let text = String::from_utf8_lossy(pdf);
    let at = text.find("/MediaBox").expect("a MediaBox");
    let rest = &text[at + "/MediaBox".len()..];
    let (open, close) = (rest.find('[').unwrap(), rest.find(']').unwrap());
    let v: Vec<f64> = rest[open + 1..close]
        .split_whitespace()
        .map(|s| s.parse().unwrap())
        .collect();
    [v[0], v[1], v[2], v[3]]
}

#[test]
fn a_pdf_page_is_the_requested_size() {
    let dir = std::env::temp_dir().join(format!("tensegrity-io-pdf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("fig.pdf");
    let opts = RenderOptions::parse(Some("6x4in"), None).unwrap();
    figure().save_with(&path, &opts).unwrap();
    let pdf = std::fs::read(&path).unwrap();
    assert!(pdf.starts_with(b"%PDF-"));
    let [x0, y0, x1, y1] = media_box(&pdf);
    assert!(
        (x1 - x0 - 432.0).abs() < 0.01 && (y1 - y0 - 288.0).abs() < 0.01,
        "{x0} {y0} {x1} {y1}"
    );
    // the figure's own size: 800 × 300 px = 600 × 225 pt
    let own = figure().to_pdf_with(&RenderOptions::default()).unwrap();
    let [x0, y0, x1, y1] = media_box(&own);
    assert!((x1 - x0 - 600.0).abs() < 0.01 && (y1 - y0 - 225.0).abs() < 0.01);
    // rendered by poppler where it is installed (not on CI): 6 × 4 in at 50 dpi = 300 × 200
    let rendered = std::process::Command::new("pdftoppm")
        .args(["-r", "50", "-png", "-singlefile"])
        .arg(&path)
        .arg(dir.join("page"))
        .status();
    if let Ok(status) = rendered {
        assert!(status.success());
        let png = std::fs::read(dir.join("page.png")).unwrap();
        assert_eq!(png_size(&png), (300, 200));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn equal_axes_keep_one_scale_at_any_size() {
    // a 2 m × 0.5 m rectangle drawn in a tall and in a wide figure
    let rect = vec![(0.0, 0.0), (2.0, 0.0), (2.0, 0.5), (0.0, 0.5), (0.0, 0.0)];
    let panel = Panel::new("rect", "y [m]", "z [m]")
        .with_equal_axes()
        .series(Series::new("outline", rect.clone()));
    for size in ["300x900", "1200x300", "6x4in"] {
        let opts = RenderOptions::parse(Some(size), None).unwrap();
        let svg = Figure::new(vec![panel.clone()]).to_svg_with(&opts).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let line = doc
            .descendants()
            .find(|n| n.has_tag_name("polyline"))
            .unwrap();
        let pts: Vec<(f64, f64)> = line
            .attribute("points")
            .unwrap()
            .split(' ')
            .map(|p| {
                let (x, y) = p.split_once(',').unwrap();
                (x.parse().unwrap(), y.parse().unwrap())
            })
            .collect();
        let sx = (pts[1].0 - pts[0].0) / 2.0;
        let sy = (pts[1].1 - pts[2].1) / 0.5;
        assert!((sx / sy - 1.0).abs() < 1e-6, "{size}: {sx} vs {sy}");
    }
}

#[test]
fn the_legend_covers_no_curve() {
    // a curve across the upper right, where a fixed legend used to sit
    let pts: Vec<(f64, f64)> = (0..=100)
        .map(|i| (i as f64, (i as f64 / 10.0).powi(2)))
        .collect();
    let panel = Panel::new("p", "x [s]", "y [m]")
        .series(Series::new("rising", pts.clone()))
        .series(Series::new("flat", vec![(0.0, 100.0), (100.0, 100.0)]));
    let svg = Figure::new(vec![panel]).to_svg().unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let legend = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("legend"))
        .unwrap();
    let f = |a: &str| legend.attribute(a).unwrap().parse::<f64>().unwrap();
    let (x, y, w, h) = (f("x"), f("y"), f("width"), f("height"));
    for line in doc.descendants().filter(|n| n.has_tag_name("polyline")) {
        let pts: Vec<(f64, f64)> = line
            .attribute("points")
            .unwrap()
            .split(' ')
            .map(|p| {
                let (a, b) = p.split_once(',').unwrap();
                (a.parse().unwrap(), b.parse().unwrap())
            })
            .collect();
        for seg in pts.windows(2) {
            for k in 0..=20 {
                let t = k as f64 / 20.0;
                let px = seg[0].0 + t * (seg[1].0 - seg[0].0);
                let py = seg[0].1 + t * (seg[1].1 - seg[0].1);
                assert!(
                    !(px > x && px < x + w && py > y && py < y + h),
                    "({px}, {py}) under the legend"
                );
            }
        }
    }
}
