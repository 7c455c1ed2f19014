//! The baseline: the mean angle before bending began, subtracted from every angle (the paper's
//! "the mean value of the angle before bending commenced was subtracted").
//!
//! The pin is rarely mounted exactly along the joint, nor the joint exactly horizontal in the
//! image, so the angle at rest is an offset to remove. The window is either the first `T`
//! seconds (`--baseline-s T`) or, by default, every fitted frame before motion is detected: the
//! first frame whose unsmoothed angle differs from the first fitted frame's by more than a
//! threshold (`--motion-deg`) ends it. The mean is of the unsmoothed angles: the centred moving
//! average already carries the first motion into the last few frames before it.

use super::FluoroError;

/// How the baseline window is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BaselineRule {
    /// No baseline: angles are the fitted axis angles.
    Off,
    /// Frames with `time_s < first frame's time + seconds`.
    Seconds(f64),
    /// Frames before the first whose angle departs from the first fitted one by more than
    /// `threshold_deg`.
    UntilMotion {
        /// The departure that counts as motion (°).
        threshold_deg: f64,
    },
}

/// The baseline found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Baseline {
    /// The mean subtracted (°).
    pub mean_deg: f64,
    /// Fitted frames in the window.
    pub frames: usize,
    /// Time of the first frame after the window (s), `None` when the window is the whole
    /// series.
    pub end_s: Option<f64>,
}

/// The baseline of unwrapped, unsmoothed angles `raw_deg` (`None` for frames without a pin) at
/// `time_s`.
///
/// # Errors
/// [`FluoroError::EmptyBaseline`] when a `Seconds` window holds no fitted frame.
pub fn baseline(
    time_s: &[f64],
    raw_deg: &[Option<f64>],
    rule: BaselineRule,
) -> Result<Baseline, FluoroError> {
    let fitted = || {
        time_s
            .iter()
            .zip(raw_deg)
            .filter_map(|(&t, a)| a.map(|a| (t, a)))
    };
    let (end, window): (Option<f64>, Vec<f64>) = match rule {
        BaselineRule::Off => {
            return Ok(Baseline {
                mean_deg: 0.0,
                frames: 0,
                end_s: time_s.first().copied(),
            })
        }
        BaselineRule::Seconds(seconds) => {
            let t0 = time_s.first().copied().unwrap_or(0.0);
            let end = t0 + seconds;
            let window: Vec<f64> = fitted().filter(|(t, _)| *t < end).map(|(_, a)| a).collect();
            if window.is_empty() {
                return Err(FluoroError::EmptyBaseline {
                    baseline_s: seconds,
                });
            }
            (time_s.iter().copied().find(|&t| t >= end), window)
        }
        BaselineRule::UntilMotion { threshold_deg } => {
            let first = fitted().next().map_or(0.0, |(_, a)| a);
            let moving = fitted().find(|(_, a)| (a - first).abs() > threshold_deg);
            let end = moving.map(|(t, _)| t);
            let window = fitted()
                .take_while(|(t, _)| end.map_or(true, |e| *t < e))
                .map(|(_, a)| a)
                .collect();
            (end, window)
        }
    };
    let frames = window.len();
    Ok(Baseline {
        mean_deg: window.iter().sum::<f64>() / frames.max(1) as f64,
        frames,
        end_s: end,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_by_time_and_by_motion() {
        let t: Vec<f64> = (0..8).map(|k| k as f64 * 0.5).collect();
        let a = [
            Some(10.0),
            Some(10.4),
            None,
            Some(9.8),
            Some(14.0),
            Some(20.0),
            Some(25.0),
            Some(30.0),
        ];
        let b = baseline(&t, &a, BaselineRule::Seconds(1.6)).unwrap();
        assert_eq!((b.frames, b.end_s), (3, Some(2.0)));
        assert!((b.mean_deg - (10.0 + 10.4 + 9.8) / 3.0).abs() < 1e-12);
        let m = baseline(&t, &a, BaselineRule::UntilMotion { threshold_deg: 2.0 }).unwrap();
        assert_eq!(m, b);
        let off = baseline(&t, &a, BaselineRule::Off).unwrap();
        assert_eq!(off.mean_deg, 0.0);
        let none = [None, None, Some(1.0), Some(1.0), None, None, None, None];
        let err = baseline(&t, &none, BaselineRule::Seconds(1.0))
            .unwrap_err()
            .to_string();
        assert!(err.contains("first 1 s"), "{err}");
        let still = baseline(
            &t,
            &[Some(1.0); 8],
            BaselineRule::UntilMotion { threshold_deg: 2.0 },
        )
        .unwrap();
        assert_eq!((still.frames, still.end_s), (8, None));
    }
}
