//! The sensing side of the robot commands (issue 34 §4, `docs/robots.md`): `estimator-config`,
//! `simulate`, `estimate` and `fit` given a robot file, a robot recording or a robot config.

use std::path::Path;

use anyhow::Context;
use dlw::output::write_atomic;
use dlw::recording::robot::RobotRecording;
use dlw::replay::robot::{replay_robot, JointMetrics, TipMetrics};
use dlw::replay::{load_robot_config, robot_config_text, ConfigFormat};
use dlw::robot::estimator_config::{estimator_config as config_of, nominal_linear, SensorSetting};
use dlw::sim::robot::{plan_robot, Coupling};
use dlw::sim::Scenario;
use dlw_geometry::Divider;
use serde::Serialize;

/// `dlw estimator-config ROBOT --gauge-factor G… --r0-ohm R… [--divider-ohm D…] -o cfg`.
pub(crate) fn estimator_config(
    path: &Path,
    gauge_factor: &[f64],
    r0_ohm: &[f64],
    divider_ohm: &[f64],
    supply_v: f64,
    output: &Path,
    format: ConfigFormat,
) -> anyhow::Result<()> {
    let robot = super::robot::load(path)?;
    let m = robot.sensors.len();
    let config = nominal_linear(&robot, gauge_factor, r0_ohm, divider_ohm, supply_v)?;
    let note = format!(
        "Nominal linear estimator config for the robot {:?} (robot checksum {}), written by dlw estimator-config\nbefore any characterization: {} joints, {} sensors, the crosstalk matrix from the geometry (dlw inspect).",
        robot.robot.name,
        robot.robot.checksum,
        robot.robot.joints.len(),
        m
    );
    let text = robot_config_text(&config, format, &note)?;
    write_atomic(output, text.as_bytes())?;
    println!(
        "wrote {}: {} joints, {} sensors, linear models, crosstalk from the geometry (largest off-diagonal {:.2} %)",
        output.display(),
        robot.robot.joints.len(),
        m,
        largest_crosstalk(&robot.crosstalk_matrix(), &robot.robot.sensors()) * 100.0
    );
    Ok(())
}

fn largest_crosstalk(c: &[Vec<f64>], sensors: &[dlw::robot::RobotSensor]) -> f64 {
    c.iter()
        .zip(sensors)
        .flat_map(|(row, s)| {
            row.iter()
                .enumerate()
                .filter(move |(j, _)| *j != s.joint)
                .map(|(_, v)| v.abs())
        })
        .fold(0.0, f64::max)
}

/// `dlw simulate --design ROBOT …`.
pub(crate) fn simulate(
    path: &Path,
    scenario: Scenario,
    coupling: Coupling,
    output: &Path,
    force: bool,
) -> anyhow::Result<()> {
    let robot = super::robot::load(path)?;
    let plan = plan_robot(&robot, scenario, coupling)
        .with_context(|| format!("simulating {:?}", robot.robot.name))?;
    let run = plan
        .run()
        .with_context(|| format!("simulating {:?}", robot.robot.name))?;
    let peaks: Vec<String> = run
        .true_angle_deg
        .iter()
        .map(|a| format!("{:.1}°", a.iter().fold(0.0f64, |m, x| m.max(x.abs()))))
        .collect();
    let recording = plan.recording(run);
    recording
        .write(output, force)
        .with_context(|| format!("writing recording {}", output.display()))?;
    let first = &plan.joints[0].scenario;
    println!(
        "wrote {}: {} samples ({} s at {} Hz), {} joints, {} sensors, {} protocol, seed {}, tendon coupling {}, peak angles {}",
        output.display(),
        plan.samples(),
        first.duration_s.unwrap_or(0.0),
        first.sample_hz,
        plan.joints.len(),
        plan.sensors.len(),
        first.protocol.map_or("?", |p| p.name()),
        first.seed,
        coupling.name(),
        peaks.join(", ")
    );
    Ok(())
}

/// What `estimate --json` prints for a robot; the keys are part of the interface.
#[derive(Debug, Serialize)]
struct EstimateReport {
    /// Per joint, against `angleK_deg`; absent without per-joint angles.
    #[serde(skip_serializing_if = "Option::is_none")]
    joints: Option<Vec<JointMetrics>>,
    /// Against the tracked tip; absent without tip columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    tip: Option<TipMetrics>,
    samples: usize,
    flagged_samples: usize,
    estimates: std::path::PathBuf,
    warnings: Vec<String>,
}

/// `dlw estimate --config ROBOT_CFG REC`.
pub(crate) fn estimate(
    config_path: &Path,
    recording_path: &Path,
    output: &Path,
    precision: u32,
    json: bool,
    report: Option<&Path>,
    design: Option<&Path>,
) -> anyhow::Result<()> {
    let config = load_robot_config(config_path)?;
    let recording = RobotRecording::read(recording_path)?;
    let geometry = design
        .map(|path| {
            let robot = super::robot::load(path)?;
            dlw::replay::robot_report::geometric_crosstalk(&config, &robot)
                .with_context(|| format!("the robot file {}", path.display()))
        })
        .transpose()?;
    let result = replay_robot(&config, &recording)
        .with_context(|| format!("estimating over {}", recording_path.display()))?;
    let page = report
        .map(|_| {
            dlw::replay::robot_report::robot_report(
                &config,
                &recording,
                &result,
                &recording_path.display().to_string(),
                geometry.as_deref(),
            )
            .files()
        })
        .transpose()
        .context("drawing the report")?;
    // The report first, so a failed report leaves no estimates behind.
    if let (Some(dir), Some(files)) = (report, page) {
        dlw::output::write_folder_atomic(dir, &files)?;
    }
    write_atomic(output, &result.csv_bytes(&recording, precision))?;
    if json {
        let report = EstimateReport {
            joints: result.joints.clone(),
            tip: result.tip,
            samples: result.samples,
            flagged_samples: result.flagged_samples,
            estimates: output.to_path_buf(),
            warnings: result.warnings.clone(),
        };
        println!("{}", dlw::finite::to_json(&report)?);
        return Ok(());
    }
    for w in &result.warnings {
        eprintln!("warning: {w}");
    }
    println!("{}", recording_path.display());
    println!("  samples             {}", result.samples);
    match &result.joints {
        Some(joints) => {
            for (j, m) in joints.iter().enumerate() {
                println!(
                    "  joint {}             RMSE {:.3}°, max |error| {:.3}°",
                    j + 1,
                    m.rmse_deg,
                    m.max_abs_deg
                );
            }
        }
        None => println!("  joints              — (no per-joint angles in the recording)"),
    }
    match &result.tip {
        Some(t) => println!(
            "  tip                 RMSE {:.3} mm, max {:.3} mm",
            t.rmse_mm, t.max_mm
        ),
        None => println!("  tip                 — (no tip columns in the recording)"),
    }
    println!("  flagged samples     {}", result.flagged_samples);
    println!("  estimates           {}", output.display());
    Ok(())
}

/// How the config's note says the crosstalk matrix was had.
fn crosstalk_source(fitted: &dlw::fit::robot::RobotFit) -> &'static str {
    if !fitted.crosstalk_fitted {
        return "the crosstalk matrix the geometry's (the recording cannot tell the joints apart)";
    }
    match fitted.angles_from {
        dlw::fit::robot::AnglesFrom::Joints => {
            "the crosstalk matrix fitted by least squares on the recorded joint angles"
        }
        dlw::fit::robot::AnglesFrom::Tip => {
            "the crosstalk matrix fitted by least squares on the joint angles from the tracked tip (inverse kinematics)"
        }
    }
}

/// What `fit --json` prints for a robot; the keys are part of the interface.
#[derive(Debug, Serialize)]
struct FitReport<'a> {
    #[serde(flatten)]
    fit: &'a dlw::fit::robot::RobotFit,
    config: std::path::PathBuf,
}

/// `dlw fit --design ROBOT REC [--model linear|pi] -o cfg`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn fit(
    path: &Path,
    recording_path: &Path,
    model: dlw::fit::ModelKind,
    order: dlw::fit::PlayOrder,
    prefilter: dlw::signal::Prefilter,
    output: &Path,
    format: ConfigFormat,
    json: bool,
) -> anyhow::Result<()> {
    let robot = super::robot::load(path)?;
    let recording = RobotRecording::read(recording_path)?;
    let fitted = dlw::fit::robot::fit_robot(&robot, &recording, model, order, prefilter)
        .with_context(|| format!("fitting {}", recording_path.display()))?;
    let settings = fitted
        .sensors
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let divider = Divider::new(recording.rig.divider_ohm[i], recording.rig.supply_v)
                .with_context(|| format!("sensor {}'s divider in rig.toml", i + 1))?;
            Ok(SensorSetting {
                model: s.model,
                divider,
            })
        })
        .collect::<anyhow::Result<Vec<_>>>()?;
    let crosstalk: Vec<Vec<f64>> = fitted.sensors.iter().map(|s| s.crosstalk.clone()).collect();
    let mut config = config_of(&robot, &settings, &crosstalk)
        .context("the fitted config (the runtime refused it)")?;
    if model != dlw::fit::ModelKind::Linear {
        // The one-joint fit's prefilter is its config's input filter.
        if let dlw::signal::Prefilter::MovingAverage(n) = prefilter {
            config.input_filter = dlw_estimator::FilterConfig::MovingAverage { samples: n };
        }
    }
    let note = format!(
        "Fitted by dlw fit from {} for the robot {:?} (robot checksum {}): {} model per sensor,\n{}.",
        recording_path.display(),
        robot.robot.name,
        robot.robot.checksum,
        fitted.model,
        crosstalk_source(&fitted)
    );
    let text = robot_config_text(&config, format, &note)?;
    // Everything printed is computed before the config is written, so a failure leaves none.
    let report = json
        .then(|| {
            dlw::finite::to_json(&FitReport {
                fit: &fitted,
                config: output.to_path_buf(),
            })
        })
        .transpose()?;
    write_atomic(output, text.as_bytes())?;
    if let Some(report) = report {
        println!("{report}");
        return Ok(());
    }
    for w in &fitted.warnings {
        eprintln!("warning: {w}");
    }
    println!(
        "{}: {} rows fitted, angle columns' condition number {}, {} model, crosstalk {}",
        recording_path.display(),
        fitted.samples_fitted,
        fitted
            .angle_condition
            .map_or("— (a joint did not move)".to_string(), |c| format!(
                "{c:.2}"
            )),
        fitted.model,
        if fitted.crosstalk_fitted {
            "fitted"
        } else {
            "kept from the geometry"
        }
    );
    if let Some(t) = &fitted.tip_angles {
        println!(
            "  angles from the tip {} of {} tracked rows used; dropped {} not identifiable, {} ambiguous, {} off the kinematics; tracker noise {:.3e} mm",
            t.used,
            t.rows,
            t.dropped_not_identifiable,
            t.dropped_ambiguous,
            t.dropped_off_kinematics,
            t.tip_noise_mm
        );
    }
    for (i, s) in fitted.sensors.iter().enumerate() {
        let row = |c: &[f64]| {
            c.iter()
                .map(|v| format!("{v:.4}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        println!(
            "  sensor {} (joint {} sensor {})  GF {:.4}, R0 {:.1} Ω, crosstalk [{}] (geometry [{}]), residual {:.1} Ω RMS",
            i + 1,
            s.joint,
            s.sensor,
            s.gauge_factor,
            s.r0_ohm,
            row(&s.crosstalk),
            row(&s.crosstalk_geometry),
            s.residual_rms_ohm
        );
    }
    println!("  config              {}", output.display());
    Ok(())
}
