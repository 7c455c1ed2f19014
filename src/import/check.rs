//! The check after the alignment: with the clocks as found, the angle predicted from sensor 1's
//! voltage must agree with the tracker's angle in every window of about [`CHECK_WINDOW_S`]
//! along the recording. The prediction is one least-squares fit over every aligned frame,
//! `angle ≈ a + b·V + c·V²` (linear in its coefficients, as the alignment's correlation: the
//! square takes up the divider's curvature, which a straight line leaves as a 0.35° residual on
//! the test bench, enough to hide a 0.1 s slip of one half of the recording; the quadratic
//! leaves 0.06°).
//!
//! Each window's RMS departure from the prediction is measured at the clocks found, and again
//! with the sensor shifted by the lag (within ±[`LOCAL_LAG_S`]) that suits that window best. A
//! window fails when its departure exceeds [`LAG_RATIO`] times what it reaches at its own best
//! lag (its clocks do not line up: a DAQ or a tracker that lost samples the files do not show,
//! a compromise between two clocks), or [`WINDOW_RATIO`] times the median window's (the sensor
//! disagrees there in a way no shift mends) — unless it stays within [`CHECK_FLOOR_SHARE`] of
//! the angle's range, the accuracy the import promises anyway. Every limit is measured on the
//! recording itself; the import is refused naming the window that fails.

use super::align::{solve3, Signal};

/// The length of the windows checked (s of DAQ time), about.
pub const CHECK_WINDOW_S: f64 = 30.0;
/// How far each window's own best lag is searched (s): a slip the check must see is at least
/// tens of milliseconds; beyond half a second the window search of the alignment would have
/// refused already.
pub const LOCAL_LAG_S: f64 = 0.5;
/// The step of that search (s), or the DAQ's period if longer.
pub const LOCAL_LAG_STEP_S: f64 = 0.002;
/// How many times its own best-lag departure a window may reach. On the clean test bench every
/// window is within 1.03 times it (a linear sensor, and a hysteretic one aligned on itself);
/// the recording with a 0.1 s slip hidden in its middle reaches 2.6 times.
pub const LAG_RATIO: f64 = 2.0;
/// How many times the median window's departure a window may reach: a recording's windows
/// differ in how far and how fast the joint moves there, so this is loose (on the test bench
/// the worst window is 1.1 times the median with the linear sensor, 1.3 times with the
/// hysteretic one).
pub const WINDOW_RATIO: f64 = 4.0;
/// The share of the angle's range (its 1st to 99th percentile) a window's RMS departure may
/// always reach: 1 % is 0.34° on the test bench, the size of its 0.3° angle acceptance.
pub const CHECK_FLOOR_SHARE: f64 = 0.01;
/// The fewest aligned frames a window needs to be checked.
pub const MIN_CHECK_FRAMES: usize = 50;

/// One window's result.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WindowCheck {
    /// Its start (s of DAQ time).
    pub from_s: f64,
    /// Its end (s of DAQ time).
    pub to_s: f64,
    /// The RMS departure of the predicted angle from the tracker's at the clocks found (°).
    pub rms_deg: f64,
    /// The lag that suits this window best (s): the sensor at `t + lag` (0 when aligned).
    pub best_lag_s: f64,
    /// The RMS departure at that lag (°).
    pub best_rms_deg: f64,
    /// The limit it had to keep (°).
    pub limit_deg: f64,
    /// Frames in it.
    pub frames: usize,
}

/// What the check found: `check` in the import's JSON.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AlignmentCheck {
    /// Windows checked.
    pub windows: usize,
    /// The median window's RMS departure (°).
    pub median_deg: f64,
    /// The floor every limit keeps (°): [`CHECK_FLOOR_SHARE`] of the angle's range.
    pub floor_deg: f64,
    /// The window that came closest to its limit (its departure over its limit).
    pub worst: WindowCheck,
}

/// Why the check failed.
#[derive(Debug, thiserror::Error)]
pub enum CheckError {
    /// A window departs from the prediction.
    #[error("the check after the alignment fails in {:.1}–{:.1} s of DAQ time: the angle predicted from sensor 1 departs from the tracker's by {:.2}° RMS there (limit {:.2}°), where the sensor shifted by {:+.3} s would depart by {:.2}° and the median of the {} windows departs by {:.2}°: {}", .check.worst.from_s, .check.worst.to_s, .check.worst.rms_deg, .check.worst.limit_deg, .check.worst.best_lag_s, .check.worst.best_rms_deg, .check.windows, .check.median_deg, .why)]
    Window {
        /// The check's figures.
        check: AlignmentCheck,
        /// What it means, in words.
        why: &'static str,
    },
    /// Nothing to check.
    #[error("the check after the alignment has {frames} aligned frames with the tool; it needs at least {MIN_CHECK_FRAMES}")]
    TooFew {
        /// Frames.
        frames: usize,
    },
}

/// Checks the alignment on `frames` (per aligned tracker frame with the tool: its DAQ time (s)
/// and its angle (°)) against sensor 1's `signal`.
///
/// # Errors
/// [`CheckError`].
pub fn check(frames: &[(f64, f64)], signal: &Signal<'_>) -> Result<AlignmentCheck, CheckError> {
    let at =
        |lag: f64| -> Vec<Option<f64>> { frames.iter().map(|f| signal.at(f.0 + lag)).collect() };
    let aligned = at(0.0);
    let usable = aligned.iter().filter(|v| v.is_some()).count();
    if usable < MIN_CHECK_FRAMES {
        return Err(CheckError::TooFew { frames: usable });
    }
    // angle ≈ a + b·x + c·x², x = V − V̄ for conditioning.
    let centre = aligned.iter().flatten().sum::<f64>() / usable as f64;
    let mut m = [[0.0_f64; 3]; 3];
    let mut b = [0.0_f64; 3];
    for (f, v) in frames.iter().zip(&aligned) {
        let Some(v) = v else { continue };
        let x = v - centre;
        let row = [1.0, x, x * x];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * f.1;
        }
    }
    let coef = solve3(m, b).unwrap_or([b[0] / m[0][0], 0.0, 0.0]);
    let predict = |v: f64| {
        let x = v - centre;
        coef[0] + coef[1] * x + coef[2] * x * x
    };
    let (t0, t1) = frames
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| {
            (a.min(f.0), b.max(f.0))
        });
    let count = ((t1 - t0) / CHECK_WINDOW_S).round().max(1.0) as usize;
    let width = (t1 - t0) / count as f64;
    let window_of = |t: f64| (((t - t0) / width) as usize).min(count - 1);
    // RMS departure per window at a lag.
    let departure = |values: &[Option<f64>]| -> Vec<(f64, usize)> {
        let mut sums = vec![(0.0, 0usize); count];
        for (f, v) in frames.iter().zip(values) {
            if let Some(v) = v {
                let w = window_of(f.0);
                sums[w].0 += (f.1 - predict(*v)).powi(2);
                sums[w].1 += 1;
            }
        }
        sums.iter()
            .map(|&(ss, n)| ((ss / n.max(1) as f64).sqrt(), n))
            .collect()
    };
    let here = departure(&aligned);
    let step = LOCAL_LAG_STEP_S.max(signal.period_s);
    let steps = (LOCAL_LAG_S / step).round() as i64;
    let mut best: Vec<(f64, f64)> = here.iter().map(|&(r, _)| (r, 0.0)).collect();
    for k in -steps..=steps {
        let lag = k as f64 * step;
        for (w, &(r, n)) in departure(&at(lag)).iter().enumerate() {
            // Only a shift that keeps most of the window's frames on the samples counts.
            if 10 * n >= 9 * here[w].1 && r < best[w].0 {
                best[w] = (r, lag);
            }
        }
    }
    let mut angles: Vec<f64> = frames.iter().map(|f| f.1).collect();
    angles.sort_by(f64::total_cmp);
    let pick = |p: f64| angles[((angles.len() - 1) as f64 * p).round() as usize];
    let floor_deg = CHECK_FLOOR_SHARE * (pick(0.99) - pick(0.01));
    let checked: Vec<usize> = (0..count)
        .filter(|&w| here[w].1 >= MIN_CHECK_FRAMES)
        .collect();
    if checked.is_empty() {
        return Err(CheckError::TooFew { frames: usable });
    }
    let mut sorted: Vec<f64> = checked.iter().map(|&w| here[w].0).collect();
    sorted.sort_by(f64::total_cmp);
    let median_deg = sorted[sorted.len() / 2];
    let windows: Vec<WindowCheck> = checked
        .iter()
        .map(|&w| WindowCheck {
            from_s: t0 + w as f64 * width,
            to_s: t0 + (w + 1) as f64 * width,
            rms_deg: here[w].0,
            best_lag_s: best[w].1,
            best_rms_deg: best[w].0,
            limit_deg: (LAG_RATIO * best[w].0)
                .min(WINDOW_RATIO * median_deg)
                .max(floor_deg),
            frames: here[w].1,
        })
        .collect();
    let worst = windows
        .iter()
        .max_by(|a, b| (a.rms_deg / a.limit_deg).total_cmp(&(b.rms_deg / b.limit_deg)))
        .cloned()
        .unwrap_or_else(|| windows[0].clone());
    let result = AlignmentCheck {
        windows: windows.len(),
        median_deg,
        floor_deg,
        worst,
    };
    if result.worst.rms_deg > result.worst.limit_deg {
        let why = if result.worst.rms_deg > LAG_RATIO * result.worst.best_rms_deg {
            "the clocks do not line up there (did the DAQ or the tracker lose samples the files do not show, or are two runs in one file?)"
        } else {
            "the sensor and the tracker disagree there in a way no shift of the clocks mends (another tool, a loose sensor, a channel that changed?)"
        };
        return Err(CheckError::Window { check: result, why });
    }
    Ok(result)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sensor that follows a ramping angle, aligned, passes; the same with the second half
    /// 0.1 s late fails in a window of the second half; a window where the sensor reads
    /// nonsense fails as a disagreement.
    #[test]
    fn a_window_whose_clock_slipped_is_named() {
        let angle = |t: f64| 20.0 * (0.9 * t).sin() + 10.0 * (0.23 * t).sin();
        let time: Vec<f64> = (0..120_000).map(|i| f64::from(i) / 500.0).collect();
        let volts = |slip: f64, junk: bool| -> Vec<f64> {
            time.iter()
                .map(|&t| {
                    let late = if t > 120.0 { slip } else { 0.0 };
                    if junk && (60.0..90.0).contains(&t) {
                        3.0 + 0.2 * (37.0 * t).sin()
                    } else {
                        3.0 + 0.01 * angle(t - late)
                    }
                })
                .collect()
        };
        let frames: Vec<(f64, f64)> = (0..9500)
            .map(|k| {
                let t = 0.5 + f64::from(k) / 40.0;
                (
                    t,
                    angle(t) + 0.05 * ((k * 7919 % 1000) as f64 / 1000.0 - 0.5),
                )
            })
            .collect();
        let run = |slip: f64, junk: bool| {
            let v = volts(slip, junk);
            check(
                &frames,
                &Signal {
                    time_s: &time,
                    values: &v,
                    period_s: 0.002,
                },
            )
        };
        let ok = run(0.0, false).unwrap();
        assert_eq!(ok.windows, 8);
        assert!(ok.worst.rms_deg < ok.worst.limit_deg);
        let err = run(0.1, false).unwrap_err();
        let CheckError::Window { check, .. } = &err else {
            panic!("{err}")
        };
        assert!(check.worst.from_s >= 119.0, "{err}");
        assert!((check.worst.best_lag_s - 0.1).abs() < 0.01, "{err}");
        assert!(err.to_string().contains("do not line up"), "{err}");
        let err = run(0.0, true).unwrap_err();
        let CheckError::Window { check, .. } = &err else {
            panic!("{err}")
        };
        assert!((45.0..75.0).contains(&check.worst.from_s), "{err}");
        assert!(err.to_string().contains("no shift"), "{err}");
    }
}
