//! Fitting the PI models (Section IV-A1) by variable projection.
//!
//! Once the tanh curves and the radii are fixed, both play models are linear in their weights
//! `Pᵢ` and in a constant: the plays' outputs are columns of a matrix and the weights solve a
//! constrained linear least-squares problem ([`super::nnls`]). What is left to search is
//! seven constants, the [`Shape`]: the loading tanh's slope and offset, the unloading tanh's
//! amplitude ratio, slope, offset and shift, and the largest radius `ρ_max`. `docs/fit.md`
//! has the derivation; the steps:
//!
//! 1. the characteristic points `R_c`, `m_c`, `ε_c`, `R_peak` ([`characteristic`]);
//! 2. a grid of Eq. 15 shapes: the slope `a₂ = k·m_c/a₁` with `a₁ = R_peak − R_c` for each
//!    `k` of [`SLOPE_RESTARTS`] (the paper's `k = ½` among them), times `ρ_max` as each share
//!    of [`RADIUS_SHARES`] of half the input's span; the [`GRID_STARTS`] best, with different
//!    radii, start a search. Eq. 15's `P⁽⁰⁾ᵢ = (R_peak − R_c)/N` would multiply the span `a₁`
//!    by `a₁` again; here no weight is guessed: the projection solves them;
//! 3. one more start, [`Start::Linear`]: tanh curves so shallow that they are straight over
//!    the recording. With the weight on `ρ₁ = 0` alone the model is then the least-squares
//!    line, and that weight vector is feasible, so the projection at this shape is never worse
//!    than the line;
//! 4. from each start, a coordinate scan (a dense one over `ln ρ_max`, where the residual has
//!    many shallow minima) alternating with Levenberg-Marquardt (the `levenberg-marquardt`
//!    crate) on the projected residual, with a forward-difference Jacobian; on at most
//!    [`COARSE_SAMPLES`] samples;
//! 5. the best start on every sample, refined once more there. No step is ever taken that
//!    raises the residual, so the fit is never worse than the linear start, hence than the line.
//!
//! The largest radius never exceeds half the span of the plays' input over the recording
//! (`Projection::half_span`): every play then moves in every full loop, so every weight is
//! fitted to what the whole recording shows, not to its first rise.
//!
//! Constraints: generalized PI keeps `P₁ > 0` and every partial sum `Sᵢ ≥ 1.5·m·P₁`
//! ([`PARTIAL_SUM_MARGIN`] `m`), so the inverse of Eq. 13 exists; continuous PI keeps every
//! `Pᵢ ≥ 10⁻⁴·P₁ > 0`. Both become `β ≥ 0` on re-parametrized columns.
//!
//! [`characteristic`]: super::characteristic::characteristic

use std::sync::atomic::{AtomicUsize, Ordering};

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::characteristic::Characteristic;
use super::nnls::nnls;
use super::plays::{PlayKind, PlayModel, Unpacked, CONTINUOUS_WEIGHT_FLOOR, PARTIAL_SUM_MARGIN};
use super::FitError;

/// Multipliers `k` of Eq. 15's initial slope `a₂ = k·m_c/a₁` on the start grid.
pub const SLOPE_RESTARTS: [f64; 5] = [0.25, 0.5, 1.0, 2.0, 4.0];

/// Shares of half the initial input's span tried as `ρ_max` on the start grid.
pub const RADIUS_SHARES: [f64; 5] = [0.1, 0.2, 0.35, 0.6, 1.0];

/// Grid shapes that start a search, besides the linear start.
pub const GRID_STARTS: usize = 2;

/// Rounds of hops at most: another round runs only from a hop that lowered the mean square
/// residual by at least [`HOP_IMPROVEMENT`] of itself.
pub const HOP_ROUNDS: usize = 4;
/// See [`HOP_ROUNDS`].
pub const HOP_IMPROVEMENT: f64 = 0.01;

/// Rounds of scan and search of the best shape on every sample, at most.
pub const FULL_REFINEMENTS: usize = 1;

/// Changes of the shift `(a₈ − a₄)/a₁` from the best start's shape, each searched again.
pub const SHIFT_HOPS: [f64; 2] = [-0.04, 0.04];

/// Rounds of scan and search from each start, at most.
pub const REFINEMENTS: usize = 4;

/// The starts are searched on every `k`-th sample, `k` the least that leaves at most this many;
/// the winner is refined on all.
pub const COARSE_SAMPLES: usize = 3000;

/// The linear start's tanh argument at the recording's largest `|ε − ε_c|`: `tanh(10⁻³)`
/// departs from a line by 3·10⁻⁷ of its span.
pub const LINEAR_START_REACH: f64 = 1e-3;

/// The least first weight `P₁`, as the share of the target's spread the first play's output
/// then carries.
///
/// Right after a reversal only the first play moves, so `P₁` sets the model's least slope and
/// the inverse's greatest gain. With a share of 10⁻³ (it only had to keep `P₁ > 0` for the
/// runtime's `P₁ = 1` normalization) the half-size reproduction fitted Joint D's N = 3 model
/// with weights 1 : 454 : 67: after every reversal the inverse read the voltage's noise with
/// about 500 times its mean gain, and the closed loop followed the jumps (12.8° against 3.7°
/// in open loop). At a tenth, the inverse's gain after a reversal stays within about ten times
/// its mean; the full-size fits of Joints A-D do not reach the floor, and are unchanged.
pub const FIRST_WEIGHT_SHARE: f64 = 0.1;

/// A round that lowers the mean square residual by less than this fraction (the RMSE by less
/// than half of it) ends the search.
const IMPROVEMENT: f64 = 1e-4;
/// Levenberg-Marquardt's evaluations per round, per shape constant plus one.
const PATIENCE: usize = 12;
/// The dense scan of `ln ρ_max`: this spacing, this many steps each way.
const RADIUS_SCAN_SPACING: f64 = 0.1;
const RADIUS_SCAN_STEPS: i32 = 20;
/// Where the shift sits in a [`Shape`].
const SHIFT: usize = 5;
/// Step sizes of the other constants' scans, coarse to fine.
const COORDINATE_STEPS: [f64; 3] = [0.3, 0.05, 0.01];

/// The box the shape stays in: the tanh argument at the largest `|ε − ε_c|` …
pub const TANH_REACH: (f64, f64) = (1e-5, 200.0);
/// … its offset `|a₃|, |a₇|` …
pub const MAX_TANH_OFFSET: f64 = 3.0;
/// … `|ln(a₅/a₁)|` …
pub const MAX_LOG_RATIO: f64 = 5.0;
/// … `|a₈ − a₄|/a₁` …
pub const MAX_OFFSET_RATIO: f64 = 10.0;
/// … and `ln(ρ_max/a₁)`.
pub const LOG_RADIUS: (f64, f64) = (-12.0, 3.0);

/// Constants of a shape.
const SHAPE: usize = 7;

/// The nonlinear constants of a play model, in the units the search moves:
/// `[ln(a₂·x̂), a₃, ln(a₅/a₁), ln(a₆·x̂), a₇, (a₈ − a₄)/a₁, ln(ρ_max/a₁)]`, `x̂` the recording's
/// largest `|ε − ε_c|`. The amplitude `a₁`, the offset `a₄` and the weights are the linear part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shape(pub [f64; SHAPE]);

impl Shape {
    /// The nearest shape inside the box (NaN goes to the box's middle).
    fn clamp(self) -> Self {
        let bounds = [
            (TANH_REACH.0.ln(), TANH_REACH.1.ln()),
            (-MAX_TANH_OFFSET, MAX_TANH_OFFSET),
            (-MAX_LOG_RATIO, MAX_LOG_RATIO),
            (TANH_REACH.0.ln(), TANH_REACH.1.ln()),
            (-MAX_TANH_OFFSET, MAX_TANH_OFFSET),
            (-MAX_OFFSET_RATIO, MAX_OFFSET_RATIO),
            LOG_RADIUS,
        ];
        let mut z = self.0;
        for (v, (lo, hi)) in z.iter_mut().zip(bounds) {
            *v = if v.is_nan() {
                0.5 * (lo + hi)
            } else {
                v.clamp(lo, hi)
            };
        }
        Self(z)
    }

    /// The unit-amplitude loading and unloading tanh and `ρ_max`, for the largest `|ε − ε_c|`
    /// `reach`.
    fn branches(&self, reach: f64) -> ([f64; 4], [f64; 4], f64) {
        let z = self.0;
        (
            [1.0, z[0].exp() / reach, z[1], 0.0],
            [z[2].exp(), z[3].exp() / reach, z[4], z[5]],
            z[6].exp(),
        )
    }
}

/// Where a search began.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// Eq. 15's tanh with the slope multiplier `k` and `ρ_max` as a share of half the input's
    /// span.
    Grid {
        /// `k` of `a₂ = k·m_c/a₁`.
        slope: f64,
        /// `ρ_max` over half the input's span.
        radius_share: f64,
    },
    /// A tanh straight over the recording: the least-squares line.
    Linear,
    /// The best shape of the other starts with its shift changed by this much.
    Hop(f64),
}

impl std::fmt::Display for Start {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Grid {
                slope,
                radius_share,
            } => write!(f, "k = {slope}, ρ share {radius_share}"),
            Self::Linear => f.write_str("linear"),
            Self::Hop(shift) => write!(f, "best, shift {shift:+}"),
        }
    }
}

/// What the search from one start reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Restart {
    /// Where it began.
    pub start: Start,
    /// RMS residual of its shape on every sample (Ω).
    pub rmse_ohm: f64,
    /// Whether its last round stopped improving (rather than running out of rounds).
    pub converged: bool,
}

/// A fitted play model.
#[derive(Debug, Clone, PartialEq)]
pub struct PlayFit {
    /// The model with its radii and centre.
    pub model: PlayModel,
    /// The fitted parameter vector (see [`super::plays`]).
    pub theta: Vec<f64>,
    /// Branches and weights.
    pub values: Unpacked,
    /// Initial play state `M₀` (units of the input).
    pub initial_state: f64,
    /// RMS of `R_model − R` over the fitted samples (Ω), from the runtime form of the model.
    pub rmse_ohm: f64,
    /// What each start reached.
    pub restarts: Vec<Restart>,
    /// Projections (weight solves) over all starts.
    pub evaluations: usize,
    /// When the model is the line it contains: the RMSE of the best hysteretic model, set aside
    /// because its improvement did not pay for its parameters (Ω).
    pub set_aside_rmse_ohm: Option<f64>,
}

impl PlayFit {
    /// The fitted model's resistance over `strain` (Ω), from relaxed plays, the generalized
    /// model's direction taken from consecutive samples.
    pub fn predict(&self, strain: &[f64]) -> Vec<f64> {
        let mut ohm = vec![0.0; strain.len()];
        self.model.evaluate(&self.theta, strain, &mut ohm);
        ohm
    }

    /// Constants the fit chose: `θ` (the branches and the weights after `P₁ = 1`) and `ρ_max`,
    /// which the projection searches too.
    pub fn parameters(&self) -> usize {
        self.theta.len() + 1
    }

    /// The fitted model's resistance over decimated observations, with the direction the
    /// full-rate signal had at each ([`super::Observations::falling`]): the samples its RMSE
    /// is computed on.
    pub fn predict_observed(&self, obs: &super::Observations) -> Vec<f64> {
        let mut ohm = vec![0.0; obs.strain.len()];
        self.model
            .evaluate_directed(&self.theta, &obs.strain, Some(&obs.falling), &mut ohm);
        ohm
    }
}

/// Fits a PI model of `kind` with `order` plays to `(strain, ohm)`, the starts searched on up to
/// two threads.
///
/// # Errors
/// [`FitError::NotIncreasing`] when the loop does not rise; [`FitError::NotConverged`] only if
/// the runtime form of the best model disagrees with the projection by more than 1 % (a defect,
/// named with both numbers), or gives `P₁ = 0`.
pub fn fit_plays(
    kind: PlayKind,
    order: usize,
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
) -> Result<PlayFit, FitError> {
    fit_plays_on(kind, order, strain, ohm, points, 2)
}

/// [`fit_plays`] on `threads` threads (1: all starts on the caller's). The result does not
/// depend on `threads`: each start is searched alone and the results are compared in a fixed
/// order.
///
/// # Errors
/// As [`fit_plays`].
pub fn fit_plays_on(
    kind: PlayKind,
    order: usize,
    strain: &[f64],
    ohm: &[f64],
    points: &Characteristic,
    threads: usize,
) -> Result<PlayFit, FitError> {
    fit_plays_directed(kind, order, strain, None, ohm, points, threads)
}

/// [`fit_plays_on`] with the generalized model's direction at each sample given (`falling`,
/// [`super::Observations::falling`]): decimated samples of a signal the runtime steps through at
/// the full rate, where a reversal between two kept samples is not a reversal the runtime sees,
/// and noise the prefilter leaves flips the direction the runtime does see. Judged from the kept
/// samples alone, a fit can put the branches far apart at no cost on the samples it fits and
/// then jump between them on every such flip at the full rate.
///
/// # Errors
/// As [`fit_plays`].
#[allow(clippy::too_many_arguments)]
pub fn fit_plays_directed(
    kind: PlayKind,
    order: usize,
    strain: &[f64],
    falling: Option<&[bool]>,
    ohm: &[f64],
    points: &Characteristic,
    threads: usize,
) -> Result<PlayFit, FitError> {
    let name = match kind {
        PlayKind::Generalized => "pi",
        PlayKind::Continuous => "continuous-pi",
    };
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
    let full = Projection::new(kind, order, strain, falling, ohm, points, 1);
    if !(full.reach > 0.0) {
        return Err(FitError::FlatStrain {
            samples: strain.len(),
        });
    }
    let coarse = Projection::new(
        kind,
        order,
        strain,
        falling,
        ohm,
        points,
        strain.len().div_ceil(COARSE_SAMPLES).max(1),
    );
    let mut starts = grid_starts(&coarse, points.center_slope_ohm / span);
    starts.push((Start::Linear, coarse.linear_shape()));
    let mut restarts = Vec::new();
    let mut best: Option<(Shape, f64)> = None;
    let mut score = |searched: Vec<(Start, Shape, bool)>| {
        for (start, shape, converged) in searched {
            let cost = full.cost(&shape);
            restarts.push(Restart {
                start,
                rmse_ohm: cost.sqrt(),
                converged,
            });
            if best.map_or(true, |(_, c)| cost < c) {
                best = Some((shape, cost));
            }
        }
        best.expect("at least one start is searched")
    };
    let mut found = score(search_all(&coarse, &starts, threads));
    // Hops: the best shape with the unloading tanh shifted either way, searched again, and again
    // from a hop that improved (up to `HOP_ROUNDS`). The shift and the radii trade off, and a
    // search can settle on the wrong side of that valley, or part of the way along it.
    for _ in 0..HOP_ROUNDS {
        let (from, before) = found;
        let hops: Vec<(Start, Shape)> = SHIFT_HOPS
            .iter()
            .map(|&hop| {
                let mut moved = from;
                moved.0[SHIFT] += hop;
                (Start::Hop(hop), moved.clamp())
            })
            .collect();
        found = score(search_all(&coarse, &hops, threads));
        if !(found.1 < before * (1.0 - HOP_IMPROVEMENT)) {
            break;
        }
    }
    let (shape, _) = found;
    let (shape, cost, _) = refine(&full, shape, FULL_REFINEMENTS);
    let (shape, solved, cost, set_aside) = line_or_hysteretic(&full, shape, cost, order);
    let evaluations = full.evaluations() + coarse.evaluations();
    let mut fit = full
        .play_fit(&shape, solved)
        .map_err(|reason| FitError::NotConverged {
            model: name,
            reason,
        })?;
    fit.set_aside_rmse_ohm = set_aside;
    let projected = cost.sqrt();
    if !((fit.rmse_ohm - projected).abs() <= 0.01 * projected + 1e-9 * span) {
        return Err(FitError::NotConverged {
            model: name,
            reason: format!(
                "the runtime model's RMSE {:.6} Ω differs from the projection's {projected:.6} Ω by more than 1 %",
                fit.rmse_ohm
            ),
        });
    }
    fit.restarts = restarts;
    fit.evaluations = evaluations;
    Ok(fit)
}

/// The hysteretic model against the line it contains: kept only where its lower residual
/// pays for its extra parameters by the Bayesian information criterion. Otherwise the extra
/// constants fit noise, and an inverse through noise-fitted partial sums amplifies it (Joint C's
/// nearly linear sensor: 0.4 % lower RMSE, 4.0° against the line's 0.81°). Returns the shape
/// kept, its solution, its cost and, when the line was kept, the set-aside hysteretic RMSE.
fn line_or_hysteretic(
    full: &Projection,
    shape: Shape,
    cost: f64,
    order: usize,
) -> (Shape, Solved, f64, Option<f64>) {
    let samples = full.strain.len() as f64;
    // The model's constants are the shape, the N weights and the constant; the line's two.
    let extra = (SHAPE + order + 1 - 2) as f64;
    let line_shape = full.linear_shape_at(LOG_RADIUS.0);
    let chosen = match full.line(&line_shape) {
        Some(line) => {
            let line_cost = line.residuals.norm_squared() / samples;
            if samples * (line_cost / cost).ln() > extra * samples.ln() {
                None
            } else {
                Some((line_shape, line, line_cost))
            }
        }
        None => None,
    };
    match chosen {
        Some((line_shape, line, line_cost)) => (line_shape, line, line_cost, Some(cost.sqrt())),
        None => (shape, full.solve(&shape), cost, None),
    }
}

/// [`refine`] from each start, on `threads` threads; the results in the order of `starts`.
fn search_all(
    p: &Projection,
    starts: &[(Start, Shape)],
    threads: usize,
) -> Vec<(Start, Shape, bool)> {
    let search = |&(start, shape): &(Start, Shape)| {
        let (shape, _, converged) = refine(p, shape, REFINEMENTS);
        (start, shape, converged)
    };
    if threads > 1 {
        std::thread::scope(|scope| {
            let handles: Vec<_> = starts
                .iter()
                .map(|s| scope.spawn(move || search(s)))
                .collect();
            handles
                .into_iter()
                .zip(starts)
                .map(|(h, s)| h.join().unwrap_or((s.0, s.1, false)))
                .collect()
        })
    } else {
        starts.iter().map(search).collect()
    }
}

/// The [`GRID_STARTS`] best Eq. 15 shapes of the grid, no two with the same radius share, for
/// the initial slope `m_c/a₁` (per unit strain) at `k = 1`.
fn grid_starts(p: &Projection, slope: f64) -> Vec<(Start, Shape)> {
    let mut grid: Vec<(Start, Shape, f64)> = Vec::new();
    for k in SLOPE_RESTARTS {
        for share in RADIUS_SHARES {
            let a2 = k * slope;
            let input = |x: f64| (a2 * x).tanh();
            let half_span = 0.5 * (input(p.x_range.1) - input(p.x_range.0));
            let reach = (a2 * p.reach).ln();
            let shape = Shape([reach, 0.0, 0.0, reach, 0.0, 0.0, (share * half_span).ln()]).clamp();
            let start = Start::Grid {
                slope: k,
                radius_share: share,
            };
            grid.push((start, shape, p.cost(&shape)));
        }
    }
    // A stable sort on the cost keeps the grid's order among ties.
    grid.sort_by(|a, b| a.2.total_cmp(&b.2));
    let mut chosen: Vec<(Start, Shape)> = Vec::new();
    for (start, shape, _) in grid {
        let share = |s: &Start| match s {
            Start::Grid { radius_share, .. } => *radius_share,
            Start::Linear | Start::Hop(_) => f64::NAN,
        };
        if chosen.len() < GRID_STARTS && chosen.iter().all(|(s, _)| share(s) != share(&start)) {
            chosen.push((start, shape));
        }
    }
    chosen
}

/// Rounds of scan and Levenberg-Marquardt from `shape` on `p`, at most `rounds`: the shape, its
/// mean square residual, and whether the last round stopped improving.
fn refine(p: &Projection, shape: Shape, rounds: usize) -> (Shape, f64, bool) {
    let mut shape = shape.clamp();
    let mut cost = p.cost(&shape);
    for _ in 0..rounds {
        let before = cost;
        (shape, cost) = scan(p, shape, cost);
        (shape, cost) = search(p, shape, cost);
        if !(cost < before * (1.0 - IMPROVEMENT)) {
            return (shape, cost, true);
        }
    }
    (shape, cost, false)
}

/// A coordinate scan: `ln ρ_max` over a dense grid around its value, then each other constant
/// stepped both ways while it improves, coarse steps first.
fn scan(p: &Projection, mut shape: Shape, mut cost: f64) -> (Shape, f64) {
    let radius = SHAPE - 1;
    let centre = shape.0[radius];
    for k in -RADIUS_SCAN_STEPS..=RADIUS_SCAN_STEPS {
        let mut trial = shape;
        trial.0[radius] = centre + k as f64 * RADIUS_SCAN_SPACING;
        let trial = trial.clamp();
        let c = p.cost(&trial);
        if c < cost {
            (shape, cost) = (trial, c);
        }
    }
    for j in 0..radius {
        for step in COORDINATE_STEPS {
            for direction in [1.0, -1.0] {
                loop {
                    let mut trial = shape;
                    trial.0[j] += direction * step;
                    let trial = trial.clamp();
                    let c = p.cost(&trial);
                    if c < cost && trial != shape {
                        (shape, cost) = (trial, c);
                    } else {
                        break;
                    }
                }
            }
        }
    }
    (shape, cost)
}

/// Levenberg-Marquardt on the projected residual from `shape`; kept only where it improves.
fn search(p: &Projection, shape: Shape, cost: f64) -> (Shape, f64) {
    let problem = Reduced::new(p, shape);
    let (problem, _) = LevenbergMarquardt::new()
        .with_ftol(1e-10)
        .with_xtol(1e-10)
        .with_gtol(1e-12)
        .with_patience(PATIENCE)
        .minimize(problem);
    let found = problem.shape;
    let c = p.cost(&found);
    if c < cost {
        (found, c)
    } else {
        (shape, cost)
    }
}

/// The weights' problem on a recording (or every `step`-th sample of it): the resistance less
/// `R_c`, and what a shape needs to produce the plays' columns.
struct Projection {
    kind: PlayKind,
    order: usize,
    strain: Vec<f64>,
    /// The generalized model's direction per sample, where it is given.
    falling: Option<Vec<bool>>,
    /// `R − R_c` (Ω).
    target: DVector<f64>,
    center_strain: f64,
    center_ohm: f64,
    /// Largest `|ε − ε_c|`.
    reach: f64,
    /// Smallest and largest `ε − ε_c`.
    x_range: (f64, f64),
    evaluations: AtomicUsize,
}

/// The weights at a shape.
struct Solved {
    /// Non-negative coefficients of the columns.
    beta: DVector<f64>,
    /// The constant (Ω).
    constant: f64,
    /// `R_model − R` (Ω).
    residuals: DVector<f64>,
}

impl Projection {
    fn new(
        kind: PlayKind,
        order: usize,
        strain: &[f64],
        falling: Option<&[bool]>,
        ohm: &[f64],
        points: &Characteristic,
        step: usize,
    ) -> Self {
        let strain: Vec<f64> = strain.iter().step_by(step).copied().collect();
        let falling = falling.map(|f| f.iter().step_by(step).copied().collect());
        let target = DVector::from_iterator(
            strain.len(),
            ohm.iter().step_by(step).map(|r| r - points.center_ohm),
        );
        let x_range = strain.iter().fold((0.0f64, 0.0f64), |(lo, hi), e| {
            let x = e - points.center_strain;
            (lo.min(x), hi.max(x))
        });
        Self {
            kind,
            order,
            reach: x_range.0.abs().max(x_range.1.abs()),
            x_range,
            strain,
            falling,
            target,
            center_strain: points.center_strain,
            center_ohm: points.center_ohm,
            evaluations: AtomicUsize::new(0),
        }
    }

    /// Half the span of the plays' input over the recording: the least radius a play needs
    /// to stay still through a full loop. A larger radius moves only on the first rise (or a
    /// new extreme), so its weight would be fitted to the recording's start alone.
    fn half_span(&self, l: &[f64; 4], u: &[f64; 4]) -> f64 {
        let nu = super::plays::branch;
        let (x0, x1) = self.x_range;
        let lo = nu(l, x0).min(nu(u, x0));
        let hi = nu(l, x1).max(nu(u, x1));
        0.5 * (hi - lo)
    }

    fn evaluations(&self) -> usize {
        self.evaluations.load(Ordering::Relaxed)
    }

    /// The linear start: both tanh at [`LINEAR_START_REACH`], `ρ_max` a tenth of half the span.
    fn linear_shape(&self) -> Shape {
        self.linear_shape_at((0.1 * LINEAR_START_REACH).ln())
    }

    /// Both tanh at [`LINEAR_START_REACH`], alike, and `ln ρ_max` as given.
    fn linear_shape_at(&self, log_radius: f64) -> Shape {
        let z = LINEAR_START_REACH.ln();
        Shape([z, 0.0, 0.0, z, 0.0, 0.0, log_radius]).clamp()
    }

    /// Visits the plays' outputs sample by sample, as the row of columns the non-negative
    /// weights multiply (see the module's constraints).
    fn rows(&self, shape: &Shape, mut visit: impl FnMut(usize, &[f64])) {
        let (l, u, rho_max) = shape.branches(self.reach);
        let rho_max = rho_max.min(self.half_span(&l, &u));
        let n = self.order;
        let radii: Vec<f64> = (0..n)
            .map(|i| rho_max * i as f64 / (n - 1).max(1) as f64)
            .collect();
        // tanh through one exp (`1 − 2/(e^{2z} + 1)`, exact at both saturations), a third of the
        // cost of libm's tanh, which the runtime form uses: the final check compares the two.
        let tanh = |a: &[f64; 4], x: f64| {
            a[0] * (1.0 - 2.0 / ((2.0 * (a[1] * x + a[2])).exp() + 1.0)) + a[3]
        };
        let margin = 1.5 * PARTIAL_SUM_MARGIN;
        let mut y = vec![0.0; n];
        let mut row = vec![0.0; n];
        let mut previous = f64::NEG_INFINITY;
        for (t, &e) in self.strain.iter().enumerate() {
            let x = e - self.center_strain;
            let (lower_in, upper_in) = match self.kind {
                PlayKind::Generalized => {
                    let loading = self.falling.as_ref().map_or(e >= previous, |f| !f[t]);
                    let v = if loading { tanh(&l, x) } else { tanh(&u, x) };
                    (v, v)
                }
                PlayKind::Continuous => (tanh(&l, x), tanh(&u, x)),
            };
            previous = e;
            if t == 0 {
                y.fill(lower_in);
            }
            // The play update of `PlayModel::evaluate`: `max(lower, min(upper, y))`, the lower
            // bound winning where the two cross.
            for (yi, r) in y.iter_mut().zip(&radii) {
                *yi = yi.min(upper_in + r).max(lower_in - r);
            }
            match self.kind {
                // Σ Pᵢyᵢ = Σ Sᵢ(yᵢ − yᵢ₊₁) with S₁ = β₀ and Sᵢ = 1.5·m·β₀ + βᵢ₋₁.
                PlayKind::Generalized => {
                    for i in 0..n {
                        let next = if i + 1 < n { y[i + 1] } else { 0.0 };
                        row[i] = y[i] - next;
                    }
                    if n > 1 {
                        row[0] += margin * y[1];
                    }
                }
                // Pᵢ = f·β₀ + βᵢ₋₁ for i > 1, f the weight floor.
                PlayKind::Continuous => {
                    let rest: f64 = y[1..].iter().sum();
                    row[0] = y[0] + CONTINUOUS_WEIGHT_FLOOR * rest;
                    row[1..].copy_from_slice(&y[1..]);
                }
            }
            visit(t, &row);
        }
    }

    /// The columns at `shape` and, last, the target, each less its first row's value (so that a
    /// column that hardly varies keeps its variation through the centring), one row per sample.
    fn design(&self, shape: &Shape) -> (DMatrix<f64>, DVector<f64>) {
        let n = self.order;
        let mut design = DMatrix::zeros(self.strain.len(), n + 1);
        let mut origin = DVector::zeros(n + 1);
        self.rows(shape, |t, row| {
            if t == 0 {
                origin.rows_mut(0, n).copy_from_slice(row);
                origin[n] = self.target[0];
            }
            for (i, v) in row.iter().enumerate() {
                design[(t, i)] = v - origin[i];
            }
            design[(t, n)] = self.target[t] - origin[n];
        });
        (design, origin)
    }

    /// The non-negative weights and the free constant at `shape`, by least squares on the
    /// centred normal equations, and the residuals they leave.
    fn solve(&self, shape: &Shape) -> Solved {
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        let n = self.order;
        let (design, origin) = self.design(shape);
        let rows = design.nrows().max(1) as f64;
        let sums = design.row_sum().transpose();
        let mut moment = design.tr_mul(&design);
        moment -= &sums * sums.transpose() / rows;
        let g = moment.view((0, 0), (n, n)).into_owned();
        let b = moment.view((0, n), (n, 1)).column(0).into_owned();
        // P₁ stays well away from zero: β₀ = P₁ is at least the weight at which the first
        // play's output carries FIRST_WEIGHT_SHARE of the target's spread, and the rest is
        // solved with that part of the first column removed.
        // The first play's own output y₁ in the columns: generalized, the first column is
        // y₁ − y₂ + m′y₂ and the others telescope to y₂; continuous, it is y₁ + f·Σyᵢ₊₁.
        let rest = match self.kind {
            PlayKind::Generalized => 1.0 - 1.5 * PARTIAL_SUM_MARGIN,
            PlayKind::Continuous => -CONTINUOUS_WEIGHT_FLOOR,
        };
        let first_play = DVector::from_fn(n, |i, _| if i == 0 { 1.0 } else { rest });
        let first_variance = first_play.dot(&(&g * &first_play));
        let floor = if first_variance > 0.0 {
            FIRST_WEIGHT_SHARE * (moment[(n, n)].max(0.0) / first_variance).sqrt()
        } else {
            0.0
        };
        let mut beta = nnls(&g, &(b - g.column(0) * floor));
        beta[0] += floor;
        let means = &sums / rows;
        // r = Σβᵢ(dᵢ − d̄ᵢ) − (d_y − d̄_y); the origins cancel.
        let offset = means.rows(0, n).dot(&beta) - means[n];
        let mut residuals = design.columns(0, n) * &beta - design.column(n);
        residuals.add_scalar_mut(-offset);
        let level = origin + means;
        Solved {
            constant: level[n] - level.rows(0, n).dot(&beta),
            beta,
            residuals,
        }
    }

    /// `R_model − R` at `shape` (Ω), sample by sample.
    fn residuals(&self, shape: &Shape) -> DVector<f64> {
        self.solve(shape).residuals
    }

    /// Mean square residual at `shape` (Ω²); infinite where it is not finite.
    fn cost(&self, shape: &Shape) -> f64 {
        let c = self.solve(shape).residuals.norm_squared() / self.strain.len().max(1) as f64;
        if c.is_finite() {
            c
        } else {
            f64::INFINITY
        }
    }

    /// The model at `shape` in the runtime's form: `P₁ = 1`, the amplitude and radii scaled by
    /// the first weight, the constant moved into `a₄` and `a₈`.
    fn play_fit(&self, shape: &Shape, solved: Solved) -> Result<PlayFit, String> {
        let beta = &solved.beta;
        let first = beta[0];
        if !(first > 0.0) {
            return Err(format!(
                "the best shape puts no weight on the first play (P₁ = {first})"
            ));
        }
        let n = self.order;
        let weights: Vec<f64> = match self.kind {
            PlayKind::Generalized => {
                let partial = |i: usize| {
                    if i == 0 {
                        first
                    } else {
                        1.5 * PARTIAL_SUM_MARGIN * first + beta[i]
                    }
                };
                (0..n)
                    .map(|i| partial(i) - if i == 0 { 0.0 } else { partial(i - 1) })
                    .collect()
            }
            PlayKind::Continuous => (0..n)
                .map(|i| {
                    if i == 0 {
                        first
                    } else {
                        CONTINUOUS_WEIGHT_FLOOR * first + beta[i]
                    }
                })
                .collect(),
        };
        let total: f64 = weights.iter().sum();
        let (l, u, rho_max) = shape.branches(self.reach);
        let rho_max = rho_max.min(self.half_span(&l, &u));
        // Σ Pᵢ·yᵢ + C = Σ (Pᵢ/P₁)·(P₁·yᵢ + c) with c = C·P₁/ΣPᵢ.
        let c = solved.constant * first / total;
        let loading = [first * l[0], l[1], l[2], c];
        let unloading = [first * u[0], u[1], u[2], first * u[3] + c];
        let model = PlayModel {
            kind: self.kind,
            radii: (0..n)
                .map(|i| first * rho_max * i as f64 / (n - 1).max(1) as f64)
                .collect(),
            center_strain: self.center_strain,
            center_ohm: self.center_ohm,
        };
        let normalized: Vec<f64> = weights.iter().map(|w| w / first).collect();
        let theta = model.pack(loading, unloading, &normalized);
        if !theta.iter().all(|v| v.is_finite()) {
            return Err("the fitted parameters are not finite".into());
        }
        let values = model.unpack(&theta);
        let mut ohm = vec![0.0; self.strain.len()];
        model.evaluate_directed(&theta, &self.strain, self.falling.as_deref(), &mut ohm);
        let rss: f64 = ohm
            .iter()
            .zip(self.target.iter())
            .map(|(m, r)| (m - self.center_ohm - r).powi(2))
            .sum();
        let x0 = self.strain[0] - self.center_strain;
        let lv = values.loading;
        Ok(PlayFit {
            initial_state: lv[0] * (lv[1] * x0 + lv[2]).tanh() + lv[3],
            values,
            theta,
            model,
            rmse_ohm: (rss / self.strain.len() as f64).sqrt(),
            restarts: Vec::new(),
            evaluations: 0,
            set_aside_rmse_ohm: None,
        })
    }

    /// The line inside the model at a straight `shape`: one weight on the first play and the
    /// others such that no other play contributes (generalized: every partial sum `P₁`;
    /// continuous: the floor), the slope and constant by least squares. `None` when the line
    /// does not rise.
    fn line(&self, shape: &Shape) -> Option<Solved> {
        let n = self.order;
        let (design, origin) = self.design(shape);
        let mut w = DVector::zeros(n);
        w[0] = 1.0;
        if self.kind == PlayKind::Generalized {
            for i in 1..n {
                w[i] = 1.0 - 1.5 * PARTIAL_SUM_MARGIN;
            }
        }
        let u = design.columns(0, n) * &w;
        let y = design.column(n);
        let rows = u.len().max(1) as f64;
        let (mu, my) = (u.sum() / rows, y.sum() / rows);
        let var: f64 = u.iter().map(|v| (v - mu).powi(2)).sum();
        let cov: f64 = u
            .iter()
            .zip(y.iter())
            .map(|(a, b)| (a - mu) * (b - my))
            .sum();
        let gamma = cov / var;
        if !(gamma > 0.0 && gamma.is_finite()) {
            return None;
        }
        let beta = w * gamma;
        let residuals = u.map(|v| (v - mu) * gamma) - y.add_scalar(-my);
        let level_u = origin.rows(0, n).dot(&beta) + gamma * mu;
        Some(Solved {
            constant: origin[n] + my - level_u,
            beta,
            residuals,
        })
    }
}

/// The projected residual as a problem for `levenberg-marquardt`: the parameters are the shape,
/// the Jacobian is by forward differences, and a step out of the box is pulled back onto it.
struct Reduced<'a> {
    projection: &'a Projection,
    shape: Shape,
    residuals: DVector<f64>,
}

impl<'a> Reduced<'a> {
    fn new(projection: &'a Projection, shape: Shape) -> Self {
        let shape = shape.clamp();
        Self {
            residuals: projection.residuals(&shape),
            projection,
            shape,
        }
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Reduced<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, z: &DVector<f64>) {
        let mut values = [0.0; SHAPE];
        values.copy_from_slice(z.as_slice());
        self.shape = Shape(values).clamp();
        self.residuals = self.projection.residuals(&self.shape);
    }

    fn params(&self) -> DVector<f64> {
        DVector::from_column_slice(&self.shape.0)
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.residuals
            .iter()
            .all(|r| r.is_finite())
            .then(|| self.residuals.clone())
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let mut jacobian = DMatrix::zeros(self.residuals.len(), SHAPE);
        for j in 0..SHAPE {
            let h = 1e-6 * self.shape.0[j].abs().max(1.0);
            let mut up = self.shape;
            up.0[j] += h;
            let mut moved = up.clamp();
            let mut step = moved.0[j] - self.shape.0[j];
            if step == 0.0 {
                // At the box's upper edge: difference backwards.
                let mut down = self.shape;
                down.0[j] -= h;
                moved = down.clamp();
                step = moved.0[j] - self.shape.0[j];
            }
            if step == 0.0 {
                continue;
            }
            let r = self.projection.residuals(&moved);
            jacobian.set_column(j, &((r - &self.residuals) / step));
        }
        jacobian.iter().all(|v| v.is_finite()).then_some(jacobian)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Loops of unequal amplitude on a slow drift.
    fn strain(samples: usize) -> Vec<f64> {
        (0..samples)
            .map(|i| {
                let t = i as f64 * 24.8 / samples as f64;
                0.0062 + 0.0061 * (t * 1.31).sin() * (0.7 + 0.3 * (t * 0.29).cos()) + 1e-6 * t
            })
            .collect()
    }

    fn noise(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    fn line_rmse(e: &[f64], ohm: &[f64]) -> f64 {
        let n = e.len() as f64;
        let (me, mr) = (e.iter().sum::<f64>() / n, ohm.iter().sum::<f64>() / n);
        let see: f64 = e.iter().map(|x| (x - me) * (x - me)).sum();
        let ser: f64 = e.iter().zip(ohm).map(|(x, r)| (x - me) * (r - mr)).sum();
        let slope = ser / see;
        (e.iter()
            .zip(ohm)
            .map(|(x, r)| (mr + slope * (x - me) - r).powi(2))
            .sum::<f64>()
            / n)
            .sqrt()
    }

    fn points(e: &[f64], ohm: &[f64], slope: f64) -> Characteristic {
        let i = e
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1 - 0.006).abs().total_cmp(&(b.1 - 0.006).abs()))
            .unwrap()
            .0;
        Characteristic {
            center_strain: e[i],
            center_ohm: ohm[i],
            center_slope_ohm: slope,
            peak_ohm: ohm.iter().copied().fold(f64::MIN, f64::max),
            peak_strain: 0.0123,
        }
    }

    /// On a line with scatter both PI models reproduce the line's RMSE to 1 %, and never exceed
    /// it: the linear start is the line.
    #[test]
    fn on_a_linear_sensor_both_models_are_the_line() {
        let e = strain(3000);
        let mut seed = 12345u64;
        let ohm: Vec<f64> = e
            .iter()
            .map(|&x| 74e3 * (1.0 + 1.28 * x) + 80.0 * noise(&mut seed))
            .collect();
        let line = line_rmse(&e, &ohm);
        let p = points(&e, &ohm, 74e3 * 1.28);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let fit = fit_plays(kind, 10, &e, &ohm, &p).unwrap();
            assert!(
                fit.rmse_ohm <= line * 1.0001 && fit.rmse_ohm >= line * 0.99,
                "{kind:?}: fit {} Ω, line {line} Ω",
                fit.rmse_ohm
            );
            assert!(fit.restarts.iter().any(|r| r.start == Start::Linear));
        }
    }

    /// A generalized PI model with hysteresis is recovered to within its noise (σ = 20 Ω).
    #[test]
    fn a_hysteretic_model_is_recovered_to_its_noise() {
        let e = strain(4000);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let truth = PlayModel {
                kind,
                radii: (0..6).map(|i| i as f64 * 1.2e3).collect(),
                center_strain: 0.006,
                center_ohm: 224e3,
            };
            let theta = truth.pack(
                [26e3, 190.0, 0.1, 300.0],
                [24e3, 210.0, -0.05, -400.0],
                &[1.0, 0.3, 0.2, 0.1, 0.15, 0.1],
            );
            let mut clean = vec![0.0; e.len()];
            truth.evaluate(&theta, &e, &mut clean);
            let mut seed = 99u64;
            let sigma = 20.0;
            let ohm: Vec<f64> = clean
                .iter()
                .map(|r| r + sigma * 12f64.sqrt() * noise(&mut seed))
                .collect();
            let p = points(&e, &ohm, 26e3 * 190.0);
            let fit = fit_plays(kind, 6, &e, &ohm, &p).unwrap();
            let predicted = fit.predict(&e);
            let error = (predicted
                .iter()
                .zip(&clean)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                / e.len() as f64)
                .sqrt();
            assert!(
                error < 0.5 * sigma,
                "{kind:?}: response error {error} Ω, noise {sigma} Ω, fit RMSE {}, restarts {:?}",
                fit.rmse_ohm,
                fit.restarts
            );
            assert!(fit.rmse_ohm < 1.05 * sigma, "{kind:?}: {}", fit.rmse_ohm);
        }
    }

    /// A sensor that barely moves after each reversal (its first play weighs a hundredth of the
    /// others) is fitted with a model whose inverse stays usable: the fitted model's least
    /// slope along the loops is more than a thirtieth of its mean slope (measured: 0.049),
    /// where the truth's is below a hundredth. (With the first weight's floor at 10⁻³ of the spread the fit followed
    /// the truth, and Joint D's half-size inverse amplified the noise by about 500.)
    #[test]
    fn the_first_play_keeps_the_inverse_gain_bounded() {
        let e = strain(3000);
        let truth = PlayModel {
            kind: PlayKind::Generalized,
            radii: vec![0.0, 1.5e3, 3e3],
            center_strain: 0.006,
            center_ohm: 224e3,
        };
        let theta = truth.pack(
            [26e3, 190.0, 0.0, 0.0],
            [26e3, 190.0, 0.0, 0.0],
            &[1.0, 100.0, 50.0],
        );
        let mut ohm = vec![0.0; e.len()];
        truth.evaluate(&theta, &e, &mut ohm);
        let p = points(&e, &ohm, 26e3 * 190.0);
        // The least and the mean of |dR/dε| over steps that move the strain by at least 10⁻⁶.
        let slopes = |r: &[f64]| {
            let steps: Vec<f64> = (1..e.len())
                .filter(|&i| (e[i] - e[i - 1]).abs() > 1e-6)
                .map(|i| ((r[i] - r[i - 1]) / (e[i] - e[i - 1])).abs())
                .collect();
            let least = steps.iter().copied().fold(f64::INFINITY, f64::min);
            (least, steps.iter().sum::<f64>() / steps.len() as f64)
        };
        let (least, mean) = slopes(&ohm);
        assert!(least < 0.01 * mean, "truth: least {least}, mean {mean}");
        let fit = fit_plays(PlayKind::Generalized, 3, &e, &ohm, &p).unwrap();
        let (least, mean) = slopes(&fit.predict(&e));
        assert!(
            least > mean / 30.0,
            "fit: least slope {least} Ω against a mean of {mean} Ω, weights {:?}",
            fit.values.weights
        );
    }

    /// The projection's residual is the runtime form's: the columns, the constraints' change of
    /// variables and the move to `P₁ = 1` agree to round-off at shapes away from the optimum.
    #[test]
    fn the_runtime_form_has_the_projections_residual() {
        let e = strain(1500);
        let mut seed = 3u64;
        let ohm: Vec<f64> = e
            .iter()
            .map(|&x| 2e5 + 3e6 * x + 4e7 * x * x + 300.0 * noise(&mut seed))
            .collect();
        let p = points(&e, &ohm, 3e6);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let projection = Projection::new(kind, 8, &e, None, &ohm, &p, 1);
            let linear = projection.linear_shape().0;
            for shape in [
                Shape(linear),
                Shape([0.5, 0.1, 0.1, 0.6, -0.1, 0.02, -1.5]),
                Shape([-0.5, -0.1, -0.05, -0.4, 0.1, -0.01, -4.0]),
            ] {
                let fit = projection
                    .play_fit(&shape, projection.solve(&shape))
                    .unwrap();
                let projected = projection.cost(&shape).sqrt();
                assert!(
                    (fit.rmse_ohm - projected).abs() < 1e-6 * projected,
                    "{kind:?} at {shape:?}: runtime {} Ω, projection {projected} Ω",
                    fit.rmse_ohm
                );
            }
        }
    }

    /// The same config to the last digit on one thread or two.
    #[test]
    fn the_fit_does_not_depend_on_the_threads() {
        let e = strain(2000);
        let ohm: Vec<f64> = e
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                2e5 + 3e6 * x + 1e3 * (x * 400.0).tanh() + 50.0 * ((i as f64) * 0.7).sin()
            })
            .collect();
        let p = points(&e, &ohm, 3e6);
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let one = fit_plays_on(kind, 10, &e, &ohm, &p, 1).unwrap();
            let two = fit_plays_on(kind, 10, &e, &ohm, &p, 2).unwrap();
            assert_eq!(one, two);
        }
    }
}
