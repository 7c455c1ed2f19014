//! The play count `N` of a PI model, checked once.

use dlw_estimator::MAX_PLAYS;
use serde::Serialize;

use super::FitError;

/// The number of play operators `N` of a PI model (Eqs. 8-11): from [`PlayOrder::MIN`] to
/// [`PlayOrder::MAX`], what the runtime crate runs. Made only through [`PlayOrder::new`], so a
/// fit never sees an order out of range; serialized as the number.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(transparent)]
pub struct PlayOrder(usize);

impl PlayOrder {
    /// Fewest play operators a PI model is fitted with.
    pub const MIN: usize = 2;
    /// Most play operators: what the runtime crate runs.
    pub const MAX: usize = MAX_PLAYS;
    /// The paper's `N = 10` (`dlw fit`'s and `dlw characterize`'s default).
    pub const DEFAULT: PlayOrder = PlayOrder(10);

    /// `n` play operators, or `None` out of range: for constants
    /// (`const N: PlayOrder = PlayOrder::checked(3).unwrap()` fails to compile out of range).
    pub const fn checked(n: usize) -> Option<Self> {
        if n >= Self::MIN && n <= Self::MAX {
            Some(Self(n))
        } else {
            None
        }
    }

    /// `n` play operators.
    ///
    /// # Errors
    /// [`FitError::Order`] outside [`PlayOrder::MIN`] to [`PlayOrder::MAX`].
    pub fn new(n: usize) -> Result<Self, FitError> {
        if (Self::MIN..=Self::MAX).contains(&n) {
            Ok(Self(n))
        } else {
            Err(FitError::Order {
                order: n,
                min: Self::MIN,
                max: Self::MAX,
            })
        }
    }

    /// The count.
    pub fn get(self) -> usize {
        self.0
    }
}

impl std::fmt::Display for PlayOrder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.fmt(f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_order_is_made_only_in_range() {
        assert_eq!(PlayOrder::new(2).unwrap().get(), 2);
        assert_eq!(PlayOrder::new(16).unwrap().get(), 16);
        assert_eq!(PlayOrder::DEFAULT, PlayOrder::new(10).unwrap());
        for n in [0, 1, 17] {
            let e = PlayOrder::new(n).unwrap_err().to_string();
            assert!(e.contains(&format!("order {n}")) && e.contains("16"), "{e}");
        }
    }
}
