//! Per-sample cost of the estimator's models. Each benchmark feeds a block of 1000 samples
//! (a slow triangle wave with noise, so the PI models see reversals), and criterion reports
//! the time per block; divide by 1000 for the time per sample (the "thrpt" line gives
//! samples per second).
//!
//! Run: `cargo bench -p dlw-estimator --bench estimator -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dlw_estimator::{
    nominal_divider, Coeffs, ContinuousPiConfig, ContinuousPiInverse, Estimator, EstimatorConfig,
    FilterConfig, GeneralizedPi, JointConfig, ModelConfig, PiConfig, PiInverse,
};
use dlw_geometry::NotchStyle;

const BLOCK: usize = 1000;

#[path = "../tests/common/table_one.rs"]
mod table_one;
use table_one::joint;

/// Joint A's PI model from the paper's initial guesses, N = 10.
fn pi_n10() -> PiConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 2.5e3).collect();
    PiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_tanh: [26.0e3, 98.77, 0.0, 0.0],
        unloading_tanh: [26.0e3, 118.5, 0.05, -150.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_ohm: 200.0e3,
        max_ohm: 250.0e3,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    }
}

fn continuous_pi_n10() -> ContinuousPiConfig {
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 1.0e3).collect();
    ContinuousPiConfig {
        weights: Coeffs::from_slice("weights", &[0.1; 10]).unwrap(),
        radii: Coeffs::from_slice("radii", &radii).unwrap(),
        loading_envelope: [26.0e3, 98.77, 0.0, 0.0],
        unloading_envelope: [26.0e3, 98.77, 0.1, 0.0],
        center_strain: 0.00307,
        center_ohm: 224.0e3,
        min_strain: -0.01,
        max_strain: 0.02,
        strain_tolerance: 1e-12,
        resistance_tolerance_ohm: 0.0,
        initial_state: 0.0,
    }
}

/// Strain: a triangle between 0 and 1.35 % over 400 samples plus ±0.005 % noise.
fn strains() -> Vec<f64> {
    let mut seed = 0x2545_f491_4f6c_dd1d_u64;
    (0..BLOCK)
        .map(|k| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let noise = (seed as f64 / u64::MAX as f64 - 0.5) * 1e-4;
            let phase = (k % 400) as f64 / 200.0;
            let triangle = if phase < 1.0 { phase } else { 2.0 - phase };
            0.0135 * triangle + noise
        })
        .collect()
}

/// Resistances the Joint A PI model gives for the strain sequence.
fn pi_resistances() -> Vec<f64> {
    let mut forward = GeneralizedPi::new(&pi_n10()).unwrap();
    strains().into_iter().map(|s| forward.step(s)).collect()
}

fn volts(resistances: &[f64]) -> Vec<f64> {
    resistances
        .iter()
        .map(|&r| nominal_divider().voltage(r))
        .collect()
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("per_block_of_1000");
    group.throughput(Throughput::Elements(BLOCK as u64));

    let resistances = pi_resistances();
    let mut inverse = PiInverse::new(&pi_n10()).unwrap();
    group.bench_function("pi_n10_inverse", |b| {
        b.iter(|| {
            for &r in &resistances {
                black_box(inverse.step(black_box(r)));
            }
        })
    });

    let mut continuous = ContinuousPiInverse::new(&continuous_pi_n10()).unwrap();
    group.bench_function("continuous_pi_n10_inverse", |b| {
        b.iter(|| {
            for &r in &resistances {
                black_box(continuous.step(black_box(r)));
            }
        })
    });

    let linear =
        EstimatorConfig::nominal_linear(joint(NotchStyle::Uan), 15.3, 215.0e3, nominal_divider())
            .unwrap();
    let v = volts(&resistances);
    let mut est = Box::new(Estimator::new(&linear).unwrap());
    group.bench_function("estimator_linear", |b| {
        b.iter(|| {
            for &x in &v {
                black_box(est.step(black_box(x)));
            }
        })
    });

    let mut with_pi = linear;
    with_pi.sensor.model = ModelConfig::Pi(pi_n10());
    let mut est = Box::new(Estimator::new(&with_pi).unwrap());
    group.bench_function("estimator_pi_n10", |b| {
        b.iter(|| {
            for &x in &v {
                black_box(est.step(black_box(x)));
            }
        })
    });

    with_pi.output_filter = FilterConfig::MovingAverage { samples: 1000 };
    let mut est = Box::new(Estimator::new(&with_pi).unwrap());
    group.bench_function("estimator_pi_n10_ma1000", |b| {
        b.iter(|| {
            for &x in &v {
                black_box(est.step(black_box(x)));
            }
        })
    });

    let two =
        EstimatorConfig::nominal_linear(joint(NotchStyle::Bsn), 1.28, 74.0e3, nominal_divider())
            .unwrap();
    let v2: Vec<f64> = v.iter().map(|x| 5.0 - x).collect();
    let mut est = Box::new(Estimator::new(&two).unwrap());
    group.bench_function("estimator_two_sensor_linear", |b| {
        b.iter(|| {
            for (&x1, &x2) in v.iter().zip(&v2) {
                black_box(est.step2(black_box(x1), black_box(x2)));
            }
        })
    });

    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
