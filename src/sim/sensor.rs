//! The sensor: strain → resistance.
//!
//! The strain the sensor feels is `ε` for sensor 1 and `−ε` for sensor 2 of a BSN joint (it lies
//! at `−y_s`). Then, in order:
//!
//! 1. **Saturation** (switchable): the sensor feels `ε_s·tanh(ε/ε_s)`.
//! 2. **Model**: linear, Eq. 6, `R = R0·(1 + GF·ε)`; or the generalized PI model (Eqs. 8-11)
//!    or its continuous variant, run forward by the estimator crate (`GeneralizedPi`,
//!    `ContinuousPi`): the very code whose inverse the estimator uses.
//! 3. **Rate dependence** (switchable), on the change `ΔR = R − R_ref` (`R_ref`: the model at
//!    zero strain), in one of two forms:
//!    - `log`: `ΔR` is scaled by `1 + k·log10(1 + r̄/r_ref)`, `r̄` being `|dε/dt|` through a
//!      first-order low-pass: faster reads more sensitive, loading and unloading alike;
//!    - `signed`: `c·ṙ` is added, `ṙ` being the signed `dε/dt` through the same low-pass and
//!      `c` in Ω·s: loading reads high, unloading low.
//! 4. **Creep** (switchable): `c ← c + (φ·ΔR − c)·(1 − e^(−Δt/τ))` is added, so a held strain's
//!    resistance change grows by `φ` with time constant `τ`; a second term of its own `φ_f`
//!    and `τ_f` is added the same way (a two-term Prony series).
//! 5. **Gain drift** (switchable): `ΔR` is scaled by `1 − fade·t` (fatigue: the sensitivity
//!    fades over the run), after the rate and before the creep.
//! 6. **Baseline drift** (switchable): `rate·t + settle·(1 − e^(−t/τ)) + W(t)` is added, `W` a
//!    Gaussian random walk with
//!    `W(t + Δt) = W(t) + σ·√Δt·N(0, 1)`.
//! 7. **Noise** (switchable): the resistance is scaled by `1 + n`, `n` the sensor's own
//!    first-order autoregressive noise (`[sensorN.noise]`, [`super::correlated::Ar1`]).

use dlw_estimator::{ContinuousPi, GeneralizedPi};

use super::correlated::Ar1;
use super::rng::Stream;
use super::scenario::{RateForm, ScenarioError, SensorModelKind, SensorParams};

/// One sensor's strain → resistance model, stepped once per sample.
#[derive(Debug, Clone)]
pub struct Sensor {
    sign: f64,
    model: Model,
    reference_ohm: f64,
    saturation_strain: Option<f64>,
    rate: Option<Rate>,
    creep: Option<Creep>,
    drift: Option<Drift>,
    /// Sensitivity lost per sample (fraction), and the samples so far.
    gain_fade: Option<(f64, u64)>,
    /// The relative resistance noise.
    noise: Option<Ar1>,
}

#[derive(Debug, Clone)]
enum Model {
    Linear { r0_ohm: f64, gauge_factor: f64 },
    Pi(Box<GeneralizedPi>),
    ContinuousPi(Box<ContinuousPi>),
}

#[derive(Debug, Clone)]
struct Rate {
    form: RateForm,
    per_decade: f64,
    reference_per_s: f64,
    ohm_per_strain_per_s: f64,
    alpha: f64,
    inv_dt: f64,
    previous_strain: Option<f64>,
    smoothed_per_s: f64,
}

#[derive(Debug, Clone)]
struct Creep {
    /// Per term: the fraction, the filter's weight per sample, and the term's resistance.
    terms: [(f64, f64, f64); 2],
}

#[derive(Debug, Clone)]
struct Drift {
    rate_ohm_per_sample: f64,
    settle_ohm: f64,
    settle_alpha: f64,
    settled_ohm: f64,
    step_ohm: f64,
    walk_ohm: f64,
    linear_ohm: f64,
    rng: Stream,
}

impl Sensor {
    /// Sensor `index` (1 or 2) from resolved parameters, sampled every `dt_s` seconds; `rng`
    /// feeds its drift and `noise_rng` its noise. Sensor 2 reads `−ε`.
    ///
    /// Parameters are taken as validated by [`super::Scenario::resolve`], which fills every
    /// `None` this reads.
    ///
    /// # Errors
    /// The PI parameters the estimator crate refuses, or a PI model without parameters (both
    /// caught by `resolve` already).
    pub fn new(
        params: &SensorParams,
        index: usize,
        dt_s: f64,
        rng: Stream,
        noise_rng: Stream,
    ) -> Result<Self, ScenarioError> {
        let missing = |model| ScenarioError::MissingModel {
            sensor: index,
            model,
            why: "the scenario was not resolved",
        };
        let refused = |name: &str| {
            let table = format!("sensor{index}.{name}");
            move |reason| ScenarioError::Model { table, reason }
        };
        let model = match params.model {
            SensorModelKind::Linear => Model::Linear {
                r0_ohm: params.r0_ohm.unwrap_or(f64::NAN),
                gauge_factor: params.gauge_factor.unwrap_or(f64::NAN),
            },
            SensorModelKind::Pi => {
                let config = params.pi.as_ref().ok_or_else(|| missing("pi"))?;
                Model::Pi(Box::new(GeneralizedPi::new(config).map_err(refused("pi"))?))
            }
            SensorModelKind::ContinuousPi => {
                let config = params
                    .continuous_pi
                    .as_ref()
                    .ok_or_else(|| missing("continuous_pi"))?;
                Model::ContinuousPi(Box::new(
                    ContinuousPi::new(config).map_err(refused("continuous_pi"))?,
                ))
            }
        };
        let reference_ohm = model.clone().step(0.0);
        let alpha = |tau_s: f64| 1.0 - (-dt_s / tau_s).exp();
        Ok(Self {
            sign: if index == 2 { -1.0 } else { 1.0 },
            model,
            reference_ohm,
            saturation_strain: params
                .saturation
                .enabled
                .then_some(params.saturation.strain),
            rate: params.rate.enabled.then(|| Rate {
                form: params.rate.form,
                per_decade: params.rate.per_decade,
                reference_per_s: params.rate.reference_rate_per_s,
                ohm_per_strain_per_s: params.rate.ohm_per_strain_per_s.unwrap_or(0.0),
                alpha: alpha(params.rate.smoothing_s),
                inv_dt: 1.0 / dt_s,
                previous_strain: None,
                smoothed_per_s: 0.0,
            }),
            gain_fade: params
                .gain_drift
                .enabled
                .then_some((params.gain_drift.fade_per_hour * dt_s / 3600.0, 0)),
            creep: params.creep.enabled.then(|| Creep {
                terms: [
                    (params.creep.fraction, alpha(params.creep.tau_s), 0.0),
                    (
                        params.creep.fast_fraction,
                        alpha(params.creep.fast_tau_s),
                        0.0,
                    ),
                ],
            }),
            drift: params.drift.enabled.then(|| Drift {
                rate_ohm_per_sample: params.drift.rate_ohm_per_s * dt_s,
                settle_ohm: params.drift.settle_ohm,
                settle_alpha: alpha(params.drift.settle_tau_s),
                settled_ohm: 0.0,
                step_ohm: params.drift.random_walk_ohm_per_sqrt_s.unwrap_or(0.0) * dt_s.sqrt(),
                walk_ohm: 0.0,
                linear_ohm: 0.0,
                rng,
            }),
            noise: params.noise.enabled.then(|| {
                Ar1::new(
                    params.noise.sigma_ppm * 1e-6,
                    params.noise.tau_s,
                    dt_s,
                    noise_rng,
                )
            }),
        })
    }

    /// Resistance (Ω) at joint strain `strain` (sensor 1's sign convention). May be zero or
    /// negative if the scenario drives a model beyond where it is physical; the caller checks.
    #[inline]
    pub fn step(&mut self, strain: f64) -> f64 {
        let mut felt = self.sign * strain;
        if let Some(s) = self.saturation_strain {
            felt = s * (felt / s).tanh();
        }
        let mut change = self.model.step(felt) - self.reference_ohm;
        if let Some(r) = &mut self.rate {
            let rate = r.previous_strain.map_or(0.0, |p| (felt - p) * r.inv_dt);
            r.previous_strain = Some(felt);
            match r.form {
                RateForm::Log => {
                    r.smoothed_per_s += (rate.abs() - r.smoothed_per_s) * r.alpha;
                    change *=
                        1.0 + r.per_decade * (1.0 + r.smoothed_per_s / r.reference_per_s).log10();
                }
                RateForm::Signed => {
                    r.smoothed_per_s += (rate - r.smoothed_per_s) * r.alpha;
                    change += r.ohm_per_strain_per_s * r.smoothed_per_s;
                }
            }
        }
        if let Some((per_sample, n)) = &mut self.gain_fade {
            change *= (1.0 - *per_sample * *n as f64).max(0.0);
            *n += 1;
        }
        let mut ohm = self.reference_ohm + change;
        if let Some(c) = &mut self.creep {
            for (fraction, alpha, term_ohm) in &mut c.terms {
                *term_ohm += (*fraction * change - *term_ohm) * *alpha;
                ohm += *term_ohm;
            }
        }
        if let Some(d) = &mut self.drift {
            ohm += d.linear_ohm + d.walk_ohm + d.settled_ohm;
            d.settled_ohm += (d.settle_ohm - d.settled_ohm) * d.settle_alpha;
            d.linear_ohm += d.rate_ohm_per_sample;
            d.walk_ohm += d.step_ohm * d.rng.normal();
        }
        if let Some(n) = &mut self.noise {
            ohm *= 1.0 + n.next_value();
        }
        ohm
    }
}

impl Model {
    #[inline]
    fn step(&mut self, strain: f64) -> f64 {
        match self {
            Self::Linear {
                r0_ohm,
                gauge_factor,
            } => *r0_ohm * (1.0 + *gauge_factor * strain),
            Self::Pi(m) => m.step(strain),
            Self::ContinuousPi(m) => m.step(strain),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::scenario::Scenario;
    use approx::assert_relative_eq;
    use dlw_geometry::NotchStyle;

    const DT: f64 = 0.002;

    fn params(
        style: NotchStyle,
        edit: impl FnOnce(&mut SensorParams),
    ) -> (SensorParams, Option<SensorParams>) {
        let s = Scenario::default()
            .resolve(&crate::sim::test_design(style))
            .unwrap();
        let (mut a, b) = (s.sensor1, s.sensor2);
        edit(&mut a);
        (a, b)
    }

    fn sensor(p: &SensorParams, index: usize) -> Sensor {
        Sensor::new(p, index, DT, Stream::new(1, 4), Stream::new(1, 10)).unwrap()
    }

    #[test]
    fn linear_is_eq5_and_sensor_two_reads_minus_strain() {
        let (a, b) = params(NotchStyle::Bsn, |_| {});
        let mut s1 = sensor(&a, 1);
        let mut s2 = sensor(&b.unwrap(), 2);
        assert_relative_eq!(
            s1.step(0.01),
            74.0e3 * (1.0 + 1.28 * 0.01),
            max_relative = 1e-14
        );
        assert_relative_eq!(
            s2.step(0.01),
            88.9e3 * (1.0 - 0.680 * 0.01),
            max_relative = 1e-14
        );
    }

    #[test]
    fn pi_model_is_the_estimator_crates_forward() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.model = SensorModelKind::Pi;
            p.pi = Some(crate::sim::JOINT_A_PI.to_config());
        });
        let mut s = sensor(&a, 1);
        let mut reference = GeneralizedPi::new(a.pi.as_ref().unwrap()).unwrap();
        for e in [0.0, 0.004, 0.012, 0.006, 0.001, 0.009] {
            assert_relative_eq!(s.step(e), reference.step(e), max_relative = 1e-14);
        }
    }

    #[test]
    fn saturation_flattens_large_strain() {
        let (a, _) = params(NotchStyle::Uan, |p| p.saturation.enabled = true);
        let mut s = sensor(&a, 1);
        let r = s.step(0.02);
        assert_relative_eq!(
            r,
            215e3 * (1.0 + 15.3 * 0.02 * 1f64.tanh()),
            max_relative = 1e-12
        );
    }

    #[test]
    fn creep_grows_a_held_change_by_its_fraction() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.creep.enabled = true;
            p.creep.fraction = 0.1;
            p.creep.tau_s = 1.0;
        });
        let mut s = sensor(&a, 1);
        let mut r = 0.0;
        for _ in 0..20_000 {
            r = s.step(0.01);
        }
        let change = 215e3 * 15.3 * 0.01;
        assert_relative_eq!(r, 215e3 + 1.1 * change, max_relative = 1e-9);
    }

    #[test]
    fn a_two_term_creep_adds_each_terms_share_of_a_held_change() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.creep.enabled = true;
            p.creep.fraction = 0.1;
            p.creep.tau_s = 100.0;
            p.creep.fast_fraction = 0.05;
            p.creep.fast_tau_s = 1.0;
        });
        let mut s = sensor(&a, 1);
        let steps = 500;
        let mut r = 0.0;
        for _ in 0..steps {
            r = s.step(0.01);
        }
        let t = steps as f64 * DT;
        let change = 215e3 * 15.3 * 0.01;
        let grown = 0.1 * (1.0 - (-t / 100.0).exp()) + 0.05 * (1.0 - (-t / 1.0).exp());
        assert_relative_eq!(r, 215e3 + (1.0 + grown) * change, max_relative = 1e-9);
    }

    #[test]
    fn rate_dependence_raises_sensitivity_when_fast() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.rate.enabled = true;
            p.rate.per_decade = 0.1;
        });
        // Ramp to 1 % at 1e-3/s (10 s) and at 1e-2/s (1 s): the fast one reads higher.
        let ramp = |rate: f64| {
            let mut s = sensor(&a, 1);
            let n = (0.01 / rate / DT) as usize;
            (0..=n)
                .map(|i| s.step(rate * DT * i as f64))
                .last()
                .unwrap()
        };
        let (slow, fast) = (ramp(1e-3), ramp(1e-2));
        let change = 215e3 * 15.3 * 0.01;
        // Smoothed rate ≈ the ramp's rate once past the 1 s low-pass.
        assert_relative_eq!(
            slow,
            215e3 + change * (1.0 + 0.1 * 2f64.log10()),
            max_relative = 1e-3
        );
        assert!(fast > slow + 0.05 * change, "{fast} vs {slow}");
    }

    /// The signed form adds `c·ε̇` once the low-pass has settled: up on loading, down by the
    /// same amount on unloading at the same speed, nothing when held; the log form reads high
    /// both ways.
    #[test]
    fn signed_rate_form_follows_the_sign_of_the_rate() {
        let c = 2e5;
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.rate.enabled = true;
            p.rate.form = RateForm::Signed;
            p.rate.ohm_per_strain_per_s = Some(c);
            p.rate.smoothing_s = 0.1;
        });
        let mut s = sensor(&a, 1);
        let rate = 2e-3;
        let linear = |e: f64| 215e3 * (1.0 + 15.3 * e);
        // Load to 1 % in 5 s (50 time constants of the low-pass), hold 5 s, unload in 5 s.
        let n = (5.0 / DT) as usize;
        let mut strain = 0.0;
        let mut up = 0.0;
        for _ in 0..n {
            strain += rate * DT;
            up = s.step(strain) - linear(strain);
        }
        let mut held = 0.0;
        for _ in 0..n {
            held = s.step(strain) - linear(strain);
        }
        let mut down = 0.0;
        for _ in 0..n {
            strain -= rate * DT;
            down = s.step(strain) - linear(strain);
        }
        assert_relative_eq!(up, c * rate, max_relative = 1e-9);
        assert!(held.abs() < 1e-6 * c * rate, "{held}");
        assert_relative_eq!(down, -c * rate, max_relative = 1e-9);
    }

    #[test]
    fn signed_rate_default_is_a_50_ms_lead_of_the_linear_sensitivity() {
        let s = Scenario::default()
            .resolve(&crate::sim::test_design(NotchStyle::Bsn))
            .unwrap();
        assert_relative_eq!(
            s.sensor1.rate.ohm_per_strain_per_s.unwrap(),
            0.05 * 74.0e3 * 1.28,
            max_relative = 1e-12
        );
        let s2 = s.sensor2.unwrap();
        assert_relative_eq!(
            s2.rate.ohm_per_strain_per_s.unwrap(),
            0.05 * 88.9e3 * 0.680,
            max_relative = 1e-12
        );
    }

    #[test]
    fn drift_random_walk_has_the_configured_spread() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.drift.enabled = true;
            p.drift.rate_ohm_per_s = 1.0;
        });
        // σ = 20 Ω/√s: after 100 s the walk's spread is 200 Ω; the mean drift is +100 Ω.
        let runs = 200;
        let n = 50_000;
        let ends: Vec<f64> = (0..runs)
            .map(|k| {
                let mut s = Sensor::new(&a, 1, DT, Stream::new(k, 4), Stream::new(k, 10)).unwrap();
                (0..=n).map(|_| s.step(0.0)).last().unwrap() - 215e3
            })
            .collect();
        let mean = ends.iter().sum::<f64>() / runs as f64;
        let sd = (ends.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / runs as f64).sqrt();
        // Standard errors with 200 runs: 14 Ω on the mean, 10 Ω on the spread.
        assert!((mean - 100.0).abs() < 50.0, "{mean}");
        assert!((sd - 200.0).abs() < 40.0, "{sd}");
    }

    /// `[sensorN.noise]`: the resistance at a held strain wanders by `sigma_ppm` of itself with
    /// the configured correlation, from its own stream (the drift's draws are unchanged).
    #[test]
    fn noise_is_relative_with_its_spread_and_correlation() {
        let (a, _) = params(NotchStyle::Uan, |p| {
            p.noise.enabled = true;
            p.noise.sigma_ppm = 2000.0;
            p.noise.tau_s = 0.1;
        });
        let mut s = sensor(&a, 1);
        let rel: Vec<f64> = (0..400_000).map(|_| s.step(0.0) / 215e3 - 1.0).collect();
        let (sd, r1) = crate::sim::correlated::sd_and_autocorrelation(&rel, 1);
        // τ = 50 samples over 400 000: 8000 correlation times, relative standard error ≈ 1.6 %.
        assert_relative_eq!(sd, 2e-3, max_relative = 0.06);
        assert!((r1 - (-DT / 0.1f64).exp()).abs() < 2e-3, "{r1}");
        let (off, _) = params(NotchStyle::Uan, |_| {});
        assert_eq!(sensor(&off, 1).step(0.0), 215e3);
    }
}
