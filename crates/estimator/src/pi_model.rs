use crate::coeffs::Coeffs;
use crate::error::{finite, range, EstimatorError};
use crate::flags::Flags;
use crate::pi::{InversePiOperator, PiOperator};
use crate::tanh_input::TanhInput;

/// Parameters of the generalized PI sensor model of the paper (Eqs. 10-14).
///
/// Forward (Eq. 11): `R(t) = Σᵢ Pᵢ·Γ_ρᵢ(ν(ε(t) − ε_c)) + R_c`, where `ν` is the
/// direction-switched tanh input of Eq. 10 (`loading_tanh` while `ε(t) ≥ ε(t−1)`,
/// `unloading_tanh` while it falls). Strain is a fraction; `ν`, the radii and `initial_state`
/// share one unit, and `weights` turn it into ohms.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PiConfig {
    /// Play weights `Pᵢ` (Ω per unit of `ν`); `P₁ > 0` and every partial sum positive.
    pub weights: Coeffs,
    /// Play radii `ρᵢ` (units of `ν`): `ρ₁ = 0`, strictly increasing.
    pub radii: Coeffs,
    /// `[a₁, a₂, a₃, a₄]`: `ν = a₁·tanh(a₂·(ε − ε_c) + a₃) + a₄` while loading.
    pub loading_tanh: [f64; 4],
    /// `[a₅, a₆, a₇, a₈]`: `ν = a₅·tanh(a₆·(ε − ε_c) + a₇) + a₈` while unloading.
    pub unloading_tanh: [f64; 4],
    /// Strain at the centre `ε_c` (fraction, 0.00307 for Joint A).
    pub center_strain: f64,
    /// Resistance at the centre `R_c` (Ω).
    pub center_ohm: f64,
    /// Smallest resistance seen while characterizing (Ω); the inverse clamps below it.
    pub min_ohm: f64,
    /// Largest resistance seen while characterizing (Ω); the inverse clamps above it.
    pub max_ohm: f64,
    /// Smallest strain seen while characterizing (fraction); the inverse never reports less.
    /// Optional (older configs have none), but `dlw fit` always writes it: where the fitted tanh
    /// flattens near the ends of the range, a resistance inside `[min_ohm, max_ohm]` that the
    /// model misses by a little can invert to a strain far outside what was characterized.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub min_strain: Option<f64>,
    /// Largest strain seen while characterizing (fraction); the inverse never reports more.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub max_strain: Option<f64>,
    /// Initial state `M₀` of every forward play (Eq. 9), in units of `ν`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub initial_state: f64,
}

impl PiConfig {
    /// Checks every parameter.
    ///
    /// # Errors
    /// As [`PiOperator::new`] and [`TanhInput::new`]; a centre that is not finite;
    /// `min_ohm ≥ max_ohm`; a strain bound that is not finite, or `min_strain ≥ max_strain`.
    pub fn validate(&self) -> Result<(), EstimatorError> {
        self.parts().map(|_| ())
    }

    fn parts(&self) -> Result<(TanhInput, PiOperator), EstimatorError> {
        let input = TanhInput::new(self.loading_tanh, self.unloading_tanh)?;
        let plays = PiOperator::new(
            self.weights.as_slice(),
            self.radii.as_slice(),
            self.initial_state,
        )?;
        finite("center_strain", self.center_strain)?;
        finite("center_ohm", self.center_ohm)?;
        range("min_ohm", self.min_ohm, "max_ohm", self.max_ohm)?;
        let (min_strain, max_strain) = self.strain_bounds();
        match (self.min_strain, self.max_strain) {
            (Some(_), Some(_)) => range("min_strain", min_strain, "max_strain", max_strain)?,
            (Some(v), None) => finite("min_strain", v).map(|_| ())?,
            (None, Some(v)) => finite("max_strain", v).map(|_| ())?,
            (None, None) => (),
        }
        Ok((input, plays))
    }

    /// `[min_strain, max_strain]`, unbounded where absent.
    fn strain_bounds(&self) -> (f64, f64) {
        (
            self.min_strain.unwrap_or(f64::NEG_INFINITY),
            self.max_strain.unwrap_or(f64::INFINITY),
        )
    }
}

/// The forward generalized PI model (Eq. 11): strain in, resistance out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralizedPi {
    input: TanhInput,
    plays: PiOperator,
    center_strain: f64,
    center_ohm: f64,
    previous_strain: f64,
    last_ohm: f64,
}

impl GeneralizedPi {
    /// The model from validated parameters.
    ///
    /// # Errors
    /// As [`PiConfig::validate`].
    pub fn new(config: &PiConfig) -> Result<Self, EstimatorError> {
        let (input, plays) = config.parts()?;
        Ok(Self {
            input,
            plays,
            center_strain: config.center_strain,
            center_ohm: config.center_ohm,
            previous_strain: f64::NEG_INFINITY,
            last_ohm: config.center_ohm,
        })
    }

    /// The tanh input `ν`.
    pub fn input(&self) -> &TanhInput {
        &self.input
    }

    /// Feeds one strain sample and returns the resistance (Ω). The first sample uses the
    /// loading branch. A non-finite strain returns the last resistance and changes nothing.
    #[inline]
    pub fn step(&mut self, strain: f64) -> f64 {
        if !strain.is_finite() {
            return self.last_ohm;
        }
        let loading = strain >= self.previous_strain;
        self.previous_strain = strain;
        let nu = self.input.nu(strain - self.center_strain, loading);
        self.last_ohm = self.plays.step(nu) + self.center_ohm;
        self.last_ohm
    }

    /// Returns to the initial state.
    pub fn reset(&mut self) {
        self.plays.reset();
        self.previous_strain = f64::NEG_INFINITY;
        self.last_ohm = self.center_ohm;
    }
}

/// The inverse generalized PI model (Eqs. 12-14): resistance in, strain out.
///
/// `ε(t) = ν⁻¹(Σᵢ Qᵢ·Γ_ζᵢ(R(t) − R_c)) + ε_c` with the corrected weights of
/// [`PiOperator::inverse`]; `ν⁻¹` takes the loading branch while `μ(t) ≥ μ(t−1)`.
///
/// Away from reversals and clamps it inverts [`GeneralizedPi`] exactly (to rounding). At a
/// reversal sample the two may disagree by up to [`TanhInput::branch_gap`]; the sample is
/// flagged [`Flags::REVERSAL`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PiInverse {
    input: TanhInput,
    plays: InversePiOperator,
    center_strain: f64,
    center_ohm: f64,
    min_ohm: f64,
    max_ohm: f64,
    min_strain: f64,
    max_strain: f64,
    previous_mu: f64,
    previous_loading: bool,
    last_strain: f64,
}

impl PiInverse {
    /// The inverse from validated parameters, starting from the state matching the forward
    /// model's `M₀`.
    ///
    /// # Errors
    /// As [`PiConfig::validate`].
    pub fn new(config: &PiConfig) -> Result<Self, EstimatorError> {
        let (input, plays) = config.parts()?;
        Ok(Self {
            input,
            plays: plays.inverse(),
            center_strain: config.center_strain,
            center_ohm: config.center_ohm,
            min_ohm: config.min_ohm,
            max_ohm: config.max_ohm,
            min_strain: config.strain_bounds().0,
            max_strain: config.strain_bounds().1,
            previous_mu: f64::NEG_INFINITY,
            previous_loading: true,
            last_strain: config.center_strain,
        })
    }

    /// The tanh input `ν`.
    pub fn input(&self) -> &TanhInput {
        &self.input
    }

    /// The inverse play operators `Σ Qᵢ·Γ_ζᵢ`.
    pub fn plays(&self) -> &InversePiOperator {
        &self.plays
    }

    /// Feeds one resistance sample (Ω) and returns the strain and what happened:
    /// [`Flags::RESISTANCE_CLAMPED`] when `R` lay outside `[min_ohm, max_ohm]` (it is clamped,
    /// as in the paper's Section IV-C) or the strain it inverts to outside `[min_strain,
    /// max_strain]` (the strain is clamped), [`Flags::ATANH_CLAMPED`], [`Flags::REVERSAL`] when the
    /// branch switched. A non-finite `R` returns the last strain with
    /// [`Flags::NON_FINITE`] and [`Flags::HELD`] and changes nothing.
    #[inline]
    pub fn step(&mut self, resistance_ohm: f64) -> (f64, Flags) {
        if !resistance_ohm.is_finite() {
            return (self.last_strain, Flags::NON_FINITE | Flags::HELD);
        }
        let below = resistance_ohm < self.min_ohm;
        let above = resistance_ohm > self.max_ohm;
        let ohm = if below {
            self.min_ohm
        } else if above {
            self.max_ohm
        } else {
            resistance_ohm
        };
        let mu = self.plays.step(ohm - self.center_ohm);
        let loading = mu >= self.previous_mu;
        let (x, atanh_clamped) = self.input.nu_inverse(mu, loading);
        let strain = x + self.center_strain;
        let clamped = strain.clamp(self.min_strain, self.max_strain);
        let flags = Flags::when(
            below | above | (clamped != strain),
            Flags::RESISTANCE_CLAMPED,
        ) | Flags::when(atanh_clamped, Flags::ATANH_CLAMPED)
            | Flags::when(loading != self.previous_loading, Flags::REVERSAL);
        self.previous_mu = mu;
        self.previous_loading = loading;
        self.last_strain = clamped;
        (self.last_strain, flags)
    }

    /// Returns to the initial state.
    pub fn reset(&mut self) {
        self.plays.reset();
        self.previous_mu = f64::NEG_INFINITY;
        self.previous_loading = true;
        self.last_strain = self.center_strain;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// A Joint-A-like model: the paper's initial guesses (Section IV-A) with N = 10,
    /// R_c = 224 kΩ, R_peak = 250 kΩ, m_c = 5136 kΩ, ε_c = 0.307 %, ε_peak = 1.35 %.
    pub(crate) fn joint_a() -> PiConfig {
        let (r_c, r_peak, m_c) = (224.0e3, 250.0e3, 5136.0e3);
        let a1 = r_peak - r_c;
        let a2 = m_c / (2.0 * a1);
        let rho_max = a1 * libm::tanh(a2 * 0.0135);
        let mut radii = [0.0; 10];
        for (i, r) in radii.iter_mut().enumerate() {
            *r = rho_max * i as f64 / 9.0;
        }
        PiConfig {
            weights: Coeffs::try_from([1.0 / 10.0; 10]).unwrap(),
            radii: Coeffs::try_from(radii).unwrap(),
            loading_tanh: [a1, a2, 0.0, 0.0],
            unloading_tanh: [a1, a2 * 1.2, 0.05, 0.0],
            center_strain: 0.00307,
            center_ohm: r_c,
            min_ohm: 200.0e3,
            max_ohm: 250.0e3,
            min_strain: None,
            max_strain: None,
            initial_state: 0.0,
        }
    }

    #[test]
    fn forward_then_inverse_on_a_monotone_ramp() {
        let config = joint_a();
        let (mut fwd, mut inv) = (
            GeneralizedPi::new(&config).unwrap(),
            PiInverse::new(&config).unwrap(),
        );
        for k in 0..100 {
            let strain = 0.00307 + 0.00002 * k as f64;
            let (back, flags) = inv.step(fwd.step(strain));
            assert!(flags.is_empty(), "{k}: {flags}");
            assert_relative_eq!(back, strain, epsilon = 1e-9);
        }
    }

    #[test]
    fn out_of_range_resistance_is_clamped_and_flagged() {
        let config = joint_a();
        let mut inv = PiInverse::new(&config).unwrap();
        let (high, flags) = inv.step(1.0e9);
        assert!(flags.contains(Flags::RESISTANCE_CLAMPED) && high.is_finite());
        inv.reset();
        let (at_max, flags) = inv.step(config.max_ohm);
        assert!(!flags.contains(Flags::RESISTANCE_CLAMPED));
        assert_eq!(high, at_max);
        let (_, flags) = inv.step(-5.0);
        assert!(flags.contains(Flags::RESISTANCE_CLAMPED));
    }

    /// A resistance inside `[min_ohm, max_ohm]` can invert, where the tanh flattens, to a strain
    /// far beyond the characterized range; with the strain range set, the inverse stops at its
    /// end and flags it, and inside the range it changes nothing.
    #[test]
    fn the_strain_is_clamped_to_the_characterized_range() {
        let open = joint_a();
        let bounded = PiConfig {
            min_strain: Some(0.0),
            max_strain: Some(0.012),
            ..open
        };
        let mut free = PiInverse::new(&open).unwrap();
        let mut clamped = PiInverse::new(&bounded).unwrap();
        // 249.9 kΩ is inside [200, 250] kΩ but near the tanh's asymptote (224 + 26 kΩ).
        for ohm in [226.0e3, 240.0e3, 249.9e3, 235.0e3, 210.0e3] {
            let (a, fa) = free.step(ohm);
            let (b, fb) = clamped.step(ohm);
            if !(0.0..=0.012).contains(&a) {
                assert_eq!(b, a.clamp(0.0, 0.012), "{ohm} Ω: {a} unclamped");
                assert!(fb.contains(Flags::RESISTANCE_CLAMPED));
                assert!(!fa.contains(Flags::RESISTANCE_CLAMPED));
            } else {
                assert_eq!((a, fa), (b, fb), "{ohm} Ω");
            }
        }
        let mut probe = PiInverse::new(&open).unwrap();
        assert!(
            probe.step(249.9e3).0 > 0.012,
            "the probe must leave the range above"
        );
        assert!(probe.step(210.0e3).0 < 0.0, "and below");
        let mut c = bounded;
        c.max_strain = Some(0.0);
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::EmptyRange { .. })
        ));
        c.max_strain = Some(f64::NAN);
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::NotFinite { .. })
        ));
    }

    #[test]
    fn non_finite_input_is_held() {
        let config = joint_a();
        let mut inv = PiInverse::new(&config).unwrap();
        let (good, _) = inv.step(230.0e3);
        for bad in [f64::NAN, f64::INFINITY] {
            assert_eq!(inv.step(bad), (good, Flags::NON_FINITE | Flags::HELD));
        }
        let mut fwd = GeneralizedPi::new(&config).unwrap();
        let r = fwd.step(0.005);
        assert_eq!(fwd.step(f64::NAN), r);
    }

    #[test]
    fn reset_repeats_the_same_output() {
        let config = joint_a();
        let mut fwd = GeneralizedPi::new(&config).unwrap();
        let first: [f64; 3] = [0.004, 0.009, 0.002].map(|e| fwd.step(e));
        fwd.reset();
        let again: [f64; 3] = [0.004, 0.009, 0.002].map(|e| fwd.step(e));
        assert_eq!(first, again);
    }

    #[test]
    fn refuses_bad_configs() {
        let mut c = joint_a();
        c.min_ohm = c.max_ohm;
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::EmptyRange { .. })
        ));
        let mut c = joint_a();
        c.unloading_tanh[0] = -1.0;
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::BranchNotIncreasing { .. })
        ));
        let mut c = joint_a();
        c.radii = Coeffs::try_from([0.0; 9]).unwrap();
        assert!(matches!(
            c.validate(),
            Err(EstimatorError::LengthMismatch { .. })
        ));
        let mut c = joint_a();
        c.center_ohm = f64::NAN;
        assert!(c.validate().is_err());
        assert!(joint_a().validate().is_ok());
    }
}
