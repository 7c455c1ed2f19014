use crate::coeffs::{Coeffs, MAX_PLAYS};
use crate::error::{finite, positive, range, EstimatorError};
use crate::flags::Flags;
use crate::pi::validate;
use crate::tanh_input::TanhBranch;

/// Most iterations of the inverse's root search per sample. Each halves the bracket at worst,
/// so 200 reach any `strain_tolerance` above `1e-60` times the bracket width.
pub const MAX_INVERSE_ITERATIONS: u32 = 200;

/// Parameters of the continuous generalized PI model (Al Janaideh's generalized play operator).
///
/// Each play follows its own pair of envelopes instead of a shared, direction-switched input:
///
/// `yᵢ(t) = max(γ_l(x(t)) − ρᵢ, min(γ_r(x(t)) + ρᵢ, yᵢ(t−1)))`, `x = ε − ε_c`,
/// `R(t) = Σᵢ Pᵢ·yᵢ(t) + R_c`,
///
/// with `γ_l(x) = a₁·tanh(a₂·x + a₃) + a₄` pushing the plays up while loading and
/// `γ_r(x) = a₅·tanh(a₆·x + a₇) + a₈` pushing them down while unloading. The output is a
/// continuous function of the strain, so unlike Eq. 10 nothing jumps at a reversal.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ContinuousPiConfig {
    /// Play weights `Pᵢ` (Ω per unit of `γ`): `P₁ > 0`, every other `Pᵢ ≥ 0`.
    pub weights: Coeffs,
    /// Play radii `ρᵢ` (units of `γ`): `ρ₁ = 0`, strictly increasing.
    pub radii: Coeffs,
    /// `[a₁, a₂, a₃, a₄]` of the loading envelope `γ_l`.
    pub loading_envelope: [f64; 4],
    /// `[a₅, a₆, a₇, a₈]` of the unloading envelope `γ_r`.
    pub unloading_envelope: [f64; 4],
    /// Strain at the centre `ε_c` (fraction).
    pub center_strain: f64,
    /// Resistance at the centre `R_c` (Ω).
    pub center_ohm: f64,
    /// Smallest strain the inverse may return (fraction): the characterized range.
    pub min_strain: f64,
    /// Largest strain the inverse may return (fraction).
    pub max_strain: f64,
    /// The inverse stops once the strain is known to within this (fraction, e.g. `1e-12`).
    pub strain_tolerance: f64,
    /// Resistance changes up to this are taken as no change, so the inverse holds its strain
    /// (Ω, ≥ 0). Inside a dead band any change moves the strain to the band's edge, so set it
    /// to the noise level of the (filtered) resistance; 0 holds only on repeats, up to the
    /// rounding of `R − R_c`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub resistance_tolerance_ohm: f64,
    /// Initial state `M₀` of every play, in units of `γ`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_state: f64,
}

impl ContinuousPiConfig {
    /// Checks every parameter.
    ///
    /// # Errors
    /// As [`crate::PiOperator::new`]; a negative weight; an envelope that is not finite or
    /// does not increase; `min_strain ≥ max_strain`; a tolerance that is not positive.
    pub fn validate(&self) -> Result<(), EstimatorError> {
        self.core().map(|_| ())
    }

    fn core(&self) -> Result<Core, EstimatorError> {
        let (weights, radii) = (self.weights.as_slice(), self.radii.as_slice());
        validate(weights, radii)?;
        if let Some(index) = weights.iter().position(|&w| w < 0.0) {
            return Err(EstimatorError::NegativeWeight {
                index,
                value: weights[index],
            });
        }
        finite("initial_state", self.initial_state)?;
        finite("center_strain", self.center_strain)?;
        finite("center_ohm", self.center_ohm)?;
        range("min_strain", self.min_strain, "max_strain", self.max_strain)?;
        positive("strain_tolerance", self.strain_tolerance)?;
        if finite("resistance_tolerance_ohm", self.resistance_tolerance_ohm)? < 0.0 {
            return Err(EstimatorError::NotPositive {
                name: "resistance_tolerance_ohm",
                value: self.resistance_tolerance_ohm,
            });
        }
        let mut core = Core {
            len: weights.len(),
            weights: [0.0; MAX_PLAYS],
            radii: [0.0; MAX_PLAYS],
            initial: self.initial_state,
            states: [self.initial_state; MAX_PLAYS],
            loading: TanhBranch::new("loading_envelope", self.loading_envelope)?,
            unloading: TanhBranch::new("unloading_envelope", self.unloading_envelope)?,
        };
        core.weights[..core.len].copy_from_slice(weights);
        core.radii[..core.len].copy_from_slice(radii);
        Ok(core)
    }
}

/// Plays, weights and envelopes shared by the forward and inverse models.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Core {
    len: usize,
    weights: [f64; MAX_PLAYS],
    radii: [f64; MAX_PLAYS],
    initial: f64,
    states: [f64; MAX_PLAYS],
    loading: TanhBranch,
    unloading: TanhBranch,
}

impl Core {
    /// `Σ Pᵢ·yᵢ` if the plays were fed `x` now, and its slope `d/dx` (without changing state).
    #[inline]
    fn trial(&self, x: f64) -> (f64, f64) {
        let (up, up_slope) = self.loading.value_and_slope(x);
        let (down, down_slope) = self.unloading.value_and_slope(x);
        let mut sum = 0.0;
        let mut slope = 0.0;
        for i in 0..self.len {
            let (lower, upper) = (up - self.radii[i], down + self.radii[i]);
            let (value, d) = if lower >= upper.min(self.states[i]) {
                (lower, up_slope)
            } else if upper < self.states[i] {
                (upper, down_slope)
            } else {
                (self.states[i], 0.0)
            };
            sum += self.weights[i] * value;
            slope += self.weights[i] * d;
        }
        (sum, slope)
    }

    /// Feeds `x` to the plays and returns `Σ Pᵢ·yᵢ`.
    #[inline]
    fn step(&mut self, x: f64) -> f64 {
        let (up, down) = (self.loading.value(x), self.unloading.value(x));
        let mut sum = 0.0;
        for i in 0..self.len {
            let held = f64::min(down + self.radii[i], self.states[i]);
            self.states[i] = f64::max(up - self.radii[i], held);
            sum += self.weights[i] * self.states[i];
        }
        sum
    }

    fn reset(&mut self) {
        self.states = [self.initial; MAX_PLAYS];
    }
}

/// The forward continuous generalized PI model: strain in, resistance out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuousPi {
    core: Core,
    center_strain: f64,
    center_ohm: f64,
    last_ohm: f64,
}

impl ContinuousPi {
    /// The model from validated parameters.
    ///
    /// # Errors
    /// As [`ContinuousPiConfig::validate`].
    pub fn new(config: &ContinuousPiConfig) -> Result<Self, EstimatorError> {
        let core = config.core()?;
        let mut model = Self {
            core,
            center_strain: config.center_strain,
            center_ohm: config.center_ohm,
            last_ohm: 0.0,
        };
        model.reset();
        Ok(model)
    }

    /// Feeds one strain sample and returns the resistance (Ω). A non-finite strain returns the
    /// last resistance and changes nothing.
    #[inline]
    pub fn step(&mut self, strain: f64) -> f64 {
        if strain.is_finite() {
            self.last_ohm = self.core.step(strain - self.center_strain) + self.center_ohm;
        }
        self.last_ohm
    }

    /// Returns to the initial state.
    pub fn reset(&mut self) {
        self.core.reset();
        self.last_ohm = self.core.trial(0.0).0 + self.center_ohm;
    }
}

/// The inverse of [`ContinuousPi`], solved numerically per sample.
///
/// It runs its own copy of the forward plays. For each resistance it finds the strain `x` with
/// `Σ Pᵢ·yᵢ(x) = R − R_c` given the plays' states, by Newton steps kept inside a bracket
/// (bisection when a step leaves it), then feeds `x` to its plays. Every `yᵢ(x)` is
/// non-decreasing in `x` (envelopes increase, weights are not negative), and strictly increasing
/// once a play is pushed, so the root on the side the resistance moved to is unique.
///
/// Where the resistance did not move, the strain is held: within a reversal's dead band no play
/// is pushed, so the forward model's output does not depend on the strain and no inverse can
/// tell where in the band the strain is. The error there is at most the band's width, the
/// horizontal distance between `γ_l` and `γ_r` at the plays' level; everywhere else the inverse
/// matches the forward model to `strain_tolerance` (and exactly reproduces its resistance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContinuousPiInverse {
    core: Core,
    center_strain: f64,
    center_ohm: f64,
    min_x: f64,
    max_x: f64,
    tolerance: f64,
    resistance_tolerance: f64,
    previous_x: f64,
    previous_target: f64,
    rising: bool,
}

impl ContinuousPiInverse {
    /// The inverse from validated parameters.
    ///
    /// # Errors
    /// As [`ContinuousPiConfig::validate`].
    pub fn new(config: &ContinuousPiConfig) -> Result<Self, EstimatorError> {
        let core = config.core()?;
        let mut inverse = Self {
            core,
            center_strain: config.center_strain,
            center_ohm: config.center_ohm,
            min_x: config.min_strain - config.center_strain,
            max_x: config.max_strain - config.center_strain,
            tolerance: config.strain_tolerance,
            resistance_tolerance: config.resistance_tolerance_ohm,
            previous_x: 0.0,
            previous_target: 0.0,
            rising: true,
        };
        inverse.reset();
        Ok(inverse)
    }

    /// Feeds one resistance sample (Ω) and returns the strain and what happened:
    /// [`Flags::RESISTANCE_CLAMPED`] when no strain in `[min_strain, max_strain]` explains `R`
    /// (the strain is clamped to the nearer end), [`Flags::REVERSAL`] when the resistance turned,
    /// [`Flags::NOT_CONVERGED`] when the root search stopped at its iteration limit.
    /// A non-finite `R` returns the last strain with [`Flags::NON_FINITE`] and [`Flags::HELD`].
    pub fn step(&mut self, resistance_ohm: f64) -> (f64, Flags) {
        if !resistance_ohm.is_finite() {
            return (
                self.previous_x + self.center_strain,
                Flags::NON_FINITE | Flags::HELD,
            );
        }
        let target = resistance_ohm - self.center_ohm;
        // Compared with the resistance the strain was last solved for, not with the plays'
        // output there, which differs by up to slope × strain_tolerance. `R − R_c` keeps only
        // the bits of R above R_c's rounding, so a few ulps of either count as no change.
        let rounding = 4.0 * f64::EPSILON * (resistance_ohm.abs() + self.center_ohm.abs());
        let mut flags = Flags::empty();
        let x = if (target - self.previous_target).abs()
            <= f64::max(self.resistance_tolerance, rounding)
        {
            self.previous_x
        } else {
            self.previous_target = target;
            let (now, slope) = self.core.trial(self.previous_x);
            let rising = target > now;
            flags |= Flags::when(rising != self.rising, Flags::REVERSAL);
            self.rising = rising;
            let end = if rising { self.max_x } else { self.min_x };
            let (at_end, _) = self.core.trial(end);
            if (rising && at_end <= target) || (!rising && at_end >= target) {
                flags |= Flags::when(at_end != target, Flags::RESISTANCE_CLAMPED);
                end
            } else {
                // First guess: a Newton step from where the plays are now.
                let guess = self.previous_x + (target - now) / slope;
                let (low, high) = if rising {
                    (self.previous_x, end)
                } else {
                    (end, self.previous_x)
                };
                let (x, converged) = self.solve(target, low, high, guess);
                flags |= Flags::when(!converged, Flags::NOT_CONVERGED);
                x
            }
        };
        self.core.step(x);
        self.previous_x = x;
        (x + self.center_strain, flags)
    }

    /// Root of `trial(x) = target` in `[low, high]`, where `trial(low) < target < trial(high)`,
    /// starting from `guess` (the midpoint if it lies outside), and whether it converged:
    /// `false` when [`MAX_INVERSE_ITERATIONS`] steps did not bring the step below the tolerance
    /// (the root is then the middle of the last bracket).
    ///
    /// Newton steps kept in the bracket, falling back to bisection whenever a step would leave
    /// it or would not at least halve the step before last (as in Numerical Recipes' `rtsafe`),
    /// so two Newton steps cannot bounce between the bracket's ends.
    fn solve(&self, target: f64, mut low: f64, mut high: f64, guess: f64) -> (f64, bool) {
        let mut x = if guess > low && guess < high {
            guess
        } else {
            0.5 * (low + high)
        };
        let mut step = high - low;
        let mut step_before = step;
        for _ in 0..MAX_INVERSE_ITERATIONS {
            let (value, slope) = self.core.trial(x);
            let error = value - target;
            if error < 0.0 {
                low = x;
            } else if error > 0.0 {
                high = x;
            } else {
                return (x, true);
            }
            let newton = x - error / slope;
            // Written so that the NaN of a zero slope in a dead band counts as not fast and
            // not inside, which bisects.
            let fast = 2.0 * error.abs() < (step_before * slope).abs();
            let inside = newton > low && newton < high;
            step_before = step;
            if !fast || !inside {
                step = 0.5 * (high - low);
                x = low + step;
            } else {
                step = (newton - x).abs();
                x = newton;
            }
            if step <= self.tolerance {
                return (x, true);
            }
        }
        (0.5 * (low + high), false)
    }

    /// Returns to the initial state.
    pub fn reset(&mut self) {
        self.core.reset();
        self.previous_x = 0.0f64.clamp(self.min_x, self.max_x);
        self.previous_target = self.core.trial(self.previous_x).0;
        self.rising = true;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    pub(crate) fn config(unloading_shift: f64) -> ContinuousPiConfig {
        ContinuousPiConfig {
            weights: Coeffs::try_from([0.5, 0.2, 0.2, 0.1]).unwrap(),
            radii: Coeffs::try_from([0.0, 2.0e3, 4.0e3, 6.0e3]).unwrap(),
            loading_envelope: [20.0e3, 100.0, 0.0, 0.0],
            unloading_envelope: [20.0e3, 100.0, unloading_shift, 0.0],
            center_strain: 0.005,
            center_ohm: 100.0e3,
            min_strain: -0.01,
            max_strain: 0.02,
            strain_tolerance: 1e-13,
            resistance_tolerance_ohm: 0.0,
            initial_state: 0.0,
        }
    }

    /// With γ_l = γ_r the first play never holds, so the inverse is exact on every sample.
    #[test]
    fn equal_envelopes_round_trip_exactly() {
        let c = config(0.0);
        let (mut fwd, mut inv) = (
            ContinuousPi::new(&c).unwrap(),
            ContinuousPiInverse::new(&c).unwrap(),
        );
        for k in 0..300 {
            let strain = 0.005 + 0.008 * libm::sin(k as f64 * 0.05) * libm::cos(k as f64 * 0.013);
            let (back, flags) = inv.step(fwd.step(strain));
            assert!(!flags.contains(Flags::RESISTANCE_CLAMPED));
            assert_relative_eq!(back, strain, epsilon = 1e-10);
        }
    }

    /// Without a jump: a strain step of 1e-6 moves the resistance by at most the steepest
    /// slope, Σ Pᵢ·a·b = 2e6 Ω, times 1e-6, also at reversals. The tanh-switched model of
    /// Eq. 10 with the same curves jumps there.
    #[test]
    fn no_jump_at_reversals() {
        let c = config(0.3);
        let mut fwd = ContinuousPi::new(&c).unwrap();
        let switched = crate::PiConfig {
            weights: c.weights,
            radii: c.radii,
            loading_tanh: c.loading_envelope,
            unloading_tanh: c.unloading_envelope,
            center_strain: c.center_strain,
            center_ohm: c.center_ohm,
            min_ohm: 0.0,
            max_ohm: 1.0e6,
            min_strain: None,
            max_strain: None,
            initial_state: 0.0,
        };
        let mut jumping = crate::GeneralizedPi::new(&switched).unwrap();
        let (mut previous, mut previous_jumping) = (fwd.step(0.008), jumping.step(0.008));
        let mut largest_jump: f64 = 0.0;
        for strain in [0.008_001, 0.008_002, 0.008_001, 0.008_000, 0.008_001] {
            let (r, rj) = (fwd.step(strain), jumping.step(strain));
            assert!(
                (r - previous).abs() <= 2.0 + 1e-9,
                "{strain}: {r} vs {previous}"
            );
            largest_jump = largest_jump.max((rj - previous_jumping).abs());
            (previous, previous_jumping) = (r, rj);
        }
        assert!(largest_jump > 100.0, "{largest_jump}");
    }

    #[test]
    fn out_of_range_is_clamped_and_flagged() {
        let c = config(0.3);
        let mut inv = ContinuousPiInverse::new(&c).unwrap();
        let (strain, flags) = inv.step(1.0e9);
        assert_relative_eq!(strain, c.max_strain, epsilon = 1e-17);
        assert!(flags.contains(Flags::RESISTANCE_CLAMPED));
        let (strain, flags) = inv.step(-1.0e9);
        assert_relative_eq!(strain, c.min_strain, epsilon = 1e-17);
        assert!(flags.contains(Flags::RESISTANCE_CLAMPED | Flags::REVERSAL));
        let (held, flags) = inv.step(f64::NAN);
        assert_eq!((held, flags), (strain, Flags::NON_FINITE | Flags::HELD));
    }

    /// A tolerance below what f64 can resolve stops the search at its limit, flagged; the
    /// strain is still inside the bracket, close to the root.
    #[test]
    fn an_unreachable_tolerance_is_flagged_not_converged() {
        let mut c = config(0.3);
        let mut fwd = ContinuousPi::new(&c).unwrap();
        let mut inv = ContinuousPiInverse::new(&c).unwrap();
        let r = fwd.step(0.008);
        let (strain, flags) = inv.step(r);
        assert!(!flags.contains(Flags::NOT_CONVERGED), "{flags}");
        assert_relative_eq!(strain, 0.008, epsilon = 1e-10);
        c.strain_tolerance = 1e-300;
        let mut inv = ContinuousPiInverse::new(&c).unwrap();
        let (strain, flags) = inv.step(r);
        assert!(flags.contains(Flags::NOT_CONVERGED), "{flags}");
        assert_relative_eq!(strain, 0.008, epsilon = 1e-10);
    }

    #[test]
    fn refuses_bad_configs() {
        let mut c = config(0.0);
        c.weights = Coeffs::try_from([0.5, -0.1, 0.2, 0.1]).unwrap();
        assert_eq!(
            c.validate(),
            Err(EstimatorError::NegativeWeight {
                index: 1,
                value: -0.1
            })
        );
        let mut c = config(0.0);
        c.strain_tolerance = 0.0;
        assert!(c.validate().is_err());
        let mut c = config(0.0);
        c.resistance_tolerance_ohm = -1.0;
        assert!(c.validate().is_err());
        let mut c = config(0.0);
        c.max_strain = c.min_strain;
        assert!(c.validate().is_err());
        let mut c = config(0.0);
        c.loading_envelope[1] = -1.0;
        assert!(c.validate().is_err());
    }
}
