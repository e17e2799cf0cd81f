//! Subcommands of the `tensegrity` binary: argument parsing and output only, no mechanics.

pub mod bench;
pub mod demo;
pub mod exit;
pub mod fig_rolling;
pub mod figure_args;
pub mod figures;
pub mod formfind;
pub mod guard;
pub mod michell;
pub mod michell_optimize;
pub mod michell_text;
pub mod output;
pub mod request_args;
pub mod roll;
pub mod simulate;
pub mod spell;
pub mod statics;
pub mod sweep;
pub mod tbar;
pub mod tbar_mass;
pub mod tbar_roll;
pub mod tipover;
pub mod tipover_dynamic;
pub mod toroid;
pub mod values;
