//! `dlw reproduce -o DIR [--duration-scale F | --short] [--ideal | --twin | --bench FILE] [--seed N]
//! [--json]`.

use super::written::Written;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use dlw::analysis::Analysis;
use dlw::reproduce::{page, reproduce, Bench, BenchFile, Settings, SHORT_SCALE, STEPS};

/// Arguments of `dlw reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    #[command(flatten)]
    out: Written,
    /// Every protocol timing times F, in (0, 1]; 1 (the default) is the paper's 1000 s
    /// characterization and 3000 s of each other protocol.
    #[arg(long, conflicts_with = "short")]
    duration_scale: Option<f64>,
    /// A short run for CI: every timing a tenth of the paper's.
    #[arg(long)]
    short: bool,
    /// Run the clean simulated joints instead of the calibrated twin.
    #[arg(long, conflicts_with_all = ["bench", "twin"])]
    ideal: bool,
    /// Run the calibrated twin of the paper's bench (designs/scenarios/paper-bench.toml): the
    /// default.
    #[arg(long, conflicts_with = "bench")]
    twin: bool,
    /// A bench file of one scenario per joint (`dlw calibrate` writes one) instead of the
    /// shipped twin.
    #[arg(long)]
    bench: Option<PathBuf>,
    /// Draw every simulation's noise from another seed (0, the default, is the one every
    /// shipped number was measured with): a second run of the same bench.
    #[arg(long, default_value_t = 0)]
    seed: u64,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let start = Instant::now();
    let bench = match (&args.bench, args.ideal) {
        (Some(path), _) => Bench::Twin(BenchFile::load(path)?.into()),
        (None, true) => Bench::Ideal,
        (None, false) => Bench::paper()?,
    };
    let settings = Settings {
        seed: args.seed,
        ..Settings::new(
            if args.short {
                SHORT_SCALE
            } else {
                args.duration_scale.unwrap_or(1.0)
            },
            bench,
        )
    };
    let inputs: Vec<&PathBuf> = args.bench.iter().collect();
    args.out.claim_folder(inputs)?;
    let bar = if std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(STEPS);
        bar.set_style(
            indicatif::ProgressStyle::with_template("{elapsed:>4} [{bar:30}] {pos}/{len} {msg}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    let progress = |msg: &str| {
        bar.inc(1);
        bar.set_message(msg.to_owned());
    };
    let mut r = reproduce(settings, &progress)?;
    bar.set_message("drawing the report");
    page(&r)
        .write(&args.out.output)
        .with_context(|| format!("writing {}", args.out.output.display()))?;
    bar.finish_and_clear();
    r.written_to(&args.out.output);
    r.seconds = start.elapsed().as_secs_f64();
    if args.out.json {
        println!("{}", dlw::finite::to_json(&r)?);
    } else {
        print!("{}", r.summary());
    }
    Ok(())
}
