//! Subcommands of the `tensegrity` binary: argument parsing and output only, no mechanics.

pub mod demo;
pub mod statics;
