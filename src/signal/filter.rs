//! Streaming filters as the command line and the reports name them (`none`, `ma:N`, `lp:T`):
//! one grammar, parsed once, for the estimator's `--filter` and the analyses' `--prefilter`.

use dlw_estimator::FilterConfig;

/// A streaming filter, as written `none`, `ma:N` (a causal moving average of `N` samples) or
/// `lp:T` (a first-order low-pass of time constant `T` samples); parsed and checked against
/// the runtime's limits once, here.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterSpec(FilterConfig);

impl FilterSpec {
    /// The runtime estimator's filter.
    pub fn config(self) -> FilterConfig {
        self.0
    }
}

impl std::str::FromStr for FilterSpec {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("unknown filter {s:?} (expected none, ma:N or lp:T)");
        let config = match s.split_once(':') {
            None if s == "none" => FilterConfig::None,
            Some(("ma", n)) => FilterConfig::MovingAverage {
                samples: n.parse().map_err(|_| bad())?,
            },
            Some(("lp", t)) => FilterConfig::LowPass {
                time_constant_samples: crate::limits::within(
                    "lp:T",
                    t.parse().map_err(|_| bad())?,
                    0.0,
                    crate::limits::MAX_LOW_PASS_SAMPLES,
                    "samples",
                )?,
            },
            _ => return Err(bad()),
        };
        config.validate().map_err(|e| e.to_string())?;
        Ok(Self(config))
    }
}

impl std::fmt::Display for FilterSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            FilterConfig::None => write!(f, "none"),
            FilterConfig::MovingAverage { samples } => write!(f, "ma:{samples}"),
            FilterConfig::LowPass {
                time_constant_samples,
            } => write!(f, "lp:{time_constant_samples}"),
        }
    }
}

/// The prefilter applied to strain and resistance alike before an analysis, and then by the
/// runtime estimator to the resistance (the config's `input_filter`): `none` or `ma:N`, the
/// [`FilterSpec`] grammar without the low-pass, whose response has no window to decimate by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prefilter {
    /// No filter.
    None,
    /// Causal moving average of this many samples.
    MovingAverage(u32),
}

impl Prefilter {
    /// The runtime estimator's filter that does the same.
    pub fn filter_config(self) -> FilterConfig {
        match self {
            Self::None => FilterConfig::None,
            Self::MovingAverage(samples) => FilterConfig::MovingAverage { samples },
        }
    }

    /// The samples each filtered value averages (1 without a filter).
    pub fn window(self) -> usize {
        match self {
            Self::None => 1,
            Self::MovingAverage(n) => n as usize,
        }
    }

    /// Keep every `k`-th sample after this filter: half its window, so that the decimated
    /// series still has two samples per averaging window and aliases nothing the filter
    /// passes (a moving average of `N` has its first null at `f_s/N`).
    pub fn decimation(self) -> usize {
        match self {
            Self::None => 1,
            Self::MovingAverage(n) => (n as usize / 2).max(1),
        }
    }
}

impl std::str::FromStr for Prefilter {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        match s.parse::<FilterSpec>()?.config() {
            FilterConfig::None => Ok(Self::None),
            FilterConfig::MovingAverage { samples } => Ok(Self::MovingAverage(samples)),
            FilterConfig::LowPass { .. } => Err(format!(
                "prefilter {s:?} is a low-pass; a prefilter is none or ma:N (its window sets \
                 the decimation)"
            )),
        }
    }
}

impl std::fmt::Display for Prefilter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        FilterSpec(self.filter_config()).fmt(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_grammar_for_filters_and_prefilters() {
        for text in ["none", "ma:50", "lp:12.5"] {
            assert_eq!(text.parse::<FilterSpec>().unwrap().to_string(), text);
        }
        for text in ["none", "ma:100"] {
            assert_eq!(text.parse::<Prefilter>().unwrap().to_string(), text);
        }
        assert_eq!(
            "ma:100".parse::<Prefilter>(),
            Ok(Prefilter::MovingAverage(100))
        );
        for bad in ["wobble", "ma:x", "ma:", "lp:x", "ma:0", "ma:5000", "lp:-1"] {
            assert!(bad.parse::<FilterSpec>().is_err(), "{bad}");
            assert!(bad.parse::<Prefilter>().is_err(), "{bad}");
        }
        let err = "lp:5".parse::<Prefilter>().unwrap_err();
        assert!(err.contains("none or ma:N"), "{err}");
        assert!("wobble"
            .parse::<Prefilter>()
            .unwrap_err()
            .contains("unknown filter \"wobble\""));
    }
}
