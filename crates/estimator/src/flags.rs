use core::fmt;
use core::ops::{BitOr, BitOrAssign};

/// What happened while one sample was turned into an estimate: a small bit set.
///
/// An estimate with no flags was computed from this sample by the model as configured. Any
/// flag says the number is less trustworthy, and [`Flags::HELD`] says it is not from this
/// sample at all.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Flags(u8);

impl Flags {
    /// A divider voltage at or beyond a rail (`V ≤ 0` or `V ≥ V+`): no finite resistance
    /// explains it (open or shorted sensor, disconnected lead, ADC saturation).
    pub const RAIL: Self = Self(1 << 0);
    /// The resistance lay outside the model's characterized range and was clamped to it
    /// (`[min_ohm, max_ohm]` for the PI model; the strain bracket for the continuous PI model),
    /// or the strain it inverted to lay outside the characterized strain range and was clamped.
    pub const RESISTANCE_CLAMPED: Self = Self(1 << 1);
    /// The argument of `atanh` in the PI inverse (Eq. 14) was clamped to `±ATANH_BOUND`.
    pub const ATANH_CLAMPED: Self = Self(1 << 2);
    /// The PI inverse switched tanh branch (or, for the continuous model, the resistance turned)
    /// at this sample. Near a turn of the strain the tanh-PI inverse may be off by up to the
    /// branch gap for one sample (see `TanhInput::branch_gap`); it cannot always tell which.
    pub const REVERSAL: Self = Self(1 << 3);
    /// An input (or a value computed from it) was NaN or infinite.
    pub const NON_FINITE: Self = Self(1 << 4);
    /// The estimate is the last good one, held because this sample could not be used.
    pub const HELD: Self = Self(1 << 5);
    /// The continuous PI inverse's root search stopped after
    /// [`crate::MAX_INVERSE_ITERATIONS`] steps without reaching its `strain_tolerance`: the
    /// strain is the middle of the last bracket, which still contains the root.
    pub const NOT_CONVERGED: Self = Self(1 << 6);

    /// Every flag with its name, in bit order.
    pub const ALL: [(Self, &'static str); 7] = [
        (Self::RAIL, "rail"),
        (Self::RESISTANCE_CLAMPED, "resistance_clamped"),
        (Self::ATANH_CLAMPED, "atanh_clamped"),
        (Self::REVERSAL, "reversal"),
        (Self::NON_FINITE, "non_finite"),
        (Self::HELD, "held"),
        (Self::NOT_CONVERGED, "not_converged"),
    ];

    /// No flags.
    pub const fn empty() -> Self {
        Self(0)
    }

    /// The raw bits (bit 0 is [`Flags::RAIL`]), for logging.
    pub const fn bits(self) -> u8 {
        self.0
    }

    /// Flags from raw bits; bits that name no flag are dropped.
    pub const fn from_bits_truncate(bits: u8) -> Self {
        Self(bits & 0b0111_1111)
    }

    /// Whether no flag is set.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether every flag in `other` is set.
    pub const fn contains(self, other: Self) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether any flag in `other` is set.
    pub const fn intersects(self, other: Self) -> bool {
        self.0 & other.0 != 0
    }

    /// Sets the flags in `other`.
    pub fn insert(&mut self, other: Self) {
        self.0 |= other.0;
    }

    /// `other` if `condition` holds, else no flags (lets hot paths set flags without a branch).
    #[inline]
    pub const fn when(condition: bool, other: Self) -> Self {
        Self(other.0 * condition as u8)
    }
}

impl BitOr for Flags {
    type Output = Self;

    fn bitor(self, rhs: Self) -> Self {
        Self(self.0 | rhs.0)
    }
}

impl BitOrAssign for Flags {
    fn bitor_assign(&mut self, rhs: Self) {
        self.0 |= rhs.0;
    }
}

/// Names joined by `|`, or `none`.
impl fmt::Display for Flags {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("none");
        }
        let mut first = true;
        for (flag, name) in Self::ALL {
            if self.contains(flag) {
                if !first {
                    f.write_str("|")?;
                }
                f.write_str(name)?;
                first = false;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::string::ToString;

    #[test]
    fn flags_are_distinct_bits() {
        let mut seen = 0u8;
        for (flag, _) in Flags::ALL {
            assert_eq!(flag.bits().count_ones(), 1);
            assert_eq!(seen & flag.bits(), 0);
            seen |= flag.bits();
        }
        assert_eq!(Flags::from_bits_truncate(0xff).bits(), seen);
    }

    #[test]
    fn set_operations() {
        let mut f = Flags::empty();
        assert!(f.is_empty());
        f.insert(Flags::RAIL);
        f |= Flags::HELD;
        assert!(f.contains(Flags::RAIL | Flags::HELD));
        assert!(!f.contains(Flags::RAIL | Flags::REVERSAL));
        assert!(f.intersects(Flags::RAIL | Flags::REVERSAL));
        assert_eq!(Flags::when(true, Flags::REVERSAL), Flags::REVERSAL);
        assert_eq!(Flags::when(false, Flags::REVERSAL), Flags::empty());
    }

    #[test]
    fn display_lists_names() {
        assert_eq!(Flags::empty().to_string(), "none");
        assert_eq!((Flags::HELD | Flags::RAIL).to_string(), "rail|held");
    }
}
