//! What the command line writes beside its reports, for Python: the history of `tipover`'s
//! timed runs (`--dynamic`, `--rolling`: the rows of `--out`), the friction map of
//! `tipover --grid`, the T-bar studies (`tbar --loop-study`, `tbar --mass-sweep`), the
//! per-sample history of `tbar roll`'s first T-bar run, the exports (`export mjcf`, `json`,
//! `schema`) and the project's figures (`figures --only N`) — each through the library call
//! the CLI makes, its values handed back as the engine's values or f64 columns (no text).

use crate::errors::Failure;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use tbar_wheel::roll::{TbarRollReport, TbarRollRequest, Watch};
use tensegrity_core::budget::Limits;
use tensegrity_core::request::{Categorized, Category, InvalidParameter, Request};
use tensegrity_engine::value::{to_value, Map, Value};
use tensegrity_engine::SceneSource;
use tensegrity_io::figure::RenderOptions;
use tensegrity_io::sink::{CsvSink, FigureSink, RollingOutputs};
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};
use wheel_rolling::{Fidelity, Observer};

/// The columns of `tipover --dynamic --out`.
pub const TIPOVER_DYNAMIC_COLUMNS: [&str; 5] = ["t", "force", "lean", "near_normal", "far_normal"];
/// The columns of `tipover --rolling --out`.
pub const TIPOVER_ROLLING_COLUMNS: [&str; 4] = ["t", "lean", "downhill", "across"];
/// The columns of `tipover --grid`.
pub const FRICTION_GRID_COLUMNS: [&str; 3] = ["sigma", "epsilon", "normalized_friction"];

/// A history: its rows, each as long as its columns, flattened.
pub type Rows = Vec<f64>;

/// A library error as the registry's run reports it, with the CLI's context.
fn failed<E: std::fmt::Display + Categorized>(e: &E, context: &str) -> Failure {
    Failure::run(tensegrity_engine::RunError::of(e)).context(context)
}

/// A report as the engine's value tree with the conventional keys (as `--json`).
fn json(report: &impl serde::Serialize) -> Result<Value, Failure> {
    to_value(report)
        .map(tensegrity_engine::keys::conventional)
        .map_err(|e| Failure::new(Category::Numerical, e.to_string()))
}

/// Runs `tipover --dynamic` (`rolling`: `--rolling`) on `values` as the CLI does: the report
/// (under `strict`, one that is not valid is an error) and its history, the rows of `--out`;
/// `progress`: where the run's end time (its last sample's) goes once it ran (the library
/// runs it in one call: a progress report paces it by its estimate meanwhile).
pub fn tipover(
    rolling: bool,
    values: Map<String, Value>,
    progress: Option<Arc<AtomicU64>>,
) -> Result<(Value, Rows), Failure> {
    let (report, rows, end) = if rolling {
        let req = TipoverRollingRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
        let r = req
            .run()
            .map_err(|e| failed(&e, "rolling lean run failed"))?;
        let rows = r
            .samples
            .iter()
            .flat_map(|s| [s.t, s.lean, s.downhill, s.across])
            .collect();
        let end = r.samples.last().map_or(req.t_end, |s| s.t);
        (json(&r)?, rows, end)
    } else {
        let req = TipoverDynamicRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
        let r = req
            .run()
            .map_err(|e| failed(&e, "dynamic tip-over run failed"))?;
        let rows = r
            .samples
            .iter()
            .flat_map(|s| [s.t, s.force, s.lean, s.near_normal, s.far_normal])
            .collect();
        let end = r.samples.last().map_or(req.settings.t_end(), |s| s.t);
        (json(&r)?, rows, end)
    };
    if let Some(p) = progress {
        p.store(end.to_bits(), Ordering::Relaxed);
    }
    Ok((report, rows))
}

/// The simulated time of `tipover --dynamic` (`rolling`: `--rolling`) on `values` (s): the
/// total of its progress.
pub fn tipover_t_end(rolling: bool, values: &Map<String, Value>) -> Result<f64, Failure> {
    let values = values.clone();
    if rolling {
        let req = TipoverRollingRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
        Ok(req.t_end)
    } else {
        let req = TipoverDynamicRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
        Ok(req.settings.t_end())
    }
}

/// Checks the friction map's estimate against `limits` (as the CLI's guard).
pub fn admit_friction_grid(points: usize, limits: &Limits) -> Result<(), Failure> {
    if points < 2 {
        let p = InvalidParameter::raw("grid_points", points, "must be at least 2");
        return Err(Failure::invalid(&p));
    }
    limits
        .check(&tensegrity_engine::estimate::friction_grid(points))
        .map_err(|over| Failure::over_budget(&over))
}

/// `tipover --grid`: F_f/F_e over the σ × ε grid, rows (σ, ε, F_f/F_e), σ outer.
pub fn friction_grid(points: usize, eps_max: f64) -> Result<Rows, Failure> {
    if !(eps_max.is_finite() && eps_max > 0.0) {
        let p = InvalidParameter::raw("eps_max", eps_max, "must be finite and positive");
        return Err(Failure::invalid(&p));
    }
    let rows = sweeps::grids::friction_grid(points, eps_max).map_err(|e| failed(&e, ""))?;
    Ok(rows.into_iter().flat_map(|(s, e, f)| [s, e, f]).collect())
}

/// The T-bar request of `tbar`'s flags (`values`).
fn tbar_request(values: Map<String, Value>) -> Result<tbar_wheel::TbarStaticRequest, Failure> {
    let request =
        tbar_wheel::TbarStaticRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
    request.validate().map_err(|e| Failure::invalid(&e))?;
    Ok(request)
}

/// A T-bar error; a bad parameter (the T-bar's or its Michell parameterisation's) names it.
fn tbar_failed(e: tbar_wheel::TbarError) -> Failure {
    use tbar_wheel::TbarError;
    match e {
        TbarError::InvalidParameter(p)
        | TbarError::Michell(michell3d::MichellError::InvalidParameter(p)) => Failure::invalid(&p),
        e => failed(&e, ""),
    }
}

/// `tbar --loop-study`: the six cases (the wheel and the extended wheel with a free rim body,
/// free and standing), as `--json` prints them.
pub fn loop_study(values: Map<String, Value>) -> Result<Value, Failure> {
    let request = tbar_request(values)?;
    let offset = request.extended.unwrap_or(0.5 * request.r0);
    let req = request.request();
    let rows = tbar_wheel::standing::loop_study(&req.params, offset).map_err(tbar_failed)?;
    json(&rows)
}

/// `tbar --mass-sweep` over `complexities` × `deltas`, as `--json` prints it.
pub fn mass_sweep(
    values: Map<String, Value>,
    complexities: &[usize],
    deltas: &[f64],
) -> Result<Value, Failure> {
    if let Some(q) = complexities.iter().find(|&&q| q == 0) {
        let p = InvalidParameter::raw(
            "sweep_complexities",
            q,
            "every complexity must be at least 1",
        );
        return Err(Failure::invalid(&p));
    }
    if let Some(d) = deltas.iter().find(|d| !d.is_finite()) {
        let p = InvalidParameter::raw("sweep_deltas", d, "every offset must be finite");
        return Err(Failure::invalid(&p));
    }
    let req = tbar_request(values)?.request();
    let rows = tbar_wheel::mass::mass_sweep(
        &req.params,
        complexities,
        deltas,
        req.load,
        req.ea,
        &req.material,
    );
    json(&rows)
}

/// `tbar roll` on `values` as the CLI runs it, the T-bar run of its first row (the first
/// number of treads) observed: the report and that run's samples, rows of
/// [`crate::runs::HISTORY_COLUMNS`].
///
/// With `progress` (simulated seconds over every row's T-bar run: row k counts from
/// k·t_end, [`tbar_roll_total`]), each number of treads runs as a request of its own, its
/// T-bar run observed, in the order the engine runs them; the report is the engine's
/// report of the row whose model ran the full dynamics (else the first) holding every row,
/// judged again over them ([`TbarRollReport::judged`]): the rows are those of one call.
pub fn tbar_roll(
    request: TbarRollRequest,
    progress: Option<Arc<AtomicU64>>,
) -> (Result<Value, Failure>, Vec<[f64; 9]>) {
    let mut history = crate::runs::History::new(RollingOutputs::new(None, None), None);
    let report = match progress {
        None => {
            let watch = Watch {
                times: &[],
                observer: &mut history,
            };
            tensegrity_engine::tbar_roll::report_watched(&request, Some(watch))
                .map_err(|e| failed(&e, ""))
        }
        Some(p) => rows_counted(&request, &mut history, &p),
    };
    let report = report.and_then(|r| {
        tensegrity_engine::tbar_roll::strict_check(&request, &r).map_err(|e| failed(&e, ""))?;
        json(&r)
    });
    (report, history.take_rows())
}

/// The total of `tbar roll`'s progress: t_end for every number of treads (s).
pub fn tbar_roll_total(request: &TbarRollRequest) -> f64 {
    request.treads().len() as f64 * request.t_end()
}

/// `tbar roll` one number of treads at a time (see [`tbar_roll`]): the first row's T-bar
/// run kept in `history`, every row's simulated time counted into `progress`.
fn rows_counted(
    request: &TbarRollRequest,
    history: &mut crate::runs::History<'_>,
    progress: &Arc<AtomicU64>,
) -> Result<TbarRollReport, Failure> {
    let t_end = request.t_end();
    let mut reports: Vec<TbarRollReport> = Vec::new();
    for (k, n) in request.treads().into_iter().enumerate() {
        let one = TbarRollRequest {
            treads: Some(vec![n]),
            ..request.clone()
        };
        let mut outputs = RollingOutputs::new(None, None);
        let observer: &mut dyn Observer = if k == 0 { &mut *history } else { &mut outputs };
        let mut counted = Counted {
            inner: observer,
            offset: k as f64 * t_end,
            progress,
        };
        let watch = Watch {
            times: &[],
            observer: &mut counted,
        };
        let r = tensegrity_engine::tbar_roll::report_watched(&one, Some(watch))
            .map_err(|e| failed(&e, ""))?;
        progress.store(((k + 1) as f64 * t_end).to_bits(), Ordering::Relaxed);
        reports.push(r);
    }
    if reports.is_empty() {
        // no number of treads: the engine's own answer
        return tensegrity_engine::tbar_roll::report(request).map_err(|e| failed(&e, ""));
    }
    let rows: Vec<_> = reports
        .iter()
        .flat_map(|r| r.rows.iter().cloned())
        .collect();
    let full = reports.iter().position(|r| r.model == Fidelity::Full);
    let mut report = reports.swap_remove(full.unwrap_or(0));
    report.rows = rows;
    Ok(report.judged())
}

/// An observer of a T-bar run handing everything to `inner`, its simulated time (from
/// `offset`) to `progress`.
struct Counted<'a> {
    inner: &'a mut dyn Observer,
    offset: f64,
    progress: &'a Arc<AtomicU64>,
}

impl Observer for Counted<'_> {
    fn sample(&mut self, s: &wheel_rolling::RollingSample) -> wheel_rolling::Flow {
        let done = self.offset + s.t;
        self.progress.store(done.to_bits(), Ordering::Relaxed);
        self.inner.sample(s)
    }

    fn frame(&mut self, frame: &wheel_rolling::WheelFrame) -> wheel_rolling::Flow {
        self.inner.frame(frame)
    }

    fn keep_going(&mut self) -> bool {
        self.inner.keep_going()
    }

    fn stop_flag(&self) -> Option<&'static std::sync::atomic::AtomicBool> {
        self.inner.stop_flag()
    }

    fn keeps_frames(&self) -> bool {
        self.inner.keeps_frames()
    }
}

/// The `tbar roll` request of `values` (refused before any work, as the CLI refuses it).
pub fn tbar_roll_request(values: Map<String, Value>) -> Result<TbarRollRequest, Failure> {
    let request = TbarRollRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
    request.validate().map_err(|e| Failure::invalid(&e))?;
    Ok(request)
}

/// The scene of a `scene` value (a path, TOML or JSON text, or a structure's data).
fn scene(value: Value) -> Result<tensegrity_io::scene::Scene, Failure> {
    let source: SceneSource = tensegrity_engine::value::from_value(value)
        .map_err(|e| Failure::invalid(&InvalidParameter::raw("scene", "(value)", e.to_string())))?;
    source
        .load()
        .map_err(|e| Failure::new(e.category(), e.to_string()))
}

/// `export mjcf`: the MJCF text of the scene (`source`: its name in the model, the path the
/// CLI is given).
pub fn mjcf(
    scene_value: Value,
    source: String,
    timestep: f64,
    ground_height: Option<f64>,
) -> Result<String, Failure> {
    let s = scene(scene_value)?;
    let options = tensegrity_io::mjcf::MjcfOptions {
        source,
        timestep,
        ground: ground_height.map(tensegrity_io::mjcf::MjcfGround::height),
    };
    tensegrity_io::mjcf::scene_to_mjcf(&s, &options)
        .map_err(|e| Failure::new(e.category(), e.to_string()))
}

/// `export json`: the scene as JSON of the same shape as its TOML.
pub fn scene_json(scene_value: Value) -> Result<String, Failure> {
    Ok(scene(scene_value)?.to_json())
}

/// `export schema`: the JSON Schema of scene files, as the CLI writes it.
pub fn schema() -> Result<String, Failure> {
    tensegrity_engine::exports::schema_text()
        .map_err(|e| Failure::new(Category::Numerical, e.to_string()))
}

/// The figure `number` (`3.10`, `fig_3_10`) of the catalogue, checked against `limits`
/// and the render options: its spec and the options.
pub fn figure_spec(
    number: &str,
    quick: bool,
    size: Option<&str>,
    dpi: Option<f64>,
    png: bool,
    limits: &Limits,
) -> Result<(&'static tensegrity_figures::FigureSpec, RenderOptions), Failure> {
    let bad = |e: tensegrity_figures::FigureError, name: &str| match e {
        tensegrity_figures::FigureError::InvalidParameter(mut p) => {
            p.name = name.to_string().into();
            Failure::invalid(&p)
        }
        e => Failure::new(e.category(), e.to_string()),
    };
    let request = tensegrity_figures::FiguresRequest {
        quick,
        only: vec![number.to_string()],
        png,
        threads: Some(1),
    };
    let chosen = request.selected().map_err(|e| bad(e, "name"))?;
    // the size parsed first, then the dpi: each error names its own argument
    let page = size
        .map(str::parse::<tensegrity_io::figure::PageSize>)
        .transpose()
        .map_err(|e| {
            Failure::invalid(&InvalidParameter::raw(
                "size",
                size.unwrap_or(""),
                e.to_string(),
            ))
        })?;
    let options = RenderOptions::new(page, dpi).map_err(|e| {
        Failure::invalid(&InvalidParameter::raw(
            "dpi",
            dpi.map_or(String::new(), |d| d.to_string()),
            e.to_string(),
        ))
    })?;
    tensegrity_figures::page::check_options(&chosen, &options, png).map_err(|e| bad(e, "size"))?;
    limits
        .check(&tensegrity_figures::estimate::figures(&request, &chosen))
        .map_err(|over| Failure::over_budget(&over))?;
    Ok((chosen[0], options))
}

/// Builds the figure `spec` (its sweeps' CSVs into `data_dir`) and writes it to `path`
/// (SVG, PNG or PDF by its extension) and, given `data`, its data table there as CSV.
pub fn write_figure(
    spec: &'static tensegrity_figures::FigureSpec,
    options: RenderOptions,
    quick: bool,
    path: &Path,
    data: Option<&Path>,
    data_dir: &Path,
) -> Result<(), Failure> {
    let io = |e: tensegrity_io::IoError| Failure::new(e.category(), e.to_string());
    let sink = FigureSink::open_with(path, options).map_err(io)?;
    let data_sink = match data {
        Some(p) => Some(CsvSink::open_records(p, "figure data").map_err(io)?),
        None => None,
    };
    let ctx = tensegrity_figures::Context::new(quick, data_dir);
    let drawn = spec
        .build(&ctx)
        .map_err(|e| Failure::new(e.category(), e.to_string()))?;
    sink.finish(&drawn.figure).map_err(io)?;
    if let Some(d) = data_sink {
        drawn.data.write(d).map_err(io)?;
    }
    Ok(())
}

/// The catalogue of figures: (number, description, file stem).
pub fn figure_catalog() -> Vec<(&'static str, &'static str, String)> {
    tensegrity_figures::FIGURES
        .iter()
        .map(|f| {
            let stem = f.file_name("svg");
            let stem = stem.trim_end_matches(".svg").to_string();
            (f.number, f.description, stem)
        })
        .collect()
}
