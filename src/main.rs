//! The `tensegrity` command-line tool.

mod cli;

use clap::{Parser, Subcommand};

/// Tensegrity mechanics: statics, sizing and more, from scene files or built-in models.
#[derive(Parser, Debug)]
#[command(name = "tensegrity", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Resource limits of every command (estimated before any work).
    #[command(flatten)]
    limits: cli::guard::LimitArgs,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run the bundled examples (scene statics, toroid wheel) on built-in defaults.
    Demo(cli::demo::DemoArgs),
    /// Equilibrium matrix, self-stress, prestressability, load solve and sizing of a scene.
    Statics(cli::statics::StaticsArgs),
    /// Simulate a scene in time (rigid-bar dynamics; RK4, adaptive RK45 or RATTLE).
    Simulate(cli::simulate::SimulateArgs),
    /// Form-finding: the equilibrium geometry and prestress of a topology file or a built-in
    /// form (force density, adaptive, dynamic relaxation), written as a scene.
    Formfind(cli::formfind::FormfindArgs),
    /// Inverse form-finding: the force densities whose form best meets a design file's goals
    /// (positions, shape, lengths, forces, reactions, load path, smoothness), by L-BFGS-B on
    /// the exact gradient.
    Design(cli::design::DesignArgs),
    /// Benchmarks: the work–precision report of the integrators; `bench anchors`, the anchor
    /// scenes and the scaling series.
    Bench(cli::bench::BenchArgs),
    /// Discrete Michell truss (planar, cylindrical δ or spherical ε): nodes, forces, sizing.
    Michell(cli::michell::MichellArgs),
    /// Fig. 4.18: Michell truss mass against complexity, planar and δ = 0.1, 0.25, 0.5 (CSV).
    MichellTable(cli::michell::MichellTableArgs),
    /// Build and analyse the 3-bar-prism tensegrity toroid (counts, prestress, flexes, inertia).
    Toroid(cli::toroid::ToroidArgs),
    /// Roll the toroid wheel down an incline (rigid or full model, with validity).
    Roll(cli::roll::RollArgs),
    /// Thesis Figs. 3.10 and 3.11: axle height and reactions of wheels rolling down 50° (SVG).
    FigRolling(cli::fig_rolling::FigRollingArgs),
    /// Tip-over of the toroid wheel under a lateral force, or the friction map of Fig. 3.13.
    Tipover(cli::tipover::TipoverArgs),
    /// T-bar tread or wheel (thesis ch. 5): geometry, statics, omnidirectional load envelope,
    /// mass; `tbar roll`: rolling and tip-over.
    Tbar(cli::tbar::TbarArgs),
    /// Parameter sweeps from a TOML spec to CSV (parallel, resumable, shardable), and
    /// `sweep merge` of shard files.
    Sweep(cli::sweep::SweepArgs),
    /// Regenerate every figure of the thesis the project computes (SVG, one per figure).
    Figures(cli::figures::FiguresArgs),
    /// Load path of a scene: elastic bars, tension-only strings, large displacements, through
    /// limit points (arc length) or in load steps, with a stability verdict at every point.
    Solve(cli::solve::SolveArgs),
    /// Another code's model as a scene: `import motes`, MOTES's or TsgFEM's matrices N, C_b,
    /// C_s (text or CSV); `import ntrt`, an NTRT YAML model.
    Import(cli::import::ImportArgs),
    /// A scene as another code's model file: `export mjcf`, MuJoCo's MJCF (bars as bodies
    /// with free joints, strings as spatial tendons with a slack dead band).
    Export(cli::export::ExportArgs),
}

fn main() {
    quiet_on_broken_pipe();
    let cli = parse();
    cli::guard::init(&cli.limits);
    cli::exit::install_interrupt_handler();
    let result = match &cli.command {
        Command::Demo(args) => cli::demo::run(args),
        Command::Statics(args) => cli::statics::run(args),
        Command::Simulate(args) => cli::simulate::run(args),
        Command::Formfind(args) => cli::formfind::run(args),
        Command::Design(args) => cli::design::run(args),
        Command::Bench(args) => cli::bench::run(args),
        Command::Michell(args) => cli::michell::run(args),
        Command::MichellTable(args) => cli::michell::run_table(args),
        Command::Toroid(args) => cli::toroid::run_toroid(args),
        Command::Roll(args) => cli::roll::run_roll(args),
        Command::Tipover(args) => cli::tipover::run_tipover(args),
        Command::FigRolling(args) => cli::fig_rolling::run(args),
        Command::Tbar(args) => cli::tbar::run(args),
        Command::Sweep(args) => cli::sweep::run(args),
        Command::Figures(args) => cli::figures::run(args),
        Command::Solve(args) => cli::solve::run(args),
        Command::Import(args) => cli::import::run(args),
        Command::Export(args) => cli::export::run(args),
    };
    if let Err(e) = result {
        let code = cli::exit::code(&e);
        if code != 0 {
            eprintln!("error: {}", cli::exit::message(&e));
        }
        std::process::exit(code);
    }
}

/// Parses the command line; every subcommand takes negative numbers as values
/// (`--outer-radius -1` is a bad value, not an unknown flag).
fn parse() -> Cli {
    use clap::{CommandFactory, FromArgMatches};
    let command = Cli::command().mut_subcommands(|c| c.allow_negative_numbers(true));
    let matches = command.get_matches();
    Cli::from_arg_matches(&matches).unwrap_or_else(|e| e.exit())
}

/// `tensegrity ... | head` closes stdout early: end quietly instead of panicking.
fn quiet_on_broken_pipe() {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .unwrap_or("");
        if message.contains("Broken pipe") {
            std::process::exit(0);
        }
        default_hook(info);
    }));
}
