//! `dlw estimate --config C DIR [--filter none|ma:N|lp:T] [--truth angles.csv] [--json]
//! [-o estimates.csv]`.

use std::path::PathBuf;

use anyhow::bail;
use dlw::analysis::Analysis;
use dlw::output::write_atomic;
use dlw::recording::{read_angles, Recording};
use dlw::replay::{estimate, load_config, EstimateRequest};
use dlw::signal::FilterSpec;

use super::written::DefaultedOutput;

/// The default estimates file, inside the recording folder.
const DEFAULT_OUTPUT: &str = "estimates.csv";

/// Arguments of `dlw estimate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Estimator config (.toml or .json), e.g. from `dlw estimator-config`.
    #[arg(long)]
    config: PathBuf,
    /// Recording folder (rig.toml + data.csv).
    recording: PathBuf,
    /// Filter on the estimated angle, replacing the config's output_filter: `none`, `ma:N`
    /// (moving average of N samples, delay (N−1)/2) or `lp:T` (first-order low-pass, time
    /// constant T samples, delay ≈ T).
    #[arg(long)]
    filter: Option<FilterSpec>,
    /// Print the report as JSON (keys rmse_deg, max_abs_error_deg, samples, …).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    out: DefaultedOutput,
    /// Ground truth from fluoroscopy (`dlw fluoro`'s angles.csv, or any CSV with time_s and
    /// angle_deg columns): the estimates are interpolated at its frame times and compared with
    /// it, in place of the tracker column, which may then be empty.
    #[arg(long)]
    truth: Option<PathBuf>,
    /// Decimal places of estimate_deg and error_deg in the CSV (0 to 15; 12 or more to compare
    /// with the C or Python estimator to 1e-9).
    #[arg(long, default_value_t = dlw::replay::ESTIMATE_DECIMALS, value_parser = parse_precision)]
    precision: u32,
    /// For a robot's config: write an HTML report into this folder (the shape over time as
    /// small multiples, estimated against tracked; each joint's error; the crosstalk undone).
    #[arg(long)]
    report: Option<PathBuf>,
    /// With --report: the robot file, whose geometric crosstalk matrix the report draws against
    /// the config's.
    #[arg(long, requires = "report")]
    design: Option<PathBuf>,
}

fn parse_precision(s: &str) -> Result<u32, String> {
    let max = dlw::replay::MAX_ESTIMATE_DECIMALS;
    match s.parse::<u32>() {
        Ok(n) if n <= max => Ok(n),
        _ => Err(format!(
            "precision {s:?} is not a number of decimals from 0 to {max}"
        )),
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    // A recording folder's own files are the input: estimates.csv written beside them by an
    // earlier run is an output, replaced with --force like any other.
    let recording_files = if args.recording.is_dir() {
        vec![
            args.recording.join(dlw::recording::DATA_FILE),
            args.recording.join(dlw::recording::RIG_FILE),
        ]
    } else {
        vec![args.recording.clone()]
    };
    let designs: Vec<std::path::PathBuf> = args
        .design
        .iter()
        .flat_map(|d| dlw::robot::design_inputs(d))
        .collect();
    let inputs = std::iter::once(&args.config)
        .chain(&recording_files)
        .chain(&args.truth)
        .chain(&designs);
    let out = args.out.or(|| args.recording.join(DEFAULT_OUTPUT));
    let report: Vec<&std::path::Path> = args.report.iter().map(|p| p.as_path()).collect();
    out.claim_with(&report, inputs)?;
    let output = out.output;
    if dlw::replay::is_robot_config(&args.config) {
        if args.truth.is_some() || args.filter.is_some() {
            bail!("--truth and --filter are for a joint's config; a robot's config sets its filters in the file (docs/robot-runtime.md)");
        }
        return super::robot_sensing::estimate(
            &args.config,
            &args.recording,
            &output,
            args.precision,
            args.json,
            args.report.as_deref(),
            args.design.as_deref(),
        );
    }
    if args.report.is_some() {
        bail!("--report is for a robot's config; a joint's estimates are reported by dlw fit --report and dlw characterize");
    }
    let mut config = load_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter.config();
    }
    let truth = args.truth.as_ref().map(|p| read_angles(p)).transpose()?;
    let recording = match truth {
        Some(_) => Recording::read_allowing_empty_angle(&args.recording)?,
        None => Recording::read(&args.recording)?,
    };
    let (recording_name, truth_name) = (
        args.recording.display().to_string(),
        args.truth.as_ref().map(|p| p.display().to_string()),
    );
    let mut result = estimate(&EstimateRequest {
        config: &config,
        recording: &recording,
        recording_name: &recording_name,
        truth: truth.as_ref().zip(truth_name.as_deref()),
    })?;
    write_atomic(&output, &result.csv_bytes(&recording, args.precision))?;
    result.set_estimates(output);
    if args.json {
        println!("{}", dlw::finite::to_json(&result)?);
    } else {
        for w in result.warnings() {
            eprintln!("warning: {w}");
        }
        print!("{}", result.summary());
    }
    Ok(())
}
