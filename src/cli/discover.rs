//! `dlw discover --design D REC [--scenario S] [--holdout REC2] -o DIR [--json] [--fast]`.

use super::written::Written;
use std::path::PathBuf;

use anyhow::Context;
use dlw::analysis::Analysis;
use dlw::design::Design;
use dlw::discover::{self, scenario};
use dlw::output::write_folder_atomic;
use dlw::recording::Recording;
use dlw::sim::Scenario;

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
    #[command(flatten)]
    out: Written,
    /// A quick look: no bootstrap; names by the fixed rule (a threshold in nats, a lead over
    /// the runner-up, nested evidence) instead of calibrating each on the recording.
    #[arg(long)]
    fast: bool,
}

/// Runs `dlw discover`.
pub fn run(args: Args) -> anyhow::Result<()> {
    args.out.claim_folder(
        [&args.design, &args.recording]
            .into_iter()
            .chain(&args.scenario)
            .chain(&args.holdout),
    )?;
    let design = Design::load(&args.design)?;
    let recording = Recording::read_measured(&args.recording)?;
    let holdout = args
        .holdout
        .as_ref()
        .map(|p| Recording::read_measured(p))
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
    let outcome = discover::discover_with(
        &recording,
        holdout.as_ref(),
        &design.joint,
        &known,
        discover::Options { fast: args.fast },
        &|m: &str| bar.set_message(m.to_owned()),
    )
    .with_context(|| format!("discovering on {}", args.recording.display()))?;
    bar.finish_and_clear();
    let mut result = discover::DiscoverResult::new(outcome);
    let text = result
        .scenario_text(&base, &recording, &design)
        .map_err(anyhow::Error::msg)?;
    let name = args.recording.file_name().map_or_else(
        || args.recording.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let mut files = result.report_page(&name).files()?;
    files.push(("scenario.toml".to_owned(), text.into_bytes()));
    write_folder_atomic(&args.out.output, &files)?;
    result.written = Some(discover::Written {
        scenario: args.out.output.join("scenario.toml"),
        report: args.out.output.join("report.html"),
    });
    if args.out.json {
        // Printed from the result itself (its keys in order), checked for non-finite numbers.
        println!("{}", dlw::finite::to_json(&result)?);
    } else {
        print!("{}", result.summary());
    }
    Ok(())
}
