//! Text in figures is plain unless marked as math: `mean_speed` is drawn with its underscore
//! (one `<text>` with no `<tspan>`, no `dy`), while `$q_{ij}$` and `$σ_y$` keep their
//! subscripts (issue 46: a sweep's column `mean_speed` was drawn as mean<sub>s</sub>peed).

use tensegrity_io::figure::{literal, plain_text, Figure, Panel, Series};

/// The `<text>` elements of `svg`: (all their text, the `<tspan>`s as (text, dy, font size)).
type Tspan = (String, Option<f64>, f64);

fn texts(svg: &str) -> Vec<(String, Vec<Tspan>)> {
    let doc = roxmltree::Document::parse(svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|t| {
            let all: String = t
                .descendants()
                .filter(|n| n.is_text())
                .filter_map(|n| n.text())
                .collect();
            let spans = t
                .children()
                .filter(|n| n.has_tag_name("tspan"))
                .map(|s| {
                    (
                        s.text().unwrap_or("").to_string(),
                        s.attribute("dy").map(|d| d.parse().unwrap()),
                        s.attribute("font-size").unwrap().parse().unwrap(),
                    )
                })
                .collect();
            (all, spans)
        })
        .collect()
}

fn find<'a>(texts: &'a [(String, Vec<Tspan>)], text: &str) -> &'a [Tspan] {
    &texts
        .iter()
        .find(|(t, _)| t == text)
        .unwrap_or_else(|| panic!("no text {text:?} in {texts:?}"))
        .1
}

#[test]
fn underscores_are_text_and_math_between_dollars_keeps_its_scripts() {
    let panel = Panel::new("prism_drop.toml", "$q_{ij}$ [N/m]", "mean_speed")
        .series(Series::new("$σ_y$ = 250 MPa", vec![(0.0, 1.0), (1.0, 2.0)]))
        .series(Series::new(
            "wheel_kind = a^2",
            vec![(0.0, 2.0), (1.0, 1.0)],
        ));
    let svg = Figure::new(vec![panel]).to_svg().unwrap();
    assert!(!svg.contains("baseline-shift"));
    let texts = texts(&svg);
    // plain text: one run, as written
    for plain in ["prism_drop.toml", "mean_speed", "wheel_kind = a^2"] {
        assert!(find(&texts, plain).is_empty(), "{plain} has tspans");
    }
    // math: the subscript lowered by 0.28 of the size, at 0.72 of it, then raised back
    let q = find(&texts, "qij [N/m]");
    assert_eq!(q.len(), 3, "{q:?}");
    let size = q[0].2;
    let close = |a: Option<f64>, b: f64| (a.unwrap() - b).abs() < 1e-4;
    assert_eq!(q[1].0, "ij");
    assert!(
        close(q[1].1, 0.28 * size) && close(Some(q[1].2), 0.72 * size),
        "{q:?}"
    );
    assert!(close(q[2].1, -0.28 * size), "{q:?}");
    let sigma = find(&texts, "σy = 250 MPa");
    assert_eq!(sigma[1].0, "y");
    assert!(sigma[1].1.unwrap() > 0.0);
}

#[test]
fn literal_text_stays_text_even_with_dollars() {
    let name = "cost_$a_b$.csv";
    let panel = Panel::new(literal(name), "x", "y").series(Series::new("", vec![(0.0, 0.0)]));
    let svg = Figure::new(vec![panel]).to_svg().unwrap();
    assert!(find(&texts(&svg), name).is_empty());
    assert_eq!(plain_text(&literal(name)), name);
    assert_eq!(plain_text("$F_f/F_e$ [–]"), "Ff/Fe [–]");
}
