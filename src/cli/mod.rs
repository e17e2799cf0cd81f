//! Subcommands of the `tensegrity` binary: argument parsing and output only, no mechanics.

pub mod angle;
pub mod bench;
pub mod demo;
pub mod exit;
pub mod guard;
pub mod michell;
pub mod roll;
pub mod simulate;
pub mod statics;
pub mod stream;
pub mod sweep;
pub mod tbar;
pub mod tipover;
pub mod toroid;
pub mod values;
