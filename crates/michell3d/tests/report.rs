//! The analysis behind `tensegrity michell` and its JSON.

use michell3d::*;
use std::f64::consts::{FRAC_PI_6, PI};

#[test]
fn json_has_the_documented_shape() {
    let mut req = AnalysisRequest::new(MichellParams::cylindrical(
        2,
        1.0,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ));
    req.load = 500.0;
    let r = analyse(&req).unwrap();
    let v: serde_json::Value = serde_json::to_value(&r).unwrap();
    assert_eq!(v["nodes"].as_array().unwrap().len(), 10);
    assert_eq!(v["nodes"][0]["index"], serde_json::json!([0, 0, 0, 0]));
    assert_eq!(
        v["nodes"][0]["position"],
        serde_json::json!([0.0, 1.0, 0.0])
    );
    let members = v["members"].as_array().unwrap();
    assert_eq!(members.len(), 12);
    assert_eq!(members[2]["parent"], serde_json::json!([0, 0, 0, 0]));
    assert_eq!(members[2]["child"], serde_json::json!([0, 1, 0, 0]));
    // q = 1 tip members under −ι̂₃: strings, strings, bar (eq. 4.18–4.20 signs).
    assert_eq!(members[0]["kind"], "string");
    assert_eq!(members[1]["kind"], "string");
    assert_eq!(members[2]["kind"], "bar");
    for m in members {
        let (q, l, f) = (
            m["force_density"].as_f64().unwrap(),
            m["length"].as_f64().unwrap(),
            m["force"].as_f64().unwrap(),
        );
        assert!((q * l - f).abs() < 1e-9 * f.abs().max(1.0));
    }
    let my = v["mass_kg"]["yield"].as_f64().unwrap();
    let myb = v["mass_kg"]["yield_buckling"].as_f64().unwrap();
    assert!(myb >= my && my > 0.0);
    // normalized_yield_mass = Σ|q| l² / (w₀ r₀), and yield mass = ρ/σ w₀ r₀ × it (steel).
    let nym: f64 = members
        .iter()
        .map(|m| m["force_density"].as_f64().unwrap().abs() * m["length"].as_f64().unwrap().powi(2))
        .sum::<f64>()
        / 500.0;
    assert!((v["normalized_yield_mass"].as_f64().unwrap() - nym).abs() < 1e-12 * nym);
    assert!((my - 7862.0 / 690e6 * 500.0 * nym).abs() < 1e-12 * my);
}

#[test]
fn planar_labels_and_extra_strings_in_report() {
    let r = analyse(&AnalysisRequest::new(MichellParams::planar(
        3,
        1.0,
        FRAC_PI_6,
        PI / 3.0,
    )))
    .unwrap();
    assert_eq!(r.nodes[4].index, vec![1, 1]);
    assert_eq!(r.members.len(), 12);
    assert!(
        (r.normalized_yield_mass - michell3d::planar::yield_mass_normalized(&r.params)).abs()
            < 1e-10
    );
    // Planar kinds follow Fig. 4.4 for the bending load: U spiral tension, D compression.
    for m in &r.members {
        let up = m.child[0] > m.parent[0];
        assert_eq!(
            m.kind,
            if up {
                MemberKind::String
            } else {
                MemberKind::Bar
            }
        );
    }

    let mut req = AnalysisRequest::new(MichellParams::cylindrical(
        3,
        1.0,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ));
    req.extra_strings = Some(200.0);
    req.method = Method::Global;
    let r = analyse(&req).unwrap();
    assert_eq!(r.extra_strings.len(), 12);
    assert!(r
        .extra_strings
        .iter()
        .all(|s| s.kind == MemberKind::String && (s.force - 200.0).abs() < 1e-9));
    let without = analyse(&AnalysisRequest {
        extra_strings: None,
        ..req.clone()
    })
    .unwrap();
    assert!(r.mass_kg.yield_only > without.mass_kg.yield_only);
}
