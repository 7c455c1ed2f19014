//! C API of the runtime estimator (`dlw-estimator`): `libdlw_estimator.{a,so}` and
//! `include/dlw_estimator.h`.
//!
//! ```c
//! char err[256];
//! DlwEstimator *e = dlw_estimator_from_toml(config_text, err, sizeof err);
//! if (!e) { fprintf(stderr, "%s\n", err); return 1; }
//! double angle; uint32_t flags;
//! if (dlw_estimator_step(e, v1, v2, &angle, &flags) == DLW_OK) { ... }
//! dlw_estimator_free(e);
//! ```
//!
//! The robot estimator (several joints, crosstalk undone, the tip's pose) has the same shape
//! under `dlw_robot_estimator_*`: see [`robot`] and `docs/c-api.md`.
//!
//! Every entry point catches panics (`catch_unwind`), so none unwinds into C; the library is
//! built with the default `panic = "unwind"`, which that needs. [`dlw_estimator_step`] does not
//! allocate: the estimator's buffers are allocated once, by [`dlw_estimator_from_toml`].

use std::ffi::{c_char, c_int, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};

use runtime::{Estimator, EstimatorConfig, Flags};

pub mod robot;
pub use robot::*;

/// Success.
pub const DLW_OK: c_int = 0;
/// A pointer argument (`e`, `angle_deg` or `flags`) was NULL; nothing was done.
pub const DLW_ERR_NULL: c_int = -1;
/// The estimator panicked (a bug): the outputs are untouched and the estimator was reset.
pub const DLW_ERR_PANIC: c_int = -2;

/// Flag: a divider voltage at or beyond a rail (`V <= 0` or `V >= V+`).
pub const DLW_FLAG_RAIL: u32 = 1 << 0;
/// Flag: the resistance or strain lay outside the model's characterized range and was clamped.
pub const DLW_FLAG_RESISTANCE_CLAMPED: u32 = 1 << 1;
/// Flag: the argument of atanh in the PI inverse was clamped.
pub const DLW_FLAG_ATANH_CLAMPED: u32 = 1 << 2;
/// Flag: the PI inverse switched branch (a reversal of the strain) at this sample.
pub const DLW_FLAG_REVERSAL: u32 = 1 << 3;
/// Flag: an input, or a value computed from it, was NaN or infinite.
pub const DLW_FLAG_NON_FINITE: u32 = 1 << 4;
/// Flag: the angle is the last good one, held because this sample could not be used.
pub const DLW_FLAG_HELD: u32 = 1 << 5;
/// Flag: the continuous PI inverse's root search stopped at its iteration limit.
pub const DLW_FLAG_NOT_CONVERGED: u32 = 1 << 6;

// The C flag bits are the runtime crate's, checked at compile time.
const _: () = {
    assert!(DLW_FLAG_RAIL == Flags::RAIL.bits() as u32);
    assert!(DLW_FLAG_RESISTANCE_CLAMPED == Flags::RESISTANCE_CLAMPED.bits() as u32);
    assert!(DLW_FLAG_ATANH_CLAMPED == Flags::ATANH_CLAMPED.bits() as u32);
    assert!(DLW_FLAG_REVERSAL == Flags::REVERSAL.bits() as u32);
    assert!(DLW_FLAG_NON_FINITE == Flags::NON_FINITE.bits() as u32);
    assert!(DLW_FLAG_HELD == Flags::HELD.bits() as u32);
    assert!(DLW_FLAG_NOT_CONVERGED == Flags::NOT_CONVERGED.bits() as u32);
};

/// An estimator: opaque to C, created by `dlw_estimator_from_toml`, freed by
/// `dlw_estimator_free`.
pub struct DlwEstimator {
    estimator: Estimator,
    two_sensors: bool,
}

/// Why a config was refused: the message `dlw estimate` prints for it.
fn build(config_toml: &str) -> Result<DlwEstimator, String> {
    let config: EstimatorConfig = toml::from_str(config_toml)
        .map_err(|e| format!("estimator config: {}", e.to_string().trim_end()))?;
    let estimator =
        Estimator::new(&config).map_err(|e| format!("invalid estimator config: {e}"))?;
    Ok(DlwEstimator {
        estimator,
        two_sensors: config.second_sensor.is_some(),
    })
}

/// Writes `message` into `error` (at most `error_len` bytes, NUL-terminated, truncated at a
/// UTF-8 character boundary); nothing if `error` is NULL or `error_len` is 0.
///
/// # Safety
/// `error` is NULL or points to `error_len` writable bytes.
pub(crate) unsafe fn write_error(error: *mut c_char, error_len: usize, message: &str) {
    if error.is_null() || error_len == 0 {
        return;
    }
    let mut n = message.len().min(error_len - 1);
    while !message.is_char_boundary(n) {
        n -= 1;
    }
    std::ptr::copy_nonoverlapping(message.as_ptr(), error.cast::<u8>(), n);
    *error.add(n) = 0;
}

/// A new estimator from the text of an estimator config (TOML, as `dlw estimator-config` or
/// `dlw fit` write it), or NULL with the reason in `error` (`error_len` bytes, NUL-terminated;
/// `error` may be NULL). Free it with `dlw_estimator_free`.
///
/// # Safety
/// `config_toml` is NULL or a NUL-terminated string; `error` is NULL or points to `error_len`
/// writable bytes.
#[no_mangle]
pub unsafe extern "C" fn dlw_estimator_from_toml(
    config_toml: *const c_char,
    error: *mut c_char,
    error_len: usize,
) -> *mut DlwEstimator {
    from_toml(config_toml, error, error_len, build)
}

/// What every `*_from_toml` shares: `build` run on the config's text, never unwinding into C; a
/// new heap object, or NULL with the reason in `error` (NULL config, not UTF-8, refused, or a
/// panic).
///
/// # Safety
/// As the callers': `config_toml` is NULL or a NUL-terminated string; `error` is NULL or points
/// to `error_len` writable bytes.
pub(crate) unsafe fn from_toml<T>(
    config_toml: *const c_char,
    error: *mut c_char,
    error_len: usize,
    build: fn(&str) -> Result<T, String>,
) -> *mut T {
    let result = catch_unwind(AssertUnwindSafe(|| {
        if config_toml.is_null() {
            return Err("config_toml is NULL".to_string());
        }
        let text = CStr::from_ptr(config_toml)
            .to_str()
            .map_err(|e| format!("config_toml is not UTF-8: {e}"))?;
        build(text).map(Box::new)
    }));
    match result {
        Ok(Ok(estimator)) => Box::into_raw(estimator),
        Ok(Err(message)) => {
            write_error(error, error_len, &message);
            std::ptr::null_mut()
        }
        Err(_) => {
            write_error(
                error,
                error_len,
                "internal error (panic) while reading the config",
            );
            std::ptr::null_mut()
        }
    }
}

/// Runs one sample: divider voltages `v1` and `v2` (V; `v2` is ignored for a one-sensor
/// config) to the joint angle (degrees) in `*angle_deg` and the `DLW_FLAG_*` bits in `*flags`.
/// Returns `DLW_OK`, `DLW_ERR_NULL` or `DLW_ERR_PANIC`. A flagged sample still returns
/// `DLW_OK`: the flags say how far to trust the angle. Does not allocate.
///
/// # Safety
/// `e` is NULL or from `dlw_estimator_from_toml` and not freed; `angle_deg` and `flags` are
/// NULL or writable.
#[no_mangle]
pub unsafe extern "C" fn dlw_estimator_step(
    e: *mut DlwEstimator,
    v1: f64,
    v2: f64,
    angle_deg: *mut f64,
    flags: *mut u32,
) -> c_int {
    if e.is_null() || angle_deg.is_null() || flags.is_null() {
        return DLW_ERR_NULL;
    }
    let e = &mut *e;
    let result = catch_unwind(AssertUnwindSafe(|| {
        if e.two_sensors {
            e.estimator.step2(v1, v2)
        } else {
            e.estimator.step(v1)
        }
    }));
    match result {
        Ok(estimate) => {
            *angle_deg = estimate.angle_deg;
            *flags = u32::from(estimate.flags.bits());
            DLW_OK
        }
        Err(_) => {
            let _ = catch_unwind(AssertUnwindSafe(|| e.estimator.reset()));
            DLW_ERR_PANIC
        }
    }
}

/// Resets the estimator's state (filters, plays, last estimate) to that of a new one. NULL is
/// ignored.
///
/// # Safety
/// `e` is NULL or from `dlw_estimator_from_toml` and not freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_estimator_reset(e: *mut DlwEstimator) {
    if let Some(e) = e.as_mut() {
        let _ = catch_unwind(AssertUnwindSafe(|| e.estimator.reset()));
    }
}

/// Frees an estimator. NULL is ignored.
///
/// # Safety
/// `e` is NULL or from `dlw_estimator_from_toml` and not already freed.
#[no_mangle]
pub unsafe extern "C" fn dlw_estimator_free(e: *mut DlwEstimator) {
    if !e.is_null() {
        let _ = catch_unwind(AssertUnwindSafe(|| drop(Box::from_raw(e))));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use runtime::{nominal_divider, JointConfig};

    fn config_toml() -> std::ffi::CString {
        let joint = JointConfig {
            style: dlw_geometry::NotchStyle::Uan,
            outer_radius_mm: 1.24,
            inner_radius_mm: 0.875,
            notch_arc_mm: 5.61,
            notch_width_mm: 0.5,
            notch_spacing_mm: 0.5,
            notch_count: 10,
            joint_length_mm: 9.5,
            sensor_arc_mm: 0.4,
        };
        let config =
            EstimatorConfig::nominal_linear(joint, 15.3, 215.0e3, nominal_divider()).unwrap();
        std::ffi::CString::new(toml::to_string(&config).unwrap()).unwrap()
    }

    #[test]
    fn null_pointers_are_refused_not_dereferenced() {
        let (mut angle, mut flags) = (0.0, 0u32);
        unsafe {
            assert_eq!(
                dlw_estimator_step(std::ptr::null_mut(), 2.5, 0.0, &mut angle, &mut flags),
                DLW_ERR_NULL
            );
            let e = dlw_estimator_from_toml(config_toml().as_ptr(), std::ptr::null_mut(), 0);
            assert!(!e.is_null());
            assert_eq!(
                dlw_estimator_step(e, 2.5, 0.0, std::ptr::null_mut(), &mut flags),
                DLW_ERR_NULL
            );
            dlw_estimator_reset(std::ptr::null_mut());
            dlw_estimator_free(std::ptr::null_mut());
            dlw_estimator_free(e);
            assert!(dlw_estimator_from_toml(std::ptr::null(), std::ptr::null_mut(), 0).is_null());
        }
    }

    #[test]
    fn step_reset_and_flags_match_the_runtime_crate() {
        let text = config_toml();
        let config: EstimatorConfig = toml::from_str(text.to_str().unwrap()).unwrap();
        let mut direct = Box::new(Estimator::new(&config).unwrap());
        let (mut angle, mut flags) = (0.0, 0u32);
        unsafe {
            let e = dlw_estimator_from_toml(text.as_ptr(), std::ptr::null_mut(), 0);
            for v in [2.6, 2.4, 5.0, f64::NAN, 2.5] {
                assert_eq!(
                    dlw_estimator_step(e, v, 0.0, &mut angle, &mut flags),
                    DLW_OK
                );
                let want = direct.step(v);
                assert_eq!(angle.to_bits(), want.angle_deg.to_bits());
                assert_eq!(flags, u32::from(want.flags.bits()));
            }
            dlw_estimator_step(e, 5.0, 0.0, &mut angle, &mut flags);
            assert_eq!(flags, DLW_FLAG_RAIL | DLW_FLAG_HELD);
            dlw_estimator_reset(e);
            direct.reset();
            dlw_estimator_step(e, 2.6, 0.0, &mut angle, &mut flags);
            assert_eq!(angle.to_bits(), direct.step(2.6).angle_deg.to_bits());
            dlw_estimator_free(e);
        }
    }

    #[test]
    fn a_bad_config_names_the_reason_truncated_and_terminated() {
        let bad = std::ffi::CString::new("sensor = 3").unwrap();
        let mut buf = [0x55 as c_char; 16];
        unsafe {
            let e = dlw_estimator_from_toml(bad.as_ptr(), buf.as_mut_ptr(), buf.len());
            assert!(e.is_null());
            let message = CStr::from_ptr(buf.as_ptr()).to_str().unwrap();
            assert_eq!(message.len(), 15, "truncated to the buffer: {message:?}");
            assert!(message.starts_with("estimator conf"));
            let mut big = [0 as c_char; 512];
            dlw_estimator_from_toml(bad.as_ptr(), big.as_mut_ptr(), big.len());
            let full = CStr::from_ptr(big.as_ptr()).to_str().unwrap();
            assert!(full.contains("sensor"), "{full}");
        }
    }
}
