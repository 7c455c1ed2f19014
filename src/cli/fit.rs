//! `dlw fit --design D REC [--model linear|pi|continuous-pi] [--order N] [--prefilter none|ma:N]
//! [--sensor 1|2|both] [--validate REC2] -o CONFIG [--json] [--report DIR]`.

use super::written::Written;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context};
use dlw::analysis::Analysis;
use dlw::design::Design;
use dlw::fit::{fit, FitRequest, ModelKind, PlayOrder};
use dlw::output::write_atomic;
use dlw::recording::Recording;
use dlw::replay::ConfigFormat;
use dlw::sensor::Sensors;
use dlw::signal::Prefilter;

/// Arguments of `dlw fit`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file of the recorded joint (TOML), or a robot file (each sensor's model and the
    /// crosstalk matrix, from a robot recording).
    #[arg(long)]
    design: PathBuf,
    /// Recording folder (rig.toml + data.csv), e.g. a characterization run.
    recording: PathBuf,
    /// The model fitted and written to the config (`--compare` fits every model).
    #[arg(long, value_enum, default_value_t = ModelKind::Pi)]
    model: ModelKind,
    /// Play operators N of the PI models (2 to 16).
    #[arg(long, default_value = "10", value_parser = super::parse_order)]
    order: PlayOrder,
    /// Filter on strain and resistance before fitting, and the config's input filter:
    /// `none` or `ma:N` (moving average of N samples).
    #[arg(long, default_value = "ma:100")]
    prefilter: Prefilter,
    /// Fit every model and report them side by side; the config still gets `--model`.
    #[arg(long)]
    compare: bool,
    /// Which sensor: 1 (plane +y_s, v1_V), 2 (a BSN joint's compression sensor, v2_V) or both
    /// (BSN: a two-sensor config, Eq. 7). Default: both for a BSN recording with two columns.
    #[arg(long, value_parser = sensors_parser())]
    sensor: Option<Sensors>,
    /// A second recording of the same sensor: each fitted model is run over it through the
    /// runtime estimator and its angle RMSE reported.
    #[arg(long)]
    validate: Option<PathBuf>,
    #[command(flatten)]
    out: Written,
    /// Write an HTML report with SVG plots into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// `--sensor`: `1`, `2` or `both`, parsed into the one sensor identity ([`Sensors`]).
fn sensors_parser() -> impl clap::builder::TypedValueParser<Value = Sensors> {
    use clap::builder::TypedValueParser;
    clap::builder::PossibleValuesParser::new(["1", "2", "both"]).try_map(|s| s.parse::<Sensors>())
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let report: Vec<&std::path::Path> = args.report.iter().map(|p| p.as_path()).collect();
    args.out.claim_with(
        &report,
        dlw::robot::design_inputs(&args.design)
            .iter()
            .chain([&args.recording])
            .chain(&args.validate),
    )?;
    let start = Instant::now();
    let format = ConfigFormat::of(&args.out.output)?;
    if dlw::robot::is_robot_file(&args.design) {
        if args.compare || args.validate.is_some() || args.sensor.is_some() || args.report.is_some()
        {
            bail!("--compare, --validate, --sensor and --report are for a joint's fit; a robot's fit takes --model, --order and --prefilter");
        }
        return super::robot_sensing::fit(
            &args.design,
            &args.recording,
            args.model,
            args.order,
            args.prefilter,
            &args.out.output,
            format,
            args.out.json,
        );
    }
    let design = Design::load(&args.design)?;
    let recording = Recording::read_measured(&args.recording)?;
    let validate = args
        .validate
        .as_ref()
        .map(|p| Recording::read_measured(p))
        .transpose()?;
    let t_read = start.elapsed().as_secs_f64();
    let request = FitRequest {
        joint: &design.joint,
        recording: &recording,
        recording_name: args.recording.display().to_string(),
        design_name: args.design.display().to_string(),
        model: args.model,
        order: args.order,
        prefilter: args.prefilter,
        sensors: args.sensor,
        compare: args.compare,
        validate: validate.as_ref(),
    };
    let bar = super::spinner();
    let say = |m: &str| bar.set_message(m.to_owned());
    let result = fit(&request, &say);
    bar.finish_and_clear();
    let mut result = result.with_context(|| format!("fitting {}", args.recording.display()))?;
    let text = result.config_text(format)?;
    let page = args
        .report
        .as_ref()
        .map(|_| result.report_page().files())
        .transpose()?;
    // Everything is computed: now write, the config last so a failed report leaves none.
    if let (Some(dir), Some(files)) = (&args.report, page) {
        dlw::output::write_folder_atomic(dir, &files)?;
    }
    write_atomic(&args.out.output, text.as_bytes())?;
    result.config = Some(args.out.output.clone());
    result.report = args.report.clone();
    result.timings_s.read = t_read;
    result.timings_s.total = start.elapsed().as_secs_f64();
    if args.out.json {
        let json = result.to_json().context("serializing the report")?;
        println!("{}", dlw::finite::to_json(&json)?);
    } else {
        print!("{}", result.summary());
    }
    Ok(())
}
