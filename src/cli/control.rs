//! `dlw control --design D --config C [--scenario S] [--profile desired.csv | --protocol P]
//! [--gains kp,ki,kd] [--duration-s T] [--seed N] -o DIR [--json]`; with a robot file and a
//! robot config, every joint's loop on its estimated angle (`--profile` once or once per joint,
//! `--coupling`).

use super::written::Written;
use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::analysis::Analysis;
use dlw::control::robot::RobotControl;
use dlw::control::{Control, ControlResult, DesiredSource, Gains, RobotControlResult, PAPER_GAINS};
use dlw::design::Design;
use dlw::output::write_folder_atomic;
use dlw::replay::{load_config, load_robot_config};
use dlw::signal::FilterSpec;

use super::scenario_args::ScenarioArgs;
use super::simulate::CouplingArg;

/// Arguments of `dlw control`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (every joint's loop; then --config is the robot's).
    #[arg(long)]
    design: PathBuf,
    /// Estimator config (.toml or .json) the closed loop senses the angle with.
    #[arg(long)]
    config: PathBuf,
    /// For a robot: whether a distal tendon's tension bends the proximal joints it runs
    /// through (the York/Swaney moment, docs/robots.md). Default: york-swaney.
    #[arg(long, value_enum)]
    coupling: Option<CouplingArg>,
    #[command(flatten)]
    scenario: ScenarioArgs,
    /// Desired angle CSV with the header `time_s,angle_deg`, interpolated linearly. For a
    /// robot: once for every joint, or once per joint (joint 1, the distal one, first).
    #[arg(long, conflicts_with = "protocol")]
    profile: Vec<PathBuf>,
    /// PID gains `kp,ki,kd` on the angle error: kp in mm/°, ki in mm/(°·s), kd in mm·s/°
    /// (default: the paper's 0.1,0.1,0).
    #[arg(long, value_parser = parse_gains)]
    gains: Option<Gains>,
    /// Feed-forward slope m_t (°/mm); default: the scenario's plant gain (35.49 by default).
    #[arg(long)]
    mt_deg_per_mm: Option<f64>,
    /// Filter on the sensed angle, replacing the config's output_filter: none, ma:N or lp:T.
    #[arg(long)]
    filter: Option<FilterSpec>,
    #[command(flatten)]
    out: Written,
}

fn parse_gains(s: &str) -> Result<Gains, String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let [kp, ki, kd] = parts[..] else {
        return Err(format!(
            "gains {s:?} must be three numbers kp,ki,kd (e.g. 0.1,0.1,0)"
        ));
    };
    let num = |name: &str, v: &str| {
        v.parse::<f64>()
            .map_err(|_| format!("gain {name} = {v:?} is not a number"))
    };
    Ok(Gains {
        kp_mm_per_deg: num("kp", kp)?,
        ki_mm_per_deg_s: num("ki", ki)?,
        kd_mm_s_per_deg: num("kd", kd)?,
    })
}

pub fn run(args: Args) -> anyhow::Result<()> {
    args.out.claim_folder(
        dlw::robot::design_inputs(&args.design)
            .iter()
            .chain([&args.config])
            .chain(&args.scenario.scenario)
            .chain(&args.profile),
    )?;
    let robot = dlw::robot::is_robot_file(&args.design);
    if robot != dlw::replay::is_robot_config(&args.config) {
        bail!(
            "{} is {} but {} is {}: a robot takes the config dlw estimator-config ROBOT writes, a joint a joint's",
            args.design.display(),
            if robot { "a robot file" } else { "a joint design" },
            args.config.display(),
            if robot { "not a robot's config" } else { "a robot's config" }
        );
    }
    if robot {
        return run_robot(args);
    }
    if args.coupling.is_some() {
        bail!(
            "--coupling is for a robot's tendons, and {} is a joint design",
            args.design.display()
        );
    }
    if args.profile.len() > 1 {
        bail!(
            "--profile is given {} times; a joint takes one desired-angle profile",
            args.profile.len()
        );
    }
    let design = Design::load(&args.design)?;
    let mut config = load_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter.config();
    }
    let scenario = args.scenario.load()?;
    let source = match args.profile.into_iter().next() {
        Some(path) => DesiredSource::Csv(path),
        None => DesiredSource::Protocol,
    };
    let control = Control::new(
        &design,
        scenario,
        &source,
        config,
        args.gains.unwrap_or(PAPER_GAINS),
        args.mt_deg_per_mm,
    )?;
    let run = control
        .run()
        .with_context(|| format!("simulating control of {}", design.file.name))?;
    let mut result = ControlResult::new(control, run);
    let files = result.files();
    finish(
        &args.out,
        files,
        &mut result,
        ControlResult::written_to,
        |r| (r.warnings.clone(), r.summary()),
    )
}

/// `dlw control --design ROBOT --config ROBOT_CFG`: the output folder already claimed.
fn run_robot(args: Args) -> anyhow::Result<()> {
    let robot = super::robot::load(&args.design)?;
    let mut config = load_robot_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter.config();
    }
    let control = RobotControl::new(
        &robot,
        args.scenario.load()?,
        &args.profile,
        config,
        args.gains.unwrap_or(PAPER_GAINS),
        args.mt_deg_per_mm,
        CouplingArg::resolve(args.coupling),
    )
    .with_context(|| format!("controlling the robot {:?}", robot.robot.name))?;
    let run = control
        .run()
        .with_context(|| format!("simulating control of the robot {:?}", robot.robot.name))?;
    let mut result = RobotControlResult::new(control, run);
    let files = result.files();
    finish(
        &args.out,
        files,
        &mut result,
        RobotControlResult::written_to,
        |r| (r.warnings.clone(), r.summary()),
    )
}

/// Writes the report folder `-o` (its `files`, drawn), tells the result where, then prints it:
/// its JSON with `--json`, else its warnings on stderr and its summary.
fn finish<R: serde::Serialize>(
    out: &Written,
    files: Result<Vec<(String, Vec<u8>)>, dlw::report::ChartError>,
    result: &mut R,
    written_to: fn(&mut R, &std::path::Path),
    lines: fn(&R) -> (Vec<String>, String),
) -> anyhow::Result<()> {
    let files = files.context("drawing the report")?;
    write_folder_atomic(&out.output, &files)
        .with_context(|| format!("writing {}", out.output.display()))?;
    written_to(result, &out.output);
    if out.json {
        println!("{}", dlw::finite::to_json(result)?);
    } else {
        let (warnings, summary) = lines(result);
        super::print_warnings(&warnings);
        print!("{summary}");
    }
    Ok(())
}
