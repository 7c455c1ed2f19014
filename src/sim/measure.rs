//! Measurement: the divider, the ADC and the EM tracker.
//!
//! - **Divider** (Eq. 4 read forwards): `V = V+·R/(R + R_k)`, `dlw_geometry::Divider::voltage`,
//!   the same code the estimator inverts.
//! - **ADC**: `V + N(0, noise_v²)`, clipped to `[min_v, max_v]`, rounded to the nearest of
//!   `2^bits` codes: `V_q = min_v + round((V − min_v)/LSB)·LSB`, `LSB = (max_v − min_v)/(2^bits − 1)`.
//! - **EM tracker**: the recorded angle is the true angle plus `N(0, noise_deg²)`.

use super::rng::Stream;
use super::scenario::{AdcParams, TrackerParams};

/// The DAQ's analog-to-digital converter for one channel.
#[derive(Debug, Clone)]
pub struct Adc {
    settings: Option<AdcSettings>,
    rng: Stream,
}

#[derive(Debug, Clone, Copy)]
struct AdcSettings {
    min_v: f64,
    max_v: f64,
    lsb_v: f64,
    noise_v: f64,
}

impl Adc {
    /// One channel; `rng` feeds its noise. A disabled ADC passes voltages through exactly.
    pub fn new(params: &AdcParams, rng: Stream) -> Self {
        let codes = (2f64).powi(params.bits as i32) - 1.0;
        Self {
            settings: params.enabled.then_some(AdcSettings {
                min_v: params.min_v,
                max_v: params.max_v,
                lsb_v: (params.max_v - params.min_v) / codes,
                noise_v: params.noise_v,
            }),
            rng,
        }
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
        let noisy = volts + s.noise_v * self.rng.normal();
        let code = ((noisy.clamp(s.min_v, s.max_v) - s.min_v) / s.lsb_v).round();
        s.min_v + code * s.lsb_v
    }
}

/// The EM tracker that records the ground-truth angle.
#[derive(Debug, Clone)]
pub struct Tracker {
    noise_deg: Option<f64>,
    rng: Stream,
}

impl Tracker {
    /// The tracker; `rng` feeds its noise.
    pub fn new(params: &TrackerParams, rng: Stream) -> Self {
        Self {
            noise_deg: params.enabled.then_some(params.noise_deg),
            rng,
        }
    }

    /// The recorded angle (°) for the true angle `angle_deg`.
    #[inline]
    pub fn read(&mut self, angle_deg: f64) -> f64 {
        match self.noise_deg {
            Some(sd) => angle_deg + sd * self.rng.normal(),
            None => angle_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn quantizes_to_codes_and_clips() {
        let params = AdcParams {
            noise_v: 0.0,
            ..AdcParams::default()
        };
        let mut adc = Adc::new(&params, Stream::new(1, 2));
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
        let mut adc = Adc::new(&AdcParams::default(), Stream::new(1, 2));
        let n = 20_000;
        let errs: Vec<f64> = (0..n).map(|_| adc.read(2.5) - 2.5).collect();
        let rms = (errs.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt();
        // 5 mV noise plus 0.305 mV/√12 quantization; standard error √(1/2n) ≈ 0.5 %.
        let expected = (0.005f64.powi(2) + (20.0 / 65535.0f64).powi(2) / 12.0).sqrt();
        assert_relative_eq!(rms, expected, max_relative = 0.03);
        let off = AdcParams {
            enabled: false,
            ..AdcParams::default()
        };
        assert_eq!(Adc::new(&off, Stream::new(1, 2)).read(1.0 / 3.0), 1.0 / 3.0);
    }

    #[test]
    fn tracker_adds_noise_only_when_enabled() {
        let mut t = Tracker::new(&TrackerParams::default(), Stream::new(1, 1));
        assert_ne!(t.read(10.0), 10.0);
        let off = TrackerParams {
            enabled: false,
            noise_deg: 1.0,
        };
        assert_eq!(Tracker::new(&off, Stream::new(1, 1)).read(10.0), 10.0);
    }
}
