//! Command-line flags from the request descriptions ([`Param`]): [`RequestArgs`] builds one
//! `--kebab-name` flag per parameter of a request (help = the parameter's help, unit and
//! `[default: …]` from the request's [`Default`]; a [`Kind::Flag`] is a switch (one whose
//! default is true is written negated, `--no-name`, and sets it false), a
//! [`Kind::Choice`] lists its values, a list is comma-separated), collects only the values
//! given on the command line and hands them to [`Request::from_values`]. A bad value is a
//! usage error (exit 2) naming the flag ([`flag_of`]: the one place where a library's
//! parameter name becomes a flag).
//!
//! A parameter named in [`POSITIONAL`] (the scene of `statics` and `simulate`) is the
//! command's positional argument (`tensegrity statics SCENE.toml`) instead of a flag.
//!
//! A command with several modes (`tipover`, `--dynamic`, `--rolling`) takes the flags of
//! several requests at once ([`Modes`]): each value is checked by its kind while parsing, and
//! the chosen mode's request is built afterwards ([`RequestArgs::request`]).

use clap::builder::PossibleValuesParser;
use clap::error::ErrorKind;
use clap::parser::ValueSource;
use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches};
use serde_json::{Map, Value};
use std::marker::PhantomData;
use tensegrity_core::request::{InvalidParameter, Kind, Param, Request};

/// The parameters taken by position rather than as a flag (first the first).
pub const POSITIONAL: &[&str] = &["scene", "topology", "design"];

pub use tensegrity_engine::spelling::flag_of;

/// The message of a bad flag value: the flag, then the library's parameter error.
pub fn usage_message(e: &InvalidParameter) -> String {
    format!("invalid value for {}: {e}", flag_of(&e.name))
}

/// A bad flag value as the command's error (exit code 2).
pub fn usage(e: InvalidParameter) -> anyhow::Error {
    let message = usage_message(&e);
    anyhow::Error::new(e).context(message)
}

/// The parameters a command takes flags for: one request's, or several requests' ([`Modes`]).
pub trait Flags {
    /// The parameters, each name once.
    fn params() -> Vec<Param>;
    /// Their defaults.
    fn defaults() -> Map<String, Value>;
    /// Checks the values given, while parsing.
    fn check(given: &Map<String, Value>) -> Result<(), InvalidParameter>;
}

impl<R: Request> Flags for R {
    fn params() -> Vec<Param> {
        R::params()
    }

    fn defaults() -> Map<String, Value> {
        R::defaults()
    }

    /// The whole request: every rule, and its cross-field check.
    fn check(given: &Map<String, Value>) -> Result<(), InvalidParameter> {
        R::from_values(given.clone()).map(|_| ())
    }
}

/// The flags of the requests `A`, `B`, `C` on one command (the first description of a name
/// wins); each value is checked by its kind while parsing.
#[derive(Debug)]
pub struct Modes<A, B, C>(PhantomData<(A, B, C)>);

impl<A: Request, B: Request, C: Request> Flags for Modes<A, B, C> {
    fn params() -> Vec<Param> {
        let mut all: Vec<Param> = A::params();
        for p in B::params().into_iter().chain(C::params()) {
            if !all.iter().any(|q| q.name == p.name) {
                all.push(p);
            }
        }
        all
    }

    fn defaults() -> Map<String, Value> {
        let mut all = C::defaults();
        all.extend(B::defaults());
        all.extend(A::defaults());
        all
    }

    fn check(given: &Map<String, Value>) -> Result<(), InvalidParameter> {
        let params = Self::params();
        for (name, v) in given {
            if let Some(p) = params.iter().find(|p| p.name == name) {
                p.check(&p.normalize(v)?)?;
            }
        }
        Ok(())
    }
}

/// The request flags of a command: what the command line gave, by parameter name.
#[derive(Debug, Clone)]
pub struct RequestArgs<F> {
    given: Map<String, Value>,
    _flags: PhantomData<fn() -> F>,
}

impl<F: Flags> RequestArgs<F> {
    /// Whether the field `name` was given on the command line (at any value, its default's
    /// included).
    pub fn given(&self, name: &str) -> bool {
        self.given.contains_key(name)
    }

    /// The request of the given values over its defaults; a value of a flag that is not one
    /// of `R`'s (another mode's) or that `R` refuses is a usage error naming the flag.
    pub fn request<R: Request>(&self) -> anyhow::Result<R> {
        let params = R::params();
        if let Some((name, v)) = self
            .given
            .iter()
            .find(|(n, _)| !params.iter().any(|p| p.name == *n))
        {
            let reason = format!("does not apply to `{}`", R::NAME);
            return Err(usage(InvalidParameter::raw(name.clone(), v, reason)));
        }
        R::from_values(self.given.clone()).map_err(usage)
    }
}

impl<F: Flags> FromArgMatches for RequestArgs<F> {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Map::new();
        let defaults = F::defaults();
        for p in F::params() {
            if m.value_source(p.name) != Some(ValueSource::CommandLine) {
                continue;
            }
            let value = match p.kind {
                Kind::Flag => Value::Bool(!negated(&p, &defaults)),
                _ => Value::String(m.get_one::<String>(p.name).cloned().unwrap_or_default()),
            };
            given.insert(p.name.to_string(), value);
        }
        // a subcommand (`michell optimize`, `tbar roll`) takes its own flags
        if m.subcommand_name().is_none() {
            F::check(&given).map_err(|e| {
                clap::Error::raw(ErrorKind::ValueValidation, usage_message(&e) + "\n")
            })?;
        }
        Ok(Self {
            given,
            _flags: PhantomData,
        })
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}

impl<F: Flags> Args for RequestArgs<F> {
    fn augment_args(cmd: Command) -> Command {
        let defaults = F::defaults();
        let mut positional = 0;
        F::params().iter().fold(cmd, |c, p| {
            let index = POSITIONAL.contains(&p.name).then(|| {
                positional += 1;
                positional
            });
            c.arg(arg(p, defaults.get(p.name), index))
        })
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

/// Whether the switch of `p` is written negated (`--no-name`): a flag whose default is true.
fn negated(p: &Param, defaults: &Map<String, Value>) -> bool {
    p.kind == Kind::Flag && defaults.get(p.name) == Some(&Value::Bool(true))
}

/// The flag (or the positional argument at `index`, [`POSITIONAL`]) of one parameter.
fn arg(p: &Param, default: Option<&Value>, index: Option<usize>) -> Arg {
    let a = Arg::new(p.name).help(help(p, default)).required(p.required);
    let on_by_default = p.kind == Kind::Flag && default == Some(&Value::Bool(true));
    let a = match index {
        Some(i) => a.index(i),
        None if on_by_default => a
            .long(format!("no-{}", p.name.replace('_', "-")))
            .help(format!(
                "Skip this, which is on by default: {}",
                help(p, None)
            )),
        None => a.long(p.name.replace('_', "-")),
    };
    match p.kind {
        Kind::Flag => a.action(ArgAction::SetTrue),
        Kind::Choice(choices) => a
            .value_name(p.name.to_uppercase())
            .value_parser(PossibleValuesParser::new(choices.iter().copied())),
        Kind::Number | Kind::Angle | Kind::Numbers => a
            .value_name(p.name.to_uppercase())
            .allow_hyphen_values(true),
        _ => a.value_name(p.name.to_uppercase()),
    }
}

/// The help line: the parameter's help, its unit and its default.
fn help(p: &Param, default: Option<&Value>) -> String {
    let mut h = p.help.to_string();
    if !p.unit.is_empty() {
        h += &format!(" ({})", p.unit);
    }
    if p.kind == Kind::Angle {
        h += "; radians, or e.g. `30deg`, `pi/8`";
    }
    match default {
        Some(Value::Null) | None => {}
        Some(_) if p.kind == Kind::Flag => {}
        Some(v) => h += &format!(" [default: {}]", written(v)),
    }
    h
}

/// A default as the command line writes it.
fn written(v: &Value) -> String {
    match v {
        Value::String(s) => s.clone(),
        Value::Array(items) => items.iter().map(written).collect::<Vec<_>>().join(","),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::{CommandFactory, Parser};
    use toroid::{TipoverDynamicRequest, TipoverRequest, TipoverRollingRequest, ToroidRequest};

    #[derive(Parser, Debug)]
    struct One {
        #[command(flatten)]
        request: RequestArgs<ToroidRequest>,
    }

    #[derive(Parser, Debug)]
    struct Three {
        #[command(flatten)]
        request: RequestArgs<Modes<TipoverRequest, TipoverDynamicRequest, TipoverRollingRequest>>,
    }

    #[test]
    fn flags_are_the_parameters_and_only_given_values_are_kept() {
        let o = One::try_parse_from(["t", "--sides", "12", "--prism-only"]).unwrap();
        assert_eq!(o.request.given.len(), 2);
        let r: ToroidRequest = o.request.request().unwrap();
        assert_eq!((r.wheel.params.sides, r.prism_only), (12, true));
        assert_eq!(
            One::try_parse_from(["t"])
                .unwrap()
                .request
                .request::<ToroidRequest>()
                .unwrap(),
            ToroidRequest::default()
        );
        let e = One::try_parse_from(["t", "--outer-tread", "-1"]).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--outer-tread") && e.to_string().contains("must be"));
        assert!(One::try_parse_from(["t", "--bogus", "1"]).is_err());
        let help = One::command().render_help().to_string();
        assert!(
            help.contains("--rim-radius") && help.contains("[default: 0.8]"),
            "{help}"
        );
        assert_eq!(flag_of("t_end"), "--t-end");
    }

    #[test]
    fn modes_take_every_flag_once_and_build_the_chosen_request() {
        let t = Three::try_parse_from(["t", "--incline", "20deg", "--mu", "0.5"]).unwrap();
        let r: TipoverRollingRequest = t.request.request().unwrap();
        assert!((r.incline - 20f64.to_radians()).abs() < 1e-15);
        assert_eq!(r.mu, 0.5);
        let e = t.request.request::<TipoverRequest>().unwrap_err();
        assert!(format!("{e:#}").contains("--incline"), "{e:#}");
        assert!(Three::try_parse_from(["t", "--incline", "steep"]).is_err());
    }
}
