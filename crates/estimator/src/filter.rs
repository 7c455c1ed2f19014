use crate::error::EstimatorError;
use crate::low_pass::LowPass;
use crate::moving_average::MovingAverage;

/// Which streaming filter to use, as written in config files.
///
/// In TOML: `output_filter = "none"`, or a table `[output_filter.moving_average]` with
/// `samples = 1000`, or `[output_filter.low_pass]` with `time_constant_samples = 50.0`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(
    feature = "serde",
    serde(rename_all = "snake_case", deny_unknown_fields)
)]
pub enum FilterConfig {
    /// Pass samples through.
    #[default]
    None,
    /// Mean of the last `samples` samples (1 to [`crate::MAX_MOVING_AVERAGE`]); delay
    /// `(samples − 1)/2`.
    MovingAverage {
        /// Window length (samples).
        samples: u32,
    },
    /// First-order low-pass with time constant `τ` (samples); delay about `τ − ½`.
    LowPass {
        /// Time constant `τ` (samples, > 0).
        time_constant_samples: f64,
    },
}

impl FilterConfig {
    /// Checks the parameters.
    ///
    /// # Errors
    /// As [`MovingAverage::new`] and [`LowPass::new`].
    pub fn validate(&self) -> Result<(), EstimatorError> {
        match *self {
            Self::None => Ok(()),
            Self::MovingAverage { samples } => {
                check_window(samples)?;
                Ok(())
            }
            Self::LowPass {
                time_constant_samples,
            } => LowPass::new(time_constant_samples).map(|_| ()),
        }
    }
}

/// Window check without building the 32 KiB buffer.
fn check_window(samples: u32) -> Result<(), EstimatorError> {
    if samples == 0 || samples as usize > crate::MAX_MOVING_AVERAGE {
        return MovingAverage::new(samples).map(|_| ());
    }
    Ok(())
}

/// A running filter built from a [`FilterConfig`].
// Without an allocator the moving average's buffer has to live inline, so every variant is as
// large as it (32 KiB).
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Filter {
    /// Passes samples through.
    None,
    /// A moving average.
    MovingAverage(MovingAverage),
    /// A first-order low-pass.
    LowPass(LowPass),
}

impl Filter {
    /// The filter `config` describes.
    ///
    /// # Errors
    /// As [`FilterConfig::validate`].
    pub fn new(config: &FilterConfig) -> Result<Self, EstimatorError> {
        Ok(match *config {
            FilterConfig::None => Self::None,
            FilterConfig::MovingAverage { samples } => {
                Self::MovingAverage(MovingAverage::new(samples)?)
            }
            FilterConfig::LowPass {
                time_constant_samples,
            } => Self::LowPass(LowPass::new(time_constant_samples)?),
        })
    }

    /// Feeds one sample and returns the filtered value.
    #[inline]
    pub fn step(&mut self, x: f64) -> f64 {
        match self {
            Self::None => x,
            Self::MovingAverage(f) => f.step(x),
            Self::LowPass(f) => f.step(x),
        }
    }

    /// Delay a ramp sees once the filter has settled (samples).
    pub fn delay_samples(&self) -> f64 {
        match self {
            Self::None => 0.0,
            Self::MovingAverage(f) => f.delay_samples(),
            Self::LowPass(f) => f.delay_samples(),
        }
    }

    /// Forgets past samples.
    pub fn reset(&mut self) {
        match self {
            Self::None => {}
            Self::MovingAverage(f) => f.reset(),
            Self::LowPass(f) => f.reset(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_what_the_config_says() {
        let table = [
            (FilterConfig::None, 0.0),
            (FilterConfig::MovingAverage { samples: 501 }, 250.0),
            (
                FilterConfig::LowPass {
                    time_constant_samples: 1.0,
                },
                1.0 / (1f64.exp() - 1.0),
            ),
        ];
        for (config, delay) in table {
            assert!(config.validate().is_ok());
            let mut f = Filter::new(&config).unwrap();
            assert!((f.delay_samples() - delay).abs() < 1e-12, "{config:?}");
            assert_eq!(f.step(4.0), 4.0);
            f.reset();
            assert_eq!(f.step(-1.0), -1.0);
        }
    }

    #[test]
    fn refuses_out_of_range() {
        for config in [
            FilterConfig::MovingAverage { samples: 0 },
            FilterConfig::MovingAverage { samples: 100_000 },
            FilterConfig::LowPass {
                time_constant_samples: -1.0,
            },
        ] {
            assert!(config.validate().is_err(), "{config:?}");
            assert!(Filter::new(&config).is_err());
        }
    }
}
