use super::*;
use crate::params::Value;
use std::collections::BTreeMap;

fn params(pairs: &[(&str, Value)]) -> Params {
    Params::new(
        pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect::<BTreeMap<_, _>>(),
    )
}

/// Scalar leaves of a JSON value, as `.`-joined paths (sorted).
fn leaves(v: &serde_json::Value, prefix: &str, out: &mut Vec<String>) {
    scalar_leaves(v, prefix, true, out);
}

/// Scalar leaves, nulls included or not.
fn scalar_leaves(v: &serde_json::Value, prefix: &str, nulls: bool, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, v) in m {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                scalar_leaves(v, &p, nulls, out);
            }
        }
        serde_json::Value::Array(_) => {}
        serde_json::Value::Null if !nulls => {}
        _ => out.push(prefix.to_string()),
    }
}

/// The columns are exactly the report's scalars, in the report's key order.
fn check_columns<T: Serialize>(study: Study, reports: &[T]) {
    let mut all = Vec::new();
    for r in reports {
        leaves(&serde_json::to_value(r).unwrap(), "", &mut all);
    }
    all.sort();
    all.dedup();
    let mut cols: Vec<String> = study.columns().iter().map(|c| c.name.to_string()).collect();
    cols.sort();
    assert_eq!(cols, all, "{}", study.name());
    // order: the top-level keys appear in the serialised text in the columns' order
    let text = serde_json::to_string(&reports[0]).unwrap();
    let mut last = 0;
    for c in study.columns() {
        let key = format!("\"{}\":", c.name.split('.').next().unwrap());
        let at = text.find(&key).unwrap_or_else(|| panic!("{key}"));
        assert!(at >= last, "{} out of order", c.name);
        last = at;
    }
}

#[test]
fn columns_are_the_scalars_of_the_reports() {
    let t = toroid::toroid_report(&toroid::ToroidRequest::default()).unwrap();
    check_columns(Study::Toroid, &[t]);
    let mut r = toroid::roll(&toroid::RollRequest {
        fidelity: toroid::FidelityChoice::Rigid,
        t_end: 0.2,
        ..Default::default()
    })
    .unwrap();
    // the optional keys as a run with an impact and a penalty ground has them
    r.summary.first_impact = Some(toroid::FirstImpact {
        t: 0.5,
        omega_before: 2.0,
        omega_after: 1.5,
    });
    r.ground_damping = Some(100.0);
    check_columns(Study::Roll, &[r]);
    check_columns(
        Study::Tipover,
        &[toroid::tipover_report(&Default::default()).unwrap()],
    );
    use michell3d::{analyse, AnalysisRequest, MichellParams};
    let (b, f) = (std::f64::consts::FRAC_PI_6, std::f64::consts::FRAC_PI_4);
    let cyl = analyse(&AnalysisRequest {
        extra_strings: Some(10.0),
        ..AnalysisRequest::new(MichellParams::cylindrical(2, 1.0, b, f, 0.25))
    })
    .unwrap();
    let sph = analyse(&AnalysisRequest::new(MichellParams::spherical(
        2,
        1.0,
        b,
        f / 2.0,
        0.1,
    )))
    .unwrap();
    check_columns(Study::Michell, &[cyl, sph]);
}

#[test]
fn empty_params_are_the_cli_defaults() {
    let p = Params::default();
    assert_eq!(
        wheel::toroid_request(&p).unwrap(),
        toroid::ToroidRequest::default()
    );
    assert_eq!(
        roll::roll_request(&p).unwrap(),
        toroid::RollRequest::default()
    );
    assert_eq!(
        wheel::tipover_request(&p).unwrap(),
        toroid::TipoverRequest::default()
    );
}

#[test]
fn flags_map_onto_the_requests() {
    let p = params(&[
        ("sides", Value::Integer(12)),
        ("stabilize", Value::Text("spokes,outer".into())),
        ("incline", Value::Text("30deg".into())),
        ("fidelity", Value::Text("rigid".into())),
        ("contact", Value::Text("penalty".into())),
        ("mu", Value::Float(0.5)),
    ]);
    let r = roll::roll_request(&p).unwrap();
    assert_eq!(r.wheel.params.sides, 12);
    assert!(r.wheel.stabilize.outer && !r.wheel.stabilize.inner);
    assert_eq!(r.settings.incline, 30f64.to_radians());
    assert_eq!(
        (r.fidelity, r.contact, r.mu),
        (
            toroid::FidelityChoice::Rigid,
            toroid::ContactKind::Penalty,
            0.5
        )
    );
    let bad = params(&[("fidelity", Value::Text("exact".into()))]);
    let e = roll::roll_request(&bad).unwrap_err().to_string();
    assert!(
        e.contains("`fidelity`") && e.contains("rigid, full, auto"),
        "{e}"
    );
}

#[test]
fn sigma_and_epsilon_set_the_inner_radius_and_tread() {
    let p = params(&[
        ("sigma", Value::Float(0.5)),
        ("epsilon", Value::Float(0.25)),
        ("outer_radius", Value::Float(2.0)),
    ]);
    let r = wheel::tipover_request(&p).unwrap();
    assert_eq!(
        (r.wheel.params.inner_radius, r.wheel.params.inner_tread),
        (1.0, 0.25 * 0.4)
    );
    let report = toroid::tipover_report(&r).unwrap();
    assert_eq!((report.sigma, report.epsilon), (0.5, 0.25));
    // eq. 3.29: F_f' = −(σ + ε)/(1 − σ)
    assert!((report.normalized_friction + 0.75 / 0.5).abs() < 1e-12);
    let both = params(&[
        ("sigma", Value::Float(0.5)),
        ("inner_radius", Value::Float(0.5)),
    ]);
    assert!(wheel::tipover_request(&both)
        .unwrap_err()
        .to_string()
        .contains("not both"));
}

#[test]
fn michell_needs_exactly_one_geometry() {
    let base = [
        ("complexity", Value::Integer(3)),
        ("beta", Value::Text("pi/6".into())),
        ("phi", Value::Text("pi/8".into())),
    ];
    let with = |extra: &[(&str, Value)]| {
        let mut all = base.to_vec();
        all.extend_from_slice(extra);
        michell::request(&params(&all))
    };
    assert!(with(&[]).unwrap_err().to_string().contains("exactly one"));
    let two = with(&[
        ("planar", Value::Bool(true)),
        ("cylindrical", Value::Float(0.1)),
    ]);
    assert!(two.is_err());
    let r = with(&[
        ("spherical", Value::Text("pi/24".into())),
        ("method", Value::Text("global".into())),
    ])
    .unwrap();
    assert_eq!(
        r.params,
        michell3d::MichellParams::spherical(
            3,
            1.0,
            std::f64::consts::PI / 6.0,
            std::f64::consts::PI / 8.0,
            std::f64::consts::PI / 24.0
        )
    );
    assert_eq!(r.method, michell3d::Method::Global);
    assert_eq!((r.load, r.material.as_str()), (1000.0, "steel"));
}

#[test]
fn a_failing_case_is_an_error_message() {
    let ctx = Context::default();
    let e = Study::Toroid
        .report(&params(&[("sides", Value::Integer(1))]), &ctx)
        .unwrap_err();
    assert!(!e.is_empty());
    let e = Study::Integrators
        .report(
            &params(&[
                ("scene", Value::Text("pendulum".into())),
                ("integrator", Value::Text("rk4".into())),
                ("parameter", Value::Float(1e-3)),
            ]),
            &ctx,
        )
        .unwrap_err();
    assert!(e.contains("double-pendulum"), "{e}");
}

#[test]
fn an_integrators_point_converges_at_fourth_order() {
    // RK4 on the oscillating prism: halving dt divides the error against the shared RK45
    // reference by about 2⁴
    let ctx = Context::default();
    let point = |dt: f64| {
        let p = params(&[
            ("scene", Value::Text("prism-oscillating".into())),
            ("integrator", Value::Text("rk4".into())),
            ("parameter", Value::Float(dt)),
        ]);
        Study::Integrators.report(&p, &ctx).unwrap()
    };
    let (a, b) = (point(4e-3), point(2e-3));
    assert_eq!(a["scene"], "prism-oscillating");
    assert_eq!(a["integrator"], "rk4");
    assert_eq!(a["steps"], 250);
    let ratio = a["error"].as_f64().unwrap() / b["error"].as_f64().unwrap();
    assert!((10.0..24.0).contains(&ratio), "{ratio}");
}

#[test]
fn tbar_columns_are_the_scalars_of_its_reports_and_rows_equal_the_library_report() {
    use crate::params::Value;
    let text = |s: &str| Value::Text(s.to_string());
    let cases = [
        params(&[
            ("beta", text("pi/6")),
            ("phi", text("pi/8")),
            ("cylindrical", Value::Float(0.25)),
            ("prestress", Value::Float(5.0)),
            ("directions", Value::Integer(50)),
        ]),
        params(&[
            ("beta", text("pi/6")),
            ("phi", text("pi/8")),
            ("spherical", text("pi/12")),
            ("wheel", Value::Bool(true)),
        ]),
        params(&[
            ("beta", text("pi/6")),
            ("phi", text("pi/8")),
            ("spherical", text("pi/12")),
            ("extended", Value::Float(0.5)),
            ("bar_base", text("chord")),
        ]),
    ];
    let mut seen = Vec::new();
    let cols: Vec<&str> = Study::Tbar.columns().iter().map(|c| c.name).collect();
    for p in &cases {
        let req = tbar::request(p).unwrap();
        let direct = serde_json::to_value(tbar_wheel::tbar_report(&req).unwrap()).unwrap();
        let via_study = Study::Tbar.report(p, &Context::default()).unwrap();
        assert_eq!(direct, via_study);
        let mut leaves = Vec::new();
        scalar_leaves(&direct, "", false, &mut leaves);
        for l in &leaves {
            assert!(cols.contains(&l.as_str()), "{l} is not a column");
        }
        seen.extend(leaves);
    }
    for c in &cols {
        assert!(seen.iter().any(|s| s == c), "column {c} never filled");
    }
    // the first case is the q = 1 tread of the tbar-wheel tests: min_prestress = 3.2357686 w0
    let r = tbar_wheel::tbar_report(&tbar::request(&cases[0]).unwrap()).unwrap();
    assert!((r.min_prestress.unwrap() - 3.235768601).abs() < 1e-8);
}
