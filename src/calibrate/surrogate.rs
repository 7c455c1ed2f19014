//! The surrogate a calibration searches instead of the simulator: a design of experiments
//! (a Latin hypercube in the unit box), a ridge-regularized quadratic model per metric fitted
//! to the evaluations (`ln(value)` against `1, u_i, u_i²`), and the inverse problem solved on
//! the models by Levenberg-Marquardt (the `levenberg-marquardt` crate) from several starts.
//!
//! A quadratic in each parameter without cross terms is what the errors' physics suggests: an
//! RMSE is the root of a sum of variances, each growing with one effect's size, so `ln(RMSE)`
//! is smooth and nearly separable in the effects. The cross terms an evaluation shows (the PI
//! inverse amplifying noise near its ends) are left to the sequential rounds, which refit the
//! models with evaluations near the proposed point.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{storage::Owned, DMatrix, DVector, Dyn};

use crate::sim::Stream;

/// A Latin hypercube of `n` points in `[0, 1]^dim`, seeded: each coordinate's `n` strata are
/// each hit once, in a random order, at a random place inside the stratum.
pub fn latin_hypercube(n: usize, dim: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = Stream::new(seed, 0);
    let mut points = vec![vec![0.0; dim]; n];
    for d in 0..dim {
        let mut order: Vec<usize> = (0..n).collect();
        for i in (1..n).rev() {
            let j = ((rng.uniform() * (i + 1) as f64) as usize).min(i);
            order.swap(i, j);
        }
        for (point, stratum) in points.iter_mut().zip(order) {
            point[d] = (stratum as f64 + rng.uniform()) / n as f64;
        }
    }
    points
}

/// Ridge penalty on the models' coefficients, relative to the number of evaluations: enough to
/// keep a coefficient that the design does not determine near zero, small next to the fit.
const RIDGE: f64 = 1e-3;

/// `ln(metric)` as a quadratic in each parameter it depends on: `c₀ + Σ bᵢ·uᵢ + Σ aᵢ·uᵢ²`
/// over the parameters `i` of its mask; the others' coefficients are 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Quadratic {
    coefficients: DVector<f64>,
    mask: Vec<bool>,
}

/// The features `1, uᵢ, uᵢ²`, each 0 for a parameter outside `mask`.
fn features<'a>(u: &'a [f64], mask: &'a [bool]) -> impl Iterator<Item = f64> + 'a {
    let on = move |(x, m): (&f64, &bool)| if *m { *x } else { 0.0 };
    std::iter::once(1.0)
        .chain(u.iter().zip(mask).map(on))
        .chain(u.iter().zip(mask).map(on).map(|x| x * x))
}

impl Quadratic {
    /// Fits `ln(values)` at `points` by ridge regression with weights `weights`; points whose
    /// value is missing or not positive are left out. `None` with fewer points than parameters.
    pub fn fit(points: &[Vec<f64>], values: &[Option<f64>], weights: &[f64]) -> Option<Self> {
        let dim = points.first()?.len();
        Self::fit_on(points, values, weights, &vec![true; dim])
    }

    /// [`Quadratic::fit`] in the parameters of `mask` only: a metric that cannot depend on a
    /// parameter (another joint's) gets no coefficient for it, so the design's chance
    /// correlations cannot give it one. `None` with fewer points than parameters in the mask.
    pub fn fit_on(
        points: &[Vec<f64>],
        values: &[Option<f64>],
        weights: &[f64],
        mask: &[bool],
    ) -> Option<Self> {
        let dim = mask.len();
        let k = 1 + 2 * dim;
        let rows: Vec<(&Vec<f64>, f64, f64)> = points
            .iter()
            .zip(values)
            .zip(weights)
            .filter_map(|((p, v), w)| v.filter(|v| *v > 0.0).map(|v| (p, v.ln(), *w)))
            .collect();
        if rows.len() <= mask.iter().filter(|m| **m).count() {
            return None;
        }
        let mut a = DMatrix::<f64>::zeros(k, k);
        let mut b = DVector::<f64>::zeros(k);
        for (p, y, w) in &rows {
            let f: Vec<f64> = features(p, mask).collect();
            for i in 0..k {
                b[i] += w * f[i] * y;
                for j in 0..k {
                    a[(i, j)] += w * f[i] * f[j];
                }
            }
        }
        let total: f64 = rows.iter().map(|r| r.2).sum();
        for i in 1..k {
            a[(i, i)] += RIDGE * total;
        }
        let coefficients = a.cholesky()?.solve(&b);
        coefficients.iter().all(|c| c.is_finite()).then_some(Self {
            coefficients,
            mask: mask.to_vec(),
        })
    }

    /// The model's value (not its log) at `u`.
    pub fn predict(&self, u: &[f64]) -> f64 {
        features(u, &self.mask)
            .zip(self.coefficients.iter())
            .map(|(f, c)| f * c)
            .sum::<f64>()
            .exp()
    }

    /// `d ln(value)/du_i` at `u`.
    pub fn log_slope(&self, u: &[f64], i: usize) -> f64 {
        if !self.mask[i] {
            return 0.0;
        }
        let dim = u.len();
        self.coefficients[1 + i] + 2.0 * self.coefficients[1 + dim + i] * u[i]
    }
}

/// A least-squares problem in the unit box: `residuals(u)` with `u = (1 − cos z)/2`, so the
/// unconstrained `z` of Levenberg-Marquardt never leaves the box.
pub struct Boxed<'a> {
    residuals: &'a dyn Fn(&[f64]) -> Vec<f64>,
    z: DVector<f64>,
    r: DVector<f64>,
}

/// The box coordinate of `z`.
pub fn unit_of(z: f64) -> f64 {
    0.5 * (1.0 - z.cos())
}

/// A `z` for the box coordinate `u`.
pub fn z_of(u: f64) -> f64 {
    // Off the box's faces, where the cosine's slope is 0 and the search would stick.
    (1.0 - 2.0 * u.clamp(0.01, 0.99)).acos()
}

impl<'a> Boxed<'a> {
    fn new(residuals: &'a dyn Fn(&[f64]) -> Vec<f64>, start: &[f64]) -> Self {
        let z = DVector::from_iterator(start.len(), start.iter().map(|&u| z_of(u)));
        let mut me = Self {
            residuals,
            z: z.clone(),
            r: DVector::zeros(0),
        };
        me.set_params(&z);
        me
    }

    fn point(&self) -> Vec<f64> {
        self.z.iter().map(|&z| unit_of(z)).collect()
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Boxed<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, z: &DVector<f64>) {
        self.z = z.clone();
        let r = (self.residuals)(&self.point());
        self.r = DVector::from_vec(r);
    }

    fn params(&self) -> DVector<f64> {
        self.z.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.r.iter().all(|x| x.is_finite()).then(|| self.r.clone())
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let n = self.z.len();
        let mut jac = DMatrix::zeros(self.r.len(), n);
        for j in 0..n {
            let h = 1e-6;
            let mut z = self.z.clone();
            z[j] += h;
            let u: Vec<f64> = z.iter().map(|&z| unit_of(z)).collect();
            let up = (self.residuals)(&u);
            for (i, v) in up.iter().enumerate() {
                jac[(i, j)] = (v - self.r[i]) / h;
            }
        }
        jac.iter().all(|x| x.is_finite()).then_some(jac)
    }
}

/// Minimizes `Σ residuals(u)²` over the unit box from each start; returns the best point and
/// its sum of squares.
pub fn minimize(residuals: &dyn Fn(&[f64]) -> Vec<f64>, starts: &[Vec<f64>]) -> (Vec<f64>, f64) {
    let cost = |u: &[f64]| residuals(u).iter().map(|r| r * r).sum::<f64>();
    let mut best = (starts[0].clone(), cost(&starts[0]));
    for start in starts {
        let problem = Boxed::new(residuals, start);
        let (solved, _) = LevenbergMarquardt::new()
            .with_patience(200)
            .minimize(problem);
        let u = solved.point();
        let c = cost(&u);
        if c < best.1 {
            best = (u, c);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn a_latin_hypercube_hits_every_stratum_once() {
        let points = latin_hypercube(16, 3, 7);
        for d in 0..3 {
            let mut strata: Vec<usize> = points.iter().map(|p| (p[d] * 16.0) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..16).collect::<Vec<_>>());
        }
        assert_eq!(points, latin_hypercube(16, 3, 7));
    }

    /// A metric of one parameter, fitted on a small design where a second parameter happens to
    /// track it: the unmasked fit gives the second a slope, the masked one none, and still
    /// recovers the first.
    #[test]
    fn a_masked_parameter_gets_no_slope_from_a_chance_correlation() {
        let points: Vec<Vec<f64>> = (0..8)
            .map(|i| {
                let x = f64::from(i) / 7.0;
                vec![x, (x + 0.05 * (f64::from(i) * 2.3).sin()).clamp(0.0, 1.0)]
            })
            .collect();
        let values: Vec<Option<f64>> = points.iter().map(|p| Some((0.3 + p[0]).exp())).collect();
        let weights = vec![1.0; points.len()];
        let open = Quadratic::fit(&points, &values, &weights).unwrap();
        let masked = Quadratic::fit_on(&points, &values, &weights, &[true, false]).unwrap();
        let u = [0.5, 0.5];
        assert!(
            open.log_slope(&u, 1).abs() > 0.05,
            "{}",
            open.log_slope(&u, 1)
        );
        assert_eq!(masked.log_slope(&u, 1), 0.0);
        assert_relative_eq!(masked.log_slope(&u, 0), 1.0, epsilon = 0.05);
        assert_relative_eq!(
            masked.predict(&[0.2, 0.9]),
            0.5f64.exp(),
            max_relative = 0.02
        );
    }

    /// A metric that is exactly `exp(quadratic)` is recovered, and the boxed minimizer finds a
    /// target value inside the box, and stops at the face when the target lies beyond it.
    #[test]
    fn the_quadratic_and_the_boxed_minimizer_recover_a_known_model() {
        let truth = |u: &[f64]| (0.5 + 1.2 * u[0] - 0.4 * u[1] * u[1]).exp();
        let points = latin_hypercube(30, 2, 1);
        let values: Vec<Option<f64>> = points.iter().map(|p| Some(truth(p))).collect();
        let q = Quadratic::fit(&points, &values, &vec![1.0; 30]).unwrap();
        for u in [[0.1, 0.9], [0.7, 0.3]] {
            assert_relative_eq!(q.predict(&u), truth(&u), max_relative = 0.02);
        }
        let target = truth(&[0.6, 0.5]);
        let f = |u: &[f64]| vec![(q.predict(u) / target).ln(), 0.01 * (u[1] - 0.5)];
        let (u, _) = minimize(&f, &[vec![0.2, 0.2]]);
        assert_relative_eq!(u[0], 0.6, epsilon = 0.03);
        let beyond = |u: &[f64]| vec![(q.predict(u) / (target * 10.0)).ln()];
        let (u, _) = minimize(&beyond, &[vec![0.2, 0.2]]);
        assert!(u[0] > 0.98, "{u:?}");
    }
}
