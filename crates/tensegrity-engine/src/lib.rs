//! # tensegrity-engine
//!
//! The one engine behind the three front ends (the command line, sweeps, Python): every
//! command of the toolkit as a request ([`tensegrity_core::request::Request`]: plain data
//! with defaults, one validation and one description per field) and one library call that
//! returns a `Serialize` report. Commands that compose several topology crates (the T-bar
//! wheel rolling beside the toroid of the same size) are composed here, since topology
//! crates never depend on each other.
#![warn(missing_docs)]

pub mod tbar_roll;
