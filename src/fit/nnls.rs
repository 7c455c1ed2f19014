//! Non-negative least squares on the normal equations: `min ‖Aβ − y‖²` subject to `β ≥ 0`,
//! given `G = AᵀA` and `b = Aᵀy`, by Lawson and Hanson's active-set method (*Solving Least
//! Squares Problems*, 1974, ch. 23), with each passive-set subproblem solved by `nalgebra`'s
//! Cholesky factorization (its SVD where `G` restricted to the set is singular).
//!
//! Written here rather than taken from a crate: `nnls` 0.5 takes an `ndarray` matrix of every
//! sample (not the `N × N` Gram matrix the play fit already has) and panics on round-off in its
//! inner loop (`src/lib.rs:191`); `clarabel` solves the problem by an interior-point method
//! whose tolerance-level noise in `β` would enter the finite-difference Jacobian of the
//! projected residual. `docs/fit.md` has the comparison.

use nalgebra::{DMatrix, DVector};

/// Iterations of the outer loop allowed per unknown.
const ITERATIONS_PER_UNKNOWN: usize = 3;

/// The solution of `min ‖Aβ − y‖², β ≥ 0` from `g = AᵀA` and `b = Aᵀy`. Always finite: an
/// ill-posed subproblem falls back to the SVD's minimum-norm solution, and a non-finite one
/// leaves the set it would have added.
pub fn nnls(g: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = b.len();
    let mut x = DVector::<f64>::zeros(n);
    let mut passive = vec![false; n];
    // Columns whose entry changed nothing (numerically dependent on the passive set).
    let mut refused = vec![false; n];
    let scale = b.amax().max(f64::MIN_POSITIVE);
    let tol = 1e-12 * scale;
    for _ in 0..ITERATIONS_PER_UNKNOWN * n.max(1) {
        let w = b - g * &x;
        let Some(j) = (0..n)
            .filter(|&j| !passive[j] && !refused[j] && w[j] > tol)
            .max_by(|&i, &k| w[i].total_cmp(&w[k]))
        else {
            break;
        };
        passive[j] = true;
        let before = x.clone();
        for _ in 0..n + 1 {
            let Some(z) = solve_passive(g, b, &passive) else {
                passive[j] = false;
                break;
            };
            if (0..n).all(|i| !passive[i] || z[i] > 0.0) {
                x = z;
                break;
            }
            // Step from x toward z as far as the bounds allow, and drop what reached zero.
            let alpha = (0..n)
                .filter(|&i| passive[i] && z[i] <= 0.0)
                .map(|i| x[i] / (x[i] - z[i]))
                .fold(1.0f64, f64::min);
            x += (z - &x) * alpha;
            for i in 0..n {
                if passive[i] && x[i] <= tol * 1e-3 {
                    passive[i] = false;
                    x[i] = 0.0;
                }
            }
        }
        if !passive[j] && x == before {
            refused[j] = true;
        } else {
            refused.fill(false);
        }
    }
    x
}

/// The unconstrained least-squares solution on the passive set, zero elsewhere.
fn solve_passive(g: &DMatrix<f64>, b: &DVector<f64>, passive: &[bool]) -> Option<DVector<f64>> {
    let idx: Vec<usize> = (0..passive.len()).filter(|&i| passive[i]).collect();
    let gp = DMatrix::from_fn(idx.len(), idx.len(), |r, c| g[(idx[r], idx[c])]);
    let bp = DVector::from_fn(idx.len(), |r, _| b[idx[r]]);
    let zp = match gp.clone().cholesky() {
        Some(ch) => ch.solve(&bp),
        None => gp.svd(true, true).solve(&bp, 1e-12 * g.amax()).ok()?,
    };
    if !zp.iter().all(|v| v.is_finite()) {
        return None;
    }
    let mut z = DVector::zeros(passive.len());
    for (k, &i) in idx.iter().enumerate() {
        z[i] = zp[k];
    }
    Some(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn normal(a: &DMatrix<f64>, y: &DVector<f64>) -> (DMatrix<f64>, DVector<f64>) {
        (a.tr_mul(a), a.tr_mul(y))
    }

    /// The KKT conditions: β ≥ 0, the gradient `Aᵀ(y − Aβ)` is zero where β > 0 and not
    /// positive where β = 0.
    fn assert_kkt(g: &DMatrix<f64>, b: &DVector<f64>, x: &DVector<f64>) {
        let w = b - g * x;
        let scale = b.amax();
        for i in 0..x.len() {
            assert!(x[i] >= 0.0, "β[{i}] = {}", x[i]);
            if x[i] > 0.0 {
                assert!(
                    w[i].abs() <= 1e-8 * scale,
                    "β[{i}] > 0 but gradient {}",
                    w[i]
                );
            } else {
                assert!(w[i] <= 1e-8 * scale, "β[{i}] = 0 but gradient {}", w[i]);
            }
        }
    }

    #[test]
    fn an_interior_solution_is_the_least_squares_one() {
        let a = DMatrix::from_row_slice(4, 2, &[1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0]);
        let truth = DVector::from_vec(vec![2.0, 3.0]);
        let y = &a * &truth;
        let (g, b) = normal(&a, &y);
        let x = nnls(&g, &b);
        assert!((x - truth).amax() < 1e-10);
    }

    #[test]
    fn a_negative_least_squares_coefficient_is_held_at_zero() {
        // y = 2·a₀ − 1·a₁ exactly; with β ≥ 0 the best is β₁ = 0 and β₀ refitted alone.
        let a = DMatrix::from_row_slice(4, 2, &[1.0, 0.5, 2.0, 0.1, 3.0, 2.0, 4.0, 0.3]);
        let y = &a * DVector::from_vec(vec![2.0, -1.0]);
        let (g, b) = normal(&a, &y);
        let x = nnls(&g, &b);
        assert_eq!(x[1], 0.0);
        assert_kkt(&g, &b, &x);
    }

    #[test]
    fn random_problems_meet_the_kkt_conditions() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for _ in 0..200 {
            let a = DMatrix::from_fn(30, 6, |_, _| next());
            let y = DVector::from_fn(30, |_, _| next());
            let (g, b) = normal(&a, &y);
            assert_kkt(&g, &b, &nnls(&g, &b));
        }
    }

    #[test]
    fn dependent_columns_give_a_finite_answer() {
        let a = DMatrix::from_row_slice(3, 3, &[1.0, 1.0, 0.0, 2.0, 2.0, 1.0, 3.0, 3.0, 0.0]);
        let y = DVector::from_vec(vec![1.0, 2.0, 3.0]);
        let (g, b) = normal(&a, &y);
        let x = nnls(&g, &b);
        assert!(x.iter().all(|v| v.is_finite() && *v >= 0.0));
        assert!((&a * &x - y).norm() < 1e-9);
    }
}
