//! The command line: clap types describe it, each command lives in its own file with an
//! `Args` struct and a `run` function that resolves the arguments and calls the library.

use clap::{Parser, Subcommand};

mod estimate;
mod estimator_config;
mod inspect;
mod simulate;

/// From a sensing continuum-robot joint's design parameters to drawings, laser programs and a
/// working sensor.
#[derive(Debug, Parser)]
#[command(name = "dlw", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print a design's geometry and design-rule warnings.
    Inspect(inspect::Args),
    /// Simulate the paper's bench and write a recording folder.
    Simulate(simulate::Args),
    /// Write a nominal linear estimator config from a design's geometry.
    EstimatorConfig(estimator_config::Args),
    /// Run the runtime estimator over a recording and report its error.
    Estimate(estimate::Args),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Inspect(args) => inspect::run(args),
        Command::Simulate(args) => simulate::run(args),
        Command::EstimatorConfig(args) => estimator_config::run(args),
        Command::Estimate(args) => estimate::run(args),
    }
}
