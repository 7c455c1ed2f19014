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
    /// The best lag lies at the edge of the range searched.
    #[error("the best lag between the clocks, {lag_s:.2} s, lies at the edge of the ±{max_s} s searched: the clocks may differ by more; pass --max-offset-s {wider} to search wider")]
    Edge {
        /// The lag found (s).
        lag_s: f64,
        /// The range searched (s).
        max_s: f64,
        /// A range that would hold it (s).
        wider: f64,
    },
    /// Most windows' best lags lie at the edge of their search around the whole recording's
    /// lag.
    #[error("{edges} of the {windows} windows that correlate do so best at the edge of the ±{half_s:.2} s searched around the whole recording's lag of {whole_s:.3} s (the window around tracker time {centre_s:.1} s at {lag_s:.3} s): over the recording the lag moves by more than a drift of ±{MAX_DRIFT_PPM} ppm allows (did the DAQ or the tracker lose samples, or are these files of two runs?)")]
    WindowEdge {
        /// Windows at the edge.
        edges: usize,
        /// Windows that correlate.
        windows: usize,
        /// The window's centre (s of tracker time).
        centre_s: f64,
        /// Its best lag (s).
        lag_s: f64,
        /// The half-width searched (s).
        half_s: f64,
        /// The whole recording's lag (s).
        whole_s: f64,
    },
    /// A window correlates best the other way round.
    #[error("the window around tracker time {centre_s:.1} s correlates best at r = {r:.2} (negative), against {whole_r:+.2} over the whole recording: sensor 1 answers the angle the other way there (a channel re-wired or swapped mid-recording?), so no one alignment fits")]
    Negative {
        /// The window's centre (s of tracker time).
        centre_s: f64,
        /// Its best correlation, signed as the whole recording's.
        r: f64,
        /// The whole recording's.
        whole_r: f64,
    },
    /// The drift found is beyond any clock's.
    #[error("the clocks' drift comes out {ppm:.0} ppm (± {se_ppm:.0}); more than ±{MAX_DRIFT_PPM} ppm is not a clock's drift: are both files of one run, and is the DAQ's rate right?")]
    Drift {
        /// The drift found (ppm).
        ppm: f64,
        /// Its standard error (ppm).
        se_ppm: f64,
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

/// The largest clock offset searched by default (s); `--max-offset-s` widens it.
pub const MAX_OFFSET_S: f64 = 10.0;
/// The largest drift accepted (ppm), as for a sync pulse: a quartz clock drifts tens of ppm,
/// a cheap one a few hundred; beyond this, the lags are not a clock's.
pub const MAX_DRIFT_PPM: f64 = super::sync::MAX_DRIFT_PPM;
/// A step of the DAQ's time column longer than this many sample periods is a jump: no value is
/// interpolated across it.
pub const JUMP_PERIODS: f64 = 1.5;
/// The coarse grid of the whole-recording search (s).
pub const COARSE_STEP_S: f64 = 0.01;
/// How far around the coarse lag each window searches, at least (s); over a long recording,
/// the half-width grows to 1.5 times what a drift of [`MAX_DRIFT_PPM`] moves the lag over half
/// the recording, so that only a drift beyond the limit puts a window's lag at the edge.
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

/// A DAQ signal: its samples at the times of the DAQ's time column, `period_s` apart for the
/// most part.
#[derive(Debug, Clone, Copy)]
pub struct Signal<'a> {
    /// Each sample's time (s of DAQ time), increasing.
    pub time_s: &'a [f64],
    /// The samples.
    pub values: &'a [f64],
    /// The sample period (s): the time column's median step.
    pub period_s: f64,
}

impl Signal<'_> {
    /// The signal at DAQ time `t`, linearly between the samples around it, found by the time
    /// column (not by counting samples, so an uneven clock is read as it is); `None` outside
    /// the samples or across a step longer than [`JUMP_PERIODS`] periods.
    pub fn at(&self, t: f64) -> Option<f64> {
        let time = self.time_s;
        let n = time.len().min(self.values.len());
        if n < 2 || !(t >= time[0] && t <= time[n - 1]) {
            return None;
        }
        // Where an even clock puts it, then a few steps; a binary search if that fails.
        let guess = ((t - time[0]) / self.period_s) as usize;
        let mut i = guess.min(n - 2);
        for _ in 0..4 {
            if time[i] > t && i > 0 {
                i -= 1;
            } else if time[i + 1] < t && i + 2 < n {
                i += 1;
            } else {
                break;
            }
        }
        if !(time[i] <= t && t <= time[i + 1]) {
            i = time[..n].partition_point(|&x| x <= t).clamp(1, n - 1) - 1;
        }
        let (t0, t1) = (time[i], time[i + 1]);
        if t1 - t0 > JUMP_PERIODS * self.period_s {
            return None;
        }
        let f = (t - t0) / (t1 - t0);
        Some(self.values[i] * (1.0 - f) + self.values[i + 1] * f)
    }
}

/// How well the signal at `τ + lag` explains the angle frames in `frames`: the square root of
/// the R² of the angle regressed on the signal and its square, signed by the linear term's
/// direction. A quadratic takes up the divider's and the sensor's curvature, which would
/// otherwise bias the lag of best plain correlation by milliseconds.
fn correlation(
    tau_s: &[f64],
    angle: &[Option<f64>],
    frames: std::ops::Range<usize>,
    signal: &Signal<'_>,
    lag_s: &dyn Fn(f64) -> f64,
) -> f64 {
    // Moments about the first point, for conditioning.
    let mut m = [[0.0_f64; 3]; 3];
    let mut b = [0.0_f64; 3];
    let (mut n, mut sy, mut syy) = (0.0, 0.0, 0.0);
    let mut centre = None;
    for k in frames {
        let (Some(y), Some(x)) = (angle[k], signal.at(tau_s[k] + lag_s(tau_s[k]))) else {
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
pub(crate) fn solve3(m: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
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

/// Aligns the tracker's `angle` (per frame, at the tracker's `tau_s`) with the DAQ's `signal`,
/// searching lags within ±`max_offset_s`.
///
/// # Errors
/// [`AlignError`]: no lag correlates, the best lag at the edge of the search (overall or in a
/// window), a window that correlates the other way, a drift beyond [`MAX_DRIFT_PPM`], too few
/// windows.
pub fn auto(
    tau_s: &[f64],
    angle: &[Option<f64>],
    signal: &Signal<'_>,
    max_offset_s: f64,
) -> Result<Alignment, AlignError> {
    let search = Search {
        tau_s,
        angle,
        signal,
    };
    let whole = search.whole(max_offset_s)?;
    let windows = search.windows(&whole)?;
    let line = Line::through(&windows.points);
    let (offset, slope) = search.refine(&whole, &windows, &line);
    // Only the final drift is held to the limit: on a short recording the windows' line is
    // loose (±2300 ppm on 60 s) and the fit on every frame pins it.
    if (slope * 1e6).abs() > MAX_DRIFT_PPM {
        return Err(AlignError::Drift {
            ppm: slope * 1e6,
            se_ppm: line.drift_se * 1e6,
        });
    }
    Ok(Alignment {
        offset_s: offset,
        drift_ppm: slope * 1e6,
        offset_uncertainty_s: line.offset_se,
        drift_uncertainty_ppm: line.drift_se * 1e6,
        correlation: whole.sign * whole.r,
        windows: windows.points.len(),
        lags: windows.points,
    })
}

/// The search of [`auto`]: the tracker's angle against the DAQ's signal.
struct Search<'a> {
    /// Each frame's tracker time (s).
    tau_s: &'a [f64],
    /// Each frame's angle.
    angle: &'a [Option<f64>],
    /// The DAQ's signal.
    signal: &'a Signal<'a>,
}

/// The whole recording's lag, on the coarse grid.
struct WholeLag {
    /// The lag (s).
    lag_s: f64,
    /// Its correlation, signed as the sensor's response (`sign·r`).
    r: f64,
    /// The sign of the sensor's response.
    sign: f64,
}

/// The windows' lags.
struct WindowLags {
    /// The frames that fall on the DAQ's samples at the whole recording's lag.
    frames: std::ops::Range<usize>,
    /// Each window's centre (s of tracker time) and lag (s).
    points: Vec<(f64, f64)>,
}

/// `lag = offset + slope·τ` through the windows' lags by least squares, with standard errors.
struct Line {
    /// The intercept (s).
    offset: f64,
    /// The slope.
    slope: f64,
    /// The offset's standard error (s).
    offset_se: f64,
    /// The slope's standard error.
    drift_se: f64,
}

impl Line {
    /// The least-squares line through `points` (`τ`, lag).
    fn through(points: &[(f64, f64)]) -> Line {
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
        Line {
            offset,
            slope,
            offset_se: (sigma2 * (1.0 / n + mx * mx / sxx)).sqrt(),
            drift_se: (sigma2 / sxx).sqrt(),
        }
    }
}

impl Search<'_> {
    /// The correlation over `frames` with the signal at `τ + lag_s(τ)`.
    fn r(&self, frames: std::ops::Range<usize>, lag_s: &dyn Fn(f64) -> f64) -> f64 {
        correlation(self.tau_s, self.angle, frames, self.signal, lag_s)
    }

    /// The whole recording's lag on a coarse grid over at most [`COARSE_FRAMES`] frames, and
    /// the sign of the sensor's response.
    ///
    /// # Errors
    /// [`AlignError::Weak`], [`AlignError::Edge`].
    fn whole(&self, max_offset_s: f64) -> Result<WholeLag, AlignError> {
        let coarse: Vec<f64> = {
            let steps = (max_offset_s / COARSE_STEP_S).round() as i64;
            (-steps..=steps).map(|k| k as f64 * COARSE_STEP_S).collect()
        };
        let (sparse_tau, sparse_angle) = every_kth(self.tau_s, self.angle, COARSE_FRAMES);
        let coarse_r: Vec<f64> = coarse
            .iter()
            .map(|&lag| {
                let frames = 0..sparse_tau.len();
                correlation(&sparse_tau, &sparse_angle, frames, self.signal, &|_| lag)
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
                max_s: max_offset_s,
                min: MIN_CORRELATION,
            });
        }
        if lag0.abs() > max_offset_s - 1.5 * COARSE_STEP_S {
            return Err(AlignError::Edge {
                lag_s: lag0,
                max_s: max_offset_s,
                wider: (2.0 * max_offset_s).max(lag0.abs().ceil() + 10.0),
            });
        }
        Ok(WholeLag {
            lag_s: lag0,
            r: r0,
            sign,
        })
    }

    /// The frames that fall on the DAQ's samples at the whole recording's lag.
    fn frames_inside(&self, lag0: f64) -> std::ops::Range<usize> {
        let time_s = self.signal.time_s;
        let (t_first, t_last) = (time_s[0], time_s[time_s.len() - 1]);
        let inside: Vec<usize> = (0..self.tau_s.len())
            .filter(|&k| (t_first..=t_last).contains(&(self.tau_s[k] + lag0)))
            .collect();
        match (inside.first(), inside.last()) {
            (Some(&lo), Some(&hi)) => lo..hi + 1,
            _ => 0..0,
        }
    }

    /// Each of [`WINDOWS`] windows' lag, searched around the whole recording's: first on a
    /// grid of [`WINDOW_COARSE_STEP_S`], then on the DAQ's sample grid around its best.
    ///
    /// # Errors
    /// [`AlignError::Negative`], [`AlignError::WindowEdge`], [`AlignError::Windows`].
    fn windows(&self, whole: &WholeLag) -> Result<WindowLags, AlignError> {
        let (lag0, sign) = (whole.lag_s, whole.sign);
        let dt_s = self.signal.period_s;
        let std::ops::Range { start: lo, end: hi } = self.frames_inside(lag0);
        let span_s = if hi > lo {
            self.tau_s[hi - 1] - self.tau_s[lo]
        } else {
            0.0
        };
        let half_s = WINDOW_SEARCH_S.max(1.5 * MAX_DRIFT_PPM * 1e-6 * span_s / 2.0);
        let step = WINDOW_COARSE_STEP_S.max(dt_s);
        let steps = (half_s / step).ceil() as i64;
        let first: Vec<f64> = (-steps..=steps).map(|k| lag0 + k as f64 * step).collect();
        let near = (step / dt_s).ceil() as i64;
        let per = (hi - lo) / WINDOWS;
        let mut points = Vec::new();
        let mut edges = Vec::new();
        for w in 0..WINDOWS {
            let frames = lo + w * per..if w + 1 == WINDOWS {
                hi
            } else {
                lo + (w + 1) * per
            };
            if frames.is_empty() {
                continue;
            }
            let centre = frames.clone().map(|k| self.tau_s[k]).sum::<f64>() / frames.len() as f64;
            let r_w = |lag: f64| self.r(frames.clone(), &|_| lag);
            let rs: Vec<f64> = first.iter().map(|&l| r_w(l)).collect();
            let (rough, r_rough) = peak(&first, &rs, sign);
            let (_, r_other) = peak(&first, &rs, -sign);
            if r_other >= MIN_CORRELATION && r_other > r_rough {
                return Err(AlignError::Negative {
                    centre_s: centre,
                    r: -r_other,
                    whole_r: whole.r,
                });
            }
            if r_rough < MIN_CORRELATION {
                continue;
            }
            if (rough - lag0).abs() > half_s - 0.5 * step {
                // A window whose best lag is at the edge of its search is left out, as one that
                // does not correlate: a monotonic stretch correlates at any lag. Most windows at
                // the edge is a refusal (below).
                edges.push((centre, rough));
                continue;
            }
            let fine: Vec<f64> = (-near..=near).map(|k| rough + k as f64 * dt_s).collect();
            let rs: Vec<f64> = fine.iter().map(|&l| r_w(l)).collect();
            let (lag, r) = peak(&fine, &rs, sign);
            if r >= MIN_CORRELATION {
                points.push((centre, lag));
            }
        }
        if edges.len() > points.len() {
            let (centre_s, lag_s) = edges[edges.len() / 2];
            return Err(AlignError::WindowEdge {
                centre_s,
                lag_s,
                half_s,
                whole_s: lag0,
                edges: edges.len(),
                windows: edges.len() + points.len(),
            });
        }
        if points.len() < MIN_WINDOWS {
            return Err(AlignError::Windows {
                windows: points.len(),
                min: MIN_WINDOWS,
            });
        }
        Ok(WindowLags {
            frames: lo..hi,
            points,
        })
    }

    /// The offset and slope that correlate best on every frame at once: the line through the
    /// windows is the start, and a search over a grid of ±[`REFINE_SPAN`] standard errors in
    /// each, [`REFINE_ROUNDS`] times, each time around the best point, tightens it (the
    /// windows' lags scatter by milliseconds; the whole recording pins the line down further).
    fn refine(&self, whole: &WholeLag, windows: &WindowLags, line: &Line) -> (f64, f64) {
        let r_line = |offset: f64, slope: f64| {
            whole.sign * self.r(windows.frames.clone(), &|tau| offset + slope * tau)
        };
        let (mut best_offset, mut best_slope) = (line.offset, line.slope);
        let (mut half_o, mut half_s) = (
            REFINE_SPAN * line.offset_se.max(self.signal.period_s / 4.0),
            REFINE_SPAN * line.drift_se.max(1e-6),
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
        (best_offset, best_slope)
    }
}
