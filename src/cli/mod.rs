//! Subcommands of the `tensegrity` binary: argument parsing and output only, no mechanics.

pub mod angle;
pub mod demo;
pub mod statics;
pub mod toroid;
