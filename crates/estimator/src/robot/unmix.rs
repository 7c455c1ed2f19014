use dlw_geometry::MAX_JOINTS;
use nalgebra::SMatrix;

use super::error::RobotError;

/// Most sensors a robot estimator holds: two per joint (BSN joints carry two).
pub const MAX_SENSORS: usize = 2 * MAX_JOINTS;

/// The condition number a crosstalk matrix may have unless the config says otherwise. The
/// geometric crosstalk of `dlw inspect` is a few percent (issue 33 warns above 5 %), which
/// gives condition numbers near 1 for one sensor per joint and near √2 where a BSN joint's two
/// sensors give it two rows (the test robots measure 1.0-1.5); 10 still admits fitted matrices
/// with crosstalk of order 1, while refusing ones that could turn a 1 % error of the sensors
/// into more than 10 % on the joint angles.
pub const DEFAULT_MAX_CONDITION_NUMBER: f64 = 10.0;

/// Most sweeps of the singular value decomposition of the (at most 16 × 8) crosstalk matrix.
/// It converges in a few dozen; the limit only turns a non-converging one into an error.
const MAX_SVD_ITERATIONS: usize = 10_000;

/// Multiple of `ε·κ·max(M, N)` (κ the condition number) allowed as rounding, in the
/// pseudo-inverse's self-check `P·C = I` and when telling an entry of `P` that is zero in exact
/// arithmetic from one that is not: the SVD is backward stable, so its errors in `P` are a
/// small multiple of that; 64 leaves a margin and still lies far below any crosstalk a sensor
/// can read (`1e-13` for κ = 10).
const ROUNDING_ALLOWANCE: f64 = 64.0;

/// Undoes the crosstalk: the least-squares solution of `a = C·θ`, `θ = C⁺·a`, with the
/// pseudo-inverse `C⁺` computed once, at construction, from the singular value decomposition of
/// `C` (`M` sensors × `N` joints, `M ≥ N`).
///
/// `C` must have full column rank and a condition number `σ_max/σ_min` within the configured
/// limit; `C⁺` is checked against `C⁺·C = I` before it is used. Entries of `C⁺` that are zero to
/// rounding are set to zero, so that a joint's angle (and its flags) depends on exactly the
/// sensors that carry information about it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unmixing {
    joints: usize,
    sensors: usize,
    crosstalk: [[f64; MAX_JOINTS]; MAX_SENSORS],
    pseudo_inverse: [[f64; MAX_SENSORS]; MAX_JOINTS],
    /// Bit `i` of entry `j`: joint `j`'s angle depends on sensor `i`.
    uses: [u16; MAX_JOINTS],
    condition_number: f64,
}

impl Unmixing {
    /// The unmixing of crosstalk matrix `rows` (one row per sensor, its first `joints` entries
    /// used; the caller has checked that every entry is finite).
    ///
    /// # Errors
    /// [`RobotError::TooFewSensors`], [`RobotError::ConditionLimit`],
    /// [`RobotError::RankDeficient`], [`RobotError::IllConditioned`],
    /// [`RobotError::Decomposition`] or [`RobotError::SelfCheck`].
    pub fn new(
        rows: &[[f64; MAX_JOINTS]],
        joints: usize,
        max_condition_number: f64,
    ) -> Result<Self, RobotError> {
        let sensors = rows.len();
        if sensors < joints || joints == 0 {
            return Err(RobotError::TooFewSensors { sensors, joints });
        }
        if !(max_condition_number.is_finite() && max_condition_number >= 1.0) {
            return Err(RobotError::ConditionLimit {
                value: max_condition_number,
            });
        }
        let sensors = sensors.min(MAX_SENSORS);
        let joints = joints.min(MAX_JOINTS);
        // Padded with zeros to the largest size, so one static size serves every robot: the
        // padding adds zero singular values only, below all of C's when C has full rank.
        let mut c = SMatrix::<f64, MAX_SENSORS, MAX_JOINTS>::zeros();
        for (i, row) in rows.iter().take(sensors).enumerate() {
            for j in 0..joints {
                c[(i, j)] = row[j];
            }
        }
        let svd = c
            .try_svd(true, true, f64::EPSILON, MAX_SVD_ITERATIONS)
            .ok_or(RobotError::Decomposition {
                iterations: MAX_SVD_ITERATIONS,
            })?;
        let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
            return Err(RobotError::Decomposition {
                iterations: MAX_SVD_ITERATIONS,
            });
        };
        let sigma = svd.singular_values;
        let (largest, smallest) = (sigma[0], sigma[joints - 1]);
        let threshold = sensors.max(joints) as f64 * f64::EPSILON * largest;
        // Written to refuse a NaN too.
        if smallest.partial_cmp(&threshold) != Some(core::cmp::Ordering::Greater) {
            return Err(RobotError::RankDeficient {
                smallest,
                threshold,
            });
        }
        let condition_number = largest / smallest;
        if condition_number > max_condition_number {
            return Err(RobotError::IllConditioned {
                condition: condition_number,
                limit: max_condition_number,
            });
        }
        let mut out = Self {
            joints,
            sensors,
            crosstalk: [[0.0; MAX_JOINTS]; MAX_SENSORS],
            pseudo_inverse: [[0.0; MAX_SENSORS]; MAX_JOINTS],
            uses: [0; MAX_JOINTS],
            condition_number,
        };
        for (i, row) in rows.iter().take(sensors).enumerate() {
            out.crosstalk[i][..joints].copy_from_slice(&row[..joints]);
        }
        // C⁺ = V·Σ⁻¹·Uᵀ over C's own N singular triplets.
        let mut largest_entry: f64 = 0.0;
        for j in 0..joints {
            for i in 0..sensors {
                let p: f64 = (0..joints)
                    .map(|k| v_t[(k, j)] * u[(i, k)] / sigma[k])
                    .sum();
                out.pseudo_inverse[j][i] = p;
            }
        }
        out.refine();
        for row in &out.pseudo_inverse[..joints] {
            for p in &row[..sensors] {
                largest_entry = largest_entry.max(p.abs());
            }
        }
        let rounding =
            ROUNDING_ALLOWANCE * f64::EPSILON * condition_number * sensors.max(joints) as f64;
        for j in 0..joints {
            for i in 0..sensors {
                if out.pseudo_inverse[j][i].abs() <= rounding * largest_entry {
                    out.pseudo_inverse[j][i] = 0.0;
                } else {
                    out.uses[j] |= 1 << i;
                }
            }
        }
        let error = out.self_check_error();
        if error.is_nan() || error > rounding {
            return Err(RobotError::SelfCheck {
                error,
                limit: rounding,
            });
        }
        Ok(out)
    }

    /// One Newton-Schulz step, `P ← (2I − P·C)·P`: with `R = I − P·C` the new residual is
    /// `R²`, so the SVD's rounding (which grows with the condition number) drops to that of
    /// this product. The rows of `P` stay combinations of its rows, in the range of `C`, so `P`
    /// stays the pseudo-inverse rather than another left inverse.
    fn refine(&mut self) {
        let (n, m) = (self.joints, self.sensors);
        let mut residual = [[0.0; MAX_JOINTS]; MAX_JOINTS];
        for (j, row) in residual.iter_mut().enumerate().take(n) {
            for (k, r) in row.iter_mut().enumerate().take(n) {
                let product: f64 = (0..m)
                    .map(|i| self.pseudo_inverse[j][i] * self.crosstalk[i][k])
                    .sum();
                *r = if j == k { 1.0 } else { 0.0 } - product;
            }
        }
        let previous = self.pseudo_inverse;
        for (j, row) in self.pseudo_inverse.iter_mut().enumerate().take(n) {
            for (i, p) in row.iter_mut().enumerate().take(m) {
                *p += (0..n).map(|k| residual[j][k] * previous[k][i]).sum::<f64>();
            }
        }
    }

    /// `max |C⁺·C − I|`.
    fn self_check_error(&self) -> f64 {
        let mut worst: f64 = 0.0;
        for j in 0..self.joints {
            for k in 0..self.joints {
                let product: f64 = (0..self.sensors)
                    .map(|i| self.pseudo_inverse[j][i] * self.crosstalk[i][k])
                    .sum();
                let identity = if j == k { 1.0 } else { 0.0 };
                worst = worst.max((product - identity).abs());
            }
        }
        worst
    }

    /// Joints `N`.
    pub fn joint_count(&self) -> usize {
        self.joints
    }

    /// Sensors `M`.
    pub fn sensor_count(&self) -> usize {
        self.sensors
    }

    /// The condition number `σ_max/σ_min` of `C`: the most by which a relative error of the
    /// sensors' mixed angles can grow in the joint angles.
    pub fn condition_number(&self) -> f64 {
        self.condition_number
    }

    /// Row `sensor` (0-based) of `C`: how much of each joint's angle that sensor reads.
    pub fn crosstalk(&self, sensor: usize) -> &[f64] {
        &self.crosstalk[sensor][..self.joints]
    }

    /// Row `joint` (0-based) of `C⁺`: the weight of each sensor's mixed angle in that joint's.
    pub fn pseudo_inverse(&self, joint: usize) -> &[f64] {
        &self.pseudo_inverse[joint][..self.sensors]
    }

    /// Whether joint `joint`'s angle depends on sensor `sensor` (both 0-based).
    pub fn depends_on(&self, joint: usize, sensor: usize) -> bool {
        self.uses[joint] & (1 << sensor) != 0
    }

    /// The sensors (bit `i` for sensor `i`, 0-based) joint `joint`'s angle depends on.
    #[inline]
    pub(crate) fn uses(&self, joint: usize) -> u16 {
        self.uses[joint]
    }

    /// `θ = C⁺·a` for the sensors' mixed angles `mixed` (at least `M` entries), into the first
    /// `N` entries of `angles`.
    #[inline]
    pub fn solve(&self, mixed: &[f64], angles: &mut [f64]) {
        let mixed = &mixed[..self.sensors];
        for (angle, row) in angles.iter_mut().zip(&self.pseudo_inverse[..self.joints]) {
            *angle = row[..self.sensors]
                .iter()
                .zip(mixed)
                .map(|(p, a)| p * a)
                .sum();
        }
    }

    /// The root mean square of the least-squares residual `a − C·θ` (rad): 0 (to rounding)
    /// when there are as many sensors as joints; with more, how far the sensors disagree.
    #[inline]
    pub fn residual_rms(&self, mixed: &[f64], angles: &[f64]) -> f64 {
        let angles = &angles[..self.joints];
        let sum: f64 = self.crosstalk[..self.sensors]
            .iter()
            .zip(mixed)
            .map(|(row, a)| {
                let r = a - row[..self.joints]
                    .iter()
                    .zip(angles)
                    .map(|(c, t)| c * t)
                    .sum::<f64>();
                r * r
            })
            .sum();
        libm::sqrt(sum / self.sensors as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn rows(c: &[&[f64]]) -> [[f64; MAX_JOINTS]; MAX_SENSORS] {
        let mut out = [[0.0; MAX_JOINTS]; MAX_SENSORS];
        for (i, r) in c.iter().enumerate() {
            out[i][..r.len()].copy_from_slice(r);
        }
        out
    }

    /// Three UAN joints whose distal sensors' leads cross the proximal joints: C is upper
    /// triangular with a unit diagonal, so is C⁻¹, worked by hand, with exact zeros below.
    #[test]
    fn upper_triangular_crosstalk_inverts_exactly() {
        let (a, b, c) = (0.04, -0.02, 0.03);
        let m = rows(&[&[1.0, a, b], &[0.0, 1.0, c], &[0.0, 0.0, 1.0]]);
        let unmix = Unmixing::new(&m[..3], 3, DEFAULT_MAX_CONDITION_NUMBER).unwrap();
        let want = [[1.0, -a, a * c - b], [0.0, 1.0, -c], [0.0, 0.0, 1.0]];
        for (j, row) in want.iter().enumerate() {
            for (i, w) in row.iter().enumerate() {
                assert_relative_eq!(unmix.pseudo_inverse(j)[i], *w, epsilon = 1e-14);
            }
        }
        assert_eq!(&unmix.pseudo_inverse(2)[..2], &[0.0, 0.0], "exact zeros");
        assert!(unmix.depends_on(0, 2) && !unmix.depends_on(2, 0));
        let theta = [0.3, -0.2, 0.5];
        let mixed: [f64; 3] = core::array::from_fn(|i| (0..3).map(|j| m[i][j] * theta[j]).sum());
        let mut back = [0.0; 3];
        unmix.solve(&mixed, &mut back);
        for (b, t) in back.iter().zip(theta) {
            assert_relative_eq!(*b, t, epsilon = 1e-15);
        }
        assert!(unmix.residual_rms(&mixed, &back) < 1e-15);
        assert!(unmix.condition_number() > 1.0 && unmix.condition_number() < 1.2);
    }

    /// Two sensors of one joint (a BSN pair) and one of another: least squares averages the
    /// pair, and the residual is their disagreement.
    #[test]
    fn least_squares_averages_a_pair() {
        let m = rows(&[&[1.0, 0.0], &[1.0, 0.0], &[0.0, 1.0]]);
        let unmix = Unmixing::new(&m[..3], 2, 10.0).unwrap();
        assert_eq!(unmix.pseudo_inverse(0).len(), 3);
        let mut theta = [0.0; 2];
        unmix.solve(&[0.2, 0.4, -0.1], &mut theta);
        assert_relative_eq!(theta[0], 0.3, epsilon = 1e-15);
        assert_relative_eq!(theta[1], -0.1, epsilon = 1e-15);
        // Residuals ±0.1 and 0: RMS = 0.1·sqrt(2/3).
        assert_relative_eq!(
            unmix.residual_rms(&[0.2, 0.4, -0.1], &theta),
            0.1 * libm::sqrt(2.0 / 3.0),
            epsilon = 1e-15
        );
        assert!(!unmix.depends_on(1, 0) && unmix.depends_on(0, 1));
    }

    #[test]
    fn refuses_rank_deficient_and_ill_conditioned_matrices() {
        // Both sensors read the same mix of both joints.
        let same = rows(&[&[1.0, 0.5], &[1.0, 0.5]]);
        assert!(matches!(
            Unmixing::new(&same[..2], 2, 10.0),
            Err(RobotError::RankDeficient { .. })
        ));
        // Nearly the same: condition number about 2/δ.
        let near = rows(&[&[1.0, 1.0], &[1.0, 1.0 + 1e-3]]);
        match Unmixing::new(&near[..2], 2, 10.0) {
            Err(RobotError::IllConditioned { condition, limit }) => {
                assert!(condition > 3000.0 && condition < 5000.0, "{condition}");
                assert_eq!(limit, 10.0);
            }
            other => panic!("{other:?}"),
        }
        let ok = Unmixing::new(&near[..2], 2, 1e4);
        assert!(ok.is_ok(), "{ok:?}");
        assert_eq!(
            Unmixing::new(&near[..1], 2, 10.0),
            Err(RobotError::TooFewSensors {
                sensors: 1,
                joints: 2
            })
        );
        assert_eq!(
            Unmixing::new(&near[..2], 2, 0.5),
            Err(RobotError::ConditionLimit { value: 0.5 })
        );
    }
}
