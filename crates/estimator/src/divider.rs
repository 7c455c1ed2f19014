use dlw_geometry::Divider;

use crate::flags::Flags;

/// Sensor resistance from a divider reading (Eq. 4), `R = R_k/((V+/V) − 1)`, computed by
/// [`Divider::resistance`] so the planner and the estimator share one formula.
///
/// Never returns NaN or an infinite resistance. A reading that has no finite, positive
/// resistance is reported by its flags instead:
///
/// - NaN or ±∞ volts: [`Flags::NON_FINITE`];
/// - finite volts at or beyond a rail (`V ≤ 0`, `V ≥ V+`), or so close to `V+` that
///   `V+/V − 1` rounds to 0: [`Flags::RAIL`].
///
/// # Errors
/// The flags above, in place of a resistance.
#[inline]
pub fn divider_resistance(divider: &Divider, volts: f64) -> Result<f64, Flags> {
    if !volts.is_finite() {
        return Err(Flags::NON_FINITE);
    }
    match divider.resistance(volts) {
        Ok(ohm) if ohm.is_finite() => Ok(ohm),
        _ => Err(Flags::RAIL),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn bench_divider() -> Divider {
        Divider::new(99.6e3, 5.0).unwrap()
    }

    /// Hand-computed Eq. 4 values: V = V+·R/(R + R_k).
    #[test]
    fn eq4_vectors() {
        let d = bench_divider();
        let table = [
            (2.5, 99.6e3),                  // R = R_k at mid-supply
            (1.0, 99.6e3 / 4.0),            // V+/V − 1 = 4
            (4.0, 99.6e3 * 4.0),            // V+/V − 1 = 1/4
            (5.0 * 215.0 / 314.6, 215.0e3), // Joint A's R_0
        ];
        for (volts, ohm) in table {
            assert_relative_eq!(
                divider_resistance(&d, volts).unwrap(),
                ohm,
                max_relative = 1e-12
            );
        }
    }

    #[test]
    fn rails_are_flagged_not_nan() {
        let d = bench_divider();
        for volts in [0.0, -0.0, -1.0, 5.0, 5.0 + 1e-12, 1e300, -1e300] {
            assert_eq!(divider_resistance(&d, volts), Err(Flags::RAIL), "{volts}");
        }
        for volts in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                divider_resistance(&d, volts),
                Err(Flags::NON_FINITE),
                "{volts}"
            );
        }
    }

    /// Just inside the rails the resistance is extreme but finite (or flagged), never NaN.
    #[test]
    fn just_inside_the_rails_is_finite_or_flagged() {
        let d = bench_divider();
        let below_top = f64::from_bits(5.0f64.to_bits() - 1);
        for volts in [f64::MIN_POSITIVE, 5e-324, 1e-300, below_top] {
            match divider_resistance(&d, volts) {
                Ok(ohm) => assert!(ohm.is_finite() && ohm >= 0.0, "{volts} -> {ohm}"),
                Err(flags) => assert_eq!(flags, Flags::RAIL),
            }
        }
    }
}
