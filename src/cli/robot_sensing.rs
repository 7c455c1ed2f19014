//! The sensing side of the robot commands (issue 34 §4, `docs/robots.md`): `estimator-config`,
//! `simulate`, `estimate` and `fit` given a robot file, a robot recording or a robot config.

use std::path::Path;

use anyhow::Context;
use dlw::fit::robot_config::{robot_fit_config, robot_fit_note, RobotFitReport};
use dlw::output::write_atomic;
use dlw::recording::robot::RobotRecording;
use dlw::replay::robot::replay_robot;
use dlw::replay::{load_robot_config, robot_config_text, ConfigFormat};
use dlw::robot::estimator_config::{nominal_linear, nominal_note};
use dlw::sim::robot::{plan_robot, Coupling};
use dlw::sim::Scenario;

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
    let config = nominal_linear(&robot, gauge_factor, r0_ohm, divider_ohm, supply_v)?;
    let text = robot_config_text(&config, format, &nominal_note(&robot))?;
    write_atomic(output, text.as_bytes())?;
    println!(
        "wrote {}: {} joints, {} sensors, linear models, crosstalk from the geometry (largest off-diagonal {:.2} %)",
        output.display(),
        robot.robot.joints.len(),
        robot.sensors.len(),
        robot.largest_crosstalk() * 100.0
    );
    Ok(())
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
    let summary = plan.summary(&run, output);
    plan.recording(run)
        .write(output, force)
        .with_context(|| format!("writing recording {}", output.display()))?;
    print!("{summary}");
    Ok(())
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
        println!("{}", dlw::finite::to_json(&result.report(output))?);
        return Ok(());
    }
    super::print_warnings(&result.warnings);
    print!(
        "{}",
        result.summary(&recording_path.display().to_string(), output)
    );
    Ok(())
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
    let recording = RobotRecording::read_measured(recording_path)?;
    let fitted = dlw::fit::robot::fit_robot(&robot, &recording, model, order, prefilter)
        .with_context(|| format!("fitting {}", recording_path.display()))?;
    let config = robot_fit_config(&robot, &fitted, &recording.rig, model, prefilter)?;
    let name = recording_path.display().to_string();
    let text = robot_config_text(&config, format, &robot_fit_note(&robot, &fitted, &name))?;
    // Everything printed is computed before the config is written, so a failure leaves none.
    let report = json
        .then(|| {
            dlw::finite::to_json(&RobotFitReport {
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
    super::print_warnings(&fitted.warnings);
    print!("{}", fitted.summary(&name, output));
    Ok(())
}
