//! `dlw characterize --design D REC [--kind loops|rate|relaxation|estimation] [--config C]...
//! [--prefilter none|ma:N] [--paper-processing] [--min-hold-s T] -o DIR [--json]`.

use std::path::{Path, PathBuf};

use anyhow::Context;
use dlw::analysis::{Analysis, Placement};
use dlw::characterize::{
    estimate, loops, planes, rate, relaxation, Kind, NamedConfig, Options, DEFAULT_MIN_HOLD_S,
};
use dlw::design::Design;
use dlw::fit::{prefilter_name, Prefilter};
use dlw::recording::Recording;
use dlw::replay::load_config;
use dlw::report::Page;
use dlw_estimator::MAX_PLAYS;
use serde::Serialize;

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
    kind: Option<Kind>,
    /// Estimator config(s) for `estimation` (.toml or .json); repeat for several.
    #[arg(long)]
    config: Vec<PathBuf>,
    /// Filter on strain and resistance before the analysis: `none` or `ma:N`.
    #[arg(long, default_value = "ma:100")]
    prefilter: Prefilter,
    /// Play operators of the PI fits (`loops`), 2 to 16.
    #[arg(long, default_value_t = 10)]
    order: usize,
    /// Shortest hold (s) the relaxation analysis accepts.
    #[arg(long, default_value_t = DEFAULT_MIN_HOLD_S)]
    min_hold_s: f64,
    /// `estimation`: the paper's processing, a 1000-sample moving average on the angle (PI
    /// configs clamp to the characterized resistance range themselves).
    #[arg(long)]
    paper_processing: bool,
    /// Output folder: report.html and its SVG figures (replaced if it exists).
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

/// What `--json` prints: the kind and its result's fields.
#[derive(Debug, Serialize)]
struct Report<'a, T: Serialize> {
    kind: Kind,
    recording: &'a std::path::Path,
    report: PathBuf,
    #[serde(flatten)]
    result: &'a T,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim(
        &args.output,
        [&args.design, &args.recording]
            .into_iter()
            .chain(&args.config),
        args.force,
    )?;
    if !(2..=MAX_PLAYS).contains(&args.order) {
        anyhow::bail!(
            "--order {} must lie between 2 and {MAX_PLAYS} play operators",
            args.order
        );
    }
    if !(args.min_hold_s.is_finite() && args.min_hold_s > 0.0) {
        anyhow::bail!(
            "--min-hold-s {} must be finite and greater than 0",
            args.min_hold_s
        );
    }
    let design = Design::load(&args.design)?;
    let recording = Recording::read(&args.recording)?;
    let kind = match args.kind {
        Some(k) => k,
        None => Kind::of_recording(&recording)
            .with_context(|| format!("choosing the analysis for {}", args.recording.display()))?,
    };
    if kind != Kind::Estimation && !args.config.is_empty() {
        anyhow::bail!(
            "--config is for --kind estimation; the {} analysis takes none",
            kind.name()
        );
    }
    let configs: Vec<NamedConfig> = args
        .config
        .iter()
        .map(|p| {
            Ok(NamedConfig {
                name: p
                    .file_stem()
                    .map_or_else(|| p.display().to_string(), |s| s.to_string_lossy().into()),
                config: load_config(p)?,
            })
        })
        .collect::<anyhow::Result<_>>()?;
    let options = Options {
        prefilter: args.prefilter,
        order: args.order,
        min_hold_s: args.min_hold_s,
        paper_processing: args.paper_processing,
        decimation: None,
        models: &dlw::fit::ModelKind::ALL,
    };
    let joint = design.joint;
    let planes = planes(&recording, &joint, &design.file.name)?;
    let name = args.recording.display().to_string();
    let mut page = Page::new(format!(
        "Characterization ({}): {}",
        kind.name(),
        design.file.name
    ));
    page.text(format!(
        "Recording {name}, {} samples at {} Hz; design {}. Strain from the tracker angle (Eq. 3), \
         resistance from the divider voltage (Eq. 4), both through the prefilter {}.",
        recording.samples.len(),
        recording.rig.sample_hz,
        args.design.display(),
        prefilter_name(args.prefilter)
    ));
    let context = || format!("{} analysis of {name}", kind.name());
    let report = args.output.join("report.html");
    let finish = |page: Page, heading: &str, r: &dyn Section| -> anyhow::Result<()> {
        let mut page = page;
        page.heading(heading);
        r.add(&mut page);
        page.write(&args.output)?;
        if args.json {
            r.print_json(kind, &args.recording, report.clone())
        } else {
            print!("{}", r.text());
            println!("report {}", report.display());
            Ok(())
        }
    };
    match kind {
        Kind::Loops => finish(
            page,
            "Resistance-strain loops (Section IV-A1, Fig. 4, Table III)",
            &loops(&recording, &joint, &planes, &options).with_context(context)?,
        ),
        Kind::Rate => finish(
            page,
            "Rate dependence (Section IV-A2, Fig. 5)",
            &rate(&recording, &joint, &planes, &options).with_context(context)?,
        ),
        Kind::Relaxation => finish(
            page,
            "Relaxation (Section IV-A3, Fig. 6)",
            &relaxation(&recording, &joint, &planes, &options).with_context(context)?,
        ),
        Kind::Estimation => finish(
            page,
            "Angle estimation (Section IV-B, Tables IV-V, Figs. 7-8)",
            &estimate(&recording, &configs, &options).with_context(context)?,
        ),
    }
}

/// Any analysis's result, through [`Analysis`], without naming its type at the call.
trait Section {
    fn add(&self, page: &mut Page);
    fn text(&self) -> String;
    fn print_json(&self, kind: Kind, recording: &Path, report: PathBuf) -> anyhow::Result<()>;
}

impl<T: Analysis> Section for T {
    fn add(&self, page: &mut Page) {
        self.add_to_page(page, Placement::ALONE);
    }

    fn text(&self) -> String {
        self.summary()
    }

    fn print_json(&self, kind: Kind, recording: &Path, report: PathBuf) -> anyhow::Result<()> {
        let r = Report {
            kind,
            recording,
            report,
            result: self,
        };
        println!("{}", dlw::finite::to_json(&r)?);
        Ok(())
    }
}
