//! `dlw control --design D --config C [--scenario S] [--profile desired.csv | --protocol P]
//! [--gains kp,ki,kd] [--duration-s T] [--seed N] -o DIR [--json]`.

use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::control::{report, Control, DesiredSource, Gains, Scheme, PAPER_GAINS};
use dlw::design::Design;
use dlw::output::write_folder_atomic;
use dlw::replay::load_config;
use dlw_estimator::FilterConfig;
use serde::Serialize;

use super::estimate::parse_filter;
use super::scenario_args::ScenarioArgs;

/// Arguments of `dlw control`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file (TOML).
    #[arg(long)]
    design: PathBuf,
    /// Estimator config (.toml or .json) the closed loop senses the angle with.
    #[arg(long)]
    config: PathBuf,
    #[command(flatten)]
    scenario: ScenarioArgs,
    /// Desired angle CSV with the header `time_s,angle_deg`, interpolated linearly.
    #[arg(long, conflicts_with = "protocol")]
    profile: Option<PathBuf>,
    /// PID gains `kp,ki,kd` on the angle error: kp in mm/°, ki in mm/(°·s), kd in mm·s/°
    /// (default: the paper's 0.1,0.1,0).
    #[arg(long, value_parser = parse_gains)]
    gains: Option<Gains>,
    /// Feed-forward slope m_t (°/mm); default: the scenario's plant gain (35.49 by default).
    #[arg(long)]
    mt_deg_per_mm: Option<f64>,
    /// Filter on the sensed angle, replacing the config's output_filter: none, ma:N or lp:T.
    #[arg(long, value_parser = parse_filter)]
    filter: Option<FilterConfig>,
    /// Output folder: report.html, its SVG figures and control.csv.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Print every number as JSON.
    #[arg(long)]
    json: bool,
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

/// What `control --json` prints; the keys are part of the interface.
#[derive(Debug, Serialize)]
struct Report<'a> {
    design: &'a str,
    samples: usize,
    duration_s: f64,
    sample_hz: f64,
    seed: u64,
    desired: &'a str,
    mt_deg_per_mm: f64,
    mt_source: dlw::control::MtSource,
    gains: Gains,
    correction_limit_mm: f64,
    open_loop: dlw::control::SchemeMetrics,
    closed_loop: dlw::control::SchemeMetrics,
    paper: Paper,
    report: PathBuf,
    csv: PathBuf,
    warnings: Vec<String>,
}

/// The paper's Table VI.
#[derive(Debug, Serialize)]
struct Paper {
    open_loop: PaperRow,
    closed_loop: PaperRow,
}

#[derive(Debug, Serialize)]
struct PaperRow {
    sensed_vs_actual_rmse_deg: f64,
    actual_vs_desired_rmse_deg: f64,
    sensed_vs_desired_rmse_deg: f64,
}

impl From<(f64, f64, f64)> for PaperRow {
    fn from((a, b, c): (f64, f64, f64)) -> Self {
        Self {
            sensed_vs_actual_rmse_deg: a,
            actual_vs_desired_rmse_deg: b,
            sensed_vs_desired_rmse_deg: c,
        }
    }
}

pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim(
        &args.output,
        [&args.design, &args.config]
            .into_iter()
            .chain(&args.scenario.scenario)
            .chain(&args.profile),
        args.force,
    )?;
    let occupied = match std::fs::read_dir(&args.output) {
        Ok(mut entries) => entries.next().is_some(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => false,
        Err(_) => true,
    };
    if occupied && !args.force {
        bail!(
            "output folder {} already exists and is not empty (pass --force to replace it)",
            args.output.display()
        );
    }
    let design = Design::load(&args.design)?;
    let mut config = load_config(&args.config)?;
    if let Some(filter) = args.filter {
        config.output_filter = filter;
    }
    let scenario = args.scenario.load()?;
    let source = match args.profile {
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
    let files = report::files(&control, &run).context("drawing the report")?;
    write_folder_atomic(&args.output, &files)
        .with_context(|| format!("writing {}", args.output.display()))?;
    let sc = &control.desired.scenario;
    let n = control.desired.angle_deg.len();
    let report_path = args.output.join("report.html");
    let csv_path = args.output.join(report::CSV_FILE);
    if args.json {
        let r = Report {
            design: &design.file.name,
            samples: n,
            duration_s: n as f64 / sc.sample_hz,
            sample_hz: sc.sample_hz,
            seed: sc.seed,
            desired: &control.desired.description,
            mt_deg_per_mm: control.mt_deg_per_mm,
            mt_source: control.mt_source,
            gains: control.gains,
            correction_limit_mm: control.pid.output_max,
            open_loop: run.metrics[0],
            closed_loop: run.metrics[1],
            paper: Paper {
                open_loop: dlw::control::PAPER_TABLE_VI[0].into(),
                closed_loop: dlw::control::PAPER_TABLE_VI[1].into(),
            },
            report: report_path,
            csv: csv_path,
            warnings: control
                .warnings
                .iter()
                .chain(&run.warnings)
                .cloned()
                .collect(),
        };
        println!("{}", dlw::finite::to_json(&r)?);
    } else {
        for w in control.warnings.iter().chain(&run.warnings) {
            eprintln!("warning: {w}");
        }
        println!(
            "{}: {} samples ({} s at {} Hz), seed {}, m_t {} °/mm, gains kp {} mm/°, ki {} mm/(°·s), kd {} mm·s/°",
            design.file.name,
            n,
            n as f64 / sc.sample_hz,
            sc.sample_hz,
            sc.seed,
            control.mt_deg_per_mm,
            control.gains.kp_mm_per_deg,
            control.gains.ki_mm_per_deg_s,
            control.gains.kd_mm_s_per_deg
        );
        println!("  RMSE (°)             open loop   closed loop   (paper: open, closed)");
        let names = [
            "sensed vs actual ",
            "actual vs desired",
            "sensed vs desired",
        ];
        let (open, closed) = (run.metrics[0].table_vi(), run.metrics[1].table_vi());
        let paper = dlw::control::PAPER_TABLE_VI.map(|(a, b, c)| [a, b, c]);
        for (k, name) in names.iter().enumerate() {
            println!(
                "  {name}    {:>9.2}   {:>11.2}   ({:.2}, {:.2})",
                open[k], closed[k], paper[0][k], paper[1][k]
            );
        }
        for (scheme, m) in Scheme::BOTH.iter().zip(&run.metrics) {
            if m.held_samples > 0 {
                println!("  {}: {} held samples", scheme.title(), m.held_samples);
            }
        }
        println!("  report               {}", report_path.display());
        println!("  samples              {}", csv_path.display());
    }
    Ok(())
}
