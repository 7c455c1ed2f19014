//! The robot estimator and its kinematics from C: `dlw_robot_estimator_*`.

use std::ffi::{c_char, c_int};
use std::panic::{catch_unwind, AssertUnwindSafe};

use runtime::{RobotEstimator, RobotEstimatorConfig, MAX_JOINTS, MAX_SENSORS};

use crate::{DLW_ERR_NULL, DLW_ERR_PANIC, DLW_OK};

/// A count argument (`n_volts`, `n_joints`) is not the robot's: nothing was done.
pub const DLW_ERR_LENGTH: c_int = -3;
/// An angle passed to `dlw_robot_estimator_tip` or `_backbone` is NaN or infinite: nothing was
/// written.
pub const DLW_ERR_NOT_FINITE: c_int = -4;

/// Most joints a robot estimator holds.
pub const DLW_MAX_JOINTS: usize = 8;
/// Most sensors a robot estimator holds.
pub const DLW_MAX_SENSORS: usize = 16;

const _: () = {
    assert!(DLW_MAX_JOINTS == MAX_JOINTS);
    assert!(DLW_MAX_SENSORS == MAX_SENSORS);
};

/// A robot estimator: opaque to C, created by `dlw_robot_estimator_from_toml`, freed by
/// `dlw_robot_estimator_free`.
pub struct DlwRobotEstimator {
    estimator: RobotEstimator,
}

/// Why a config was refused, as a message.
fn build(config_toml: &str) -> Result<DlwRobotEstimator, String> {
    let config: RobotEstimatorConfig = toml::from_str(config_toml)
        .map_err(|e| format!("robot estimator config: {}", e.to_string().trim_end()))?;
    let estimator =
        RobotEstimator::new(&config).map_err(|e| format!("invalid robot estimator config: {e}"))?;
    Ok(DlwRobotEstimator { estimator })
}

/// A new robot estimator from the text of a robot estimator config (TOML,
/// `docs/robot-runtime.md`), or NULL with the reason in `error` (`error_len` bytes,
/// NUL-terminated; `error` may be NULL). Free it with `dlw_robot_estimator_free`.
///
/// # Safety
/// `config_toml` is NULL or a NUL-terminated string; `error` is NULL or points to `error_len`
/// writable bytes.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_from_toml(
    config_toml: *const c_char,
    error: *mut c_char,
    error_len: usize,
) -> *mut DlwRobotEstimator {
    crate::from_toml(config_toml, error, error_len, build)
}

/// Joints `N` of the robot (0 for NULL).
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_joints(e: *const DlwRobotEstimator) -> usize {
    e.as_ref().map_or(0, |e| e.estimator.joint_count())
}

/// Sensors `M` of the robot: the voltages per sample (0 for NULL).
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_sensors(e: *const DlwRobotEstimator) -> usize {
    e.as_ref().map_or(0, |e| e.estimator.sensor_count())
}

/// Condition number of the robot's crosstalk matrix (0 for NULL).
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_condition_number(e: *const DlwRobotEstimator) -> f64 {
    e.as_ref()
        .map_or(0.0, |e| e.estimator.unmixing().condition_number())
}

/// Runs one sample: the sensors' divider voltages `volts[0..n_volts]` (V, in the config's
/// sensor order; `n_volts` must be the robot's sensor count) to every joint's angle (degrees)
/// in `angles_deg[0..n_joints]` and its `DLW_FLAG_*` bits in `flags[0..n_joints]` (`n_joints`
/// must be the robot's joint count). Returns `DLW_OK`, `DLW_ERR_NULL`, `DLW_ERR_LENGTH` or
/// `DLW_ERR_PANIC`. A flagged sample still returns `DLW_OK`. Does not allocate.
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed; `volts` is NULL or points
/// to `n_volts` doubles; `angles_deg` and `flags` are NULL or point to `n_joints` writable
/// values.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_step(
    e: *mut DlwRobotEstimator,
    volts: *const f64,
    n_volts: usize,
    angles_deg: *mut f64,
    flags: *mut u32,
    n_joints: usize,
) -> c_int {
    if e.is_null() || volts.is_null() || angles_deg.is_null() || flags.is_null() {
        return DLW_ERR_NULL;
    }
    let e = &mut *e;
    if n_volts != e.estimator.sensor_count() || n_joints != e.estimator.joint_count() {
        return DLW_ERR_LENGTH;
    }
    let volts = std::slice::from_raw_parts(volts, n_volts);
    let result = catch_unwind(AssertUnwindSafe(|| e.estimator.step(volts)));
    match result {
        Ok(estimate) => {
            let angles = std::slice::from_raw_parts_mut(angles_deg, n_joints);
            let out_flags = std::slice::from_raw_parts_mut(flags, n_joints);
            for (j, (angle, flag)) in angles.iter_mut().zip(out_flags).enumerate() {
                *angle = estimate.angle_deg(j);
                *flag = u32::from(estimate.flags()[j].bits());
            }
            DLW_OK
        }
        Err(_) => {
            let _ = catch_unwind(AssertUnwindSafe(|| e.estimator.reset()));
            DLW_ERR_PANIC
        }
    }
}

/// Joint angles in degrees to radians, or the return code saying why not.
///
/// # Safety
/// `angles_deg` points to `n_joints` doubles.
unsafe fn angles_rad(
    e: &DlwRobotEstimator,
    angles_deg: *const f64,
    n_joints: usize,
) -> Result<[f64; MAX_JOINTS], c_int> {
    if n_joints != e.estimator.joint_count() {
        return Err(DLW_ERR_LENGTH);
    }
    let mut out = [0.0; MAX_JOINTS];
    for (o, a) in out
        .iter_mut()
        .zip(std::slice::from_raw_parts(angles_deg, n_joints))
    {
        if !a.is_finite() {
            return Err(DLW_ERR_NOT_FINITE);
        }
        *o = a.to_radians();
    }
    Ok(out)
}

/// The tip's pose at joint angles `angles_deg[0..n_joints]` (degrees, joint 1 first), in the
/// robot's base frame (`docs/robot-runtime.md`): its position (mm) in `position_mm[0..3]`,
/// its rotation matrix in `rotation[0..9]` (row-major: `rotation[3*r + c]`; the columns are
/// the tip frame's axes, the third its tangent) and the same rotation as a unit quaternion
/// `w, x, y, z` (`w >= 0`) in `quaternion[0..4]`. Returns `DLW_OK`, `DLW_ERR_NULL`,
/// `DLW_ERR_LENGTH`, `DLW_ERR_NOT_FINITE` or `DLW_ERR_PANIC`. Does not allocate.
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed; `angles_deg` is NULL or
/// points to `n_joints` doubles; `position_mm`, `rotation` and `quaternion` are NULL or point
/// to 3, 9 and 4 writable doubles.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_tip(
    e: *const DlwRobotEstimator,
    angles_deg: *const f64,
    n_joints: usize,
    position_mm: *mut f64,
    rotation: *mut f64,
    quaternion: *mut f64,
) -> c_int {
    let Some(e) = e.as_ref() else {
        return DLW_ERR_NULL;
    };
    if angles_deg.is_null() || position_mm.is_null() || rotation.is_null() || quaternion.is_null() {
        return DLW_ERR_NULL;
    }
    let angles = match angles_rad(e, angles_deg, n_joints) {
        Ok(a) => a,
        Err(code) => return code,
    };
    let pose = catch_unwind(AssertUnwindSafe(|| {
        e.estimator.kinematics().tip(&angles[..n_joints])
    }));
    match pose {
        Ok(Ok(pose)) => {
            std::slice::from_raw_parts_mut(position_mm, 3).copy_from_slice(&pose.position_mm);
            let r = std::slice::from_raw_parts_mut(rotation, 9);
            for (row, values) in pose.rotation.iter().enumerate() {
                r[3 * row..3 * row + 3].copy_from_slice(values);
            }
            std::slice::from_raw_parts_mut(quaternion, 4).copy_from_slice(&pose.quaternion);
            DLW_OK
        }
        // The angles were checked above: a refusal here is a bug.
        Ok(Err(_)) | Err(_) => DLW_ERR_PANIC,
    }
}

/// `n_points` points of the backbone at joint angles `angles_deg[0..n_joints]` (degrees),
/// equally spaced in arc length from the base (first) to the tip (last), in
/// `points_mm[0..3*n_points]` as `x, y, z` triples (mm, base frame). Returns `DLW_OK`,
/// `DLW_ERR_NULL`, `DLW_ERR_LENGTH`, `DLW_ERR_NOT_FINITE` or `DLW_ERR_PANIC`. Does not
/// allocate.
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed; `angles_deg` is NULL or
/// points to `n_joints` doubles; `points_mm` is NULL or points to `3*n_points` writable doubles.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_backbone(
    e: *const DlwRobotEstimator,
    angles_deg: *const f64,
    n_joints: usize,
    points_mm: *mut f64,
    n_points: usize,
) -> c_int {
    let Some(e) = e.as_ref() else {
        return DLW_ERR_NULL;
    };
    if angles_deg.is_null() || points_mm.is_null() {
        return DLW_ERR_NULL;
    }
    let angles = match angles_rad(e, angles_deg, n_joints) {
        Ok(a) => a,
        Err(code) => return code,
    };
    // `[f64; 3]` has the layout of three doubles, so the caller's flat buffer is the points.
    let points = std::slice::from_raw_parts_mut(points_mm.cast::<[f64; 3]>(), n_points);
    let result = catch_unwind(AssertUnwindSafe(|| {
        e.estimator
            .kinematics()
            .backbone(&angles[..n_joints], points)
    }));
    match result {
        Ok(Ok(())) => DLW_OK,
        Ok(Err(_)) | Err(_) => DLW_ERR_PANIC,
    }
}

/// Resets every sensor's filters and model and forgets past estimates. NULL is ignored.
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_reset(e: *mut DlwRobotEstimator) {
    if let Some(e) = e.as_mut() {
        let _ = catch_unwind(AssertUnwindSafe(|| e.estimator.reset()));
    }
}

/// Frees a robot estimator. NULL is ignored.
///
/// # Safety
/// `e` is NULL or from `dlw_robot_estimator_from_toml` and not already freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_robot_estimator_free(e: *mut DlwRobotEstimator) {
    if !e.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| drop(Box::from_raw(e))));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use runtime::{nominal_divider, JointConfig, RobotJointConfig, RobotSensorConfig};
    use std::ffi::CStr;

    /// Joint B (UAN) at rotation 0 and a second Joint B at 90°, one sensor each; sensor 1's
    /// leads cross joint 2.
    fn config() -> RobotEstimatorConfig {
        let geometry = JointConfig {
            style: dlw_geometry::NotchStyle::Uan,
            outer_radius_mm: 0.8,
            inner_radius_mm: 0.61,
            notch_arc_mm: 3.52,
            notch_width_mm: 0.5,
            notch_spacing_mm: 0.5,
            notch_count: 10,
            joint_length_mm: 9.5,
            sensor_arc_mm: 0.4,
        };
        let joints = [
            RobotJointConfig {
                rotation_deg: 0.0,
                x_start_mm: 0.5,
                x_end_mm: 10.0,
                geometry,
            },
            RobotJointConfig {
                rotation_deg: 90.0,
                x_start_mm: 13.0,
                x_end_mm: 22.5,
                geometry,
            },
        ];
        let d = nominal_divider();
        let sensors = [
            RobotSensorConfig::linear(1, 1, 15.3, 215.0e3, d, &[1.0, 0.04]).unwrap(),
            RobotSensorConfig::linear(2, 1, 15.3, 215.0e3, d, &[0.0, 1.0]).unwrap(),
        ];
        RobotEstimatorConfig::new(&joints, &sensors).unwrap()
    }

    fn text() -> std::ffi::CString {
        std::ffi::CString::new(toml::to_string(&config()).unwrap()).unwrap()
    }

    #[test]
    fn step_tip_and_backbone_match_the_runtime_crate() {
        let mut direct = RobotEstimator::new(&config()).unwrap();
        let (mut angles, mut flags) = ([0.0; 2], [0u32; 2]);
        unsafe {
            let e = dlw_robot_estimator_from_toml(text().as_ptr(), std::ptr::null_mut(), 0);
            assert!(!e.is_null());
            assert_eq!(dlw_robot_estimator_joints(e), 2);
            assert_eq!(dlw_robot_estimator_sensors(e), 2);
            assert!(dlw_robot_estimator_condition_number(e) >= 1.0);
            for volts in [[2.6, 2.4], [5.0, 2.5], [2.45, f64::NAN], [2.55, 2.52]] {
                let rc = dlw_robot_estimator_step(
                    e,
                    volts.as_ptr(),
                    2,
                    angles.as_mut_ptr(),
                    flags.as_mut_ptr(),
                    2,
                );
                assert_eq!(rc, DLW_OK);
                let want = direct.step(&volts);
                for j in 0..2 {
                    assert_eq!(angles[j].to_bits(), want.angle_deg(j).to_bits());
                    assert_eq!(flags[j], u32::from(want.flags()[j].bits()));
                }
            }
            let (mut p, mut r, mut q) = ([0.0; 3], [0.0; 9], [0.0; 4]);
            let deg = [30.0, -45.0];
            let rc = dlw_robot_estimator_tip(
                e,
                deg.as_ptr(),
                2,
                p.as_mut_ptr(),
                r.as_mut_ptr(),
                q.as_mut_ptr(),
            );
            assert_eq!(rc, DLW_OK);
            let rad = [30f64.to_radians(), -45f64.to_radians()];
            let want = direct.kinematics().tip(&rad).unwrap();
            assert_eq!(p, want.position_mm);
            assert_eq!(q, want.quaternion);
            assert_eq!(&r[3..6], &want.rotation[1]);
            let mut points = [0.0; 3 * 7];
            let rc = dlw_robot_estimator_backbone(e, deg.as_ptr(), 2, points.as_mut_ptr(), 7);
            assert_eq!(rc, DLW_OK);
            let mut want = [[0.0; 3]; 7];
            direct.kinematics().backbone(&rad, &mut want).unwrap();
            assert_eq!(points.as_slice(), want.as_flattened());
            dlw_robot_estimator_reset(e);
            direct.reset();
            let volts = [2.6, 2.4];
            dlw_robot_estimator_step(
                e,
                volts.as_ptr(),
                2,
                angles.as_mut_ptr(),
                flags.as_mut_ptr(),
                2,
            );
            assert_eq!(
                angles[0].to_bits(),
                direct.step(&volts).angle_deg(0).to_bits()
            );
            dlw_robot_estimator_free(e);
        }
    }

    #[test]
    fn null_pointers_wrong_lengths_and_bad_angles_are_refused() {
        let (mut angles, mut flags) = ([7.0; 2], [7u32; 2]);
        let volts = [2.5, 2.5];
        unsafe {
            let e = dlw_robot_estimator_from_toml(text().as_ptr(), std::ptr::null_mut(), 0);
            let step = |e, v: *const f64, nv, a: *mut f64, f: *mut u32, nj| {
                dlw_robot_estimator_step(e, v, nv, a, f, nj)
            };
            let (a, f) = (angles.as_mut_ptr(), flags.as_mut_ptr());
            assert_eq!(
                step(std::ptr::null_mut(), volts.as_ptr(), 2, a, f, 2),
                DLW_ERR_NULL
            );
            assert_eq!(step(e, std::ptr::null(), 2, a, f, 2), DLW_ERR_NULL);
            assert_eq!(
                step(e, volts.as_ptr(), 2, std::ptr::null_mut(), f, 2),
                DLW_ERR_NULL
            );
            assert_eq!(step(e, volts.as_ptr(), 1, a, f, 2), DLW_ERR_LENGTH);
            assert_eq!(step(e, volts.as_ptr(), 2, a, f, 3), DLW_ERR_LENGTH);
            assert_eq!((angles, flags), ([7.0; 2], [7; 2]), "nothing written");
            let (mut p, mut r, mut q) = ([0.0; 3], [0.0; 9], [0.0; 4]);
            let nan = [f64::NAN, 0.0];
            let (pp, rp, qp) = (p.as_mut_ptr(), r.as_mut_ptr(), q.as_mut_ptr());
            assert_eq!(
                dlw_robot_estimator_tip(e, nan.as_ptr(), 2, pp, rp, qp),
                DLW_ERR_NOT_FINITE
            );
            assert_eq!(
                dlw_robot_estimator_tip(e, volts.as_ptr(), 1, pp, rp, qp),
                DLW_ERR_LENGTH
            );
            assert_eq!(
                dlw_robot_estimator_tip(std::ptr::null(), volts.as_ptr(), 2, pp, rp, qp),
                DLW_ERR_NULL
            );
            assert_eq!(p, [0.0; 3]);
            assert_eq!(
                dlw_robot_estimator_backbone(e, volts.as_ptr(), 2, std::ptr::null_mut(), 3),
                DLW_ERR_NULL
            );
            assert_eq!(dlw_robot_estimator_joints(std::ptr::null()), 0);
            dlw_robot_estimator_reset(std::ptr::null_mut());
            dlw_robot_estimator_free(std::ptr::null_mut());
            dlw_robot_estimator_free(e);
        }
    }

    #[test]
    fn a_bad_config_names_the_sensor_and_the_limit() {
        let mut bad = config();
        bad.sensor.as_mut_slice()[1].crosstalk.as_mut_slice()[1] = 0.5;
        let text = std::ffi::CString::new(toml::to_string(&bad).unwrap()).unwrap();
        let mut buf = [0 as c_char; 512];
        unsafe {
            let e = dlw_robot_estimator_from_toml(text.as_ptr(), buf.as_mut_ptr(), buf.len());
            assert!(e.is_null());
            let message = CStr::from_ptr(buf.as_ptr()).to_str().unwrap();
            assert_eq!(
                message,
                "invalid robot estimator config: sensor 2: crosstalk[2] = 0.5 is its own joint's and must be 1 (the sensor's gain lives in its model)"
            );
            let e =
                dlw_robot_estimator_from_toml(c"joint = 3".as_ptr(), buf.as_mut_ptr(), buf.len());
            assert!(e.is_null());
            let message = CStr::from_ptr(buf.as_ptr()).to_str().unwrap();
            assert!(message.starts_with("robot estimator config: "), "{message}");
        }
    }
}
