//! `dlw discover --design D REC [--scenario S] [--holdout REC2] -o DIR [--json]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::design::Design;
use dlw::discover::{self, scenario, Outcome};
use dlw::output::write_folder_atomic;
use dlw::recording::Recording;
use dlw::sim::Scenario;
use serde::Serialize;

/// Arguments of `dlw discover`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file of the recorded joint (TOML).
    #[arg(long)]
    design: PathBuf,
    /// Recording folder (rig.toml + data.csv); it must start with the joint at rest.
    recording: PathBuf,
    /// The base model's scenario (TOML); without it, the nominal one: a linear plant and
    /// linear sensors, no effects.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// A second recording of the same joint on the same rig, to measure the gaps on (otherwise
    /// held-out blocks of REC).
    #[arg(long)]
    holdout: Option<PathBuf>,
    /// Output folder: report.html, its SVGs and scenario.toml (replaced if it exists).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Print the result as JSON.
    #[arg(long)]
    json: bool,
}

/// `--json`. The keys are part of the interface (issue 9).
#[derive(Debug, Serialize)]
struct Json {
    #[serde(flatten)]
    summary: discover::Summary,
    scenario: PathBuf,
    report: PathBuf,
}

/// Runs `dlw discover`.
pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim(
        &args.output,
        [&args.design, &args.recording]
            .into_iter()
            .chain(&args.scenario)
            .chain(&args.holdout),
        args.force,
    )?;
    let design = Design::load(&args.design)?;
    let recording = Recording::read(&args.recording)?;
    let holdout = args
        .holdout
        .as_ref()
        .map(|p| Recording::read(p))
        .transpose()?;
    let base = match &args.scenario {
        Some(path) => Scenario::load(path)?,
        None => Scenario::default(),
    };
    let resolved = base
        .clone()
        .resolve(&design)
        .with_context(|| "resolving the base scenario".to_owned())?;
    let known = scenario::known(&resolved);
    let bar = super::spinner();
    let outcome = discover::discover(
        &recording,
        holdout.as_ref(),
        &design.joint,
        &known,
        &|m: &str| bar.set_message(m.to_owned()),
    )
    .with_context(|| format!("discovering on {}", args.recording.display()))?;
    bar.finish_and_clear();
    let text = discover::scenario_text(&base, &recording, &design, &outcome)
        .map_err(anyhow::Error::msg)?;
    let name = args.recording.file_name().map_or_else(
        || args.recording.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let page = discover::report::page(&name, &outcome);
    let mut files = page.files()?;
    files.push(("scenario.toml".to_owned(), text.into_bytes()));
    write_folder_atomic(&args.output, &files)?;
    let scenario_path = args.output.join("scenario.toml");
    let report_path = args.output.join("report.html");
    if args.json {
        println!(
            "{}",
            dlw::finite::to_json(&Json {
                summary: discover::Summary::of(&outcome),
                scenario: scenario_path,
                report: report_path,
            })?
        );
    } else {
        print_text(&outcome, &scenario_path, &report_path);
    }
    Ok(())
}

fn print_text(outcome: &Outcome, scenario: &std::path::Path, report: &std::path::Path) {
    if outcome.discovered.is_empty() {
        println!("discovered: none");
    }
    for d in &outcome.discovered {
        println!(
            "discovered {} on {} (evidence {:.1}{})",
            d.effect.name(),
            d.channel.name(),
            d.evidence,
            d.runner_up.map_or(String::new(), |(e, v)| format!(
                "; runner-up {} {v:.1}",
                e.name()
            ))
        );
    }
    for a in &outcome.ambiguous {
        println!(
            "ambiguous on {}: {}",
            a.channel.name(),
            a.contenders
                .iter()
                .map(|(e, v)| format!("{} {v:.1}", e.name()))
                .collect::<Vec<_>>()
                .join(", ")
        );
    }
    for u in &outcome.unexplained {
        println!(
            "unexplained on {}: evidence {:.1} for structure no candidate explains, {}",
            u.channel.name(),
            u.evidence,
            u.place
        );
    }
    for g in &outcome.gaps {
        let deg = match (g.before_deg, g.after_deg) {
            (Some(b), Some(a)) => format!(" ({b:.3}° → {a:.3}° of estimate)"),
            _ => String::new(),
        };
        println!(
            "gap {:<8} {:.4} → {:.4} {} on {}{deg}",
            g.channel.name(),
            g.before,
            g.after,
            g.unit,
            g.on
        );
    }
    println!("scenario {}", scenario.display());
    println!("report   {}", report.display());
}
