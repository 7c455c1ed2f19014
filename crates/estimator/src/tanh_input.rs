use crate::error::{finite, EstimatorError};

/// Bound on the argument of `atanh` in the inverse (Eq. 13): `|(μ − d)/a| ≤ 1 − 10⁻⁹`.
///
/// `atanh` is infinite at ±1. Clamping there keeps the strain finite: `|atanh| ≤ 10.71`, so the
/// inverse's strain lies within `(±10.71 − c)/b` of the branch's centre. A clamped sample is
/// flagged with [`crate::Flags::ATANH_CLAMPED`].
pub const ATANH_BOUND: f64 = 1.0 - 1e-9;

/// One saturating branch `f(x) = a·tanh(b·x + c) + d` of the play operators' input (Eq. 10),
/// with `a·b > 0` so that it increases with strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TanhBranch {
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    inv_a: f64,
    inv_b: f64,
}

impl TanhBranch {
    /// The branch `a·tanh(b·x + c) + d` from `[a, b, c, d]` (the paper's `a₁..a₄` or `a₅..a₈`).
    ///
    /// # Errors
    /// A coefficient that is not finite (named `name[i]`), or `a·b ≤ 0`.
    pub fn new(name: &'static str, [a, b, c, d]: [f64; 4]) -> Result<Self, EstimatorError> {
        for value in [a, b, c, d] {
            finite(name, value)?;
        }
        let slope = a * b;
        if slope.is_nan() || slope <= 0.0 {
            return Err(EstimatorError::BranchNotIncreasing { name, slope });
        }
        Ok(Self {
            a,
            b,
            c,
            d,
            inv_a: 1.0 / a,
            inv_b: 1.0 / b,
        })
    }

    /// The coefficients `[a, b, c, d]`.
    pub fn coefficients(&self) -> [f64; 4] {
        [self.a, self.b, self.c, self.d]
    }

    /// `f(x) = a·tanh(b·x + c) + d`.
    #[inline]
    pub fn value(&self, x: f64) -> f64 {
        self.a * libm::tanh(self.b * x + self.c) + self.d
    }

    /// `f'(x) = a·b·(1 − tanh²(b·x + c))`.
    #[inline]
    pub fn slope(&self, x: f64) -> f64 {
        let t = libm::tanh(self.b * x + self.c);
        self.a * self.b * (1.0 - t * t)
    }

    /// `(f(x), f'(x))` with one `tanh`.
    #[inline]
    pub fn value_and_slope(&self, x: f64) -> (f64, f64) {
        let t = libm::tanh(self.b * x + self.c);
        (self.a * t + self.d, self.a * self.b * (1.0 - t * t))
    }

    /// `f⁻¹(μ) = (atanh((μ − d)/a) − c)/b` (Eq. 13), with the `atanh` argument clamped to
    /// `±`[`ATANH_BOUND`]. Returns the strain and whether it was clamped.
    #[inline]
    pub fn inverse(&self, mu: f64) -> (f64, bool) {
        let arg = (mu - self.d) * self.inv_a;
        let clamped = arg.abs() > ATANH_BOUND;
        let arg = arg.clamp(-ATANH_BOUND, ATANH_BOUND);
        ((libm::atanh(arg) - self.c) * self.inv_b, clamped)
    }
}

/// The direction-switched input of the play operators (Eq. 10): the loading branch while the
/// strain rises or holds (`ε(t) ≥ ε(t−1)`), the unloading branch while it falls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TanhInput {
    /// `a₁·tanh(a₂·x + a₃) + a₄`, used while `ε(t) ≥ ε(t−1)`.
    pub loading: TanhBranch,
    /// `a₅·tanh(a₆·x + a₇) + a₈`, used while `ε(t) < ε(t−1)`.
    pub unloading: TanhBranch,
}

impl TanhInput {
    /// The input from `[a₁, a₂, a₃, a₄]` and `[a₅, a₆, a₇, a₈]`.
    ///
    /// # Errors
    /// As [`TanhBranch::new`], for either branch.
    pub fn new(loading: [f64; 4], unloading: [f64; 4]) -> Result<Self, EstimatorError> {
        Ok(Self {
            loading: TanhBranch::new("loading_tanh", loading)?,
            unloading: TanhBranch::new("unloading_tanh", unloading)?,
        })
    }

    /// `ν(x)` on the loading (`true`) or unloading branch (Eq. 10).
    #[inline]
    pub fn nu(&self, x: f64, loading: bool) -> f64 {
        if loading {
            self.loading.value(x)
        } else {
            self.unloading.value(x)
        }
    }

    /// `ν⁻¹(μ)` on the loading (`true`) or unloading branch (Eq. 13), and whether the `atanh`
    /// argument was clamped.
    #[inline]
    pub fn nu_inverse(&self, mu: f64, loading: bool) -> (f64, bool) {
        if loading {
            self.loading.inverse(mu)
        } else {
            self.unloading.inverse(mu)
        }
    }

    /// The error bound of the inverse at a reversal, at strain `x` (relative to `ε_c`).
    ///
    /// At a reversal the forward model switches branch, so `ν` jumps from one tanh curve to the
    /// other and its direction need not match the strain's. The inverse picks its branch from
    /// the direction of `μ = ν` (Eq. 13), so for that one sample it may invert `ν` with the other
    /// branch and return `x'` with `f_other(x') = f_this(x)`. The error `|x' − x|` is the
    /// horizontal distance between the two curves at height `ν(x)`; this returns the larger of
    /// the two directions (clamped like the inverse, so it is finite):
    ///
    /// `gap(x) = max(|f_U⁻¹(f_L(x)) − x|, |f_L⁻¹(f_U(x)) − x|)`.
    ///
    /// After the reversal sample both branches agree again: within one branch `ν` moves with
    /// the strain (both branches increase), so the inverse picks the right branch.
    pub fn branch_gap(&self, x: f64) -> f64 {
        let up_then_down = self.unloading.inverse(self.loading.value(x)).0 - x;
        let down_then_up = self.loading.inverse(self.unloading.value(x)).0 - x;
        f64::max(up_then_down.abs(), down_then_up.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn input() -> TanhInput {
        TanhInput::new([30.0e3, 120.0, 0.1, 2.0e3], [28.0e3, 140.0, 0.3, 1.0e3]).unwrap()
    }

    #[test]
    fn branches_invert_each_other() {
        let nu = input();
        for loading in [true, false] {
            for x in [-0.01, -0.002, 0.0, 0.003, 0.009] {
                let (back, clamped) = nu.nu_inverse(nu.nu(x, loading), loading);
                assert!(!clamped);
                assert_relative_eq!(back, x, epsilon = 1e-12);
            }
        }
    }

    /// Eq. 10 by hand: a·tanh(b·x + c) + d.
    #[test]
    fn eq10_vectors() {
        let b = TanhBranch::new("loading_tanh", [2.0, 3.0, 0.5, -1.0]).unwrap();
        let table = [
            (0.0, 2.0 * 0.5f64.tanh() - 1.0),
            (1.0, 2.0 * 3.5f64.tanh() - 1.0),
        ];
        for (x, y) in table {
            assert_relative_eq!(b.value(x), y, epsilon = 1e-15);
        }
        let h = 1e-6;
        assert_relative_eq!(
            b.slope(0.2),
            (b.value(0.2 + h) - b.value(0.2 - h)) / (2.0 * h),
            max_relative = 1e-8
        );
        assert_eq!(b.value_and_slope(0.2), (b.value(0.2), b.slope(0.2)));
    }

    #[test]
    fn atanh_argument_is_clamped_and_flagged() {
        let b = TanhBranch::new("loading_tanh", [1.0, 1.0, 0.0, 0.0]).unwrap();
        let limit = libm::atanh(ATANH_BOUND);
        assert!(limit.is_finite() && limit < 10.72);
        for (mu, expected) in [(1.0, limit), (5.0, limit), (-1.0, -limit), (-1e300, -limit)] {
            let (x, clamped) = b.inverse(mu);
            assert!(clamped);
            assert_eq!(x, expected);
        }
        assert_eq!(b.inverse(0.5), (libm::atanh(0.5), false));
    }

    #[test]
    fn gap_is_zero_for_equal_branches_and_positive_otherwise() {
        let same = TanhInput::new([1.0, 2.0, 0.0, 0.5], [1.0, 2.0, 0.0, 0.5]).unwrap();
        assert_eq!(same.branch_gap(0.1), 0.0);
        let nu = input();
        let x = 0.004;
        let expected = (nu.unloading.inverse(nu.loading.value(x)).0 - x).abs();
        assert!(nu.branch_gap(x) >= expected && expected > 0.0);
    }

    #[test]
    fn refuses_decreasing_or_non_finite_branches() {
        assert_eq!(
            TanhBranch::new("loading_tanh", [-1.0, 1.0, 0.0, 0.0]),
            Err(EstimatorError::BranchNotIncreasing {
                name: "loading_tanh",
                slope: -1.0
            })
        );
        assert!(TanhInput::new([1.0, 1.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0]).is_err());
        assert!(TanhBranch::new("loading_tanh", [1.0, 1.0, f64::NAN, 0.0]).is_err());
    }
}
