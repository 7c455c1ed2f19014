//! `dlw fit --design D REC [--model linear|pi|continuous-pi] [--order N] [--prefilter none|ma:N]
//! [--sensor 1|2|both] [--validate REC2] -o CONFIG [--json] [--report DIR]`.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Context};
use dlw::design::Design;
use dlw::fit::{
    estimator_config, fit_sensor, model_name, report_page, FitOptions, ModelKind, ModelSummary,
    Prefilter, SensorFit, Validation,
};
use dlw::output::write_atomic;
use dlw::replay::{config_text, replay, ConfigFormat};
use dlw::sim::Recording;
use dlw_estimator::{SensorPlane, MAX_PLAYS};
use dlw_geometry::NotchStyle;
use serde::Serialize;

/// Arguments of `dlw fit`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Design file of the recorded joint (TOML).
    #[arg(long)]
    design: PathBuf,
    /// Recording folder (rig.toml + data.csv), e.g. a characterization run.
    recording: PathBuf,
    /// The model the config gets; every model is fitted and reported either way.
    #[arg(long, value_enum, default_value_t = ModelKind::Pi)]
    model: ModelKind,
    /// Play operators N of the PI models (2 to 16).
    #[arg(long, default_value_t = 10)]
    order: usize,
    /// Filter on strain and resistance before fitting, and the config's input filter:
    /// `none` or `ma:N` (moving average of N samples).
    #[arg(long, default_value = "ma:100")]
    prefilter: Prefilter,
    /// Which sensor: 1 (plane +y_s, v1_V), 2 (a BSN joint's compression sensor, v2_V) or both
    /// (BSN: a two-sensor config, Eq. 7). Default: both for a BSN recording with two columns.
    #[arg(long)]
    sensor: Option<SensorArg>,
    /// A second recording of the same sensor: every fitted model is run over it through the
    /// runtime estimator and its angle RMSE reported.
    #[arg(long)]
    validate: Option<PathBuf>,
    /// Output config (.toml or .json), as `dlw estimate` and the runtime crate read it.
    #[arg(short = 'o', long = "output")]
    output: PathBuf,
    /// Replace an existing output; an output that is or holds an input is refused even with
    /// it (docs/outputs.md).
    #[arg(long)]
    force: bool,
    /// Print every fitted number and the timings as JSON.
    #[arg(long)]
    json: bool,
    /// Write an HTML report with SVG plots into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum SensorArg {
    #[value(name = "1")]
    One,
    #[value(name = "2")]
    Two,
    Both,
}

/// `--json`: every fitted number. The keys are part of the interface.
#[derive(Debug, Serialize)]
struct Report {
    model: ModelKind,
    config: PathBuf,
    #[serde(skip_serializing_if = "Option::is_none")]
    report: Option<PathBuf>,
    prefilter: String,
    decimation: usize,
    samples_fitted: usize,
    sensors: Vec<SensorReport>,
    validation: Vec<Validation>,
    timings_s: Timings,
}

#[derive(Debug, Serialize)]
struct SensorReport {
    column: String,
    plane: SensorPlane,
    gauge_factor: f64,
    r0_ohm: f64,
    r2: f64,
    rmse_ohm: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    characteristic: Option<dlw::fit::Characteristic>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pi: Option<PlayReport>,
    #[serde(skip_serializing_if = "Option::is_none")]
    continuous_pi: Option<PlayReport>,
    models: Vec<ModelSummary>,
}

#[derive(Debug, Serialize)]
struct PlayReport {
    weights: Vec<f64>,
    radii: Vec<f64>,
    a: [f64; 8],
    center_ohm: f64,
    center_strain: f64,
    initial_state: f64,
    clamp_ohm: Option<(f64, f64)>,
    clamp_strain: Option<(f64, f64)>,
    rmse_ohm: f64,
    restarts: Vec<Restart>,
    evaluations: usize,
}

#[derive(Debug, Serialize)]
struct Restart {
    /// `"k = 0.5"` (Eq. 15's tanh with that slope multiplier) or `"linear"`.
    start: String,
    rmse_ohm: f64,
    converged: bool,
}

#[derive(Debug, Serialize)]
struct Timings {
    read: f64,
    observe: f64,
    linear: f64,
    pi: f64,
    continuous_pi: f64,
    validate: f64,
    total: f64,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = std::iter::once(&args.output).chain(&args.report).map(|p| p.as_path()).collect();
    dlw::output::claim_all(&outputs, [&args.design, &args.recording].into_iter().chain(&args.validate), args.force)?;
    let start = Instant::now();
    let format = ConfigFormat::of(&args.output)?;
    if !(2..=MAX_PLAYS).contains(&args.order) {
        bail!(
            "--order {} must lie between 2 and {MAX_PLAYS} play operators",
            args.order
        );
    }
    let design = Design::load(&args.design)?;
    let joint = design.joint;
    let recording = Recording::read(&args.recording)?;
    let validate = args
        .validate
        .as_ref()
        .map(|p| Recording::read(p))
        .transpose()?;
    let t_read = start.elapsed().as_secs_f64();
    let columns = recording.samples.volts.len();
    let bsn = joint.style() == NotchStyle::Bsn;
    let sensor = args.sensor.unwrap_or(if bsn && columns >= 2 {
        SensorArg::Both
    } else {
        SensorArg::One
    });
    let planes: &[SensorPlane] = match sensor {
        SensorArg::One => &[SensorPlane::PlusYs],
        SensorArg::Two => &[SensorPlane::MinusYs],
        SensorArg::Both => &[SensorPlane::PlusYs, SensorPlane::MinusYs],
    };
    if sensor != SensorArg::One && !bsn {
        bail!(
            "--sensor {} needs a BSN joint (two sensors); {} is UAN",
            if sensor == SensorArg::Two {
                "2"
            } else {
                "both"
            },
            args.design.display()
        );
    }
    let options = FitOptions {
        model: args.model,
        order: args.order,
        prefilter: args.prefilter,
        decimation: None,
    };
    let bar = super::spinner();
    let say = |m: &str| bar.set_message(m.to_owned());
    let mut fits: Vec<SensorFit> = Vec::new();
    for &plane in planes {
        say(&format!("sensor v{}_V", plane.column()));
        let fit = fit_sensor(&recording, &joint, plane, &options, &say).with_context(|| {
            format!(
                "fitting sensor v{}_V of {}",
                plane.column(),
                args.recording.display()
            )
        })?;
        fits.push(fit);
    }
    let config = estimator_config(&joint, &fits, args.model, args.prefilter)?;
    let clock = Instant::now();
    let validation = match &validate {
        None => Vec::new(),
        Some(rec) => {
            say("validating");
            [ModelKind::Linear, ModelKind::Pi, ModelKind::ContinuousPi]
                .into_iter()
                .map(|model| {
                    let result = estimator_config(&joint, &fits, model, args.prefilter)
                        .map_err(|e| e.to_string())
                        .and_then(|c| replay(&c, rec).map_err(|e| e.to_string()));
                    match result {
                        Ok(r) => Validation {
                            model,
                            rmse_deg: Some(r.metrics.rmse_deg),
                            error: None,
                        },
                        Err(e) => Validation {
                            model,
                            rmse_deg: None,
                            error: Some(e),
                        },
                    }
                })
                .collect()
        }
    };
    let t_validate = clock.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let note = format!(
        "Fitted by dlw fit ({} model, prefilter {}) from {} for {}.\nThe input filter is the fit's prefilter; the clamp range is the range the recording saw.",
        model_name(args.model),
        prefilter_name(args.prefilter),
        args.recording.display(),
        args.design.display()
    );
    let text = config_text(&config, format, &note)?;
    let name = args.recording.display().to_string();
    let page = args
        .report
        .as_ref()
        .map(|_| report_page(&name, &fits, &validation).files())
        .transpose()?;
    // Everything is computed: now write, the config last so a failed report leaves none.
    if let (Some(dir), Some(files)) = (&args.report, page) {
        dlw::output::write_folder_atomic(dir, &files)?;
    }
    write_atomic(&args.output, text.as_bytes())?;
    let sum = |i: usize| fits.iter().map(|f| f.seconds[i]).sum::<f64>();
    let report = Report {
        model: args.model,
        config: args.output.clone(),
        report: args.report.clone(),
        prefilter: prefilter_name(args.prefilter),
        decimation: fits[0].observations.decimation,
        samples_fitted: fits[0].observations.len(),
        sensors: fits.iter().map(sensor_report).collect(),
        validation,
        timings_s: Timings {
            read: t_read,
            observe: sum(0),
            linear: sum(1),
            pi: sum(2),
            continuous_pi: sum(3),
            validate: t_validate,
            total: start.elapsed().as_secs_f64(),
        },
    };
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&report).context("serializing the report")?
        );
    } else {
        print_text(&report);
    }
    Ok(())
}

fn prefilter_name(p: Prefilter) -> String {
    match p {
        Prefilter::None => "none".into(),
        Prefilter::MovingAverage(n) => format!("ma:{n}"),
    }
}

fn sensor_report(fit: &SensorFit) -> SensorReport {
    let play = |r: &Result<dlw::fit::PlayFit, String>, generalized: bool| {
        r.as_ref().ok().map(|p| {
            let (l, u) = (p.values.loading, p.values.unloading);
            let obs = &fit.observations;
            let strain = obs
                .strain
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &e| {
                    (a.min(e), b.max(e))
                });
            PlayReport {
                weights: p.values.weights.clone(),
                radii: p.model.radii.clone(),
                a: [l[0], l[1], l[2], l[3], u[0], u[1], u[2], u[3]],
                center_ohm: p.model.center_ohm,
                center_strain: p.model.center_strain,
                initial_state: p.initial_state,
                clamp_ohm: generalized.then_some(obs.ohm_range),
                clamp_strain: (!generalized).then_some(strain),
                rmse_ohm: p.rmse_ohm,
                restarts: p
                    .restarts
                    .iter()
                    .map(|r| Restart {
                        start: r.start.to_string(),
                        rmse_ohm: r.rmse_ohm,
                        converged: r.converged,
                    })
                    .collect(),
                evaluations: p.evaluations,
            }
        })
    };
    SensorReport {
        column: format!("v{}_V", fit.plane.column()),
        plane: fit.plane,
        gauge_factor: fit.linear.gauge_factor,
        r0_ohm: fit.linear.r0_ohm,
        r2: fit.linear.r2,
        rmse_ohm: fit.linear.rmse_ohm,
        characteristic: fit.characteristic,
        pi: play(&fit.pi, true),
        continuous_pi: play(&fit.continuous_pi, false),
        models: fit.summaries.clone(),
    }
}

fn print_text(r: &Report) {
    println!(
        "config {} ({} model)",
        r.config.display(),
        model_name(r.model)
    );
    for s in &r.sensors {
        println!("sensor {}", s.column);
        println!(
            "  linear  GF = {:.4}, R0 = {:.1} Ω, r² = {:.4}",
            s.gauge_factor, s.r0_ohm, s.r2
        );
        for m in &s.models {
            match &m.skipped {
                Some(why) => println!("  {:<14} not fitted: {why}", model_name(m.model)),
                None => println!(
                    "  {:<14} RMSE {:>9.1} Ω   BIC {:>12.1}   ({} parameters)",
                    model_name(m.model),
                    m.rmse_ohm,
                    m.bic,
                    m.parameters
                ),
            }
        }
    }
    for v in &r.validation {
        match (v.rmse_deg, &v.error) {
            (Some(rmse), _) => println!(
                "validation {:<14} angle RMSE {rmse:.3}°",
                model_name(v.model)
            ),
            (None, Some(e)) => println!("validation {:<14} {e}", model_name(v.model)),
            _ => {}
        }
    }
    if let Some(dir) = &r.report {
        println!("report {}", dir.join("report.html").display());
    }
    println!(
        "fitted {} samples (prefilter {}, every {}th) in {:.2} s",
        r.samples_fitted, r.prefilter, r.decimation, r.timings_s.total
    );
}
