//! The inverse PI operator (Eqs. 12-14): the corrected weights invert the forward operator,
//! the paper's printed weights do not, and the tanh-switched model's inverse is exact away from
//! reversals and within `TanhInput::branch_gap` at them.

use dlw_estimator::{Coeffs, Flags, GeneralizedPi, PiConfig, PiInverse, PiOperator, PlayOperator};
use proptest::prelude::*;

/// Weights with `P₁ > 0` and every partial sum at least 0.05 (some single weights negative),
/// radii from 0 strictly increasing, an initial state and an input sequence.
fn operator_and_inputs() -> impl Strategy<Value = (Vec<f64>, Vec<f64>, f64, Vec<f64>)> {
    (1usize..=16)
        .prop_flat_map(|n| {
            (
                prop::collection::vec(-1.0f64..2.0, n),
                prop::collection::vec(0.01f64..1.0, n),
                -2.0f64..2.0,
                prop::collection::vec(-8.0f64..8.0, 1..300),
            )
        })
        .prop_map(|(mut weights, steps, initial, inputs)| {
            weights[0] = weights[0].abs().max(0.05);
            let mut radii = vec![0.0; steps.len()];
            for i in 1..steps.len() {
                radii[i] = radii[i - 1] + steps[i];
            }
            (weights, radii, initial, inputs)
        })
        .prop_filter("partial sums must stay positive", |(weights, ..)| {
            let mut s = 0.0;
            weights.iter().all(|w| {
                s += w;
                s >= 0.05
            })
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// `Π⁻¹[Π[x]] = x` to 1e-9 for every sequence, from any common initial state.
    #[test]
    fn corrected_inverse_round_trips((weights, radii, initial, inputs) in operator_and_inputs()) {
        let mut forward = PiOperator::new(&weights, &radii, initial).unwrap();
        let mut inverse = forward.inverse();
        for (k, &x) in inputs.iter().enumerate() {
            let back = inverse.step(forward.step(x));
            prop_assert!((back - x).abs() <= 1e-9, "sample {k}: {x} came back as {back}");
        }
    }

    /// The paper's printed weights fail the same round trip for every operator with a second
    /// play of non-negligible weight, on a ramp that loads every play.
    #[test]
    fn printed_inverse_fails((weights, radii, _initial, _inputs) in operator_and_inputs()) {
        prop_assume!(weights.len() >= 2 && weights[1].abs() > 0.05);
        let error = printed_round_trip_error(&weights, &radii);
        prop_assert!(error > 1e-6, "printed weights inverted to within {error}");
    }
}

/// Largest round-trip error on a ramp from 0 past the last radius and back, when the inverse
/// uses the weights as printed in the paper: `Qᵢ = −Pᵢ/((P₁ + Sᵢ)(P₁ + Sᵢ₋₁))`.
fn printed_round_trip_error(weights: &[f64], radii: &[f64]) -> f64 {
    let mut forward = PiOperator::new(weights, radii, 0.0).unwrap();
    let correct = forward.inverse();
    let p1 = weights[0];
    let mut partial = 0.0;
    let mut printed: Vec<(f64, PlayOperator)> = Vec::new();
    for (i, (&p, &zeta)) in weights.iter().zip(correct.radii()).enumerate() {
        let previous = partial;
        partial += p;
        let q = if i == 0 {
            1.0 / p1
        } else {
            -p / ((p1 + partial) * (p1 + previous))
        };
        printed.push((q, PlayOperator::new(zeta, 0.0)));
    }
    let top = radii[radii.len() - 1] + 2.0;
    let mut worst: f64 = 0.0;
    for k in (0..=200).chain((0..200).rev()) {
        let x = top * f64::from(k) / 200.0;
        let y = forward.step(x);
        let back: f64 = printed.iter_mut().map(|(q, play)| *q * play.step(y)).sum();
        worst = worst.max((back - x).abs());
    }
    worst
}

/// The paper's initial guess (Section IV-A): N = 10 equal weights, radii evenly spaced from 0.
/// The printed weights miss the ramp's top by far more than the corrected ones.
#[test]
fn printed_formula_fails_on_the_papers_initial_guess() {
    let weights = [0.1; 10];
    let radii: Vec<f64> = (0..10).map(|i| f64::from(i) * 0.5).collect();
    let printed = printed_round_trip_error(&weights, &radii);
    assert!(printed > 1.0, "printed error {printed}");

    let mut forward = PiOperator::new(&weights, &radii, 0.0).unwrap();
    let mut inverse = forward.inverse();
    for k in 0..=200 {
        let x = 6.5 * f64::from(k) / 200.0;
        assert!((inverse.step(forward.step(x)) - x).abs() < 1e-12);
    }
}

/// The hand-worked operator P = (1, 2, 1), ρ = (0, 1, 3): printed Q₂ = −2/((1 + 3)(1 + 1)) =
/// −1/4 instead of −2/3, so at x = 2 (y = 4) the printed inverse returns 4 − 0.25·3 = 3.25.
#[test]
fn printed_formula_by_hand() {
    let mut forward = PiOperator::new(&[1.0, 2.0, 1.0], &[0.0, 1.0, 3.0], 0.0).unwrap();
    assert_eq!(forward.step(2.0), 4.0);
    let printed = 1.0 * 4.0 - 0.25 * (4.0 - 1.0);
    assert_eq!(printed, 3.25);
    let corrected = 1.0 * 4.0 - 2.0 / 3.0 * (4.0 - 1.0);
    assert!((corrected - 2.0_f64).abs() < 1e-15);
}

fn tanh_model(weights: &[f64], radii: &[f64], loading: [f64; 4], unloading: [f64; 4]) -> PiConfig {
    PiConfig {
        weights: Coeffs::from_slice("weights", weights).unwrap(),
        radii: Coeffs::from_slice("radii", radii).unwrap(),
        loading_tanh: loading,
        unloading_tanh: unloading,
        center_strain: 0.005,
        center_ohm: 100.0e3,
        min_ohm: -1.0e9,
        max_ohm: 1.0e9,
        min_strain: None,
        max_strain: None,
        initial_state: 0.0,
    }
}

fn tanh_model_strategy() -> impl Strategy<Value = (PiConfig, Vec<f64>)> {
    (
        prop::collection::vec(0.05f64..1.0, 1..=10),
        0.5f64..3.0,
        (
            5.0e3f64..30.0e3,
            50.0f64..200.0,
            -0.3f64..0.3,
            -2.0e3f64..2.0e3,
        ),
        (
            5.0e3f64..30.0e3,
            50.0f64..200.0,
            -0.3f64..0.3,
            -2.0e3f64..2.0e3,
        ),
        prop::collection::vec(-0.005f64..0.015, 2..300),
    )
        .prop_map(
            |(weights, spread, (a1, a2, a3, a4), (a5, a6, a7, a8), strains)| {
                let radii: Vec<f64> = (0..weights.len())
                    .map(|i| i as f64 * spread * 1.0e3)
                    .collect();
                let config = tanh_model(&weights, &radii, [a1, a2, a3, a4], [a5, a6, a7, a8]);
                (config, strains)
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Where the forward model stays on one tanh branch, its inverse returns the strain to
    /// 1e-9; where it switches branch (the strain turned), the error is at most the branch
    /// gap at that strain. So the two disagree only at reversal samples, one at a time.
    #[test]
    fn tanh_pi_inverse_is_exact_except_at_reversals((config, strains) in tanh_model_strategy()) {
        let mut forward = GeneralizedPi::new(&config).unwrap();
        let mut inverse = PiInverse::new(&config).unwrap();
        let mut previous = f64::NEG_INFINITY;
        let mut previous_loading = true;
        for (k, &strain) in strains.iter().enumerate() {
            let loading = strain >= previous;
            let switched = loading != previous_loading;
            (previous, previous_loading) = (strain, loading);
            let (back, flags) = inverse.step(forward.step(strain));
            prop_assert!(!flags.contains(Flags::RESISTANCE_CLAMPED));
            if flags.contains(Flags::ATANH_CLAMPED) {
                continue;
            }
            let error = (back - strain).abs();
            if switched {
                let bound = forward.input().branch_gap(strain - config.center_strain);
                prop_assert!(error <= bound + 1e-9, "sample {k}: error {error} > gap {bound}");
            } else {
                prop_assert!(error <= 1e-9, "sample {k}: error {error} off a reversal");
            }
        }
    }
}

/// The bound is reached: a reversal where the unloading curve lies above the loading one
/// makes the inverse keep the loading branch for that sample.
#[test]
fn reversal_error_reaches_the_gap_for_one_sample() {
    let config = tanh_model(
        &[1.0],
        &[0.0],
        [20.0e3, 100.0, 0.0, 0.0],
        [20.0e3, 100.0, 0.3, 0.0],
    );
    let mut forward = GeneralizedPi::new(&config).unwrap();
    let mut inverse = PiInverse::new(&config).unwrap();
    let strains = [0.006, 0.007, 0.008, 0.0079, 0.0078, 0.0077];
    let mut errors = Vec::new();
    for &s in &strains {
        let (back, _) = inverse.step(forward.step(s));
        errors.push((back - s).abs());
    }
    // Sample 3 is the reversal: the loading branch inverts the unloading value.
    let x = 0.0079 - config.center_strain;
    let expected = (forward
        .input()
        .loading
        .inverse(forward.input().unloading.value(x))
        .0
        - x)
        .abs();
    assert!(
        (errors[3] - expected).abs() < 1e-12 && expected > 1e-3,
        "{errors:?}"
    );
    assert!(errors[3] <= forward.input().branch_gap(x) + 1e-12);
    for (k, e) in errors.iter().enumerate().filter(|(k, _)| *k != 3) {
        assert!(*e < 1e-9, "sample {k}: {e}");
    }
}
