//! Figures that say what the numbers say (issue 46): `statics --modes K` lists in its JSON and
//! text the same modes its `--svg` draws, the zero (rigid-body) modes skipped in both and
//! counted in `zero_modes_skipped`; `sweep plot` draws column names and file names as plain
//! text (`mean_speed` with its underscore), and its `--title`, `--xlabel`, `--ylabel` replace
//! the defaults, math only between `$` pairs.

use crate::common;

use common::{assert_ok, json, run, scratch};

/// The text of every `<text>` of `svg` and whether it has `<tspan>`s (sub- or superscripts).
fn texts(svg: &str) -> Vec<(String, bool)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|t| {
            let all = t
                .descendants()
                .filter(|n| n.is_text())
                .filter_map(|n| n.text())
                .collect();
            (all, t.children().any(|n| n.has_tag_name("tspan")))
        })
        .collect()
}

#[test]
fn the_modes_listed_are_the_modes_drawn_without_the_rigid_body_modes() {
    let dir = scratch("figure-truth", "modes");
    let svg = dir.join("modes.svg");
    let svg = svg.to_str().unwrap();
    let args = ["statics", "examples/prism.toml", "--modes", "4"];
    let v = json(&[&args[..], &["--json", "--svg", svg]].concat());
    // the free prism: six rigid-body modes, skipped
    assert_eq!(v["zero_modes_skipped"], 6);
    let listed = common::numbers(&v["natural_frequencies_hz"]);
    assert_eq!(listed.len(), 4);
    // the prestress-stiffened mechanism first: 1.5559 Hz (lumped masses)
    assert!((listed[0] - 1.5559).abs() < 1e-4, "{listed:?}");
    assert!(listed.windows(2).all(|w| w[0] <= w[1]), "{listed:?}");
    // the panels' titles: `mode i: f = F Hz`, the same frequencies, modes 7 to 10
    let text = std::fs::read_to_string(svg).unwrap();
    let titles: Vec<(usize, f64)> = texts(&text)
        .into_iter()
        .filter_map(|(t, _)| {
            let rest = t.strip_prefix("mode ")?;
            let (i, f) = rest.split_once(": f = ")?;
            Some((i.parse().unwrap(), f.strip_suffix(" Hz")?.parse().unwrap()))
        })
        .collect();
    assert_eq!(
        titles.iter().map(|t| t.0).collect::<Vec<_>>(),
        [7, 8, 9, 10]
    );
    for ((_, drawn), listed) in titles.iter().zip(&listed) {
        assert!(
            (drawn - listed).abs() < 1e-4,
            "{titles:?} against {listed:?}"
        );
        assert!(*drawn > 1.0, "a zero mode drawn: {titles:?}");
    }
    // the text report says how many it skipped and lists the same values
    let out = run(&args);
    assert_ok(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("lowest natural frequencies"))
        .unwrap();
    assert_eq!(
        line,
        "lowest natural frequencies [Hz] (6 zero-frequency modes skipped): 1.5559, 5.3518, 5.3518, 8.2631"
    );
}

#[test]
fn sweep_plot_draws_column_and_file_names_as_text_and_takes_its_labels() {
    let dir = scratch("figure-truth", "plot");
    let csv = dir.join("prism_drop.csv");
    std::fs::write(
        &csv,
        "case,status,tread_width,mean_speed,wheel_kind\n\
         0,ok,0.1,1.5,a_b\n1,ok,0.2,1.7,a_b\n2,ok,0.1,1.1,c\n3,ok,0.2,1.2,c\n",
    )
    .unwrap();
    let svg = dir.join("plot.svg");
    let base = [
        "sweep",
        "plot",
        csv.to_str().unwrap(),
        "--x",
        "tread_width",
        "--y",
        "mean_speed",
        "--group",
        "wheel_kind",
        "--out",
        svg.to_str().unwrap(),
    ];
    assert_ok(&run(&base));
    let t = texts(&std::fs::read_to_string(&svg).unwrap());
    for want in [
        "prism_drop.csv",
        "tread_width",
        "mean_speed",
        "wheel_kind = a_b",
    ] {
        let found = t.iter().find(|(s, _)| s == want);
        assert_eq!(found, Some(&(want.to_string(), false)), "{want}: {t:?}");
    }
    // given labels: plain text as written, math between dollars
    let given = [
        "--title",
        "drop_test 3",
        "--xlabel",
        "width_w [m]",
        "--ylabel",
        "$v_x$ [m/s]",
    ];
    assert_ok(&run(&[&base[..], &given].concat()));
    let t = texts(&std::fs::read_to_string(&svg).unwrap());
    let has = |s: &str, scripts: bool| t.iter().any(|x| x.0 == s && x.1 == scripts);
    assert!(
        has("drop_test 3", false) && has("width_w [m]", false),
        "{t:?}"
    );
    assert!(has("vx [m/s]", true), "{t:?}");
    assert!(!t
        .iter()
        .any(|x| x.0 == "mean_speed" || x.0 == "prism_drop.csv"));
}
