//! The toroid-wheel figures of chapter 3, each with its data ([`crate::data`]):
//!
//! - Fig. 3.1: the six nodes of prism 0 (`toroid::prism_nodes`, n6 = [0, R_m tan(π/n), −R_m]
//!   as corrected by ERRATA 3.1), labelled;
//! - Fig. 3.2: the seven parameters on the reference wheel: the circles R_o, R_m, R_i in the
//!   side view, prism 0 from above with the treads T, t and the offset D;
//! - Fig. 3.3: the reference wheel (n = 8) with the stabilising options (1, 2), (1, 3),
//!   (2, 3), isometric ([`toroid::WheelSpec::build`]), its prestress design's member forces
//!   and margin in the data;
//! - Fig. 3.8: the n = 8 wheel rolling down 50° at three instants, drawn from the run's own
//!   node frames ([`toroid::roll_with_frames`]) in the incline's frame (s along the slope,
//!   h above it), so a node in contact is on the slope, less the reported penetration;
//! - Fig. 3.9: wheels of complexity 6, 24, 100, side view, with `scale_with_n`
//!   (D = 0.8/n, [`toroid::WheelSpec::geometry`]): every one prestressable, its margin in
//!   the data;
//! - Figs. 3.10–3.11: the axle height above the incline less its mean, and the normal contact
//!   force, of the n = 8, 12, 16, 24 wheels ([`toroid::rolling_series`] with the default
//!   request, run once for both figures);
//! - Fig. 3.13: F_f/F_e against σ = R_i/R_o, one curve per ε (a `tipover` sweep over real
//!   wheels; eq. 3.29 gives F_f/F_e = −(σ + ε)/(1 − σ)).
//!
//! With `quick` the rolling runs are shorter and use the reduced rigid model. A rolling run
//! whose net normal force goes negative (the wheel would leave the slope: outside the
//! model's assumptions) is flagged in the figure's title and by a [`crate::Warning`].

use crate::context::Context as Ctx;
use crate::data::{Drawn, StructureFigure};
use crate::draw::{Group, View, BLUE, GREY, RED};
use crate::error::Result;
use tensegrity_core::warning::LiftOff;
use tensegrity_io::figure::{Figure, Panel, Series};
use tensegrity_io::figure_data::Value;
use toroid::{
    FidelityChoice, RollReport, RollRequest, Stabilize, Toroid, ToroidRequest, WheelSpec,
};

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

/// Member `k` of group `g` of [`wheel_groups`] in a list of forces, bars then strings.
fn bar_then_string(forces: &[f64], bars: usize, g: usize, k: usize) -> Option<f64> {
    forces.get(if g == 0 { k } else { bars + k }).copied()
}

/// A wheel drawn with its prestress design: the report (margin, design forces) of `wheel`.
fn designed(wheel: WheelSpec) -> Result<(Toroid, toroid::ToroidReport)> {
    let report = toroid::toroid_report(&ToroidRequest {
        wheel,
        ..ToroidRequest::default()
    })?;
    Ok((wheel.build()?, report))
}

/// The data columns of a designed wheel.
const WHEEL_COLUMNS: [(&str, &str); 5] = [
    ("sides", ""),
    ("offset", "m"),
    ("scale_with_n", ""),
    ("prestressable", ""),
    ("prestress_margin", ""),
];

/// Adds a designed wheel as a panel: members with their design forces (smallest string
/// tension [`toroid::defaults::DESIGN_MIN_TENSION`]), the margin in the data.
fn wheel_panel(fig: &mut StructureFigure, title: &str, view: View, wheel: WheelSpec) -> Result<()> {
    let (t, r) = designed(wheel)?;
    let forces = r.prestress_member_force.clone().unwrap_or_default();
    let bars = r.bars;
    let extra: Vec<Value> = vec![
        t.params.sides.into(),
        t.params.offset.into(),
        wheel.scale_with_n.into(),
        r.prestressable.into(),
        r.prestress_margin.into(),
    ];
    fig.add(
        title,
        view,
        t.structure.nodes(),
        &wheel_groups(&t),
        &|g, k, _| bar_then_string(&forces, bars, g, k),
        extra,
    );
    Ok(())
}

/// Fig. 3.1: the six nodes of prism 0 (n = 8 reference wheel, n6 as corrected by ERRATA
/// 3.1), isometric and side (y–z), each node a labelled marker.
pub fn fig_3_1(_: &Ctx) -> Result<Drawn> {
    let p = toroid::ToroidParams::REFERENCE;
    let t = toroid::build_prism(&p, toroid::defaults::BAR_DENSITY)?;
    let nodes = t.structure.nodes();
    let mut fig = StructureFigure::new(&[]);
    fig.node_labels = (1..=nodes.len()).map(|i| format!("n{i}")).collect();
    for (view, title) in [
        (View::Iso, "3-bar prism, isometric"),
        (View::Side, "side (y–z)"),
    ] {
        fig.add(
            title,
            view,
            nodes,
            &wheel_groups(&t),
            &crate::data::no_forces,
            vec![],
        );
        let panel = fig.panels.last_mut().expect("just added");
        for (i, n) in nodes.iter().enumerate() {
            let label = format!("n{}", i + 1);
            let point = view.project(n);
            // a marker: a polyline of one point twice (no line to draw)
            let s = Series::new(label, vec![point, point]).with_markers();
            panel.series.push(s);
        }
    }
    Ok(fig.finish())
}

/// Fig. 3.2: the toroid's parameters on the reference wheel (spokes + inner rings): the side
/// (y–z) with the circles R_o, R_m, R_i, and prism 0 from above (y–x) with the tread widths
/// T, t and the offset D; the seven parameters in the data.
pub fn fig_3_2(_: &Ctx) -> Result<Drawn> {
    let w = WheelSpec::default();
    let t = w.build()?;
    let p = t.params;
    let extra: Vec<Value> = vec![
        p.sides.into(),
        p.outer_tread.into(),
        p.inner_tread.into(),
        p.offset.into(),
        p.outer_radius.into(),
        p.inner_radius.into(),
        p.rim_radius.into(),
    ];
    let mut fig = StructureFigure::new(&[
        ("sides", ""),
        ("outer_tread", "m"),
        ("inner_tread", "m"),
        ("offset", "m"),
        ("outer_radius", "m"),
        ("inner_radius", "m"),
        ("rim_radius", "m"),
    ]);
    let groups = wheel_groups(&t);
    let nodes = t.structure.nodes();
    let none = &crate::data::no_forces;
    fig.add(
        "side: $R_o$, $R_m$, $R_i$",
        View::Side,
        nodes,
        &groups,
        none,
        extra.clone(),
    );
    let circle = |r: f64| -> Vec<(f64, f64)> {
        (0..=120)
            .map(|k| {
                let a = 2.0 * std::f64::consts::PI * k as f64 / 120.0;
                (r * a.cos(), r * a.sin())
            })
            .collect()
    };
    let side = fig.panels.last_mut().expect("just added");
    for (name, r, rgb) in [
        ("$R_o$", p.outer_radius, GREY),
        ("$R_m$", p.rim_radius, (0x2c, 0xa0, 0x2c)),
        ("$R_i$", p.inner_radius, (0x94, 0x67, 0xbd)),
    ] {
        let label = format!("{name} = {r} m");
        side.series
            .push(Series::new(label, circle(r)).with_color(rgb));
    }
    // one prism from above: n1, n2 at x = ±T/2; n4, n5 at x = ∓t/2, y = ∓D
    let prism = toroid::build_prism(&p, w.bar_density)?;
    let title = "prism 0 from above: T, t, D";
    fig.add(
        title,
        View::Top,
        prism.structure.nodes(),
        &wheel_groups(&prism),
        none,
        extra,
    );
    Ok(fig.finish())
}

/// Fig. 3.3: the reference wheel (n = 8) with options (1, 2), (1, 3) and (2, 3), with the
/// prestress design's member forces in the data.
pub fn fig_3_3(_: &Ctx) -> Result<Drawn> {
    let mut fig = StructureFigure::new(&WHEEL_COLUMNS);
    for o in ["spokes,inner", "spokes,outer", "inner,outer"] {
        let wheel = WheelSpec {
            stabilize: o.parse::<Stabilize>()?,
            ..WheelSpec::default()
        };
        wheel_panel(&mut fig, o, View::Iso, wheel)?;
    }
    Ok(fig.finish())
}

/// Fig. 3.9: wheels of complexity 6, 24 and 100 (side view), with `scale_with_n`: the tread
/// offset D = 0.8/n ([`WheelSpec::geometry`]), so that every wheel is prestressable (the
/// reference D = 0.1 at n = 100 is not: margin 0); margins and design forces in the data.
pub fn fig_3_9(_: &Ctx) -> Result<Drawn> {
    let mut fig = StructureFigure::new(&WHEEL_COLUMNS);
    for n in [6, 24, 100] {
        let wheel = WheelSpec {
            scale_with_n: true,
            ..WheelSpec::with_sides(n)
        };
        let d = wheel.geometry().offset;
        wheel_panel(
            &mut fig,
            &format!("n = {n}, D = 0.8/n = {d:.3} m"),
            View::Side,
            wheel,
        )?;
    }
    Ok(fig.finish())
}

/// The default rolling request at half the full model's default step (there the n = 16 and
/// 24 wheels' first impact and impact count converge, as `fig-rolling --dt 1.25e-4`), shorter
/// and on the reduced rigid model with `quick`.
fn rolling_request(ctx: &Ctx, t_end: f64) -> RollRequest {
    rolling_request_of(ctx.quick(), t_end)
}

/// [`rolling_request`] of a context that is `quick` or not.
fn rolling_request_of(quick: bool, t_end: f64) -> RollRequest {
    let d = RollRequest::default();
    if quick {
        RollRequest {
            t_end,
            fidelity: FidelityChoice::Rigid,
            ..d
        }
    } else {
        let mut r = d;
        r.settings.dt = Some(0.5 * d.spec().full_dt());
        r
    }
}

/// Fig. 3.8: the n = 8 wheel at t = 0, 1.5 and 3 s (0, 0.25, 0.5 s with `quick`), from the
/// run's own node frames in the incline's frame ([`fig_3_8_of`]).
pub fn fig_3_8(ctx: &Ctx) -> Result<Drawn> {
    let times = fig_3_8_times(ctx.quick());
    let mut req = rolling_request(ctx, times[2]);
    req.wheel.params.sides = 8;
    fig_3_8_of(ctx, &req, &times)
}

/// Fig. 3.8's three instants (s).
fn fig_3_8_times(quick: bool) -> [f64; 3] {
    if quick {
        [0.0, 0.25, 0.5]
    } else {
        [0.0, 1.5, 3.0]
    }
}

/// The frames of one `roll` run at `times`, as the run placed the wheel
/// ([`toroid::roll_with_frames`]: the full model's nodes, or the rigid wheel placed by its
/// pose): y = s along the slope, z = h above it, so a node in contact is at h = 0 (less the
/// reported penetration). The data: every node at every frame, with the frame's time, the
/// model and the run's `max_penetration`; the member forces of the full model.
pub fn fig_3_8_of(ctx: &Ctx, req: &RollRequest, times: &[f64]) -> Result<Drawn> {
    let report = toroid::roll_with_frames(req, times)?;
    let flagged = flag_lift_off(ctx, "3.8", &[&report]);
    let t = req.wheel.build()?;
    let mut fig = StructureFigure::new(&[("t", "s"), ("fidelity", ""), ("max_penetration", "m")]);
    let bars = t.structure.bars().len();
    let r = t.params.outer_radius;
    for frame in &report.frames {
        let mut frame = frame.clone();
        if report.fidelity == wheel_rolling::Fidelity::Rigid {
            if let Some(sample) = report.samples.iter().find(|s| s.t == frame.t) {
                snap_to_contact(&mut frame, sample);
            }
        }
        let title = format!(
            "t = {:.2} s ({}){}",
            frame.t,
            fidelity(&report),
            note(flagged)
        );
        let extra: Vec<Value> = vec![
            frame.t.into(),
            fidelity(&report).into(),
            report.summary.max_penetration.into(),
        ];
        let forces = &frame.member_forces;
        fig.add(
            &title,
            View::Side,
            &frame.nodes,
            &wheel_groups(&t),
            &|g, k, _| bar_then_string(forces, bars, g, k),
            extra,
        );
        let s = frame.nodes.iter().map(|p| p.y).sum::<f64>() / frame.nodes.len() as f64;
        let ground = Series::new("incline", vec![(s - 1.3 * r, 0.0), (s + 1.3 * r, 0.0)]);
        let panel = fig.panels.last_mut().expect("just added");
        panel.series.push(ground.with_color(GREY));
    }
    let mut drawn = fig.finish();
    drawn.figure = mark(drawn.figure, flagged, &[&report]);
    Ok(drawn)
}

/// The rigid model's frame turned onto its contact: the frame places the wheel by the turn
/// ψ = ∫ω dt summed over the samples (trapezoidal rule), whose quadrature error leaves the
/// contact vertex up to ~10⁻⁸ m off the slope; in contact (normal force > 0) the model's own
/// pose has the contact pair at (`pivot`, 0), so the wheel is turned about its hub by the
/// small angle that puts the vertex nearest to it there (skipped if that angle is not small).
fn snap_to_contact(frame: &mut wheel_rolling::WheelFrame, sample: &wheel_rolling::RollingSample) {
    if sample.normal <= 0.0 {
        return;
    }
    let hub = (sample.s, sample.h);
    let target = (sample.pivot - hub.0, -hub.1);
    let nearest = frame.nodes.iter().min_by(|a, b| {
        let d = |p: &&nalgebra::Vector3<f64>| (p.y - sample.pivot).hypot(p.z);
        d(a).total_cmp(&d(b))
    });
    let Some(c) = nearest.map(|p| (p.y - hub.0, p.z - hub.1)) else {
        return;
    };
    let delta = target.1.atan2(target.0) - c.1.atan2(c.0);
    let delta = (delta + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    if delta.abs() > 1e-4 {
        return;
    }
    let (sin, cos) = delta.sin_cos();
    for p in &mut frame.nodes {
        let (y, z) = (p.y - hub.0, p.z - hub.1);
        p.y = hub.0 + y * cos - z * sin;
        p.z = hub.1 + y * sin + z * cos;
    }
}

/// Flags the runs whose net normal force went negative (the model keeps the wheel on the
/// slope where the real one would leave it, so the curves there are outside its assumptions),
/// and else the runs not valid for another reason (each warning of theirs, `in_run`): a
/// figure never draws a run that is not valid without a word.
fn flag_lift_off(ctx: &Ctx, number: &'static str, runs: &[&RollReport]) -> Flag {
    let lifted: Vec<LiftOff> = runs
        .iter()
        .filter(|r| r.summary.min_normal_force < 0.0)
        .map(|r| LiftOff {
            sides: r.sides,
            min_normal: r.summary.min_normal_force,
        })
        .collect();
    if !lifted.is_empty() {
        let model = fidelity(runs[0]).to_string();
        ctx.warn(
            number,
            tensegrity_core::Warning::LiftOff {
                model,
                runs: lifted,
            },
        );
        return Flag::LiftOff;
    }
    // a run outside its assumptions or not converged is drawn, and said so
    let mut flag = Flag::None;
    for r in runs.iter().filter(|r| !r.summary.valid) {
        flag = Flag::Invalid;
        for w in &r.summary.warnings {
            ctx.warn(number, w.clone().in_run(r.sides, fidelity(r).to_string()));
        }
    }
    flag
}

/// What a figure's runs were flagged for ([`flag_lift_off`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Flag {
    /// Every run valid.
    None,
    /// A run's ground pulled.
    LiftOff,
    /// A run not valid for another reason (e.g. not converged).
    Invalid,
}

/// `figure` marked ([`tensegrity_io::figure::Figure::mark_invalid`]) when its runs were
/// flagged: `lift_off`, or the first warning of the first run not valid (`n = 8: …`).
fn mark(figure: Figure, flag: Flag, runs: &[&RollReport]) -> Figure {
    match flag {
        Flag::None => figure,
        Flag::LiftOff => figure.mark_invalid("lift_off (the model holds the wheel on the slope)"),
        Flag::Invalid => {
            let warnings: Vec<tensegrity_core::Warning> = runs
                .iter()
                .filter(|r| !r.summary.valid)
                .flat_map(|r| {
                    let run = fidelity(r);
                    (r.summary.warnings.iter()).map(move |w| w.clone().in_run(r.sides, run))
                })
                .collect();
            figure.mark_invalid(crate::warning::invalid_reason(&warnings))
        }
    }
}

/// The title's note when a run is outside its model's assumptions or not converged.
fn note(flag: Flag) -> &'static str {
    match flag {
        Flag::None => "",
        Flag::LiftOff => " — lifts off: see warning",
        Flag::Invalid => " — a run is not valid: see warnings",
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
pub fn fig_3_10(ctx: &Ctx) -> Result<Drawn> {
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
    let figure = mark(
        Figure::new(vec![panel]),
        flagged,
        &runs.iter().collect::<Vec<_>>(),
    );
    Ok(Drawn::plot(
        figure,
        ("t", "s"),
        ("axle_height_minus_mean", "m"),
    ))
}

/// Fig. 3.11: the normal contact force of the n = 8 and n = 16 wheels against time.
pub fn fig_3_11(ctx: &Ctx) -> Result<Drawn> {
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
    for r in &runs {
        let pts = r.samples.iter().map(|s| (s.t, s.normal)).collect();
        panel = panel.series(Series::new(format!("n = {}", r.sides), pts));
    }
    Ok(Drawn::plot(
        mark(Figure::new(vec![panel]), flagged, &runs),
        ("t", "s"),
        ("normal_force", "N"),
    ))
}

/// Fig. 3.13: F_f/F_e against σ, one curve per ε — a `tipover` sweep over real wheels
/// (R_i = σ R_o, t = ε T of the reference geometry), its CSV kept beside the figure.
pub fn fig_3_13(ctx: &Ctx) -> Result<Drawn> {
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
        "σ = $R_i/R_o$ [–]",
        "$F_f/F_e$ [–]",
    );
    for (eps, pts) in curves {
        panel = panel.series(Series::new(format!("ε = {eps}"), pts));
    }
    Ok(Drawn::plot(
        Figure::new(vec![panel]),
        ("sigma", "1"),
        ("normalized_friction", "1"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_figure_of_flagged_runs_is_marked_and_of_valid_runs_not() {
        let mut r = toroid::roll(&RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 0.01,
            ..RollRequest::with_sides(8)
        })
        .unwrap();
        let fig = || Figure::new(vec![Panel::new("t", "x", "y")]);
        assert!(mark(fig(), Flag::None, &[&r]).invalid.is_none());
        let lifted = mark(fig(), Flag::LiftOff, &[&r]).invalid.unwrap();
        assert!(lifted.starts_with("lift_off"), "{lifted}");
        r.summary.valid = false;
        r.summary.warnings = vec![tensegrity_core::Warning::RimFreeBody];
        let invalid = mark(fig(), Flag::Invalid, &[&r]).invalid;
        assert_eq!(invalid.as_deref(), Some("n = 8: rim_free_body"));
    }
}
