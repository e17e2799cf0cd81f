//! # tensegrity-engine
//!
//! The one engine behind the three front ends (the command line, sweeps, Python): every
//! command of the toolkit as a request ([`tensegrity_core::request::Request`]: plain data
//! with defaults, one validation and one description per field) and one library call that
//! returns a `Serialize` report. Commands that compose several topology crates (the T-bar
//! wheel rolling beside the toroid of the same size) are composed here, since topology
//! crates never depend on each other.
//!
//! The [`registry`] names every command that takes a request, with its parameters, the
//! scalar result columns of its report (the report type's
//! [`Columns`](tensegrity_core::columns::Columns), declared on its fields with
//! `#[derive(Columns)]` of `tensegrity-derive`) and a `run` from named JSON values to
//! the report as JSON; the sweeps run any of them as a study of the same name.
//!
//! | command (study) | request | library call |
//! |---|---|---|
//! | `toroid` | [`toroid::ToroidRequest`] | [`toroid::toroid_report`] |
//! | `roll` | [`toroid::RollRequest`] | [`toroid::roll()`] |
//! | `tipover` | [`toroid::TipoverRequest`] | [`toroid::tipover_report`] |
//! | `tipover_dynamic` | [`toroid::TipoverDynamicRequest`] | its `run` |
//! | `tipover_rolling` (alias `lean`) | [`toroid::TipoverRollingRequest`] | its `run` |
//! | `michell` | [`michell3d::MichellRequest`] | its `run` (extra strings resolved) |
//! | `michell_optimize` | [`michell3d::MichellOptimizeRequest`] | [`michell3d::optimize::optimize`] |
//! | `michell_table` | [`michell3d::MichellTableRequest`] | [`michell3d::mass_vs_complexity`] |
//! | `integrators` | [`integrators::IntegratorsRequest`] | [`integrators::point`] |
//! | `tbar` | [`tbar_wheel::TbarStaticRequest`] | [`tbar_wheel::tbar_report`] |
//! | `tbar_roll` | [`tbar_wheel::TbarRollRequest`] | [`tbar_roll::tbar_roll`] (the toroid column composed here) |
//! | `statics` | [`statics::StaticsCommand`] | [`statics::statics`] (a scene's statics report) |
//! | `simulate` | [`simulate::SimulateCommand`] | [`simulate::simulate`] (a scene run in time) |
//! | `solve` | [`solve::SolveCommand`] | [`solve::solve`] (a scene's load path, elastic, through limit points) |
//! | `formfind` | [`formfind::FormfindRequest`] | [`formfind::formfind`] (form-finding, then the rest lengths of the prestress) |
//! | `bench_work_precision` | [`bench::WorkPrecisionRequest`] | [`bench::work_precision()`] |
//!
//! Every command's resource estimate is here too ([`estimate`]: the [`estimate::Estimated`]
//! requests, and the grids front ends add), so every front end refuses the same requests;
//! the default limits and the sizes they are written in are in [`limits`].
#![warn(missing_docs)]

pub mod bench;
mod context;
pub mod design;
mod entries;
pub mod estimate;
pub mod exports;
pub mod formfind;
pub mod integrators;
pub mod keys;
pub mod limits;
pub mod registry;
mod run_error;
pub mod scene;
pub mod sensitivity;
pub mod simulate;
pub mod solve;
pub mod spelling;
pub mod statics;
pub mod tbar_roll;

/// The engine's data model of named values and reports: the tree every front end hands in
/// (`Request::from_values`) and gets back from a registry run. Front ends build and read it
/// natively (the Python package converts its objects to and from it, without text); it is
/// serde_json's value tree, re-exported so that a front end needs no serde_json of its own.
pub mod value {
    pub use serde_json::{from_value, json, to_value, Error, Map, Number, Value};
}

pub use estimate::Estimated;
pub use integrators::Context;
pub use registry::{
    col, command, commands, entry, entry_in, estimated, estimated_in, Column, Command, RunError,
};
pub use scene::{SceneError, SceneSource};

#[cfg(test)]
mod tests;

/// The README's example, run as a doc-test.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
