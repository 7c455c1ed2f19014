//! The rest a recording starts with: the samples before the stroke first moves, where the
//! joint holds still and only the instruments' noise is seen. Discovery freezes its noise model
//! there; the clock check ([`super::clock`]) starts its blocks after it.

/// Bands of the stroke's own noise the stroke may stray from its start and still be at rest.
/// Five: over a rest of a few hundred samples a Gaussian noise leaves the band with a
/// probability of about 1e-4.
pub const REST_NOISE_BANDS: f64 = 5.0;

/// The first sample where the stroke has left its start: by more than 0.1 % of its span, or
/// [`REST_NOISE_BANDS`] times its own noise when that is larger. The start and the noise are
/// the median and the spread ([`spread`]) of the first second, where a recording starts at
/// rest. A stroke read by the DAQ through an analog channel (an LVDT, a potentiometer: `dlw
/// import-recording --stroke-scale`) carries the DAQ's noise; with the 0.1 % alone, a noise of
/// 1 µm on a 0.74 mm stroke ended the rest after 2.8 s of a 10 s one and the recording was
/// refused for want of a rest.
pub fn rest_end(stroke_mm: &[f64], dt_s: f64) -> usize {
    let n = stroke_mm.len();
    let first = &stroke_mm[..((1.0 / dt_s).round() as usize).clamp(1, n.max(1)).min(n)];
    let Some(start) = crate::stats::median(first) else {
        return 0;
    };
    let span = stroke_mm
        .iter()
        .fold(0.0_f64, |m, v| m.max((v - start).abs()));
    let band = (1e-3 * span.max(1e-9)).max(REST_NOISE_BANDS * spread(first));
    stroke_mm
        .iter()
        .position(|v| (v - start).abs() > band)
        .unwrap_or(n)
}

/// The spread of samples that hold still (a stroke at rest): their median absolute deviation,
/// ×1.4826 for a normal spread (so that a stray sample does not set it). A stroke recorded
/// without noise (a stage's encoder) has none.
pub fn spread(v: &[f64]) -> f64 {
    crate::stats::median_abs_deviation(v).map_or(0.0, |mad| 1.4826 * mad)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10 s rest at 25 Hz, then a 1 s ramp of 0.74 mm, with white noise of 0.25 µm: 0.1 % of
    /// the span (0.74 µm) is three spreads, which a few hundred samples exceed; five of the
    /// noise's own spreads they do not. The rest ends where the ramp starts, and a noise-free
    /// stroke's rest ends there too.
    #[test]
    fn the_rest_ends_where_the_stroke_moves_not_where_its_noise_strays() {
        let (dt, rest) = (0.04, 250);
        let clean: Vec<f64> = (0..1000)
            .map(|i| {
                if i < rest {
                    0.0
                } else {
                    (0.74 * (i - rest) as f64 * dt).min(0.74)
                }
            })
            .collect();
        let mut seed = 0x2545_F491_u64;
        let mut normal = || {
            let mut u = || {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 11) as f64 / (1u64 << 53) as f64 + 1e-12
            };
            let (a, b) = (u(), u());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        };
        let noisy: Vec<f64> = clean.iter().map(|x| x + 0.25e-3 * normal()).collect();
        for stroke in [&clean, &noisy] {
            let end = rest_end(stroke, dt);
            assert!((rest..rest + 3).contains(&end), "rest ends at {end}");
        }
        let sd = spread(&noisy[..rest]);
        assert!((0.2e-3..0.3e-3).contains(&sd), "{sd}");
        assert_eq!(spread(&clean[..rest]), 0.0);
        // The 0.1 % rule alone ends it early.
        let early = noisy
            .iter()
            .position(|v| (v - noisy[0]).abs() > 0.74e-3)
            .unwrap();
        assert!(early < rest, "{early}");
    }
}
