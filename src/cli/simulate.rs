//! `dlw simulate --design D --protocol P [--scenario S.toml] [--seed N] [--duration-s T]
//! [--noise white|realistic] -o DIR`.

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
    /// Scenario file (TOML): which effects are on, with their parameters. Without one, only
    /// white ADC and EM-tracker noise are on.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// Seed of every random stream (noise, drift, the random pattern); overrides the scenario's.
    #[arg(long)]
    seed: Option<u64>,
    /// Recording length (s); defaults to the protocol's: 10 s at rest, then 1000 s
    /// characterization or 3000 s of the others; a CSV profile's last time.
    #[arg(long)]
    duration_s: Option<f64>,
    /// `realistic` switches the correlated ADC and tracker noise on (`[adc.correlated]`,
    /// `[tracker.correlated]`, with the scenario's or the default parameters); `white` switches
    /// it off. Without the flag the scenario decides (default: white only).
    #[arg(long, value_enum)]
    noise: Option<NoisePreset>,
    /// Stroke profile CSV (`time_s,stroke_mm`) for `--protocol custom`.
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Output recording folder (must not exist or be empty, unless --force).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
}

/// The `--noise` presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum NoisePreset {
    /// White ADC and tracker noise only.
    White,
    /// White plus correlated (first-order autoregressive) ADC and tracker noise.
    Realistic,
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
    dlw::output::claim(
        &args.output,
        std::iter::once(&args.design)
            .chain(&args.scenario)
            .chain(&args.profile),
        args.force,
    )?;
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
    if let Some(noise) = args.noise {
        scenario.set_correlated_noise(noise == NoisePreset::Realistic);
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
    let correlated = match (sc.adc.correlated.enabled, sc.tracker.correlated.enabled) {
        (true, true) => ", correlated ADC and tracker noise",
        (true, false) => ", correlated ADC noise",
        (false, true) => ", correlated tracker noise",
        (false, false) => "",
    };
    println!(
        "wrote {}: {} samples ({} s at {} Hz), {} protocol, seed {}{correlated}, peak angle {:.2}°",
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
