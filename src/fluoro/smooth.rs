//! The moving average over frames (the paper's "moving average filter of width 8").
//!
//! Centred, as an offline filter can be, so that the smoothed angle does not lag: sample `k`
//! averages samples `k − ⌊N/2⌋ … k + ⌊(N − 1)/2⌋` (for N = 8, four before and three after, as
//! MATLAB's `movmean`), and the window shrinks at both ends of the series rather than padding.
//! `N = 1` leaves the series unchanged.

/// The centred moving average of `values` over `width` samples (`width ≥ 1`).
pub fn moving_average(values: &[f64], width: usize) -> Vec<f64> {
    let width = width.max(1);
    let (before, after) = (width / 2, (width - 1) / 2);
    (0..values.len())
        .map(|k| {
            let lo = k.saturating_sub(before);
            let hi = (k + after + 1).min(values.len());
            values[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_window_shrinks_at_the_ends() {
        let v: Vec<f64> = (0..10).map(|k| (k * k) as f64).collect();
        let s = moving_average(&v, 8);
        // k = 5: samples 1..=8.
        let mid: f64 = (1..=8).map(|k| (k * k) as f64).sum::<f64>() / 8.0;
        assert_eq!(s[5], mid);
        // k = 0: samples 0..=3; k = 9: samples 5..=9.
        assert_eq!(s[0], (0.0 + 1.0 + 4.0 + 9.0) / 4.0);
        assert_eq!(s[9], (25.0 + 36.0 + 49.0 + 64.0 + 81.0) / 5.0);
        assert_eq!(moving_average(&v, 1), v);
        // A ramp is not delayed by an odd window.
        let ramp: Vec<f64> = (0..20).map(f64::from).collect();
        assert_eq!(moving_average(&ramp, 5)[10], 10.0);
    }
}
