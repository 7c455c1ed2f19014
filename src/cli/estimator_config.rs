//! `dlw estimator-config DESIGN --gauge-factor GF --r0-ohm R0 [--divider-ohm RK] [--supply-v V]
//! -o FILE`.

use std::path::PathBuf;

use anyhow::bail;
use dlw::design::Design;
use dlw::output::write_atomic;
use dlw::replay::nominal::{nominal_config, nominal_note, NominalSensor};
use dlw::replay::{config_text, ConfigFormat};
use dlw::robot::estimator_config::joint_alone;
use dlw_estimator::{DEFAULT_DIVIDER_OHM, DEFAULT_SUPPLY_V};

use super::written::Output;

/// Arguments of `dlw estimator-config`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML), or a robot file with --joint.
    design: PathBuf,
    /// For a robot file: the joint (1 = distal) whose own sensors alone the config is for (a
    /// one-joint config). Without it a robot file gets the robot's own config: every joint, every
    /// sensor and the crosstalk matrix from the geometry.
    #[arg(long, value_name = "N")]
    joint: Option<usize>,
    /// Gauge factor GF of the linear model (Eq. 5). For a robot: once for every sensor, or once
    /// per sensor in `dlw inspect`'s order.
    #[arg(long, required = true)]
    gauge_factor: Vec<f64>,
    /// Unstrained resistance R0 (Ω). For a robot: once, or once per sensor.
    #[arg(long, required = true)]
    r0_ohm: Vec<f64>,
    /// Divider's fixed resistor R_k (Ω). Default 99.6 kΩ; for a robot: once, or once per sensor
    /// (default: 99.6 kΩ for each sensor 1, 102.5 kΩ for a BSN joint's sensor 2, as the
    /// simulator's bench).
    #[arg(long)]
    divider_ohm: Vec<f64>,
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
    #[command(flatten)]
    out: Output,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    args.out.claim(dlw::robot::design_inputs(&args.design))?;
    let format = ConfigFormat::of(&args.out.output)?;
    if dlw::robot::is_robot_file(&args.design) && args.joint.is_none() {
        if args.second_gauge_factor.is_some()
            || args.second_r0_ohm.is_some()
            || args.second_divider_ohm.is_some()
        {
            bail!("--second-* options set a BSN joint's sensor 2 in a joint's config; for a robot give --gauge-factor, --r0-ohm and --divider-ohm once per sensor, in dlw inspect's order");
        }
        return super::robot_sensing::estimator_config(
            &args.design,
            &args.gauge_factor,
            &args.r0_ohm,
            &args.divider_ohm,
            args.supply_v,
            &args.out.output,
            format,
        );
    }
    let (design, robot_note) = if dlw::robot::is_robot_file(&args.design) {
        let robot = super::robot::load(&args.design)?;
        let (design, note) = joint_alone(&robot, &args.design, args.joint)?;
        (design, Some(note))
    } else {
        if args.joint.is_some() {
            bail!(
                "--joint picks a joint of a robot file, and {} is a joint design",
                args.design.display()
            );
        }
        (Design::load(&args.design)?, None)
    };
    let one = |name: &str, v: &[f64], default: Option<f64>| {
        match (v, default) {
        ([x], _) => Ok(*x),
        ([], Some(d)) => Ok(d),
        _ => Err(anyhow::anyhow!(
            "--{name} is given {} times; a joint's config takes it once (the --second-* options set a BSN joint's sensor 2)",
            v.len()
        )),
    }
    };
    let first = NominalSensor {
        gauge_factor: one("gauge-factor", &args.gauge_factor, None)?,
        r0_ohm: one("r0-ohm", &args.r0_ohm, None)?,
        divider_ohm: one("divider-ohm", &args.divider_ohm, Some(DEFAULT_DIVIDER_OHM))?,
    };
    let second_given = args.second_gauge_factor.is_some()
        || args.second_r0_ohm.is_some()
        || args.second_divider_ohm.is_some();
    let second = second_given.then(|| NominalSensor {
        gauge_factor: args.second_gauge_factor.unwrap_or(first.gauge_factor),
        r0_ohm: args.second_r0_ohm.unwrap_or(first.r0_ohm),
        divider_ohm: args.second_divider_ohm.unwrap_or(first.divider_ohm),
    });
    let config = nominal_config(&design, first, second, args.supply_v)?;
    let note = nominal_note(&design, robot_note.as_deref());
    let text = config_text(&config, format, &note)?;
    write_atomic(&args.out.output, text.as_bytes())?;
    println!(
        "wrote {}: linear model, GF {}, R0 {} Ω, {} sensor(s), divider {} Ω at {} V",
        args.out.output.display(),
        first.gauge_factor,
        first.r0_ohm,
        config.sensor_count(),
        first.divider_ohm,
        args.supply_v
    );
    Ok(())
}
