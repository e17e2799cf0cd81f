//! The rolling figures of the toroid wheel: the `fig_rolling` study (thesis Figs. 3.10 and
//! 3.11 with valid models, [`fig_rolling`]) and the panels of a single `roll` run
//! ([`roll_figure`]).
//!
//! [`fig_rolling`] rolls the reference wheel (spokes + inner rings) with n = 8, 12, 16 and 24
//! sides ([`toroid::defaults::FIG_3_10_SIDES`]) down the incline of a [`FigRollingRequest`],
//! one [`toroid::roll`] per wheel on its own thread; [`FigRolling::figure`] draws the axle
//! height above the slope of all four (Fig. 3.10) and the normal contact reaction of n = 8 and
//! 16 (Fig. 3.11), each curve labelled with the model that ran and `NOT VALID` when its
//! validity checks failed; [`FigRolling::impacts`] gives the impulse per new contact (the
//! §3.3.1 claim: more sides, gentler impacts) as means over each run's impact log.
//!
//! [`roll_figure`] draws one run: the wheel's members in the rolling plane (s along the slope,
//! h above it) at chosen times (thesis Fig. 3.8, from the run's node frames), or its axle
//! height and reaction against time.

use crate::error::{FigureError, Result};
use serde::{Deserialize, Serialize};
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_derive::Params;
use tensegrity_io::figure::{Figure, Panel, Series};
use toroid::{defaults, RollReport, RollRequest};
use wheel_rolling::{ContactKind, FidelityChoice, RollSettings, RollingSample, WheelFrame};

/// The `fig_rolling` study: how the four wheels roll. Its serde form is flat, every field
/// named as the command's flag in snake_case: `{"fidelity": "rigid", "t_end": 2}`.
///
/// ```
/// use tensegrity_core::request::Request;
/// use tensegrity_figures::rolling::FigRollingRequest;
/// let r = FigRollingRequest::from_values([("incline", serde_json::json!("30deg"))]).unwrap();
/// assert!((r.roll_request(8).settings.incline - 30f64.to_radians()).abs() < 1e-15);
/// assert_eq!(r.roll_request(12).wheel.params.sides, 12);
/// let e = FigRollingRequest::from_values([("restitution", serde_json::json!(2))]).unwrap_err();
/// assert_eq!(e.name, "restitution");
/// // a step for both models, as roll's --dt (the full model's default halved)
/// let fine = FigRollingRequest::from_values([("dt", serde_json::json!(1.25e-4))]).unwrap();
/// assert_eq!(fine.roll_request(16).spec().full_dt(), 1.25e-4);
/// assert_eq!(FigRollingRequest::default().roll_request(16).spec().full_dt(), 2.5e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct FigRollingRequest {
    /// The model: `rigid`, `full` or `auto` (the cheapest valid one per wheel).
    #[param(choice = FidelityChoice::NAMES, help = "Model (auto: the cheapest valid one per wheel; with the default strings, full)")]
    pub fidelity: FidelityChoice,
    /// Ground contact of the full model: `penalty` or `thesis`.
    #[param(choice = ContactKind::NAMES, help = "Ground contact of the full model")]
    pub contact: ContactKind,
    /// Slope angle (rad; reads `50deg`, `pi/4`, …).
    #[serde(with = "tensegrity_core::angle::serde_angle")]
    #[param(angle, help = wheel_rolling::settings::help::INCLINE, rule = HalfOpen(0.0, std::f64::consts::FRAC_PI_2))]
    pub incline: f64,
    /// Simulated time (s).
    #[param(number, unit = "s", help = "Simulated time", positive)]
    pub t_end: f64,
    /// Static friction coefficient μ_s; μ_k = 0.75 μ_s.
    #[param(
        number,
        help = "Static friction coefficient μ_s (μ_k = 0.75 μ_s)",
        non_negative
    )]
    pub mu: f64,
    /// Normal coefficient of restitution e of an impact, in [0, 1].
    #[param(number, help = wheel_rolling::settings::help::RESTITUTION, rule = Closed(0.0, 1.0))]
    pub restitution: f64,
    /// Integration step of both models (s); unset: each model's default, as `roll`'s `dt`.
    /// Half the full model's default (`1.25e-4`) makes the n = 16 and 24 wheels' check
    /// converge (their first impact and impact count move at the default step).
    #[param(
        number,
        unit = "s",
        help = "Integration step of both models (unset: each model's default, as roll's dt; 1.25e-4 makes the full n = 16 and 24 runs converge)",
        positive,
        optional
    )]
    pub dt: Option<f64>,
    /// Ensemble size K per wheel: with K ≥ 2, K copies from perturbed starting poses
    /// ([`wheel_rolling::ensemble`]) and one run of the other model; the figure draws the
    /// copies' mean axle height and its 95 % band instead of the single run, and the
    /// output states where the spread exceeds the difference between the models. 0: none.
    #[param(
        count,
        help = "Copies per wheel from perturbed starting poses (K >= 2): draws their mean and 95 % band, and states where the spread exceeds the difference between the models"
    )]
    pub ensemble: usize,
}

impl Default for FigRollingRequest {
    /// The `roll` defaults: `auto`, penalty contact, 50°, [`defaults::ROLL_T_END`],
    /// μ_s = [`defaults::STATIC_FRICTION`], e = [`defaults::RESTITUTION`].
    fn default() -> Self {
        let roll = RollRequest::default();
        Self {
            fidelity: roll.fidelity,
            contact: roll.contact,
            incline: roll.settings.incline,
            t_end: defaults::ROLL_T_END,
            mu: defaults::STATIC_FRICTION,
            restitution: defaults::RESTITUTION,
            dt: None,
            ensemble: 0,
        }
    }
}

impl Request for FigRollingRequest {
    const NAME: &'static str = "fig_rolling";

    /// Finite numbers (a non-finite number set in code serialises as `null`).
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        wheel_rolling::settings::finite(&[
            ("incline", self.incline),
            ("t_end", self.t_end),
            ("mu", self.mu),
            ("restitution", self.restitution),
            ("dt", self.dt.unwrap_or(1.0)),
        ])
    }
}

impl FigRollingRequest {
    /// The wheel sizes rolled: n = 8, 12, 16, 24.
    pub const SIDES: [usize; 4] = defaults::FIG_3_10_SIDES;

    /// The `roll` request of the reference wheel with `sides` sides under these settings.
    pub fn roll_request(&self, sides: usize) -> RollRequest {
        let mut r = RollRequest {
            fidelity: self.fidelity,
            contact: self.contact,
            settings: RollSettings {
                incline: self.incline,
                restitution: self.restitution,
                dt: self.dt,
                ..RollSettings::default()
            },
            t_end: self.t_end,
            mu: self.mu,
            ensemble: self.ensemble,
            ..RollRequest::default()
        };
        r.wheel.params.sides = sides;
        r
    }
}

/// The four rolled wheels of [`fig_rolling`], in the order of [`FigRollingRequest::SIDES`].
#[derive(Debug, Clone)]
pub struct FigRolling {
    /// One report per wheel.
    pub runs: Vec<RollReport>,
    /// The wheels re-run at a finer step by [`fig_rolling_within`], each once.
    pub refined: Vec<Refined>,
}

/// A wheel re-run at half its step because its first run only failed to converge
/// ([`fig_rolling_within`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Refined {
    /// The wheel's sides n.
    pub sides: usize,
    /// The step of the first run (s).
    pub from_dt: f64,
    /// The step of the run kept (s).
    pub to_dt: f64,
}

/// Means over one run's impacts (§3.3.1).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ImpactMeans {
    /// The wheel's sides n.
    pub sides: usize,
    /// Impacts in the run.
    pub impacts: usize,
    /// Mean normal impulse per impact (N s).
    pub normal_impulse: f64,
    /// Mean tangential impulse per impact (N s).
    pub tangential_impulse: f64,
    /// Mean normal impulse per unit of wheel mass (m/s).
    pub normal_per_mass: f64,
    /// Mean ω⁺/ω⁻ over the impacts (NaN where ω⁻ = 0).
    pub omega_ratio: f64,
}

impl ImpactMeans {
    /// The means of `run`'s impact log (zeros without impacts).
    pub fn of(run: &RollReport) -> Self {
        let n = run.impact_log.len().max(1) as f64;
        let sum = run.impact_log.iter().fold((0.0, 0.0, 0.0), |acc, i| {
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
        Self {
            sides: run.sides,
            impacts: run.summary.impacts,
            normal_impulse: sum.0 / n,
            tangential_impulse: sum.1 / n,
            normal_per_mass: sum.0 / n / run.mass_kg,
            omega_ratio: sum.2 / n,
        }
    }
}

/// A fixed colour per wheel (n = 8, 12, 16, 24), so that a band and its mean share it: the
/// first four of the series palette ([`tensegrity_io::figure::style::PALETTE`]).
const WHEEL_COLOURS: [(u8, u8, u8); 4] = {
    let p = tensegrity_io::figure::style::PALETTE;
    [p[0], p[1], p[2], p[3]]
};

impl FigRolling {
    /// Figs. 3.10 (axle height of every wheel) and 3.11 (reactions of n = 8 and 16) side by
    /// side, each curve labelled `n = 8 rigid` (and `(NOT VALID)` when the run is not). With
    /// an ensemble, the axle height of each wheel is the copies' mean (`mean of K`) between
    /// the two edges of its 95 % band (mean ± 1.96 s at each time), in the wheel's colour.
    pub fn figure(&self) -> Figure {
        let labelled: Vec<(String, &[RollingSample])> = self
            .runs
            .iter()
            .map(|r| {
                let mark = if r.summary.valid { "" } else { " (NOT VALID)" };
                let label = format!("n = {} {}{mark}", r.sides, r.fidelity.name());
                (label, r.samples.as_slice())
            })
            .collect();
        // Fig. 3.11 shows the reactions of n = 8 and 16 only
        let some: Vec<(String, &[RollingSample])> = self
            .runs
            .iter()
            .zip(&labelled)
            .filter(|(r, _)| [8, 16].contains(&r.sides))
            .map(|(_, l)| l.clone())
            .collect();
        let axle = if self.runs.iter().any(|r| r.ensemble_samples.len() >= 2) {
            self.band_panel()
        } else {
            axle_panel(&labelled)
        };
        let invalid: Vec<tensegrity_core::Warning> = (self.runs.iter())
            .filter(|r| !r.summary.valid)
            .flat_map(|r| {
                let run = r.fidelity.name();
                (r.summary.warnings.iter()).map(move |w| w.clone().in_run(r.sides, run))
            })
            .collect();
        let valid = self.runs.iter().all(|r| r.summary.valid);
        crate::warning::marked(
            Figure::new(vec![axle, reaction_panel(&some)]),
            valid,
            &invalid,
        )
    }

    /// The axle height of every wheel as its ensemble's mean and 95 % band (a wheel without
    /// copies: its single run).
    fn band_panel(&self) -> Panel {
        let mut panel = axle_panel(&[]).legend_above(legend_band(self.runs.len()));
        for (i, r) in self.runs.iter().enumerate() {
            let colour = WHEEL_COLOURS[i % WHEEL_COLOURS.len()];
            let model = r.fidelity.name();
            let mark = if r.summary.valid { "" } else { " (NOT VALID)" };
            let k = r.ensemble_samples.len();
            if k < 2 {
                let points = r.samples.iter().map(|s| (s.t, s.h)).collect();
                let label = format!("n = {} {model}{mark}", r.sides);
                panel
                    .series
                    .push(Series::new(label, points).with_color(colour));
                continue;
            }
            let b = wheel_rolling::ensemble::band(&r.ensemble_samples, |s| s.h);
            let label = format!("n = {} {model}: mean of {k}, 95 % band{mark}", r.sides);
            let mean = b.iter().map(|p| (p.0, p.1)).collect();
            panel
                .series
                .push(Series::new(label, mean).with_color(colour));
            for edge in [
                |p: &(f64, f64, f64, f64)| p.2,
                |p: &(f64, f64, f64, f64)| p.3,
            ] {
                let points = b.iter().map(|p| (p.0, edge(p))).collect();
                panel
                    .series
                    .push(Series::new("", points).with_color(colour));
            }
        }
        panel
    }

    /// The impulse per new contact of every wheel.
    pub fn impacts(&self) -> Vec<ImpactMeans> {
        self.runs.iter().map(ImpactMeans::of).collect()
    }

    /// One line per wheel with an ensemble: its size, and where the spread of the copies
    /// exceeds the difference between the models (the ensemble's `note`), or that it does not.
    pub fn ensemble_notes(&self) -> Vec<String> {
        self.runs
            .iter()
            .filter_map(|r| {
                let e = r.ensemble.as_ref()?;
                let what = if e.note.is_empty() {
                    "the spread of the copies is within the difference between the models on every headline quantity".to_string()
                } else {
                    e.note.clone()
                };
                Some(format!(
                    "n = {} ({} model, ensemble of {}): {what}",
                    r.sides,
                    r.fidelity.name(),
                    e.members
                ))
            })
            .collect()
    }
}

/// Rolls the four wheels of `request` in parallel (one thread per wheel).
pub fn fig_rolling(request: &FigRollingRequest) -> Result<FigRolling> {
    request.validate()?;
    let requests: Vec<RollRequest> = FigRollingRequest::SIDES
        .iter()
        .map(|&n| request.roll_request(n))
        .collect();
    let runs = roll_all(&requests)?.into_iter().map(|(r, _)| r).collect();
    Ok(FigRolling {
        runs,
        refined: Vec::new(),
    })
}

/// [`fig_rolling`], then, once, the wheels whose only warnings are unconverged quantities
/// re-run at half their step, when that fits the `budget_s` seconds of wall time left: the
/// refined runs are predicted at twice their first runs' wall time, shared over the cores
/// (`cores`). What was refined is in [`FigRolling::refined`]; a wheel that does not fit keeps
/// its first run, not valid. This is `fig-rolling` refining within its work limit: on its
/// defaults the full n = 16 and 24 runs do not converge at 2.5·10⁻⁴ s and do at 1.25·10⁻⁴ s.
pub fn fig_rolling_within(
    request: &FigRollingRequest,
    budget_s: f64,
    cores: usize,
) -> Result<FigRolling> {
    request.validate()?;
    let start = std::time::Instant::now();
    let requests: Vec<RollRequest> = FigRollingRequest::SIDES
        .iter()
        .map(|&n| request.roll_request(n))
        .collect();
    let first = roll_all(&requests)?;
    let redo: Vec<usize> = (0..first.len())
        .filter(|&i| first[i].0.summary.only_unconverged())
        .collect();
    let predicted: f64 = 2.0 * redo.iter().map(|&i| first[i].1).sum::<f64>()
        / redo.len().clamp(1, cores.max(1)) as f64;
    let mut runs: Vec<RollReport> = first.into_iter().map(|(r, _)| r).collect();
    let mut refined = Vec::new();
    if !redo.is_empty() && start.elapsed().as_secs_f64() + predicted <= budget_s {
        let finer: Vec<RollRequest> = redo
            .iter()
            .map(|&i| {
                let mut r = requests[i];
                r.settings.dt = Some(0.5 * runs[i].dt);
                r
            })
            .collect();
        for (k, (report, _)) in roll_all(&finer)?.into_iter().enumerate() {
            let i = redo[k];
            refined.push(Refined {
                sides: runs[i].sides,
                from_dt: runs[i].dt,
                to_dt: report.dt,
            });
            runs[i] = report;
        }
    }
    Ok(FigRolling { runs, refined })
}

/// Rolls each request on its own thread: the reports and each run's wall time (s).
fn roll_all(requests: &[RollRequest]) -> Result<Vec<(RollReport, f64)>> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = requests
            .iter()
            .map(|r| {
                scope.spawn(move || {
                    let t = std::time::Instant::now();
                    toroid::roll(r).map(|report| (report, t.elapsed().as_secs_f64()))
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| match h.join() {
                Ok(report) => Ok(report?),
                Err(_) => Err(FigureError::Panicked),
            })
            .collect::<Result<Vec<_>>>()
    })
}

/// The figure of one `roll` run: with `frame_times`, the wheel's members at those times
/// (the report's frames within one step `dt` of each time, thesis Fig. 3.8); without, the
/// axle height above the slope and the normal reaction against time. A run that is not valid
/// is marked on the figure (`NOT VALID: <first warning's kind>`,
/// [`crate::warning::invalid_reason`]).
pub fn roll_figure(
    request: &RollRequest,
    report: &RollReport,
    frame_times: Option<&[f64]>,
) -> Result<Figure> {
    let figure = run_figure(request, report, frame_times)?;
    let s = &report.summary;
    Ok(crate::warning::marked(figure, s.valid, &s.warnings))
}

/// [`roll_figure`] unmarked.
fn run_figure(
    request: &RollRequest,
    report: &RollReport,
    frame_times: Option<&[f64]>,
) -> Result<Figure> {
    match frame_times {
        Some(times) => {
            let toroid = request.wheel.build()?;
            let dt = request.coarser_step();
            let panels = times
                .iter()
                .filter_map(|&t| report.frames.iter().find(|f| (f.t - t).abs() <= dt))
                .map(|f| wheel_on_slope_panel(f, &toroid.structure))
                .collect();
            Ok(crate::draw::drawing_figure(panels))
        }
        None => {
            let runs = [(format!("n = {}", report.sides), report.samples.as_slice())];
            Ok(Figure::new(vec![axle_panel(&runs), reaction_panel(&runs)]))
        }
    }
}

/// The wheel at one frame in the rolling plane (s along the slope, h above it), in the
/// structure style of [`crate::draw`] (to scale, bars thick and dark, strings thin), above the
/// slope h = 0.
pub fn wheel_on_slope_panel(frame: &WheelFrame, structure: &tensegrity_core::Structure) -> Panel {
    use crate::draw::{drawing_panel, Drawing, Style, View};
    let drawing = Drawing {
        nodes: frame.nodes.clone(),
        ..Drawing::of(structure)
    };
    let style = Style {
        view: View::Side,
        ..Style::default()
    };
    let mut panel = drawing_panel(format!("t = {:.3} s", frame.t), &drawing, &style);
    panel.x_label = "along the slope s [m]".into();
    panel.y_label = "above the slope h [m]".into();
    let (lo, hi) = frame
        .nodes
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.y), hi.max(p.y))
        });
    let pad = 0.15 * (hi - lo);
    panel.series.insert(
        0,
        Series::new("slope", vec![(lo - pad, 0.0), (hi + pad, 0.0)])
            .with_color((0x60, 0x60, 0x60))
            .with_width(2.5),
    );
    panel
}

/// The wheel's members in the rolling plane (s, h) at one time (thesis Fig. 3.8), above the
/// slope drawn under the wheel.
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

/// The empty band above the data that a legend of `entries` lines needs (fraction of the
/// data's span).
fn legend_band(entries: usize) -> f64 {
    0.1 + 0.1 * entries as f64
}

/// Axle height above the incline against time (Fig. 3.10), one curve per labelled run.
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

/// Normal contact reaction against time (Fig. 3.11), one curve per labelled run.
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

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;
    use tensegrity_core::request::Params;

    #[test]
    fn the_request_describes_every_field_and_reads_its_flat_form() {
        tensegrity_core::request::check_description::<FigRollingRequest>().unwrap();
        let names: Vec<&str> = FigRollingRequest::params().iter().map(|p| p.name).collect();
        assert_eq!(
            names,
            [
                "fidelity",
                "contact",
                "incline",
                "t_end",
                "mu",
                "restitution",
                "dt",
                "ensemble"
            ]
        );
        let r = FigRollingRequest::from_values([
            ("fidelity", serde_json::json!("rigid")),
            ("contact", serde_json::json!("thesis")),
            ("t_end", serde_json::json!("2")),
        ])
        .unwrap();
        assert_eq!(
            (r.fidelity, r.contact, r.t_end),
            (FidelityChoice::Rigid, ContactKind::Thesis, 2.0)
        );
        let json = serde_json::to_value(r).unwrap();
        assert_eq!(
            (json["fidelity"].as_str(), json["contact"].as_str()),
            (Some("rigid"), Some("thesis"))
        );
        assert!(serde_json::from_str::<FigRollingRequest>(r#"{"sides": 8}"#).is_err());
        // the defaults are those of `roll`
        let d = FigRollingRequest::default().roll_request(8);
        assert_eq!(d, RollRequest::with_sides(8));
        let e = FigRollingRequest::from_values([("t_end", serde_json::json!(0))]).unwrap_err();
        assert_eq!(e.name, "t_end");
    }

    /// `fig_rolling_within`: the wheels whose only warnings are unconverged quantities are
    /// re-run once at half their step when the budget allows, and kept; with no budget none
    /// is. On 1 s of the four full wheels every first run is unconverged (IMEX-ARK at
    /// 2.5·10⁻⁴ s); at 1.25·10⁻⁴ s n = 12 and 16 converge. (n = 8 converged there from
    /// issue 48 until its coarse estimate was made to decide only within half a tolerance,
    /// `wheel_rolling::convergence::FULL_COARSE_DECIDES`: its slip fraction, 1.2·10⁻² at
    /// 2 dt against 0.02, now goes to the refined check, which estimates it and the final
    /// speed past their tolerances, 2.2·10⁻² and 2.9·10⁻², where they are 3·10⁻³ and
    /// 1.3·10⁻² off a run at 3.9·10⁻⁶ s: over-stated, not under-stated.)
    #[test]
    fn unconverged_wheels_are_refined_within_the_budget() {
        let request = FigRollingRequest {
            fidelity: FidelityChoice::Full,
            t_end: 1.0,
            ..FigRollingRequest::default()
        };
        let none = fig_rolling_within(&request, 0.0, 2).unwrap();
        assert!(none.refined.is_empty());
        assert!(none.runs.iter().all(|r| !r.summary.valid && r.dt == 2.5e-4));
        let all = fig_rolling_within(&request, 1e9, 2).unwrap();
        let sides: Vec<usize> = all.refined.iter().map(|r| r.sides).collect();
        assert_eq!(sides, [8, 12, 16, 24]);
        for (r, run) in all.refined.iter().zip(&all.runs) {
            assert_eq!((r.from_dt, r.to_dt, run.dt), (2.5e-4, 1.25e-4, 1.25e-4));
        }
        let valid: Vec<usize> = all
            .runs
            .iter()
            .filter(|r| r.summary.valid)
            .map(|r| r.sides)
            .collect();
        assert_eq!(valid, [12, 16]);
    }

    /// `ensemble = K`: each wheel's axle height is the mean of its K copies between the two
    /// edges of the 95 % band (one colour per wheel), and the output says, per wheel,
    /// whether the spread exceeds the difference between the models.
    #[test]
    fn an_ensemble_draws_the_mean_and_the_band_and_states_the_spread() {
        let request = FigRollingRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 1.0,
            ensemble: 3,
            ..FigRollingRequest::default()
        };
        let roll = |n: usize| {
            let mut r = request.roll_request(n);
            r.checks = wheel_rolling::RunChecks::NONE;
            toroid::roll(&r).unwrap()
        };
        let rolled = FigRolling {
            refined: Vec::new(),
            runs: vec![roll(8), roll(24)],
        };
        assert_eq!(rolled.runs[0].ensemble_samples.len(), 3);
        let f = rolled.figure();
        let axle = &f.panels[0];
        // mean, low edge, high edge per wheel
        assert_eq!(axle.series.len(), 6);
        assert!(axle.series[0].label.contains("mean of 3, 95 % band"));
        assert_eq!(
            (axle.series[1].label.as_str(), axle.series[2].label.as_str()),
            ("", "")
        );
        assert_eq!(axle.series[0].color, axle.series[2].color);
        assert_ne!(axle.series[0].color, axle.series[3].color);
        // the band holds its mean, and the mean is the copies' mean at each time
        let b = wheel_rolling::ensemble::band(&rolled.runs[0].ensemble_samples, |s| s.h);
        for ((lo, mid), hi) in axle.series[1]
            .points
            .iter()
            .zip(&axle.series[0].points)
            .zip(&axle.series[2].points)
        {
            assert!(lo.1 <= mid.1 + 1e-12 && mid.1 <= hi.1 + 1e-12);
        }
        let copies = &rolled.runs[0].ensemble_samples;
        let j = copies[0].len() / 2;
        let mean = copies.iter().map(|c| c[j].h).sum::<f64>() / 3.0;
        assert!((b[j].1 - mean).abs() < 1e-12, "{} vs {mean}", b[j].1);
        let notes = rolled.ensemble_notes();
        assert_eq!(notes.len(), 2);
        assert!(
            notes[0].starts_with("n = 8 (rigid model, ensemble of 3)"),
            "{}",
            notes[0]
        );
    }

    /// A short rigid run of the reference wheel with `sides` sides, marked (in)valid.
    fn run(sides: usize, valid: bool) -> RollReport {
        let mut r = toroid::roll(&RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 0.01,
            ..RollRequest::with_sides(sides)
        })
        .unwrap();
        r.summary.valid = valid;
        r
    }

    #[test]
    fn a_figure_of_a_run_that_is_not_valid_is_marked_with_its_first_warning() {
        let valid = run(8, true);
        let fig = roll_figure(&RollRequest::with_sides(8), &valid, None).unwrap();
        assert!(fig.invalid.is_none());
        assert!(!fig.to_svg().unwrap().contains("class=\"invalid\""));
        let mut bad = run(8, false);
        bad.summary.warnings = vec![
            tensegrity_core::Warning::NotPrestressable,
            tensegrity_core::Warning::RimFreeBody,
        ];
        let fig = roll_figure(&RollRequest::with_sides(8), &bad, None).unwrap();
        let svg = fig.to_svg().unwrap();
        assert!(
            svg.contains("NOT VALID: not_prestressable (+1 more)"),
            "{svg}"
        );
        let all = FigRolling {
            refined: Vec::new(),
            runs: vec![valid, bad],
        };
        assert_eq!(
            all.figure().invalid.as_deref(),
            Some("n = 8: not_prestressable (+1 more)")
        );
    }

    #[test]
    fn fig_rolling_draws_every_axle_height_and_the_reactions_of_8_and_16() {
        let runs = FigRolling {
            refined: Vec::new(),
            runs: vec![run(8, true), run(12, false), run(16, true), run(24, true)],
        };
        let f = runs.figure();
        assert_eq!(f.panels.len(), 2);
        let labels = |p: &Panel| p.series.iter().map(|s| s.label.clone()).collect::<Vec<_>>();
        assert_eq!(
            labels(&f.panels[0]),
            [
                "n = 8 rigid",
                "n = 12 rigid (NOT VALID)",
                "n = 16 rigid",
                "n = 24 rigid"
            ]
        );
        assert_eq!(labels(&f.panels[1]), ["n = 8 rigid", "n = 16 rigid"]);
        // the figure says so above its panels (issue 46): the run not valid, without warnings
        assert_eq!(f.invalid.as_deref(), Some("see the report"));
        let first = &runs.runs[0].samples;
        assert_eq!(f.panels[0].series[0].points[0], (first[0].t, first[0].h));
        assert_eq!(
            f.panels[1].series[0].points[0],
            (first[0].t, first[0].normal)
        );
    }

    #[test]
    fn impact_means_are_the_means_of_the_log() {
        let mut r = run(8, true);
        r.impact_log.truncate(0);
        let none = ImpactMeans::of(&r);
        assert_eq!((none.normal_impulse, none.tangential_impulse), (0.0, 0.0));
        let rolled = toroid::roll(&RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 2.0,
            ..RollRequest::with_sides(8)
        })
        .unwrap();
        let log = &rolled.impact_log;
        assert!(!log.is_empty());
        let m = ImpactMeans::of(&rolled);
        assert_eq!((m.sides, m.impacts), (8, log.len()));
        let n = log.len() as f64;
        let mean =
            |f: &dyn Fn(&wheel_rolling::ImpactRecord) -> f64| log.iter().map(f).sum::<f64>() / n;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs();
        let normal = mean(&|i| i.normal_impulse);
        assert!(close(m.normal_impulse, normal));
        assert!(close(m.tangential_impulse, mean(&|i| i.tangential_impulse)));
        assert!(close(m.normal_per_mass * rolled.mass_kg, normal));
        assert!(close(
            m.omega_ratio,
            mean(&|i| i.omega_after / i.omega_before)
        ));
        // the ground pushes: every normal impulse is positive
        assert!(log.iter().all(|i| i.normal_impulse > 0.0), "{log:?}");
    }

    #[test]
    fn fig_rolling_rolls_each_wheel_as_roll_does_and_more_sides_impact_gentler() {
        let request = FigRollingRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 2.0,
            ..FigRollingRequest::default()
        };
        let rolled = fig_rolling(&request).unwrap();
        let sides: Vec<usize> = rolled.runs.iter().map(|r| r.sides).collect();
        assert_eq!(sides, FigRollingRequest::SIDES);
        // the parallel runs are the serial `roll` calls, sample for sample
        for r in &rolled.runs {
            let alone = toroid::roll(&request.roll_request(r.sides)).unwrap();
            assert_eq!(r.samples, alone.samples, "n = {}", r.sides);
            assert_eq!(r.impact_log, alone.impact_log, "n = {}", r.sides);
            assert!(r.summary.valid, "n = {}: {:?}", r.sides, r.summary.warnings);
        }
        // §3.3.1: more sides, more and gentler impacts (normal impulse per unit mass, m/s:
        // 1.85, 1.28, 0.84, 0.62 for n = 8, 12, 16, 24 over 2 s down 50°)
        let m = rolled.impacts();
        for pair in m.windows(2) {
            assert!(pair[1].impacts > pair[0].impacts, "{m:?}");
            assert!(pair[1].normal_per_mass < pair[0].normal_per_mass, "{m:?}");
        }
        assert!(m[3].normal_per_mass < 0.5 * m[0].normal_per_mass, "{m:?}");
        // a bad request is refused before any wheel rolls
        let bad = FigRollingRequest {
            restitution: 2.0,
            ..request
        };
        assert!(
            matches!(fig_rolling(&bad), Err(FigureError::InvalidParameter(p)) if p.name == "restitution")
        );
    }

    #[test]
    fn a_frame_is_the_slope_and_one_segment_per_member_in_the_rolling_plane() {
        let frame = WheelFrame {
            t: 0.5,
            nodes: vec![
                Vector3::new(0.0, -1.0, 0.5),
                Vector3::new(0.0, 1.0, 1.5),
                Vector3::new(0.3, 0.0, 2.0),
            ],
            velocities: Vec::new(),
            member_forces: Vec::new(),
        };
        let p = frame_panel(&frame, &[[0, 1], [1, 2]]);
        assert_eq!(p.title, "t = 0.500 s");
        assert_eq!(p.series[0].points, [(-1.0, 0.0), (1.0, 0.0)]);
        assert_eq!(p.series[1].points, [(-1.0, 0.5), (1.0, 1.5)]);
        assert_eq!(p.series[2].points, [(1.0, 1.5), (0.0, 2.0)]);
    }
}
