//! `dlw characterize --design D REC [--kind loops|rate|relaxation|estimation] [--config C]...
//! [--prefilter none|ma:N] [--paper-processing] [--min-hold-s T] -o DIR [--json]`.

use super::written::Written;
use std::path::PathBuf;

use dlw::analysis::Analysis;
use dlw::characterize::{
    characterize, AnalysisKind, CharacterizeRequest, Options, DEFAULT_MIN_HOLD_S,
};
use dlw::design::Design;
use dlw::fit::PlayOrder;
use dlw::recording::Recording;
use dlw::signal::Prefilter;

/// Arguments of `dlw characterize`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file of the recorded joint (TOML).
    #[arg(long)]
    design: PathBuf,
    /// Recording folder (rig.toml + data.csv).
    recording: PathBuf,
    /// The analysis; default: from the protocol rig.toml records (characterization → loops,
    /// rate-dependence → rate, relaxation → relaxation, random → estimation).
    #[arg(long, value_enum)]
    kind: Option<AnalysisKind>,
    /// Estimator config(s) for `estimation` (.toml or .json); repeat for several.
    #[arg(long)]
    config: Vec<PathBuf>,
    /// Filter on strain and resistance before the analysis: `none` or `ma:N`.
    #[arg(long, default_value = "ma:100")]
    prefilter: Prefilter,
    /// Play operators of the PI fits (`loops`), 2 to 16.
    #[arg(long, default_value = "10", value_parser = super::parse_order)]
    order: PlayOrder,
    /// Shortest hold (s) the relaxation analysis accepts.
    #[arg(long, default_value_t = DEFAULT_MIN_HOLD_S)]
    min_hold_s: f64,
    /// `estimation`: the paper's processing, a 1000-sample moving average on the angle (PI
    /// configs clamp to the characterized resistance range themselves).
    #[arg(long)]
    paper_processing: bool,
    #[command(flatten)]
    out: Written,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    args.out.claim_folder(
        [&args.design, &args.recording]
            .into_iter()
            .chain(&args.config),
    )?;
    let design = Design::load(&args.design)?;
    let recording = Recording::read_measured(&args.recording)?;
    let request = CharacterizeRequest {
        recording: &recording,
        recording_name: args.recording.display().to_string(),
        joint: &design.joint,
        design_name: design.file.name.clone(),
        design_source: args.design.display().to_string(),
        kind: args.kind,
        configs: args.config.clone(),
        options: Options {
            prefilter: args.prefilter,
            order: args.order,
            min_hold_s: args.min_hold_s,
            paper_processing: args.paper_processing,
            decimation: None,
            models: &dlw::fit::ModelKind::ALL,
        },
    };
    let mut result = characterize(&request)?;
    result.report_page().write(&args.out.output)?;
    result.report = Some(args.out.output.join("report.html"));
    if args.out.json {
        println!("{}", dlw::finite::to_json(&result)?);
    } else {
        print!("{}", result.summary());
    }
    Ok(())
}
