//! The commands: the engine's registry described for Python, and runs of it — every command
//! through [`tensegrity_engine::Command::run`] (as a sweep runs it), after its estimate is
//! checked against the limits (as the CLI's guard does); `simulate` and `roll` through the
//! same library calls as the CLI with an observer that keeps the samples and stops on the
//! interrupt flag; sweeps through [`sweeps::run`].

use crate::errors::Failure;
use tensegrity_core::budget::Limits;
use tensegrity_core::request::{Category, InvalidParameter, Kind, Param};
use tensegrity_engine::value::{json, Map, Value};
use tensegrity_engine::{command, Command, Context};

/// The registry as the engine's value tree: per command its name, aliases, parameters (name, kind, choices,
/// unit, help, rule, optional, required, default) and result columns.
pub fn describe() -> Value {
    let commands: Vec<Value> = tensegrity_engine::commands()
        .iter()
        .map(|c| {
            let defaults = c.defaults();
            let params: Vec<Value> = c
                .params()
                .iter()
                .map(|p| describe_param(p, defaults.get(p.name)))
                .collect();
            let columns: Vec<Value> = c
                .columns
                .iter()
                .map(|col| json!({"name": col.name, "unit": col.unit}))
                .collect();
            json!({"name": c.name, "aliases": c.aliases, "params": params, "columns": columns})
        })
        .collect();
    Value::Array(commands)
}

fn describe_param(p: &Param, default: Option<&Value>) -> Value {
    let (kind, choices): (&str, &[&str]) = match p.kind {
        Kind::Count => ("count", &[]),
        Kind::Number => ("number", &[]),
        Kind::Angle => ("angle", &[]),
        Kind::Flag => ("flag", &[]),
        Kind::Choice(c) => ("choice", c),
        Kind::Text => ("text", &[]),
        Kind::Counts => ("counts", &[]),
        Kind::Numbers => ("numbers", &[]),
    };
    json!({
        "name": p.name,
        "kind": kind,
        "choices": choices,
        "unit": p.unit,
        "help": p.help,
        "rule": p.rule.describe(),
        "optional": p.optional,
        "required": p.required,
        "default": default.cloned().unwrap_or(Value::Null),
    })
}

/// The command of `name`, or an input error listing the known ones.
pub fn find(name: &str) -> Result<&'static Command, Failure> {
    command(name).ok_or_else(|| {
        Failure::new(
            Category::Input,
            format!(
                "no command `{name}` (known: {})",
                tensegrity_engine::registry::names()
            ),
        )
    })
}

/// The limits of a call: the process's defaults, each replaced by the value given (`null`:
/// the default; a size may be written as the CLI's flags take it, `500M`, `16Gi`).
pub fn limits(given: &Map<String, Value>) -> Result<Limits, Failure> {
    let mut l = tensegrity_engine::limits::for_this_process();
    let size = |name: &str, v: &Value| -> Result<Option<f64>, Failure> {
        let bad =
            |reason: String| Failure::invalid(&InvalidParameter::raw(name.to_string(), v, reason));
        match v {
            Value::Null => Ok(None),
            Value::Number(n) => match n.as_f64() {
                Some(x) if x > 0.0 && x.is_finite() => Ok(Some(x)),
                _ => Err(bad("must be finite and positive".into())),
            },
            Value::String(s) => tensegrity_engine::limits::parse_size(s)
                .map(Some)
                .map_err(|e| bad(e.to_string())),
            _ => Err(bad("expected a number or a size such as 500M".into())),
        }
    };
    for (name, v) in given {
        let x = size(name, v)?;
        match (name.as_str(), x) {
            (_, None) => {}
            ("max_memory", Some(x)) => l.memory_bytes = x,
            ("max_work", Some(x)) => l.work_s = x,
            ("max_output", Some(x)) => l.output_bytes = x,
            _ => {}
        }
    }
    Ok(l)
}

/// The given values of the request `c` when the call offers the flags of several requests
/// (`tipover`, with `dynamic`/`rolling`: the CLI's `Modes`): each value is checked by the kind
/// of the first description of its name, then a value that is not one of `c`'s parameters
/// is refused naming it (`does not apply to `tipover_dynamic``).
pub fn check_modes(
    c: &Command,
    modes: &[&Command],
    values: &Map<String, Value>,
) -> Result<(), Failure> {
    let mut all: Vec<Param> = Vec::new();
    for m in modes {
        for p in m.params() {
            if !all.iter().any(|q| q.name == p.name) {
                all.push(p);
            }
        }
    }
    for (name, v) in values {
        if let Some(p) = all.iter().find(|p| p.name == name) {
            p.normalize(v)
                .and_then(|x| p.check(&x))
                .map_err(|e| Failure::invalid(&e))?;
        }
    }
    let own = c.params();
    if let Some((name, v)) = values
        .iter()
        .find(|(n, _)| !own.iter().any(|p| p.name == *n))
    {
        let reason = format!("does not apply to `{}`", c.name);
        return Err(Failure::invalid(&InvalidParameter::raw(
            name.clone(),
            v,
            reason,
        )));
    }
    Ok(())
}

/// Checks the estimate of `c` on `values` against `limits` (the CLI's guard); a bad value
/// is refused here, before any work, as the run would refuse it. The estimated work (s), if
/// the command estimates one (what paces a progress report that cannot count).
pub fn admit(
    c: &Command,
    values: &Map<String, Value>,
    limits: &Limits,
) -> Result<Option<f64>, Failure> {
    let estimate = c.estimate(values.clone()).map_err(Failure::run)?;
    if let Some(e) = &estimate {
        limits
            .check(e)
            .map_err(|over| Failure::over_budget(&over))?;
    }
    Ok(estimate.map(|e| e.work_s))
}

/// The command line's context of a failed library call of `c` (`michell truss analysis
/// failed: …`), where it adds one.
pub fn context(c: &Command) -> &'static str {
    match c.name {
        "michell" => "michell truss analysis failed",
        "tipover_dynamic" => "dynamic tip-over run failed",
        "tipover_rolling" => "rolling lean run failed",
        "michell_optimize" => "Michell optimisation failed",
        _ => "",
    }
}

/// Runs `c` on `values` (after [`admit`]) within `limits`: the report.
pub fn run(
    c: &'static Command,
    values: Map<String, Value>,
    limits: Limits,
) -> Result<Value, Failure> {
    c.run(values, &Context::within(limits))
        .map_err(|e| Failure::run(e).context(context(c)))
}
