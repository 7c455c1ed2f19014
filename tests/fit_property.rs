//! Property tests of the PI fit (issue 15): on random generalized-PI sensors the fit, from its
//! default starts, recovers the forward response to within the noise, every time; on linear
//! data both PI models reproduce the line's RMSE to 1 %; and the fit does not depend on the
//! number of threads.

use dlw::fit::{characteristic, fit_plays_on, PlayKind, PlayModel};
use dlw::signal::{cycles, phases};
use proptest::prelude::*;

/// White noise of standard deviation σ from a seeded generator (uniform, scaled).
fn noise(seed: &mut u64, sigma: f64) -> f64 {
    *seed = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let u = (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
    sigma * 12f64.sqrt() * u
}

/// Loops of varying amplitude, as a characterization protocol drives them, sampled like the
/// fit's decimated observations.
fn strain(samples: usize, peak: f64) -> Vec<f64> {
    (0..samples)
        .map(|i| {
            let t = i as f64 * 30.0 / samples as f64;
            0.5 * peak * (1.0 - (t * 1.7).cos() * (0.75 + 0.25 * (t * 0.23).cos()))
        })
        .collect()
}

/// The library's own characteristic points and a fit on `threads` threads.
fn fit(
    kind: PlayKind,
    e: &[f64],
    ohm: &[f64],
    threads: usize,
) -> Result<dlw::fit::PlayFit, dlw::fit::FitError> {
    let (lo, hi) = e
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    let c = cycles(&phases(e, 0.1 * (hi - lo)));
    let points = characteristic(e, ohm, &c)?;
    fit_plays_on(kind, 10, e, ohm, &points, threads)
}

fn rms(a: &[f64], b: &[f64]) -> f64 {
    (a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum::<f64>() / a.len() as f64).sqrt()
}

const SIGMA: f64 = 20.0;

/// `PROPTEST_CASES` if set, else 12.
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(12)
}

proptest! {
    // 12 random sensors in CI (each a full PI fit of 4000 samples); `PROPTEST_CASES=N` for more.
    #![proptest_config(ProptestConfig { cases: cases(), ..ProptestConfig::default() })]

    /// A random generalized-PI sensor: tanh constants, ten evenly spaced radii up to a random
    /// ρ_max and random weights whose partial sums stay positive. The fitted response is within
    /// the noise σ of the true one.
    #[test]
    fn the_fit_recovers_a_random_pi_sensor(
        a1 in 5e3..40e3f64,
        reach in 0.3..2.5f64,
        a3 in -0.4..0.4f64,
        ratio in 0.93..1.07f64,
        slope_ratio in 0.9..1.1f64,
        a7_delta in -0.1..0.1f64,
        shift in -0.02..0.02f64,
        radius in 0.02..0.4f64,
        weights in proptest::collection::vec(0.0..0.6f64, 9),
        peak in 0.006..0.014f64,
        seed in 0u64..1000,
    ) {
        let e = strain(4000, peak);
        let center = 0.5 * peak;
        let a2 = reach / (0.5 * peak);
        let model = PlayModel {
            kind: PlayKind::Generalized,
            radii: (0..10).map(|i| radius * a1 * i as f64 / 9.0).collect(),
            center_strain: center,
            center_ohm: 200e3,
        };
        let mut w = vec![1.0];
        w.extend(weights);
        let theta = model.pack(
            [a1, a2, a3, 0.0],
            [a1 * ratio, a2 * slope_ratio, a3 + a7_delta, shift * a1],
            &w,
        );
        let mut clean = vec![0.0; e.len()];
        model.evaluate(&theta, &e, &mut clean);
        let mut s = seed;
        let ohm: Vec<f64> = clean.iter().map(|r| r + noise(&mut s, SIGMA)).collect();
        let fitted = fit(PlayKind::Generalized, &e, &ohm, 2).expect("a valid recording fits");
        let error = rms(&fitted.predict(&e), &clean);
        prop_assert!(
            error < SIGMA,
            "response error {error:.2} Ω against noise {SIGMA} Ω (fit RMSE {:.2} Ω, restarts {:?})",
            fitted.rmse_ohm,
            fitted.restarts
        );
    }
}

/// On a line with scatter, PI and continuous PI reproduce the line's RMSE to 1 %.
#[test]
fn on_linear_data_both_pi_models_match_the_line() {
    for (peak, gain, sigma) in [(0.012, 2.4e6, 40.0), (0.006, 9e5, 5.0), (0.02, 4e6, 200.0)] {
        let e = strain(5000, peak);
        let mut s = 17u64;
        let ohm: Vec<f64> = e
            .iter()
            .map(|x| 150e3 + gain * x + noise(&mut s, sigma))
            .collect();
        let n = e.len() as f64;
        let (me, mr) = (e.iter().sum::<f64>() / n, ohm.iter().sum::<f64>() / n);
        let slope = e
            .iter()
            .zip(&ohm)
            .map(|(x, r)| (x - me) * (r - mr))
            .sum::<f64>()
            / e.iter().map(|x| (x - me).powi(2)).sum::<f64>();
        let line: Vec<f64> = e.iter().map(|x| mr + slope * (x - me)).collect();
        let line_rmse = rms(&line, &ohm);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let f = fit(kind, &e, &ohm, 2).expect("fits");
            assert!(
                (f.rmse_ohm - line_rmse).abs() <= 0.01 * line_rmse,
                "{kind:?} peak {peak}: PI RMSE {} Ω, line {line_rmse} Ω",
                f.rmse_ohm
            );
        }
    }
}

/// The same model, to the last bit, on one thread and on two.
#[test]
fn one_or_two_threads_give_the_same_fit() {
    let e = strain(3000, 0.01);
    let model = PlayModel {
        kind: PlayKind::Generalized,
        radii: (0..10).map(|i| 600.0 * i as f64).collect(),
        center_strain: 0.005,
        center_ohm: 200e3,
    };
    let theta = model.pack(
        [20e3, 250.0, 0.1, 0.0],
        [19e3, 260.0, 0.0, 100.0],
        &[1.0, 0.2, 0.1, 0.3, 0.0, 0.1, 0.2, 0.0, 0.1, 0.05],
    );
    let mut ohm = vec![0.0; e.len()];
    model.evaluate(&theta, &e, &mut ohm);
    let mut s = 5u64;
    for r in &mut ohm {
        *r += noise(&mut s, SIGMA);
    }
    for kind in [PlayKind::Generalized, PlayKind::Continuous] {
        let one = fit(kind, &e, &ohm, 1).unwrap();
        let two = fit(kind, &e, &ohm, 2).unwrap();
        assert_eq!(one.theta, two.theta, "{kind:?}");
        assert_eq!(one.rmse_ohm.to_bits(), two.rmse_ohm.to_bits(), "{kind:?}");
    }
}
