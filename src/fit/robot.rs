//! A robot's sensors fitted from its recording (issue 34 §4, `dlw fit --design ROBOT REC`): each
//! sensor's model and its row of the crosstalk matrix.
//!
//! Under the sensing model (`docs/robot-runtime.md`) sensor `i` of joint `J` reads the mixed
//! angle `a_i = Σ_j C[i][j]·θ_j` through its joint's geometry, `ε_i = σ·k_J·a_i` (`k_J` the
//! joint's strain per radian, Eq. 3; `σ = −1` for a BSN joint's sensor 2), and, linear, Eq. 5:
//!
//! ```text
//! R_i = R0·(1 + GF·ε_i) = R0 + Σ_j (R0·GF·σ·k_J·C[i][j])·θ_j
//! ```
//!
//! which is linear in the recorded angles: a least-squares line `R_i = b_0 + Σ_j b_j·θ_j` over
//! the rows the tracker measured gives `R0 = b_0`, `GF = b_J/(R0·σ·k_J)` and
//! `C[i][j] = b_j/b_J` (so `C[i][J] = 1`), in closed form, with no start point to choose; the
//! geometry's row is reported beside it. The solve is checked before it is returned: the
//! recorded angles must move independently enough to tell the joints apart (every joint moves,
//! and the condition number of the standardized angle columns is at most
//! [`MAX_ANGLE_CONDITION`]); otherwise the crosstalk is not fitted, the geometry's rows are
//! kept, each sensor's line is fitted on its mixed angle through them, and a warning says so
//! (a characterization protocol drives every joint alike). The sensor must read its own joint
//! (`|b_J|` above its standard error by [`MIN_OWN_T`]); otherwise the fit refuses, naming the
//! sensor and the number. For `--model pi` the crosstalk comes from the
//! line, then each sensor's PI model is fitted by the one-joint fit on its own mixed angle
//! (a recording of that one sensor, `angle_deg = a_i`), exactly as for a joint alone.
//!
//! A recording without per-joint angles but with a tracked tip is fitted through the
//! kinematics: each row's angles from the tip by [`super::tip_angles`], the rows it cannot vouch
//! for marked invalid, then the same fit; [`RobotFit::angles_from`] says which.

use dlw_estimator::{LinearModel, ModelConfig};
use dlw_geometry::Divider;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;

use crate::recording::robot::RobotRecording;
use crate::recording::{Recording, Samples};
use crate::robot::{CheckedRobot, RobotSensor};

use super::tip_angles::MIN_SINGULAR_RATIO;
use super::tip_angles::{angles_from_tip, TipAnglesError, TipAnglesSummary, TipSolver};
use super::{fit, FitRequest, ModelKind, Prefilter};

/// The largest condition number of the standardized angle columns a fit accepts: above it the
/// joints moved too much alike for the recording to tell their shares of a sensor apart
/// (a crosstalk error of 0.02 needs the angles' independent parts to be well above the noise;
/// 30 leaves the smallest independent direction at 1/30 of the largest).
pub const MAX_ANGLE_CONDITION: f64 = 30.0;
/// The least ratio of a sensor's own-joint slope to its standard error: below it the recording
/// does not show the sensor reading its own joint.
pub const MIN_OWN_T: f64 = 10.0;

/// Why a robot fit was refused.
#[derive(Debug, thiserror::Error)]
pub enum RobotFitError {
    /// The recording is not of this robot.
    #[error("the robot has {joints} joints and {sensors} sensors, the recording {rec_joints} joint columns and {rec_sensors} voltage columns")]
    Shape {
        /// Joints of the robot.
        joints: usize,
        /// Sensors of the robot.
        sensors: usize,
        /// Joints in the recording.
        rec_joints: usize,
        /// Sensors in the recording.
        rec_sensors: usize,
    },
    /// Neither per-joint angles nor a tip.
    #[error("the recording has neither per-joint angles (angleK_deg empty) nor a tracked tip (tip_x_mm, tip_y_mm, tip_z_mm): there is no angle to fit the sensors against")]
    NoJointAngles,
    /// The angles could not be had from the tip.
    #[error("joint angles from the tracked tip: {0}")]
    Tip(#[from] TipAnglesError),
    /// Too few rows gave angles from the tip.
    #[error("joint angles from the tracked tip: {used} of {rows} tracked rows gave usable angles, at least {min} needed to fit {unknowns} numbers per sensor; dropped: {not_identifiable} not identifiable (the tip Jacobian's smallest singular value under {min_ratio} of its largest{largest}: some combination of the angles barely moves the tip; near straight the tip moves only sideways, its height being second order in the angles), {ambiguous} ambiguous (another set of angles within the joints' ranges puts the tip as close), {off} off the kinematics (no angles put the tip within {tolerance_mm:.3e} mm)")]
    TooFewTipRows {
        /// Rows with usable angles.
        used: usize,
        /// Rows tracked.
        rows: usize,
        /// Rows needed.
        min: usize,
        /// Unknowns per sensor.
        unknowns: usize,
        /// Rows dropped as not identifiable.
        not_identifiable: usize,
        /// Rows dropped as ambiguous.
        ambiguous: usize,
        /// Rows dropped as off the kinematics.
        off: usize,
        /// [`MIN_SINGULAR_RATIO`].
        min_ratio: f64,
        /// `", at most X in these rows"`, or nothing.
        largest: String,
        /// The residual tolerance (mm).
        tolerance_mm: f64,
    },
    /// Too few rows.
    #[error("{rows} rows with a tracked angle, at least {min} needed to fit {unknowns} numbers per sensor")]
    TooFewRows {
        /// Rows usable.
        rows: usize,
        /// Rows needed.
        min: usize,
        /// Unknowns per sensor.
        unknowns: usize,
    },
    /// A sensor does not read its own joint.
    #[error("sensor {sensor} (joint {joint} sensor {within}): its slope on its own joint is {slope:.3e} Ω/rad, only {t:.1} times its standard error (at least {min} needed): the recording does not show it reading its joint")]
    OwnJoint {
        /// 1-based sensor.
        sensor: usize,
        /// 1-based joint.
        joint: usize,
        /// 1 or 2.
        within: usize,
        /// The slope (Ω/rad).
        slope: f64,
        /// Its ratio to its standard error.
        t: f64,
        /// The least ratio.
        min: f64,
    },
    /// A fitted number is not usable (non-finite or refused by the model).
    #[error("sensor {sensor}: {message}")]
    Model {
        /// 1-based sensor.
        sensor: usize,
        /// What was wrong.
        message: String,
    },
}

/// One sensor's fit. The JSON keys are part of the interface.
#[derive(Debug, Clone, Serialize)]
pub struct SensorFitReport {
    /// Its joint, 1-based.
    pub joint: usize,
    /// Within its joint, 1 or 2.
    pub sensor: usize,
    /// The linear line's gauge factor.
    pub gauge_factor: f64,
    /// The linear line's unstrained resistance (Ω).
    pub r0_ohm: f64,
    /// The fitted crosstalk row (one per joint, own = 1).
    pub crosstalk: Vec<f64>,
    /// The geometry's row (`dlw inspect`), where the fit started from and what it is compared
    /// with.
    pub crosstalk_geometry: Vec<f64>,
    /// RMS of the line's residual resistance (Ω).
    pub residual_rms_ohm: f64,
    /// The model written to the config (linear, or PI fitted on the mixed angle).
    pub model: ModelConfig,
}

/// Where the fitted joint angles came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum AnglesFrom {
    /// The recording's `angleK_deg` columns.
    Joints,
    /// The tracked tip, by inverse kinematics ([`super::tip_angles`]).
    Tip,
}

/// A robot's fit.
#[derive(Debug, Clone, Serialize)]
pub struct RobotFit {
    /// Where the joint angles came from.
    pub angles_from: AnglesFrom,
    /// With angles from the tip: how many rows gave them, how many were dropped and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip_angles: Option<TipAnglesSummary>,
    /// One per sensor, in the robot's order.
    pub sensors: Vec<SensorFitReport>,
    /// Rows fitted (tracker valid).
    pub samples_fitted: usize,
    /// Condition number of the standardized angle columns; `None` when a joint did not move or
    /// the columns are exactly collinear.
    pub angle_condition: Option<f64>,
    /// Whether the crosstalk was fitted; `false` when the recording cannot tell the joints
    /// apart, and the geometry's rows are kept.
    pub crosstalk_fitted: bool,
    /// What the user should know (the crosstalk kept from the geometry, and why).
    pub warnings: Vec<String>,
    /// The model kind fitted.
    pub model: String,
}

/// Fits every sensor of `robot` on `recording`.
///
/// # Errors
/// [`RobotFitError`] naming the sensor or joint and the number that failed its check.
pub fn fit_robot(
    robot: &CheckedRobot,
    recording: &RobotRecording,
    model: ModelKind,
    order: crate::fit::PlayOrder,
    prefilter: Prefilter,
) -> Result<RobotFit, RobotFitError> {
    let s = &recording.samples;
    let joints = &robot.robot.joints;
    let n = joints.len();
    let sensors = robot.robot.sensors();
    if s.joints() != n || s.sensors() != sensors.len() {
        return Err(RobotFitError::Shape {
            joints: n,
            sensors: sensors.len(),
            rec_joints: s.joints(),
            rec_sensors: s.sensors(),
        });
    }
    let from_tip;
    let (recording, tip_angles) = if s.has_joint_angles() {
        (recording, None)
    } else {
        from_tip = with_angles_from_tip(robot, recording)?;
        (&from_tip.0, Some(from_tip.1.clone()))
    };
    let s = &recording.samples;
    let rows = fitted_rows(recording, n).map_err(|e| match (&e, &tip_angles) {
        (RobotFitError::TooFewRows { min, unknowns, .. }, Some(t)) => {
            RobotFitError::TooFewTipRows {
                used: t.used,
                rows: t.rows,
                min: *min,
                unknowns: *unknowns,
                not_identifiable: t.dropped_not_identifiable,
                ambiguous: t.dropped_ambiguous,
                off: t.dropped_off_kinematics,
                min_ratio: MIN_SINGULAR_RATIO,
                largest: t.largest_singular_ratio.map_or(String::new(), |r| {
                    format!(", at most {r:.3} at the angles found in these rows")
                }),
                tolerance_mm: t.tolerance_mm,
            }
        }
        _ => e,
    })?;
    let theta = |j: usize, i: usize| s.angle_deg[j][i].to_radians();
    let (angle_condition, still) = angle_conditioning(n, &rows, theta);
    let geometry = robot.crosstalk_matrix();
    let mut warnings = Vec::new();
    let crosstalk_fitted = still.is_none() && angle_condition <= MAX_ANGLE_CONDITION;
    // Exactly collinear columns give an infinite condition number, which no report carries.
    let angle_condition =
        (still.is_none() && angle_condition.is_finite()).then_some(angle_condition);
    if !crosstalk_fitted {
        warnings.push(cannot_separate(still, angle_condition));
    }
    let fitter = SensorFitter {
        robot,
        recording,
        rows: &rows,
        geometry: &geometry,
        crosstalk_fitted,
        kind: model,
        order,
        prefilter,
    };
    let out = sensors
        .iter()
        .enumerate()
        .map(|(i, sensor)| fitter.fit(i, sensor))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(RobotFit {
        angles_from: if tip_angles.is_some() {
            AnglesFrom::Tip
        } else {
            AnglesFrom::Joints
        },
        tip_angles,
        sensors: out,
        samples_fitted: rows.len(),
        angle_condition,
        crosstalk_fitted,
        model: super::model_name(model).to_string(),
        warnings,
    })
}

/// `recording` with every joint's angle from its tracked tip, and the rows not to use marked
/// invalid; or [`RobotFitError::NoJointAngles`] when it has no tip either.
fn with_angles_from_tip(
    robot: &CheckedRobot,
    recording: &RobotRecording,
) -> Result<(RobotRecording, TipAnglesSummary), RobotFitError> {
    let s = &recording.samples;
    let tip = s.tip_mm.as_ref().ok_or(RobotFitError::NoJointAngles)?;
    let joints = &robot.robot.joints;
    let sections: Vec<_> = joints.iter().map(|j| j.bending_section()).collect();
    // Every angle the tube can reach: up to its notches' closing, either way.
    let bounds: Vec<f64> = joints
        .iter()
        .map(|j| j.design().joint.closing_angle_rad())
        .collect();
    let solver = TipSolver::new(&sections, &bounds)?;
    let got = angles_from_tip(&solver, tip, |i| s.tracker_valid_at(i))?;
    let mut out = recording.clone();
    out.samples.angle_deg = got.angle_deg;
    out.samples.tracker_valid = got.used;
    Ok((out, got.summary))
}

/// The rows the tracker saw, or an error when they are too few for `n` joints' line.
fn fitted_rows(recording: &RobotRecording, n: usize) -> Result<Vec<usize>, RobotFitError> {
    let s = &recording.samples;
    let rows: Vec<usize> = (0..s.len()).filter(|&i| s.tracker_valid_at(i)).collect();
    let unknowns = n + 1;
    if rows.len() < 10 * unknowns {
        return Err(RobotFitError::TooFewRows {
            rows: rows.len(),
            min: 10 * unknowns,
            unknowns,
        });
    }
    Ok(rows)
}

/// The warning when the recording cannot tell the joints apart: the joint that did not move
/// (`still`), or else the angles' condition number.
fn cannot_separate(still: Option<(usize, f64)>, angle_condition: Option<f64>) -> String {
    let why = match still {
        Some((joint, std_deg)) => format!(
            "joint {joint}'s recorded angle does not move (standard deviation {std_deg:.2e}°)"
        ),
        None => format!(
            "the recorded angles' standardized columns have condition number {:.1}, above {MAX_ANGLE_CONDITION} (the joints moved together)",
            angle_condition.unwrap_or(f64::INFINITY)
        ),
    };
    format!(
        "cannot tell the joints apart: {why}; the crosstalk is not fitted and stays the geometry's (dlw inspect), and each sensor's model is fitted on its mixed angle through it. Record the joints moving independently to fit the crosstalk"
    )
}

/// What every sensor's line is fitted on.
struct SensorFitter<'a> {
    robot: &'a CheckedRobot,
    recording: &'a RobotRecording,
    /// The rows fitted (tracker valid).
    rows: &'a [usize],
    /// The geometry's crosstalk matrix.
    geometry: &'a [Vec<f64>],
    crosstalk_fitted: bool,
    kind: ModelKind,
    order: crate::fit::PlayOrder,
    prefilter: Prefilter,
}

impl SensorFitter<'_> {
    /// Joint `j`'s tracked angle (rad) at row `i`.
    fn theta(&self, j: usize, i: usize) -> f64 {
        self.recording.samples.angle_deg[j][i].to_radians()
    }

    /// Sensor `i`'s line, crosstalk row and model.
    fn fit(&self, i: usize, sensor: &RobotSensor) -> Result<SensorFitReport, RobotFitError> {
        let n = self.robot.robot.joints.len();
        let bad = |message: String| RobotFitError::Model {
            sensor: i + 1,
            message,
        };
        let divider = Divider::new(
            self.recording.rig.divider_ohm[i],
            self.recording.rig.supply_v,
        )
        .map_err(|e| bad(e.to_string()))?;
        let ohm: Vec<f64> = self
            .rows
            .iter()
            .map(|&r| divider.resistance(self.recording.samples.volts[i][r]))
            .collect::<Result<_, _>>()
            .map_err(|e| bad(e.to_string()))?;
        let y = DVector::from_vec(ohm);
        // The line on every joint's angle, or, when the joints cannot be told apart, on the
        // sensor's mixed angle through the geometry's row.
        let x = if self.crosstalk_fitted {
            DMatrix::from_fn(self.rows.len(), n + 1, |r, c| {
                if c == 0 {
                    1.0
                } else {
                    self.theta(c - 1, self.rows[r])
                }
            })
        } else {
            DMatrix::from_fn(self.rows.len(), 2, |r, c| {
                if c == 0 {
                    1.0
                } else {
                    (0..n)
                        .map(|j| self.geometry[i][j] * self.theta(j, self.rows[r]))
                        .sum()
                }
            })
        };
        let own = if self.crosstalk_fitted {
            sensor.joint + 1
        } else {
            1
        };
        let line = Line::fit(&x, &y).ok_or_else(|| {
            bad("the least-squares line has no unique solution (the angles do not vary)".into())
        })?;
        let t = line.b[own].abs() / line.standard_error[own];
        if !(t >= MIN_OWN_T) {
            return Err(RobotFitError::OwnJoint {
                sensor: i + 1,
                joint: sensor.joint + 1,
                within: sensor.sensor + 1,
                slope: line.b[own],
                t,
                min: MIN_OWN_T,
            });
        }
        let sign = if sensor.sensor == 1 { -1.0 } else { 1.0 };
        let k = self.robot.robot.joints[sensor.joint]
            .design()
            .joint
            .strain_per_rad();
        let r0_ohm = line.b[0];
        let gauge_factor = line.b[own] / (r0_ohm * sign * k);
        let crosstalk: Vec<f64> = if self.crosstalk_fitted {
            (0..n).map(|j| line.b[j + 1] / line.b[own]).collect()
        } else {
            self.geometry[i].clone()
        };
        let linear = LinearModel::new(gauge_factor, r0_ohm).map_err(|e| bad(e.to_string()))?;
        let model = match self.kind {
            ModelKind::Linear => ModelConfig::Linear(linear),
            kind => fit_on_mixed_angle(
                self.robot,
                self.recording,
                i,
                &crosstalk,
                kind,
                self.order,
                self.prefilter,
            )
            .map_err(bad)?,
        };
        Ok(SensorFitReport {
            joint: sensor.joint + 1,
            sensor: sensor.sensor + 1,
            gauge_factor,
            r0_ohm,
            crosstalk,
            crosstalk_geometry: self.geometry[i].clone(),
            residual_rms_ohm: line.residual_rms,
            model,
        })
    }
}

/// The condition number of the standardized angle columns over `rows`, and the first joint
/// (1-based) whose angle does not move, with its standard deviation (°).
fn angle_conditioning(
    n: usize,
    rows: &[usize],
    theta: impl Fn(usize, usize) -> f64,
) -> (f64, Option<(usize, f64)>) {
    let mut z = DMatrix::from_fn(rows.len(), n, |r, j| theta(j, rows[r]));
    for (j, mut col) in z.column_iter_mut().enumerate() {
        let mean = col.mean();
        col.add_scalar_mut(-mean);
        let std = (col.norm_squared() / rows.len() as f64).sqrt();
        // Below a microradian a joint has not moved for any tracker.
        if !(std > 1e-6) {
            return (f64::INFINITY, Some((j + 1, std.to_degrees())));
        }
        col /= std;
    }
    let sv = z.singular_values();
    (sv.max() / sv.min(), None)
}

/// A least-squares line with its coefficients' standard errors.
struct Line {
    b: DVector<f64>,
    standard_error: Vec<f64>,
    residual_rms: f64,
}

impl Line {
    fn fit(x: &DMatrix<f64>, y: &DVector<f64>) -> Option<Self> {
        let xtx_inv = (x.transpose() * x).try_inverse()?;
        let b = x.clone().svd(true, true).solve(y, 1e-12).ok()?;
        let residual = y - x * &b;
        let dof = (x.nrows() - x.ncols()) as f64;
        let sigma2 = residual.norm_squared() / dof;
        let standard_error = (0..x.ncols())
            .map(|c| (sigma2 * xtx_inv[(c, c)]).sqrt())
            .collect();
        Some(Self {
            b,
            standard_error,
            residual_rms: sigma2.sqrt(),
        })
    }
}

/// Sensor `i`'s model by the one-joint fit, on a recording of that sensor alone whose angle is
/// its mixed angle.
fn fit_on_mixed_angle(
    robot: &CheckedRobot,
    recording: &RobotRecording,
    i: usize,
    crosstalk: &[f64],
    kind: ModelKind,
    order: crate::fit::PlayOrder,
    prefilter: Prefilter,
) -> Result<ModelConfig, String> {
    let s = &recording.samples;
    let sensor = robot.robot.sensors()[i];
    let design = robot.robot.joints[sensor.joint].design();
    let mixed_deg: Vec<f64> = (0..s.len())
        .map(|r| {
            (0..s.joints())
                .map(|j| crosstalk[j] * s.angle_deg[j][r])
                .sum()
        })
        .collect();
    // Sensor 2 of a BSN joint is the second column of a joint's recording.
    let second = sensor.sensor == 1;
    let column = s.volts[i].clone();
    let (volts, divider_ohm) = if second {
        (
            vec![column.clone(), column],
            vec![recording.rig.divider_ohm[i]; 2],
        )
    } else {
        (vec![column], vec![recording.rig.divider_ohm[i]])
    };
    let one = Recording {
        rig: crate::recording::Rig {
            divider_ohm,
            ..recording.rig.clone()
        },
        samples: Samples {
            time_s: s.time_s.clone(),
            stroke_mm: s.stroke_mm[sensor.joint].clone(),
            angle_deg: mixed_deg,
            volts,
            tracker_valid: s.tracker_valid.clone(),
        },
    };
    let mut request = FitRequest::new(&design.joint, &one);
    request.model = kind;
    request.order = order;
    request.prefilter = prefilter;
    request.sensors = Some(crate::sensor::Sensors::Single(if second {
        crate::sensor::Sensor::Two
    } else {
        crate::sensor::Sensor::One
    }));
    let result = fit(&request, &|_| {}).map_err(|e| format!("its {kind:?} model: {e}"))?;
    Ok(result.estimator.sensor.model)
}
