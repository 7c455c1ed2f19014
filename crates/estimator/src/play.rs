/// One step of the play (backlash) operator of radius `ρ` (Eq. 7):
/// `Γ_ρ(ν(t)) = max(ν(t) − ρ, min(ν(t) + ρ, Γ_ρ(ν(t−1))))`.
///
/// The output follows the input at distance `ρ` while the input pushes it, and holds while the
/// input moves back within the band `[y − ρ, y + ρ]`.
#[inline(always)]
pub(crate) fn play(input: f64, radius: f64, previous: f64) -> f64 {
    // Written with comparisons instead of f64::max/min: those also handle NaN, which never
    // reaches here (the estimator screens inputs), and the plain form compiles to maxsd/minsd.
    let upper = input + radius;
    let lower = input - radius;
    let held = if previous < upper { previous } else { upper };
    if lower > held {
        lower
    } else {
        held
    }
}

/// The play operator `Γ_ρ` as a small state machine (Eqs. 7-8).
///
/// Its state is the last output; it starts at `M₀`, so the first step is Eq. 8,
/// `Γ_ρ(ν(0)) = max(ν(0) − ρ, min(ν(0) + ρ, M₀))`, and every later one is Eq. 7.
///
/// ```
/// use dlw_estimator::PlayOperator;
///
/// let mut play = PlayOperator::new(1.0, 0.0);
/// assert_eq!(play.step(3.0), 2.0); // pushed up: follows at ν − ρ
/// assert_eq!(play.step(2.5), 2.0); // inside the band: holds
/// assert_eq!(play.step(0.0), 1.0); // pushed down: follows at ν + ρ
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlayOperator {
    radius: f64,
    initial: f64,
    state: f64,
}

impl PlayOperator {
    /// A play operator of radius `ρ ≥ 0` and initial state `M₀`.
    ///
    /// A negative radius would make the band empty; it is taken as its magnitude.
    pub fn new(radius: f64, initial: f64) -> Self {
        Self {
            radius: radius.abs(),
            initial,
            state: initial,
        }
    }

    /// Radius `ρ`.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The current output `Γ_ρ(ν(t−1))` (or `M₀` before the first step).
    pub fn state(&self) -> f64 {
        self.state
    }

    /// Feeds one input sample and returns the output (Eq. 7, or Eq. 8 on the first step).
    #[inline]
    pub fn step(&mut self, input: f64) -> f64 {
        self.state = play(input, self.radius, self.state);
        self.state
    }

    /// Returns to the initial state `M₀`.
    pub fn reset(&mut self) {
        self.state = self.initial;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hand-traced sequence for `ρ = 0.5`, `M₀ = 0`.
    #[test]
    fn traces_a_backlash_loop() {
        let mut p = PlayOperator::new(0.5, 0.0);
        let table = [
            (0.3, 0.0),   // inside [−0.5, 0.5] of M₀: holds
            (1.0, 0.5),   // pushed up
            (2.0, 1.5),   // follows
            (1.4, 1.5),   // reversal: holds within the band
            (1.0, 1.5),   // edge of the band
            (0.0, 0.5),   // pushed down
            (-1.0, -0.5), // follows
            (-0.6, -0.5), // holds again
        ];
        for (i, (input, output)) in table.into_iter().enumerate() {
            assert_eq!(p.step(input), output, "step {i}");
        }
    }

    #[test]
    fn eq8_initial_state_and_reset() {
        // M₀ outside the first band is pulled into it at once.
        let mut p = PlayOperator::new(1.0, 10.0);
        assert_eq!(p.step(0.0), 1.0);
        p.reset();
        assert_eq!(p.state(), 10.0);
        // M₀ inside the band is kept.
        let mut q = PlayOperator::new(1.0, 0.7);
        assert_eq!(q.step(0.0), 0.7);
    }

    #[test]
    fn zero_radius_is_identity() {
        let mut p = PlayOperator::new(0.0, 3.0);
        for x in [-2.0, 5.0, 1.25, 1.25, -7.5] {
            assert_eq!(p.step(x), x);
        }
        assert_eq!(PlayOperator::new(-2.0, 0.0).radius(), 2.0);
    }

    #[test]
    fn matches_max_min_form() {
        let (r, mut prev) = (0.3, 0.1);
        for k in 0..200 {
            let x = libm::sin(k as f64 * 0.37) * 2.0;
            let expected = f64::max(x - r, f64::min(x + r, prev));
            let got = play(x, r, prev);
            assert_eq!(got, expected);
            prev = got;
        }
    }
}
