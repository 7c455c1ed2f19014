//! `dlw estimate --config C DIR [--filter none|ma:N|lp:T] [--json] [-o estimates.csv]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::output::write_atomic;
use dlw::replay::{load_config, replay, Metrics};
use dlw::sim::Recording;
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
}

pub(super) fn parse_filter(s: &str) -> Result<FilterConfig, String> {
    let bad = || format!("unknown filter {s:?} (expected none, ma:N or lp:T)");
    let config = match s.split_once(':') {
        None if s == "none" => FilterConfig::None,
        Some(("ma", n)) => FilterConfig::MovingAverage {
            samples: n.parse().map_err(|_| bad())?,
        },
        Some(("lp", t)) => FilterConfig::LowPass {
            time_constant_samples: t.parse().map_err(|_| bad())?,
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

pub fn run(args: Args) -> anyhow::Result<()> {
    let mut config = load_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter;
    }
    let recording = Recording::read(&args.recording)?;
    let result = replay(&config, &recording)
        .with_context(|| format!("estimating over {}", args.recording.display()))?;
    let output = args
        .output
        .unwrap_or_else(|| args.recording.join(DEFAULT_OUTPUT));
    write_atomic(&output, &result.csv_bytes(&recording))?;
    let m = &result.metrics;
    if args.json {
        let report = Report {
            metrics: *m,
            estimates: output,
            warnings: result.warnings,
        };
        println!(
            "{}",
            serde_json::to_string_pretty(&report).context("serializing the report")?
        );
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
