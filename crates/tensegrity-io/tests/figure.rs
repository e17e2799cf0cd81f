//! Figures: the SVG is XML with one polyline per series and its labels; the PNG decodes at the
//! requested size and is not blank; the file type follows the extension.

use tensegrity_io::figure::{Figure, Panel, Scale, Series};

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
        "1e-3",
    ] {
        assert!(texts.contains(&label), "{label} missing from {texts:?}");
    }
    // markers on the two marked series only
    assert_eq!(
        doc.descendants()
            .filter(|n| n.has_tag_name("circle"))
            .count(),
        5
    );
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
        .filter(|p| p == &[0xd6, 0x27, 0x28])
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
        .save(&dir.join("figure.pdf"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("figure.pdf") && e.contains("svg, png"), "{e}");
    let e = Figure::new(vec![]).to_svg().unwrap_err().to_string();
    assert!(e.contains("at least one panel"), "{e}");
    assert_eq!(Panel::new("a", "b", "c").x_scale, Scale::Linear);
}
