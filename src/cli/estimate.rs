//! `dlw estimate --config C DIR [--filter none|ma:N|lp:T] [--truth angles.csv] [--json]
//! [-o estimates.csv]`.

use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::fluoro::read_angles;
use dlw::output::write_atomic;
use dlw::recording::Recording;
use dlw::replay::{load_config, replay, replay_against_truth, Metrics, TruthMetrics};
use dlw_estimator::FilterConfig;
use serde::Serialize;

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
    #[arg(long, value_parser = parse_filter)]
    filter: Option<FilterConfig>,
    /// Print the report as JSON (keys rmse_deg, max_abs_error_deg, samples, …).
    #[arg(long)]
    json: bool,
    /// Estimates CSV (default: estimates.csv in the recording folder).
    #[arg(short = 'o', long = "output")]
    output: Option<PathBuf>,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
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

pub(super) fn parse_filter(s: &str) -> Result<FilterConfig, String> {
    let bad = || format!("unknown filter {s:?} (expected none, ma:N or lp:T)");
    let config = match s.split_once(':') {
        None if s == "none" => FilterConfig::None,
        Some(("ma", n)) => FilterConfig::MovingAverage {
            samples: n.parse().map_err(|_| bad())?,
        },
        Some(("lp", t)) => FilterConfig::LowPass {
            time_constant_samples: dlw::limits::within(
                "lp:T",
                t.parse().map_err(|_| bad())?,
                0.0,
                dlw::limits::MAX_LOW_PASS_SAMPLES,
                "samples",
            )?,
        },
        _ => return Err(bad()),
    };
    config.validate().map_err(|e| e.to_string())?;
    Ok(config)
}

/// What `estimate --json` prints; the keys are part of the interface.
#[derive(Debug, Serialize)]
struct Report {
    #[serde(flatten)]
    metrics: Metrics,
    estimates: PathBuf,
    warnings: Vec<String>,
}

/// What `estimate --truth --json` prints; the keys are part of the interface.
#[derive(Debug, Serialize)]
struct TruthReport {
    /// The comparison with the ground truth.
    truth: TruthMetrics,
    /// The comparison with the tracker, `null` for a recording without its angle.
    tracker: Option<Metrics>,
    flagged_samples: usize,
    held_samples: usize,
    filter_delay_samples: f64,
    filter_delay_s: f64,
    estimates: PathBuf,
    warnings: Vec<String>,
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
    let inputs = std::iter::once(&args.config)
        .chain(&recording_files)
        .chain(&args.truth);
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| args.recording.join(DEFAULT_OUTPUT));
    let outputs: Vec<&std::path::Path> = std::iter::once(output.as_path())
        .chain(args.report.as_deref())
        .collect();
    dlw::output::claim_all(&outputs, inputs, args.force)?;
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
        );
    }
    if args.report.is_some() {
        bail!("--report is for a robot's config; a joint's estimates are reported by dlw fit --report and dlw characterize");
    }
    let mut config = load_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter;
    }
    if let Some(truth) = &args.truth {
        return run_with_truth(&args, &config, truth);
    }
    let recording = Recording::read(&args.recording)?;
    let result = replay(&config, &recording)
        .with_context(|| format!("estimating over {}", args.recording.display()))?;
    let output = args
        .output
        .unwrap_or_else(|| args.recording.join(DEFAULT_OUTPUT));
    write_atomic(&output, &result.csv_bytes_with(&recording, args.precision))?;
    let m = &result.metrics;
    if args.json {
        let report = Report {
            metrics: *m,
            estimates: output,
            warnings: result.warnings,
        };
        println!("{}", dlw::finite::to_json(&report)?);
    } else {
        for w in &result.warnings {
            eprintln!("warning: {w}");
        }
        println!("{}", args.recording.display());
        println!("  samples             {}", m.samples);
        println!("  RMSE                {:.3}°", m.rmse_deg);
        println!("  max |error|         {:.3}°", m.max_abs_error_deg);
        println!(
            "  filter delay        {} samples ({:.3} s), not compensated in the error",
            m.filter_delay_samples, m.filter_delay_s
        );
        println!(
            "  flagged samples     {} ({} held)",
            m.flagged_samples, m.held_samples
        );
        println!("  estimates           {}", output.display());
    }
    Ok(())
}

fn run_with_truth(
    args: &Args,
    config: &dlw_estimator::EstimatorConfig,
    truth_path: &std::path::Path,
) -> anyhow::Result<()> {
    let truth = read_angles(truth_path)?;
    let recording = Recording::read_allowing_empty_angle(&args.recording)?;
    let result = replay_against_truth(config, &recording, &truth).with_context(|| {
        format!(
            "comparing the estimates over {} with {}",
            args.recording.display(),
            truth_path.display()
        )
    })?;
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| args.recording.join(DEFAULT_OUTPUT));
    write_atomic(&output, &result.csv_bytes_with(&recording, args.precision))?;
    let t = &result.truth;
    if args.json {
        let report = TruthReport {
            truth: *t,
            tracker: result.tracker,
            flagged_samples: result.flagged_samples,
            held_samples: result.held_samples,
            filter_delay_samples: result.filter_delay_samples,
            filter_delay_s: result.filter_delay_s,
            estimates: output,
            warnings: result.warnings,
        };
        println!("{}", dlw::finite::to_json(&report)?);
        return Ok(());
    }
    for w in &result.warnings {
        eprintln!("warning: {w}");
    }
    println!(
        "{} against {}",
        args.recording.display(),
        truth_path.display()
    );
    println!(
        "  frames compared     {} ({} outside the recording, {} without an angle)",
        t.frames, t.frames_outside, t.frames_without_angle
    );
    println!("  RMSE                {:.3}°", t.rmse_deg);
    println!("  max |error|         {:.3}°", t.max_abs_error_deg);
    println!("  mean error          {:.3}°", t.mean_error_deg);
    match &result.tracker {
        Some(m) => println!(
            "  RMSE vs tracker     {:.3}° over {} samples",
            m.rmse_deg, m.samples
        ),
        None => println!("  RMSE vs tracker     — (no tracker angle in the recording)"),
    }
    println!(
        "  filter delay        {} samples ({:.3} s), not compensated in the error",
        result.filter_delay_samples, result.filter_delay_s
    );
    println!(
        "  flagged samples     {} ({} held)",
        result.flagged_samples, result.held_samples
    );
    println!("  estimates           {}", output.display());
    Ok(())
}
