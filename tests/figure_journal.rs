//! Every kind of figure at a journal's sizes — the smallest the figures promise (6 × 4 cm, where
//! text and gaps are set smaller and three panels stand side by side 2 cm wide), one column
//! (8.5 × 6 cm) and two (17.8 × 8 cm): the thesis figures (`figures --quick`) and each
//! command's own figure (`statics`, its modes, `michell`, `michell-table`, `roll`,
//! `fig-rolling`, `solve`, `tbar`, `formfind`, `sweep plot`), read back from the SVG by an
//! independent parser and renderer (roxmltree for the panels, usvg's text layout on the
//! bundled font for the ink of every text) and checked, every check at every size:
//!
//! - nothing clipped: every text's ink and every plot box lies on the page;
//! - nothing overlaps: no two texts outside the drawings share ink, no such text covers a
//!   plot box, no legend text leaves its legend box, no two plot boxes overlap (a text is
//!   inside a drawing when a group above it is clipped to the plot, `clip-path`, or is the
//!   plot's data group, `class="data"`);
//! - structure panels fill their axes: the drawing spans ≥ 70 % of its plot box's width or
//!   height (no 1 m prism drawn on ±10 m axes);
//! - one scale: the structure panels of a figure have the same px per metre.

use crate::common;
use std::path::{Path, PathBuf};

const SIZES: [&str; 3] = ["6x4cm", "8.5x6cm", "17.8x8cm"];

/// An axis-aligned box: x0, y0, x1, y1 (px).
#[derive(Debug, Clone, Copy)]
struct Boxed(f64, f64, f64, f64);

impl Boxed {
    fn overlaps(&self, o: &Boxed, tol: f64) -> bool {
        self.0.max(o.0) + tol < self.2.min(o.2) && self.1.max(o.1) + tol < self.3.min(o.3)
    }
    fn inside(&self, o: &Boxed, tol: f64) -> bool {
        self.0 >= o.0 - tol && self.1 >= o.1 - tol && self.2 <= o.2 + tol && self.3 <= o.3 + tol
    }
}

/// A text of the SVG: its characters, ink box, and whether it is drawn inside a plot (a note
/// on the drawing) or a legend.
#[derive(Debug)]
struct Text {
    text: String,
    ink: Boxed,
    in_plot: bool,
}

fn numbers(s: &str) -> Vec<f64> {
    s.split([' ', ','])
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect()
}

fn usvg_options() -> usvg::Options<'static> {
    let font = std::fs::read(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("crates/tensegrity-io/assets/DejaVuSans.ttf"),
    )
    .unwrap();
    let mut db = usvg::fontdb::Database::new();
    db.load_font_data(font);
    db.set_sans_serif_family("DejaVu Sans");
    usvg::Options {
        font_family: "DejaVu Sans".into(),
        fontdb: std::sync::Arc::new(db),
        ..usvg::Options::default()
    }
}

/// The ink boxes of the texts, in document order, as usvg lays them out.
fn ink_boxes(svg: &str, options: &usvg::Options) -> Vec<(String, Boxed)> {
    fn walk(g: &usvg::Group, out: &mut Vec<(String, Boxed)>) {
        for node in g.children() {
            match node {
                usvg::Node::Group(g) => walk(g, out),
                usvg::Node::Text(t) => {
                    // the glyphs' outlines in the text's own space, turned and moved by its
                    // transform (a y-axis label is turned by −90°)
                    let r = t.flattened().bounding_box();
                    let m = t.abs_transform();
                    let corners = [
                        (r.left(), r.top()),
                        (r.right(), r.top()),
                        (r.left(), r.bottom()),
                        (r.right(), r.bottom()),
                    ]
                    .map(|(x, y)| {
                        let mut p = usvg::tiny_skia_path::Point { x, y };
                        m.map_point(&mut p);
                        (p.x as f64, p.y as f64)
                    });
                    let text: String = t.chunks().iter().map(|c| c.text()).collect();
                    out.push((
                        text,
                        Boxed(
                            corners.iter().map(|c| c.0).fold(f64::MAX, f64::min),
                            corners.iter().map(|c| c.1).fold(f64::MAX, f64::min),
                            corners.iter().map(|c| c.0).fold(f64::MIN, f64::max),
                            corners.iter().map(|c| c.1).fold(f64::MIN, f64::max),
                        ),
                    ));
                }
                _ => {}
            }
        }
    }
    let tree = usvg::Tree::from_str(svg, options).unwrap();
    let mut out = Vec::new();
    walk(tree.root(), &mut out);
    out
}

/// Whether `node` is drawn inside a plot: under a group clipped to the plot box (a
/// `clip-path`) or the plot's data group (`class="data"`, which a panel whose drawing stays
/// clear of the box's edges writes without a clip).
fn in_plot(node: &roxmltree::Node) -> bool {
    node.ancestors()
        .any(|a| a.attribute("clip-path").is_some() || a.attribute("class") == Some("data"))
}

/// Checks one SVG; returns its failures.
fn check(path: &Path, options: &usvg::Options) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let root = doc.root_element();
    let vb = numbers(root.attribute("viewBox").unwrap());
    let page = Boxed(0.0, 0.0, vb[2], vb[3]);
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    let mut fails = Vec::new();
    // panels: plot boxes, ranges, and what they draw
    let mut plots = Vec::new();
    let mut equal_scales = Vec::new();
    for g in doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("panel"))
    {
        let p = numbers(g.attribute("data-plot").unwrap());
        let plot = Boxed(p[0], p[1], p[0] + p[2], p[1] + p[3]);
        if !plot.inside(&page, 0.5) {
            fails.push(format!("{name}: plot box {plot:?} leaves the page"));
        }
        let xr = numbers(g.attribute("data-x-range").unwrap());
        let yr = numbers(g.attribute("data-y-range").unwrap());
        let (sx, sy) = (p[2] / (xr[1] - xr[0]), p[3] / (yr[1] - yr[0]));
        if (sx / sy - 1.0).abs() < 1e-6 {
            equal_scales.push(sx);
            // the drawing's extent: every polyline point in the clipped drawing
            let pts: Vec<f64> = g
                .descendants()
                .filter(|n| n.has_tag_name("polyline"))
                .filter(|n| in_plot(n))
                .flat_map(|n| numbers(n.attribute("points").unwrap()))
                .collect();
            if pts.len() >= 4 {
                let xs = pts.iter().step_by(2);
                let ys = pts.iter().skip(1).step_by(2);
                let span = |v: &mut dyn Iterator<Item = &f64>| {
                    let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
                    hi - lo
                };
                let (w, h) = (span(&mut xs.clone()), span(&mut ys.clone()));
                if w < 0.7 * p[2] && h < 0.7 * p[3] {
                    fails.push(format!(
                        "{name}: the drawing ({w:.0} × {h:.0} px) does not fill its plot box ({:.0} × {:.0} px)",
                        p[2], p[3]
                    ));
                }
            }
        }
        plots.push(plot);
    }
    for (i, a) in plots.iter().enumerate() {
        for b in &plots[i + 1..] {
            if a.overlaps(b, 0.5) {
                fails.push(format!("{name}: plot boxes {a:?} and {b:?} overlap"));
            }
        }
    }
    if let Some(&s0) = equal_scales.first() {
        if equal_scales.iter().any(|s| (s / s0 - 1.0).abs() > 1e-6) {
            fails.push(format!(
                "{name}: structure panels at different scales {equal_scales:?}"
            ));
        }
    }
    let legends: Vec<Boxed> = doc
        .descendants()
        .filter(|n| n.has_tag_name("rect") && n.attribute("class") == Some("legend"))
        .map(|n| {
            let v = |a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
            Boxed(v("x"), v("y"), v("x") + v("width"), v("y") + v("height"))
        })
        .collect();
    // texts: the parser's order is the document's
    let text_nodes: Vec<roxmltree::Node> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .collect();
    let inks = ink_boxes(&svg, options);
    assert_eq!(inks.len(), text_nodes.len(), "{name}: texts laid out");
    let texts: Vec<Text> = text_nodes
        .iter()
        .zip(inks)
        .map(|(n, (text, ink))| Text {
            text,
            ink,
            in_plot: in_plot(n),
        })
        .collect();
    for t in &texts {
        if !t.ink.inside(&page, 0.5) {
            fails.push(format!("{name}: `{}` is clipped ({:?})", t.text, t.ink));
        }
    }
    let in_legend = |t: &Text| legends.iter().any(|l| t.ink.overlaps(l, 0.0));
    for t in texts.iter().filter(|t| in_legend(t)) {
        if !legends.iter().any(|l| t.ink.inside(l, 0.5)) {
            fails.push(format!("{name}: legend text `{}` leaves its box", t.text));
        }
    }
    let free: Vec<&Text> = texts
        .iter()
        .filter(|t| !t.in_plot && !in_legend(t))
        .collect();
    for (i, a) in free.iter().enumerate() {
        for b in &free[i + 1..] {
            if a.ink.overlaps(&b.ink, 0.5) {
                fails.push(format!("{name}: `{}` and `{}` overlap", a.text, b.text));
            }
        }
        for p in &plots {
            if a.ink.overlaps(p, 1.0) {
                fails.push(format!("{name}: `{}` covers a plot box", a.text));
            }
        }
    }
    fails
}

/// The command figures at `size` in `dir`.
fn command_figures(dir: &Path, size: &str) -> Vec<PathBuf> {
    let out = |n: &str| dir.join(n).to_string_lossy().into_owned();
    let runs: Vec<(String, Vec<String>)> = vec![
        ("statics.svg", "statics examples/prism.toml --svg"),
        ("modes.svg", "statics examples/prism.toml --modes 3 --svg"),
        ("dbar.svg", "statics examples/dbar_loaded.toml --svg"),
        (
            "michell.svg",
            "michell --complexity 3 --planar --beta pi/6 --phi pi/8 --svg",
        ),
        (
            "roll.svg",
            "roll --sides 12 --fidelity rigid --t-end 1 --svg",
        ),
        (
            "rolling.svg",
            "fig-rolling --fidelity rigid --t-end 0.5 --out",
        ),
        (
            "solve.svg",
            "solve examples/von_mises.toml --target 2 --svg",
        ),
        (
            "tbar.svg",
            "tbar --beta pi/6 --phi pi/8 --cylindrical 0.25 --svg",
        ),
        ("formfind.svg", "formfind --builtin prism:3 --svg"),
        (
            "sweep.svg",
            "sweep plot docs/data/roll.csv --x incline --y mean_speed --group sides --out",
        ),
    ]
    .into_iter()
    .map(|(file, cmd)| (file.to_string(), cmd.split(' ').map(String::from).collect()))
    .collect();
    let mut files = Vec::new();
    for (file, mut args) in runs {
        args.push(out(&file));
        args.extend(["--size".into(), size.into()]);
        if args[0] == "formfind" {
            args.extend(["--out".into(), out("formfind.toml")]);
        }
        let argv: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = common::run(&argv);
        common::assert_ok(&o);
        files.push(dir.join(file));
    }
    files
}

#[test]
fn every_figure_kind_fits_a_journal_column_and_page() {
    let options = usvg_options();
    let mut fails = Vec::new();
    let mut checked = 0;
    for (k, size) in SIZES.iter().enumerate() {
        let dir = common::scratch("journal", &k.to_string());
        let thesis = dir.join("thesis");
        let o = common::run(&[
            "figures",
            "--quick",
            "--quiet",
            "--size",
            size,
            "--out",
            thesis.to_str().unwrap(),
        ]);
        common::assert_ok(&o);
        let mut files: Vec<PathBuf> = std::fs::read_dir(&thesis)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "svg"))
            .collect();
        files.sort();
        assert!(files.len() >= 30, "{} thesis figures", files.len());
        files.extend(command_figures(&dir, size));
        for f in &files {
            fails.extend(
                check(f, &options)
                    .into_iter()
                    .map(|e| format!("{size}: {e}")),
            );
            checked += 1;
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    assert!(checked >= 120, "{checked} figures checked");
    assert!(
        fails.is_empty(),
        "{} failures:\n{}",
        fails.len(),
        fails.join("\n")
    );
}
