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
//! Every entry point catches panics (`catch_unwind`), so none unwinds into C; the library is
//! built with the default `panic = "unwind"`, which that needs. [`dlw_estimator_step`] does not
//! allocate: the estimator's buffers are allocated once, by [`dlw_estimator_from_toml`].

use std::ffi::{c_char, c_int, CStr};
use std::panic::{catch_unwind, AssertUnwindSafe};

use runtime::{Estimator, EstimatorConfig, Flags};

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

// The C flag bits are the runtime crate's, checked at compile time.
const _: () = {
    assert!(DLW_FLAG_RAIL == Flags::RAIL.bits() as u32);
    assert!(DLW_FLAG_RESISTANCE_CLAMPED == Flags::RESISTANCE_CLAMPED.bits() as u32);
    assert!(DLW_FLAG_ATANH_CLAMPED == Flags::ATANH_CLAMPED.bits() as u32);
    assert!(DLW_FLAG_REVERSAL == Flags::REVERSAL.bits() as u32);
    assert!(DLW_FLAG_NON_FINITE == Flags::NON_FINITE.bits() as u32);
    assert!(DLW_FLAG_HELD == Flags::HELD.bits() as u32);
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
unsafe fn write_error(error: *mut c_char, error_len: usize, message: &str) {
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
