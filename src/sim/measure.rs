//! Measurement: the divider, the ADC and the EM tracker.
//!
//! - **Divider** (Eq. 4 read forwards): `V = V+·R/(R + R_k)`, `dlw_geometry::Divider::voltage`,
//!   the same code the estimator inverts.
//! - **ADC**: `V + N(0, noise_v²) + c_v`, clipped to `[min_v, max_v]`, rounded to the nearest of
//!   `2^bits` codes: `V_q = min_v + round((V − min_v)/LSB)·LSB`, `LSB = (max_v − min_v)/(2^bits − 1)`.
//!   `c_v` is the correlated noise of `[adc.correlated]` (a first-order autoregressive process,
//!   [`super::correlated`]) when switched on, otherwise 0.
//! - **EM tracker**: the recorded angle is the true angle plus `N(0, noise_deg²)` plus the
//!   correlated error `c_θ` of `[tracker.correlated]` when switched on.
//!
//! White and correlated noise come from separate streams ([`super::rng::streams`]), so
//! switching the correlated part on leaves the white draws of a seed unchanged.

use super::correlated::Ar1;
use super::rng::{streams, Stream};
use super::scenario::{AdcParams, TrackerParams};

/// The DAQ's analog-to-digital converter for one channel.
#[derive(Debug, Clone)]
pub struct Adc {
    settings: Option<AdcSettings>,
    rng: Stream,
    correlated: Option<Ar1>,
}

#[derive(Debug, Clone, Copy)]
struct AdcSettings {
    min_v: f64,
    max_v: f64,
    lsb_v: f64,
    noise_v: f64,
}

impl Adc {
    /// One channel sampled every `dt_s` seconds; `rng` feeds its white noise and
    /// `correlated_rng` its correlated noise. A disabled ADC passes voltages through exactly.
    pub fn new(params: &AdcParams, dt_s: f64, rng: Stream, correlated_rng: Stream) -> Self {
        let codes = (2f64).powi(params.bits as i32) - 1.0;
        let c = &params.correlated;
        Self {
            settings: params.enabled.then_some(AdcSettings {
                min_v: params.min_v,
                max_v: params.max_v,
                lsb_v: (params.max_v - params.min_v) / codes,
                noise_v: params.noise_v,
            }),
            rng,
            correlated: (params.enabled && c.enabled)
                .then(|| Ar1::new(c.sigma_v, c.tau_s, dt_s, correlated_rng)),
        }
    }

    /// Channel `channel` (0 for sensor 1, 1 for sensor 2) of a bench seeded with `seed`, with
    /// the streams [`super::Plan::run`] uses.
    pub fn for_channel(params: &AdcParams, seed: u64, channel: u64, dt_s: f64) -> Self {
        Self::new(
            params,
            dt_s,
            Stream::new(seed, streams::ADC + channel),
            Stream::new(seed, streams::ADC_CORRELATED + channel),
        )
    }

    /// The quantization step (V), if the ADC is on.
    pub fn lsb_v(&self) -> Option<f64> {
        self.settings.map(|s| s.lsb_v)
    }

    /// Converts one voltage.
    #[inline]
    pub fn read(&mut self, volts: f64) -> f64 {
        let Some(s) = self.settings else {
            return volts;
        };
        let mut noisy = volts + s.noise_v * self.rng.normal();
        if let Some(c) = &mut self.correlated {
            noisy += c.next_value();
        }
        let code = ((noisy.clamp(s.min_v, s.max_v) - s.min_v) / s.lsb_v).round();
        s.min_v + code * s.lsb_v
    }
}

/// The EM tracker that records the ground-truth angle.
#[derive(Debug, Clone)]
pub struct Tracker {
    noise_deg: Option<f64>,
    rng: Stream,
    correlated: Option<Ar1>,
}

impl Tracker {
    /// The tracker sampled every `dt_s` seconds; `rng` feeds its white noise and
    /// `correlated_rng` its correlated error.
    pub fn new(params: &TrackerParams, dt_s: f64, rng: Stream, correlated_rng: Stream) -> Self {
        let c = &params.correlated;
        Self {
            noise_deg: params.enabled.then_some(params.noise_deg),
            rng,
            correlated: (params.enabled && c.enabled)
                .then(|| Ar1::new(c.sigma_deg, c.tau_s, dt_s, correlated_rng)),
        }
    }

    /// The tracker of a bench seeded with `seed`, with the streams [`super::Plan::run`] uses.
    pub fn for_seed(params: &TrackerParams, seed: u64, dt_s: f64) -> Self {
        Self::new(
            params,
            dt_s,
            Stream::new(seed, streams::TRACKER),
            Stream::new(seed, streams::TRACKER_CORRELATED),
        )
    }

    /// The recorded angle (°) for the true angle `angle_deg`.
    #[inline]
    pub fn read(&mut self, angle_deg: f64) -> f64 {
        let Some(sd) = self.noise_deg else {
            return angle_deg;
        };
        let mut recorded = angle_deg + sd * self.rng.normal();
        if let Some(c) = &mut self.correlated {
            recorded += c.next_value();
        }
        recorded
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::correlated::sd_and_autocorrelation;
    use crate::sim::scenario::{AdcCorrelated, TrackerCorrelated};
    use approx::assert_relative_eq;

    const DT: f64 = 0.002;

    fn adc(params: &AdcParams) -> Adc {
        Adc::for_channel(params, 1, 0, DT)
    }

    #[test]
    fn quantizes_to_codes_and_clips() {
        let params = AdcParams {
            noise_v: 0.0,
            ..AdcParams::default()
        };
        let mut adc = adc(&params);
        let lsb = adc.lsb_v().unwrap();
        assert_relative_eq!(lsb, 20.0 / 65535.0);
        let v = adc.read(1.234_567);
        assert!((v - 1.234_567).abs() <= lsb / 2.0 + 1e-15);
        let code = (v + 10.0) / lsb;
        assert_relative_eq!(code, code.round(), epsilon = 1e-6);
        assert_eq!(adc.read(50.0), 10.0);
        assert_eq!(adc.read(-50.0), -10.0);
    }

    #[test]
    fn noise_has_the_configured_spread_and_off_passes_through() {
        let mut a = adc(&AdcParams::default());
        let n = 20_000;
        let errs: Vec<f64> = (0..n).map(|_| a.read(2.5) - 2.5).collect();
        let rms = (errs.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt();
        // 5 mV noise plus 0.305 mV/√12 quantization; standard error √(1/2n) ≈ 0.5 %.
        let expected = (0.005f64.powi(2) + (20.0 / 65535.0f64).powi(2) / 12.0).sqrt();
        assert_relative_eq!(rms, expected, max_relative = 0.03);
        // White: neighbours are uncorrelated (standard error 1/√n = 0.007).
        let (_, r1) = sd_and_autocorrelation(&errs, 1);
        assert!(r1.abs() < 0.035, "{r1}");
        let off = AdcParams {
            enabled: false,
            correlated: AdcCorrelated {
                enabled: true,
                ..AdcCorrelated::default()
            },
            ..AdcParams::default()
        };
        assert_eq!(adc(&off).read(1.0 / 3.0), 1.0 / 3.0);
    }

    /// White plus correlated noise: variance `σ_w² + σ_c² + q²/12` and lag-1 autocorrelation
    /// `σ_c²·φ/(σ_w² + σ_c² + q²/12)`. τ = 0.2 s (100 samples) over 600 000 samples: the
    /// variance's relative standard error is about 2 %, the autocorrelation's about 0.01 relative.
    #[test]
    fn correlated_noise_adds_its_variance_and_autocorrelation() {
        let (white, sigma, tau) = (0.002, 0.004, 0.2);
        let params = AdcParams {
            noise_v: white,
            correlated: AdcCorrelated {
                enabled: true,
                sigma_v: sigma,
                tau_s: tau,
            },
            ..AdcParams::default()
        };
        let mut a = adc(&params);
        let errs: Vec<f64> = (0..600_000).map(|_| a.read(2.5) - 2.5).collect();
        let q2 = (20.0 / 65535.0f64).powi(2) / 12.0;
        let total = white * white + sigma * sigma + q2;
        let (sd, r1) = sd_and_autocorrelation(&errs, 1);
        assert_relative_eq!(sd, total.sqrt(), max_relative = 0.05);
        let phi = (-DT / tau).exp();
        assert_relative_eq!(r1, sigma * sigma * phi / total, max_relative = 0.05);
    }

    /// The white draws do not depend on whether correlated noise is on: the difference of the
    /// two readings is the correlated process alone, whose neighbours are correlated by φ.
    #[test]
    fn switching_correlated_noise_on_keeps_the_white_draws() {
        let params = |on: bool| AdcParams {
            bits: 32,
            correlated: AdcCorrelated {
                enabled: on,
                ..AdcCorrelated::default()
            },
            ..AdcParams::default()
        };
        let (mut white, mut both) = (adc(&params(false)), adc(&params(true)));
        let diff: Vec<f64> = (0..200_000)
            .map(|_| both.read(2.5) - white.read(2.5))
            .collect();
        let (sd, r1) = sd_and_autocorrelation(&diff, 1);
        // 32-bit codes are 4.7 nV: the difference is the 2 mV process to well under 1 %.
        assert!((sd / 0.002 - 1.0).abs() < 0.25, "{sd}");
        assert!(r1 > 0.99, "{r1}");
    }

    #[test]
    fn tracker_adds_noise_only_when_enabled() {
        let mut t = Tracker::for_seed(&TrackerParams::default(), 1, DT);
        assert_ne!(t.read(10.0), 10.0);
        let off = TrackerParams {
            enabled: false,
            noise_deg: 1.0,
            correlated: TrackerCorrelated {
                enabled: true,
                ..TrackerCorrelated::default()
            },
        };
        assert_eq!(Tracker::for_seed(&off, 1, DT).read(10.0), 10.0);
    }

    /// The tracker's white noise is stream [`streams::TRACKER`] exactly, with or without the
    /// correlated error (whose own stream is [`streams::TRACKER_CORRELATED`]).
    #[test]
    fn tracker_streams_are_the_documented_ones() {
        let mut white = Stream::new(4, streams::TRACKER);
        let mut t = Tracker::for_seed(&TrackerParams::default(), 4, DT);
        for _ in 0..100 {
            assert_eq!(t.read(1.5), 1.5 + 0.3 * white.normal());
        }
        let params = TrackerParams {
            noise_deg: 0.0,
            correlated: TrackerCorrelated {
                enabled: true,
                sigma_deg: 0.5,
                tau_s: 0.05,
            },
            ..TrackerParams::default()
        };
        let mut t = Tracker::for_seed(&params, 4, DT);
        let angles: Vec<f64> = (0..400_000).map(|_| t.read(0.0)).collect();
        let (sd, r1) = sd_and_autocorrelation(&angles, 1);
        // τ = 25 samples: 16 000 correlation times, standard errors ≈ 1 % and 3·10⁻⁴.
        assert_relative_eq!(sd, 0.5, max_relative = 0.05);
        assert!((r1 - (-DT / 0.05f64).exp()).abs() < 2e-3, "{r1}");
    }
}
