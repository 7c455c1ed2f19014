//! The two clocks: the tracker's time `τ` (from its first logged frame) against the DAQ's `t`
//! (from its first sample), `t = offset_s + τ·(1 + drift_ppm·10⁻⁶)`.
//!
//! `--sync auto` finds both by cross-correlating the tracker's angle with a DAQ signal that
//! follows it without a lag: the sensor's resistance (the stroke leads the joint by tens of
//! milliseconds). First one lag over the whole recording on a coarse grid, then, in windows
//! along the recording, the lag that correlates best on the DAQ's own sample grid, refined by
//! a parabola through the peak; a straight line through the windows' lags against their time
//! gives the offset (its intercept) and the drift (its slope), with standard errors from the
//! scatter about the line.

/// Why the clocks could not be aligned.
#[derive(Debug, thiserror::Error)]
pub enum AlignError {
    /// No lag correlates well.
    #[error("the tracker's angle and the DAQ's sensor signal correlate at most |r| = {r:.2} at any lag within ±{max_s} s (needed: {min}); a still recording cannot be aligned: record motion, or use --sync CH with a sync pulse")]
    Weak {
        /// Best |r|.
        r: f64,
        /// The lag range searched (s).
        max_s: f64,
        /// Needed.
        min: f64,
    },
    /// Too few windows to fit a line.
    #[error("only {windows} windows of the recording correlate well enough to measure the lag; the drift needs at least {min} (a longer recording with motion throughout)")]
    Windows {
        /// Usable windows.
        windows: usize,
        /// Needed.
        min: usize,
    },
}

/// The largest clock offset searched (s).
pub const MAX_OFFSET_S: f64 = 10.0;
/// The coarse grid of the whole-recording search (s).
pub const COARSE_STEP_S: f64 = 0.01;
/// How far around the coarse lag each window searches (s): more than a drift of 1000 ppm
/// moves the lag over 300 s.
pub const WINDOW_SEARCH_S: f64 = 0.4;
/// Windows along the recording.
pub const WINDOWS: usize = 20;
/// The least |r| the whole-recording search and a window must reach.
pub const MIN_CORRELATION: f64 = 0.6;
/// The whole-recording refinement: its grid spans ± this many of the windows' standard errors.
pub const REFINE_SPAN: f64 = 3.0;
/// Grid points on each side of the centre in the refinement.
pub const REFINE_STEPS: i32 = 6;
/// Refinement rounds, each a finer grid around the last best point.
pub const REFINE_ROUNDS: usize = 3;
/// The fewest windows the line is fitted through.
pub const MIN_WINDOWS: usize = 3;
/// The most frames the whole-recording coarse search correlates (every k-th frame beyond):
/// it only has to land within [`WINDOW_SEARCH_S`] of the lag, and on all 120 k frames of a
/// 3000 s log its 2001 lags took most of the import's 9.7 s (`benches/import.rs`).
pub const COARSE_FRAMES: usize = 4000;
/// The windows' first pass steps by this (s), then the DAQ's sample grid within one step of
/// its best: the same peak as the sample grid throughout, for a fifth of the lags.
pub const WINDOW_COARSE_STEP_S: f64 = 0.01;

/// The alignment found.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Alignment {
    /// `offset_s` (s).
    pub offset_s: f64,
    /// `drift_ppm`.
    pub drift_ppm: f64,
    /// Standard error of the offset (s).
    pub offset_uncertainty_s: f64,
    /// Standard error of the drift (ppm).
    pub drift_uncertainty_ppm: f64,
    /// The whole-recording correlation at the coarse lag.
    pub correlation: f64,
    /// Windows the line went through.
    pub windows: usize,
    /// Each window's centre (s of tracker time `τ`) and lag `t_daq − τ` (s): the points the
    /// line was fitted through.
    pub lags: Vec<(f64, f64)>,
}

/// `signal` (uniformly sampled from `t = 0` at `dt_s`) at time `t`, linearly interpolated;
/// `None` outside.
fn at(signal: &[f64], dt_s: f64, t: f64) -> Option<f64> {
    let x = t / dt_s;
    if x.is_nan() || x < 0.0 {
        return None;
    }
    let i = x.floor() as usize;
    let f = x - i as f64;
    Some(signal.get(i)? * (1.0 - f) + signal.get(i + 1)? * f)
}

/// How well the signal at `τ + lag` explains the angle frames in `frames`: the square root of
/// the R² of the angle regressed on the signal and its square, signed by the linear term's
/// direction. A quadratic takes up the divider's and the sensor's curvature, which would
/// otherwise bias the lag of best plain correlation by milliseconds.
fn correlation(
    tau_s: &[f64],
    angle: &[Option<f64>],
    frames: std::ops::Range<usize>,
    signal: &[f64],
    dt_s: f64,
    lag_s: &dyn Fn(f64) -> f64,
) -> f64 {
    // Moments about the first point, for conditioning.
    let mut m = [[0.0_f64; 3]; 3];
    let mut b = [0.0_f64; 3];
    let (mut n, mut sy, mut syy) = (0.0, 0.0, 0.0);
    let mut centre = None;
    for k in frames {
        let (Some(y), Some(x)) = (angle[k], at(signal, dt_s, tau_s[k] + lag_s(tau_s[k]))) else {
            continue;
        };
        let x = x - *centre.get_or_insert(x);
        let row = [1.0, x, x * x];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * y;
        }
        n += 1.0;
        sy += y;
        syy += y * y;
    }
    if n < 10.0 {
        return 0.0;
    }
    let total = syy - sy * sy / n;
    let Some(coef) = solve3(m, b) else {
        return 0.0;
    };
    // Explained sum of squares: coef·b − (Σy)²/n.
    let explained = coef[0] * b[0] + coef[1] * b[1] + coef[2] * b[2] - sy * sy / n;
    if total.is_nan() || total <= 0.0 {
        return 0.0;
    }
    let r2 = (explained / total).clamp(0.0, 1.0);
    // The direction: the slope at the data's mean signal.
    let mean_x = m[0][1] / n;
    let slope = coef[1] + 2.0 * coef[2] * mean_x;
    r2.sqrt() * slope.signum()
}

/// Solves the 3×3 system `m·x = b` (Cramer's rule); `None` when singular.
fn solve3(m: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let d = det(m);
    if !(d.abs() > 0.0 && d.is_finite()) {
        return None;
    }
    let mut x = [0.0; 3];
    for (c, xc) in x.iter_mut().enumerate() {
        let mut a = m;
        for r in 0..3 {
            a[r][c] = b[r];
        }
        *xc = det(a) / d;
    }
    Some(x)
}

/// The best lag on `grid` by `sign·r`, refined by a parabola through the peak; with its r.
fn best_lag(grid: &[f64], r_of: &dyn Fn(f64) -> f64, sign: f64) -> (f64, f64) {
    let rs: Vec<f64> = grid.iter().map(|&l| r_of(l)).collect();
    peak(grid, &rs, sign)
}

/// Every k-th frame's time and angle, k the least that keeps at most `most` frames.
fn every_kth(tau_s: &[f64], angle: &[Option<f64>], most: usize) -> (Vec<f64>, Vec<Option<f64>>) {
    let k = tau_s.len().div_ceil(most.max(1)).max(1);
    (
        tau_s.iter().step_by(k).copied().collect(),
        angle.iter().step_by(k).copied().collect(),
    )
}

/// The peak of `sign·r` over `grid` (`r` per grid point), refined by a parabola; with its
/// `sign·r`.
fn peak(grid: &[f64], r: &[f64], sign: f64) -> (f64, f64) {
    let rs: Vec<f64> = r.iter().map(|v| sign * v).collect();
    let (i, &r) = rs
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .unwrap_or((0, &0.0));
    if i == 0 || i + 1 >= rs.len() {
        return (grid[i], r);
    }
    let (a, b, c) = (rs[i - 1], rs[i], rs[i + 1]);
    let denominator = a - 2.0 * b + c;
    let shift = if denominator < 0.0 {
        (0.5 * (a - c) / denominator).clamp(-0.5, 0.5)
    } else {
        0.0
    };
    (grid[i] + shift * (grid[i + 1] - grid[i]), r)
}

/// Aligns the tracker's `angle` (per frame, at the tracker's `tau_s`) with the DAQ's `signal`
/// (sampled every `dt_s` from 0).
///
/// # Errors
/// [`AlignError`].
pub fn auto(
    tau_s: &[f64],
    angle: &[Option<f64>],
    signal: &[f64],
    dt_s: f64,
) -> Result<Alignment, AlignError> {
    let all = 0..tau_s.len();
    let coarse: Vec<f64> = {
        let steps = (MAX_OFFSET_S / COARSE_STEP_S).round() as i64;
        (-steps..=steps).map(|k| k as f64 * COARSE_STEP_S).collect()
    };
    let (sparse_tau, sparse_angle) = every_kth(tau_s, angle, COARSE_FRAMES);
    let coarse_r: Vec<f64> = coarse
        .iter()
        .map(|&lag| {
            let frames = 0..sparse_tau.len();
            correlation(&sparse_tau, &sparse_angle, frames, signal, dt_s, &|_| lag)
        })
        .collect();
    // The sign of the sensor's response (a sensor on −y_s reads less when the joint bends).
    let (up, r_up) = peak(&coarse, &coarse_r, 1.0);
    let (down, r_down) = peak(&coarse, &coarse_r, -1.0);
    let (lag0, r0, sign) = if r_up >= r_down {
        (up, r_up, 1.0)
    } else {
        (down, r_down, -1.0)
    };
    if r0.is_nan() || r0 < MIN_CORRELATION {
        return Err(AlignError::Weak {
            r: r0.max(0.0),
            max_s: MAX_OFFSET_S,
            min: MIN_CORRELATION,
        });
    }
    let step = WINDOW_COARSE_STEP_S.max(dt_s);
    let steps = (WINDOW_SEARCH_S / step).ceil() as i64;
    let first: Vec<f64> = (-steps..=steps).map(|k| lag0 + k as f64 * step).collect();
    let near = (step / dt_s).ceil() as i64;
    let per = tau_s.len() / WINDOWS;
    let mut points = Vec::new();
    for w in 0..WINDOWS {
        let frames = w * per..if w + 1 == WINDOWS {
            tau_s.len()
        } else {
            (w + 1) * per
        };
        let r_w = |lag: f64| correlation(tau_s, angle, frames.clone(), signal, dt_s, &|_| lag);
        let (rough, _) = best_lag(&first, &r_w, sign);
        let fine: Vec<f64> = (-near..=near).map(|k| rough + k as f64 * dt_s).collect();
        let (lag, r) = best_lag(&fine, &r_w, sign);
        if r >= MIN_CORRELATION {
            let centre = frames.clone().map(|k| tau_s[k]).sum::<f64>() / frames.len() as f64;
            points.push((centre, lag));
        }
    }
    if points.len() < MIN_WINDOWS {
        return Err(AlignError::Windows {
            windows: points.len(),
            min: MIN_WINDOWS,
        });
    }
    // lag = offset + drift·τ by least squares, with standard errors.
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let slope = sxy / sxx;
    let offset = my - slope * mx;
    let ss: f64 = points
        .iter()
        .map(|p| (p.1 - offset - slope * p.0).powi(2))
        .sum();
    let sigma2 = if n > 2.0 { ss / (n - 2.0) } else { 0.0 };
    let offset_se = (sigma2 * (1.0 / n + mx * mx / sxx)).sqrt();
    let drift_se = (sigma2 / sxx).sqrt();
    // Then both together on every frame at once: the line through the windows is the start,
    // and a search over a grid of ±REFINE_SPAN standard errors in each, twice, each time
    // around the best point, tightens it (the windows' lags scatter by milliseconds; the whole
    // recording pins the line down further).
    let r_line = |offset: f64, slope: f64| {
        sign * correlation(tau_s, angle, all.clone(), signal, dt_s, &|tau| {
            offset + slope * tau
        })
    };
    let (mut best_offset, mut best_slope) = (offset, slope);
    let (mut half_o, mut half_s) = (
        REFINE_SPAN * offset_se.max(dt_s / 4.0),
        REFINE_SPAN * drift_se.max(1e-6),
    );
    for _ in 0..REFINE_ROUNDS {
        let mut best = (r_line(best_offset, best_slope), best_offset, best_slope);
        for i in -REFINE_STEPS..=REFINE_STEPS {
            for j in -REFINE_STEPS..=REFINE_STEPS {
                let o = best_offset + half_o * f64::from(i) / f64::from(REFINE_STEPS);
                let d = best_slope + half_s * f64::from(j) / f64::from(REFINE_STEPS);
                let r = r_line(o, d);
                if r > best.0 {
                    best = (r, o, d);
                }
            }
        }
        best_offset = best.1;
        best_slope = best.2;
        half_o /= f64::from(REFINE_STEPS);
        half_s /= f64::from(REFINE_STEPS);
    }
    Ok(Alignment {
        offset_s: best_offset,
        drift_ppm: best_slope * 1e6,
        offset_uncertainty_s: offset_se,
        drift_uncertainty_ppm: drift_se * 1e6,
        correlation: sign * r0,
        windows: points.len(),
        lags: points,
    })
}
