//! The plant: tendon stroke → joint angle.
//!
//! `θ = gain·s` (the paper's Joint D: `m_t = 35.49 °/mm`), with three switchable effects applied
//! in this order:
//!
//! 1. **Tendon backlash**: the stroke passes a play operator of radius `width_mm/2` (Eq. 8's
//!    operator, the estimator crate's `PlayOperator`, started at 0), so the joint does not move for the first `width_mm` of stroke
//!    after each reversal.
//! 2. **Viscoelastic relaxation**, a standard linear solid: the elastic angle `θₑ = gain·s` loses
//!    `δ`, which follows `fraction·θₑ` with time constant `τ`:
//!    `δ ← δ + (fraction·θₑ − δ)·(1 − e^(−Δt/τ))` (exact for a held stroke). Under a hold the
//!    angle decays from `θₑ` to `(1 − fraction)·θₑ`, as in the paper's relaxation experiment (Section IV-A3).
//!    With a Prony series (`[[plant.relaxation.terms]]`), one such `δₖ` per term, and the angle
//!    loses their sum.
//! 3. **Notch-closing limit**: the angle stops at `Joint::closing_angle_rad` (UAN: positive
//!    angles only, since a negative angle opens the notches; BSN: both ways).

use dlw_estimator::PlayOperator;
use dlw_geometry::{Joint, NotchStyle};

use super::scenario::PlantParams;

/// The stroke → angle model, a small state machine stepped once per sample.
#[derive(Debug, Clone)]
pub struct Plant {
    gain_rad_per_mm: f64,
    backlash: Option<PlayOperator>,
    /// Each relaxation term's `(fraction, 1 − e^(−Δt/τ))` and the angle it has relaxed (rad).
    relax: Vec<(f64, f64, f64)>,
    limits_rad: (f64, f64),
}

impl Plant {
    /// The plant for `joint` sampled every `dt_s` seconds. Parameters are taken as validated by
    /// the scenario.
    pub fn new(params: &PlantParams, joint: &Joint, dt_s: f64) -> Self {
        let close = joint.closing_angle_rad();
        let limits_rad = match (params.notch_limit.enabled, joint.style()) {
            (false, _) => (f64::NEG_INFINITY, f64::INFINITY),
            (true, NotchStyle::Uan) => (f64::NEG_INFINITY, close),
            (true, NotchStyle::Bsn) => (-close, close),
        };
        Self {
            gain_rad_per_mm: params.gain_deg_per_mm.to_radians(),
            backlash: params
                .backlash
                .enabled
                .then(|| PlayOperator::new(params.backlash.width_mm / 2.0, 0.0)),
            relax: if params.relaxation.enabled {
                params
                    .relaxation
                    .series()
                    .into_iter()
                    .map(|(fraction, tau_s)| (fraction, 1.0 - (-dt_s / tau_s).exp(), 0.0))
                    .collect()
            } else {
                Vec::new()
            },
            limits_rad,
        }
    }

    /// Advances one sample: the angle (rad) at stroke `stroke_mm`.
    #[inline]
    pub fn step(&mut self, stroke_mm: f64) -> f64 {
        let s = match &mut self.backlash {
            Some(play) => play.step(stroke_mm),
            None => stroke_mm,
        };
        let elastic = self.gain_rad_per_mm * s;
        let mut angle = elastic;
        for (fraction, alpha, relaxed) in &mut self.relax {
            *relaxed += (*fraction * elastic - *relaxed) * *alpha;
            angle -= *relaxed;
        }
        angle.clamp(self.limits_rad.0, self.limits_rad.1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::scenario::PlantParams;
    use approx::assert_relative_eq;
    use dlw_geometry::CrossSection;

    fn joint_d() -> Joint {
        let s = CrossSection::new(NotchStyle::Uan, 0.8, 0.61, 3.52, 0.4).unwrap();
        Joint::new(s, 0.5, 0.5, 10, 9.5).unwrap()
    }

    #[test]
    fn plain_gain_is_linear() {
        let mut p = Plant::new(&PlantParams::default(), &joint_d(), 0.002);
        assert_relative_eq!(p.step(1.0).to_degrees(), 35.49, epsilon = 1e-12);
        assert_relative_eq!(p.step(-0.5).to_degrees(), -17.745, epsilon = 1e-12);
    }

    /// A Prony series of two terms is the sum of two standard linear solids: under a held
    /// stroke from rest, `θ = θₑ·(1 − Σ fₖ·(1 − e^(−t/τₖ)))` at the step's sample times.
    #[test]
    fn a_prony_series_relaxes_as_the_sum_of_its_terms() {
        use crate::sim::scenario::RelaxationTerm;
        let mut params = PlantParams::default();
        params.relaxation.enabled = true;
        params.relaxation.terms = vec![
            RelaxationTerm {
                fraction: 0.1,
                tau_s: 2.0,
            },
            RelaxationTerm {
                fraction: 0.05,
                tau_s: 50.0,
            },
        ];
        let dt = 0.01;
        let mut p = Plant::new(&params, &joint_d(), dt);
        let elastic = 35.49f64.to_radians();
        let mut angle = 0.0;
        for _ in 0..1000 {
            angle = p.step(1.0);
        }
        // The discrete update relaxes by 1 − (1 − α)^n with α = 1 − e^(−Δt/τ): exactly e^(−t/τ).
        let t = 1000.0 * dt;
        let lost = 0.1 * (1.0 - (-t / 2.0f64).exp()) + 0.05 * (1.0 - (-t / 50.0f64).exp());
        assert_relative_eq!(angle, elastic * (1.0 - lost), epsilon = 1e-12);
    }

    #[test]
    fn backlash_is_a_dead_band_at_reversals() {
        let mut params = PlantParams::default();
        params.backlash.enabled = true;
        params.backlash.width_mm = 0.2;
        let mut p = Plant::new(&params, &joint_d(), 0.002);
        assert_eq!(p.step(0.05), 0.0);
        let gain = 35.49f64.to_radians();
        assert_relative_eq!(p.step(1.0), gain * 0.9, epsilon = 1e-12);
        // Reversing: the first 0.2 mm of release does not move the joint.
        assert_relative_eq!(p.step(0.85), gain * 0.9, epsilon = 1e-12);
        assert_relative_eq!(p.step(0.5), gain * 0.6, epsilon = 1e-12);
    }

    #[test]
    fn relaxation_decays_to_its_fraction_with_tau() {
        let mut params = PlantParams::default();
        params.relaxation.enabled = true;
        params.relaxation.fraction = 0.1;
        params.relaxation.tau_s = 10.0;
        let dt = 0.002;
        let mut p = Plant::new(&params, &joint_d(), dt);
        let elastic = 35.49f64.to_radians();
        let mut angle = 0.0;
        // Held for one time constant: 1 − e^(−1) of the 10 % loss.
        for _ in 0..5000 {
            angle = p.step(1.0);
        }
        let expected = elastic * (1.0 - 0.1 * (1.0 - (-1.0f64).exp()));
        assert_relative_eq!(angle, expected, max_relative = 1e-3);
        for _ in 0..100_000 {
            angle = p.step(1.0);
        }
        assert_relative_eq!(angle, 0.9 * elastic, max_relative = 1e-6);
    }

    #[test]
    fn notch_limit_stops_at_closing() {
        let mut params = PlantParams::default();
        params.notch_limit.enabled = true;
        let j = joint_d();
        let mut p = Plant::new(&params, &j, 0.002);
        assert_eq!(p.step(100.0), j.closing_angle_rad());
        assert!(p.step(-100.0) < -j.closing_angle_rad(), "UAN opens freely");
    }
}
