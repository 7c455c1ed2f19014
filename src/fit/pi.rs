//! Fitting the PI models (Section IV-A1) by Levenberg-Marquardt.
//!
//! The paper's procedure, with the departures `docs/fit.md` explains:
//!
//! 1. the characteristic points `R_c`, `m_c`, `ε_c`, `R_peak`, `ε_peak` ([`characteristic`]);
//! 2. the initial tanh curves of Eq. 15: `a₁ = a₅ = R_peak − R_c`, `a₃ = a₄ = a₇ = a₈ = 0` and
//!    `a₂ = a₆ = k·m_c/a₁` (the paper's `k = ½`; restarts also try `k = 1` and `k = 2`);
//! 3. `N` radii evenly spaced over `[0, ρ_max]`, where `ρ_max` is half the span of the initial
//!    input over the recording: a play whose radius exceeds half its input's span never moves
//!    after its first excursion;
//! 4. initial weights by linear least squares (the model is linear in the weights once the
//!    curves and radii are fixed), then normalized to `P₁ = 1`. Eq. 15's `P⁽⁰⁾ᵢ = (R_peak −
//!    R_c)/N` would multiply the span `a₁` by `a₁` again;
//! 5. Levenberg-Marquardt (the `levenberg-marquardt` crate) on all of `θ` (see
//!    [`super::plays`]) with the analytic Jacobian; the restart with the lowest residual wins;
//! 6. one more start that is the least-squares line itself ([`Start::Linear`]): a tanh so wide
//!    that it is straight over the recording, and one play. Levenberg-Marquardt never accepts
//!    a step that raises the residual, so the PI fit is never worse than the linear fit on the
//!    samples it was fitted to, even where the tanh starts fall into a poor local minimum
//!    (Joint C's nearly linear sensors: 60.6 Ω from the best tanh start, 31.6 Ω linear).
//!
//! [`characteristic`]: super::characteristic::characteristic

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::characteristic::Characteristic;
use super::plays::{PlayKind, PlayModel, Unpacked};
use super::FitError;

/// Multipliers `k` of the initial slope `a₂ = k·m_c/a₁` tried, the paper's first.
pub const SLOPE_RESTARTS: [f64; 3] = [0.5, 1.0, 2.0];

/// Evaluations each restart may spend, per parameter plus one (the crate's `patience`). A
/// restart that runs out keeps the lowest residual it reached and competes with the others, so
/// more patience buys only the last digits: on the characterizations of Joints A, B and D the
/// PI RMSE is the same to 0.1 Ω at 100 as at 500, in a fifth of the time (README tour's Joint
/// D fit: 89.8 s → 18.4 s for PI and continuous PI together).
pub const PATIENCE: usize = 100;

/// The optimizer stops when a step reduces the sum of squares by less than this fraction…
pub const FTOL: f64 = 1e-9;
/// …or moves the parameters by less than this fraction of their size…
pub const XTOL: f64 = 1e-9;
/// …or the residuals are this close to orthogonal to the Jacobian's columns.
pub const GTOL: f64 = 1e-12;

/// Where a restart began.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// Eq. 15's tanh curves with the initial slope `a₂ = k·m_c/a₁`.
    Slope(f64),
    /// The least-squares line: a tanh straight over the recording and one play.
    Linear,
}

impl std::fmt::Display for Start {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Slope(k) => write!(f, "k = {k}"),
            Self::Linear => f.write_str("linear"),
        }
    }
}

/// What one restart reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restart {
    /// Where it began.
    pub start: Start,
    /// RMS of the residuals where it stopped (Ω).
    pub rmse_ohm: f64,
    /// Whether the optimizer reported convergence.
    pub converged: bool,
}

/// How far into its saturation the linear start's tanh reaches at the recording's largest
/// `|ε − ε_c|`: `tanh(0.05)` departs from a line by 0.08 %.
const LINEAR_START_REACH: f64 = 0.05;

/// A fitted play model.
#[derive(Debug, Clone, PartialEq)]
pub struct PlayFit {
    /// The model with its radii and centre.
    pub model: PlayModel,
    /// The fitted parameter vector.
    pub theta: Vec<f64>,
    /// Branches and weights.
    pub values: Unpacked,
    /// Initial play state `M₀` (units of the input).
    pub initial_state: f64,
    /// RMS of `R_model − R` over the fitted samples (Ω).
    pub rmse_ohm: f64,
    /// What each restart reached.
    pub restarts: Vec<Restart>,
    /// Residual evaluations over all restarts.
    pub evaluations: usize,
}

impl PlayFit {
    /// The fitted model's resistance over `strain` (Ω), from relaxed plays.
    pub fn predict(&self, strain: &[f64]) -> Vec<f64> {
        let mut ohm = vec![0.0; strain.len()];
        self.model.evaluate(&self.theta, strain, &mut ohm, None);
        ohm
    }
}

/// Fits a PI model of `kind` with `order` plays to `(strain, ohm)`.
///
/// # Errors
/// [`FitError::NotConverged`] when no restart reaches finite parameters (none does on a
/// recording that passed the observations' checks: the linear start is the line itself).
pub fn fit_plays(
    kind: PlayKind,
    order: usize,
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
) -> Result<PlayFit, FitError> {
    // Eq. 15's a₁ = R_peak − R_c assumes R_c near the bottom of the loop. A BSN compression
    // sensor (plane −y_s) rests at its largest strain, so its first loading phase ends at rest
    // and R_c can sit near the top: take the larger side of the loop around R_c.
    let low = ohm.iter().copied().fold(f64::INFINITY, f64::min);
    let span = (points.peak_ohm - points.center_ohm).max(points.center_ohm - low);
    if !(span > 0.0 && points.center_slope_ohm > 0.0) {
        return Err(FitError::NotIncreasing {
            slope_ohm_per_strain: points.center_slope_ohm,
            r2: 0.0,
            min_r2: 0.0,
        });
    }
    let mut best: Option<PlayFit> = None;
    let mut restarts = Vec::new();
    let mut evaluations = 0;
    let mut last_reason = String::from("no restart ran");
    let starts: Vec<Start> = SLOPE_RESTARTS
        .into_iter()
        .map(Start::Slope)
        .chain([Start::Linear])
        .collect();
    // The restarts are independent: each runs on its own thread, and the results are taken in
    // the order of `starts`, so the outcome does not depend on the scheduling.
    let runs: Vec<Run> = std::thread::scope(|scope| {
        let handles: Vec<_> = starts
            .iter()
            .map(|&start| {
                scope.spawn(move || run_start(kind, order, start, span, strain, ohm, points))
            })
            .collect();
        handles
            .into_iter()
            .zip(&starts)
            .map(|(h, &start)| {
                h.join().unwrap_or_else(|_| Run::Failed {
                    start,
                    reason: "the restart's thread panicked".into(),
                })
            })
            .collect()
    });
    for run in runs {
        match run {
            Run::Failed { start, reason } => {
                last_reason = format!("{start}: {reason}");
            }
            Run::Done {
                start,
                model,
                theta,
                rmse,
                converged,
                evaluations: used,
                reason,
            } => {
                evaluations += used;
                restarts.push(Restart {
                    start,
                    rmse_ohm: rmse,
                    converged,
                });
                // A restart that ran out of patience still holds the lowest residual it
                // reached (Levenberg-Marquardt never accepts a step that raises it), so it
                // competes like the others: the linear start's result is then never worse
                // than the line, and a valid recording never ends in "did not converge".
                if !(rmse.is_finite() && theta.iter().all(|v| v.is_finite())) {
                    last_reason = reason;
                    continue;
                }
                if best.as_ref().map_or(true, |b| rmse < b.rmse_ohm) {
                    let values = model.unpack(&theta);
                    let x0 = strain[0] - model.center_strain;
                    let l = values.loading;
                    best = Some(PlayFit {
                        initial_state: l[0] * (l[1] * x0 + l[2]).tanh() + l[3],
                        values,
                        theta,
                        model,
                        rmse_ohm: rmse,
                        restarts: Vec::new(),
                        evaluations: 0,
                    });
                }
            }
        }
    }
    let mut fit = best.ok_or(FitError::NotConverged {
        model: match kind {
            PlayKind::Generalized => "pi",
            PlayKind::Continuous => "continuous-pi",
        },
        reason: last_reason,
    })?;
    fit.restarts = restarts;
    fit.evaluations = evaluations;
    Ok(fit)
}

/// What one restart ended with.
enum Run {
    /// No finite starting point.
    Failed { start: Start, reason: String },
    /// Levenberg-Marquardt ran.
    Done {
        start: Start,
        model: PlayModel,
        theta: Vec<f64>,
        rmse: f64,
        converged: bool,
        evaluations: usize,
        reason: String,
    },
}

/// One restart from `start`: the initial model and `θ`, then Levenberg-Marquardt.
fn run_start(
    kind: PlayKind,
    order: usize,
    start: Start,
    span: f64,
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
) -> Run {
    let initial = match start {
        Start::Slope(k) => {
            let a = [span, k * points.center_slope_ohm / span, 0.0, 0.0];
            initial(kind, order, a, strain, ohm, points)
        }
        Start::Linear => linear_start(kind, order, strain, ohm, points),
    };
    let Some((model, theta0)) = initial else {
        return Run::Failed {
            start,
            reason: "the initial parameters are not finite".into(),
        };
    };
    let problem = Problem::new(&model, strain, ohm, theta0);
    let (problem, report) = LevenbergMarquardt::new()
        .with_ftol(FTOL)
        .with_xtol(XTOL)
        .with_gtol(GTOL)
        .with_patience(PATIENCE)
        .minimize(problem);
    let converged = report.termination.was_successful()
        || matches!(
            report.termination,
            TerminationReason::NoImprovementPossible(_)
        );
    Run::Done {
        start,
        rmse: problem.rmse(),
        theta: problem.theta.iter().copied().collect(),
        model,
        converged,
        evaluations: report.number_of_evaluations,
        reason: format!("{:?}", report.termination),
    }
}

/// The model and starting `θ` of [`Start::Linear`]: the least-squares line `R = c₀ + c₁·ε` as
/// one play on a tanh whose argument stays within ±[`LINEAR_START_REACH`], the other weights
/// zero, the radii over half the line's span. `None` when the line does not rise.
fn linear_start(
    kind: PlayKind,
    order: usize,
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
) -> Option<(PlayModel, Vec<f64>)> {
    let n = strain.len() as f64;
    let (mean_e, mean_r) = (strain.iter().sum::<f64>() / n, ohm.iter().sum::<f64>() / n);
    let slope = super::linear::slope(strain, ohm).unwrap_or(f64::NAN);
    let reach = strain
        .iter()
        .map(|e| (e - points.center_strain).abs())
        .fold(0.0, f64::max);
    if !(slope > 0.0 && reach > 0.0) {
        return None;
    }
    let a2 = LINEAR_START_REACH / reach;
    let a1 = slope / a2;
    let a4 = mean_r + slope * (points.center_strain - mean_e) - points.center_ohm;
    let a = [a1, a2, 0.0, a4];
    let (lo, hi) = super::min_max(strain);
    let rho_max = 0.5 * slope * (hi - lo);
    let model = PlayModel {
        kind,
        radii: (0..order)
            .map(|i| rho_max * i as f64 / (order - 1).max(1) as f64)
            .collect(),
        center_strain: points.center_strain,
        center_ohm: points.center_ohm,
    };
    let mut weights = vec![0.0; order];
    weights[0] = 1.0;
    let theta = model.pack(a, a, &weights);
    theta
        .iter()
        .all(|v| v.is_finite())
        .then_some((model, theta))
}

/// The model and starting `θ` for initial curves `a` (both branches alike): radii over half
/// the input's span, weights by linear least squares normalized to `P₁ = 1`.
fn initial(
    kind: PlayKind,
    order: usize,
    a: [f64; 4],
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
) -> Option<(PlayModel, Vec<f64>)> {
    let input = |e: f64| a[0] * (a[1] * (e - points.center_strain) + a[2]).tanh() + a[3];
    let (lo, hi) = strain
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &e| {
            (lo.min(input(e)), hi.max(input(e)))
        });
    let rho_max = 0.5 * (hi - lo);
    let radii: Vec<f64> = (0..order)
        .map(|i| rho_max * i as f64 / (order - 1).max(1) as f64)
        .collect();
    let model = PlayModel {
        kind,
        radii,
        center_strain: points.center_strain,
        center_ohm: points.center_ohm,
    };
    // The plays' outputs with unit weights, one column each, and a constant.
    let n = strain.len();
    let mut columns = DMatrix::<f64>::zeros(n, order + 1);
    for i in 0..order {
        let mut w = vec![0.0; order];
        w[i] = 1.0;
        let probe = PlayModel {
            kind: PlayKind::Continuous,
            ..model.clone()
        };
        // Unit weight on play i only: evaluate through the continuous parametrization, whose
        // weights are free, with both curves equal (for the generalized model the direction
        // switch changes nothing while the branches are equal).
        let mut theta = probe.pack(a, a, &[1.0; 1]);
        theta.truncate(super::plays::BRANCH_PARAMS);
        let single = PlayModel {
            radii: vec![model.radii[i]],
            ..probe
        };
        let mut col = vec![0.0; n];
        single.evaluate(&theta, strain, &mut col, None);
        for t in 0..n {
            columns[(t, i)] = col[t] - model.center_ohm;
        }
    }
    for t in 0..n {
        columns[(t, order)] = 1.0;
    }
    let target = DVector::from_iterator(n, ohm.iter().map(|r| r - points.center_ohm));
    let solution = columns.svd(true, true).solve(&target, 1e-12).ok()?;
    let mut weights: Vec<f64> = solution.iter().take(order).copied().collect();
    let offset = solution[order];
    let mut p1 = weights[0];
    if !(p1 > 0.0) || !weights.iter().all(|w| w.is_finite()) {
        // The least-squares weights do not start with a rising play: start flat instead.
        weights = vec![1.0 / order as f64; order];
        p1 = weights[0];
    }
    // Normalize to P₁ = 1: scale amplitudes, offsets and radii by p1.
    let total: f64 = weights.iter().sum::<f64>() / p1;
    let shift = if total > 0.0 { offset / total } else { 0.0 };
    let scaled = [a[0] * p1, a[1], a[2], a[3] * p1 + shift];
    for w in &mut weights {
        *w /= p1;
    }
    let model = PlayModel {
        radii: model.radii.iter().map(|r| r * p1).collect(),
        ..model
    };
    let theta = model.pack(scaled, scaled, &weights);
    theta
        .iter()
        .all(|v| v.is_finite())
        .then_some((model, theta))
}

/// The least-squares problem the optimizer sees: residuals `R_model − R` and their Jacobian,
/// both computed once per parameter update.
pub struct Problem<'a> {
    model: &'a PlayModel,
    strain: &'a [f64],
    ohm: &'a [f64],
    theta: DVector<f64>,
    residuals: DVector<f64>,
    jacobian: DMatrix<f64>,
}

impl<'a> Problem<'a> {
    /// The problem at `theta`.
    pub fn new(model: &'a PlayModel, strain: &'a [f64], ohm: &'a [f64], theta: Vec<f64>) -> Self {
        let n = strain.len();
        let mut p = Self {
            model,
            strain,
            ohm,
            theta: DVector::from_vec(theta),
            residuals: DVector::zeros(n),
            jacobian: DMatrix::zeros(n, model.parameter_count()),
        };
        p.update();
        p
    }

    fn update(&mut self) {
        let theta: Vec<f64> = self.theta.iter().copied().collect();
        let out = self.residuals.as_mut_slice();
        self.model
            .evaluate(&theta, self.strain, out, Some(&mut self.jacobian));
        for (r, y) in out.iter_mut().zip(self.ohm) {
            *r -= y;
        }
    }

    /// RMS of the residuals (Ω).
    pub fn rmse(&self) -> f64 {
        (self.residuals.norm_squared() / self.residuals.len().max(1) as f64).sqrt()
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, theta: &DVector<f64>) {
        self.theta.copy_from(theta);
        self.update();
    }

    fn params(&self) -> DVector<f64> {
        self.theta.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals
            .iter()
            .all(|r| r.is_finite())
            .then(|| self.residuals.clone())
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.jacobian
            .iter()
            .all(|j| j.is_finite())
            .then(|| self.jacobian.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use levenberg_marquardt::differentiate_numerically;

    /// Loops of unequal amplitude on a slow drift: no two samples repeat a value exactly (an
    /// exact tie sits on a kink of the plays, where no derivative exists).
    fn strain(samples: usize) -> Vec<f64> {
        (0..samples)
            .map(|i| {
                let t = i as f64 * 24.8 / samples as f64;
                0.0062 + 0.0061 * (t * 1.31).sin() * (0.7 + 0.3 * (t * 0.29).cos()) + 1e-6 * t
            })
            .collect()
    }

    fn problem_at(kind: PlayKind) -> (PlayModel, Vec<f64>) {
        let model = PlayModel {
            kind,
            radii: (0..5).map(|i| i as f64 * 3e3).collect(),
            center_strain: 0.004,
            center_ohm: 224e3,
        };
        let theta = model.pack(
            [26e3, 190.0, 0.1, 300.0],
            [24e3, 230.0, -0.05, -200.0],
            &[1.0, 0.3, -0.1, 0.2, 0.15],
        );
        (model, theta)
    }

    fn assert_close(analytic: &DMatrix<f64>, numerical: &DMatrix<f64>, tol: f64, kind: PlayKind) {
        for c in 0..analytic.ncols() {
            for r in 0..analytic.nrows() {
                let (a, b) = (analytic[(r, c)], numerical[(r, c)]);
                assert!(
                    (a - b).abs() <= tol * (1.0 + b.abs()),
                    "{kind:?} row {r} column {c}: analytic {a}, numerical {b}"
                );
            }
        }
        // The check can fail: one wrong column is caught.
        let mut wrong = analytic.clone();
        wrong.column_mut(3).scale_mut(1.01);
        assert!(wrong
            .iter()
            .zip(numerical.iter())
            .any(|(a, b)| (a - b).abs() > tol * (1.0 + b.abs())));
    }

    /// The problem in units of `θ/SCALE`: levenberg-marquardt's adaptive differences start from
    /// a step of 1 in each parameter, wide enough to straddle the plays' kinks, where the
    /// model has no derivative. In these units they step by at most `SCALE` in `θ`.
    struct Scaled<'a>(Problem<'a>);
    const SCALE: f64 = 1e-4;

    impl LeastSquaresProblem<f64, Dyn, Dyn> for Scaled<'_> {
        type ResidualStorage = Owned<f64, Dyn>;
        type JacobianStorage = Owned<f64, Dyn, Dyn>;
        type ParameterStorage = Owned<f64, Dyn>;
        fn set_params(&mut self, x: &DVector<f64>) {
            self.0.set_params(&(x * SCALE));
        }
        fn params(&self) -> DVector<f64> {
            self.0.params() / SCALE
        }
        fn residuals(&self) -> Option<DVector<f64>> {
            self.0.residuals()
        }
        fn jacobian(&self) -> Option<DMatrix<f64>> {
            self.0.jacobian().map(|j| j * SCALE)
        }
    }

    /// The analytic Jacobian against levenberg-marquardt's `differentiate_numerically`, for
    /// both models, at a point with negative weights, offsets and active plays of every radius.
    #[test]
    fn analytic_jacobian_matches_the_crates_numerical_differentiation() {
        let e = strain(150);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let (model, theta) = problem_at(kind);
            let ohm = vec![224e3; e.len()];
            let mut problem = Scaled(Problem::new(&model, &e, &ohm, theta));
            let numerical = differentiate_numerically(&mut problem).unwrap() / SCALE;
            let analytic = problem.jacobian().unwrap() / SCALE;
            assert_close(&analytic, &numerical, 1e-4, kind);
        }
    }

    /// Central differences with a step of 1e-6 (relative) on a record of 2000 samples.
    #[test]
    fn analytic_jacobian_matches_central_differences_on_a_long_record() {
        let e = strain(2000);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let (model, theta) = problem_at(kind);
            let mut analytic = DMatrix::zeros(e.len(), theta.len());
            let mut r = vec![0.0; e.len()];
            model.evaluate(&theta, &e, &mut r, Some(&mut analytic));
            let mut numerical = DMatrix::zeros(e.len(), theta.len());
            for c in 0..theta.len() {
                let h = 1e-6 * theta[c].abs().max(1.0);
                let (mut up, mut down) = (theta.clone(), theta.clone());
                up[c] += h;
                down[c] -= h;
                let (mut ru, mut rd) = (vec![0.0; e.len()], vec![0.0; e.len()]);
                model.evaluate(&up, &e, &mut ru, None);
                model.evaluate(&down, &e, &mut rd, None);
                for t in 0..e.len() {
                    numerical[(t, c)] = (ru[t] - rd[t]) / (2.0 * h);
                }
            }
            assert_close(&analytic, &numerical, 1e-3, kind);
        }
    }

    /// The linear start reproduces the least-squares line, so no PI fit ends worse than the
    /// line on the samples it was fitted to, whatever the tanh starts do.
    #[test]
    fn the_linear_start_is_the_least_squares_line_and_bounds_the_fit() {
        let e = strain(600);
        // A line with a small quadratic bend and deterministic scatter of ±40 Ω.
        let mut seed = 12345u64;
        let ohm: Vec<f64> = e
            .iter()
            .map(|&x| {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                74e3 * (1.0 + 1.28 * x) + 2e6 * x * x + 80.0 * u
            })
            .collect();
        let n = e.len() as f64;
        let (me, mr) = (e.iter().sum::<f64>() / n, ohm.iter().sum::<f64>() / n);
        let see: f64 = e.iter().map(|x| (x - me) * (x - me)).sum();
        let ser: f64 = e.iter().zip(&ohm).map(|(x, r)| (x - me) * (r - mr)).sum();
        let slope = ser / see;
        let line_rmse = (e
            .iter()
            .zip(&ohm)
            .map(|(x, r)| (mr + slope * (x - me) - r).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        let points = Characteristic {
            center_strain: 0.006,
            center_ohm: 74e3 * (1.0 + 1.28 * 0.006),
            center_slope_ohm: slope,
            peak_ohm: ohm.iter().copied().fold(f64::MIN, f64::max),
            peak_strain: 0.0123,
        };
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let (model, theta) = linear_start(kind, 10, &e, &ohm, &points).unwrap();
            let start = Problem::new(&model, &e, &ohm, theta).rmse();
            assert!(
                (start - line_rmse).abs() < 0.01 * line_rmse,
                "{kind:?}: linear start {start} Ω, line {line_rmse} Ω"
            );
            let fit = fit_plays(kind, 10, &e, &ohm, &points).unwrap();
            assert!(fit.restarts.iter().any(|r| r.start == Start::Linear));
            assert!(
                fit.rmse_ohm <= start * (1.0 + 1e-9),
                "{kind:?}: fit {} Ω, linear start {start} Ω",
                fit.rmse_ohm
            );
        }
    }
}
