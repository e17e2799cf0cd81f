//! The two-bar (von Mises) truss: two elastic bars from supports at (±a, 0) to an apex at
//! (0, h), a downward load λ P at the apex. On the symmetric path the apex height w gives
//!
//! > λ P = 2 EA w (1/L − 1/L₀),  L = √(a² + w²),  L₀ = √(a² + h²),
//!
//! whose maximum (the limit point) is where dλ/dw = 0: L*³ = a² L₀, w* = √(L*² − a²). The
//! path snaps through: λ falls past zero (the bars horizontal) to −λ* at −w*, then rises on
//! the inverted truss; unstable between the two folds.

use nalgebra::Vector3;
use tensegrity_path::point::Event;
use tensegrity_path::stability::Stability;
use tensegrity_path::{
    follow, load_steps, ElasticMember, ElasticModel, MemberKind, PathSettings, Support,
};

const A: f64 = 1.0;
const H: f64 = 0.5;
const EA: f64 = 1000.0;
const P: f64 = 100.0;

fn truss() -> ElasticModel {
    let l0 = (A * A + H * H).sqrt();
    let bar = |i| ElasticMember {
        nodes: [i, 2],
        kind: MemberKind::Bar,
        ea: EA,
        rest_length: l0,
    };
    ElasticModel {
        nodes: vec![
            Vector3::new(-A, 0.0, 0.0),
            Vector3::new(A, 0.0, 0.0),
            Vector3::new(0.0, H, 0.0),
        ],
        members: vec![bar(0), bar(1)],
        clusters: Vec::new(),
        supports: vec![
            Support::pinned(0),
            Support::pinned(1),
            Support {
                node: 2,
                directions: vec![Vector3::z()],
                stiffness: None,
            },
        ],
        load: vec![
            Vector3::zeros(),
            Vector3::zeros(),
            Vector3::new(0.0, -P, 0.0),
        ],
        drivers: Default::default(),
    }
}

/// λ of the closed form at apex height w.
fn lambda_at(w: f64) -> f64 {
    let (l, l0) = ((A * A + w * w).sqrt(), (A * A + H * H).sqrt());
    2.0 * EA * w * (1.0 / l - 1.0 / l0) / P
}

/// The limit point's (w*, λ*).
fn fold() -> (f64, f64) {
    let l0 = (A * A + H * H).sqrt();
    let l = (A * A * l0).cbrt();
    let w = (l * l - A * A).sqrt();
    (w, lambda_at(w))
}

#[test]
fn every_point_of_the_path_is_the_closed_form_and_both_folds_are_located() {
    let path = follow(
        &truss(),
        &PathSettings {
            target: 1.0,
            ..PathSettings::default()
        },
    )
    .unwrap();
    assert_eq!(path.stop, tensegrity_path::point::Stop::ReachedTarget);
    // every point on the symmetric branch: apex on the axis, λ of its height
    for p in &path.points {
        let [x, y, _] = p.nodes[2];
        assert!(x.abs() < 1e-9, "step {}: apex off the axis by {x}", p.step);
        let expected = lambda_at(y);
        assert!(
            (p.lambda - expected).abs() < 1e-9 * (1.0 + expected.abs()),
            "step {}: {} against {expected}",
            p.step,
            p.lambda
        );
    }
    // it went through: the apex ends below the supports, in tension at λ = 1
    let last = path.points.last().unwrap();
    assert_eq!(last.lambda, 1.0);
    assert!(
        last.nodes[2][1] < -H && last.tensions[0] > 0.0,
        "{:?}",
        last.nodes[2]
    );
    // two limit points at ±λ*, located to 1e-8 relative
    let (w_star, l_star) = fold();
    let folds: Vec<(f64, f64)> = path
        .events
        .iter()
        .filter_map(|e| match e {
            Event::LimitPoint {
                lambda,
                max_displacement,
                ..
            } => Some((*lambda, *max_displacement)),
            _ => None,
        })
        .collect();
    assert_eq!(folds.len(), 2, "{:?}", path.events);
    assert!(
        (folds[0].0 - l_star).abs() < 1e-8 * l_star,
        "{} against {l_star}",
        folds[0].0
    );
    assert!(
        (folds[1].0 + l_star).abs() < 1e-8 * l_star,
        "{} against {}",
        folds[1].0,
        -l_star
    );
    assert!(
        (folds[0].1 - (H - w_star)).abs() < 1e-4,
        "{} against {}",
        folds[0].1,
        H - w_star
    );
    assert!((folds[1].1 - (H + w_star)).abs() < 1e-4);
    // the mode at a fold is the apex moving vertically
    if let Event::LimitPoint { mode, .. } = &path.events[0] {
        assert!(
            (mode[2][1].abs() - 1.0).abs() < 1e-9 && mode[2][0].abs() < 1e-6,
            "{mode:?}"
        );
    }
    // stable up to the first fold and after the second, unstable between
    for p in &path.points {
        let y = p.nodes[2][1];
        let expected = if y > w_star + 1e-6 || y < -w_star - 1e-6 {
            Stability::Stable
        } else if y.abs() < w_star - 1e-6 {
            Stability::Unstable
        } else {
            continue;
        };
        assert_eq!(
            p.stability, expected,
            "step {} at apex height {y}: {:?}",
            p.step, p.smallest_eigenvalues
        );
    }
}

#[test]
fn the_reactions_balance_the_load_at_every_point() {
    let path = follow(&truss(), &PathSettings::default()).unwrap();
    for p in &path.points {
        let mut total = Vector3::new(0.0, -P * p.lambda, 0.0);
        for r in &p.reactions {
            total += Vector3::from(r.direction) * r.force;
        }
        assert!(total.amax() < 1e-8 * P, "step {}: {total:?}", p.step);
    }
}

#[test]
fn load_control_stops_at_the_limit_point_and_names_the_path() {
    let (_, l_star) = fold();
    // below the fold load control agrees with the path
    let below = load_steps(&truss(), 10, 0.9 * l_star).unwrap();
    let y = below.points.last().unwrap().nodes[2][1];
    assert!((lambda_at(y) - 0.9 * l_star).abs() < 1e-9);
    // past it there is no equilibrium near: an error naming the arc-length path
    let err = load_steps(&truss(), 10, 1.2 * l_star)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("arc length") || err.contains("limit point"),
        "{err}"
    );
}

#[test]
fn load_control_that_lands_past_the_fold_reports_the_jump() {
    // steps of 0.3 λ*: from 0.9 λ* Newton lands on the inverted truss at 1.2 λ*… or fails
    let (_, l_star) = fold();
    match load_steps(&truss(), 4, 1.2 * l_star) {
        Ok(path) => {
            let jumps: Vec<&Event> = path
                .events
                .iter()
                .filter(|e| matches!(e, Event::Jump { .. }))
                .collect();
            assert_eq!(jumps.len(), 1, "{:?}", path.events);
            let last = path.points.last().unwrap();
            assert!(
                last.nodes[2][1] < -H,
                "on the inverted branch: {:?}",
                last.nodes[2]
            );
        }
        Err(e) => assert!(e.to_string().contains("arc length"), "{e}"),
    }
    // examples/von_mises.toml (EA = 1e7 Pa × π (0.01 m)²) in 10 steps to λ = 2, as
    // `solve examples/von_mises.toml --load-steps 10 --target 2`: from λ = 1.2, below its fold
    // at 1.2059, Newton lands on the inverted truss at 1.4, and the report says so
    let mut scene = truss();
    for m in &mut scene.members {
        m.ea = 1e7 * std::f64::consts::PI * 1e-4;
    }
    let path = load_steps(&scene, 10, 2.0).unwrap();
    let jump = path.events.iter().find_map(|e| match e {
        Event::Jump {
            from_lambda,
            to_lambda,
            ratio,
        } => Some((*from_lambda, *to_lambda, *ratio)),
        _ => None,
    });
    let (from, to, ratio) = jump.expect("the snap is reported");
    assert!(
        (from - 1.2).abs() < 1e-12 && (to - 1.4).abs() < 1e-12 && ratio > 3.0,
        "{from} {to} {ratio}"
    );
    assert!(path.points.last().unwrap().nodes[2][1] < -H);
}

/// Self-weight (a scene with `[gravity]` and bar masses): each bar puts half its weight on
/// the apex from the start, so the live load at the fold is the closed form's less the bars'
/// weight on the apex: λ* P − (m g/2)·2.
#[test]
fn the_bars_weight_is_a_dead_load_that_lowers_the_fold_by_itself() {
    use tensegrity_core::{Bar, Material, Structure, Support as Held};
    let (mass, g) = (1.5, 9.81);
    // E π r² = EA: r = 0.01 m, E = EA/(π 10⁻⁴)
    let e = EA / (std::f64::consts::PI * 1e-4);
    let s = Structure::builder()
        .node([-A, 0.0, 0.0])
        .node([A, 0.0, 0.0])
        .node([0.0, H, 0.0])
        .material("soft", Material::new(1000.0, e, 1e6))
        .bar(Bar::new(0, 2).material("soft").radius(0.01).mass(mass))
        .bar(Bar::new(1, 2).material("soft").radius(0.01).mass(mass))
        .support(Held::pinned(0))
        .support(Held::pinned(1))
        .support(Held::directions(2, [false, false, true]))
        .load(2, [0.0, -P, 0.0])
        .gravity([0.0, -g, 0.0])
        .build()
        .unwrap();
    let model = ElasticModel::from_structure(&s).unwrap();
    assert!((model.drivers.dead_load[2].y + mass * g).abs() < 1e-12);
    let path = follow(&model, &PathSettings::default()).unwrap();
    let (_, l_star) = fold();
    let expected = l_star - mass * g / P;
    let first = path.events.iter().find_map(|e| match e {
        Event::LimitPoint { lambda, .. } => Some(*lambda),
        _ => None,
    });
    let first = first.unwrap();
    assert!(
        (first - expected).abs() < 1e-8 * expected,
        "{first} against {expected}"
    );
    // at λ = 0 the truss already sags under its weight: the closed form at m g
    let y0 = path.points[0].nodes[2][1];
    assert!(
        (lambda_at(y0) * P - mass * g).abs() < 1e-9 * P,
        "{}",
        lambda_at(y0) * P
    );
}
