use crate::coeffs::MAX_PLAYS;
use crate::error::{finite, EstimatorError};
use crate::play::play;

/// The Prandtl-Ishlinskii (PI) operator: a weighted sum of play operators,
/// `Π[ν](t) = Σᵢ Pᵢ·Γ_ρᵢ(ν(t))` (the sum in Eq. 11, without the tanh input and the offsets).
///
/// Built only if it is invertible, which [`PiOperator::inverse`] then gives exactly:
/// `ρ₁ = 0`, radii strictly increasing, and every partial sum `Sᵢ = P₁ + … + Pᵢ > 0` (so the
/// initial loading curve, of slope `Sᵢ` between `ρᵢ` and `ρᵢ₊₁`, strictly increases). Single
/// weights may be negative as long as the partial sums stay positive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiOperator {
    len: usize,
    weights: [f64; MAX_PLAYS],
    radii: [f64; MAX_PLAYS],
    initial: f64,
    states: [f64; MAX_PLAYS],
}

impl PiOperator {
    /// The operator with weights `Pᵢ`, radii `ρᵢ` and every play starting at `M₀` (Eq. 9).
    ///
    /// # Errors
    /// No weights or more than [`MAX_PLAYS`]; lengths that differ; a value that is not finite;
    /// `ρ₁ ≠ 0`; radii not strictly increasing; a partial sum `Sᵢ ≤ 0` (in particular `P₁ ≤ 0`).
    pub fn new(weights: &[f64], radii: &[f64], initial: f64) -> Result<Self, EstimatorError> {
        validate(weights, radii)?;
        finite("initial_state", initial)?;
        let mut op = Self {
            len: weights.len(),
            weights: [0.0; MAX_PLAYS],
            radii: [0.0; MAX_PLAYS],
            initial,
            states: [initial; MAX_PLAYS],
        };
        op.weights[..op.len].copy_from_slice(weights);
        op.radii[..op.len].copy_from_slice(radii);
        Ok(op)
    }

    /// Number of play operators `N`.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always `false`: an operator has at least one play.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Weights `Pᵢ`.
    pub fn weights(&self) -> &[f64] {
        &self.weights[..self.len]
    }

    /// Radii `ρᵢ`.
    pub fn radii(&self) -> &[f64] {
        &self.radii[..self.len]
    }

    /// The plays' current outputs.
    pub fn states(&self) -> &[f64] {
        &self.states[..self.len]
    }

    /// Feeds one input sample `ν(t)` and returns `Σᵢ Pᵢ·Γ_ρᵢ(ν(t))`.
    #[inline]
    pub fn step(&mut self, input: f64) -> f64 {
        let n = self.len;
        weighted_plays(
            &mut self.states[..n],
            &self.radii[..n],
            &self.weights[..n],
            input,
        )
    }

    /// Returns every play to `M₀`.
    pub fn reset(&mut self) {
        self.states = [self.initial; MAX_PLAYS];
    }

    /// The exact inverse, starting from this operator's *current* state (so that
    /// `inverse.step(self.step(x)) == x` from here on) and resetting to the inverse of `M₀`.
    ///
    /// With partial sums `Sᵢ = P₁ + … + Pᵢ` (Eq. 13, corrected):
    ///
    /// - weights `Q₁ = 1/P₁`, `Qᵢ = −Pᵢ/(Sᵢ·Sᵢ₋₁)`;
    /// - radii `ζᵢ = Σ_{j≤i} Pⱼ·(ρᵢ − ρⱼ)`, the forward loading curve's value at `ρᵢ`;
    /// - states `qᵢ = Sᵢ·pᵢ + Σ_{j>i} Pⱼ·pⱼ` from the forward states `pⱼ` (all equal to
    ///   `S_N·M₀` when every `pⱼ = M₀`).
    ///
    /// The paper prints the denominator as `(P₁ + Σ_{j≤i} Pⱼ)(P₁ + Σ_{j<i} Pⱼ)`, counting `P₁`
    /// twice; the loading-curve slopes below show why `Sᵢ` is right, and the crate's tests show
    /// the printed weights fail the round trip.
    ///
    /// Derivation: from a relaxed state the forward loading curve is
    /// `φ(r) = Σ_{ρⱼ≤r} Pⱼ(r − ρⱼ)`, piecewise linear with slope `Sᵢ` on `[ρᵢ, ρᵢ₊₁)`. Its inverse
    /// is piecewise linear with breakpoints `ζᵢ = φ(ρᵢ)` and slopes `1/Sᵢ`, and a PI operator with
    /// radii `ζᵢ` has loading-curve slope `Q₁ + … + Qᵢ` there. So `Q₁ + … + Qᵢ = 1/Sᵢ`, giving
    /// `Qᵢ = 1/Sᵢ − 1/Sᵢ₋₁ = −Pᵢ/(Sᵢ·Sᵢ₋₁)`. A PI operator is fixed by its loading curve, and the
    /// inverse of a PI operator is the PI operator of the inverse loading curve.
    pub fn inverse(&self) -> InversePiOperator {
        let n = self.len;
        let mut inv = InversePiOperator {
            len: n,
            weights: [0.0; MAX_PLAYS],
            radii: [0.0; MAX_PLAYS],
            initial: [0.0; MAX_PLAYS],
            states: [0.0; MAX_PLAYS],
        };
        let mut partial = 0.0; // S_i
        let mut moment = 0.0; // Σ_{j≤i} P_j·ρ_j
        for i in 0..n {
            let previous = partial;
            partial += self.weights[i];
            moment += self.weights[i] * self.radii[i];
            inv.weights[i] = if i == 0 {
                1.0 / self.weights[0]
            } else {
                -self.weights[i] / (partial * previous)
            };
            inv.radii[i] = partial * self.radii[i] - moment;
        }
        let relaxed = [self.initial; MAX_PLAYS];
        inv.initial = inverse_states(self.weights(), &relaxed[..n]);
        inv.states = inverse_states(self.weights(), self.states());
        inv
    }
}

/// Inverse play states `qᵢ = Sᵢ·pᵢ + Σ_{j>i} Pⱼ·pⱼ` for forward states `pⱼ`.
fn inverse_states(weights: &[f64], states: &[f64]) -> [f64; MAX_PLAYS] {
    let mut out = [0.0; MAX_PLAYS];
    let mut partial = 0.0;
    let mut tail: f64 = weights.iter().zip(states).map(|(p, s)| p * s).sum();
    for i in 0..weights.len() {
        partial += weights[i];
        tail -= weights[i] * states[i];
        out[i] = partial * states[i] + tail;
    }
    out
}

/// The inverse of a [`PiOperator`]: `Π⁻¹[y](t) = Σᵢ Qᵢ·Γ_ζᵢ(y(t))` (the sum in Eq. 12),
/// made by [`PiOperator::inverse`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InversePiOperator {
    len: usize,
    weights: [f64; MAX_PLAYS],
    radii: [f64; MAX_PLAYS],
    initial: [f64; MAX_PLAYS],
    states: [f64; MAX_PLAYS],
}

impl InversePiOperator {
    /// Weights `Qᵢ`.
    pub fn weights(&self) -> &[f64] {
        &self.weights[..self.len]
    }

    /// Radii `ζᵢ`.
    pub fn radii(&self) -> &[f64] {
        &self.radii[..self.len]
    }

    /// Feeds one output sample `y(t)` of the forward operator and returns its input `ν(t)`.
    #[inline]
    pub fn step(&mut self, output: f64) -> f64 {
        let n = self.len;
        weighted_plays(
            &mut self.states[..n],
            &self.radii[..n],
            &self.weights[..n],
            output,
        )
    }

    /// Returns to the state matching the forward operator's `M₀`.
    pub fn reset(&mut self) {
        self.states = self.initial;
    }
}

/// The invertibility conditions shared by every PI model in this crate.
pub(crate) fn validate(weights: &[f64], radii: &[f64]) -> Result<(), EstimatorError> {
    if weights.is_empty() {
        return Err(EstimatorError::Empty { name: "weights" });
    }
    if weights.len() > MAX_PLAYS {
        return Err(EstimatorError::TooMany {
            name: "weights",
            count: weights.len(),
            max: MAX_PLAYS,
        });
    }
    if radii.len() != weights.len() {
        return Err(EstimatorError::LengthMismatch {
            name: "radii",
            len: radii.len(),
            other: "weights",
            other_len: weights.len(),
        });
    }
    let mut partial = 0.0;
    for (index, (&weight, &radius)) in weights.iter().zip(radii).enumerate() {
        finite("weights", weight)?;
        finite("radii", radius)?;
        if index == 0 && radius != 0.0 {
            return Err(EstimatorError::FirstRadiusNotZero { value: radius });
        }
        if index > 0 && radius <= radii[index - 1] {
            return Err(EstimatorError::RadiiNotIncreasing {
                index,
                value: radius,
                previous: radii[index - 1],
            });
        }
        partial += weight;
        if partial <= 0.0 {
            return Err(EstimatorError::PartialSumNotPositive {
                index,
                value: partial,
            });
        }
    }
    Ok(())
}

/// `Σᵢ wᵢ·Γ_rᵢ(x)`: advances every play by one sample and sums them, weighted. The forward
/// operator and its inverse are both this sum, with their own weights and radii.
#[inline]
fn weighted_plays(states: &mut [f64], radii: &[f64], weights: &[f64], x: f64) -> f64 {
    let mut sum = 0.0;
    for ((state, &radius), &weight) in states.iter_mut().zip(radii).zip(weights) {
        *state = play(x, radius, *state);
        sum += weight * *state;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// A 3-play operator worked by hand: P = (1, 2, 1), ρ = (0, 1, 3).
    /// S = (1, 3, 4); Q = (1, −2/(3·1), −1/(4·3)); ζᵢ = Sᵢ·ρᵢ − Σ_{j≤i} Pⱼρⱼ = (0, 3 − 2, 12 − 5).
    #[test]
    fn hand_worked_inverse_weights() {
        let op = PiOperator::new(&[1.0, 2.0, 1.0], &[0.0, 1.0, 3.0], 0.0).unwrap();
        let inv = op.inverse();
        let q = [1.0, -2.0 / 3.0, -1.0 / 12.0];
        let zeta = [0.0, 1.0, 7.0];
        for i in 0..3 {
            assert_relative_eq!(inv.weights()[i], q[i], epsilon = 1e-15);
            assert_relative_eq!(inv.radii()[i], zeta[i], epsilon = 1e-15);
        }
        // Slopes of the inverse loading curve are 1/S_i.
        let mut s = 0.0;
        for i in 0..3 {
            s += op.weights()[i];
            let slope: f64 = inv.weights()[..=i].iter().sum();
            assert_relative_eq!(slope, 1.0 / s, epsilon = 1e-15);
        }
    }

    /// The initial loading curve from the hand-worked operator: φ(r) = Σ P_j (r − ρ_j)⁺.
    #[test]
    fn loading_curve_vectors() {
        let mut op = PiOperator::new(&[1.0, 2.0, 1.0], &[0.0, 1.0, 3.0], 0.0).unwrap();
        let table = [
            (0.5, 0.5),
            (1.0, 1.0),
            (2.0, 2.0 + 2.0),
            (3.0, 3.0 + 4.0),
            (4.0, 4.0 + 6.0 + 1.0),
        ];
        for (x, y) in table {
            assert_relative_eq!(op.step(x), y, epsilon = 1e-15);
        }
        // Reversal by 1 moves only the ρ = 0 play: slope P_1 = 1 on the way down.
        assert_relative_eq!(op.step(3.0), 10.0, epsilon = 1e-15);
    }

    #[test]
    fn inverse_from_a_nonzero_initial_state_and_after_reset() {
        let mut op = PiOperator::new(&[0.5, 0.3, -0.1, 0.2], &[0.0, 0.2, 0.5, 0.9], 0.4).unwrap();
        let mut inv = op.inverse();
        let inputs = [0.4, 1.2, -0.7, 0.1, 0.05, 2.0, -2.0];
        for _ in 0..2 {
            for x in inputs {
                assert_relative_eq!(inv.step(op.step(x)), x, epsilon = 1e-12);
            }
            op.reset();
            inv.reset();
        }
        // Taking the inverse mid-stream starts from the current state.
        op.step(0.9);
        let mut late = op.inverse();
        for x in inputs {
            assert_relative_eq!(late.step(op.step(x)), x, epsilon = 1e-12);
        }
    }

    #[test]
    fn refuses_non_invertible_operators() {
        let cases: [(&[f64], &[f64], EstimatorError); 6] = [
            (&[], &[], EstimatorError::Empty { name: "weights" }),
            (
                &[1.0, 1.0],
                &[0.0],
                EstimatorError::LengthMismatch {
                    name: "radii",
                    len: 1,
                    other: "weights",
                    other_len: 2,
                },
            ),
            (
                &[1.0],
                &[0.1],
                EstimatorError::FirstRadiusNotZero { value: 0.1 },
            ),
            (
                &[1.0, 1.0],
                &[0.0, 0.0],
                EstimatorError::RadiiNotIncreasing {
                    index: 1,
                    value: 0.0,
                    previous: 0.0,
                },
            ),
            (
                &[0.0],
                &[0.0],
                EstimatorError::PartialSumNotPositive {
                    index: 0,
                    value: 0.0,
                },
            ),
            (
                &[1.0, -1.5],
                &[0.0, 1.0],
                EstimatorError::PartialSumNotPositive {
                    index: 1,
                    value: -0.5,
                },
            ),
        ];
        for (weights, radii, error) in cases {
            assert_eq!(PiOperator::new(weights, radii, 0.0), Err(error));
        }
        assert!(PiOperator::new(&[1.0; MAX_PLAYS + 1], &[0.0; MAX_PLAYS + 1], 0.0).is_err());
        assert!(PiOperator::new(&[1.0], &[0.0], f64::NAN).is_err());
    }
}
