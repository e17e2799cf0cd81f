//! The command registry: every command that takes a request, by name (the sweep study of the
//! same name), with its parameters ([`tensegrity_core::request::Params::params`]), the scalar result columns of its
//! report and a `run` from named JSON values to the report as JSON:
//!
//! > values → [`Request::from_values`] → the library call → `serde_json::to_value`.
//!
//! An entry is one line: [`entry`] takes the library call (any `fn(&R) -> Result<T, E>` with
//! `R: Request`, `T: Serialize + Columns`: the command's result columns are the report's
//! [`Columns`]), [`entry_in`] one that shares the sweep's [`Context`], and
//! [`estimated`] one whose request has a resource estimate ([`Estimated`]): the command's
//! [`Command::estimate`] on named values, which a front end checks against its limits before
//! the run (the sweeps before every case).
//!
//! ```
//! let c = tensegrity_engine::command("tipover").unwrap();
//! assert!(c.param("sigma").is_some());
//! let values = serde_json::json!({"sides": 16}).as_object().unwrap().clone();
//! let report = c.run(values, &Default::default()).unwrap();
//! assert!(report["critical_lateral_force"].as_f64().unwrap() > 0.0);
//! assert_eq!(tensegrity_engine::command("lean").unwrap().name, "tipover_rolling");
//! ```

use crate::context::Context;
pub use crate::entries::{command, commands, names};
use crate::estimate::Estimated;
pub use crate::run_error::RunError;
use serde::Serialize;
use serde_json::{Map, Value};
use std::fmt::Display;
use tensegrity_core::budget::Estimate;
pub use tensegrity_core::columns::{col, Column, Columns};
use tensegrity_core::request::{Categorized, Param, Request};

type RunFn = Box<dyn Fn(Map<String, Value>, &Context) -> Result<Value, RunError> + Send + Sync>;
type EstimateFn =
    Box<dyn Fn(Map<String, Value>) -> Result<Option<Estimate>, RunError> + Send + Sync>;

/// One command of the registry.
pub struct Command {
    /// The command's and the sweep study's name (`toroid`, `tipover_dynamic`, …).
    pub name: &'static str,
    /// Other names a sweep spec may give (`lean` for `tipover_rolling`).
    pub aliases: &'static [&'static str],
    /// The scalar result columns of the report, in its key order: the report type's
    /// [`Columns`], declared on its fields (`#[derive(Columns)]`).
    pub columns: &'static [Column],
    params: fn() -> Vec<Param>,
    defaults: fn() -> Map<String, Value>,
    run: RunFn,
    estimate: Option<EstimateFn>,
}

impl std::fmt::Debug for Command {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Command").field("name", &self.name).finish()
    }
}

impl Command {
    /// The request's parameters, in the order front ends list them.
    pub fn params(&self) -> Vec<Param> {
        (self.params)()
    }

    /// The parameter of that name.
    pub fn param(&self, name: &str) -> Option<Param> {
        self.params().into_iter().find(|p| p.name == name)
    }

    /// The default of every parameter (`null` where it has none).
    pub fn defaults(&self) -> Map<String, Value> {
        (self.defaults)()
    }

    /// Runs the command on named values (over the request's defaults): the report as JSON,
    /// with the conventional keys ([`crate::keys`]).
    pub fn run(&self, values: Map<String, Value>, ctx: &Context) -> Result<Value, RunError> {
        (self.run)(values, ctx).map(crate::keys::conventional)
    }

    /// The resource estimate of a run on named values (over the request's defaults); `None`
    /// for a command without one ([`crate::estimate`]).
    pub fn estimate(&self, values: Map<String, Value>) -> Result<Option<Estimate>, RunError> {
        match &self.estimate {
            Some(estimate) => estimate(values),
            None => Ok(None),
        }
    }

    /// The same command, also known by `aliases`.
    pub fn alias(self, aliases: &'static [&'static str]) -> Self {
        Self { aliases, ..self }
    }

    fn of<R: Request>(columns: &'static [Column], run: RunFn) -> Self {
        Self {
            name: R::NAME,
            aliases: &[],
            columns,
            params: R::params,
            defaults: R::defaults,
            run,
            estimate: None,
        }
    }
}

fn json<T: Serialize, E: Display + Categorized>(r: Result<T, E>) -> Result<Value, RunError> {
    let report = r.map_err(|e| RunError::of(&e))?;
    serde_json::to_value(&report)
        .map_err(|e| RunError::Failed(format!("the report does not serialise: {e}")))
}

/// The entry of the library call `run` of request `R`.
pub fn entry<R, T, E>(run: fn(&R) -> Result<T, E>) -> Command
where
    R: Request,
    T: Serialize + Columns + 'static,
    E: Display + Categorized + 'static,
{
    Command::of::<R>(
        T::columns(),
        Box::new(move |values, _| json(run(&R::from_values(values)?))),
    )
}

/// The entry of the library call `run` of request `R`, with `R`'s resource estimate.
pub fn estimated<R, T, E>(run: fn(&R) -> Result<T, E>) -> Command
where
    R: Estimated,
    T: Serialize + Columns + 'static,
    E: Display + Categorized + 'static,
{
    Command {
        estimate: Some(Box::new(|values| R::from_values(values)?.estimate())),
        ..entry(run)
    }
}

/// The entry of a library call that reads the sweep's [`Context`] (its limits, its shared
/// reference runs), with `R`'s resource estimate.
pub fn estimated_in<R, T, E>(run: fn(&R, &Context) -> Result<T, E>) -> Command
where
    R: Estimated,
    T: Serialize + Columns + 'static,
    E: Display + Categorized + 'static,
{
    Command {
        estimate: Some(Box::new(|values| R::from_values(values)?.estimate())),
        ..entry_in(run)
    }
}

/// The entry of a library call that shares what the cases of a sweep share ([`Context`]).
pub fn entry_in<R, T, E>(run: fn(&R, &Context) -> Result<T, E>) -> Command
where
    R: Request,
    T: Serialize + Columns + 'static,
    E: Display + Categorized + 'static,
{
    Command::of::<R>(
        T::columns(),
        Box::new(move |values, ctx| json(run(&R::from_values(values)?, ctx))),
    )
}
