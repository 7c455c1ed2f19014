use core::fmt;

use dlw_geometry::GeometryError;

/// Why an estimator configuration was refused. Every variant names the offending value and the
/// limit it broke; the per-sample path never returns an error (it flags instead).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EstimatorError {
    /// The joint geometry or a divider was refused by `dlw-geometry`.
    Geometry(GeometryError),
    /// A parameter that must be a finite number is not.
    NotFinite {
        /// Parameter name as written in config files.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A parameter that must be positive is zero or negative.
    NotPositive {
        /// Parameter name as written in config files.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A parameter that must not be negative is negative.
    Negative {
        /// Parameter name as written in config files.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// A parameter that must not be zero is zero.
    Zero {
        /// Parameter name as written in config files.
        name: &'static str,
    },
    /// A list has more entries than the fixed capacity the estimator was built with.
    TooMany {
        /// Parameter name as written in config files.
        name: &'static str,
        /// Entries given.
        count: usize,
        /// The capacity (a constant of this crate).
        max: usize,
    },
    /// A list that needs at least one entry is empty.
    Empty {
        /// Parameter name as written in config files.
        name: &'static str,
    },
    /// Two lists that pair up entry by entry have different lengths.
    LengthMismatch {
        /// The list that is too long or too short.
        name: &'static str,
        /// Its length.
        len: usize,
        /// The list it must match.
        other: &'static str,
        /// That list's length.
        other_len: usize,
    },
    /// The first play radius is not 0: the inverse needs a pure gain as its first operator.
    FirstRadiusNotZero {
        /// `radii[0]` as given.
        value: f64,
    },
    /// Play radii are not strictly increasing.
    RadiiNotIncreasing {
        /// Index of the offending radius.
        index: usize,
        /// `radii[index]`.
        value: f64,
        /// `radii[index − 1]`, which it must exceed.
        previous: f64,
    },
    /// A partial sum of the weights, `S_i = P_1 + … + P_i`, is not positive, so the
    /// Prandtl-Ishlinskii operator is not invertible.
    PartialSumNotPositive {
        /// Index `i − 1` of the last weight in the sum (0 for `S_1 = P_1`).
        index: usize,
        /// `S_i`.
        value: f64,
    },
    /// A weight that must not be negative is negative.
    NegativeWeight {
        /// Index of the offending weight.
        index: usize,
        /// `weights[index]`.
        value: f64,
    },
    /// A tanh branch `a·tanh(b·x + c) + d` does not increase with strain (`a·b ≤ 0`).
    BranchNotIncreasing {
        /// Which branch: `loading_tanh` or `unloading_tanh`.
        name: &'static str,
        /// Its slope sign `a·b`.
        slope: f64,
    },
    /// A range whose lower end is not below its upper end.
    EmptyRange {
        /// Name of the lower end.
        min_name: &'static str,
        /// The lower end.
        min: f64,
        /// Name of the upper end.
        max_name: &'static str,
        /// The upper end.
        max: f64,
    },
    /// A count outside its allowed range.
    CountOutOfRange {
        /// Parameter name as written in config files.
        name: &'static str,
        /// The value given.
        value: u64,
        /// Smallest allowed value.
        min: u64,
        /// Largest allowed value.
        max: u64,
    },
    /// More sensors are configured than the joint carries.
    TooManySensors {
        /// Sensors configured.
        configured: u32,
        /// Sensors the joint's notch style carries.
        joint_carries: u32,
    },
    /// A two-sensor config whose sensors are not on `+y_s` (first) and `−y_s` (second).
    SensorPlanes,
}

impl fmt::Display for EstimatorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Geometry(e) => e.fmt(f),
            Self::NotFinite { name, value } => write!(f, "{name} = {value} is not a finite number"),
            Self::NotPositive { name, value } => write!(f, "{name} = {value} must be greater than 0"),
            Self::Negative { name, value } => write!(f, "{name} = {value} must be at least 0"),
            Self::Zero { name } => write!(f, "{name} = 0 must not be 0"),
            Self::TooMany { name, count, max } => {
                write!(f, "{name} has {count} entries, at most {max} are supported")
            }
            Self::Empty { name } => write!(f, "{name} is empty, needs at least 1 entry"),
            Self::LengthMismatch { name, len, other, other_len } => write!(
                f,
                "{name} has {len} entries, must have as many as {other} ({other_len})"
            ),
            Self::FirstRadiusNotZero { value } => write!(
                f,
                "radii[0] = {value} must be 0 (the first play operator must be a pure gain for the inverse to exist)"
            ),
            Self::RadiiNotIncreasing { index, value, previous } => write!(
                f,
                "radii[{index}] = {value} must be greater than radii[{}] = {previous}",
                index - 1
            ),
            Self::PartialSumNotPositive { index, value } => write!(
                f,
                "partial weight sum S_{} = weights[0] + .. + weights[{index}] = {value} must be greater than 0",
                index + 1
            ),
            Self::NegativeWeight { index, value } => {
                write!(f, "weights[{index}] = {value} must be at least 0")
            }
            Self::BranchNotIncreasing { name, slope } => write!(
                f,
                "{name} slope a·b = {slope} must be greater than 0 (the branch must increase with strain)"
            ),
            Self::EmptyRange { min_name, min, max_name, max } => {
                write!(f, "{min_name} = {min} must be smaller than {max_name} = {max}")
            }
            Self::CountOutOfRange { name, value, min, max } => {
                write!(f, "{name} = {value} must lie between {min} and {max}")
            }
            Self::TooManySensors { configured, joint_carries } => write!(
                f,
                "{configured} sensors are configured but the joint carries at most {joint_carries}"
            ),
            Self::SensorPlanes => write!(
                f,
                "a two-sensor config needs sensor on plane plus_ys and second_sensor on minus_ys"
            ),
        }
    }
}

impl From<GeometryError> for EstimatorError {
    fn from(e: GeometryError) -> Self {
        Self::Geometry(e)
    }
}

#[cfg(feature = "std")]
impl std::error::Error for EstimatorError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Geometry(e) => Some(e),
            _ => None,
        }
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, EstimatorError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(EstimatorError::NotFinite { name, value })
    }
}

/// Checks that `value` is finite and positive.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, EstimatorError> {
    if finite(name, value)? <= 0.0 {
        return Err(EstimatorError::NotPositive { name, value });
    }
    Ok(value)
}

/// Checks that `min < max`, both finite.
pub(crate) fn range(
    min_name: &'static str,
    min: f64,
    max_name: &'static str,
    max: f64,
) -> Result<(), EstimatorError> {
    finite(min_name, min)?;
    finite(max_name, max)?;
    if min >= max {
        return Err(EstimatorError::EmptyRange {
            min_name,
            min,
            max_name,
            max,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    /// Every message is lowercase and names the value and the limit.
    #[test]
    fn messages_name_value_and_limit() {
        let table: [(EstimatorError, &[&str]); 6] = [
            (
                EstimatorError::TooMany {
                    name: "weights",
                    count: 20,
                    max: 16,
                },
                &["weights", "20", "16"],
            ),
            (
                EstimatorError::FirstRadiusNotZero { value: 0.5 },
                &["radii[0] = 0.5", "must be 0"],
            ),
            (
                EstimatorError::RadiiNotIncreasing {
                    index: 3,
                    value: 0.1,
                    previous: 0.2,
                },
                &["radii[3] = 0.1", "radii[2] = 0.2"],
            ),
            (
                EstimatorError::PartialSumNotPositive {
                    index: 2,
                    value: -1.5,
                },
                &["s_3", "-1.5", "greater than 0"],
            ),
            (
                EstimatorError::CountOutOfRange {
                    name: "samples",
                    value: 5000,
                    min: 1,
                    max: 4096,
                },
                &["samples = 5000", "4096"],
            ),
            (
                EstimatorError::Geometry(GeometryError::NoNotches),
                &["notch_count = 0"],
            ),
        ];
        for (error, needles) in table {
            let text = error.to_string();
            assert!(text.starts_with(|c: char| !c.is_uppercase()), "{text}");
            for needle in needles {
                assert!(
                    text.to_lowercase().contains(needle),
                    "{text} lacks {needle}"
                );
            }
        }
    }

    #[test]
    fn checks() {
        assert_eq!(positive("r0_ohm", 1.0), Ok(1.0));
        assert!(matches!(
            positive("r0_ohm", 0.0),
            Err(EstimatorError::NotPositive { .. })
        ));
        assert!(matches!(
            positive("r0_ohm", f64::NAN),
            Err(EstimatorError::NotFinite { .. })
        ));
        assert!(range("min_ohm", 1.0, "max_ohm", 2.0).is_ok());
        assert!(matches!(
            range("min_ohm", 2.0, "max_ohm", 2.0),
            Err(EstimatorError::EmptyRange { .. })
        ));
    }
}
