//! `dlw simulate --design D --protocol P [--scenario S.toml] [--seed N] [--duration-s T]
//! [--noise white|realistic] -o DIR`.

use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::design::Design;
use dlw::sim::robot::Coupling;
use dlw::sim::{self, Recording};

use super::scenario_args::ScenarioArgs;
use super::written::Output;

/// Arguments of `dlw simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file (every joint's tendon and sensors).
    #[arg(long)]
    design: PathBuf,
    /// For a robot: whether a distal tendon's tension bends the proximal joints it runs
    /// through (the York/Swaney moment, docs/robots.md). Default: york-swaney.
    #[arg(long, value_enum)]
    coupling: Option<CouplingArg>,
    #[command(flatten)]
    scenario: ScenarioArgs,
    /// `realistic` switches the correlated ADC and tracker noise on (`[adc.correlated]`,
    /// `[tracker.correlated]`, with the scenario's or the default parameters); `white` switches
    /// it off. Without the flag the scenario decides (default: white only).
    #[arg(long, value_enum)]
    noise: Option<NoisePreset>,
    /// Stroke profile CSV (`time_s,stroke_mm`) for `--protocol custom`.
    #[arg(long)]
    profile: Option<PathBuf>,
    #[command(flatten)]
    out: Output,
}

/// The `--coupling` choices.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum CouplingArg {
    /// Each joint's angle is its own plant's.
    None,
    /// A distal tendon's tension bends each proximal joint by its moment over its stiffness.
    YorkSwaney,
}

impl CouplingArg {
    /// The coupling of `--coupling`, York/Swaney without it.
    pub(crate) fn resolve(arg: Option<Self>) -> Coupling {
        match arg.unwrap_or(Self::YorkSwaney) {
            Self::None => Coupling::None,
            Self::YorkSwaney => Coupling::YorkSwaney,
        }
    }
}

/// The `--noise` presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum NoisePreset {
    /// White ADC and tracker noise only.
    White,
    /// White plus correlated (first-order autoregressive) ADC and tracker noise.
    Realistic,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    args.out.claim_folder(
        dlw::robot::design_inputs(&args.design)
            .iter()
            .chain(&args.scenario.scenario)
            .chain(&args.profile),
    )?;
    let mut scenario = args.scenario.load()?;
    if let Some(noise) = args.noise {
        scenario.set_correlated_noise(noise == NoisePreset::Realistic);
    }
    if dlw::robot::is_robot_file(&args.design) {
        if args.profile.is_some() {
            bail!("--profile gives one joint's stroke; a robot's joints each follow the protocol with their own seed (docs/robots.md)");
        }
        let coupling = CouplingArg::resolve(args.coupling);
        return super::robot_sensing::simulate(
            &args.design,
            scenario,
            coupling,
            &args.out.output,
            args.out.force,
        );
    }
    if args.coupling.is_some() {
        bail!(
            "--coupling is for a robot's tendons, and {} is a joint design",
            args.design.display()
        );
    }
    let design = Design::load(&args.design)?;
    let plan = sim::plan(&design, scenario, args.profile)?;
    let run = plan
        .run()
        .with_context(|| format!("simulating {}", design.file.name))?;
    let summary = plan.summary(&run, &args.out.output);
    let recording = Recording {
        rig: plan.rig(),
        samples: run.samples,
    };
    recording
        .write(&args.out.output, args.out.force)
        .with_context(|| format!("writing recording {}", args.out.output.display()))?;
    print!("{summary}");
    Ok(())
}
