//! `dlw simulate --design D --protocol P [--scenario S.toml] [--seed N] [--duration-s T] -o DIR`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::design::Design;
use dlw::sim::{self, ProtocolKind, Recording, Scenario};

/// Arguments of `dlw simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    #[arg(long)]
    design: PathBuf,
    /// Stroke profile: characterization, rate-dependence, relaxation, random, or custom (with
    /// --profile). Overrides the scenario's `protocol`.
    #[arg(long, value_parser = parse_protocol)]
    protocol: Option<ProtocolKind>,
    /// Scenario file (TOML): which effects are on, with their parameters. Without one, only ADC
    /// and EM-tracker noise are on.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Seed of every random stream (noise, drift, the random pattern); overrides the scenario's.
    #[arg(long)]
    seed: Option<u64>,
    /// Recording length (s); defaults to the protocol's (1000 s characterization, 3000 s the
    /// others, a CSV profile's last time).
    #[arg(long)]
    duration_s: Option<f64>,
    /// Stroke profile CSV (`time_s,stroke_mm`) for `--protocol custom`.
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Output recording folder (must not exist or be empty, unless --force).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output folder.
    #[arg(long)]
    force: bool,
}

pub(super) fn parse_protocol(s: &str) -> Result<ProtocolKind, String> {
    ProtocolKind::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = ProtocolKind::ALL.iter().map(|(_, n)| *n).collect();
        format!(
            "unknown protocol {s:?} (expected one of: {})",
            names.join(", ")
        )
    })
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let design = Design::load(&args.design)?;
    let mut scenario = match &args.scenario {
        Some(path) => Scenario::load(path)?,
        None => Scenario::default(),
    };
    if args.protocol.is_some() {
        scenario.protocol = args.protocol;
    }
    if let Some(seed) = args.seed {
        scenario.seed = seed;
    }
    if args.duration_s.is_some() {
        scenario.duration_s = args.duration_s;
    }
    let plan = sim::plan(&design, scenario, args.profile)?;
    let run = plan
        .run()
        .with_context(|| format!("simulating {}", design.file.name))?;
    let recording = Recording {
        rig: plan.rig(),
        samples: run.samples,
    };
    recording
        .write(&args.output, args.force)
        .with_context(|| format!("writing recording {}", args.output.display()))?;
    let sc = &plan.scenario;
    let peak_deg = run
        .true_angle_deg
        .iter()
        .fold(0.0f64, |m, a| m.max(a.abs()));
    println!(
        "wrote {}: {} samples ({} s at {} Hz), {} protocol, seed {}, peak angle {:.2}°",
        args.output.display(),
        plan.samples,
        sc.duration_s.unwrap_or(0.0),
        sc.sample_hz,
        sc.protocol.map_or("?", ProtocolKind::name),
        sc.seed,
        peak_deg
    );
    Ok(())
}
