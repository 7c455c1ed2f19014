//! `dlw estimator-config DESIGN --gauge-factor GF --r0-ohm R0 [--divider-ohm RK] [--supply-v V]
//! -o FILE`.

use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::design::Design;
use dlw::output::write_atomic;
use dlw::replay::{config_text, ConfigFormat};
use dlw_estimator::{
    EstimatorConfig, JointConfig, LinearModel, ModelConfig, SensorConfig, DEFAULT_DIVIDER_OHM,
    DEFAULT_SUPPLY_V,
};
use dlw_geometry::{Divider, NotchStyle};

/// Arguments of `dlw estimator-config`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file with --joint.
    design: PathBuf,
    /// For a robot file: the joint (1 = distal) whose own sensors the config is for. A robot's
    /// own estimator (all joints, the crosstalk matrix) is not written here yet.
    #[arg(long, value_name = "N")]
    joint: Option<usize>,
    /// Gauge factor GF of the linear model (Eq. 5), for every sensor unless --second-* is given.
    #[arg(long)]
    gauge_factor: f64,
    /// Unstrained resistance R0 (Ω).
    #[arg(long)]
    r0_ohm: f64,
    /// Divider's fixed resistor R_k (Ω).
    #[arg(long, default_value_t = DEFAULT_DIVIDER_OHM)]
    divider_ohm: f64,
    /// Divider supply V+ (V).
    #[arg(long, default_value_t = DEFAULT_SUPPLY_V)]
    supply_v: f64,
    /// BSN only: sensor 2's gauge factor (default: --gauge-factor).
    #[arg(long)]
    second_gauge_factor: Option<f64>,
    /// BSN only: sensor 2's R0 (Ω) (default: --r0-ohm).
    #[arg(long)]
    second_r0_ohm: Option<f64>,
    /// BSN only: sensor 2's divider resistor (Ω) (default: --divider-ohm; the paper's bench
    /// used 102.5 kΩ).
    #[arg(long)]
    second_divider_ohm: Option<f64>,
    /// Output file: .toml or .json (the extension picks the format).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim(&args.output, [&args.design], args.force)?;
    let format = ConfigFormat::of(&args.output)?;
    let (design, robot_note) = if dlw::robot::is_robot_file(&args.design) {
        super::robot::joint_for_estimator(&args.design, args.joint)?
    } else {
        if args.joint.is_some() {
            bail!(
                "--joint picks a joint of a robot file, and {} is a joint design",
                args.design.display()
            );
        }
        (Design::load(&args.design)?, None)
    };
    let divider = Divider::new(args.divider_ohm, args.supply_v).context("divider")?;
    let joint = JointConfig::from_joint(&design.joint);
    let mut config =
        EstimatorConfig::nominal_linear(joint, args.gauge_factor, args.r0_ohm, divider)
            .context("linear model")?;
    let second_given = args.second_gauge_factor.is_some()
        || args.second_r0_ohm.is_some()
        || args.second_divider_ohm.is_some();
    match (design.joint.style(), second_given) {
        (NotchStyle::Uan, true) => bail!(
            "--second-* options need a BSN design, but {:?} is UAN with one sensor",
            design.file.name
        ),
        (NotchStyle::Bsn, true) => {
            let divider = Divider::new(
                args.second_divider_ohm.unwrap_or(args.divider_ohm),
                args.supply_v,
            )
            .context("sensor 2 divider")?;
            let model = LinearModel::new(
                args.second_gauge_factor.unwrap_or(args.gauge_factor),
                args.second_r0_ohm.unwrap_or(args.r0_ohm),
            )
            .context("sensor 2 linear model")?;
            config.second_sensor = Some(SensorConfig::new(divider, ModelConfig::Linear(model)));
            config.validate().context("sensor 2")?;
        }
        _ => {}
    }
    let mut note = format!(
        "Nominal linear estimator config for {} (design checksum {}),\nwritten by dlw estimator-config before any characterization.",
        design.file.name, design.checksum
    );
    if let Some(extra) = robot_note {
        note.push('\n');
        note.push_str(&extra);
    }
    let text = config_text(&config, format, &note)?;
    write_atomic(&args.output, text.as_bytes())?;
    println!(
        "wrote {}: linear model, GF {}, R0 {} Ω, {} sensor(s), divider {} Ω at {} V",
        args.output.display(),
        args.gauge_factor,
        args.r0_ohm,
        config.sensor_count(),
        args.divider_ohm,
        args.supply_v
    );
    Ok(())
}
