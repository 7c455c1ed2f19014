//! `dlw characterize --design D REC [--kind loops|rate|relaxation|estimation] [--config C]...
//! [--prefilter none|ma:N] [--paper-processing] [--min-hold-s T] -o DIR [--json]`.

use std::path::PathBuf;

use anyhow::Context;
use dlw::characterize::{
    estimate, loops, planes, rate, relaxation, EstimationResult, Kind, LoopsResult, NamedConfig,
    Options, RateResult, RelaxationResult, DEFAULT_MIN_HOLD_S,
};
use dlw::design::Design;
use dlw::fit::Prefilter;
use dlw::replay::load_config;
use dlw::report::Page;
use dlw::sim::Recording;
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
    let json = |value: &dyn erased::Json| value.print(kind, &args.recording, report.clone());
    match kind {
        Kind::Loops => {
            let r = loops(&recording, &joint, &planes, &options).with_context(context)?;
            heading(
                &mut page,
                "Resistance-strain loops (Section IV-A1, Fig. 4, Table III)",
            );
            r.add_to_page(&mut page, "", "");
            page.write(&args.output)?;
            if args.json {
                json(&r)?;
            } else {
                print_loops(&r);
            }
        }
        Kind::Rate => {
            let r = rate(&recording, &joint, &planes, &options).with_context(context)?;
            heading(&mut page, "Rate dependence (Section IV-A2, Fig. 5)");
            r.add_to_page(&mut page, "", "");
            page.write(&args.output)?;
            if args.json {
                json(&r)?;
            } else {
                print_rate(&r);
            }
        }
        Kind::Relaxation => {
            let r = relaxation(&recording, &joint, &planes, &options).with_context(context)?;
            heading(&mut page, "Relaxation (Section IV-A3, Fig. 6)");
            r.add_to_page(&mut page, "", "");
            page.write(&args.output)?;
            if args.json {
                json(&r)?;
            } else {
                print_relaxation(&r);
            }
        }
        Kind::Estimation => {
            let r = estimate(&recording, &configs, &options).with_context(context)?;
            heading(
                &mut page,
                "Angle estimation (Section IV-B, Tables IV-V, Figs. 7-8)",
            );
            r.add_to_page(&mut page, "", "");
            page.write(&args.output)?;
            if args.json {
                json(&r)?;
            } else {
                print_estimation(&r);
            }
        }
    }
    if !args.json {
        println!("report {}", report.display());
    }
    Ok(())
}

/// `--json` for any result, without naming its type at the call.
mod erased {
    use super::{Kind, Report};
    use std::path::{Path, PathBuf};

    pub trait Json {
        fn print(&self, kind: Kind, recording: &Path, report: PathBuf) -> anyhow::Result<()>;
    }

    impl<T: serde::Serialize> Json for T {
        fn print(&self, kind: Kind, recording: &Path, report: PathBuf) -> anyhow::Result<()> {
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
}

fn heading(page: &mut Page, text: &str) {
    page.heading(text);
}

fn prefilter_name(p: Prefilter) -> String {
    match p {
        Prefilter::None => "none".into(),
        Prefilter::MovingAverage(n) => format!("ma:{n}"),
    }
}

fn print_loops(r: &LoopsResult) {
    for s in &r.sensors {
        let m = &s.summary;
        println!("sensor {}: {} cycles", m.sensor, m.cycles);
        println!(
            "  linear  GF = {:.4}, R0 = {:.1} Ω, r² = {:.4}, RMSE {:.1} Ω",
            m.gauge_factor, m.r0_ohm, m.r2, m.linear_rmse_ohm
        );
        if let Some(c) = &m.characteristic {
            println!(
                "  Table III  R_c = {:.2} kΩ, ε_c = {:.3} %, m_c = {:.0} kΩ, R_peak = {:.2} kΩ, ε_peak = {:.3} %",
                c.center_ohm / 1e3,
                c.center_strain * 100.0,
                c.center_slope_ohm / 1e3,
                c.peak_ohm / 1e3,
                c.peak_strain * 100.0
            );
        }
        match (&m.pi_rmse_ohm, &m.pi_error) {
            (Some(x), _) => println!("  PI      RMSE {x:.1} Ω"),
            (None, Some(e)) => println!("  PI      not fitted: {e}"),
            _ => {}
        }
    }
}

fn print_rate(r: &RateResult) {
    for s in &r.sensors {
        println!(
            "sensor {}: {} equal-amplitude cycles ({} smaller left out)",
            s.sensor,
            s.cycles.len(),
            s.smaller_cycles
        );
        for c in &s.cycles {
            println!(
                "  cycle {:>2}  rise {:>6.2} s  GF {:.4}  R0 {:.1} Ω",
                c.number, c.rise_s, c.gauge_factor, c.r0_ohm
            );
        }
        println!(
            "  correlation of GF with rise time {:.4}; GF changes {:+.2} % from the fastest to the slowest",
            s.gf_rise_correlation,
            s.gf_relative_change * 100.0
        );
        println!("  std dev of R0 {:.3} kΩ", s.r0_std_ohm / 1e3);
    }
}

fn print_relaxation(r: &RelaxationResult) {
    for s in &r.sensors {
        println!(
            "sensor {}: {} holds of at least {} s",
            s.sensor,
            s.holds.len(),
            r.min_hold_s
        );
        for h in &s.holds {
            println!(
                "  hold {:>2} at {:>7.1} s  stroke {:.3} mm  strain decay {:+.4} %  tau {}  ΔR {:+.1} Ω",
                h.number,
                h.start_s,
                h.stroke_mm,
                h.strain_decay * 100.0,
                if h.tau_unresolved {
                    "not resolved".to_owned()
                } else {
                    format!("{:.2} s", h.tau_s)
                },
                h.delta_ohm
            );
        }
        println!(
            "  correlation of ΔR with Δε over the holds {:.3}; share of Δε the resistance followed {:.2}",
            s.correlation, s.followed_share
        );
    }
}

fn print_estimation(r: &EstimationResult) {
    for run in &r.runs {
        println!(
            "{:<28} RMSE {:>7.3}°   max |error| {:>7.3}°",
            run.name(),
            run.metrics.rmse_deg,
            run.metrics.max_abs_error_deg
        );
    }
}
