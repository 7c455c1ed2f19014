//! `dlw discover --design D REC [--scenario S] [--holdout REC2] -o DIR [--json]`.

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{bail, Context};
use dlw::design::Design;
use dlw::discover::{self, scenario, Outcome};
use dlw::output::write_folder_atomic;
use dlw::sim::{Recording, Scenario};
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
    discovered: Vec<Named>,
    candidates: Vec<Scored>,
    ambiguous: Vec<discover::Ambiguity>,
    unexplained: Vec<discover::unexplained::Unexplained>,
    gaps: Vec<discover::Gap>,
    scenario: PathBuf,
    report: PathBuf,
}

#[derive(Debug, Serialize)]
struct Named {
    effect: &'static str,
    channel: String,
    evidence: f64,
    parameters: BTreeMap<String, f64>,
}

#[derive(Debug, Serialize)]
struct Scored {
    effect: &'static str,
    channel: String,
    evidence: f64,
    round: usize,
    shape: String,
    #[serde(skip_serializing_if = "Option::is_none")]
    memory: Option<f64>,
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
    let written = scenario::scenario(&base, &recording, &design.joint, &outcome)
        .map_err(|e| anyhow::anyhow!("writing the scenario: {e}"))?;
    let text = toml::to_string(&written).context("serializing the scenario")?;
    // The written scenario must be one `dlw simulate` accepts.
    if let Err(e) = toml::from_str::<Scenario>(&text)
        .map_err(|e| e.to_string())
        .and_then(|s| s.resolve(&design).map_err(|e| e.to_string()))
    {
        bail!("the discovered scenario does not validate: {e}");
    }
    let name = args.recording.file_name().map_or_else(
        || args.recording.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let page = discover::report::page(&name, &outcome);
    let mut files = page.files()?;
    files.push((
        "scenario.toml".to_owned(),
        header(&outcome, &text).into_bytes(),
    ));
    write_folder_atomic(&args.output, &files)?;
    let scenario_path = args.output.join("scenario.toml");
    let report_path = args.output.join("report.html");
    if args.json {
        println!(
            "{}",
            dlw::finite::to_json(&json(&outcome, scenario_path, report_path))?
        );
    } else {
        print_text(&outcome, &scenario_path, &report_path);
    }
    Ok(())
}

fn header(outcome: &Outcome, text: &str) -> String {
    let named = if outcome.discovered.is_empty() {
        "none".to_owned()
    } else {
        outcome
            .discovered
            .iter()
            .map(|d| format!("{} on {}", d.effect.name(), d.channel.name()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!("# Written by dlw discover: the base scenario calibrated to the recording, with the named effects: {named}.\n{text}")
}

fn json(outcome: &Outcome, scenario: PathBuf, report: PathBuf) -> Json {
    Json {
        discovered: outcome
            .discovered
            .iter()
            .map(|d| Named {
                effect: d.effect.name(),
                channel: d.channel.name(),
                evidence: d.evidence,
                parameters: d.parameters.clone(),
            })
            .collect(),
        candidates: outcome
            .candidates
            .iter()
            .map(|c| Scored {
                effect: c.effect.name(),
                channel: c.channel.name(),
                evidence: c.evidence,
                round: c.round,
                shape: c.shape.clone(),
                memory: c.memory,
            })
            .collect(),
        ambiguous: outcome.ambiguous.clone(),
        unexplained: outcome.unexplained.clone(),
        gaps: outcome.gaps.clone(),
        scenario,
        report,
    }
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
