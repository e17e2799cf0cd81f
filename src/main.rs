//! The `tensegrity` command-line tool.

mod cli;

use clap::{Parser, Subcommand};

/// Tensegrity mechanics: statics, sizing and more, from scene files or built-in models.
#[derive(Parser, Debug)]
#[command(name = "tensegrity", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the bundled examples (scene statics, toroid wheel) on built-in defaults.
    Demo,
    /// Equilibrium matrix, self-stress, prestressability, load solve and sizing of a scene.
    Statics(cli::statics::StaticsArgs),
    /// Build and analyse the 3-bar-prism tensegrity toroid (counts, prestress, flexes, inertia).
    Toroid(cli::toroid::ToroidArgs),
    /// Roll the toroid wheel down an incline (reduced rigid model).
    Roll(cli::toroid::RollArgs),
    /// Tip-over of the toroid wheel under a lateral force, or the friction map of Fig. 3.13.
    Tipover(cli::toroid::TipoverArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Demo => cli::demo::run(),
        Command::Statics(args) => cli::statics::run(args),
        Command::Toroid(args) => cli::toroid::run_toroid(args),
        Command::Roll(args) => cli::toroid::run_roll(args),
        Command::Tipover(args) => cli::toroid::run_tipover(args),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
