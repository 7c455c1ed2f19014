//! Least squares with some coefficients held to one sign: Lawson & Hanson's active-set method
//! for non-negative least squares (*Solving Least Squares Problems*, 1974, ch. 23, algorithm
//! NNLS), with the unconstrained coefficients always in the passive set.
//!
//! It gives a relaxation with a spread of time constants ([`super::terms::Term::RelaxationSpread`])
//! the weights a generalized Maxwell solid has: each term's share of the elastic angle is at
//! least zero. Unconstrained, the slow lags of a 300 s recording are nearly collinear and their
//! weights alternate (0.87, −1.9, 3.6, −4.7, 3.0 on the third generator's relaxation, seed 3),
//! which predicts as well but is no relaxation a simulator can be given.
//!
//! The `nnls` crate was not used: it holds every coefficient non-negative (a model's offset and
//! gain are free) and works on `ndarray`, a second linear-algebra stack beside `nalgebra`.

use nalgebra::{DMatrix, DVector};

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

/// Most passes of the outer loop, per coefficient (Lawson & Hanson's bound is finite; this
/// only guards against a loop on rounding).
const PASSES_PER_COEFFICIENT: usize = 3;

/// `argmin ‖x·β − y‖` with each `β_j` held as `signs[j]` says; `None` when a subproblem has no
/// finite solution. `signs` has one entry per column of `x`.
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
    let gram = a.tr_mul(&a);
    let atb = a.tr_mul(y);
    let constrained: Vec<bool> = signs.iter().map(|s| *s != Sign::Free).collect();
    let scale = atb.amax().max(f64::MIN_POSITIVE);
    let mut passive: Vec<bool> = constrained.iter().map(|c| !c).collect();
    let mut z = solve_on(&gram, &atb, &passive)?;
    for _ in 0..PASSES_PER_COEFFICIENT * p.max(1) {
        // The negative gradient; a constrained coefficient at zero whose gradient points
        // inward joins the passive set.
        let w = &atb - &gram * &z;
        let entering = (0..p)
            .filter(|&j| constrained[j] && !passive[j])
            .max_by(|&i, &j| w[i].total_cmp(&w[j]))
            .filter(|&j| w[j] > 1e-12 * scale);
        let Some(j) = entering else { break };
        passive[j] = true;
        loop {
            let s = solve_on(&gram, &atb, &passive)?;
            let infeasible: Vec<usize> = (0..p)
                .filter(|&k| constrained[k] && passive[k] && s[k] <= 0.0)
                .collect();
            if infeasible.is_empty() {
                z = s;
                break;
            }
            let alpha = infeasible
                .iter()
                .map(|&k| z[k] / (z[k] - s[k]))
                .fold(f64::INFINITY, f64::min)
                .clamp(0.0, 1.0);
            z += (&s - &z) * alpha;
            for k in 0..p {
                if constrained[k] && passive[k] && z[k] <= 1e-15 * scale {
                    passive[k] = false;
                    z[k] = 0.0;
                }
            }
        }
    }
    let beta = DVector::from_iterator(p, z.iter().zip(&flip).map(|(b, f)| b * f));
    beta.iter().all(|b| b.is_finite()).then_some(beta)
}

/// The least-squares solution over the passive columns (from the normal equations), zero
/// elsewhere.
fn solve_on(gram: &DMatrix<f64>, atb: &DVector<f64>, passive: &[bool]) -> Option<DVector<f64>> {
    let idx: Vec<usize> = (0..passive.len()).filter(|&j| passive[j]).collect();
    let mut full = DVector::zeros(passive.len());
    if idx.is_empty() {
        return Some(full);
    }
    let g = DMatrix::from_fn(idx.len(), idx.len(), |r, c| gram[(idx[r], idx[c])]);
    let b = DVector::from_iterator(idx.len(), idx.iter().map(|&j| atb[j]));
    let svd = g.svd(true, true);
    let tol = 1e-13 * svd.singular_values.max();
    let s = svd.solve(&b, tol).ok()?;
    for (k, &j) in idx.iter().enumerate() {
        full[j] = s[k];
    }
    full.iter().all(|v| v.is_finite()).then_some(full)
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
