//! # sweeps
//!
//! Parameter studies over any command of the engine: a TOML spec names a study — a command of
//! [`tensegrity_engine::registry`] (`toroid`, `roll`, `tipover`, `tipover_dynamic`,
//! `tipover_rolling` alias `lean`, `michell`, `michell_optimize`, `michell_table`, `tbar`,
//! `integrators`) — fixed values, axes (lists, linear or logarithmic ranges) and derived rules
//! ([`spec`], [`expr`]), every name a field of the command's request
//! ([`tensegrity_core::request::Param`]); the cases — the Cartesian product of the axes, last
//! axis fastest, ids stable — run in parallel on a rayon pool, each through the registry's
//! `run` (the same request and library call as the single-point command: no per-field code
//! here, [`values`]), and their rows stream to a CSV in case order ([`run`], [`table`]), so
//! the file is the same byte for byte for any thread count, any split into shards
//! ([`Shard`], [`merge()`]) and any interruption finished with `resume`.
//!
//! Each row holds the scalars of the single-point report (`tensegrity toroid --json`, …) for
//! that case, numbers in their shortest round-trip form; a failing case is an `error` row
//! with its message and never stops the sweep. With resource limits ([`RunOptions::limits`])
//! a case whose estimate is over them is refused before it runs: an `error` row naming the
//! limit ([`limits`]).
//!
//! [`grids`] fans out the grid studies whose points are rows rather than whole reports (sign
//! maps, the Fig. 4.18 table, the Fig. 3.13 friction map) over the same rayon machinery.
//!
//! ```
//! use sweeps::{run, RunOptions, Silent, Spec};
//! let spec = Spec::parse(r#"
//!     study = "tipover"
//!     [axes]
//!     sigma = [0.3, 0.6]
//!     epsilon = { from = 0.25, to = 0.75, step = 0.25 }
//! "#)?;
//! assert_eq!(spec.case_count()?, 6);
//! let out = std::env::temp_dir().join(format!("sweeps-doc-{}.csv", std::process::id()));
//! let summary = run(&spec, &out, &RunOptions::default(), &mut Silent)?;
//! assert_eq!((summary.written, summary.errors), (6, 0));
//! let text = std::fs::read_to_string(&out).unwrap();
//! // each name once: the report's `sigma` and `epsilon` are the axes' columns
//! assert!(text.starts_with("case,sigma,epsilon,mass_kg,rho,cot_theta,"));
//! assert!(text.lines().nth(2).unwrap().starts_with("1,0.3,0.5,"));
//! # std::fs::remove_file(&out).unwrap();
//! # Ok::<(), sweeps::SweepError>(())
//! ```
#![warn(missing_docs)]

/// The angle parser of every front end ([`tensegrity_core::angle`]).
pub use tensegrity_core::angle;
pub mod case_error;
pub mod error;
pub mod expr;
pub mod grids;
pub mod limits;
pub mod merge;
mod resume;
pub mod run;
mod shard;
pub mod spec;
pub mod table;
pub mod values;

pub use case_error::CaseError;
pub use error::{Result, SweepError};
pub use merge::{merge, MergeSummary};
pub use run::{run, Progress, RunOptions, Shard, Silent, Summary, Threads};
pub use spec::{Spec, MAX_CASES};
pub use tensegrity_engine::{Column, Context};

/// A study: the registry's command of the spec's `study` name.
pub type Study = &'static tensegrity_engine::Command;
