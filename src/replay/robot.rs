//! A robot's estimates over its recording (issue 34 §4, `dlw estimate --config ROBOT_CFG REC`):
//! the runtime's [`RobotEstimator`] run over every row (each sensor's model inverted to its mixed
//! angle, the crosstalk undone by the config's pseudo-inverse), the tip from its kinematics, and
//! the comparison with the recording's per-joint angles and tracked tip.

use dlw_estimator::{Flags, RobotEstimator, RobotEstimatorConfig};
use serde::Serialize;

use crate::fixed::push_fixed;
use crate::recording::robot::RobotRecording;

/// Why a robot's estimates could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RobotReplayError {
    /// The config and the recording disagree on the robot's joints or sensors.
    #[error("the config is for {config_joints} joints and {config_sensors} sensors, the recording has {joints} joint columns (strokeK_mm) and {sensors} voltage columns (vK_V)")]
    Shape {
        /// Joints in the config.
        config_joints: usize,
        /// Sensors in the config.
        config_sensors: usize,
        /// Joints in the recording.
        joints: usize,
        /// Sensors in the recording.
        sensors: usize,
    },
    /// The robot file given for the report is not the config's robot.
    #[error("robot {robot:?} is not the config's robot: it {what}")]
    Robot {
        /// The robot's name.
        robot: String,
        /// The first difference.
        what: String,
    },
    /// The runtime refused the config.
    #[error("the robot estimator: {0}")]
    Estimator(#[from] dlw_estimator::RobotError),
}

/// One joint's comparison with the recorded angle. The JSON keys are part of the interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JointMetrics {
    /// Root mean square of `estimate − recorded` (°).
    pub rmse_deg: f64,
    /// Largest `|estimate − recorded|` (°).
    pub max_abs_deg: f64,
}

/// The tip's comparison with the tracked tip. The JSON keys are part of the interface.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TipMetrics {
    /// Root mean square of the distance between estimated and tracked tip (mm).
    pub rmse_mm: f64,
    /// Largest distance (mm).
    pub max_mm: f64,
}

/// A robot's estimates for every row and their metrics.
#[derive(Debug, Clone)]
pub struct RobotReplay {
    /// Each joint's estimated angle per row (°).
    pub angle_est_deg: Vec<Vec<f64>>,
    /// The estimated tip per row (mm, base frame): x, y, z.
    pub tip_mm: [Vec<f64>; 3],
    /// The union of every joint's flags per row.
    pub flags: Vec<Flags>,
    /// Per joint, against `angleK_deg` (`None` without per-joint angles).
    pub joints: Option<Vec<JointMetrics>>,
    /// Against the tracked tip (`None` without tip columns).
    pub tip: Option<TipMetrics>,
    /// Rows compared (tracker valid).
    pub samples: usize,
    /// Rows whose estimate carried any flag.
    pub flagged_samples: usize,
    /// Things the user should know (a divider that differs from the rig).
    pub warnings: Vec<String>,
}

/// Runs `config`'s robot estimator over `recording`.
///
/// # Errors
/// [`RobotReplayError`]: a recording of another shape, or a config the runtime refuses.
pub fn replay_robot(
    config: &RobotEstimatorConfig,
    recording: &RobotRecording,
) -> Result<RobotReplay, RobotReplayError> {
    let s = &recording.samples;
    if s.joints() != config.joint_count() || s.sensors() != config.sensor_count() {
        return Err(RobotReplayError::Shape {
            config_joints: config.joint_count(),
            config_sensors: config.sensor_count(),
            joints: s.joints(),
            sensors: s.sensors(),
        });
    }
    let mut warnings = Vec::new();
    for (i, (c, &rig_ohm)) in config
        .sensor
        .iter()
        .zip(&recording.rig.divider_ohm)
        .enumerate()
    {
        if (c.divider_ohm - rig_ohm).abs() > 1e-9 * rig_ohm.abs() {
            warnings.push(format!(
                "sensor {} divider_ohm is {} Ω in the config but {} Ω in rig.toml",
                i + 1,
                c.divider_ohm,
                rig_ohm
            ));
        }
        if (c.supply_v - recording.rig.supply_v).abs() > 1e-9 * recording.rig.supply_v {
            warnings.push(format!(
                "sensor {} supply_v is {} V in the config but {} V in rig.toml",
                i + 1,
                c.supply_v,
                recording.rig.supply_v
            ));
        }
    }
    let mut estimator = Box::new(RobotEstimator::new(config)?);
    let n = s.len();
    let joints = config.joint_count();
    let mut angle_est_deg = vec![Vec::with_capacity(n); joints];
    let mut tip_mm: [Vec<f64>; 3] = Default::default();
    let mut flags = Vec::with_capacity(n);
    let mut volts = vec![0.0; s.sensors()];
    let mut flagged = 0;
    for i in 0..n {
        for (v, column) in volts.iter_mut().zip(&s.volts) {
            *v = column[i];
        }
        let e = estimator.step(&volts);
        for (j, out) in angle_est_deg.iter_mut().enumerate() {
            out.push(e.angle_deg(j));
        }
        let pose = estimator.tip(&e)?;
        for (c, v) in tip_mm.iter_mut().zip(pose.position_mm) {
            c.push(v);
        }
        let f = e.any_flags();
        flagged += usize::from(!f.is_empty());
        flags.push(f);
    }
    let rows: Vec<usize> = (0..n).filter(|&i| s.tracker_valid_at(i)).collect();
    let joint_metrics = s.has_joint_angles().then(|| {
        (0..joints)
            .map(|j| {
                let (mut sum_sq, mut max_abs) = (0.0f64, 0.0f64);
                for &i in &rows {
                    let err = angle_est_deg[j][i] - s.angle_deg[j][i];
                    sum_sq += err * err;
                    max_abs = max_abs.max(err.abs());
                }
                JointMetrics {
                    rmse_deg: (sum_sq / rows.len().max(1) as f64).sqrt(),
                    max_abs_deg: max_abs,
                }
            })
            .collect()
    });
    let tip = s.tip_mm.as_ref().map(|tracked| {
        let (mut sum_sq, mut max) = (0.0f64, 0.0f64);
        for &i in &rows {
            let d2: f64 = (0..3).map(|c| (tip_mm[c][i] - tracked[c][i]).powi(2)).sum();
            sum_sq += d2;
            max = max.max(d2.sqrt());
        }
        TipMetrics {
            rmse_mm: (sum_sq / rows.len().max(1) as f64).sqrt(),
            max_mm: max,
        }
    });
    Ok(RobotReplay {
        angle_est_deg,
        tip_mm,
        flags,
        joints: joint_metrics,
        tip,
        samples: rows.len(),
        flagged_samples: flagged,
        warnings,
    })
}

/// What `dlw estimate --json` prints for a robot; the keys are part of the interface.
#[derive(Debug, Serialize)]
pub struct RobotEstimateReport<'a> {
    /// Per joint, against `angleK_deg`; absent without per-joint angles.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joints: Option<&'a [JointMetrics]>,
    /// Against the tracked tip; absent without tip columns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip: Option<&'a TipMetrics>,
    /// Rows estimated.
    pub samples: usize,
    /// Rows the runtime flagged.
    pub flagged_samples: usize,
    /// The estimates file written.
    pub estimates: &'a std::path::Path,
    /// What the user should know.
    pub warnings: &'a [String],
}

impl RobotReplay {
    /// The JSON `dlw estimate --json` prints, the estimates written to `estimates`.
    pub fn report<'a>(&'a self, estimates: &'a std::path::Path) -> RobotEstimateReport<'a> {
        RobotEstimateReport {
            joints: self.joints.as_deref(),
            tip: self.tip.as_ref(),
            samples: self.samples,
            flagged_samples: self.flagged_samples,
            estimates,
            warnings: &self.warnings,
        }
    }

    /// The terminal's lines for the estimates over `recording_name`, written to `estimates`:
    /// each joint's error and the tip's, against what the recording holds.
    pub fn summary(&self, recording_name: &str, estimates: &std::path::Path) -> String {
        let mut out = format!("{recording_name}\n  samples             {}\n", self.samples);
        match &self.joints {
            Some(joints) => {
                for (j, m) in joints.iter().enumerate() {
                    out += &format!(
                        "  joint {}             RMSE {:.3}°, max |error| {:.3}°\n",
                        j + 1,
                        m.rmse_deg,
                        m.max_abs_deg
                    );
                }
            }
            None => out += "  joints              — (no per-joint angles in the recording)\n",
        }
        match &self.tip {
            Some(t) => {
                out += &format!(
                    "  tip                 RMSE {:.3} mm, max {:.3} mm\n",
                    t.rmse_mm, t.max_mm
                );
            }
            None => out += "  tip                 — (no tip columns in the recording)\n",
        }
        out += &format!("  flagged samples     {}\n", self.flagged_samples);
        out += &format!("  estimates           {}\n", estimates.display());
        out
    }

    /// `estimates.csv`: `time_s,angle1_est_deg,…,angleN_est_deg,tip_x_mm,tip_y_mm,tip_z_mm,flags`,
    /// angles and tip to `decimals` places, flags as the one-joint file's.
    pub fn csv_bytes(&self, recording: &RobotRecording, decimals: u32) -> Vec<u8> {
        let n = self.angle_est_deg.len();
        let rows = recording.samples.len();
        let mut out = Vec::with_capacity(rows * (16 + (n + 3) * (decimals as usize + 6)) + 128);
        out.extend_from_slice(b"time_s");
        for k in 1..=n {
            out.extend_from_slice(format!(",angle{k}_est_deg").as_bytes());
        }
        out.extend_from_slice(b",tip_x_mm,tip_y_mm,tip_z_mm,flags\n");
        for i in 0..rows {
            push_fixed(&mut out, recording.samples.time_s[i], 6);
            for column in self.angle_est_deg.iter().chain(&self.tip_mm) {
                out.push(b',');
                push_fixed(&mut out, column[i], decimals);
            }
            out.push(b',');
            out.extend_from_slice(self.flags[i].to_string().as_bytes());
            out.push(b'\n');
        }
        out
    }
}
