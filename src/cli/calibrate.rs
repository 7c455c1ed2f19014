//! `dlw calibrate -o DIR (paper-bench.toml, calibration.json, evaluations.json) [--design-points N] [--rounds R] [--local-points K] [--full-checks C]
//! [--seed S] [--seeds N] [--start FILE] [--json]`: the paper's bench as a calibrated twin.

use super::written::Written;
use std::time::Instant;

use anyhow::Context;
use dlw::calibrate::{Calibration, CalibrationResult, Options, Space};

/// Arguments of `dlw calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    out: Written,
    /// Points of the Latin hypercube (short-sized evaluations).
    #[arg(long, default_value_t = Options::default().design_points)]
    design_points: usize,
    /// Surrogate rounds per full-size check.
    #[arg(long, default_value_t = Options::default().rounds)]
    rounds: usize,
    /// Evaluations per round (the proposal and points around it).
    #[arg(long, default_value_t = Options::default().local_points)]
    local_points: usize,
    /// Full-size checks of the best point (each corrects the short-sized values).
    #[arg(long, default_value_t = Options::default().full_checks)]
    full_checks: usize,
    /// Seed of the design (the simulations use the reproduction's seeds).
    #[arg(long, default_value_t = Options::default().seed)]
    seed: u64,
    /// Run every evaluation on the reproduction's seeds 0 to N−1 and fit each metric's mean, so
    /// the twin holds on other seeds than the one it was fitted on (N times the cost).
    #[arg(long, default_value_t = Options::default().seeds, value_parser = clap::value_parser!(u64).range(1..=10))]
    seeds: u64,
    /// Start from a bench file's `[calibration.parameters]` (parameters it does not name keep
    /// the ideal bench's values): the point joins the design and is checked at full size first,
    /// so the result is never worse at full size.
    #[arg(long)]
    start: Option<std::path::PathBuf>,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let options = Options {
        design_points: args.design_points,
        rounds: args.rounds,
        local_points: args.local_points,
        full_checks: args.full_checks,
        seed: args.seed,
        seeds: args.seeds,
        ..Options::default()
    };
    let space = Space::paper();
    let start = match &args.start {
        Some(path) => {
            let file = dlw::reproduce::BenchFile::load(path)?;
            let named = file.calibration.map(|c| c.parameters).ok_or_else(|| {
                anyhow::anyhow!(
                    "--start {}: the bench file has no [calibration.parameters]",
                    path.display()
                )
            })?;
            let u = space
                .point(&named)
                .map_err(|e| anyhow::anyhow!("--start {}: {e}", path.display()))?;
            Some(u)
        }
        None => None,
    };
    let mut calibration = Calibration::new(space, options)?;
    if let Some(u) = start {
        calibration = calibration.with_start(u);
    }
    let start = Instant::now();
    let count = std::sync::atomic::AtomicUsize::new(0);
    calibration.log = Some(std::sync::Arc::new(move |_: &str| {
        let n = count.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
        if n % 10 == 0 {
            eprintln!("{:7.1} s  {n} evaluations", start.elapsed().as_secs_f64());
        }
    }));
    args.out.claim_folder(args.start.iter())?;
    let progress = |msg: &str| eprintln!("{:7.1} s  {msg}", start.elapsed().as_secs_f64());
    let full = calibration.run_all(&progress)?;
    let result = CalibrationResult::new(&calibration, &full, start.elapsed().as_secs_f64());
    let header = format!(
        "The paper's bench as a calibrated twin, written by `dlw calibrate` (docs/experiments.md).\n\
         {}\n\
         One scenario per joint; `dlw reproduce` runs it by default, `--ideal` the clean bench.",
        result.summary().lines().next().unwrap_or_default()
    );
    let toml = result.bench.to_toml(&header)?;
    let json = dlw::finite::to_json(&result)?;
    dlw::output::write_folder_atomic(
        &args.out.output,
        &[
            ("paper-bench.toml".to_owned(), toml.into_bytes()),
            ("calibration.json".to_owned(), json.clone().into_bytes()),
            (
                "evaluations.json".to_owned(),
                dlw::finite::to_json(&calibration.evaluations)?.into_bytes(),
            ),
        ],
    )
    .with_context(|| format!("writing {}", args.out.output.display()))?;
    if args.out.json {
        println!("{json}");
    } else {
        print!("{}", result.summary());
    }
    Ok(())
}
