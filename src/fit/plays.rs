//! The play-operator models `dlw` fits, in the runtime crate's form.
//!
//! Both of the runtime crate's PI models are a weighted sum of plays driven by saturating
//! tanh curves of `x = ε − ε_c`:
//!
//! `yᵢ(t) = max(L(t) − ρᵢ, min(U(t) + ρᵢ, yᵢ(t−1)))`, `R(t) = Σᵢ Pᵢ·yᵢ(t) + R_c`
//!
//! - generalized PI (Eqs. 8-11): `L = U = ν`, the loading tanh `a₁..a₄` while the strain does
//!   not fall and the unloading tanh `a₅..a₈` while it falls (Eq. 10);
//! - continuous PI: `L = γ_l` (`a₁..a₄`) and `U = γ_r` (`a₅..a₈`) at every sample.
//!
//! Every play starts at `M₀ = L(x(0))`, relaxed at the first sample's input.
//!
//! # Parameters
//! The vector the optimizer moves, `θ = [ln a₁, ln a₂, a₃, a₄, ln a₅, ln a₆, a₇, a₈, u₂ … u_N]`:
//!
//! - `a₁, a₂, a₅, a₆ > 0` through their logarithms, so each branch rises with strain;
//! - the weights are normalized by `P₁ = 1`. That removes the model's scale degeneracy
//!   (scaling `a₁, a₄, a₅, a₈` and the radii by `k` and the weights by `1/k` changes nothing);
//! - generalized PI: the partial sums `Sᵢ = P₁ + … + Pᵢ` are `S₁ = 1`, `Sᵢ = m + e^{uᵢ}`, so every
//!   `Sᵢ > m` whatever the optimizer does and the inverse (Eq. 13, `Qᵢ = −Pᵢ/(SᵢSᵢ₋₁)`) exists
//!   with a margin `m` ([`PARTIAL_SUM_MARGIN`]). Single weights may still be negative;
//! - continuous PI: `Pᵢ = e^{uᵢ} > 0`, as its numerical inverse requires.
//!
//! The radii are fixed while the optimizer runs.

use dlw_estimator::MAX_PLAYS;

/// The smallest partial sum of generalized-PI weights, relative to `P₁ = 1`: the slope of the
/// fitted loading curve never falls under 5 % of its initial slope, so the inverse's slopes
/// `1/Sᵢ` stay under 20 times its initial one.
pub const PARTIAL_SUM_MARGIN: f64 = 0.05;

/// The smallest continuous-PI weight, relative to `P₁ = 1`: every play keeps a share of the
/// loop, as the continuous model's numerical inverse requires `Pᵢ > 0`.
pub const CONTINUOUS_WEIGHT_FLOOR: f64 = 1e-4;

/// Parameters of the two tanh curves in `θ`.
pub const BRANCH_PARAMS: usize = 8;

/// Which play model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlayKind {
    /// The paper's generalized PI with a direction-switched input.
    Generalized,
    /// The continuous PI with envelopes inside the plays.
    Continuous,
}

/// A play model with fixed radii and centre, ready to evaluate at any `θ`.
#[derive(Debug, Clone, PartialEq)]
pub struct PlayModel {
    /// Generalized or continuous.
    pub kind: PlayKind,
    /// Radii `ρᵢ`, `ρ₁ = 0`, increasing.
    pub radii: Vec<f64>,
    /// `ε_c` (fraction).
    pub center_strain: f64,
    /// `R_c` (Ω).
    pub center_ohm: f64,
}

/// The model's values from `θ`.
#[derive(Debug, Clone, PartialEq)]
pub struct Unpacked {
    /// `[a₁, a₂, a₃, a₄]`.
    pub loading: [f64; 4],
    /// `[a₅, a₆, a₇, a₈]`.
    pub unloading: [f64; 4],
    /// `Pᵢ`.
    pub weights: Vec<f64>,
}

impl PlayModel {
    /// Number of plays `N`.
    pub fn order(&self) -> usize {
        self.radii.len()
    }

    /// Length of `θ`: 8 branch parameters and `N − 1` weight parameters.
    pub fn parameter_count(&self) -> usize {
        BRANCH_PARAMS + self.order() - 1
    }

    /// The branches and weights `θ` stands for.
    pub fn unpack(&self, theta: &[f64]) -> Unpacked {
        let b = |o: usize| {
            [
                theta[o].exp(),
                theta[o + 1].exp(),
                theta[o + 2],
                theta[o + 3],
            ]
        };
        let n = self.order();
        let mut weights = vec![0.0; n];
        weights[0] = 1.0;
        match self.kind {
            PlayKind::Generalized => {
                let mut previous = 1.0;
                for (i, w) in weights.iter_mut().enumerate().skip(1) {
                    let s = PARTIAL_SUM_MARGIN + theta[BRANCH_PARAMS + i - 1].exp();
                    *w = s - previous;
                    previous = s;
                }
            }
            PlayKind::Continuous => {
                for (i, w) in weights.iter_mut().enumerate().skip(1) {
                    *w = theta[BRANCH_PARAMS + i - 1].exp();
                }
            }
        }
        Unpacked {
            loading: b(0),
            unloading: b(4),
            weights,
        }
    }

    /// `θ` for these branches and weights (`P₁` must be 1; the inverse of [`PlayModel::unpack`]).
    /// Generalized partial sums under the margin, or continuous weights that are not positive,
    /// are raised to just above their bound.
    pub fn pack(&self, loading: [f64; 4], unloading: [f64; 4], weights: &[f64]) -> Vec<f64> {
        let mut theta = vec![
            loading[0].ln(),
            loading[1].ln(),
            loading[2],
            loading[3],
            unloading[0].ln(),
            unloading[1].ln(),
            unloading[2],
            unloading[3],
        ];
        let mut partial = weights[0];
        for &w in &weights[1..] {
            match self.kind {
                PlayKind::Generalized => {
                    partial += w;
                    let above = (partial - PARTIAL_SUM_MARGIN).max(0.5 * PARTIAL_SUM_MARGIN);
                    partial = PARTIAL_SUM_MARGIN + above;
                    theta.push(above.ln());
                }
                PlayKind::Continuous => theta.push(w.max(CONTINUOUS_WEIGHT_FLOOR).ln()),
            }
        }
        theta
    }

    /// Evaluates the model at `θ` over `strain`: writes `R(t)` into `ohm`.
    pub fn evaluate(&self, theta: &[f64], strain: &[f64], ohm: &mut [f64]) {
        self.evaluate_directed(theta, strain, None, ohm);
    }

    /// [`PlayModel::evaluate`] with the generalized model's direction given per sample
    /// (`falling[t]`: the unloading branch) instead of taken from consecutive samples of
    /// `strain`: for decimated samples of a signal whose direction is known at the full rate.
    pub fn evaluate_directed(
        &self,
        theta: &[f64],
        strain: &[f64],
        falling: Option<&[bool]>,
        ohm: &mut [f64],
    ) {
        let u = self.unpack(theta);
        let n = self.order();
        let mut y = [0.0f64; MAX_PLAYS];
        let mut previous = f64::NEG_INFINITY;
        for (t, &e) in strain.iter().enumerate() {
            let x = e - self.center_strain;
            let (l, up) = match self.kind {
                PlayKind::Generalized => {
                    let loading = falling.map_or(e >= previous, |f| !f[t]);
                    let v = if loading {
                        branch(&u.loading, x)
                    } else {
                        branch(&u.unloading, x)
                    };
                    (v, v)
                }
                PlayKind::Continuous => (branch(&u.loading, x), branch(&u.unloading, x)),
            };
            previous = e;
            if t == 0 {
                y[..n].fill(l);
            }
            let mut sum = 0.0;
            for ((yi, r), w) in y[..n].iter_mut().zip(&self.radii).zip(&u.weights) {
                let (lower, upper) = (l - r, up + r);
                let held = if *yi < upper { *yi } else { upper };
                if lower > held {
                    *yi = lower;
                } else if upper < *yi {
                    *yi = upper;
                }
                sum += w * *yi;
            }
            ohm[t] = sum + self.center_ohm;
        }
    }
}

/// `a·tanh(b·x + c) + d`.
#[inline]
pub(super) fn branch(p: &[f64; 4], x: f64) -> f64 {
    let [a, b, c, d] = *p;
    a * (b * x + c).tanh() + d
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use dlw_estimator::{Coeffs, ContinuousPi, ContinuousPiConfig, GeneralizedPi, PiConfig};

    fn strain() -> Vec<f64> {
        (0..600)
            .map(|i| {
                let t = i as f64 / 100.0;
                0.006 + 0.006 * (t * 1.3).sin() * (0.6 + 0.4 * (t * 0.37).cos())
            })
            .collect()
    }

    fn model(kind: PlayKind) -> (PlayModel, Vec<f64>) {
        let m = PlayModel {
            kind,
            radii: (0..6).map(|i| i as f64 * 2e3).collect(),
            center_strain: 0.004,
            center_ohm: 224e3,
        };
        let theta = m.pack(
            [26e3, 190.0, 0.1, 300.0],
            [24e3, 210.0, -0.05, -200.0],
            &[1.0, 0.2, -0.1, 0.3, 0.05, 0.1],
        );
        (m, theta)
    }

    /// The fit's model is the runtime crate's: same resistance, sample for sample.
    #[test]
    fn values_match_the_runtime_crates_forward_models() {
        let e = strain();
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let (m, theta) = model(kind);
            let u = m.unpack(&theta);
            let mut r = vec![0.0; e.len()];
            m.evaluate(&theta, &e, &mut r);
            let x0 = e[0] - m.center_strain;
            let weights = Coeffs::from_slice("weights", &u.weights).unwrap();
            let radii = Coeffs::from_slice("radii", &m.radii).unwrap();
            let m0 = u.loading[0] * (u.loading[1] * x0 + u.loading[2]).tanh() + u.loading[3];
            let reference: Vec<f64> = match kind {
                PlayKind::Generalized => {
                    let mut pi = GeneralizedPi::new(&PiConfig {
                        weights,
                        radii,
                        loading_tanh: u.loading,
                        unloading_tanh: u.unloading,
                        center_strain: m.center_strain,
                        center_ohm: m.center_ohm,
                        min_ohm: 0.0,
                        max_ohm: 1e9,
                        min_strain: None,
                        max_strain: None,
                        initial_state: m0,
                    })
                    .unwrap();
                    e.iter().map(|&s| pi.step(s)).collect()
                }
                PlayKind::Continuous => {
                    let mut pi = ContinuousPi::new(&ContinuousPiConfig {
                        weights,
                        radii,
                        loading_envelope: u.loading,
                        unloading_envelope: u.unloading,
                        center_strain: m.center_strain,
                        center_ohm: m.center_ohm,
                        min_strain: -1.0,
                        max_strain: 1.0,
                        strain_tolerance: 1e-12,
                        resistance_tolerance_ohm: 0.0,
                        initial_state: m0,
                    })
                    .unwrap();
                    e.iter().map(|&s| pi.step(s)).collect()
                }
            };
            for (a, b) in r.iter().zip(&reference) {
                assert_relative_eq!(*a, *b, max_relative = 1e-12);
            }
        }
    }

    #[test]
    fn pack_and_unpack_are_inverse() {
        for kind in [PlayKind::Generalized, PlayKind::Continuous] {
            let (m, theta) = model(kind);
            let u = m.unpack(&theta);
            let again = m.pack(u.loading, u.unloading, &u.weights);
            for (a, b) in theta.iter().zip(&again) {
                assert_relative_eq!(*a, *b, epsilon = 1e-12);
            }
        }
    }

    #[test]
    fn partial_sums_keep_their_margin_whatever_theta_is() {
        let (m, mut theta) = model(PlayKind::Generalized);
        for v in theta.iter_mut().skip(BRANCH_PARAMS) {
            *v = -40.0;
        }
        let w = m.unpack(&theta).weights;
        let mut s = 0.0;
        for p in w {
            s += p;
            assert!(s > PARTIAL_SUM_MARGIN * 0.999, "{s}");
        }
    }
}
