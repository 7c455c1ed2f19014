//! `dlw explore SPEC -o DIR [--json] [--top K] [--force]`: search a grid of joint designs for
//! the Pareto front of the spec's objectives (`docs/explore.md`).

use super::written::Written;
use std::path::PathBuf;

use anyhow::Context;
use dlw::explore::{files, Exploration};

/// Arguments of `dlw explore`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Exploration spec (TOML).
    spec: PathBuf,
    #[command(flatten)]
    out: Written,
    /// How many of the best designs to write as design files.
    #[arg(long, value_name = "K", default_value_t = 3)]
    top: usize,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    // Claimed twice: against the spec before reading anything, then against every file the
    // spec names (its base design, tube catalogue, process sets) once they are known.
    args.out.claim_folder([&args.spec])?;
    let mut x = Exploration::load(&args.spec, &args.out.output.join("best-1.toml"))?;
    args.out.claim_folder(&x.inputs)?;
    let bar = progress(x.candidate_count(), "scoring");
    let screen = x.screen(&|n| bar.inc(n));
    bar.finish_and_clear();
    let bar = progress(screen.survivors.len() as u64, "design rules");
    let mut feasible = x.check_rules(&screen, &|n| bar.inc(n))?;
    bar.finish_and_clear();
    let mut front = x.front(&feasible);
    if x.predicts() {
        let bar = progress(front.len() as u64, "predicting");
        bar.set_position(0);
        front = x.predict_front(&mut feasible, &front)?;
        bar.finish_and_clear();
    }
    let (out, summary) =
        files(&x, &screen, &feasible, &front, args.top).context("drawing the report")?;
    dlw::output::write_folder_atomic(&args.out.output, &out)?;
    if args.out.json {
        println!("{}", dlw::finite::to_json(&summary)?);
    } else {
        println!(
            "{} candidates: {} feasible, {} on the Pareto front",
            summary.candidates,
            summary.feasible,
            summary.front.len()
        );
        for (name, _) in &out {
            if name.ends_with(".toml") || name.ends_with(".csv") || name.ends_with(".html") {
                println!("wrote {}", args.out.output.join(name).display());
            }
        }
    }
    Ok(())
}

/// A progress bar on stderr, hidden when stderr is not a terminal (tests, pipes).
fn progress(len: u64, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_message(what.to_string());
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "{msg:>12} [{bar:40}] {human_pos}/{human_len} ({per_sec}, {eta})",
    ) {
        bar.set_style(style);
    }
    bar
}
