//! `tensegrity fig-rolling`: the wheels rolled in parallel (one thread per wheel, each a
//! [`toroid::roll`] call), their summary (the validity of each run and the impact impulse
//! per new contact against n: the §3.3.1 claim that more sides mean gentler impacts), and the
//! figure panels of the rolling figures (also `roll --svg`).

use super::request_args::choice;
use super::values;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::{defaults, RollReport, RollRequest};
use wheel_rolling::{ContactKind, FidelityChoice, RollSettings, RollingSample, WheelFrame};

/// Rolls `request` once per entry of `sides`, in parallel; the reports in the order of
/// `sides`.
pub fn parallel_series(request: &RollRequest, sides: &[usize]) -> Result<Vec<RollReport>> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = sides
            .iter()
            .map(|&n| {
                let mut r = *request;
                r.wheel.params.sides = n;
                scope.spawn(move || toroid::roll(&r))
            })
            .collect();
        handles
            .into_iter()
            .map(|h| match h.join() {
                Ok(report) => Ok(report?),
                Err(_) => Err(anyhow::anyhow!("a rolling run panicked")),
            })
            .collect()
    })
}

/// Mean of the normal impulse, tangential impulse and ω⁺/ω⁻ over a run's impacts.
fn impact_means(r: &RollReport) -> (f64, f64, f64) {
    let n = r.impact_log.len().max(1) as f64;
    let sum = r.impact_log.iter().fold((0.0, 0.0, 0.0), |acc, i| {
        let ratio = if i.omega_before != 0.0 {
            i.omega_after / i.omega_before
        } else {
            f64::NAN
        };
        (
            acc.0 + i.normal_impulse,
            acc.1 + i.tangential_impulse,
            acc.2 + ratio,
        )
    });
    (sum.0 / n, sum.1 / n, sum.2 / n)
}

/// Prints one line per wheel (model, validity, axle height, speed) and the impulse table.
pub fn print_series(runs: &[RollReport]) {
    for r in runs {
        println!(
            "n = {:>2} ({:?}, {}): mean axle height {:.4} m, oscillation {:.5} m, mean speed {:.3} m/s, airborne {:.1} %{}",
            r.sides,
            r.fidelity,
            r.contact,
            r.summary.mean_axle_height,
            r.summary.axle_height_oscillation,
            r.summary.mean_speed,
            100.0 * r.summary.airborne_fraction,
            if r.summary.valid { "" } else { "  NOT VALID" }
        );
        for w in &r.summary.warnings {
            eprintln!("warning (n = {}): {w}", r.sides);
        }
    }
    println!("\nimpact impulse per new contact (§3.3.1), means over each run's impacts:");
    println!(
        "{:>4} {:>8} {:>14} {:>18} {:>16} {:>14}",
        "n", "impacts", "normal [N s]", "tangential [N s]", "normal/m [m/s]", "omega+/omega-"
    );
    for r in runs {
        let (normal, tangential, ratio) = impact_means(r);
        println!(
            "{:>4} {:>8} {:>14.5} {:>18.5} {:>16.5} {:>14.5}",
            r.sides,
            r.summary.impacts,
            normal,
            tangential,
            normal / r.mass_kg,
            ratio
        );
    }
}

/// Arguments of `tensegrity fig-rolling`.
#[derive(clap::Args, Debug)]
pub struct FigRollingArgs {
    /// Output SVG file.
    #[arg(long, value_name = "FILE", default_value = "rolling.svg")]
    out: PathBuf,
    /// Model (auto: the cheapest valid one per wheel; with the default strings, full).
    #[arg(long, default_value = "auto", value_parser = choice::<FidelityChoice>(FidelityChoice::NAMES))]
    fidelity: FidelityChoice,
    /// Ground contact of the full model.
    #[arg(long, default_value = "penalty", value_parser = choice::<ContactKind>(ContactKind::NAMES))]
    contact: ContactKind,
    /// Slope angle.
    #[arg(long, value_parser = super::angle::parse_angle, default_value = "50deg")]
    incline: f64,
    /// Simulated time (s).
    #[arg(long, default_value_t = defaults::ROLL_T_END, value_parser = values::positive)]
    t_end: f64,
    /// Static friction coefficient μ_s (μ_k = 0.75 μ_s).
    #[arg(long, default_value_t = defaults::STATIC_FRICTION, value_parser = values::non_negative)]
    mu: f64,
    /// Normal coefficient of restitution e.
    #[arg(long, default_value_t = defaults::RESTITUTION)]
    restitution: f64,
}

/// Entry point of `tensegrity fig-rolling`: thesis Figs. 3.10 (n = 8, 12, 16, 24) and 3.11
/// (n = 8, 16) for the reference wheel with spokes + inner rings, the wheels rolled in
/// parallel, and the impact impulse per new contact against n (§3.3.1).
pub fn run_fig_rolling(args: &FigRollingArgs) -> Result<()> {
    let request = RollRequest {
        fidelity: args.fidelity,
        contact: args.contact,
        settings: RollSettings {
            incline: args.incline,
            restitution: args.restitution,
            ..RollSettings::default()
        },
        t_end: args.t_end,
        mu: args.mu,
        ..RollRequest::default()
    };
    let _progress = super::guard::rolling_series(&request, &defaults::FIG_3_10_SIDES)?;
    let runs = parallel_series(&request, &defaults::FIG_3_10_SIDES)?;
    print_series(&runs);
    let labelled: Vec<(String, &[RollingSample])> = runs
        .iter()
        .map(|r| {
            let mark = if r.summary.valid { "" } else { " (NOT VALID)" };
            let label = format!("n = {} {}{mark}", r.sides, r.fidelity.name());
            (label, r.samples.as_slice())
        })
        .collect();
    // Fig. 3.11 shows the reactions of n = 8 and 16 only
    let some = [labelled[0].clone(), labelled[2].clone()];
    write_figure(&args.out, &[axle_panel(&labelled), reaction_panel(&some)])?;
    println!("wrote {}", args.out.display());
    Ok(())
}

/// The wheel's members in the rolling plane (s, h) at one time (thesis Fig. 3.8).
pub fn frame_panel(frame: &WheelFrame, members: &[[usize; 2]]) -> Panel {
    let mut panel = Panel::new(
        format!("t = {:.3} s", frame.t),
        "along the slope s [m]",
        "above the slope h [m]",
    );
    let (lo, hi) = frame
        .nodes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    panel
        .series
        .push(Series::new("slope", vec![(lo, 0.0), (hi, 0.0)]));
    panel.series.extend(members.iter().map(|&[a, b]| {
        let (p, q) = (frame.nodes[a], frame.nodes[b]);
        Series::new("", vec![(p.y, p.z), (q.y, q.z)])
    }));
    panel
}

/// Writes figure panels side by side (SVG or PNG by the extension).
pub fn write_figure(path: &Path, panels: &[Panel]) -> Result<()> {
    Figure::new(panels.to_vec())
        .save(path)
        .with_context(|| format!("writing the figure {}", path.display()))
}

/// The empty band above the data that a legend of `entries` lines needs (fraction of the
/// data's span).
fn legend_band(entries: usize) -> f64 {
    0.1 + 0.1 * entries as f64
}

pub fn axle_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "axle height above the incline (Fig. 3.10)",
        "time [s]",
        "axle height above the slope [m]",
    )
    .legend_above(legend_band(runs.len()));
    panel.series = runs
        .iter()
        .map(|(label, samples)| {
            Series::new(label.clone(), samples.iter().map(|s| (s.t, s.h)).collect())
        })
        .collect();
    panel
}

pub fn reaction_panel(runs: &[(String, &[RollingSample])]) -> Panel {
    let mut panel = Panel::new(
        "contact reaction (Fig. 3.11)",
        "time [s]",
        "normal force [N]",
    )
    .legend_above(legend_band(runs.len()));
    panel.series = runs
        .iter()
        .map(|(label, samples)| {
            Series::new(
                label.clone(),
                samples.iter().map(|s| (s.t, s.normal)).collect(),
            )
        })
        .collect();
    panel
}
