//! Unwrapping axis angles across frames.
//!
//! An axis angle is known only modulo 180°: a pin at 95° and one at −85° look the same. Each
//! frame's angle is moved by the multiple of 180° that brings it closest to the previous frame's
//! unwrapped angle, so that a sweep past ±90° stays continuous. This assumes the pin turns by
//! less than 90° between consecutive fitted frames (at 2 Hz, less than 180°/s); the first fitted
//! frame stays in (−90°, 90°].

/// Unwraps `axis_deg` (each in (−90°, 90°]) in order; `None` entries (frames without a pin) are
/// passed through and do not break the chain.
pub fn unwrap_axis_deg(axis_deg: &[Option<f64>]) -> Vec<Option<f64>> {
    let mut previous: Option<f64> = None;
    axis_deg
        .iter()
        .map(|a| {
            let a = (*a)?;
            let u = match previous {
                None => a,
                Some(p) => a + 180.0 * ((p - a) / 180.0).round(),
            };
            previous = Some(u);
            Some(u)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fluoro::ellipse::axis_deg;

    #[test]
    fn a_sweep_past_plus_and_minus_90_stays_continuous() {
        let truth: Vec<f64> = (0..80).map(|k| -130.0 + 4.0 * k as f64).collect();
        let folded: Vec<Option<f64>> = truth.iter().map(|&t| Some(axis_deg(t))).collect();
        let u = unwrap_axis_deg(&folded);
        // The first frame is folded (−130° → 50°); every later one keeps the same offset.
        let offset = u[0].unwrap() - truth[0];
        assert_eq!(offset, 180.0);
        for (t, u) in truth.iter().zip(&u) {
            assert!((u.unwrap() - t - offset).abs() < 1e-9, "{t} {u:?}");
        }
    }

    #[test]
    fn gaps_pass_through() {
        let u = unwrap_axis_deg(&[Some(85.0), None, Some(-87.0), Some(-80.0)]);
        assert_eq!(u, [Some(85.0), None, Some(93.0), Some(100.0)]);
    }
}
