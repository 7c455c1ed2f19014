//! `--sync CH`: the clocks from a sync pulse, a TTL signal recorded on the DAQ channel `CH`
//! and, per frame, in a column of the tracker log (`--tracker-sync-column NAME`).
//!
//! NDI Track and the Combined API sample log no digital input: the tracker column must come
//! from the lab's own logger, which reads the TTL line at each frame and writes its level
//! (any numbers, such as 0/1 or 0/5) in a column of the CSV. Each signal's threshold is half
//! way between its lowest and highest value; a rising edge is a crossing of it, timed by linear
//! interpolation between the samples around it (a frame's edge falls half way between the two
//! frames, on average where it happened). The `i`-th rising edge of the tracker log is taken to
//! be the `i`-th of the DAQ file, so both must see the first pulse; extra edges at the end of
//! the longer one are left out. Pulses at irregular intervals make a wrong pairing show (as a
//! drift no clock has, or edges off the line); with regular ones, a first pulse that one file
//! missed shifts the offset by one period unseen. A straight line through the pairs, DAQ time against tracker
//! time, gives `t = offset_s + τ·(1 + drift_ppm·10⁻⁶)`; the standard errors come from the
//! scatter about it, at least that of an edge known to within a tracker frame (`T/√12`).

/// The fewest paired edges: the drift needs two.
pub const MIN_EDGES: usize = 2;
/// The largest drift believed (ppm): crystal clocks stay within about 100 ppm, so a line
/// steeper than this pairs the wrong edges.
pub const MAX_DRIFT_PPM: f64 = 1000.0;

/// Why the clocks could not be aligned on the sync pulse.
#[derive(Debug, thiserror::Error)]
pub enum SyncError {
    /// A signal that never changes.
    #[error("the {what} sync signal stays at {level}: no edge to align on")]
    Flat {
        /// `DAQ` or `tracker`.
        what: &'static str,
        /// Its level.
        level: f64,
    },
    /// Too few edges.
    #[error("the DAQ's sync channel has {daq} rising edges and the tracker's column {tracker}; aligning needs at least {MIN_EDGES} in both")]
    TooFew {
        /// DAQ edges.
        daq: usize,
        /// Tracker edges.
        tracker: usize,
    },
    /// A drift no clock has.
    #[error("the sync edges give a drift of {drift_ppm:.0} ppm (at most {MAX_DRIFT_PPM} ppm is believed): the edges are paired wrongly; do both files see the first pulse, and the same pulses?")]
    Drift {
        /// The drift found (ppm).
        drift_ppm: f64,
    },
    /// Edges that do not line up.
    #[error("sync edge {edge} is {residual_ms:.1} ms off the line through the others (allowed: {allowed_ms:.1} ms): do both files see the first pulse, and the same pulses?")]
    Mismatch {
        /// The 1-based edge.
        edge: usize,
        /// Its residual (ms).
        residual_ms: f64,
        /// The allowed residual (ms).
        allowed_ms: f64,
    },
}

/// The clocks found on the pulse.
#[derive(Debug, Clone, PartialEq)]
pub struct PulseAlignment {
    /// `offset_s` (s).
    pub offset_s: f64,
    /// `drift_ppm`.
    pub drift_ppm: f64,
    /// Standard error of the offset (s).
    pub offset_uncertainty_s: f64,
    /// Standard error of the drift (ppm).
    pub drift_uncertainty_ppm: f64,
    /// Edges paired.
    pub edges: usize,
    /// Each edge pair's tracker time `τ` (s) and lag `t_daq − τ` (s).
    pub lags: Vec<(f64, f64)>,
}

/// The times of `level`'s rising edges through its mid level, sampled at `time`.
///
/// # Errors
/// [`SyncError::Flat`] for a signal that never changes.
pub fn rising_edges(
    time: &[f64],
    level: &[f64],
    what: &'static str,
) -> Result<Vec<f64>, SyncError> {
    let (lo, hi) = level
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return Err(SyncError::Flat {
            what,
            level: if lo.is_finite() { lo } else { 0.0 },
        });
    }
    let threshold = (lo + hi) / 2.0;
    Ok((1..level.len().min(time.len()))
        .filter(|&i| level[i - 1] < threshold && level[i] >= threshold)
        .map(|i| {
            let f = (threshold - level[i - 1]) / (level[i] - level[i - 1]);
            time[i - 1] + f * (time[i] - time[i - 1])
        })
        .collect())
}

/// The clocks from the edges of the DAQ (`daq_s`, DAQ time) and of the tracker (`tracker_s`,
/// tracker time), paired in order; `frame_s` is the tracker's frame period.
///
/// # Errors
/// [`SyncError::TooFew`]; [`SyncError::Drift`] for a drift beyond [`MAX_DRIFT_PPM`];
/// [`SyncError::Mismatch`] when a pair is more than a frame and a half off the line.
pub fn align(daq_s: &[f64], tracker_s: &[f64], frame_s: f64) -> Result<PulseAlignment, SyncError> {
    let n = daq_s.len().min(tracker_s.len());
    if n < MIN_EDGES {
        return Err(SyncError::TooFew {
            daq: daq_s.len(),
            tracker: tracker_s.len(),
        });
    }
    let (x, y) = (&tracker_s[..n], &daq_s[..n]);
    let mx = x.iter().sum::<f64>() / n as f64;
    let my = y.iter().sum::<f64>() / n as f64;
    let sxx: f64 = x.iter().map(|v| (v - mx).powi(2)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let slope = sxy / sxx;
    let intercept = my - slope * mx;
    let drift_ppm = (slope - 1.0) * 1e6;
    if drift_ppm.is_nan() || drift_ppm.abs() > MAX_DRIFT_PPM {
        return Err(SyncError::Drift { drift_ppm });
    }
    let allowed = 1.5 * frame_s;
    let residuals: Vec<f64> = x
        .iter()
        .zip(y)
        .map(|(a, b)| b - (intercept + slope * a))
        .collect();
    if let Some((edge, r)) = residuals
        .iter()
        .enumerate()
        .find(|(_, r)| r.is_nan() || r.abs() > allowed)
    {
        return Err(SyncError::Mismatch {
            edge: edge + 1,
            residual_ms: r * 1e3,
            allowed_ms: allowed * 1e3,
        });
    }
    // An edge between two frames is known to T/√12 at best.
    let floor = frame_s / 12f64.sqrt();
    let scatter = if n > 2 {
        (residuals.iter().map(|r| r * r).sum::<f64>() / (n - 2) as f64).sqrt()
    } else {
        0.0
    };
    let sigma = scatter.max(floor);
    Ok(PulseAlignment {
        lags: x.iter().zip(y).map(|(t, d)| (*t, d - t)).collect(),
        offset_s: intercept,
        drift_ppm,
        offset_uncertainty_s: sigma * (1.0 / n as f64 + mx * mx / sxx).sqrt(),
        drift_uncertainty_ppm: sigma / sxx.sqrt() * 1e6,
        edges: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edges_interpolate_and_pair_into_offset_and_drift() {
        let t: Vec<f64> = (0..10).map(f64::from).collect();
        let level = [0.0, 0.0, 5.0, 5.0, 0.0, 0.0, 0.0, 2.5, 5.0, 5.0];
        assert_eq!(rising_edges(&t, &level, "DAQ").unwrap(), [1.5, 7.0]);
        assert!(rising_edges(&t, &[1.0; 10], "DAQ").is_err());
        // t = 0.4 + τ·(1 + 200e-6).
        let tau = [1.0, 13.0, 29.0, 50.0];
        let daq: Vec<f64> = tau.iter().map(|x| 0.4 + x * (1.0 + 200e-6)).collect();
        let a = align(&daq, &tau, 0.025).unwrap();
        assert!(
            (a.offset_s - 0.4).abs() < 1e-9 && (a.drift_ppm - 200.0).abs() < 1e-6,
            "{a:?}"
        );
        // A pulse the tracker missed at the start shifts the pairs: refused.
        let err = align(&daq[1..], &tau, 0.025).unwrap_err();
        assert!(matches!(err, SyncError::Drift { .. }), "{err}");
        // One edge off by 60 ms.
        let mut late = daq.clone();
        late[2] += 0.06;
        let err = align(&late, &tau, 0.025).unwrap_err();
        assert!(matches!(err, SyncError::Mismatch { edge: 3, .. }), "{err}");
        assert!(matches!(
            align(&daq[..1], &tau, 0.025),
            Err(SyncError::TooFew { daq: 1, .. })
        ));
    }
}
