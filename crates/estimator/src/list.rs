use core::fmt;
use core::ops::Deref;

use crate::error::EstimatorError;

/// A list of up to `CAP` values stored inline (the robot's joints, sensors, crosstalk rows), so
/// configs are `Copy` and never allocate.
///
/// The storage is filled with copies of the first value pushed, so `T` needs no default. With
/// the `serde` feature it reads and writes as a plain sequence (`[[joint]]` tables in TOML); a
/// longer sequence is refused with an error naming the limit.
#[derive(Clone, Copy)]
pub struct List<T: Copy, const CAP: usize> {
    items: Option<[T; CAP]>,
    len: usize,
}

impl<T: Copy, const CAP: usize> List<T, CAP> {
    /// An empty list.
    pub const fn new() -> Self {
        Self {
            items: None,
            len: 0,
        }
    }

    /// Copies `values`.
    ///
    /// # Errors
    /// [`EstimatorError::TooMany`] for more than `CAP` values (named `name`).
    pub fn from_slice(name: &'static str, values: &[T]) -> Result<Self, EstimatorError> {
        let mut out = Self::new();
        for v in values {
            if !out.push(*v) {
                return Err(EstimatorError::TooMany {
                    name,
                    count: values.len(),
                    max: CAP,
                });
            }
        }
        Ok(out)
    }

    /// Appends a value; `false` (and no change) when full.
    pub fn push(&mut self, value: T) -> bool {
        if self.len == CAP {
            return false;
        }
        let items = self.items.get_or_insert([value; CAP]);
        items[self.len] = value;
        self.len += 1;
        true
    }

    /// The values.
    pub fn as_slice(&self) -> &[T] {
        match &self.items {
            Some(items) => &items[..self.len],
            None => &[],
        }
    }

    /// The values, to change in place.
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        match &mut self.items {
            Some(items) => &mut items[..self.len],
            None => &mut [],
        }
    }
}

/// Lists are equal when their values are: the unused slots (copies of whatever was pushed
/// first) do not count.
impl<T: Copy + PartialEq, const CAP: usize> PartialEq for List<T, CAP> {
    fn eq(&self, other: &Self) -> bool {
        self.as_slice() == other.as_slice()
    }
}

impl<T: Copy, const CAP: usize> Default for List<T, CAP> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy, const CAP: usize> Deref for List<T, CAP> {
    type Target = [T];

    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Copy + fmt::Debug, const CAP: usize> fmt::Debug for List<T, CAP> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}

#[cfg(feature = "serde")]
impl<T: Copy + serde::Serialize, const CAP: usize> serde::Serialize for List<T, CAP> {
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
impl<'de, T: Copy + serde::Deserialize<'de>, const CAP: usize> serde::Deserialize<'de>
    for List<T, CAP>
{
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor<T, const CAP: usize>(core::marker::PhantomData<T>);

        impl<'de, T: Copy + serde::Deserialize<'de>, const CAP: usize> serde::de::Visitor<'de>
            for Visitor<T, CAP>
        {
            type Value = List<T, CAP>;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a list of at most {CAP} entries")
            }

            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<List<T, CAP>, A::Error> {
                let mut out = List::new();
                while let Some(v) = seq.next_element::<T>()? {
                    if !out.push(v) {
                        return Err(serde::de::Error::custom(format_args!(
                            "more than {CAP} entries (the most this runtime holds)"
                        )));
                    }
                }
                Ok(out)
            }
        }

        deserializer.deserialize_seq(Visitor::<T, CAP>(core::marker::PhantomData))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_values_and_refuses_more_than_capacity() {
        let mut list = List::<u32, 3>::new();
        assert!(list.is_empty());
        assert!(list.push(7) && list.push(8));
        assert_eq!(list.as_slice(), &[7, 8]);
        assert!(list.push(9));
        assert!(!list.push(10));
        assert_eq!(&*list, &[7, 8, 9]);
        list.as_mut_slice()[1] = 1;
        assert_eq!(list.as_slice(), &[7, 1, 9]);
        // Equal values, different unused slots.
        let (mut a, mut b) = (List::<u32, 3>::new(), List::<u32, 3>::new());
        a.push(1);
        b.push(2);
        b.as_mut_slice()[0] = 1;
        assert_eq!(a, b);
        assert_ne!(a, List::new());
        assert_eq!(
            List::<f64, 2>::from_slice("crosstalk", &[1.0, 2.0, 3.0]),
            Err(EstimatorError::TooMany {
                name: "crosstalk",
                count: 3,
                max: 2
            })
        );
    }
}
