use super::*;
use serde_json::json;
use tensegrity_core::budget::Limits;

fn err(text: &str) -> String {
    Spec::parse(text).unwrap_err().to_string()
}

#[test]
fn axes_keep_the_spec_order_and_the_last_varies_fastest() {
    let s = Spec::parse(
        r#"
        study = "toroid"
        [axes]
        stabilize = ["spokes,inner", "spokes,outer"]
        sides = [8, 12, 16]
        "#,
    )
    .unwrap();
    let names: Vec<&str> = s.axes.iter().map(|a| a.name.as_str()).collect();
    assert_eq!(names, ["stabilize", "sides"]);
    assert_eq!(s.case_count().unwrap(), 6);
    let texts: Vec<Vec<String>> = (0..6).map(|i| s.axis_texts(i)).collect();
    assert_eq!(texts[0], ["spokes,inner", "8"]);
    assert_eq!(texts[1], ["spokes,inner", "12"]);
    assert_eq!(texts[3], ["spokes,outer", "8"]);
    assert_eq!(texts[5], ["spokes,outer", "16"]);
    assert_eq!(s.digits(4), [1, 1]);
}

#[test]
fn list_values_keep_their_text() {
    let s = Spec::parse(
        r#"
        study = "roll"
        [axes]
        outer_tread = [0.40, 1e-1, 3]
        incline = ["pi/8", "30deg", 0.5]
        "#,
    )
    .unwrap();
    let t = |k: usize| -> Vec<&str> { s.axes[k].values.iter().map(|v| v.text.as_str()).collect() };
    assert_eq!(t(0), ["0.40", "1e-1", "3"]);
    assert_eq!(t(1), ["pi/8", "30deg", "0.5"]);
    assert_eq!(s.axes[0].values[1].value, json!(0.1));
}

#[test]
fn ranges() {
    let s = Spec::parse(
        r#"
        study = "tipover"
        [axes]
        sides = { from = 3, to = 9, step = 2 }
        sigma = { from = 0.1, to = 0.5, step = 0.1 }
        gravity = { from = 1, to = 100, steps = 3, log = true }
        bar_density = { from = 1e-4, to = 1e-11, steps = 8, log = true }
        offset = { from = 0, to = 1, steps = 5 }
        "#,
    )
    .unwrap();
    let t = |k: usize| -> Vec<&str> { s.axes[k].values.iter().map(|v| v.text.as_str()).collect() };
    assert_eq!(t(0), ["3", "5", "7", "9"]);
    assert_eq!(s.axes[0].values[0].value, json!(3));
    assert_eq!(t(1), ["0.1", "0.2", "0.3", "0.4", "0.5"]);
    assert_eq!(t(2), ["1", "10", "100"]);
    assert_eq!(t(3)[0], "0.0001");
    assert_eq!(t(3)[7], "0.00000000001");
    let x: Vec<f64> = s.axes[3]
        .values
        .iter()
        .map(|v| v.text.parse().unwrap())
        .collect();
    assert_eq!(x[1..7], [1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]);
    assert_eq!(t(4), ["0", "0.25", "0.5", "0.75", "1"]);
    assert_eq!(s.case_count().unwrap(), 4 * 5 * 3 * 8 * 5);
    for bad in [
        "{ from = 1, to = 2 }",
        "{ from = 1, to = 2, steps = 2, step = 1 }",
        "{ from = 1, to = 2, step = -1 }",
        "{ from = 1, to = 2, step = 0 }",
        "{ from = 0, to = 2, steps = 3, log = true }",
        "{ from = 1, to = 2, steps = 0 }",
        "{ from = 1, to = 2, steps = 3, by = 2 }",
        "[]",
        "3",
    ] {
        let e = err(&format!("study = \"tipover\"\n[axes]\nsigma = {bad}\n"));
        assert!(e.contains("sigma"), "{bad}: {e}");
    }
}

#[test]
fn derived_rules_follow_their_parameters() {
    let s = Spec::parse(
        r#"
        study = "michell"
        [fixed]
        planar = true
        beta = "pi/6"
        [axes]
        complexity = [2, 4]
        [derived]
        r0 = "2 * phi"
        phi = "pi / complexity"
        "#,
    )
    .unwrap();
    assert_eq!(s.derived[0].0, "phi");
    let p = s.case(1).params.unwrap();
    assert_eq!(p["phi"], json!(std::f64::consts::PI / 4.0));
    assert_eq!(p["r0"], json!(std::f64::consts::PI / 2.0));
    assert_eq!(p["beta"], json!("pi/6"));
    let beta = numeric(&s.study.param("beta").unwrap(), &p["beta"]).unwrap();
    assert_eq!(beta, std::f64::consts::PI / 6.0);
}

#[test]
fn spec_errors_come_before_any_case() {
    let base = "study = \"toroid\"\n";
    assert!(err("study = \"wheel\"").contains("unknown study `wheel`"));
    assert!(
        err(&format!("{base}[fixed]\nsidez = 8")).contains("unknown parameter `sidez` in [fixed]")
    );
    assert!(err(&format!("{base}[axes]\nsidez = [8]")).contains("`sidez` in [axes]"));
    assert!(err(&format!("{base}[derived]\nsidez = \"8\"")).contains("`sidez` in [derived]"));
    assert!(err(&format!("{base}[fixed]\nsides = 8\n[axes]\nsides = [8]")).contains("both"));
    assert!(err(&format!("{base}extra = 1")).contains("extra"));
    assert!(err(&format!("{base}[output]\ncolumns = [\"mass\"]")).contains("`mass`"));
    assert!(err(&format!("{base}[output]\nformat = \"csv\"")).contains("format"));
    assert!(err(&format!("{base}[derived]\noffset = \"1 / n\"")).contains("`n`"));
    assert!(err(&format!("{base}[derived]\noffset = \"(1\"")).contains("offset"));
    assert!(err(&format!("{base}[derived]\nstabilize = \"1\"")).contains("numeric"));
    assert!(err(&format!(
        "{base}[derived]\noffset = \"rim_radius\"\nrim_radius = \"offset\""
    ))
    .contains("cycle"));
    assert!(err("study = \"michell\"\n[fixed]\nbeta = 1\nphi = 1")
        .contains("needs the parameter `complexity`"));
    let big = format!("{base}[axes]\nsides = {{ from = 1, to = 100000, step = 1 }}\noffset = {{ from = 1, to = 100000, step = 1 }}");
    assert!(err(&big).contains("more than the limit"));
}

#[test]
fn a_failing_derived_rule_fails_its_case_only() {
    let s = Spec::parse(
        r#"
        study = "toroid"
        [axes]
        sides = [0, 8]
        [derived]
        offset = "0.8 / sides"
        "#,
    )
    .unwrap();
    assert!(s
        .case(0)
        .params
        .unwrap_err()
        .to_string()
        .contains("division by zero"));
    assert_eq!(s.case(1).params.unwrap()["offset"], json!(0.1));
}

#[test]
fn a_hundred_million_value_axis_is_refused_before_its_values_are_made() {
    // the issue's one-axis sweep of 10⁸ values: 12.8 GB of values, 20 GB of CSV; refused
    // from the sizes alone (it used to allocate the values and abort at the memory cap)
    let text = "study = \"tipover\"\n[axes]\nsigma = { from = 0.1, to = 0.9, steps = 100000000 }\n";
    let started = std::time::Instant::now();
    let e = Spec::parse(text).unwrap_err();
    let SweepError::OverBudget { over } = &e else {
        panic!("{e}");
    };
    assert_eq!(over.resource, tensegrity_core::budget::Resource::Memory);
    assert_eq!(over.estimated, 1e8 * crate::limits::AXIS_VALUE_BYTES);
    assert!(
        e.to_string().starts_with("axis sigma (100000000 values): "),
        "{e}"
    );
    // with the memory there, the output limit refuses it, naming the axis and the cases
    let roomy = Limits {
        memory_bytes: 1e15,
        ..Limits::default()
    };
    let e = Spec::parse_within(text, &roomy).unwrap_err().to_string();
    assert!(
        e.starts_with("axis sigma (100000000 values): 100000000 sweep cases"),
        "{e}"
    );
    assert!(e.contains("18.626 GiB of output"), "{e}");
    // a step range is sized the same way, and a product names every axis
    let two = "study = \"tipover\"\n[axes]\nsides = { from = 3, to = 10002, step = 1 }\nsigma = { from = 0.1, to = 0.9, steps = 1000 }\n";
    let e = Spec::parse_within(two, &Limits::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("axes sides (10000 values) × sigma (1000 values): 10000000 sweep cases"),
        "{e}"
    );
    assert!(
        started.elapsed().as_secs_f64() < 2.0,
        "{:?}",
        started.elapsed()
    );
    // more cases than MAX_CASES is still its own error, before any value is made
    let many = "study = \"tipover\"\n[axes]\nsigma = { from = 0.1, to = 0.9, steps = 100000 }\nepsilon = { from = 0.1, to = 0.9, steps = 100000 }\n";
    assert!(matches!(
        Spec::parse(many),
        Err(SweepError::TooManyCases {
            cases: 10_000_000_000,
            ..
        })
    ));
}

#[test]
fn a_result_column_named_as_an_axis_is_left_out() {
    // tipover's report echoes `sigma` and `epsilon`: the axes' columns hold them
    let s = Spec::parse("study = \"tipover\"\n[axes]\nsigma = [0.3]\nepsilon = [0.25]\n").unwrap();
    let h = crate::table::header(&s);
    assert!(
        h.starts_with(&[
            "case".into(),
            "sigma".into(),
            "epsilon".into(),
            "mass_kg".into(),
            "rho".into(),
            "cot_theta".into()
        ]),
        "{h:?}"
    );
    let mut names = h.clone();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), h.len(), "{h:?}");
    // a fixed value keeps its result column (it has no axis column)
    let f = Spec::parse("study = \"tipover\"\n[fixed]\nepsilon = 0.25\n[axes]\nsigma = [0.3]\n")
        .unwrap();
    assert!(f.columns.iter().any(|c| c.name == "epsilon"));
    assert!(!f.columns.iter().any(|c| c.name == "sigma"));
    // `[output] columns` repeated, or naming an axis: each name once
    let o = Spec::parse("study = \"tipover\"\n[axes]\nsigma = [0.3]\n[output]\ncolumns = [\"rho\", \"mass_kg\", \"rho\", \"sigma\"]\n").unwrap();
    assert_eq!(
        crate::table::header(&o),
        ["case", "sigma", "rho", "mass_kg", "status", "message"]
    );
}
