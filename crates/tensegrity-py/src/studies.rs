//! What the command line writes beside its reports, for Python: the history of `tipover`'s
//! timed runs (`--dynamic`, `--rolling`: the rows of `--out`), the friction map of
//! `tipover --grid`, the T-bar studies (`tbar --loop-study`, `tbar --mass-sweep`), the
//! per-sample history of `tbar roll`'s first T-bar run, the exports (`export mjcf`, `json`,
//! `schema`) and the project's figures (`figures --only N`) — each through the library call
//! the CLI makes, its values handed back as the engine's values or f64 columns (no text).

use crate::errors::Failure;
use std::path::Path;
use tbar_wheel::roll::{TbarRollRequest, Watch};
use tensegrity_core::budget::Limits;
use tensegrity_core::request::{Categorized, Category, InvalidParameter, Request};
use tensegrity_engine::value::{to_value, Map, Value};
use tensegrity_engine::SceneSource;
use tensegrity_io::figure::RenderOptions;
use tensegrity_io::sink::{CsvSink, FigureSink, RollingOutputs};
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};

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
/// (under `strict`, one that is not valid is an error) and its history, the rows of `--out`.
pub fn tipover(rolling: bool, values: Map<String, Value>) -> Result<(Value, Rows), Failure> {
    if rolling {
        let req = TipoverRollingRequest::from_values(values).map_err(|e| Failure::invalid(&e))?;
        let r = req
            .run()
            .map_err(|e| failed(&e, "rolling lean run failed"))?;
        let rows = r
            .samples
            .iter()
            .flat_map(|s| [s.t, s.lean, s.downhill, s.across])
            .collect();
        Ok((json(&r)?, rows))
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
        Ok((json(&r)?, rows))
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
pub fn tbar_roll(request: TbarRollRequest) -> (Result<Value, Failure>, Vec<[f64; 9]>) {
    let mut history = crate::runs::History::new(RollingOutputs::new(None, None), None);
    let watch = Watch {
        times: &[],
        observer: &mut history,
    };
    let report = tensegrity_engine::tbar_roll::report_watched(&request, Some(watch))
        .map_err(|e| failed(&e, ""))
        .and_then(|r| {
            tensegrity_engine::tbar_roll::strict_check(&request, &r).map_err(|e| failed(&e, ""))?;
            json(&r)
        });
    (report, history.take_rows())
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
