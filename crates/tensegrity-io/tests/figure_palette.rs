//! The series style table and the diverging map are colour-blind- and greyscale-safe
//! (issue 46): the first 12 styles differ pairwise in colour, and in (dash, marker) even
//! without colour; their colours are far apart in CIELAB (ΔE*ab, D65) with normal vision,
//! and under simulated deuteranopia and protanopia (Machado, Oliveira & Fernandes 2009,
//! severity 1) any two that come close differ in dash; the diverging map's ends differ in
//! lightness. A plot of 12 series draws 12 different strokes.

use std::collections::HashSet;
use tensegrity_io::figure::style::{series_style, Dash, Marker, PALETTE, STYLE_COUNT};
use tensegrity_io::figure::{diverging_color, Figure, Panel, Series};

fn linear(c: u8) -> f64 {
    let c = c as f64 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

fn encode(c: f64) -> f64 {
    let c = c.clamp(0.0, 1.0);
    255.0
        * if c <= 0.0031308 {
            12.92 * c
        } else {
            1.055 * c.powf(1.0 / 2.4) - 0.055
        }
}

/// CIELAB (D65) of linear sRGB.
fn lab_linear([r, g, b]: [f64; 3]) -> [f64; 3] {
    let x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
    let y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
    let z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
    let f = |t: f64| {
        if t > 216.0 / 24389.0 {
            t.cbrt()
        } else {
            (24389.0 / 27.0 * t + 16.0) / 116.0
        }
    };
    let (fx, fy, fz) = (f(x), f(y), f(z));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

fn lab((r, g, b): (u8, u8, u8)) -> [f64; 3] {
    lab_linear([linear(r), linear(g), linear(b)])
}

fn delta_e(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// The colour seen with dichromacy `m` (Machado et al. 2009, severity 1.0, on linear RGB),
/// re-encoded to 8-bit sRGB as a display would show it.
fn simulated(m: &[[f64; 3]; 3], (r, g, b): (u8, u8, u8)) -> [f64; 3] {
    let c = [linear(r), linear(g), linear(b)];
    let s: [f64; 3] = std::array::from_fn(|i| (0..3).map(|j| m[i][j] * c[j]).sum());
    // through the display: clamp, 8 bits, back to linear
    let s8 = s.map(|v| encode(v).round() as u8);
    lab_linear(s8.map(linear))
}

const DEUTERANOPIA: [[f64; 3]; 3] = [
    [0.367322, 0.860646, -0.227968],
    [0.280085, 0.672501, 0.047413],
    [-0.011820, 0.042940, 0.968881],
];
const PROTANOPIA: [[f64; 3]; 3] = [
    [0.152286, 1.052583, -0.204868],
    [0.114503, 0.786281, 0.099216],
    [-0.003882, -0.048116, 1.051998],
];

#[test]
fn the_first_twelve_styles_differ_in_colour_and_in_dash_and_marker() {
    const { assert!(STYLE_COUNT >= 12) };
    let styles: Vec<_> = (0..12).map(series_style).collect();
    let triples: HashSet<_> = styles.iter().collect();
    assert_eq!(triples.len(), 12, "distinct (colour, dash, marker)");
    let colours: HashSet<_> = styles.iter().map(|s| s.color).collect();
    assert_eq!(colours.len(), 12, "no colour twice");
    let grey: HashSet<(Dash, Marker)> = styles.iter().map(|s| (s.dash, s.marker)).collect();
    assert_eq!(grey.len(), 12, "no (dash, marker) twice: {styles:?}");
    // the first six differ in dash alone (a plain line has no marker in a panel of ≤ 6)
    let dashes: HashSet<Dash> = styles[..6].iter().map(|s| s.dash).collect();
    assert_eq!(dashes.len(), 6);
    assert_eq!(
        series_style(12),
        series_style(0),
        "the table repeats after 12"
    );
}

#[test]
fn the_palette_colours_are_far_apart_in_cielab_and_stay_apart_or_differ_in_dash_for_dichromats() {
    let mut min = f64::INFINITY;
    for i in 0..12 {
        for j in i + 1..12 {
            let d = delta_e(lab(PALETTE[i]), lab(PALETTE[j]));
            min = min.min(d);
            assert!(
                d >= 20.0,
                "colours {i} and {j}: ΔE = {d:.1} ({:?}, {:?})",
                PALETTE[i],
                PALETTE[j]
            );
        }
    }
    eprintln!("smallest ΔE*ab between two of the 12 colours: {min:.1}");
    // every colour stands out from the white page
    for (i, &c) in PALETTE.iter().enumerate() {
        assert!(lab(c)[0] < 85.0, "colour {i} too light: L* {}", lab(c)[0]);
    }
    for (name, m) in [("deuteranopia", DEUTERANOPIA), ("protanopia", PROTANOPIA)] {
        let mut close = 0;
        let mut min = f64::INFINITY;
        for i in 0..12 {
            for j in i + 1..12 {
                let d = delta_e(simulated(&m, PALETTE[i]), simulated(&m, PALETTE[j]));
                min = min.min(d);
                let (a, b) = (series_style(i), series_style(j));
                if d < 10.0 {
                    close += 1;
                    assert_ne!(
                        a.dash, b.dash,
                        "{name}: styles {i} and {j} look alike (ΔE {d:.1}) and share a dash"
                    );
                }
            }
        }
        // among the first six (a plain line's styles in small panels) nothing comes close
        for i in 0..6 {
            for j in i + 1..6 {
                let d = delta_e(simulated(&m, PALETTE[i]), simulated(&m, PALETTE[j]));
                assert!(d >= 10.0, "{name}: colours {i} and {j}, ΔE {d:.1}");
            }
        }
        eprintln!("{name}: smallest ΔE {min:.1}, {close} pairs below 10 (each differs in dash)");
    }
}

#[test]
fn the_diverging_map_has_ends_of_different_lightness_and_darkens_with_magnitude() {
    let l = |v: f64| lab(diverging_color(v, 1.0))[0];
    let (tension, compression, zero) = (l(1.0), l(-1.0), l(0.0));
    assert!(
        tension - compression >= 25.0,
        "ends L* {tension:.1} (tension) and {compression:.1} (compression)"
    );
    assert!(zero > tension + 20.0, "zero L* {zero:.1}");
    for k in 1..=10 {
        let (a, b) = ((k - 1) as f64 / 10.0, k as f64 / 10.0);
        assert!(l(b) < l(a), "tension lightness falls at {b}");
        assert!(l(-b) < l(-a), "compression lightness falls at {b}");
    }
}

/// The (stroke, dasharray, marker shape) of every series polyline and its markers.
fn strokes(svg: &str) -> Vec<(String, String, String)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let nodes: Vec<_> = doc.descendants().collect();
    let mut out = Vec::new();
    for (i, n) in nodes.iter().enumerate() {
        if !n.has_tag_name("polyline") {
            continue;
        }
        let stroke = n.attribute("stroke").unwrap().to_string();
        let dash = n.attribute("stroke-dasharray").unwrap_or("").to_string();
        let marker = nodes[i + 1..]
            .iter()
            .take_while(|m| !m.has_tag_name("polyline"))
            .find_map(|m| m.attribute("data-marker"))
            .unwrap_or("")
            .to_string();
        out.push((stroke, dash, marker));
    }
    out
}

#[test]
fn a_plot_of_twelve_dense_curves_draws_twelve_strokes_distinct_without_colour() {
    // 12 curves of 400 points and no markers asked: spaced markers tell them apart
    let mut panel = Panel::new("twelve", "x", "y");
    for k in 0..12 {
        let pts = (0..400)
            .map(|i| (i as f64, (i as f64 / 40.0 + k as f64).sin()))
            .collect();
        panel = panel.series(Series::new(format!("s{k}"), pts));
    }
    let svg = Figure::new(vec![panel]).to_svg().unwrap();
    let got = strokes(&svg);
    assert_eq!(got.len(), 12);
    let all: HashSet<_> = got.iter().collect();
    assert_eq!(all.len(), 12, "{got:?}");
    let grey: HashSet<_> = got.iter().map(|(_, d, m)| (d, m)).collect();
    assert_eq!(grey.len(), 12, "{got:?}");
    assert!(got.iter().all(|(_, _, m)| !m.is_empty()), "{got:?}");
    // and a panel of three plain curves has no markers, the dashes telling them apart
    let mut few = Panel::new("three", "x", "y");
    for k in 0..3 {
        few = few.series(Series::new(
            format!("s{k}"),
            vec![(0.0, k as f64), (1.0, 1.0)],
        ));
    }
    let svg = Figure::new(vec![few]).to_svg().unwrap();
    assert!(!svg.contains("data-marker"));
    let dashes: HashSet<_> = strokes(&svg).into_iter().map(|(_, d, _)| d).collect();
    assert_eq!(dashes.len(), 3);
}

#[test]
fn a_figure_marked_invalid_says_so_above_its_panels() {
    let panel =
        Panel::new("run", "t [s]", "h [m]").series(Series::new("h", vec![(0.0, 1.0), (1.0, 0.5)]));
    let fig = Figure::new(vec![panel.clone(), panel]);
    let clean = fig.to_svg().unwrap();
    assert!(!clean.contains("class=\"invalid\""));
    let svg = fig.clone().mark_invalid("not_converged").to_svg().unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let mark = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("invalid"))
        .expect("the mark");
    let text = mark.descendants().find(|n| n.has_tag_name("text")).unwrap();
    assert_eq!(text.text().unwrap_or_default(), "NOT VALID: not_converged");
    let y: f64 = text.attribute("y").unwrap().parse().unwrap();
    // every panel's plot and title below the mark's baseline
    for p in doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("panel"))
    {
        let plot: Vec<f64> = p
            .attribute("data-plot")
            .unwrap()
            .split(' ')
            .map(|v| v.parse().unwrap())
            .collect();
        assert!(
            plot[1] > y + 10.0,
            "plot top {} under the mark at {y}",
            plot[1]
        );
        let title = p.descendants().find(|n| n.has_tag_name("text")).unwrap();
        let ty: f64 = title.attribute("y").unwrap().parse().unwrap();
        assert!(ty - 14.0 > y, "title at {ty}, mark at {y}");
    }
    // a long reason is cut to the figure's width; PNG and PDF render it
    let long = fig.mark_invalid("x".repeat(400));
    let svg = long.to_svg().unwrap();
    assert!(svg.contains("NOT VALID: xxx") && svg.contains('…'));
    assert!(long.to_rgb().is_ok());
    assert!(long
        .to_pdf_with(&tensegrity_io::figure::RenderOptions::default())
        .is_ok());
}
