//! The report of a robot's estimates (`dlw estimate --config ROBOT_CFG REC --report DIR`):
//! the robot's shape over time as small multiples, estimated against tracked; each joint's
//! error over time; the crosstalk matrix the config undid. Every sentence is built from the
//! numbers it states.

use dlw_estimator::RobotEstimatorConfig;

use crate::recording::robot::RobotRecording;
use crate::report::{Chart, Page, Series, Table};

use super::robot::RobotReplay;

/// Frames in the small multiples.
pub const SHAPE_FRAMES: usize = 8;
/// Points along the backbone per frame.
const BACKBONE_POINTS: usize = 24;

const ESTIMATED_X: (u8, u8, u8) = (31, 119, 180);
const ESTIMATED_Y: (u8, u8, u8) = (214, 39, 40);
const TRACKED_X: (u8, u8, u8) = (120, 170, 215);
const TRACKED_Y: (u8, u8, u8) = (240, 150, 150);

/// The backbone (mm, base frame) at `angles_deg`, or `None` where the kinematics refuse them.
fn backbone(config: &RobotEstimatorConfig, angles_deg: &[f64]) -> Option<Vec<[f64; 3]>> {
    let kinematics = config.kinematics().ok()?;
    let rad: Vec<f64> = angles_deg.iter().map(|a| a.to_radians()).collect();
    let mut points = vec![[0.0; 3]; BACKBONE_POINTS];
    kinematics.backbone(&rad, &mut points).ok()?;
    Some(points)
}

/// The report page.
pub fn robot_report(
    config: &RobotEstimatorConfig,
    recording: &RobotRecording,
    replay: &RobotReplay,
    title: &str,
) -> Page {
    let s = &recording.samples;
    let n = config.joint_count();
    let rows = s.len();
    let mut page = Page::new(format!("Robot estimates: {title}"));
    page.text(format!(
        "{rows} samples, {n} joints, {} sensors; {} samples flagged.",
        config.sensor_count(),
        replay.flagged_samples
    ));
    shape_over_time(&mut page, config, recording, replay);
    joint_errors(&mut page, config, recording, replay);
    if let Some(tip) = &replay.tip {
        page.text(format!(
            "The tip: RMSE {:.3} mm, max {:.3} mm against the tracked tip.",
            tip.rmse_mm, tip.max_mm
        ));
    }
    crosstalk(&mut page, config);
    page
}

/// The small multiples: the backbone at [`SHAPE_FRAMES`] times, estimated against tracked.
fn shape_over_time(
    page: &mut Page,
    config: &RobotEstimatorConfig,
    recording: &RobotRecording,
    replay: &RobotReplay,
) {
    let s = &recording.samples;
    let n = config.joint_count();
    let rows = s.len();
    page.heading("The shape over time");
    page.text(format!(
        "{SHAPE_FRAMES} frames equally spaced in time; each the backbone's x and y (mm, base frame) against z along the tube, estimated (solid) and, where the recording has every joint's angle, from the tracked angles through the same kinematics (dots)."
    ));
    let frame_row = |f: usize| {
        if rows > 1 {
            f * (rows - 1) / (SHAPE_FRAMES - 1)
        } else {
            0
        }
    };
    // One lateral scale for every frame, so the frames compare; the top half-again above it
    // leaves the legend clear of the curves.
    let reach = (0..SHAPE_FRAMES)
        .filter_map(|f| {
            let k = frame_row(f);
            let est: Vec<f64> = (0..n).map(|j| replay.angle_est_deg[j][k]).collect();
            backbone(config, &est)
        })
        .flatten()
        .fold(1.0f64, |m, p| m.max(p[0].abs()).max(p[1].abs()));
    for f in 0..SHAPE_FRAMES {
        let k = frame_row(f);
        let est: Vec<f64> = (0..n).map(|j| replay.angle_est_deg[j][k]).collect();
        let mut chart = Chart::new(format!("t = {:.2} s", s.time_s[k]), "z (mm)", "x, y (mm)");
        chart.size = (300, 260);
        chart.y_range = Some((-1.05 * reach, 1.8 * reach));
        if let Some(points) = backbone(config, &est) {
            let z: Vec<f64> = points.iter().map(|p| p[2]).collect();
            let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
            let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
            chart.push(Series::line("x est", Series::zip(&z, &x), ESTIMATED_X));
            chart.push(Series::line("y est", Series::zip(&z, &y), ESTIMATED_Y));
        }
        if s.has_joint_angles() {
            let tracked: Vec<f64> = (0..n).map(|j| s.angle_deg[j][k]).collect();
            if let Some(points) = backbone(config, &tracked) {
                let z: Vec<f64> = points.iter().map(|p| p[2]).collect();
                let x: Vec<f64> = points.iter().map(|p| p[0]).collect();
                let y: Vec<f64> = points.iter().map(|p| p[1]).collect();
                chart.push(Series::dots("x tracked", Series::zip(&z, &x), TRACKED_X));
                chart.push(Series::dots("y tracked", Series::zip(&z, &y), TRACKED_Y));
            }
        }
        let caption = format!(
            "angles {} (estimated)",
            est.iter()
                .map(|a| format!("{a:.1}°"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        page.figure(format!("shape-{}", f + 1), chart, caption);
    }
}

/// Each joint's error table and chart, where the recording tracks every joint's angle.
fn joint_errors(
    page: &mut Page,
    config: &RobotEstimatorConfig,
    recording: &RobotRecording,
    replay: &RobotReplay,
) {
    let s = &recording.samples;
    let n = config.joint_count();
    let rows = s.len();
    if let (Some(metrics), true) = (&replay.joints, s.has_joint_angles()) {
        page.heading("Each joint's error");
        let mut table = Table::new(["joint", "RMSE (°)", "max |error| (°)"]);
        for (j, m) in metrics.iter().enumerate() {
            table.row([
                format!("{}", j + 1),
                format!("{:.3}", m.rmse_deg),
                format!("{:.3}", m.max_abs_deg),
            ]);
        }
        page.table(table);
        let mut chart = Chart::new("Estimated − tracked", "time (s)", "error (°)");
        let palette = [
            (31, 119, 180),
            (214, 39, 40),
            (44, 160, 44),
            (148, 103, 189),
            (255, 127, 14),
            (140, 86, 75),
            (227, 119, 194),
            (127, 127, 127),
        ];
        for j in 0..n {
            let err: Vec<f64> = (0..rows)
                .map(|k| replay.angle_est_deg[j][k] - s.angle_deg[j][k])
                .collect();
            chart.push(Series::line(
                format!("joint {}", j + 1),
                Series::zip(&s.time_s, &err),
                palette[j % palette.len()],
            ));
        }
        page.figure(
            "joint-errors",
            chart,
            "each joint's estimate minus its tracked angle",
        );
    }
}

/// The crosstalk matrix the config undid, one row per sensor.
fn crosstalk(page: &mut Page, config: &RobotEstimatorConfig) {
    let n = config.joint_count();
    page.heading("The crosstalk the config undid");
    let mut header = vec!["sensor".to_string(), "joint, sensor".to_string()];
    header.extend((1..=n).map(|j| format!("joint {j}")));
    let mut table = Table::new(header);
    for (i, c) in config.sensor.iter().enumerate() {
        let mut row = vec![format!("{}", i + 1), format!("{}, {}", c.joint, c.sensor)];
        row.extend(c.crosstalk.iter().map(|v| format!("{:.4}", v)));
        table.row(row);
    }
    page.table(table);
}
