//! The entries of the registry: one line per command (the library call; its report's type
//! gives the result columns, [`crate::registry::Columns`]), built
//! once into the table that [`commands`] returns and [`command`] searches by name.

use crate::registry::{entry, entry_in, estimated, estimated_in, Command};
use michell3d::{MichellOptimizeRequest, MichellRequest, MichellTableRequest};
use std::sync::OnceLock;
use tbar_wheel::TbarStaticRequest;
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};

/// Every command.
pub(crate) fn all() -> Vec<Command> {
    vec![
        estimated(toroid::toroid_report),
        estimated(toroid::roll),
        entry(toroid::tipover_report),
        estimated(TipoverDynamicRequest::run),
        estimated(TipoverRollingRequest::run).alias(&["lean"]),
        entry(MichellRequest::run),
        estimated(MichellOptimizeRequest::run),
        estimated(MichellTableRequest::run),
        entry_in(crate::integrators::point),
        estimated(TbarStaticRequest::run),
        estimated(crate::tbar_roll::tbar_roll),
        estimated_in(crate::statics::statics_in),
        estimated(crate::simulate::simulate),
        entry(crate::bench::work_precision),
        estimated(crate::formfind::formfind),
        entry(crate::design::design),
        estimated_in(crate::solve::solve_in),
    ]
}

/// Every command (built once).
pub fn commands() -> &'static [Command] {
    static REGISTRY: OnceLock<Vec<Command>> = OnceLock::new();
    REGISTRY.get_or_init(all)
}

/// The command of that name or alias.
pub fn command(name: &str) -> Option<&'static Command> {
    commands()
        .iter()
        .find(|c| c.name == name || c.aliases.contains(&name))
}

/// The names of every command, comma-separated (for messages).
pub fn names() -> String {
    let names: Vec<&str> = commands().iter().map(|c| c.name).collect();
    names.join(", ")
}
