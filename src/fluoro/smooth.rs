//! The moving average over frames (the paper's "moving average filter of width 8").
//!
//! Centred, as an offline filter can be, so that the smoothed angle does not lag. An odd width
//! `N = 2h + 1` averages samples `k − h … k + h` with equal weights. An even width `N = 2h`
//! cannot be centred with equal weights, so it uses the centred `2×N` average of time-series
//! analysis: samples `k − h … k + h`, the two end samples with weight ½, the others 1, all over
//! `N`. Either way a ramp passes through unchanged and undelayed (a plain 8-sample window,
//! four before and three after, would shift it by half a frame). Near the ends of the series
//! the window is cut off and the weights that remain are renormalized. `N = 1` leaves the series
//! unchanged.

/// The centred moving average of `values` over `width` samples (`width ≥ 1`).
pub fn moving_average(values: &[f64], width: usize) -> Vec<f64> {
    let width = width.max(1);
    let half = width / 2;
    let end_weight = if width % 2 == 0 { 0.5 } else { 1.0 };
    let n = values.len();
    (0..n)
        .map(|k| {
            let lo = k.saturating_sub(half);
            let hi = (k + half).min(n.saturating_sub(1));
            let (mut sum, mut weights) = (0.0, 0.0);
            for (j, v) in values.iter().enumerate().take(hi + 1).skip(lo) {
                let w = if j.abs_diff(k) == half && half > 0 {
                    end_weight
                } else {
                    1.0
                };
                sum += w * v;
                weights += w;
            }
            sum / weights
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_window_shrinks_at_the_ends() {
        let v: Vec<f64> = (0..12).map(|k| (k * k) as f64).collect();
        let s = moving_average(&v, 8);
        // k = 6: samples 2..=10, the ends 2 and 10 with weight ½.
        let inner: f64 = (3..=9).map(|k| (k * k) as f64).sum();
        assert_eq!(s[6], (inner + 0.5 * (4.0 + 100.0)) / 8.0);
        // k = 0: samples 0..=4, sample 4 with weight ½, over 4.5.
        assert_eq!(s[0], (0.0 + 1.0 + 4.0 + 9.0 + 0.5 * 16.0) / 4.5);
        // Odd width: equal weights.
        assert_eq!(moving_average(&v, 3)[5], (16.0 + 25.0 + 36.0) / 3.0);
        assert_eq!(moving_average(&v, 1), v);
        // A ramp passes undelayed, away from the ends, for odd and even widths.
        let ramp: Vec<f64> = (0..20).map(f64::from).collect();
        for width in [2, 5, 8] {
            assert_eq!(moving_average(&ramp, width)[10], 10.0, "width {width}");
        }
    }
}
