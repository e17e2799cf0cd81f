use super::*;
use serde::Serialize;
use serde_json::{json, Map, Value};
use tensegrity_core::request::{check_description, Category, Request};

fn values(v: Value) -> Map<String, Value> {
    v.as_object().unwrap().clone()
}

/// Scalar leaves of a JSON value, as `.`-joined paths; nulls included or not.
fn scalar_leaves(v: &Value, prefix: &str, nulls: bool, out: &mut Vec<String>) {
    match v {
        Value::Object(m) => {
            for (k, v) in m {
                let p = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                scalar_leaves(v, &p, nulls, out);
            }
        }
        Value::Array(_) => {}
        Value::Null if !nulls => {}
        _ => out.push(prefix.to_string()),
    }
}

/// The columns are exactly the report's scalars (`skip`: input echoes left out), in the
/// report's key order.
fn check_columns<T: Serialize>(name: &str, reports: &[T], skip: &[&str]) {
    let mut all = Vec::new();
    for r in reports {
        scalar_leaves(&serde_json::to_value(r).unwrap(), "", true, &mut all);
    }
    all.retain(|c| !skip.contains(&c.as_str()));
    all.sort();
    all.dedup();
    let columns = command(name).unwrap().columns;
    let mut cols: Vec<String> = columns.iter().map(|c| c.name.to_string()).collect();
    cols.sort();
    assert_eq!(cols, all, "{name}");
    let text = serde_json::to_string(&reports[0]).unwrap();
    let mut last = 0;
    for c in columns {
        let key = format!("\"{}\":", c.name.split('.').next().unwrap());
        let at = text.find(&key).unwrap_or_else(|| panic!("{key}"));
        assert!(at >= last, "{} out of order in {text}", c.name);
        last = at;
    }
}

#[test]
fn every_request_describes_its_fields() {
    check_description::<integrators::IntegratorsRequest>().unwrap();
    check_description::<toroid::RollRequest>().unwrap();
    check_description::<tbar_wheel::TbarRollRequest>().unwrap();
    for c in commands() {
        let names: Vec<&str> = c.params().iter().map(|p| p.name).collect();
        for n in c.defaults().keys() {
            assert!(names.contains(&n.as_str()), "{}: {n}", c.name);
        }
    }
}

#[test]
fn columns_are_the_scalars_of_the_reports() {
    let t = toroid::toroid_report(&toroid::ToroidRequest::default()).unwrap();
    check_columns("toroid", &[t], &[]);
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
    check_columns("roll", &[r], &[]);
    let tip = toroid::tipover_report(&Default::default()).unwrap();
    check_columns("tipover", &[tip], &[]);
    use michell3d::{analyse, AnalysisRequest, MichellParams};
    let (b, f) = (std::f64::consts::FRAC_PI_6, std::f64::consts::FRAC_PI_4);
    let cyl = analyse(&AnalysisRequest {
        extra_strings: Some(10.0),
        ..AnalysisRequest::new(MichellParams::cylindrical(2, 1.0, b, f, 0.25))
    })
    .unwrap();
    let sph = MichellParams::spherical(2, 1.0, b, f / 2.0, 0.1);
    let sph = analyse(&AnalysisRequest::new(sph)).unwrap();
    check_columns("michell", &[cyl, sph], &[]);
    let optimum = |g: &str, v: Value| {
        let mut m = values(json!({"radius_ratio": 0.25, "complexity": 3}));
        m.insert(g.into(), v);
        let req = michell3d::MichellOptimizeRequest::from_values(m).unwrap();
        req.run().unwrap()
    };
    let reports = [
        optimum("planar", json!(true)),
        optimum("cylindrical", json!(0.25)),
        optimum("spherical", json!(0.05)),
    ];
    check_columns("michell_optimize", &reports, &[]);
}

#[test]
fn a_failing_case_is_an_error_and_a_bad_value_names_its_parameter() {
    let ctx = Context::default();
    let toroid = command("toroid").unwrap();
    // a wheel the geometry rules refuse: by the request's check, naming the parameter
    let e = toroid.run(values(json!({"sides": 1})), &ctx).unwrap_err();
    assert!(
        matches!(e, RunError::InvalidParameter(ref p) if p.name == "sides"),
        "{e}"
    );
    // a case the library refuses when it runs
    let michell = command("michell").unwrap();
    let v = json!({"complexity": 200, "cylindrical": 0.25, "beta": "pi/6", "phi": "pi/8"});
    let e = michell.run(values(v), &ctx).unwrap_err();
    assert!(
        matches!(e, RunError::Refused { ref message, category: Category::Input } if message.contains("complexity = 200")),
        "{e}"
    );
    let e = toroid.run(values(json!({"sides": 8.5})), &ctx).unwrap_err();
    assert!(
        matches!(e, RunError::InvalidParameter(ref p) if p.name == "sides"),
        "{e}"
    );
    let e = command("integrators")
        .unwrap()
        .run(
            values(json!({"scene": "pendulum", "integrator": "rk4", "parameter": 1e-3})),
            &ctx,
        )
        .unwrap_err();
    assert!(e.to_string().contains("double-pendulum"), "{e}");
}

#[test]
fn an_integrators_point_converges_at_fourth_order() {
    // RK4 on the oscillating prism: halving dt divides the error against the shared RK45
    // reference by about 2⁴
    let ctx = Context::default();
    let point = |dt: f64| {
        let v = json!({"scene": "prism-oscillating", "integrator": "rk4", "parameter": dt});
        command("integrators")
            .unwrap()
            .run(values(v), &ctx)
            .unwrap()
    };
    let (a, b) = (point(4e-3), point(2e-3));
    assert_eq!(a["scene"], "prism-oscillating");
    assert_eq!(a["integrator"], "rk4");
    assert_eq!(a["steps"], 250);
    let ratio = a["error"].as_f64().unwrap() / b["error"].as_f64().unwrap();
    assert!((10.0..24.0).contains(&ratio), "{ratio}");
}

#[test]
fn tbar_columns_are_the_scalars_of_its_reports_and_runs_equal_the_library_report() {
    let cases = [
        json!({"beta": "pi/6", "phi": "pi/8", "cylindrical": 0.25, "prestress": 5.0, "directions": 50}),
        json!({"beta": "pi/6", "phi": "pi/8", "spherical": "pi/12", "wheel": true}),
        json!({"beta": "pi/6", "phi": "pi/8", "spherical": "pi/12", "extended": 0.5, "bar_base": "chord"}),
    ];
    let tbar = command("tbar").unwrap();
    let cols: Vec<&str> = tbar.columns.iter().map(|c| c.name).collect();
    let mut seen = Vec::new();
    for v in cases {
        let req = tbar_wheel::TbarStaticRequest::from_values(values(v.clone())).unwrap();
        let direct =
            serde_json::to_value(tbar_wheel::tbar_report(&req.request()).unwrap()).unwrap();
        // the registry's report is the library's with the conventional keys beside
        let conventional = crate::keys::conventional(direct.clone());
        assert_eq!(
            conventional,
            tbar.run(values(v), &Context::default()).unwrap()
        );
        let mut leaves = Vec::new();
        scalar_leaves(&direct, "", false, &mut leaves);
        for l in &leaves {
            assert!(cols.contains(&l.as_str()), "{l} is not a column");
        }
        seen.extend(leaves);
    }
    // set only for a rank decision with values on both sides of the tolerance, or without a
    // clear gap: none of these T-bars has either
    let rare = [
        "spectral_gap.sigma_below",
        "spectral_gap.ratio",
        "statics_warning",
    ];
    for c in cols.iter().filter(|c| !rare.contains(c)) {
        assert!(seen.iter().any(|s| s == c), "column {c} never filled");
    }
}

#[test]
fn the_dynamic_and_rolling_columns_are_their_reports_scalars() {
    // short runs: only the keys matter here
    let d = toroid::TipoverDynamicRequest::from_values(values(json!({
        "settle": 0.01, "ramp_time": 0.02, "output_dt": 0.01
    })))
    .unwrap();
    let mut report = d.run().unwrap();
    report.dynamic_threshold = Some(1.0);
    report.relative_difference = Some(0.0);
    report.tip_time = Some(1.0);
    check_columns("tipover_dynamic", &[report], &[]);
    let r = toroid::TipoverRollingRequest::from_values(values(json!({
        "t_end": 0.02, "output_dt": 0.01
    })))
    .unwrap();
    let mut lean = r.run().unwrap();
    lean.fall_time = Some(1.0);
    let echo = ["sides", "outer_tread", "incline", "side_slope"];
    check_columns("tipover_rolling", &[lean], &echo);
}

#[test]
fn the_scene_requests_describe_their_fields() {
    check_description::<statics::StaticsCommand>().unwrap();
    check_description::<simulate::SimulateCommand>().unwrap();
    check_description::<bench::WorkPrecisionRequest>().unwrap();
}

/// A request through its JSON form and back, and its registry entry by name.
fn round_trip<R: Request + std::fmt::Debug + PartialEq>(r: &R) {
    let v = serde_json::to_value(r).unwrap();
    assert_eq!(&serde_json::from_value::<R>(v.clone()).unwrap(), r);
    assert_eq!(&R::from_values(values(v)).unwrap(), r);
    let c = command(R::NAME).unwrap();
    assert_eq!(c.name, R::NAME);
    let params: Vec<&str> = c.params().iter().map(|p| p.name).collect();
    let fields: Vec<&str> = R::params().iter().map(|p| p.name).collect();
    assert_eq!(params, fields);
}

#[test]
fn the_scene_requests_round_trip_through_json_and_the_registry() {
    use tensegrity_dynamics::IntegratorKind;
    use tensegrity_statics::stiffness::MassModel;
    use tensegrity_statics::StaticsMethod;
    let s = statics::StaticsCommand {
        scene: Some(SceneSource::parse("../../examples/prism.toml")),
        rank_tol: Some(1e-9),
        input_precision: Some(5e-10),
        modes: Some(2),
        mass: MassModel::Consistent,
        least_squares: true,
        response: true,
        method: StaticsMethod::Sparse,
    };
    round_trip(&s);
    let v = serde_json::to_value(&s).unwrap();
    assert_eq!(v["method"], "sparse");
    assert_eq!(v["mass"], "consistent");
    assert_eq!(v["scene"], "../../examples/prism.toml");
    let text = std::fs::read_to_string("../../examples/prism.toml").unwrap();
    round_trip(&statics::StaticsCommand {
        scene: Some(SceneSource::parse(&text)),
        ..Default::default()
    });
    let m = simulate::SimulateCommand {
        scene: Some(SceneSource::parse("../../examples/double_pendulum.toml")),
        t_end: Some(0.5),
        integrator: Some(IntegratorKind::Sdirk),
        dt: Some(1e-3),
        rtol: Some(1e-7),
        atol: Some(1e-9),
        output_interval: Some(0.1),
        strict: true,
        convergence_check: false,
    };
    round_trip(&m);
    assert_eq!(serde_json::to_value(&m).unwrap()["integrator"], "sdirk");
    round_trip(&bench::WorkPrecisionRequest { quick: true });
    // the study reports a list of points: no scalar column
    assert!(command("bench_work_precision").unwrap().columns.is_empty());
}

#[test]
fn statics_by_name_gives_the_cores_rank_and_self_stress_count() {
    use tensegrity_statics::{statics_report, StaticsRequest};
    let ctx = Context::default();
    // the Snelson prism: 12 members, one self-stress state (rank 11)
    for (path, self_stress) in [
        ("../../examples/prism.toml", Some(1)),
        ("../../examples/tower.toml", None),
    ] {
        let scene = tensegrity_io::scene::Scene::from_path(path.as_ref()).unwrap();
        let direct = statics_report(&scene.structure, &StaticsRequest::default()).unwrap();
        if let Some(n) = self_stress {
            assert_eq!((direct.self_stress_dim, direct.rank), (n, 11));
        }
        let run = command("statics")
            .unwrap()
            .run(values(json!({ "scene": path })), &ctx)
            .unwrap();
        assert_eq!(run["rank"], direct.rank);
        assert_eq!(run["self_stress_dim"], direct.self_stress_dim);
        assert_eq!(run["mechanisms"], direct.mechanisms);
        // rank–nullity of the equilibrium matrix: members = rank + self-stress states
        let members = direct.bars + direct.strings;
        assert_eq!(direct.rank + direct.self_stress_dim, members);
    }
}

#[test]
fn statics_admitted_refuses_before_the_report() {
    let c = statics::StaticsCommand {
        scene: Some(SceneSource::parse("../../examples/prism.toml")),
        ..Default::default()
    };
    let refuse = |e: Option<tensegrity_core::budget::Estimate>| {
        let e = e.expect("the prism takes the dense SVD");
        let tight = tensegrity_core::budget::Limits {
            memory_bytes: 1.0,
            ..Default::default()
        };
        tight.check(&e).map_err(Box::<dyn std::error::Error>::from)
    };
    let e = statics::admitted(&c, None, refuse).unwrap_err().to_string();
    assert!(
        e.contains("memory") && e.starts_with("method = auto"),
        "{e}"
    );
    let (scene, report) = statics::admitted(&c, None, |_| Ok::<_, SceneError>(())).unwrap();
    assert_eq!(scene.structure.n_members(), report.bars + report.strings);
}

#[test]
fn statics_runs_equal_the_library_report_and_its_columns_are_its_scalars() {
    use tensegrity_statics::{statics_report, StaticsRequest};
    let path = "../../examples/dbar_loaded.toml";
    let scene = tensegrity_io::scene::Scene::from_path(path.as_ref()).unwrap();
    let direct = statics_report(&scene.structure, &StaticsRequest::default()).unwrap();
    let statics = command("statics").unwrap();
    let ctx = Context::default();
    let run = statics.run(values(json!({ "scene": path })), &ctx).unwrap();
    let direct_json = crate::keys::conventional(serde_json::to_value(&direct).unwrap());
    assert_eq!(run, direct_json);
    assert_eq!(run["node_count"], run["nodes"]);
    // the published minimum mass of the D-bar: 8.858023 kg
    assert!((run["mass_kg"].as_f64().unwrap() - 8.858023).abs() < 1e-5);
    // the scene's text gives the same report as its file
    let text = std::fs::read_to_string(path).unwrap();
    let by_text = statics.run(values(json!({ "scene": text })), &ctx).unwrap();
    assert_eq!(by_text, run);
    // the modes and the sparse path through the request's fields
    let v = json!({"scene": path, "method": "sparse", "modes": 2, "least_squares": true});
    let sparse = statics.run(values(v), &ctx).unwrap();
    assert_eq!(sparse["statics_method"], "sparse_qr");
    assert_eq!(sparse["rank"], run["rank"]);
    // every optional scalar set, for the key check
    let mut full = direct;
    full.prestress_stable = Some(true);
    full.residual = Some(0.0);
    full.load_carried = Some(true);
    full.sizing_warning = Some("w".into());
    full.modal_error = Some("m".into());
    full.sizing_error = Some("s".into());
    full.statics_method = Some(tensegrity_statics::Factorization::SparseQr);
    full.statics_warning = Some("w".into());
    check_columns("statics", &[full], &[]);
}

#[test]
fn a_scene_given_as_data_runs_as_its_toml_text() {
    use tensegrity_io::scene::{Scene, SceneArrays};
    let ctx = Context::default();
    for (command_name, path, extra) in [
        ("statics", "../../examples/dbar_loaded.toml", json!({})),
        ("statics", "../../examples/tower.toml", json!({"modes": 3})),
        (
            "simulate",
            "../../examples/prism_drop.toml",
            json!({"t_end": 0.2, "convergence_check": false}),
        ),
    ] {
        let c = command(command_name).unwrap();
        let text = std::fs::read_to_string(path).unwrap();
        let scene = Scene::from_str_named(&text, path).unwrap();
        let data = serde_json::to_value(SceneArrays::of(&scene)).unwrap();
        let run_with = |scene: Value| {
            let mut v = values(extra.clone());
            v.insert("scene".into(), scene);
            let mut r = c.run(v, &ctx).unwrap();
            r.as_object_mut().unwrap().remove("wall_time_s");
            r
        };
        assert_eq!(run_with(data.clone()), run_with(json!(text)), "{path}");
        // the request reads the object as data, and writes it back as the same object
        let mut v = values(extra.clone());
        v.insert("scene".into(), data.clone());
        if command_name == "statics" {
            let r = statics::StaticsCommand::from_values(v).unwrap();
            assert!(matches!(r.scene, Some(SceneSource::Data(_))));
            assert_eq!(serde_json::to_value(&r).unwrap()["scene"], data);
            assert_eq!(r.source().unwrap().to_string(), "structure data");
        }
    }
    // a bad value of the data is refused naming `scene`, a bad item naming the item
    let statics = command("statics").unwrap();
    let bad = json!({"scene": {"nodes": [[0.0, 0.0, 0.0]], "bar": [[0, 1]]}});
    let e = statics.run(values(bad), &ctx).unwrap_err().to_string();
    assert!(
        e.starts_with("scene = ") && e.contains("unknown field `bar`"),
        "{e}"
    );
    let bad = json!({"scene": {"nodes": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], "bars": [[0, 2]]}});
    let e = statics.run(values(bad), &ctx).unwrap_err().to_string();
    assert!(e.starts_with("structure data: bar 0: node index 2"), "{e}");
}

#[test]
fn simulate_runs_equal_the_library_run_and_strict_fails_on_drift() {
    use tensegrity_dynamics::SimulationReport;
    let path = "../../examples/prism_drop.toml";
    let scene = tensegrity_io::scene::Scene::from_path(path.as_ref()).unwrap();
    let direct = SimulationReport::from(&scene.simulation().unwrap().run().unwrap());
    let simulate = command("simulate").unwrap();
    let ctx = Context::default();
    let mut run = simulate
        .run(
            values(json!({ "scene": path, "convergence_check": false })),
            &ctx,
        )
        .unwrap();
    let mut want = serde_json::to_value(&direct).unwrap();
    // measured wall times differ; everything else is the same run
    for v in [&mut run, &mut want] {
        v.as_object_mut().unwrap().remove("wall_time_s");
    }
    assert_eq!(run, want);
    assert_eq!(run["t_end"], 3.0);
    // with the check: the same run, and its final state against the refined run's
    let checked = simulate
        .run(values(json!({ "scene": path })), &ctx)
        .unwrap();
    assert_eq!(checked["final_nodes"], want["final_nodes"]);
    let c = &checked["convergence"];
    assert_eq!(c["refinement"], "rtol/10, atol/10, largest step/2");
    assert_eq!(c["converged"], true, "{c}");
    let checked: SimulationReport = {
        let mut r = direct.clone();
        r.convergence = serde_json::from_value(c.clone()).ok();
        r
    };
    check_columns("simulate", &[checked], &[]);
    // rk4 at 0.01 s drifts (as `simulate --dt 0.01` warns): strict makes it an error
    let drift = json!({"scene": path, "integrator": "rk4", "dt": 0.01});
    let loose = simulate.run(values(drift.clone()), &ctx).unwrap();
    assert_eq!(loose["warnings"][0]["kind"], "drift");
    assert!(loose["warnings"][0]["message"]
        .as_str()
        .unwrap()
        .contains("bar lengths drifted"));
    let mut strict = values(drift);
    strict.insert("strict".into(), json!(true));
    let e = simulate.run(strict, &ctx).unwrap_err();
    let m = e.to_string();
    assert!(
        m.starts_with("strict: ") && m.contains("bar lengths drifted"),
        "{m}"
    );
}

#[test]
fn the_work_precision_study_by_name_shows_rk4_fourth_order() {
    let c = command("bench_work_precision").unwrap();
    let report = c
        .run(values(json!({ "quick": true })), &Context::default())
        .unwrap();
    let points = report["points"].as_array().unwrap();
    // every integrator is measured, or each of its runs is listed with the reason it failed
    let skipped = report["skipped"].as_array().unwrap();
    for integrator in tensegrity_dynamics::IntegratorKind::RIGID_NAMES {
        assert!(
            points.iter().any(|p| p["integrator"] == *integrator),
            "{integrator}"
        );
    }
    for s in skipped {
        assert!(!s["reason"].as_str().unwrap().is_empty(), "{s}");
    }
    // RK4 on the oscillating prism: a step 4× smaller cuts the error about 4⁴ = 256×
    let rk4: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p["scene"] == "prism-oscillating" && p["integrator"] == "rk4")
        .map(|p| {
            (
                p["parameter"].as_f64().unwrap(),
                p["error"].as_f64().unwrap(),
            )
        })
        .collect();
    let coarse = rk4.iter().find(|p| p.0 == 4e-3).unwrap();
    let fine = rk4.iter().find(|p| p.0 == 1e-3).unwrap();
    let ratio = coarse.1 / fine.1;
    assert!((128.0..512.0).contains(&ratio), "{ratio}");
}

#[test]
fn formfind_describes_its_fields_round_trips_and_its_columns_are_its_scalars() {
    check_description::<formfind::FormfindRequest>().unwrap();
    round_trip(&formfind::FormfindRequest {
        builtin: Some("prism".into()),
        n: Some(5),
        method: Some(::formfind::Method::Adaptive),
        prestress: 20.0,
        ..Default::default()
    });
    round_trip(&formfind::FormfindRequest {
        topology: Some(SceneSource::parse("../../examples/formfind/cable_net.toml")),
        group: Some("y".into()),
        ratio: 2.0,
        analyse: true,
        ..Default::default()
    });
    let report = formfind::FormfindReport {
        source: "prism:3".into(),
        n_nodes: 6,
        n_bars: 3,
        n_strings: 9,
        method: ::formfind::Method::Fdm,
        nodes: vec![[0.0; 3]; 6],
        force_density: vec![1.0; 12],
        self_stress_dim: Some(1),
        prestressable: Some(true),
        prestress_stable: Some(true),
        residual: 0.0,
        iterations: 1,
        tolerance: None,
        height: 1.0,
        max_bar_length: 1.5,
        prestress: 100.0,
        member_force: Some(vec![1.0; 12]),
        rest_length: Some(vec![1.0; 9]),
        loading: Default::default(),
        warnings: vec![tensegrity_core::Warning::NotPrestressable],
    };
    check_columns("formfind", &[report], &[]);
}
