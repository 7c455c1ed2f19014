//! The tracker's angle on the DAQ's clock: each DAQ row's time mapped into tracker time by its
//! stretch's alignment, the angle linearly between the frames around it. A row gets no angle
//! (`tracker_valid = 0`) past the log's ends, across more than [`MAX_GAP_FRAMES`] frames where
//! the tool is missing, or across frames absent from the log (a [`Gap`](super::tracker::Gap)).

use super::angle::BendingAngles;
use super::tracker::TrackerLog;
use super::StretchJson;

/// The most frames with the tool missing that the angle is interpolated across: 75 ms at
/// 40 Hz, shorter than the joint's fastest ramp.
pub const MAX_GAP_FRAMES: usize = 3;

/// The stretch whose clock places DAQ time `t_s`: the one holding it, else the nearest.
fn stretch_at(stretches: &[StretchJson], t_s: f64) -> &StretchJson {
    stretches
        .iter()
        .find(|s| s.holds(t_s))
        .or_else(|| {
            stretches.iter().min_by(|a, b| {
                let d = |s: &StretchJson| (s.from_s - t_s).abs().min((s.to_s - t_s).abs());
                d(a).total_cmp(&d(b))
            })
        })
        .unwrap_or(&stretches[0])
}

/// Per aligned frame with the tool, for the check after the alignment ([`super::check`]):
/// its DAQ time (s) and its angle (°). A frame counts when its DAQ time, by a stretch's clocks,
/// falls in that stretch.
pub fn aligned_frames(
    log: &TrackerLog,
    angles: &BendingAngles,
    stretches: &[StretchJson],
) -> Vec<(f64, f64)> {
    log.tau_s
        .iter()
        .zip(&angles.angle_deg)
        .filter_map(|(&tau, angle)| {
            let angle = (*angle)?;
            stretches.iter().find_map(|s| {
                let t = s.daq_time(tau);
                s.holds(t).then_some((t, angle))
            })
        })
        .collect()
}

/// The tracker's angle at each DAQ time of `time_s`, and whether it is a measurement.
pub fn angle_on_daq(
    time_s: &[f64],
    log: &TrackerLog,
    angles: &BendingAngles,
    stretches: &[StretchJson],
) -> (Vec<f64>, Vec<bool>) {
    let frames = log.tau_s.len();
    let seen: Vec<bool> = angles.angle_deg.iter().map(Option::is_some).collect();
    // The last frame with the tool at or before each frame, and the first at or after it.
    let mut before = vec![None; frames];
    let mut last = None;
    for i in 0..frames {
        if seen[i] {
            last = Some(i);
        }
        before[i] = last;
    }
    let mut after = vec![None; frames];
    let mut next = None;
    for i in (0..frames).rev() {
        if seen[i] {
            next = Some(i);
        }
        after[i] = next;
    }
    let at = |t: f64| -> Option<f64> {
        let tau = stretch_at(stretches, t).tracker_time(t);
        let k = log.tau_s.partition_point(|&x| x <= tau);
        if k == 0 || k >= frames {
            return None;
        }
        let (p, q) = (before[k - 1]?, after[k]?);
        if q - p - 1 > MAX_GAP_FRAMES || log.gap_between(p, q) {
            return None;
        }
        let (a, b) = (angles.angle_deg[p]?, angles.angle_deg[q]?);
        let f = (tau - log.tau_s[p]) / (log.tau_s[q] - log.tau_s[p]);
        Some(a + (b - a) * f.clamp(0.0, 1.0))
    };
    time_s
        .iter()
        .map(|&t| at(t).map_or((0.0, false), |a| (a, true)))
        .unzip()
}
