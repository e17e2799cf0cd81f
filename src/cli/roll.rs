//! `tensegrity roll`: its flags are the fields of [`RollRequest`] ([`RequestArgs`]) beside the
//! outputs; one library call ([`toroid::roll_observed`]) whose observer is the outputs
//! ([`RollingOutputs`]: the history rows and the VTK frames streamed while the run goes on),
//! then the report printed or plotted; warnings go to stderr as well.
//!
//! Every output is opened before the run (a bad path: exit 2 at once). SIGINT/SIGTERM stops
//! the run at its next step: the CSV keeps its rows with a `# incomplete: interrupted at t = …`
//! trailer, the series its frames and a `series.pvd` listing them, the partial run's report
//! is printed and the exit code is 130. `fig-rolling` is [`super::fig_rolling`]; the figure of `--svg` is
//! [`tensegrity_figures::roll_figure`].

use super::animate::Opened;
use super::output;
use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_figures::animation::{Animation, Camera, Scenery};
use tensegrity_io::interrupt::{self, Interrupted};
use tensegrity_io::sink::{CsvSink, FigureSink, RollingOutputs, VtkSeriesSink};
use toroid::defaults;
use toroid::{RollReport, RollRequest};

/// Arguments of `tensegrity roll`: the request's flags ([`RollRequest`]) and the outputs.
#[derive(clap::Args, Debug)]
pub struct RollArgs {
    #[command(flatten)]
    request: RequestArgs<RollRequest>,
    /// Write the sampled history (1 ms) to this CSV file: t, axle_s, axle_h, omega, then
    /// pivot_m, normal_N, tangential_N, energy_J, slip_m_s.
    #[arg(long)]
    out: Option<PathBuf>,
    /// With --frames: draw the wheel's members at those times (Fig. 3.8); without: plot the
    /// axle height above the slope and the normal reaction against time. SVG, PNG or PDF.
    #[arg(long, value_name = "FILE")]
    svg: Option<PathBuf>,
    #[command(flatten)]
    figure: super::figure_args::FigureArgs,
    /// Times (s) of the wheel drawings of --svg, e.g. `0,1.5,3`.
    #[arg(long, value_delimiter = ',', value_name = "T,T,..")]
    frames: Option<Vec<f64>>,
    /// Write the node trajectories as a ParaView series (DIR/series.pvd, every 10 ms, each time
    /// once; slope coordinates: x along the axle, y down the slope, z above it), with the node
    /// velocities (point data `velocity`) and, for the full model, the member forces (cell
    /// data `force`, tension positive).
    #[arg(long, value_name = "DIR")]
    vtk: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    animate: super::animate::AnimateArgs,
}

impl RollArgs {
    /// The library request the flags describe; a setting of the full model under
    /// `--fidelity rigid` is refused, at any value given ([`RollRequest::check_rigid_given`], exit 2).
    pub fn request(&self) -> Result<RollRequest> {
        let request: RollRequest = self.request.request()?;
        request
            .check_rigid_given(|name| self.request.given(name))
            .map_err(super::request_args::usage)?;
        Ok(request)
    }

    /// Every --frames time within the run.
    fn check_frames(&self, t_end: f64) -> Result<()> {
        let mut times = self.frames.iter().flatten();
        match times.find(|t| !(0.0..=t_end).contains(*t)) {
            Some(t) => anyhow::bail!("--frames: time {t} s lies outside the run [0, {t_end}] s"),
            None => Ok(()),
        }
    }

    /// The frame times the outputs need: --frames, and the --vtk grid.
    fn frame_times(&self, t_end: f64) -> Vec<f64> {
        let mut times = self.frames.clone().unwrap_or_default();
        if self.vtk.is_some() {
            let n = (t_end / defaults::ROLL_FRAME_DT).floor() as usize;
            times.extend((0..=n).map(|k| k as f64 * defaults::ROLL_FRAME_DT));
        }
        // each time once (a --frames time on the --vtk grid is one frame)
        times.sort_by(f64::total_cmp);
        times.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);
        times
    }
}

/// Entry point of `tensegrity roll`.
pub fn run_roll(args: &RollArgs) -> Result<()> {
    let request = args.request()?;
    let progress = super::guard::roll(&request)?;
    let t_end = request.t_end;
    args.check_frames(t_end)?;
    let opened = args.animate.open_with(args.figure.options()?)?;
    // the VTK series and the animation draw the built wheel's members
    let wheel = (args.vtk.is_some() || opened.is_some())
        .then(|| request.wheel.build())
        .transpose()?;
    let mut animation = opened
        .zip(wheel.as_ref())
        .map(|(o, w)| wheel_animation(o, &request, w));
    let mut times = args.frame_times(t_end);
    times.extend(animation.iter().flat_map(|a| a.times().iter().copied()));
    let (figure, outputs) = open_outputs(args, &request, wheel.as_ref())?;
    let mut outputs = outputs.with_progress(progress.handle());
    if let Some(a) = animation.as_mut() {
        outputs = outputs.with_frames(a);
    }
    let _polled = interrupt::polled();
    let mut report = toroid::roll_observed(&request, &times, Some(&mut outputs))?;
    report.frames = outputs.take_frames();
    let interrupted = interrupt::requested();
    let reason = report.summary.stopped_at.map(|t| match interrupted {
        true => format!("interrupted at t = {t} s"),
        false => format!("the integration stopped at t = {t} s"),
    });
    let written = outputs.finish(reason.as_deref())?;
    if !interrupted {
        let (valid, warnings) = (report.summary.valid, &report.summary.warnings);
        let animation = animation.map(|a| a.marked(valid, warnings));
        super::animate::finish(animation, args.animate.animate.as_deref())?;
    }
    for w in &report.summary.warnings {
        eprintln!("warning: {}", super::spell::flags(&w.to_string()));
    }
    if let (Some(sink), false) = (figure, interrupted) {
        sink.finish(&tensegrity_figures::roll_figure(
            &request,
            &report,
            args.frames.as_deref(),
        )?)?;
    }
    if let Some(dir) = &args.vtk {
        let n = written.frames;
        eprintln!("wrote {n} VTK frames to {}/series.pvd", dir.display());
    }
    if args.json {
        super::output::print_json(&report)?;
    } else {
        print_roll(&report);
    }
    end(args, &report, interrupted, written.rows)?;
    Ok(request.strict_check(&report)?)
}

/// The wheel rolling in the animation: its members in the side view turned by −incline (the
/// slope goes down to the right), the camera following it; a frame is the step nearest its time.
fn wheel_animation(o: Opened, request: &RollRequest, wheel: &toroid::Toroid) -> Animation {
    let mut s = Scenery::structure("toroid rolling", &wheel.structure, None);
    s.ground = Some((nalgebra::Vector3::zeros(), nalgebra::Vector3::z()));
    (s.tilt, s.camera) = (-request.settings.incline, Camera::Follow);
    o.start(s, request.t_end)
        .with_tolerance(request.coarser_step())
}

/// Opens `--svg` and the outputs the run streams to (`--out`, `--vtk` of `wheel`'s members),
/// each error naming its flag.
fn open_outputs<'a>(
    args: &RollArgs,
    request: &RollRequest,
    wheel: Option<&'a toroid::Toroid>,
) -> Result<(Option<FigureSink>, RollingOutputs<'a>)> {
    let csv = output::open("--out", args.out.as_deref(), |p| {
        CsvSink::open(p, "rolling history CSV")
    })?;
    let figure = args.figure.open("--svg", args.svg.as_deref())?;
    let vtk = match (&args.vtk, wheel) {
        (Some(dir), Some(t)) => Some(output::open_required("--vtk", dir, |d| {
            VtkSeriesSink::open(d, &t.structure)
        })?),
        _ => None,
    };
    let keep = args.frames.as_deref().unwrap_or_default();
    let outputs = RollingOutputs::new(csv, vtk).keeping(keep, request.coarser_step());
    Ok((figure, outputs))
}

/// The exit of a run: interrupted (130), stopped by its integration (1), or whole.
fn end(args: &RollArgs, r: &RollReport, interrupted: bool, rows: usize) -> Result<()> {
    if interrupted {
        let note = args
            .out
            .is_some()
            .then(|| format!("{rows} history rows kept, marked incomplete"));
        let t = r.summary.stopped_at;
        return Err(Interrupted { t, note }.into());
    }
    match r.summary.stopped_at {
        Some(t) => anyhow::bail!(
            "the integration stopped at t = {t} s of --t-end {} s: the results above cover [0, {t}] s only (see the warnings)",
            r.t_end
        ),
        None => Ok(()),
    }
}

fn print_roll(r: &RollReport) {
    let s = &r.summary;
    let model = r.fidelity.name();
    println!(
        "{model} rolling ({} contact), n = {}, incline {:.3} deg, {} s: {} impacts{}",
        r.contact,
        r.sides,
        r.incline_rad.to_degrees(),
        r.t_end,
        s.impacts,
        super::output::invalid_mark(s.valid)
    );
    println!("model: {model} ({})", r.fidelity_reason);
    let span = if r.t_end > 1.0 {
        "after 1 s"
    } else {
        "whole run"
    };
    println!(
        "axle height above the slope: mean {:.4} m, RMS oscillation {:.6} m ({span})",
        s.mean_axle_height, s.axle_height_oscillation
    );
    println!(
        "mean speed {:.4} m/s   final speed {:.4} m/s   max reaction {:.3} N",
        s.mean_speed, s.final_speed, s.max_reaction
    );
    if let Some(i) = s.first_impact {
        println!(
            "first impact at t = {:.6} s: omega {:.6} -> {:.6} rad/s",
            i.t, i.omega_before, i.omega_after
        );
    }
    println!(
        "validity: {}; min normal force {:.4} N, airborne {:.2} %, slipping {:.2} %, max penetration {:.3e} m, energy budget residual {:.2e}",
        if s.valid { "valid" } else { "NOT VALID" },
        s.min_normal_force,
        100.0 * s.airborne_fraction,
        100.0 * s.slip_fraction,
        s.max_penetration,
        s.energy_balance_error
    );
    super::output::print_convergence(s.convergence.as_ref());
    if let Some(e) = &r.ensemble {
        print_ensemble(e);
    }
    for w in &s.warnings {
        println!("warning: {}", super::spell::flags(&w.to_string()));
    }
}

/// The ensemble's mean and 95 % interval per headline quantity, against the other model.
fn print_ensemble(e: &wheel_rolling::Ensemble) {
    println!(
        "ensemble of {} copies ({} not valid); {}:",
        e.members, e.invalid_members, e.perturbation
    );
    for q in &e.quantities {
        let other = q
            .other_model
            .map_or(String::new(), |o| format!("; other model {o:.6}"));
        println!(
            "  {:<26} mean {:.6}, 95 % interval [{:.6}, {:.6}]{other}",
            q.name, q.mean, q.low, q.high
        );
    }
    if !e.note.is_empty() {
        println!("note: {}", e.note);
    }
}
