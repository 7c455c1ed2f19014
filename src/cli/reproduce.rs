//! `dlw reproduce -o DIR [--duration-scale F | --short] [--json]`.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use dlw::reproduce::{page, reproduce, Settings, SHORT_SCALE, STEPS};
use serde::Serialize;

/// Arguments of `dlw reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder: report.html and its SVG figures (replaced if it exists).
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Every protocol timing times F, in (0, 1]; 1 (the default) is the paper's 1000 s
    /// characterization and 3000 s of each other protocol.
    #[arg(long, conflicts_with = "short")]
    duration_scale: Option<f64>,
    /// A short run for CI: every timing a tenth of the paper's.
    #[arg(long)]
    short: bool,
    /// Print the tables' numbers as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Serialize)]
struct JointNumbers {
    joint: char,
    gauge_factor: f64,
    r0_ohm: f64,
    characteristic: Option<dlw::fit::Characteristic>,
    gf_rise_correlation: f64,
    r0_std_ohm: f64,
    relaxation_correlation: f64,
    relaxation_median_tau_s: Option<f64>,
    estimation: Vec<dlw::characterize::EstimationRun>,
}

#[derive(Debug, Serialize)]
struct Report {
    duration_scale: f64,
    patterns: Vec<dlw::reproduce::Pattern>,
    seconds: f64,
    joints: Vec<JointNumbers>,
    control_open_loop: dlw::control::SchemeMetrics,
    control_closed_loop: dlw::control::SchemeMetrics,
    report: PathBuf,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    dlw::output::claim(&args.output, [&args.output; 0], args.force)?;
    let start = Instant::now();
    let settings = Settings {
        duration_scale: if args.short {
            SHORT_SCALE
        } else {
            args.duration_scale.unwrap_or(1.0)
        },
    };
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
    let r = reproduce(settings, &progress)?;
    bar.set_message("drawing the report");
    page(&r)
        .write(&args.output)
        .with_context(|| format!("writing {}", args.output.display()))?;
    bar.finish_and_clear();
    let report = args.output.join("report.html");
    if args.json {
        let out = Report {
            duration_scale: settings.duration_scale,
            patterns: dlw::reproduce::patterns(&r),
            seconds: start.elapsed().as_secs_f64(),
            joints: r
                .joints
                .iter()
                .map(|j| {
                    let l = &j.loops.sensors[0].summary;
                    JointNumbers {
                        joint: j.letter,
                        gauge_factor: l.gauge_factor,
                        r0_ohm: l.r0_ohm,
                        characteristic: l.characteristic,
                        gf_rise_correlation: j.rate.sensors[0].gf_rise_correlation,
                        r0_std_ohm: j.rate.sensors[0].r0_std_ohm,
                        relaxation_correlation: j.relaxation.sensors[0].correlation,
                        relaxation_median_tau_s: j.relaxation.sensors[0].median_tau_s,
                        estimation: j.estimation.runs.clone(),
                    }
                })
                .collect(),
            control_open_loop: r.control.run.metrics[0],
            control_closed_loop: r.control.run.metrics[1],
            report,
        };
        println!("{}", dlw::finite::to_json(&out)?);
        return Ok(());
    }
    for j in &r.joints {
        let l = &j.loops.sensors[0].summary;
        let est = |name: &str| {
            j.estimation
                .runs
                .iter()
                .find(|x| x.config == name && !x.split)
                .map_or(f64::NAN, |x| x.metrics.rmse_deg)
        };
        println!(
            "Joint {}: GF {:.2}, R0 {:.1} kΩ; corr(GF, rise) {:.4}, std R0 {:.3} kΩ; relaxation corr {:.3}; RMSE linear {:.2}°, PI {:.2}°",
            j.letter,
            l.gauge_factor,
            l.r0_ohm / 1e3,
            j.rate.sensors[0].gf_rise_correlation,
            j.rate.sensors[0].r0_std_ohm / 1e3,
            j.relaxation.sensors[0].correlation,
            est("linear"),
            est("PI")
        );
    }
    let [o, c] = [
        r.control.run.metrics[0].table_vi(),
        r.control.run.metrics[1].table_vi(),
    ];
    println!(
        "Joint D control RMSE (°): open loop {:.2} / {:.2} / {:.2}, closed loop {:.2} / {:.2} / {:.2} (sensed-actual / actual-desired / sensed-desired)",
        o[0], o[1], o[2], c[0], c[1], c[2]
    );
    let list = dlw::reproduce::patterns(&r);
    for p in &list {
        println!(
            "pattern {}: {} (paper: {}; dlw: {})",
            p.verdict(),
            p.name,
            p.paper,
            p.dlw
        );
        if let Some(why) = &p.cannot_show {
            println!("  why: {why}");
        }
    }
    println!("{}", dlw::reproduce::patterns::tally(&list));
    println!(
        "report {} ({:.1} s)",
        report.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
