//! The toroid-wheel figures of chapter 3:
//!
//! - Fig. 3.3: the reference wheel (n = 8) with the stabilising options (1, 2), (1, 3),
//!   (2, 3), isometric ([`toroid::WheelSpec::build`]);
//! - Fig. 3.8: the n = 8 wheel rolling down 50° at three instants ([`toroid::roll`]), drawn in
//!   the frame of the incline: the wheel's (y, z) rotated by −θ about its axle at (s, h),
//!   θ(t) = ∫ω dt by the trapezoidal rule;
//! - Fig. 3.9: wheels of complexity 6, 24, 100, side view;
//! - Figs. 3.10–3.11: the axle height above the incline less its mean, and the normal contact
//!   force, of the n = 8, 12, 16, 24 wheels ([`toroid::rolling_series`] with the default
//!   request, run once for both figures);
//! - Fig. 3.13: F_f/F_e against σ = R_i/R_o, one curve per ε (a `tipover` sweep over real
//!   wheels; eq. 3.29 gives F_f/F_e = −(σ + ε)/(1 − σ)).
//!
//! With `quick` the rolling runs are shorter and use the reduced rigid model. A rolling run
//! whose net normal force goes negative (the wheel would leave the slope: outside the
//! model's assumptions) is flagged in the figure's title and by a [`crate::Warning`].

use crate::draw::{drawing_figure, structure_panel, Group, View, BLUE, GREY, RED};
use crate::driver::Context as Ctx;
use crate::error::Result;
use nalgebra::Vector3;
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::{FidelityChoice, RollReport, RollRequest, Stabilize, Toroid, WheelSpec};
use wheel_rolling::RollingSample;

/// Bars blue, strings red.
fn wheel_groups(t: &Toroid) -> [Group; 2] {
    let s = &t.structure;
    [
        Group::new("bars", BLUE, s.bars().iter().map(|b| b.nodes).collect()),
        Group::new(
            "strings",
            RED,
            s.strings().iter().map(|m| m.nodes).collect(),
        ),
    ]
}

fn wheel(sides: usize, stabilize: Stabilize) -> Result<Toroid> {
    let mut w = WheelSpec::default();
    w.params.sides = sides;
    w.stabilize = stabilize;
    Ok(w.build()?)
}

/// Fig. 3.3: the reference wheel (n = 8) with options (1, 2), (1, 3) and (2, 3).
pub fn fig_3_3(_: &Ctx) -> Result<Figure> {
    let options = ["spokes,inner", "spokes,outer", "inner,outer"];
    let panels = options
        .iter()
        .map(|o| {
            let t = wheel(8, o.parse()?)?;
            let nodes = t.structure.nodes();
            Ok(structure_panel(
                o.to_string(),
                View::Iso,
                nodes,
                &wheel_groups(&t),
            ))
        })
        .collect::<Result<Vec<Panel>>>()?;
    Ok(drawing_figure(panels))
}

/// Fig. 3.9: wheels of complexity 6, 24 and 100 (side view).
pub fn fig_3_9(_: &Ctx) -> Result<Figure> {
    let panels = [6, 24, 100]
        .iter()
        .map(|&n| {
            let t = wheel(n, Stabilize::SPOKES_INNER)?;
            let title = format!("n = {n}");
            Ok(structure_panel(
                title,
                View::Side,
                t.structure.nodes(),
                &wheel_groups(&t),
            ))
        })
        .collect::<Result<Vec<Panel>>>()?;
    Ok(drawing_figure(panels))
}

/// The default rolling request, shorter and on the reduced rigid model with `quick`.
fn rolling_request(ctx: &Ctx, t_end: f64) -> RollRequest {
    let d = RollRequest::default();
    if ctx.quick() {
        RollRequest {
            t_end,
            fidelity: FidelityChoice::Rigid,
            ..d
        }
    } else {
        d
    }
}

/// The rotation angle θ(t) = ∫ω dt of the samples (trapezoidal rule).
fn angles(samples: &[RollingSample]) -> Vec<f64> {
    let mut theta = vec![0.0; samples.len()];
    for k in 1..samples.len() {
        let (a, b) = (&samples[k - 1], &samples[k]);
        theta[k] = theta[k - 1] + 0.5 * (a.omega + b.omega) * (b.t - a.t);
    }
    theta
}

/// Fig. 3.8: the n = 8 wheel at t = 0, 1.5 and 3 s (0, 0.25, 0.5 s with `quick`), in the
/// frame of the incline: the wheel's (y, z) rotated by −θ about its axle at (s, h).
pub fn fig_3_8(ctx: &Ctx) -> Result<Figure> {
    let times = if ctx.quick() {
        [0.0, 0.25, 0.5]
    } else {
        [0.0, 1.5, 3.0]
    };
    let mut req = rolling_request(ctx, times[2]);
    req.wheel.params.sides = 8;
    let report = toroid::roll(&req)?;
    let flagged = flag_lift_off(ctx, "3.8", &[&report]);
    let t = req.wheel.build()?;
    let theta = angles(&report.samples);
    let mut panels = Vec::new();
    for &time in &times {
        let k = report
            .samples
            .iter()
            .position(|s| s.t >= time - 1e-9)
            .unwrap_or(report.samples.len() - 1);
        let (s, th) = (&report.samples[k], theta[k]);
        let (sin, cos) = (-th).sin_cos();
        let moved: Vec<Vector3<f64>> = t
            .structure
            .nodes()
            .iter()
            .map(|p| {
                let (y, z) = (p.y * cos - p.z * sin, p.y * sin + p.z * cos);
                Vector3::new(p.x, s.s + y, s.h + z)
            })
            .collect();
        let title = format!("t = {:.2} s ({}){}", s.t, fidelity(&report), note(flagged));
        let panel = structure_panel(title, View::Side, &moved, &wheel_groups(&t));
        let r = t.params.outer_radius;
        panels.push(
            panel.series(
                Series::new("incline", vec![(s.s - 1.3 * r, 0.0), (s.s + 1.3 * r, 0.0)])
                    .with_color(GREY),
            ),
        );
    }
    Ok(drawing_figure(panels))
}

/// Flags the runs whose net normal force went negative: the model keeps the wheel on the
/// slope where the real one would leave it, so the curves there are outside its assumptions.
fn flag_lift_off(ctx: &Ctx, number: &'static str, runs: &[&RollReport]) -> bool {
    let lifted: Vec<String> = runs
        .iter()
        .filter(|r| r.summary.min_normal_force < 0.0)
        .map(|r| format!("n = {} (min {:.1} N)", r.sides, r.summary.min_normal_force))
        .collect();
    if !lifted.is_empty() {
        ctx.warn(
            number,
            format!(
                "the {}'s net normal force goes negative for {}: the wheel would leave the \
                 slope there, outside the model's assumptions",
                fidelity(runs[0]),
                lifted.join(", ")
            ),
        );
    }
    !lifted.is_empty()
}

/// The title's note when a run is outside its model's assumptions.
fn note(flagged: bool) -> &'static str {
    if flagged {
        " — lifts off: see warning"
    } else {
        ""
    }
}

fn fidelity(r: &RollReport) -> &'static str {
    match r.fidelity {
        wheel_rolling::Fidelity::Rigid => "rigid model",
        wheel_rolling::Fidelity::Full => "full model",
    }
}

/// The four wheels of Fig. 3.10 (n = 8, 12, 16, 24), 50°, default request (2 s, rigid model
/// with `quick`), run once for Figs. 3.10 and 3.11.
fn rolling_runs(ctx: &Ctx) -> Result<&[RollReport]> {
    ctx.rolling(|| {
        let req = rolling_request(ctx, 2.0);
        toroid::rolling_series(&req, &toroid::defaults::FIG_3_10_SIDES)
    })
}

/// Fig. 3.10: the axle's height above the incline, less its mean, against time.
pub fn fig_3_10(ctx: &Ctx) -> Result<Figure> {
    let runs = rolling_runs(ctx)?;
    let flagged = flag_lift_off(ctx, "3.10", &runs.iter().collect::<Vec<_>>());
    let mut panel = Panel::new(
        format!("axle height, 50° ({}){}", fidelity(&runs[0]), note(flagged)),
        "time [s]",
        "axle height − mean [m]",
    );
    for r in runs {
        let mean = r.samples.iter().map(|s| s.h).sum::<f64>() / r.samples.len() as f64;
        let pts = r.samples.iter().map(|s| (s.t, s.h - mean)).collect();
        panel = panel.series(Series::new(format!("n = {}", r.sides), pts));
    }
    Ok(Figure::new(vec![panel]))
}

/// Fig. 3.11: the normal contact force of the n = 8 and n = 16 wheels against time.
pub fn fig_3_11(ctx: &Ctx) -> Result<Figure> {
    let all = rolling_runs(ctx)?;
    let runs: Vec<&RollReport> = all.iter().filter(|r| [8, 16].contains(&r.sides)).collect();
    let flagged = flag_lift_off(ctx, "3.11", &runs);
    let mut panel = Panel::new(
        format!(
            "contact reaction, 50° ({}){}",
            fidelity(&all[0]),
            note(flagged)
        ),
        "time [s]",
        "normal force [N]",
    );
    for r in runs {
        let pts = r.samples.iter().map(|s| (s.t, s.normal)).collect();
        panel = panel.series(Series::new(format!("n = {}", r.sides), pts));
    }
    Ok(Figure::new(vec![panel]))
}

/// Fig. 3.13: F_f/F_e against σ, one curve per ε — a `tipover` sweep over real wheels
/// (R_i = σ R_o, t = ε T of the reference geometry), its CSV kept beside the figure.
pub fn fig_3_13(ctx: &Ctx) -> Result<Figure> {
    let (sigma_step, eps) = if ctx.quick() {
        ("0.1", "[0.25, 0.5, 0.75, 1.0]")
    } else {
        ("0.025", "[0.1, 0.25, 0.5, 0.75, 1.0]")
    };
    let spec = format!(
        "study = \"tipover\"\n[axes]\nepsilon = {eps}\n\
         sigma = {{ from = 0.1, to = 0.9, step = {sigma_step} }}\n\
         [output]\ncolumns = [\"normalized_friction\"]\n"
    );
    let curves = ctx.sweep("fig_3_13", &spec, "sigma", "normalized_friction", "epsilon")?;
    let mut panel = Panel::new(
        "friction at the tip-over threshold (Fig. 3.13)",
        "σ = R_i/R_o",
        "F_f/F_e",
    );
    for (eps, pts) in curves {
        panel = panel.series(Series::new(format!("ε = {eps}"), pts));
    }
    Ok(Figure::new(vec![panel]))
}
