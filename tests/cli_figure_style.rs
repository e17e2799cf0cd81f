//! The structure drawings and figure formats of the CLI: `statics --svg` draws the structure
//! to scale with the load solve's forces and its reactions (one polyline per member, x and y
//! scales equal to 1e-6 against the scene's node coordinates), `statics --modes K --svg`
//! draws K mode shapes; `--size` and `--dpi` give a PDF page and a PNG of the stated size;
//! bad sizes, views and dpi are refused naming the flag (exit 2) before any work.

use crate::common;

use std::path::Path;

fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
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
}

fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert!(bytes.starts_with(b"\x89PNG"));
    (
        u32::from_be_bytes(bytes[16..20].try_into().unwrap()),
        u32::from_be_bytes(bytes[20..24].try_into().unwrap()),
    )
}

#[test]
fn statics_draws_the_loaded_dbar_to_scale_with_its_reactions() {
    let dir = common::scratch("figure-style", "statics");
    let svg = dir.join("dbar.svg");
    common::assert_ok(&common::run(&[
        "statics",
        "examples/dbar_loaded.toml",
        "--svg",
        svg.to_str().unwrap(),
        "--size",
        "1000x300",
    ]));
    let text = std::fs::read_to_string(&svg).unwrap();
    let scene =
        tensegrity_io::scene::Scene::from_path(Path::new("examples/dbar_loaded.toml")).unwrap();
    let s = &scene.structure;
    // one polyline per member
    let lines = polylines(&text);
    assert_eq!(lines.len(), s.n_members());
    // the dbar lies in the x–y plane: the drawing is its xy view; every member end is one
    // node, and px = a + k x, py = b − k y with one k
    let nodes = s.nodes();
    let (mut xs, mut pxs, mut ys, mut pys) = (vec![], vec![], vec![], vec![]);
    // every polyline end, in the member order of the drawing (strings, then bars)
    let order: Vec<[usize; 2]> = s
        .strings()
        .iter()
        .map(|m| m.nodes)
        .chain(s.bars().iter().map(|b| b.nodes))
        .collect();
    for ([i, j], line) in order.iter().zip(&lines) {
        for (n, p) in [(*i, line[0]), (*j, line[1])] {
            xs.push(nodes[n].x);
            ys.push(nodes[n].y);
            pxs.push(p.0);
            pys.push(p.1);
        }
    }
    let fit = |a: &[f64], b: &[f64]| {
        let n = a.len() as f64;
        let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
        let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
        let var: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
        let k = cov / var;
        let worst = a
            .iter()
            .zip(b)
            .map(|(x, y)| (mb + k * (x - ma) - y).abs())
            .fold(0.0, f64::max);
        (k, worst)
    };
    let (kx, rx) = fit(&xs, &pxs);
    let (ky, ry) = fit(&ys, &pys);
    assert!((kx / -ky - 1.0).abs() < 1e-6, "x {kx} px/m, y {} px/m", -ky);
    assert!(rx < 1e-4 && ry < 1e-4, "residuals {rx} {ry} px");
    // forces coloured with a colour bar, tension dashed, reactions and the load drawn
    assert!(text.contains("class=\"colorbar\""));
    assert!(text.contains("stroke-dasharray"));
    for entry in ["reaction", "load", "support", "member force [N]"] {
        assert!(text.contains(entry), "{entry} missing");
    }
}

#[test]
fn pdf_and_png_are_written_at_the_requested_size() {
    let dir = common::scratch("figure-style", "formats");
    let pdf = dir.join("prism.pdf");
    common::assert_ok(&common::run(&[
        "statics",
        "examples/prism.toml",
        "--svg",
        pdf.to_str().unwrap(),
        "--size",
        "6x4in",
    ]));
    let bytes = std::fs::read(&pdf).unwrap();
    assert!(bytes.starts_with(b"%PDF-"));
    let text = String::from_utf8_lossy(&bytes);
    let at = text.find("/MediaBox").expect("a MediaBox") + "/MediaBox".len();
    let inner = &text[at..][text[at..].find('[').unwrap() + 1..text[at..].find(']').unwrap()];
    let b: Vec<f64> = inner
        .split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect();
    assert!(
        (b[2] - b[0] - 432.0).abs() < 0.01 && (b[3] - b[1] - 288.0).abs() < 0.01,
        "MediaBox {b:?} of a 6x4in page"
    );
    // where poppler is installed (not on CI), the page renders at that size: 300 × 200 at 50 dpi
    if let Ok(status) = std::process::Command::new("pdftoppm")
        .args(["-r", "50", "-png", "-singlefile"])
        .arg(&pdf)
        .arg(dir.join("page"))
        .status()
    {
        assert!(status.success());
        assert_eq!(png_size(&dir.join("page.png")), (300, 200));
    }
    let png = dir.join("modes.png");
    common::assert_ok(&common::run(&[
        "statics",
        "examples/prism.toml",
        "--modes",
        "2",
        "--svg",
        png.to_str().unwrap(),
        "--size",
        "8x3in",
        "--dpi",
        "150",
    ]));
    assert_eq!(png_size(&png), (1200, 450));
    // the mode shapes: two panels, each over the undeformed structure, frequencies in titles
    let svg = dir.join("modes.svg");
    common::assert_ok(&common::run(&[
        "statics",
        "examples/prism.toml",
        "--modes",
        "2",
        "--svg",
        svg.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert_eq!(text.matches("class=\"panel\"").count(), 2);
    assert_eq!(
        text.matches("Hz</text>").count(),
        2,
        "frequencies in the titles"
    );
    assert!(text.contains("reference"));
}

#[test]
fn bad_figure_flags_are_refused_before_any_work() {
    let dir = common::scratch("figure-style", "bad");
    let out = dir.join("x.svg");
    for (flag, value) in [("--size", "6x"), ("--view", "front"), ("--dpi", "0")] {
        let r = common::run(&[
            "statics",
            "examples/prism.toml",
            "--svg",
            out.to_str().unwrap(),
            flag,
            value,
        ]);
        assert_eq!(r.status.code(), Some(2), "{flag} {value}");
        let stderr = String::from_utf8_lossy(&r.stderr);
        assert!(stderr.contains(flag) || stderr.contains(value), "{stderr}");
        assert!(!out.exists());
    }
    let r = common::run(&["statics", "examples/prism.toml", "--svg", "x.gif"]);
    assert_eq!(r.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&r.stderr).contains("svg, png, pdf"));
}
