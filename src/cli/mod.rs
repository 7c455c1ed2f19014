//! The command line: clap types describe it, each command lives in its own file with an
//! `Args` struct and a `run` function that resolves the arguments and calls the library.

use clap::{Parser, Subcommand};

mod draw;
mod import_dxf;
mod inspect;

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
    /// Draw a design: the unrolled layout as DXF and SVG, the cross-section as SVG.
    Draw(draw::Args),
    /// Read a DXF drawing in dlw's convention back and summarize it, with the design rules.
    ImportDxf(import_dxf::Args),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Inspect(args) => inspect::run(args),
        Command::Draw(args) => draw::run(args),
        Command::ImportDxf(args) => import_dxf::run(args),
    }
}
