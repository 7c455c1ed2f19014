//! The command line: clap types describe it, each command lives in its own file with an
//! `Args` struct and a `run` function that resolves the arguments and calls the library.

use clap::{Parser, Subcommand};

mod build;
mod calibrate;
mod characterize;
mod control;
mod daq_info;
mod discover;
mod draw;
mod estimate;
mod estimator_config;
mod explore;
mod fit;
mod fluoro;
mod fluoro_render;
mod import_dxf;
mod import_recording;
mod inspect;
mod program;
mod reproduce;
mod robot;
mod robot_sensing;
mod scenario_args;
mod simulate;
mod written;

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
    /// Write the laser program (sensor, notches, parting in one setup) and its setup sheet.
    ///
    /// Writes the program file -o, and the setup sheet --sheet.
    Program(program::Args),
    /// Write everything for one joint into a folder: DXF, SVGs, laser program, setup sheet.
    ///
    /// Writes into the folder -o (which must not exist or be empty, unless --force): the DXF,
    /// the layout and section SVGs (one section per joint of a robot), the laser program and
    /// the setup sheet, named after the design file.
    Build(build::Args),
    /// Search a grid of designs for the Pareto front of a spec's objectives; write the best.
    ///
    /// Writes into the folder -o: designs.csv, front.csv, best-K.toml, report.html.
    Explore(explore::Args),
    /// Simulate the paper's bench and write a recording folder.
    ///
    /// Writes the recording folder -o (rig.toml, data.csv), which must not exist or be empty,
    /// unless --force.
    Simulate(simulate::Args),
    /// Write a nominal linear estimator config from a design's geometry.
    ///
    /// Writes the config -o: .toml or .json (the extension picks the format).
    EstimatorConfig(estimator_config::Args),
    /// Run the runtime estimator over a recording and report its error.
    ///
    /// Writes the estimates CSV -o (default: estimates.csv in the recording folder).
    Estimate(estimate::Args),
    /// Fit linear and PI sensor models to a recording and write an estimator config.
    ///
    /// Writes the config -o (.toml or .json), as `dlw estimate` and the runtime crate read it.
    Fit(fit::Args),
    /// Find where the simulator and a recording disagree, name the missing effect, add it.
    ///
    /// Writes into the folder -o: report.html, its SVGs and scenario.toml.
    Discover(discover::Args),
    /// Measure the joint angle in fluoroscopy frames (the phantom's ground truth).
    ///
    /// Writes the CSV -o: time_s,angle_deg,raw_deg,area_px,axis_ratio,flags.
    Fluoro(fluoro::Args),
    /// Render synthetic fluoroscopy frames of a recording's angle, to try `dlw fluoro`.
    ///
    /// Writes the folder -o of PNG frames, which must not exist or be empty, unless --force.
    FluoroRender(fluoro_render::Args),
    /// Import a bench's DAQ export and EM-tracker log as one recording, clocks aligned.
    ///
    /// Writes the recording folder -o (rig.toml, data.csv), which must not exist or be empty,
    /// unless --force.
    ImportRecording(Box<import_recording::Args>),
    /// List what a DAQ file (TDMS, LVM, CSV) or a tracker log holds, before importing it.
    DaqInfo(daq_info::Args),
    /// Simulate open- and closed-loop control of a joint (Section IV-C, Table VI), or of each
    /// joint of a robot on its estimated angle.
    ///
    /// Writes into the folder -o: report.html, its SVG figures and control.csv.
    Control(control::Args),
    /// Run one of the paper's characterization analyses on a recording (Section IV-A, IV-B).
    ///
    /// Writes into the folder -o: report.html and its SVG figures.
    Characterize(characterize::Args),
    /// Run the paper's Section IV on the simulator: Tables III-VI beside the paper's.
    ///
    /// Writes into the folder -o: report.html and its SVG figures.
    Reproduce(reproduce::Args),
    /// Calibrate the simulated bench to the paper's Tables IV-VI: the twin `reproduce` runs.
    ///
    /// Writes into the folder -o: paper-bench.toml (the twin, one scenario per joint),
    /// calibration.json and evaluations.json; --json prints calibration.json.
    Calibrate(calibrate::Args),
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Inspect(args) => inspect::run(args),
        Command::Draw(args) => draw::run(args),
        Command::ImportDxf(args) => import_dxf::run(args),
        Command::Program(args) => program::run(args),
        Command::Build(args) => build::run(args),
        Command::Explore(args) => explore::run(args),
        Command::Simulate(args) => simulate::run(args),
        Command::EstimatorConfig(args) => estimator_config::run(args),
        Command::Estimate(args) => estimate::run(args),
        Command::Fit(args) => fit::run(args),
        Command::Discover(args) => discover::run(args),
        Command::Fluoro(args) => fluoro::run(args),
        Command::FluoroRender(args) => fluoro_render::run(args),
        Command::ImportRecording(args) => import_recording::run(*args),
        Command::DaqInfo(args) => daq_info::run(args),
        Command::Control(args) => control::run(args),
        Command::Characterize(args) => characterize::run(args),
        Command::Reproduce(args) => reproduce::run(args),
        Command::Calibrate(args) => calibrate::run(args),
    }
}

/// Prints each warning on stderr, as `warning: …`.
pub(crate) fn print_warnings<W: std::fmt::Display>(warnings: &[W]) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// A spinner on stderr for long work, hidden when stderr is not a terminal (tests, pipes).
pub(crate) fn spinner() -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.enable_steady_tick(std::time::Duration::from_millis(120));
        bar
    } else {
        indicatif::ProgressBar::hidden()
    }
}

/// `--order N`: the play count of the PI fits, checked by [`dlw::fit::PlayOrder::new`].
fn parse_order(s: &str) -> Result<dlw::fit::PlayOrder, String> {
    let n: usize = s
        .parse()
        .map_err(|_| format!("--order {s:?} is not a whole number of play operators"))?;
    dlw::fit::PlayOrder::new(n).map_err(|_| {
        format!(
            "--order {n} must lie between {} and {} play operators",
            dlw::fit::PlayOrder::MIN,
            dlw::fit::PlayOrder::MAX
        )
    })
}
