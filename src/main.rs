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
    /// Run the statics of the bundled example scenes and print a summary.
    Demo,
    /// Equilibrium matrix, self-stress, prestressability, load solve and sizing of a scene.
    Statics(cli::statics::StaticsArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Demo => cli::demo::run(),
        Command::Statics(args) => cli::statics::run(args),
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
