//! `tensegrity bench work-precision [--out DIR] [--quick]`: error against wall time for every
//! integrator on three scenes, written as CSV and an SVG plot (log–log, one curve per
//! integrator, one panel per scene).
//!
//! Scenes: a prestressed Snelson prism oscillating (one vertical string 1 % short, 1 s), the
//! compound double pendulum (class-2 joint, pinned support, 2 s) and a prism dropped on a
//! penalty ground (contact and friction, no normal damping, 0.5 s). The error is the largest node-position
//! difference at the end time against a tight RK45 reference (rtol = atol = 1e-13).

use anyhow::{Context, Result};
use std::fmt::Write as _;
use std::path::PathBuf;
use tensegrity_core::dynamics::examples::{double_pendulum, snelson_prism, PrismParams};
use tensegrity_core::dynamics::{IntegratorKind, Simulation};
use tensegrity_core::Structure;
use tensegrity_io::scene::{build_simulation, GroundModelKind, GroundSpec};

/// Arguments of `tensegrity bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// Which benchmark.
    #[command(subcommand)]
    pub what: BenchCommand,
}

/// Benchmarks.
#[derive(clap::Subcommand, Debug)]
pub enum BenchCommand {
    /// Error against wall time for rk4, rk45 and rattle on three scenes.
    WorkPrecision(WorkPrecisionArgs),
}

/// Arguments of `tensegrity bench work-precision`.
#[derive(clap::Args, Debug)]
pub struct WorkPrecisionArgs {
    /// Output directory for work_precision.csv and work_precision.svg.
    #[arg(long, value_name = "DIR", default_value = "work-precision")]
    pub out: PathBuf,
    /// Fewer points and a single timing repetition (for a smoke test).
    #[arg(long)]
    pub quick: bool,
}

/// One measured point.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Scene name.
    pub scene: &'static str,
    /// Integrator.
    pub integrator: IntegratorKind,
    /// dt (fixed step) or rtol (rk45).
    pub parameter: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Force evaluations.
    pub rhs_evals: u64,
    /// Max node-position error at the end time (m).
    pub error: f64,
    /// Best-of-N integration wall time (s).
    pub wall_time_s: f64,
}

struct Scene {
    name: &'static str,
    t_end: f64,
    make: fn() -> Result<Simulation>,
}

fn oscillating_prism() -> Result<Simulation> {
    let s = snelson_prism(&PrismParams::default())?;
    let mut strings = s.strings().to_vec();
    strings[6].rest_length = strings[6].rest_length.map(|l| 0.99 * l);
    let mut b = Structure::builder().nodes(s.nodes().iter().map(|n| [n.x, n.y, n.z]));
    for bar in s.bars() {
        b = b.bar(bar.clone());
    }
    for st in strings {
        b = b.string(st);
    }
    Ok(build_simulation(&b.build()?, None, None, &[])?)
}

fn pendulum() -> Result<Simulation> {
    let s = double_pendulum(std::f64::consts::FRAC_PI_4)?;
    Ok(build_simulation(&s, None, None, &[])?)
}

fn dropped_prism() -> Result<Simulation> {
    let s = snelson_prism(&PrismParams {
        z0: 0.02,
        damping: 50.0,
        prestress: 300.0,
        ..Default::default()
    })?;
    let s = s.to_builder().gravity([0.0, 0.0, -9.81]).build()?;
    let ground = GroundSpec {
        point: [0.0; 3],
        normal: [0.0, 0.0, 1.0],
        model: GroundModelKind::Penalty,
        stiffness: Some(1e4),
        // No normal damping here: with it the contact force jumps by c·v_n at touchdown,
        // a true discontinuity that no tolerance-based reference can resolve to 1e-13
        // (the string damping still dissipates; the normal force has only a kink).
        damping: Some(0.0),
        mu_static: Some(0.6),
        mu_kinetic: Some(0.5),
        regularization_velocity: Some(0.1),
        stribeck_velocity: Some(0.2),
        tolerance: None,
        nodes: None,
    };
    Ok(build_simulation(&s, None, Some(&ground), &[])?)
}

fn run_one(
    scene: &Scene,
    integrator: IntegratorKind,
    parameter: f64,
    repeats: usize,
) -> Result<(tensegrity_core::dynamics::SimulationResult, f64)> {
    let mut sim = (scene.make)()?;
    sim.settings.t_end = scene.t_end;
    sim.settings.integrator = integrator;
    match integrator {
        IntegratorKind::Rk45 => {
            sim.settings.rtol = parameter;
            sim.settings.atol = parameter * 1e-2;
            sim.settings.dt = scene.t_end;
        }
        _ => sim.settings.dt = parameter,
    }
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let r = sim
            .run()
            .with_context(|| format!("{} with {integrator} ({parameter:e})", scene.name))?;
        best = best.min(r.wall_time_s);
        last = Some(r);
    }
    Ok((last.expect("at least one run"), best))
}

/// Runs every integrator over its parameter range on every scene.
pub fn measure(quick: bool) -> Result<Vec<Point>> {
    let scenes = [
        Scene {
            name: "prism-oscillating",
            t_end: 1.0,
            make: oscillating_prism,
        },
        Scene {
            name: "double-pendulum",
            t_end: 2.0,
            make: pendulum,
        },
        Scene {
            name: "prism-dropped",
            t_end: 0.5,
            make: dropped_prism,
        },
    ];
    let repeats = if quick { 1 } else { 3 };
    let dts: Vec<f64> = if quick {
        vec![4e-3, 1e-3]
    } else {
        vec![8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4]
    };
    let tols: Vec<f64> = if quick {
        vec![1e-5, 1e-8]
    } else {
        vec![1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
    };
    let mut points = Vec::new();
    for scene in &scenes {
        let (reference, _) = run_one(scene, IntegratorKind::Rk45, 1e-13, 1)?;
        let err = |r: &tensegrity_core::dynamics::SimulationResult| {
            r.final_nodes
                .iter()
                .zip(&reference.final_nodes)
                .map(|(a, b)| (a - b).norm())
                .fold(0.0, f64::max)
        };
        for integrator in [
            IntegratorKind::Rk4,
            IntegratorKind::Rk45,
            IntegratorKind::Rattle,
        ] {
            let params = if integrator == IntegratorKind::Rk45 {
                &tols
            } else {
                &dts
            };
            for &p in params {
                // RK4 is unstable on the stiff contact scene at the largest steps: skip
                // failures (blow-up) rather than abort the report.
                let Ok((r, wall)) = run_one(scene, integrator, p, repeats) else {
                    continue;
                };
                points.push(Point {
                    scene: scene.name,
                    integrator,
                    parameter: p,
                    steps: r.steps,
                    rhs_evals: r.rhs_evals,
                    error: err(&r).max(1e-16),
                    wall_time_s: wall.max(1e-9),
                });
            }
        }
    }
    Ok(points)
}

/// Runs `tensegrity bench work-precision`.
pub fn run(args: &BenchArgs) -> Result<()> {
    match &args.what {
        BenchCommand::WorkPrecision(a) => work_precision(a),
    }
}

fn work_precision(args: &WorkPrecisionArgs) -> Result<()> {
    let points = measure(args.quick)?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("creating {}", args.out.display()))?;
    let csv_path = args.out.join("work_precision.csv");
    let mut csv = String::from(
        "scene,integrator,parameter (dt [s] or rtol),steps,rhs_evals,error [m],wall_time [s]\n",
    );
    for p in &points {
        writeln!(
            csv,
            "{},{},{:e},{},{},{:e},{:e}",
            p.scene, p.integrator, p.parameter, p.steps, p.rhs_evals, p.error, p.wall_time_s
        )?;
    }
    std::fs::write(&csv_path, csv).with_context(|| format!("writing {}", csv_path.display()))?;
    let svg_path = args.out.join("work_precision.svg");
    std::fs::write(&svg_path, svg(&points))
        .with_context(|| format!("writing {}", svg_path.display()))?;
    println!(
        "{} points written to {} and {}",
        points.len(),
        csv_path.display(),
        svg_path.display()
    );
    Ok(())
}

/// A hand-written SVG: one log–log panel per scene, error (m) against wall time (s).
pub fn svg(points: &[Point]) -> String {
    let mut scenes: Vec<&str> = points.iter().map(|p| p.scene).collect();
    scenes.dedup();
    let (pw, ph, margin) = (420.0, 320.0, 60.0);
    let width = scenes.len() as f64 * (pw + margin) + margin;
    let height = ph + 2.0 * margin + 30.0;
    let colors = [
        (IntegratorKind::Rk4, "#1f77b4"),
        (IntegratorKind::Rk45, "#d62728"),
        (IntegratorKind::Rattle, "#2ca02c"),
    ];
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    for (si, scene) in scenes.iter().enumerate() {
        // Diverged runs (error above 10 cm) stay in the CSV but are not drawn.
        let pts: Vec<&Point> = points
            .iter()
            .filter(|p| p.scene == *scene && p.error < 0.1)
            .collect();
        let lx = |v: f64| v.log10();
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in &pts {
            x0 = x0.min(lx(p.wall_time_s));
            x1 = x1.max(lx(p.wall_time_s));
            y0 = y0.min(lx(p.error));
            y1 = y1.max(lx(p.error));
        }
        let (x0, x1, y0, y1) = (x0.floor(), x1.ceil(), y0.floor(), y1.ceil());
        let (x1, y1) = (x1.max(x0 + 1.0), y1.max(y0 + 1.0));
        let ox = margin + si as f64 * (pw + margin);
        let oy = margin;
        let px = |v: f64| ox + (lx(v) - x0) / (x1 - x0) * pw;
        let py = |v: f64| oy + ph - (lx(v) - y0) / (y1 - y0) * ph;
        let _ = writeln!(
            s,
            r#"<rect x="{ox}" y="{oy}" width="{pw}" height="{ph}" fill="none" stroke="black"/>"#
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="14">{scene}</text>"#,
            ox + pw / 2.0,
            oy - 10.0
        );
        let mut e = x0 as i32;
        while e as f64 <= x1 {
            let x = ox + (e as f64 - x0) / (x1 - x0) * pw;
            let _ = writeln!(
                s,
                r##"<line x1="{x}" y1="{oy}" x2="{x}" y2="{}" stroke="#ddd"/><text x="{x}" y="{}" text-anchor="middle">1e{e}</text>"##,
                oy + ph,
                oy + ph + 15.0
            );
            e += 1;
        }
        let mut e = y0 as i32;
        while e as f64 <= y1 {
            let y = oy + ph - (e as f64 - y0) / (y1 - y0) * ph;
            let _ = writeln!(
                s,
                r##"<line x1="{ox}" y1="{y}" x2="{}" y2="{y}" stroke="#ddd"/><text x="{}" y="{}" text-anchor="end">1e{e}</text>"##,
                ox + pw,
                ox - 5.0,
                y + 4.0
            );
            e += 1;
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle">integration wall time [s]</text>"#,
            ox + pw / 2.0,
            oy + ph + 35.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" text-anchor="middle" transform="rotate(-90 {} {})">max node error [m]</text>"#,
            ox - 45.0,
            oy + ph / 2.0,
            ox - 45.0,
            oy + ph / 2.0
        );
        for (ci, (integrator, color)) in colors.iter().enumerate() {
            let mut curve: Vec<&&Point> =
                pts.iter().filter(|p| p.integrator == *integrator).collect();
            curve.sort_by(|a, b| a.wall_time_s.total_cmp(&b.wall_time_s));
            if curve.is_empty() {
                continue;
            }
            let path: Vec<String> = curve
                .iter()
                .map(|p| format!("{:.2},{:.2}", px(p.wall_time_s), py(p.error)))
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{color}" stroke-width="2"/>"#,
                path.join(" ")
            );
            for p in &curve {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{:.2}" cy="{:.2}" r="3" fill="{color}"/>"#,
                    px(p.wall_time_s),
                    py(p.error)
                );
            }
            let ly = oy + 15.0 + 16.0 * ci as f64;
            let _ = writeln!(
                s,
                r#"<line x1="{}" y1="{ly}" x2="{}" y2="{ly}" stroke="{color}" stroke-width="2"/><text x="{}" y="{}">{integrator}</text>"#,
                ox + pw - 80.0,
                ox + pw - 60.0,
                ox + pw - 55.0,
                ly + 4.0
            );
        }
    }
    let _ = writeln!(s, "</svg>");
    s
}
