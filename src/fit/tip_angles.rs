//! A robot's joint angles from a tracked tip alone (issue 34 §4: `dlw fit --design ROBOT REC`
//! when the recording has `tip_x/y/z_mm` but no `angleK_deg`), by inverse kinematics through
//! the base frame's kinematics ([`Kinematics`], `docs/robot-runtime.md`), each angle checked
//! before the fit may use it.
//!
//! # The robot
//! Refused before any sample is read: more than [`MAX_TIP_JOINTS`] joints (the tip's 3
//! coordinates cannot hold more angles), and two joints that bend in one plane. At the straight
//! pose a joint moves the tip, to first order, sideways along `−y_j` (the tip's height along `z`
//! is second order in the angle); two joints whose `y_j` are parallel move it along one line,
//! so near straight only their sum is seen, and away from it the tip stays in their common
//! plane, whose 2 coordinates leave an elbow-either-way ambiguity. The test is the singular
//! values of the pair's straight-pose tip Jacobian (columns normalized): the smallest must be
//! at least [`MIN_SINGULAR_RATIO`] of the largest.
//!
//! # Each sample
//! The search covers every joint's physical range, `|θ_j| ≤` the joint's notch-closing angle
//! (both signs, so that no solution the tube could reach is missed). A grid over that box is
//! mapped to tip positions once; since the tip moves by at most `x_end_j` mm per radian of joint
//! `j` (the arc and everything distal of it, `L_j + x_start_j`), every angle set within half a
//! grid step of a grid point puts the tip within `cover = (h/2)·Σ_j x_end_j` of that grid
//! point's tip. So every solution lies in a cell whose grid tip is within `cover + tolerance`
//! of the tracked tip; Levenberg–Marquardt (the `levenberg-marquardt` crate) starts from every
//! grid point there that is a local minimum of the tip's distance among its neighbours (each
//! branch of the map is a valley of that distance with a minimum of its own); two solutions are
//! one when they are no farther apart than the tolerance can move the angles along the
//! direction the tip moves least (`|Δθ|·σ_min(J) ≤ tolerance`). A sample is used only when
//!
//! - some angle set puts the tip within `tolerance = MAX_RESIDUAL_SIGMAS·σ` of the tracked tip
//!   (else it is *off the kinematics*: a tracker glitch, or a frame that is not the base frame),
//! - exactly one does (else it is *ambiguous*: the tip alone cannot say which), and
//! - at that angle set the tip Jacobian's smallest singular value is at least
//!   [`MIN_SINGULAR_RATIO`] of its largest (else it is *not identifiable*: near straight, or
//!   near a fold of the map, some combination of angles barely moves the tip).
//!
//! `σ`, the tracker's noise per coordinate, is measured on the recording itself: the robust
//! spread of the tip's second differences over consecutive valid rows, `MAD·1.4826/√6`
//! (white noise of `σ` gives second differences of `σ·√6`; the motion's own curvature only adds
//! to it, so `σ` is never underestimated), the largest of the three coordinates, at least
//! [`TIP_RESOLUTION_MM`].
//!
//! # The whole recording
//! Refused when more than [`MAX_OFF_KINEMATICS_SHARE`] of the tracked rows are off the
//! kinematics (the tracker is not in the base frame, or not of this robot), and when the
//! tracker's noise, carried through each used row's Jacobian (`σ²·(JᵀJ)⁻¹`), is more than
//! [`MAX_ANGLE_NOISE_SHARE`] of a joint's angle variance over the used rows: a line fitted on
//! noisy angles is flattened by `var(noise)/var(angle)` (errors in variables), which must stay
//! well inside the fit's 1 % on the gauge factor. Whether enough rows remain is the fit's own
//! rule ([`super::robot`]).

use dlw_geometry::{BendingSection, Kinematics};
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra::{DMatrix, DVector, Dyn, Owned, Vector3};
use serde::Serialize;

/// The most joints whose angles the tip's 3 coordinates can determine.
pub const MAX_TIP_JOINTS: usize = 3;
/// The least ratio of the tip Jacobian's smallest singular value to its largest for a sample
/// (or, at the straight pose, a pair of joints) to be identified from the tip: below it the
/// weakest combination of angles moves the tip 10 times less than the strongest, so the
/// tracker's noise along it is magnified 10 times more, and the noise's linear propagation
/// (what the noise check uses) no longer describes the solution near the singularity.
pub const MIN_SINGULAR_RATIO: f64 = 0.1;
/// How far, in the tracker's noise per coordinate, an angle set may put the tip from the
/// tracked tip and still explain it: the residual over 3 coordinates exceeds 5 σ with
/// probability below 2e-5 for Gaussian noise.
pub const MAX_RESIDUAL_SIGMAS: f64 = 5.0;
/// The largest share of tracked rows that no angle set explains before the whole recording is
/// refused: single glitches are dropped, but a tracker in another frame misses everywhere.
pub const MAX_OFF_KINEMATICS_SHARE: f64 = 0.05;
/// The largest share of a joint's angle variance the tracker's propagated noise may make up:
/// it flattens the fitted line by that share, half the fit's 1 % on the gauge factor.
pub const MAX_ANGLE_NOISE_SHARE: f64 = 0.005;
/// The recording's tip resolution (`data.csv` writes 6 decimals, mm): the least noise assumed.
pub const TIP_RESOLUTION_MM: f64 = 1e-6;
/// Grid points per joint for the global search, by the number of joints (1, 2, 3).
const GRID_POINTS: [usize; MAX_TIP_JOINTS] = [121, 41, 21];
/// Below this a joint's angle has not moved (rad), as in the fit's own conditioning.
const STILL_RAD: f64 = 1e-6;
/// The step of the central differences of the tip Jacobian (rad).
const JACOBIAN_STEP_RAD: f64 = 1e-6;

/// Why angles could not be had from the tip.
#[derive(Debug, thiserror::Error)]
pub enum TipAnglesError {
    /// More joints than the tip's coordinates can tell apart.
    #[error("the robot has {joints} joints; the tip's 3 coordinates determine at most {max} joint angles, so the tip alone cannot give them: record each joint's angle")]
    TooManyJoints {
        /// Joints of the robot.
        joints: usize,
        /// [`MAX_TIP_JOINTS`].
        max: usize,
    },
    /// Two joints bend in one plane.
    #[error("joints {first} and {second} bend in one plane (rotations {first_deg}° and {second_deg}°): near straight both move the tip along one line (the smallest singular value of their tip Jacobian is {ratio:.3} of the largest, at least {min} needed), and away from it the tip stays in their plane, so the tip alone cannot tell their angles apart: record each joint's angle")]
    Coplanar {
        /// 1-based joint.
        first: usize,
        /// 1-based joint.
        second: usize,
        /// Its rotation (°).
        first_deg: f64,
        /// Its rotation (°).
        second_deg: f64,
        /// The singular value ratio at the straight pose.
        ratio: f64,
        /// [`MIN_SINGULAR_RATIO`].
        min: f64,
    },
    /// The kinematics refused the robot.
    #[error("the robot's kinematics: {0}")]
    Kinematics(String),
    /// A joint's range is not a positive finite angle.
    #[error("joint {joint}: its angle range {bound_rad} rad is not a positive finite number")]
    Range {
        /// 1-based joint.
        joint: usize,
        /// The bound given (rad).
        bound_rad: f64,
    },
    /// Too many rows off the kinematics.
    #[error("the tracked tip is off the robot's kinematics in {off} of {rows} tracked rows ({share:.1} %, at most {max_percent} % allowed): no joint angles within the joints' ranges put the tip within {tolerance_mm:.3e} mm ({sigmas} times the tracker's noise {noise_mm:.3e} mm); the median miss is {median_mm:.3e} mm. The tip columns must be in the robot's base frame (docs/robot-runtime.md)")]
    OffKinematics {
        /// Rows off the kinematics.
        off: usize,
        /// Tracked rows.
        rows: usize,
        /// Their share (%).
        share: f64,
        /// The largest share allowed (%).
        max_percent: f64,
        /// The tolerance (mm).
        tolerance_mm: f64,
        /// [`MAX_RESIDUAL_SIGMAS`].
        sigmas: f64,
        /// The tracker's noise (mm).
        noise_mm: f64,
        /// The median distance of those rows' tips from the nearest reachable one (mm).
        median_mm: f64,
    },
    /// The tracker's noise makes the angles too noisy to fit a line on.
    #[error("joint {joint}: the tracker's noise ({noise_mm:.3e} mm per coordinate) scatters its angle from the tip by {scatter_deg:.3}° RMS, {share_percent:.2} % of its variance over the used rows (at most {max_percent} %: a line fitted on it would be flattened by that share)")]
    AngleNoise {
        /// 1-based joint.
        joint: usize,
        /// The tracker's noise (mm).
        noise_mm: f64,
        /// The angle's RMS scatter from the noise (°).
        scatter_deg: f64,
        /// Its share of the angle's variance (%).
        share_percent: f64,
        /// [`MAX_ANGLE_NOISE_SHARE`] (%).
        max_percent: f64,
    },
}

/// How the angles were had from the tip; the JSON keys are part of `dlw fit --json`.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct TipAnglesSummary {
    /// Rows whose tip the tracker marked valid.
    pub rows: usize,
    /// Rows whose angles the fit may use.
    pub used: usize,
    /// Rows where the tip Jacobian's smallest singular value was below
    /// `min_singular_ratio` of its largest.
    pub dropped_not_identifiable: usize,
    /// Rows where more than one angle set put the tip within the tolerance.
    pub dropped_ambiguous: usize,
    /// Rows where no angle set put the tip within the tolerance.
    pub dropped_off_kinematics: usize,
    /// The tracker's noise per coordinate, measured on the recording (mm).
    pub tip_noise_mm: f64,
    /// How far an angle set may put the tip from the tracked tip (mm).
    pub tolerance_mm: f64,
    /// [`MIN_SINGULAR_RATIO`].
    pub min_singular_ratio: f64,
    /// The largest `σ_min/σ_max` over the rows one angle set explained; `None` when none did.
    pub largest_singular_ratio: Option<f64>,
    /// Per joint, the tracker's propagated noise as a share of the angle's variance over the
    /// used rows; `None` for a joint that did not move.
    pub angle_noise_share: Vec<Option<f64>>,
}

impl TipAnglesSummary {
    fn see_ratio(&mut self, ratio: f64) {
        let best = self.largest_singular_ratio.get_or_insert(ratio);
        *best = best.max(ratio);
    }
}

/// The joint angles of every row, and which rows the fit may use.
#[derive(Debug, Clone)]
pub struct TipAngles {
    /// Per joint, per row (°). A row not used holds the best angle set found (or the previous
    /// row's), which no analysis may use.
    pub angle_deg: Vec<Vec<f64>>,
    /// Per row: whether its angles may be used.
    pub used: Vec<bool>,
    /// The counts and numbers behind them.
    pub summary: TipAnglesSummary,
}

/// What one sample's search found.
#[derive(Debug, Clone, PartialEq)]
pub enum Solved {
    /// One angle set explains the tip, and it is identifiable.
    Unique {
        /// The angles (rad).
        angles_rad: Vec<f64>,
        /// `σ_min/σ_max` of the tip Jacobian there.
        singular_ratio: f64,
    },
    /// One angle set explains the tip, but the tip barely moves along some combination.
    NotIdentifiable {
        /// The angles (rad).
        angles_rad: Vec<f64>,
        /// `σ_min/σ_max` of the tip Jacobian there.
        singular_ratio: f64,
    },
    /// Several distinct angle sets explain the tip.
    Ambiguous {
        /// The best of them (rad).
        angles_rad: Vec<f64>,
        /// How many.
        count: usize,
    },
    /// None explains the tip.
    OffKinematics {
        /// The best angle set found, if any (rad).
        angles_rad: Option<Vec<f64>>,
        /// Its distance from the tracked tip (mm), infinite when none was found.
        miss_mm: f64,
    },
}

/// The inverse kinematics of a robot from its tip, over its joints' ranges.
#[derive(Debug, Clone)]
pub struct TipSolver {
    kinematics: Kinematics,
    bound_rad: Vec<f64>,
    /// Grid points per joint.
    steps: usize,
    /// The tip at every grid point, joint 1's index fastest.
    grid_tips: Vec<Vector3<f64>>,
    /// How far a solution's tip can be from its cell's grid tip (mm).
    cover_mm: f64,
}

impl TipSolver {
    /// The solver of a robot of `sections` (joint 1 first) whose joints range over
    /// `|θ_j| ≤ bound_rad[j]`.
    ///
    /// # Errors
    /// [`TipAnglesError::TooManyJoints`], [`TipAnglesError::Coplanar`] (the robot cannot be
    /// identified from the tip), [`TipAnglesError::Kinematics`], [`TipAnglesError::Range`].
    pub fn new(sections: &[BendingSection], bound_rad: &[f64]) -> Result<Self, TipAnglesError> {
        let n = sections.len();
        if n > MAX_TIP_JOINTS {
            return Err(TipAnglesError::TooManyJoints {
                joints: n,
                max: MAX_TIP_JOINTS,
            });
        }
        let kinematics =
            Kinematics::new(sections).map_err(|e| TipAnglesError::Kinematics(e.to_string()))?;
        for (j, &b) in bound_rad.iter().enumerate() {
            if !(b.is_finite() && b > 0.0) {
                return Err(TipAnglesError::Range {
                    joint: j + 1,
                    bound_rad: b,
                });
            }
        }
        check_not_coplanar(&kinematics, sections)?;
        let steps = GRID_POINTS[n - 1];
        let step_rad: Vec<f64> = bound_rad
            .iter()
            .map(|b| 2.0 * b / (steps - 1) as f64)
            .collect();
        let mut solver = Self {
            kinematics,
            bound_rad: bound_rad.to_vec(),
            steps,
            grid_tips: Vec::with_capacity(steps.pow(n as u32)),
            cover_mm: sections
                .iter()
                .zip(&step_rad)
                .map(|(s, h)| 0.5 * h * s.x_end_mm)
                .sum(),
        };
        for index in 0..steps.pow(n as u32) {
            let angles = solver.grid_angles(index);
            let tip = solver.tip(&angles).ok_or_else(|| {
                TipAnglesError::Kinematics(format!("no tip at the grid angles {angles:?}"))
            })?;
            solver.grid_tips.push(tip);
        }
        Ok(solver)
    }

    fn joints(&self) -> usize {
        self.bound_rad.len()
    }

    /// The angles of grid point `index` (rad).
    fn grid_angles(&self, mut index: usize) -> Vec<f64> {
        self.bound_rad
            .iter()
            .map(|b| {
                let k = index % self.steps;
                index /= self.steps;
                -b + 2.0 * b * k as f64 / (self.steps - 1) as f64
            })
            .collect()
    }

    fn tip(&self, angles_rad: &[f64]) -> Option<Vector3<f64>> {
        self.kinematics
            .tip(angles_rad)
            .ok()
            .map(|p| Vector3::from(p.position_mm))
    }

    /// The tip Jacobian at `angles_rad` (mm/rad), by central differences.
    pub fn jacobian(&self, angles_rad: &[f64]) -> Option<DMatrix<f64>> {
        jacobian(&self.kinematics, angles_rad)
    }

    /// Every distinct angle set within the joints' ranges that puts the tip within
    /// `tolerance_mm` of `tip_mm`, and the sample's verdict.
    pub fn solve(&self, tip_mm: [f64; 3], tolerance_mm: f64) -> Solved {
        let target = Vector3::from(tip_mm);
        let reach = self.cover_mm + tolerance_mm;
        let distance: Vec<f64> = self.grid_tips.iter().map(|t| (t - target).norm()).collect();
        let mut found: Vec<(Vec<f64>, f64)> = Vec::new();
        let mut best: Option<(Vec<f64>, f64)> = None;
        for start in
            (0..distance.len()).filter(|&i| distance[i] <= reach && self.lowest(i, &distance))
        {
            let Some((angles, miss)) = self.refine(&self.grid_angles(start), target) else {
                continue;
            };
            if best.as_ref().map_or(true, |b| miss < b.1) {
                best = Some((angles.clone(), miss));
            }
            if miss <= tolerance_mm && self.within_range(&angles) {
                let ratio = self.jacobian(&angles).map_or(0.0, |j| singular_ratio(&j));
                found.push((angles, ratio));
            }
        }
        // The best-conditioned first, so that sameness is judged where the tip moves most.
        found.sort_by(|a, b| b.1.total_cmp(&a.1));
        let mut solutions: Vec<(Vec<f64>, f64)> = Vec::new();
        for (angles, ratio) in found {
            if !solutions
                .iter()
                .any(|(s, _)| self.same(s, &angles, tolerance_mm))
            {
                solutions.push((angles, ratio));
            }
        }
        match solutions.len() {
            0 => Solved::OffKinematics {
                miss_mm: best.as_ref().map_or(f64::INFINITY, |b| b.1),
                angles_rad: best.map(|b| b.0),
            },
            1 => {
                let (angles_rad, singular_ratio) = solutions.remove(0);
                if singular_ratio >= MIN_SINGULAR_RATIO {
                    Solved::Unique {
                        angles_rad,
                        singular_ratio,
                    }
                } else {
                    Solved::NotIdentifiable {
                        angles_rad,
                        singular_ratio,
                    }
                }
            }
            count => {
                // The best-conditioned stands for the row.
                Solved::Ambiguous {
                    angles_rad: solutions.swap_remove(0).0,
                    count,
                }
            }
        }
    }

    /// Whether solution `b` is solution `a` again: no farther from it than the tolerance can
    /// move the angles where the tip moves least, `|b − a| ≤ tolerance/σ_min(J(a))`. Two runs
    /// that found one minimum are one; two branches of the map (the tip's height reached with
    /// the angles turned either way), or two ends of a valley wider than the noise, are not.
    fn same(&self, a: &[f64], b: &[f64], tolerance_mm: f64) -> bool {
        let apart = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y).powi(2))
            .sum::<f64>()
            .sqrt();
        let weakest = self.jacobian(a).map_or(0.0, |j| j.singular_values().min());
        apart * weakest <= tolerance_mm
    }

    /// Whether `angles_rad` lie in the joints' ranges, give or take one grid step (a tip near
    /// a range's end, with noise, may solve just beyond it).
    fn within_range(&self, angles_rad: &[f64]) -> bool {
        let slack = 2.0 / (self.steps - 1) as f64;
        angles_rad
            .iter()
            .zip(&self.bound_rad)
            .all(|(a, b)| a.abs() <= b * (1.0 + slack))
    }

    /// Whether grid point `index` is a local minimum of `distance` among its neighbours
    /// (one step or none in every joint; ties go to the lower index). Every solution's cell
    /// lies within the covering radius, and the search starts from each such minimum there:
    /// two branches of the map give two valleys of the distance, each with its own minimum.
    fn lowest(&self, index: usize, distance: &[f64]) -> bool {
        let n = self.joints();
        let mut coords = [0usize; MAX_TIP_JOINTS];
        let mut rest = index;
        for c in coords.iter_mut().take(n) {
            *c = rest % self.steps;
            rest /= self.steps;
        }
        let mut stride = [1usize; MAX_TIP_JOINTS];
        for k in 1..n {
            stride[k] = stride[k - 1] * self.steps;
        }
        (0..3usize.pow(n as u32)).all(|mut offset| {
            let mut neighbour = 0usize;
            for k in 0..n {
                let step = (offset % 3) as isize - 1;
                offset /= 3;
                let c = coords[k] as isize + step;
                if c < 0 || c >= self.steps as isize {
                    return true;
                }
                neighbour += c as usize * stride[k];
            }
            neighbour == index
                || distance[neighbour] > distance[index]
                || (distance[neighbour] == distance[index] && neighbour > index)
        })
    }

    /// Levenberg–Marquardt from `start`: the angles and their tip's distance from `target`.
    fn refine(&self, start: &[f64], target: Vector3<f64>) -> Option<(Vec<f64>, f64)> {
        let problem = TipProblem::new(&self.kinematics, target, start)?;
        let (solved, _) = LevenbergMarquardt::new()
            .with_patience(100)
            .minimize(problem);
        let angles: Vec<f64> = solved.angles.iter().copied().collect();
        let miss = (self.tip(&angles)? - target).norm();
        miss.is_finite().then_some((angles, miss))
    }
}

/// Refuses a robot two of whose joints bend in one plane: at the straight pose their tip
/// Jacobian's columns (normalized) are near parallel.
fn check_not_coplanar(
    kinematics: &Kinematics,
    sections: &[BendingSection],
) -> Result<(), TipAnglesError> {
    let n = sections.len();
    let straight = vec![0.0; n];
    let j = jacobian(kinematics, &straight)
        .ok_or_else(|| TipAnglesError::Kinematics("no tip at the straight pose".into()))?;
    for a in 0..n {
        for b in a + 1..n {
            let unit = |c: usize| j.column(c).normalize();
            let pair = DMatrix::from_columns(&[unit(a), unit(b)]);
            let ratio = singular_ratio(&pair);
            if !(ratio >= MIN_SINGULAR_RATIO) {
                return Err(TipAnglesError::Coplanar {
                    first: a + 1,
                    second: b + 1,
                    first_deg: sections[a].rotation_rad.to_degrees(),
                    second_deg: sections[b].rotation_rad.to_degrees(),
                    ratio,
                    min: MIN_SINGULAR_RATIO,
                });
            }
        }
    }
    Ok(())
}

/// `σ_min/σ_max` of `m` (0 when it is zero or not finite).
fn singular_ratio(m: &DMatrix<f64>) -> f64 {
    let sv = m.singular_values();
    let (min, max) = (sv.min(), sv.max());
    if max > 0.0 && min.is_finite() {
        min / max
    } else {
        0.0
    }
}

/// The tip Jacobian of `kinematics` at `angles_rad` (3 × N, mm/rad), by central differences.
fn jacobian(kinematics: &Kinematics, angles_rad: &[f64]) -> Option<DMatrix<f64>> {
    let n = angles_rad.len();
    let mut out = DMatrix::zeros(3, n);
    let mut at = angles_rad.to_vec();
    for c in 0..n {
        at[c] = angles_rad[c] + JACOBIAN_STEP_RAD;
        let plus = kinematics.tip(&at).ok()?.position_mm;
        at[c] = angles_rad[c] - JACOBIAN_STEP_RAD;
        let minus = kinematics.tip(&at).ok()?.position_mm;
        at[c] = angles_rad[c];
        for r in 0..3 {
            out[(r, c)] = (plus[r] - minus[r]) / (2.0 * JACOBIAN_STEP_RAD);
        }
    }
    out.iter().all(|v| v.is_finite()).then_some(out)
}

/// The tip's distance from a target as a least-squares problem in the joint angles.
struct TipProblem<'a> {
    kinematics: &'a Kinematics,
    target: Vector3<f64>,
    angles: DVector<f64>,
    residual: Option<DVector<f64>>,
}

impl<'a> TipProblem<'a> {
    fn new(kinematics: &'a Kinematics, target: Vector3<f64>, start: &[f64]) -> Option<Self> {
        let mut me = Self {
            kinematics,
            target,
            angles: DVector::from_column_slice(start),
            residual: None,
        };
        me.set_params(&DVector::from_column_slice(start));
        me.residual.is_some().then_some(me)
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for TipProblem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, angles: &DVector<f64>) {
        self.angles.copy_from(angles);
        self.residual = self.kinematics.tip(angles.as_slice()).ok().map(|p| {
            let v = Vector3::from(p.position_mm) - self.target;
            DVector::from_column_slice(v.as_slice())
        });
    }

    fn params(&self) -> DVector<f64> {
        self.angles.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        self.residual.clone()
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        jacobian(self.kinematics, self.angles.as_slice())
    }
}

/// The tracker's noise per coordinate (mm): the robust spread of the tip's second differences
/// over three consecutive `valid` rows, `MAD·1.4826/√6`, the largest of the three coordinates,
/// at least [`TIP_RESOLUTION_MM`].
pub fn tip_noise_mm(tip_mm: &[Vec<f64>; 3], valid: impl Fn(usize) -> bool) -> f64 {
    let rows = tip_mm[0].len();
    let mut worst = TIP_RESOLUTION_MM;
    for column in tip_mm {
        let mut d: Vec<f64> = (1..rows.saturating_sub(1))
            .filter(|&i| valid(i - 1) && valid(i) && valid(i + 1))
            .map(|i| (column[i + 1] - 2.0 * column[i] + column[i - 1]).abs())
            .collect();
        if d.is_empty() {
            continue;
        }
        let mid = d.len() / 2;
        let (_, median, _) = d.select_nth_unstable_by(mid, f64::total_cmp);
        let sigma = *median * 1.4826 / 6f64.sqrt();
        if sigma.is_finite() {
            worst = worst.max(sigma);
        }
    }
    worst
}

/// Every row's joint angles from the tracked tip `tip_mm` (base frame, mm), over the rows for
/// which `valid` holds.
///
/// # Errors
/// [`TipAnglesError::OffKinematics`] when more than [`MAX_OFF_KINEMATICS_SHARE`] of the valid
/// rows are off the kinematics; [`TipAnglesError::AngleNoise`] when the tracker's noise makes
/// a joint's angle too noisy to fit on.
pub fn angles_from_tip(
    solver: &TipSolver,
    tip_mm: &[Vec<f64>; 3],
    valid: impl Fn(usize) -> bool,
) -> Result<TipAngles, TipAnglesError> {
    let n = solver.joints();
    let rows = tip_mm[0].len();
    let noise_mm = tip_noise_mm(tip_mm, &valid);
    let tolerance_mm = MAX_RESIDUAL_SIGMAS * noise_mm;
    let mut angle_deg = vec![Vec::with_capacity(rows); n];
    let mut used = vec![false; rows];
    let mut summary = TipAnglesSummary {
        rows: 0,
        used: 0,
        dropped_not_identifiable: 0,
        dropped_ambiguous: 0,
        dropped_off_kinematics: 0,
        tip_noise_mm: noise_mm,
        tolerance_mm,
        min_singular_ratio: MIN_SINGULAR_RATIO,
        largest_singular_ratio: None,
        angle_noise_share: vec![None; n],
    };
    let mut misses = Vec::new();
    let mut noise_var = vec![0.0; n];
    let mut previous = vec![0.0; n];
    for i in 0..rows {
        let mut angles = None;
        if valid(i) {
            summary.rows += 1;
            let tip = [tip_mm[0][i], tip_mm[1][i], tip_mm[2][i]];
            match solver.solve(tip, tolerance_mm) {
                Solved::Unique {
                    angles_rad,
                    singular_ratio,
                } => {
                    summary.see_ratio(singular_ratio);
                    if let Some(var) = propagated_variance(solver, &angles_rad, noise_mm) {
                        for (acc, v) in noise_var.iter_mut().zip(var) {
                            *acc += v;
                        }
                        used[i] = true;
                        summary.used += 1;
                    } else {
                        summary.dropped_not_identifiable += 1;
                    }
                    angles = Some(angles_rad);
                }
                Solved::NotIdentifiable {
                    angles_rad,
                    singular_ratio,
                } => {
                    summary.see_ratio(singular_ratio);
                    summary.dropped_not_identifiable += 1;
                    angles = Some(angles_rad);
                }
                Solved::Ambiguous { angles_rad, .. } => {
                    summary.dropped_ambiguous += 1;
                    angles = Some(angles_rad);
                }
                Solved::OffKinematics {
                    angles_rad,
                    miss_mm,
                } => {
                    summary.dropped_off_kinematics += 1;
                    misses.push(miss_mm);
                    angles = angles_rad;
                }
            }
        }
        if let Some(a) = angles {
            previous = a;
        }
        for (column, a) in angle_deg.iter_mut().zip(&previous) {
            column.push(a.to_degrees());
        }
    }
    let off = summary.dropped_off_kinematics;
    if off as f64 > MAX_OFF_KINEMATICS_SHARE * summary.rows as f64 {
        let mid = misses.len() / 2;
        let (_, median, _) = misses.select_nth_unstable_by(mid, f64::total_cmp);
        return Err(TipAnglesError::OffKinematics {
            off,
            rows: summary.rows,
            share: 100.0 * off as f64 / summary.rows as f64,
            max_percent: 100.0 * MAX_OFF_KINEMATICS_SHARE,
            tolerance_mm,
            sigmas: MAX_RESIDUAL_SIGMAS,
            noise_mm,
            median_mm: *median,
        });
    }
    summary.angle_noise_share =
        noise_shares(&angle_deg, &used, &noise_var, summary.used, noise_mm)?;
    Ok(TipAngles {
        angle_deg,
        used,
        summary,
    })
}

/// The diagonal of `σ²·(JᵀJ)⁻¹` at `angles_rad` (rad²): each angle's variance from the tip's
/// noise; `None` when `JᵀJ` cannot be inverted.
fn propagated_variance(solver: &TipSolver, angles_rad: &[f64], noise_mm: f64) -> Option<Vec<f64>> {
    let j = solver.jacobian(angles_rad)?;
    let inverse = (j.transpose() * &j).try_inverse()?;
    Some(
        (0..angles_rad.len())
            .map(|k| noise_mm * noise_mm * inverse[(k, k)])
            .collect(),
    )
}

/// Each joint's propagated noise as a share of its angle's variance over the used rows, or
/// [`TipAnglesError::AngleNoise`] for the first joint above [`MAX_ANGLE_NOISE_SHARE`].
fn noise_shares(
    angle_deg: &[Vec<f64>],
    used: &[bool],
    noise_var: &[f64],
    count: usize,
    noise_mm: f64,
) -> Result<Vec<Option<f64>>, TipAnglesError> {
    if count < 2 {
        return Ok(vec![None; angle_deg.len()]);
    }
    let mut shares = Vec::with_capacity(angle_deg.len());
    for (j, column) in angle_deg.iter().enumerate() {
        let values: Vec<f64> = column
            .iter()
            .zip(used)
            .filter(|(_, u)| **u)
            .map(|(a, _)| a.to_radians())
            .collect();
        let mean = values.iter().sum::<f64>() / count as f64;
        let var = values.iter().map(|a| (a - mean).powi(2)).sum::<f64>() / count as f64;
        if !(var.sqrt() > STILL_RAD) {
            shares.push(None);
            continue;
        }
        let noise = noise_var[j] / count as f64;
        let share = noise / var;
        if !(share <= MAX_ANGLE_NOISE_SHARE) {
            return Err(TipAnglesError::AngleNoise {
                joint: j + 1,
                noise_mm,
                scatter_deg: noise.sqrt().to_degrees(),
                share_percent: 100.0 * share,
                max_percent: 100.0 * MAX_ANGLE_NOISE_SHARE,
            });
        }
        shares.push(Some(share));
    }
    Ok(shares)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section(rotation_deg: f64, x_start_mm: f64, x_end_mm: f64) -> BendingSection {
        BendingSection {
            rotation_rad: rotation_deg.to_radians(),
            x_start_mm,
            x_end_mm,
        }
    }

    /// The covering radius rests on `|∂tip/∂θ_j| ≤ x_end_j`: checked over the range.
    #[test]
    fn the_tip_moves_at_most_x_end_per_radian_of_a_joint() {
        let sections = [section(0.0, 1.0, 6.0), section(90.0, 9.0, 15.0)];
        let k = Kinematics::new(&sections).unwrap();
        for a in -10..=10 {
            for b in -10..=10 {
                let angles = [0.15 * f64::from(a), 0.15 * f64::from(b)];
                let j = jacobian(&k, &angles).unwrap();
                for (c, s) in sections.iter().enumerate() {
                    assert!(
                        j.column(c).norm() <= s.x_end_mm * (1.0 + 1e-9),
                        "{angles:?}"
                    );
                }
            }
        }
    }

    /// Two joints in perpendicular planes: away from straight, the tip gives back the angles
    /// it was made from, and only them.
    #[test]
    fn perpendicular_joints_are_solved_uniquely() {
        let sections = [section(0.0, 1.0, 6.0), section(90.0, 9.0, 15.0)];
        let solver = TipSolver::new(&sections, &[1.2, 1.2]).unwrap();
        let k = Kinematics::new(&sections).unwrap();
        for angles in [[0.3, -0.4], [-0.7, 0.2], [0.9, 0.9], [0.05, 0.6]] {
            let tip = k.tip(&angles).unwrap().position_mm;
            match solver.solve(tip, 1e-6) {
                Solved::Unique { angles_rad, .. } => {
                    for (g, w) in angles_rad.iter().zip(angles) {
                        assert!((g - w).abs() < 1e-6, "{angles_rad:?} vs {angles:?}");
                    }
                }
                other => panic!("{angles:?}: {other:?}"),
            }
        }
        // A tip 2 mm off the reachable surface is off the kinematics.
        let mut tip = k.tip(&[0.3, 0.3]).unwrap().position_mm;
        tip[2] += 2.0;
        assert!(matches!(
            solver.solve(tip, 1e-3),
            Solved::OffKinematics { .. }
        ));
    }

    /// Three joints 120° apart (Robot BDB's planes): the tip's height is second order in the
    /// angles, so some tips are reached by two sets of angles, and the solver finds both.
    #[test]
    fn three_joints_can_reach_a_tip_two_ways() {
        let sections = [
            section(0.0, 1.0, 10.5),
            section(120.0, 13.5, 23.0),
            section(240.0, 26.0, 35.5),
        ];
        let solver = TipSolver::new(&sections, &[1.5; 3]).unwrap();
        let k = Kinematics::new(&sections).unwrap();
        for angles in [
            [0.5, -0.3, 0.4],
            [0.2, 0.2, 0.2],
            [-0.6, 0.1, 0.3],
            [0.05, -0.02, 0.01],
        ] {
            let tip = k.tip(&angles).unwrap().position_mm;
            let found = solver.solve(tip, 1e-4);
            assert!(
                matches!(found, Solved::Ambiguous { count: 2, .. }),
                "{angles:?}: {found:?}"
            );
        }
    }

    /// Joints in one plane (0° and 180° alike) are refused, naming both.
    #[test]
    fn coplanar_joints_are_refused() {
        for rotation in [0.0, 180.0] {
            let sections = [section(0.0, 1.0, 6.0), section(rotation, 9.0, 15.0)];
            let err = TipSolver::new(&sections, &[1.0, 1.0])
                .unwrap_err()
                .to_string();
            assert!(err.contains("joints 1 and 2 bend in one plane"), "{err}");
        }
        let four = [
            section(0.0, 1.0, 6.0),
            section(90.0, 9.0, 15.0),
            section(180.0, 18.0, 24.0),
            section(270.0, 27.0, 33.0),
        ];
        let err = TipSolver::new(&four, &[1.0; 4]).unwrap_err().to_string();
        assert!(
            err.contains("has 4 joints") && err.contains("at most 3"),
            "{err}"
        );
    }

    /// A tip whose noise is large against the angles' spread (0.2 mm against ±0.1 rad) would
    /// flatten a fitted line by more than 0.5 %: refused, naming the joint and the share; with
    /// ten times the spread, the same noise is accepted and every row used.
    #[test]
    fn angles_too_noisy_for_a_line_are_refused() {
        let sections = [section(0.0, 10.0, 20.0), section(90.0, 25.0, 35.0)];
        let solver = TipSolver::new(&sections, &[1.5, 1.5]).unwrap();
        let k = Kinematics::new(&sections).unwrap();
        let mut state = 11u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
        };
        let mut gauss = move || {
            let (a, b) = (uniform(), uniform());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        };
        let rows = 1500;
        let mut make = |amplitude: f64| -> [Vec<f64>; 3] {
            let mut tip: [Vec<f64>; 3] = Default::default();
            for i in 0..rows {
                let t = i as f64 * 0.01;
                let angles = [
                    amplitude * (0.7 * t).sin() + 0.3,
                    amplitude * (1.1 * t + 1.0).sin() - 0.3,
                ];
                let p = k.tip(&angles).unwrap().position_mm;
                for c in 0..3 {
                    tip[c].push(p[c] + 0.2 * gauss());
                }
            }
            tip
        };
        let narrow = make(0.1);
        let err = angles_from_tip(&solver, &narrow, |_| true).unwrap_err();
        let text = err.to_string();
        assert!(
            matches!(err, TipAnglesError::AngleNoise { .. }) && text.contains("at most 0.5 %"),
            "{text}"
        );
        let wide = make(1.0);
        let got = angles_from_tip(&solver, &wide, |_| true).unwrap();
        assert_eq!(got.summary.dropped_off_kinematics, 0, "{:?}", got.summary);
        assert!(got.summary.used > rows * 9 / 10, "{:?}", got.summary);
    }

    /// White noise of σ gives σ back from the second differences, whatever the smooth motion.
    #[test]
    fn the_noise_is_measured_from_second_differences() {
        let mut state = 7u64;
        let mut gauss = move || {
            // Box–Muller from a small LCG, enough for a spread check.
            let mut u = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
            };
            let (a, b) = (u(), u());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        };
        let rows = 20000;
        let tip: [Vec<f64>; 3] = std::array::from_fn(|c| {
            (0..rows)
                .map(|i| 10.0 * (i as f64 * 0.001 + c as f64).sin() + 0.05 * gauss())
                .collect()
        });
        let sigma = tip_noise_mm(&tip, |_| true);
        assert!((sigma / 0.05 - 1.0).abs() < 0.05, "{sigma}");
    }
}
