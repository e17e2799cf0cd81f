//! Figures that tell the truth (issue 46): a figure of a run that is not valid says so on the
//! figure — `NOT VALID: <first warning's kind>` in red above its panels (`roll --svg`,
//! `simulate --animate`), a valid run's figure does not; and `sweep plot` draws 12 groups in
//! 12 different strokes that differ in dash and marker even without colour.
//!
//! The invalid runs are those of `tests/cli_strict.rs`: `roll` on the full model for 1 s
//! under the split IMEX (its first impact's ω⁻ not converged) and `simulate` of the damped
//! prism drop by RATTLE at 0.01 s (its energy grows).

use crate::common;

use common::{assert_ok, run, scratch};
use std::collections::HashSet;
use std::fs::File;
use std::path::Path;

/// The text of the invalid mark of `svg`, if any.
fn mark(svg: &str) -> Option<String> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let g = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("invalid"))?;
    let text: String = g
        .descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .collect();
    Some(text.trim().to_string())
}

#[test]
fn roll_svg_of_a_run_that_is_not_valid_says_so_and_of_a_valid_run_does_not() {
    let dir = scratch("marks", "roll");
    let bad = dir.join("bad.svg");
    let args = [
        "roll",
        "--fidelity",
        "full",
        "--integrator",
        "imex",
        "--t-end",
        "1",
        "--svg",
        bad.to_str().unwrap(),
    ];
    let out = run(&args);
    assert_ok(&out);
    let text = std::fs::read_to_string(&bad).unwrap();
    assert_eq!(
        mark(&text).as_deref(),
        Some("NOT VALID: not_converged"),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    // the PDF carries it too (svg2pdf writes the text as text)
    let pdf = dir.join("bad.pdf");
    let mut pdf_args = args;
    pdf_args[8] = pdf.to_str().unwrap();
    assert_ok(&run(&pdf_args));
    assert!(std::fs::metadata(&pdf).unwrap().len() > 0);

    let good = dir.join("good.svg");
    let args = [
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "0.5",
        "--svg",
        good.to_str().unwrap(),
    ];
    assert_ok(&run(&args));
    let text = std::fs::read_to_string(&good).unwrap();
    assert_eq!(mark(&text), None);
    assert!(!text.contains("NOT VALID"));
}

/// Pixels of the first frame's top band (the invalid mark's, 19 px) that are the mark's red.
fn red_in_top_band(path: &Path) -> usize {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(File::open(path).unwrap()).unwrap();
    let f = decoder.read_next_frame().unwrap().unwrap();
    let (w, top) = (f.width as usize, f.top as usize);
    let rows = 19usize.saturating_sub(top).min(f.height as usize);
    f.buffer[..4 * w * rows]
        .chunks(4)
        .filter(|p| p[0] > 150 && p[1] < 80 && p[2] < 80)
        .count()
}

#[test]
fn simulate_animation_of_a_run_that_is_not_valid_is_marked_above_its_frames() {
    let dir = scratch("marks", "animate");
    let (bad, good) = (dir.join("bad.gif"), dir.join("good.gif"));
    let scene = "examples/prism_drop.toml";
    let bad_args = [
        "simulate",
        scene,
        "--integrator",
        "rattle",
        "--dt",
        "0.01",
        "--duration",
        "0.5",
        "--animate",
        bad.to_str().unwrap(),
    ];
    assert_ok(&run(&bad_args));
    let good_args = [
        "simulate",
        scene,
        "--duration",
        "0.5",
        "--animate",
        good.to_str().unwrap(),
    ];
    assert_ok(&run(&good_args));
    let (r_bad, r_good) = (red_in_top_band(&bad), red_in_top_band(&good));
    assert!(r_bad > 20, "{r_bad} red pixels where the mark goes");
    assert_eq!(r_good, 0);
}

#[test]
fn sweep_plot_of_twelve_groups_draws_twelve_strokes_distinct_in_dash_and_marker() {
    let dir = scratch("marks", "plot");
    let csv = dir.join("twelve.csv");
    let mut text = String::from("case,status,x,y,g\n");
    let mut case = 0;
    for g in 0..12 {
        for i in 0..5 {
            let y = (i as f64 * 0.3 + g as f64).sin() + 0.2 * g as f64;
            text.push_str(&format!("{case},ok,{i},{y},g{g}\n"));
            case += 1;
        }
    }
    std::fs::write(&csv, text).unwrap();
    let svg = dir.join("twelve.svg");
    let args = [
        "sweep",
        "plot",
        csv.to_str().unwrap(),
        "--x",
        "x",
        "--y",
        "y",
        "--group",
        "g",
        "--out",
        svg.to_str().unwrap(),
    ];
    assert_ok(&run(&args));
    let text = std::fs::read_to_string(&svg).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let nodes: Vec<_> = doc.descendants().collect();
    let mut strokes = Vec::new();
    for (i, n) in nodes.iter().enumerate() {
        if !n.has_tag_name("polyline") {
            continue;
        }
        let marker = nodes[i + 1..]
            .iter()
            .take_while(|m| !m.has_tag_name("polyline"))
            .find_map(|m| m.attribute("data-marker"))
            .unwrap_or("none");
        strokes.push((
            n.attribute("stroke").unwrap().to_string(),
            n.attribute("stroke-dasharray")
                .unwrap_or("solid")
                .to_string(),
            marker.to_string(),
        ));
    }
    assert_eq!(strokes.len(), 12);
    let colours: HashSet<_> = strokes.iter().map(|s| &s.0).collect();
    assert_eq!(colours.len(), 12, "{strokes:?}");
    let grey: HashSet<_> = strokes.iter().map(|s| (&s.1, &s.2)).collect();
    assert_eq!(grey.len(), 12, "without colour: {strokes:?}");
}
