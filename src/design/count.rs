//! Reading `notch_count` as people write it: `10`, `10.0`, or `1e9`.
//!
//! TOML tells integers from floats, so `notch_count = 1e9` used to stop at the parser with
//! "expected u32" while `notch_count = 100000` got the design rule's "must be at most 10000".
//! Any whole number that fits a `u32` is taken here and left to the rules
//! ([`crate::rules`]), so both get the rule's message; what cannot be held (negative, beyond
//! `u32`, not whole) is refused here with the same wording and the same limit.

use serde::de::{self, Deserializer, Visitor};

use crate::design::MAX_NOTCH_COUNT;

/// `deserialize_with` for `notch_count`.
pub(super) fn deserialize_notch_count<'de, D: Deserializer<'de>>(d: D) -> Result<u32, D::Error> {
    d.deserialize_any(CountVisitor)
}

struct CountVisitor;

fn refuse<E: de::Error>(value: String, limit: String) -> E {
    E::custom(format!("notch_count = {value} {limit}"))
}

impl Visitor<'_> for CountVisitor {
    type Value = u32;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a whole number of notches from 1 to {MAX_NOTCH_COUNT}")
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<u32, E> {
        u32::try_from(v)
            .map_err(|_| refuse(v.to_string(), format!("must be at most {MAX_NOTCH_COUNT}")))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<u32, E> {
        if v < 0 {
            return Err(refuse(v.to_string(), "must be at least 1".into()));
        }
        self.visit_u64(v.unsigned_abs())
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<u32, E> {
        if !v.is_finite() || v.fract() != 0.0 {
            return Err(refuse(
                v.to_string(),
                format!("must be a whole number from 1 to {MAX_NOTCH_COUNT}"),
            ));
        }
        if v < 0.0 {
            return Err(refuse(v.to_string(), "must be at least 1".into()));
        }
        if v > f64::from(u32::MAX) {
            return Err(refuse(
                v.to_string(),
                format!("must be at most {MAX_NOTCH_COUNT}"),
            ));
        }
        // Whole and within u32: exact.
        Ok(v as u32)
    }
}

#[cfg(test)]
mod tests {
    use crate::design::DesignFile;

    fn with(count: &str) -> String {
        include_str!("../../designs/joint-a.toml")
            .replace("notch_count = 10", &format!("notch_count = {count}"))
    }

    #[test]
    fn floats_and_huge_counts_get_the_integer_message() {
        // Whole floats are counts: 10.0 reads as 10, 1e9 as 1000000000 (the rules refuse it).
        assert_eq!(
            DesignFile::from_toml(&with("10.0")).unwrap().notch_count,
            10
        );
        assert_eq!(
            DesignFile::from_toml(&with("1e9")).unwrap().notch_count,
            1_000_000_000
        );
        for (text, want) in [
            ("1e10", "notch_count = 10000000000 must be at most 10000"),
            (
                "99999999999",
                "notch_count = 99999999999 must be at most 10000",
            ),
            ("-3", "notch_count = -3 must be at least 1"),
            ("-1e3", "notch_count = -1000 must be at least 1"),
            (
                "1.5",
                "notch_count = 1.5 must be a whole number from 1 to 10000",
            ),
            (
                "nan",
                "notch_count = NaN must be a whole number from 1 to 10000",
            ),
            (
                "inf",
                "notch_count = inf must be a whole number from 1 to 10000",
            ),
        ] {
            let err = DesignFile::from_toml(&with(text)).unwrap_err().to_string();
            assert!(err.contains(want), "{text}: {err}");
        }
        let err = DesignFile::from_toml(&with("\"ten\""))
            .unwrap_err()
            .to_string();
        assert!(err.contains("from 1 to 10000"), "{err}");
    }
}
