//! The report of a robot's estimates (`dlw estimate --config ROBOT_CFG REC --report DIR`):
//! the robot's shape over time as small multiples, estimated against tracked; each joint's
//! error over time; the crosstalk matrix the config undid, against the geometry's when the robot
//! file is given. Every sentence is built from the numbers it states.

use dlw_estimator::RobotEstimatorConfig;

use crate::recording::robot::RobotRecording;
use crate::report::{Chart, Legend, Page, Series, SeriesStyle, Table, PALETTE};
use crate::robot::CheckedRobot;

use super::robot::{RobotReplay, RobotReplayError};

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

/// Largest `|config − geometry|` crosstalk entry at which the config is taken to hold the
/// geometry's matrix: a TOML or JSON round trip keeps it exact, and a fit differs by its noise
/// (at least 10⁻⁴ on the tests' recordings), so this only absorbs a matrix retyped to 6 places.
pub const SAME_CROSSTALK: f64 = 1e-6;

/// The geometry's crosstalk matrix of `robot` (`dlw inspect`'s), one row per sensor, checked to
/// be for the robot `config` describes: the same joints and the same sensors in the same order.
///
/// # Errors
/// [`RobotReplayError::Robot`] naming the first difference.
pub fn geometric_crosstalk(
    config: &RobotEstimatorConfig,
    robot: &CheckedRobot,
) -> Result<Vec<Vec<f64>>, RobotReplayError> {
    let sensors = robot.robot.sensors();
    let mismatch = |what: String| RobotReplayError::Robot {
        robot: robot.robot.name.clone(),
        what,
    };
    if config.joint_count() != robot.robot.joints.len() || config.sensor_count() != sensors.len() {
        return Err(mismatch(format!(
            "has {} joints and {} sensors, the config {} and {}",
            robot.robot.joints.len(),
            sensors.len(),
            config.joint_count(),
            config.sensor_count()
        )));
    }
    for (i, (c, s)) in config.sensor.iter().zip(&sensors).enumerate() {
        if c.joint as usize != s.joint + 1 || c.sensor as usize != s.sensor + 1 {
            return Err(mismatch(format!(
                "has {s} as sensor {}, the config joint {} sensor {}",
                i + 1,
                c.joint,
                c.sensor
            )));
        }
    }
    Ok(robot.crosstalk_matrix())
}

/// The report page. `geometry` is the robot's geometric crosstalk matrix
/// ([`geometric_crosstalk`]), drawn against the config's when given.
pub fn robot_report(
    config: &RobotEstimatorConfig,
    recording: &RobotRecording,
    replay: &RobotReplay,
    title: &str,
    geometry: Option<&[Vec<f64>]>,
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
    crosstalk(&mut page, config, geometry);
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

/// A crosstalk entry to 4 places, without the sign of a rounding residue (`-0.0000`).
fn entry(v: f64) -> String {
    let s = format!("{v:.4}");
    match s.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => s,
    }
}

/// The crosstalk matrix the config undid, one row per sensor, against the geometry's.
fn crosstalk(page: &mut Page, config: &RobotEstimatorConfig, geometry: Option<&[Vec<f64>]>) {
    let n = config.joint_count();
    page.heading("The crosstalk matrix, geometric against the config's");
    let Some(geometry) = geometry else {
        page.text(
            "The crosstalk the config undid, one row per sensor. The geometry's matrix is not \
             drawn against it: pass the robot file (--design ROBOT) for that.",
        );
        let mut header = vec!["sensor".to_string(), "joint, sensor".to_string()];
        header.extend((1..=n).map(|j| format!("joint {j}")));
        let mut table = Table::new(header);
        for (i, c) in config.sensor.iter().enumerate() {
            let mut row = vec![format!("{}", i + 1), format!("{}, {}", c.joint, c.sensor)];
            row.extend(c.crosstalk.iter().map(|&v| entry(v)));
            table.row(row);
        }
        page.table(table);
        return;
    };
    // The largest difference and where, over every entry.
    let mut worst = (0.0f64, 0, 0);
    for (i, (c, g)) in config.sensor.iter().zip(geometry).enumerate() {
        for (j, (a, b)) in c.crosstalk.iter().zip(g).enumerate() {
            if (a - b).abs() > worst.0 {
                worst = ((a - b).abs(), i, j);
            }
        }
    }
    let same = worst.0 <= SAME_CROSSTALK;
    let mut header = vec!["sensor".to_string(), "joint, sensor".to_string()];
    header.extend((1..=n).map(|j| {
        if same {
            format!("joint {j}")
        } else {
            format!("joint {j}: config (geometric)")
        }
    }));
    let mut table = Table::new(header);
    for (i, (c, g)) in config.sensor.iter().zip(geometry).enumerate() {
        let mut row = vec![format!("{}", i + 1), format!("{}, {}", c.joint, c.sensor)];
        row.extend(c.crosstalk.iter().zip(g).map(|(a, b)| {
            if same {
                entry(*a)
            } else {
                format!("{} ({})", entry(*a), entry(*b))
            }
        }));
        table.row(row);
    }
    page.table(table);
    // Each off-diagonal entry as a point (geometric, config); the diagonal is 1 in both.
    let mut chart = Chart::new(
        "Crosstalk: the config's against the geometry's",
        "geometric crosstalk C[i][j] (from the routing)",
        "config's crosstalk C[i][j]",
    );
    chart.size = (640, 520);
    chart.legend = Legend::UpperLeft;
    let mut lo = 0.0f64;
    let mut hi = 0.0f64;
    for (i, (c, g)) in config.sensor.iter().zip(geometry).enumerate() {
        let own = c.joint as usize - 1;
        let points: Vec<(f64, f64)> = g
            .iter()
            .zip(c.crosstalk.iter())
            .enumerate()
            .filter(|(j, _)| *j != own)
            .map(|(_, (&x, &y))| (x, y))
            .collect();
        for &(x, y) in &points {
            lo = lo.min(x).min(y);
            hi = hi.max(x).max(y);
        }
        let mut series = Series::dots(
            format!("sensor {} (joint {} sensor {})", i + 1, c.joint, c.sensor),
            points,
            PALETTE[i % PALETTE.len()],
        );
        series.style = SeriesStyle::Dots(6);
        chart.push(series);
    }
    // A square range with room above for the legend, so the line y = x is the diagonal.
    let span = (hi - lo).max(0.01);
    let (lo, hi) = (lo - 0.1 * span, hi + 0.1 * span);
    chart.push(Series::reference(
        "config = geometric",
        vec![(lo, lo), (hi, hi)],
        (120, 120, 120),
    ));
    chart.y_range = Some((lo, hi + 0.6 * (hi - lo)));
    let caption = if same {
        format!(
            "The config holds the geometry's crosstalk matrix (every entry within {SAME_CROSSTALK:e} of dlw inspect's): nothing fitted to compare, so every point lies on the line by construction."
        )
    } else {
        format!(
            "Each off-diagonal entry, the config's against the geometry's; on the line they agree. Largest difference {:.4} (sensor {}, joint {}).",
            worst.0,
            worst.1 + 1,
            worst.2 + 1
        )
    };
    page.figure("crosstalk", chart, caption);
}
