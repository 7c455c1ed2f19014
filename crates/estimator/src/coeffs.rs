use core::fmt;

use crate::error::EstimatorError;

/// Most play operators a Prandtl-Ishlinskii model may have. The paper uses `N = 10` (and
/// `N = 3` for control); 16 leaves room while keeping a model a few hundred bytes.
pub const MAX_PLAYS: usize = 16;

/// A list of up to [`MAX_PLAYS`] numbers (play weights or radii) stored inline, so models
/// never allocate.
///
/// With the `serde` feature it reads and writes as a plain sequence (`weights = [1.0, 2.0]`);
/// a longer sequence is refused with an error naming the limit.
#[derive(Clone, Copy, PartialEq)]
pub struct Coeffs {
    values: [f64; MAX_PLAYS],
    len: usize,
}

impl Coeffs {
    /// Copies `values`.
    ///
    /// # Errors
    /// [`EstimatorError::TooMany`] for more than [`MAX_PLAYS`] values (named `name`).
    pub fn from_slice(name: &'static str, values: &[f64]) -> Result<Self, EstimatorError> {
        if values.len() > MAX_PLAYS {
            return Err(EstimatorError::TooMany {
                name,
                count: values.len(),
                max: MAX_PLAYS,
            });
        }
        let mut out = Self::default();
        out.values[..values.len()].copy_from_slice(values);
        out.len = values.len();
        Ok(out)
    }

    /// The values.
    pub fn as_slice(&self) -> &[f64] {
        &self.values[..self.len]
    }

    /// How many values.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Appends a value; `false` (and no change) when full.
    #[cfg(any(feature = "serde", test))]
    fn push(&mut self, value: f64) -> bool {
        if self.len == MAX_PLAYS {
            return false;
        }
        self.values[self.len] = value;
        self.len += 1;
        true
    }
}

impl Default for Coeffs {
    fn default() -> Self {
        Self {
            values: [0.0; MAX_PLAYS],
            len: 0,
        }
    }
}

impl fmt::Debug for Coeffs {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

impl<const N: usize> TryFrom<[f64; N]> for Coeffs {
    type Error = EstimatorError;

    fn try_from(values: [f64; N]) -> Result<Self, EstimatorError> {
        Self::from_slice("coefficients", &values)
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Coeffs {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeSeq;
        let mut seq = serializer.serialize_seq(Some(self.len))?;
        for v in self.as_slice() {
            seq.serialize_element(v)?;
        }
        seq.end()
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Coeffs {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;

        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = Coeffs;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a list of at most {MAX_PLAYS} numbers")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Coeffs, A::Error> {
                let mut out = Coeffs::default();
                while let Some(v) = seq.next_element::<f64>()? {
                    if !out.push(v) {
                        return Err(serde::de::Error::custom(format_args!(
                            "more than {MAX_PLAYS} values (the limit MAX_PLAYS)"
                        )));
                    }
                }
                Ok(out)
            }
        }

        deserializer.deserialize_seq(Visitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_values_and_length() {
        let c = Coeffs::from_slice("weights", &[1.0, 2.5, -3.0]).unwrap();
        assert_eq!(c.as_slice(), &[1.0, 2.5, -3.0]);
        assert_eq!(c.len(), 3);
        assert!(!c.is_empty());
        assert!(Coeffs::default().is_empty());
        assert_eq!(Coeffs::try_from([4.0; MAX_PLAYS]).unwrap().len(), MAX_PLAYS);
    }

    #[test]
    fn refuses_more_than_capacity() {
        assert_eq!(
            Coeffs::from_slice("radii", &[0.0; MAX_PLAYS + 1]),
            Err(EstimatorError::TooMany {
                name: "radii",
                count: MAX_PLAYS + 1,
                max: MAX_PLAYS
            })
        );
        let mut c = Coeffs::try_from([0.0; MAX_PLAYS]).unwrap();
        assert!(!c.push(1.0));
        assert_eq!(c.len(), MAX_PLAYS);
    }
}
