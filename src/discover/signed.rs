//! Least squares with some coefficients held to one sign, by the project's non-negative least
//! squares ([`crate::fit::nnls`], Lawson & Hanson's active set on the normal equations) after
//! the free coefficients are eliminated: with `A = [F C]` (free, constrained), the constrained
//! ones minimize `‖P⊥(y − C·β_C)‖²`, `P⊥` the projection off `F`'s span, whose normal equations
//! are the Schur complement `G_CC − G_CF·G_FF⁺·G_FC`, `b_C − G_CF·G_FF⁺·b_F`; then
//! `β_F = G_FF⁺·(b_F − G_FC·β_C)`.
//!
//! It gives a relaxation with a spread of time constants ([`super::terms::Term::RelaxationSpread`])
//! the weights a generalized Maxwell solid has: each term's share of the elastic angle is at
//! least zero. Unconstrained, the slow lags of a 300 s recording are nearly collinear and their
//! weights alternate (0.87, −1.9, 3.6, −4.7, 3.0 on the third generator's relaxation, seed 3),
//! which predicts as well but is no relaxation a simulator can be given.

use nalgebra::{DMatrix, DVector};

use crate::fit::nnls;

/// How each coefficient is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sign {
    /// Any value.
    Free,
    /// At least zero.
    NonNegative,
    /// At most zero.
    NonPositive,
}

/// `argmin ‖x·β − y‖` with each `β_j` held as `signs[j]` says; `None` when the free
/// coefficients' subproblem has no finite solution. `signs` has one entry per column of `x`.
pub fn least_squares(x: &DMatrix<f64>, y: &DVector<f64>, signs: &[Sign]) -> Option<DVector<f64>> {
    let p = x.ncols();
    if signs.len() != p {
        return None;
    }
    // Flip the non-positive columns, so that every constrained coefficient is non-negative.
    let flip: Vec<f64> = signs
        .iter()
        .map(|s| if *s == Sign::NonPositive { -1.0 } else { 1.0 })
        .collect();
    let mut a = x.clone();
    for (j, f) in flip.iter().enumerate() {
        if *f < 0.0 {
            a.column_mut(j).neg_mut();
        }
    }
    let g = a.tr_mul(&a);
    let b = a.tr_mul(y);
    let free: Vec<usize> = (0..p).filter(|&j| signs[j] == Sign::Free).collect();
    let held: Vec<usize> = (0..p).filter(|&j| signs[j] != Sign::Free).collect();
    let sub = |rows: &[usize], cols: &[usize]| {
        DMatrix::from_fn(rows.len(), cols.len(), |r, c| g[(rows[r], cols[c])])
    };
    let part = |rows: &[usize]| DVector::from_fn(rows.len(), |r, _| b[rows[r]]);
    let (g_ff, g_fc, g_cc) = (sub(&free, &free), sub(&free, &held), sub(&held, &held));
    let (b_f, b_c) = (part(&free), part(&held));
    let g_ff_pinv = g_ff
        .clone()
        .pseudo_inverse(1e-13 * g_ff.amax().max(f64::MIN_POSITIVE))
        .ok()?;
    let beta_c = nnls(
        &(&g_cc - g_fc.transpose() * &g_ff_pinv * &g_fc),
        &(&b_c - g_fc.transpose() * &g_ff_pinv * &b_f),
    );
    let beta_f = &g_ff_pinv * (&b_f - &g_fc * &beta_c);
    let mut beta = DVector::zeros(p);
    for (k, &j) in free.iter().enumerate() {
        beta[j] = beta_f[k];
    }
    for (k, &j) in held.iter().enumerate() {
        beta[j] = beta_c[k] * flip[j];
    }
    beta.iter().all(|v| v.is_finite()).then_some(beta)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every coefficient free: the ordinary least-squares solution.
    #[test]
    fn with_no_constraint_it_is_least_squares() {
        let x = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0, 3.0]);
        let y = DVector::from_row_slice(&[1.0, 3.1, 4.9, 7.0]);
        let b = least_squares(&x, &y, &[Sign::Free, Sign::Free]).unwrap();
        let ols = x.clone().svd(true, true).solve(&y, 1e-12).unwrap();
        assert!((b - ols).norm() < 1e-10);
    }

    /// A coefficient whose free value has the wrong sign is held at zero, and the others are
    /// the least-squares solution without it; a coefficient with the right sign is untouched.
    #[test]
    fn a_wrong_signed_coefficient_is_held_at_zero() {
        // y = 1 + 2·a − 0.5·b exactly.
        let rows: Vec<[f64; 3]> = (0..20)
            .map(|i| {
                let t = f64::from(i);
                [1.0, (0.3 * t).sin(), (0.17 * t).cos() + 0.1 * t]
            })
            .collect();
        let x = DMatrix::from_fn(20, 3, |r, c| rows[r][c]);
        let y = DVector::from_iterator(20, rows.iter().map(|r| 1.0 + 2.0 * r[1] - 0.5 * r[2]));
        let held = least_squares(&x, &y, &[Sign::Free, Sign::Free, Sign::NonNegative]).unwrap();
        assert_eq!(held[2], 0.0);
        let without = x
            .columns(0, 2)
            .into_owned()
            .svd(true, true)
            .solve(&y, 1e-12)
            .unwrap();
        assert!((held.rows(0, 2) - without).norm() < 1e-9, "{held}");
        let right = least_squares(&x, &y, &[Sign::Free, Sign::Free, Sign::NonPositive]).unwrap();
        assert!((right[2] + 0.5).abs() < 1e-9, "{right}");
    }

    /// Random problems: the result satisfies its signs and the Karush-Kuhn-Tucker conditions
    /// (the gradient is zero on free and positive coefficients and points outward at zero).
    #[test]
    fn the_result_meets_the_optimality_conditions() {
        let mut state = 12345u64;
        let mut rand = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..50 {
            let x = DMatrix::from_fn(30, 6, |_, _| rand());
            let y = DVector::from_fn(30, |_, _| rand());
            let signs = [
                Sign::Free,
                Sign::NonNegative,
                Sign::NonPositive,
                Sign::NonNegative,
                Sign::NonNegative,
                Sign::Free,
            ];
            let b = least_squares(&x, &y, &signs).unwrap();
            let grad = x.tr_mul(&(&y - &x * &b));
            for (j, s) in signs.iter().enumerate() {
                match s {
                    Sign::Free => assert!(grad[j].abs() < 1e-9),
                    Sign::NonNegative => {
                        assert!(b[j] >= 0.0);
                        assert!(if b[j] > 0.0 {
                            grad[j].abs() < 1e-9
                        } else {
                            grad[j] < 1e-9
                        });
                    }
                    Sign::NonPositive => {
                        assert!(b[j] <= 0.0);
                        assert!(if b[j] < 0.0 {
                            grad[j].abs() < 1e-9
                        } else {
                            grad[j] > -1e-9
                        });
                    }
                }
            }
        }
    }
}
