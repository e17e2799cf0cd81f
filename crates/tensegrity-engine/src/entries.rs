//! The entries of the registry: one line per command (library call, result columns), built
//! once into the table that [`commands`] returns and [`command`] searches by name.

use crate::columns as c;
use crate::registry::{entry, entry_in, estimated, estimated_in, Command};
use michell3d::{MichellOptimizeRequest, MichellRequest, MichellTableRequest};
use std::sync::OnceLock;
use tbar_wheel::TbarStaticRequest;
use toroid::{TipoverDynamicRequest, TipoverRollingRequest};

/// Every command.
pub(crate) fn all() -> Vec<Command> {
    vec![
        estimated(toroid::toroid_report, &c::TOROID),
        estimated(toroid::roll, &c::ROLL),
        entry(toroid::tipover_report, &c::TIPOVER),
        estimated(TipoverDynamicRequest::run, &c::TIPOVER_DYNAMIC),
        estimated(TipoverRollingRequest::run, &c::TIPOVER_ROLLING).alias(&["lean"]),
        entry(MichellRequest::run, &c::MICHELL),
        estimated(MichellOptimizeRequest::run, &c::MICHELL_OPTIMIZE),
        estimated(MichellTableRequest::run, &c::MICHELL_TABLE),
        entry_in(crate::integrators::point, &c::INTEGRATORS),
        estimated(TbarStaticRequest::run, &c::TBAR),
        estimated(crate::tbar_roll::tbar_roll, &c::TBAR_ROLL),
        estimated_in(crate::statics::statics_in, &c::STATICS),
        estimated(crate::simulate::simulate, &c::SIMULATE),
        entry(crate::bench::work_precision, &c::BENCH_WORK_PRECISION),
        estimated(crate::formfind::formfind, &c::FORMFIND),
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
