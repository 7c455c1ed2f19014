//! What an analysis sees of a recording: one sensor's own strain and resistance per sample,
//! after the prefilter and the decimation.

use dlw_estimator::{Filter, SensorPlane};
use dlw_geometry::Joint;

use super::{Prefilter, SignalError};
use crate::recording::Recording;
use crate::sensor::Sensor;

/// Smallest span of the recorded angle a fit accepts (°): below it the strain is noise.
pub const MIN_ANGLE_SPAN_DEG: f64 = 1.0;

/// A voltage within this fraction of the supply from either rail counts as at the rail: the
/// divider there resolves no resistance (a saturated ADC or an open or shorted sensor).
pub const RAIL_FRACTION: f64 = 1e-3;

/// A fit keeps at most about this many samples: the optimizer's cost grows with them while
/// the information in a slowly driven, prefiltered recording does not (`docs/fit.md` shows a
/// fit on every sample is no better).
pub const MAX_FIT_SAMPLES: usize = 8000;

/// One sensor's observations.
#[derive(Debug, Clone, PartialEq)]
pub struct Observations {
    /// Sample times (s).
    pub time_s: Vec<f64>,
    /// The recording's row of each kept sample (rows the tracker did not measure are left
    /// out, so this is not always every `decimation`-th row).
    pub rows: Vec<usize>,
    /// The sensor's own strain (fraction): `+ε` on `+y_s`, `−ε` on `−y_s` (Eq. 3).
    pub strain: Vec<f64>,
    /// The sensor's resistance (Ω, Eq. 4).
    pub ohm: Vec<f64>,
    /// Smallest and largest resistance seen after the prefilter (Ω): the range the runtime
    /// clamps to.
    pub ohm_range: (f64, f64),
    /// Samples between kept samples (1 = every sample).
    pub decimation: usize,
    /// Whether the prefiltered strain fell at each kept sample, judged against the sample just
    /// before it at the full rate (not the previous kept one): the direction the generalized PI
    /// model sees when the runtime steps through every sample.
    pub falling: Vec<bool>,
}

impl Observations {
    /// Number of samples kept.
    pub fn len(&self) -> usize {
        self.strain.len()
    }

    /// `true` when no sample was kept.
    pub fn is_empty(&self) -> bool {
        self.strain.is_empty()
    }
}

/// Reads the sensor on `plane` from `recording`: strain from the tracker angle through the
/// joint's geometry (Eq. 3), resistance from the voltage through the rig's divider (Eq. 4),
/// both through `prefilter` and then decimated by `decimation` (`None`: the prefilter's own,
/// or more to keep at most [`MAX_FIT_SAMPLES`]). A sample is kept only where the tracker
/// measured the angle (`tracker_valid`) on every row of the prefilter's window.
///
/// # Errors
/// [`SignalError::NoColumn`], [`SignalError::NoMotion`], [`SignalError::Rail`].
pub fn observe(
    recording: &Recording,
    joint: &Joint,
    plane: SensorPlane,
    prefilter: Prefilter,
    decimation: Option<usize>,
) -> Result<Observations, SignalError> {
    let column = plane.column() as usize;
    let s = &recording.samples;
    let rig = &recording.rig;
    let volts = s.volts.get(column - 1).ok_or(SignalError::NoColumn {
        column,
        columns: s.volts.len(),
    })?;
    // Rows whose angle the tracker did not measure (`tracker_valid = 0`) are left out.
    let (lo, hi) = s.valid_angle_range();
    if !(hi - lo >= MIN_ANGLE_SPAN_DEG) {
        return Err(SignalError::NoMotion {
            span_deg: (hi - lo).max(0.0),
            min_deg: MIN_ANGLE_SPAN_DEG,
        });
    }
    let margin = RAIL_FRACTION * rig.supply_v;
    let at_rail: Vec<usize> = (0..volts.len())
        .filter(|&i| volts[i] <= margin || volts[i] >= rig.supply_v - margin)
        .collect();
    if let Some(&first) = at_rail.first() {
        return Err(SignalError::Rail {
            column,
            count: at_rail.len(),
            time_s: s.time_s[first],
            volts: volts[first],
            margin_v: margin,
        });
    }
    let divider = rig
        .divider(Sensor::on_plane(plane))
        .ok_or(SignalError::NoColumn {
            column,
            columns: rig.divider_ohm.len(),
        })?;
    let mut strain_filter = Filter::new(&prefilter.filter_config()).map_err(SignalError::Filter)?;
    let mut ohm_filter = strain_filter.clone();
    let step = decimation
        .unwrap_or_else(|| {
            prefilter
                .decimation()
                .max(volts.len().div_ceil(MAX_FIT_SAMPLES))
        })
        .max(1);
    // The filters' warm-up: the first window is an average over fewer samples, which the
    // runtime also sees; it is kept.
    let n = volts.len();
    let mut out = Observations {
        time_s: Vec::with_capacity(n / step + 1),
        rows: Vec::with_capacity(n / step + 1),
        strain: Vec::with_capacity(n / step + 1),
        ohm: Vec::with_capacity(n / step + 1),
        ohm_range: (f64::INFINITY, f64::NEG_INFINITY),
        decimation: step,
        falling: Vec::with_capacity(n / step + 1),
    };
    let mut previous = f64::NEG_INFINITY;
    let sign = plane.sign();
    let window = prefilter.window();
    // Rows since the last one the tracker did not measure (`None`: none yet). A filtered
    // strain is kept only when its whole window is measured: the angle written on a
    // `tracker_valid = 0` row is no measurement, and averaged in it would bias the rows after
    // a gap (by 1.4 % of the gauge factor on the import test's bench with `ma:100`).
    let mut measured_run: Option<usize> = None;
    #[allow(clippy::needless_range_loop)] // four columns walk together by index
    for i in 0..n {
        let strain = sign * joint.strain(s.angle_deg[i].to_radians());
        let ohm = divider.resistance(volts[i]).unwrap_or(f64::NAN);
        let (strain, ohm) = (strain_filter.step(strain), ohm_filter.step(ohm));
        out.ohm_range = (out.ohm_range.0.min(ohm), out.ohm_range.1.max(ohm));
        measured_run = if s.angle_valid(i) {
            measured_run.map(|r| r + 1)
        } else {
            Some(0)
        };
        if i % step == 0 && measured_run.map_or(true, |r| r >= window) {
            out.time_s.push(s.time_s[i]);
            out.rows.push(i);
            out.strain.push(strain);
            out.ohm.push(ohm);
            out.falling.push(strain < previous);
        }
        previous = strain;
    }
    Ok(out)
}
