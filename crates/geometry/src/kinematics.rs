use core::fmt;

use nalgebra::{Quaternion, Unit, UnitQuaternion, Vector3};

/// Most joints a robot's kinematics (and the robot estimator) holds; storage is inline.
pub const MAX_JOINTS: usize = 8;

/// Below this half-angle (rad), `sin(h)/h` is its Taylor series `1 − h²/6 + h⁴/120`: the first
/// term left out, `h⁶/5040`, is below `2e-22` there, under half an ulp of the result.
const SINC_SERIES_BELOW_RAD: f64 = 1e-3;

/// One joint's notched section on the robot's tube, in the drawing's frame (`docs/frames.md`):
/// what `dlw inspect ROBOT --json` reports per joint (with the rotation in radians here).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BendingSection {
    /// The joint's bending plane about the tube axis: its `+y` (backbone, sensor side) lies at
    /// `s = r_o·rotation`, so `y_j = R_z(rotation)·ŷ` in the base frame (rad).
    pub rotation_rad: f64,
    /// Distal end of the notched section, drawing `x` (mm).
    pub x_start_mm: f64,
    /// Proximal end of the notched section, drawing `x` (mm).
    pub x_end_mm: f64,
}

impl BendingSection {
    /// The arc's length `L_j = x_end − x_start` (mm).
    pub fn length_mm(&self) -> f64 {
        self.x_end_mm - self.x_start_mm
    }
}

/// Where a point of the backbone is and how the tube is turned there, in the base frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Position (mm).
    pub position_mm: [f64; 3],
    /// Orientation as a rotation matrix, `rotation[row][column]`: its columns are the local
    /// frame's `x`, `y` and `z` (the tube's tangent toward the tip) in the base frame.
    pub rotation: [[f64; 3]; 3],
    /// The same orientation as a unit quaternion `[w, x, y, z]`, with `w ≥ 0`.
    pub quaternion: [f64; 4],
}

/// Why a robot's sections or a sample's angles were refused. Joints are numbered from 1, the
/// distal one first, as in the robot file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KinematicsError {
    /// No joint was given.
    NoJoints,
    /// More joints than the inline storage holds.
    TooManyJoints {
        /// Joints given.
        count: usize,
        /// [`MAX_JOINTS`].
        max: usize,
    },
    /// A section's number is not finite.
    NotFinite {
        /// 1-based joint number.
        joint: usize,
        /// `rotation_rad`, `x_start_mm` or `x_end_mm`.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// Joint 1's section starts before the tube's distal end at `x = 0`.
    BeforeTip {
        /// `x_start_mm` of joint 1.
        x_start_mm: f64,
    },
    /// A section does not end after it starts.
    EmptySection {
        /// 1-based joint number.
        joint: usize,
        /// Its `x_start_mm`.
        x_start_mm: f64,
        /// Its `x_end_mm`, which must exceed `x_start_mm`.
        x_end_mm: f64,
    },
    /// A section starts before the previous (more distal) joint's section ends.
    Overlap {
        /// 1-based joint number.
        joint: usize,
        /// Its `x_start_mm`.
        x_start_mm: f64,
        /// The previous joint's `x_end_mm`, which it must not be below.
        previous_x_end_mm: f64,
    },
    /// A sample has another number of angles than the robot has joints.
    AngleCount {
        /// Angles given.
        given: usize,
        /// Joints of the robot.
        joints: usize,
    },
    /// An angle is NaN or infinite.
    AngleNotFinite {
        /// 1-based joint number.
        joint: usize,
        /// The angle given (rad).
        value: f64,
    },
}

impl fmt::Display for KinematicsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::NoJoints => write!(f, "a robot needs at least 1 joint, none were given"),
            Self::TooManyJoints { count, max } => {
                write!(f, "{count} joints were given, at most {max} are supported")
            }
            Self::NotFinite { joint, name, value } => {
                write!(f, "joint {joint}: {name} = {value} is not a finite number")
            }
            Self::BeforeTip { x_start_mm } => write!(
                f,
                "joint 1: x_start_mm = {x_start_mm} must be at least 0 (the tip is at x = 0)"
            ),
            Self::EmptySection { joint, x_start_mm, x_end_mm } => write!(
                f,
                "joint {joint}: x_end_mm = {x_end_mm} must be greater than x_start_mm = {x_start_mm}"
            ),
            Self::Overlap { joint, x_start_mm, previous_x_end_mm } => write!(
                f,
                "joint {joint}: x_start_mm = {x_start_mm} must be at least joint {}'s x_end_mm = {previous_x_end_mm} (sections may not overlap)",
                joint - 1
            ),
            Self::AngleCount { given, joints } => write!(
                f,
                "{given} angles were given for a robot of {joints} joints (needs one per joint)"
            ),
            Self::AngleNotFinite { joint, value } => {
                write!(f, "joint {joint}: angle {value} rad is not a finite number")
            }
        }
    }
}

#[cfg(feature = "std")]
impl std::error::Error for KinematicsError {}

/// One stretch of the backbone walked from the base: an arc of constant curvature (zero for
/// the straight tube between sections).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Stretch {
    length_mm: f64,
    /// The joint whose angle bends it (0-based), or `None` for straight tube.
    joint: Option<usize>,
}

/// A joint's bending plane, in the frame at the start of its arc.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Plane {
    /// `x_j = y_j × z = R_z(rotation)·x̂`: a positive angle turns the tangent about it.
    axis: Unit<Vector3<f64>>,
    /// `−y_j`, where a positive angle moves the tube.
    toward: Vector3<f64>,
}

/// Forward kinematics of a robot of notched joints on one tube: joint angles to the tip's pose
/// and points along the backbone, in the base frame of `docs/robot-runtime.md`.
///
/// # Frame
/// Origin on the tube axis at the most proximal joint's `x_end_mm`; `z` along the tube toward
/// the tip (toward decreasing drawing `x`); `y` toward the surface point `s = 0` (the `+y` of
/// rotation 0); `x = y × z`. Joint `j`'s `y_j = R_z(rotation_j)·ŷ`, turned with the tube.
///
/// # Model
/// Each notched section bends as an arc of constant curvature `κ = θ/L`, `L = x_end − x_start`;
/// the tube between sections and beyond joint 1 (to the tip at `x = 0`) stays straight. A
/// positive `θ_j` bends toward `−y_j`: the tangent turns by `θ_j` about `x_j`. Over an arc the
/// tube moves by
///
/// `Δp = L·[ (θ/2)·sinc²(θ/2)·(−y_j) + sinc(θ/2)·cos(θ/2)·z ]`, `sinc(h) = sin(h)/h`,
///
/// which is `L·[(1 − cos θ)/θ·(−y_j) + sin θ/θ·z]` written without the division by `θ`, so a
/// straight joint (`θ → 0`) is exact and smooth. The tip's orientation is the product of the
/// joints' rotations, proximal first: `R_tip = Π_{j = N..1} Rot(x_j, θ_j)`.
///
/// Per call it never allocates: outputs go to caller-provided slices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    sections: [BendingSection; MAX_JOINTS],
    planes: [Plane; MAX_JOINTS],
    joints: usize,
    /// Stretches from the base to the tip: each joint's arc, then the straight tube after it.
    stretches: [Stretch; 2 * MAX_JOINTS],
    length_mm: f64,
}

impl Kinematics {
    /// The kinematics of a robot whose joints have `sections`, joint 1 (distal) first.
    ///
    /// # Errors
    /// No joint or more than [`MAX_JOINTS`]; a number that is not finite; joint 1 starting
    /// before `x = 0`; a section that does not end after it starts; a section overlapping the
    /// previous one.
    pub fn new(sections: &[BendingSection]) -> Result<Self, KinematicsError> {
        if sections.is_empty() {
            return Err(KinematicsError::NoJoints);
        }
        if sections.len() > MAX_JOINTS {
            return Err(KinematicsError::TooManyJoints {
                count: sections.len(),
                max: MAX_JOINTS,
            });
        }
        let mut previous_end = 0.0;
        for (index, s) in sections.iter().enumerate() {
            let joint = index + 1;
            for (name, value) in [
                ("rotation_rad", s.rotation_rad),
                ("x_start_mm", s.x_start_mm),
                ("x_end_mm", s.x_end_mm),
            ] {
                if !value.is_finite() {
                    return Err(KinematicsError::NotFinite { joint, name, value });
                }
            }
            if index == 0 && s.x_start_mm < 0.0 {
                return Err(KinematicsError::BeforeTip {
                    x_start_mm: s.x_start_mm,
                });
            }
            if index > 0 && s.x_start_mm < previous_end {
                return Err(KinematicsError::Overlap {
                    joint,
                    x_start_mm: s.x_start_mm,
                    previous_x_end_mm: previous_end,
                });
            }
            if s.x_end_mm <= s.x_start_mm {
                return Err(KinematicsError::EmptySection {
                    joint,
                    x_start_mm: s.x_start_mm,
                    x_end_mm: s.x_end_mm,
                });
            }
            previous_end = s.x_end_mm;
        }
        let mut out = Self {
            sections: [BendingSection {
                rotation_rad: 0.0,
                x_start_mm: 0.0,
                x_end_mm: 0.0,
            }; MAX_JOINTS],
            planes: [Plane {
                axis: Vector3::x_axis(),
                toward: -Vector3::y(),
            }; MAX_JOINTS],
            joints: sections.len(),
            stretches: [Stretch {
                length_mm: 0.0,
                joint: None,
            }; 2 * MAX_JOINTS],
            length_mm: previous_end,
        };
        out.sections[..sections.len()].copy_from_slice(sections);
        for (j, s) in sections.iter().enumerate() {
            let (sin, cos) = (libm::sin(s.rotation_rad), libm::cos(s.rotation_rad));
            out.planes[j] = Plane {
                axis: Unit::new_unchecked(Vector3::new(cos, sin, 0.0)),
                toward: Vector3::new(sin, -cos, 0.0),
            };
            // Walked from the base: the most proximal joint's arc comes first.
            let walk = 2 * (sections.len() - 1 - j);
            let next_end = if j == 0 {
                0.0
            } else {
                sections[j - 1].x_end_mm
            };
            out.stretches[walk] = Stretch {
                length_mm: s.length_mm(),
                joint: Some(j),
            };
            out.stretches[walk + 1] = Stretch {
                length_mm: s.x_start_mm - next_end,
                joint: None,
            };
        }
        Ok(out)
    }

    /// The sections, joint 1 first.
    pub fn sections(&self) -> &[BendingSection] {
        &self.sections[..self.joints]
    }

    /// Number of joints.
    pub fn joint_count(&self) -> usize {
        self.joints
    }

    /// Length of the backbone from the base to the tip, the most proximal `x_end_mm` (mm).
    pub fn length_mm(&self) -> f64 {
        self.length_mm
    }

    fn check(&self, angles_rad: &[f64]) -> Result<(), KinematicsError> {
        if angles_rad.len() != self.joints {
            return Err(KinematicsError::AngleCount {
                given: angles_rad.len(),
                joints: self.joints,
            });
        }
        match angles_rad.iter().position(|a| !a.is_finite()) {
            Some(j) => Err(KinematicsError::AngleNotFinite {
                joint: j + 1,
                value: angles_rad[j],
            }),
            None => Ok(()),
        }
    }

    /// The curvature (rad/mm) and bending plane of a stretch at these angles.
    #[inline]
    fn bend(&self, stretch: &Stretch, angles_rad: &[f64]) -> (f64, Plane) {
        match stretch.joint {
            Some(j) => (angles_rad[j] / stretch.length_mm, self.planes[j]),
            None => (0.0, self.planes[0]),
        }
    }

    /// The tip's pose at joint angles `angles_rad` (rad, joint 1 first).
    ///
    /// # Errors
    /// Not one angle per joint, or an angle that is not finite.
    pub fn tip(&self, angles_rad: &[f64]) -> Result<Pose, KinematicsError> {
        self.check(angles_rad)?;
        let mut position = Vector3::zeros();
        let mut turn = UnitQuaternion::identity();
        for stretch in &self.stretches[..2 * self.joints] {
            match stretch.joint {
                Some(j) => {
                    let (moved, turned) = arc(
                        angles_rad[j] / stretch.length_mm,
                        &self.planes[j],
                        stretch.length_mm,
                    );
                    position += turn * moved;
                    turn *= turned;
                }
                None => position += turn * (Vector3::z() * stretch.length_mm),
            }
        }
        Ok(pose(position, turn))
    }

    /// Points of the backbone at joint angles `angles_rad` (rad, joint 1 first), written to
    /// `points_mm`: `K = points_mm.len()` points equally spaced in arc length from the base
    /// (first) to the tip (last), both included; with `K = 1`, the tip alone.
    ///
    /// # Errors
    /// As [`Kinematics::tip`]; `points_mm` is left untouched.
    pub fn backbone(
        &self,
        angles_rad: &[f64],
        points_mm: &mut [[f64; 3]],
    ) -> Result<(), KinematicsError> {
        self.check(angles_rad)?;
        let count = points_mm.len();
        if count == 0 {
            return Ok(());
        }
        let spacing = if count > 1 {
            self.length_mm / (count - 1) as f64
        } else {
            0.0
        };
        let stretches = &self.stretches[..2 * self.joints];
        let mut position = Vector3::zeros();
        let mut turn = UnitQuaternion::identity();
        let mut start_mm = 0.0;
        // The last point is the tip, written after the walk: it lies at the end of the last
        // stretch exactly, where the arc lengths' rounding could put it just past it.
        let mut next = 0;
        for (k, stretch) in stretches.iter().enumerate() {
            let (curvature, plane) = self.bend(stretch, angles_rad);
            let last = k + 1 == stretches.len();
            while next + 1 < count {
                let local = next as f64 * spacing - start_mm;
                if !last && local > stretch.length_mm {
                    break;
                }
                let local = local.clamp(0.0, stretch.length_mm);
                let p = position + turn * along_arc(curvature, &plane, local);
                points_mm[next] = [p.x, p.y, p.z];
                next += 1;
            }
            let (moved, turned) = arc(curvature, &plane, stretch.length_mm);
            position += turn * moved;
            turn *= turned;
            start_mm += stretch.length_mm;
        }
        points_mm[count - 1] = [position.x, position.y, position.z];
        Ok(())
    }
}

/// Where the tube is after `length` mm of an arc of `curvature` (rad/mm) bending toward
/// `plane.toward`, in the frame at the arc's start (tangent `z`).
#[inline]
fn along_arc(curvature: f64, plane: &Plane, length_mm: f64) -> Vector3<f64> {
    let half = 0.5 * curvature * length_mm;
    let (sinc, cos) = sinc_cos(half);
    plane.toward * (length_mm * half * sinc * sinc) + Vector3::z() * (length_mm * sinc * cos)
}

/// [`along_arc`] over the whole `length` and the rotation the arc turns the frame by,
/// `Rot(x_j, κ·length)`, from one sine and cosine of the half angle `h`, which the unit
/// quaternion `(cos h, sin h·x_j)` shares.
#[inline]
fn arc(curvature: f64, plane: &Plane, length_mm: f64) -> (Vector3<f64>, UnitQuaternion<f64>) {
    let half = 0.5 * curvature * length_mm;
    let (sinc, cos) = sinc_cos(half);
    let moved =
        plane.toward * (length_mm * half * sinc * sinc) + Vector3::z() * (length_mm * sinc * cos);
    let axis = plane.axis.into_inner() * (half * sinc);
    let turned = UnitQuaternion::new_unchecked(Quaternion::new(cos, axis.x, axis.y, axis.z));
    (moved, turned)
}

/// `(sin(h)/h, cos(h))`, by series near 0 so that `h = 0` needs no division.
#[inline]
fn sinc_cos(half_rad: f64) -> (f64, f64) {
    if half_rad.abs() < SINC_SERIES_BELOW_RAD {
        let h2 = half_rad * half_rad;
        (
            1.0 - h2 / 6.0 + h2 * h2 / 120.0,
            1.0 - h2 / 2.0 + h2 * h2 / 24.0,
        )
    } else {
        let (sin, cos) = libm::sincos(half_rad);
        (sin / half_rad, cos)
    }
}

fn pose(position: Vector3<f64>, turn: UnitQuaternion<f64>) -> Pose {
    let m = turn.to_rotation_matrix();
    let m = m.matrix();
    let sign = if turn.w < 0.0 { -1.0 } else { 1.0 };
    Pose {
        position_mm: [position.x, position.y, position.z],
        rotation: [
            [m[(0, 0)], m[(0, 1)], m[(0, 2)]],
            [m[(1, 0)], m[(1, 1)], m[(1, 2)]],
            [m[(2, 0)], m[(2, 1)], m[(2, 2)]],
        ],
        quaternion: [sign * turn.w, sign * turn.i, sign * turn.j, sign * turn.k],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use core::f64::consts::{FRAC_PI_2, PI};

    fn section(rotation_deg: f64, x_start_mm: f64, x_end_mm: f64) -> BendingSection {
        BendingSection {
            rotation_rad: rotation_deg.to_radians(),
            x_start_mm,
            x_end_mm,
        }
    }

    fn assert_vec(got: [f64; 3], want: [f64; 3]) {
        for i in 0..3 {
            assert_relative_eq!(got[i], want[i], epsilon = 1e-12);
        }
    }

    /// One joint of rotation 0 at 90°: a quarter circle of radius 2L/π toward −y, then the
    /// straight tube of length x_start along −y.
    #[test]
    fn one_joint_at_ninety_degrees() {
        let (a, b) = (2.0, 12.0);
        let k = Kinematics::new(&[section(0.0, a, b)]).unwrap();
        let tip = k.tip(&[FRAC_PI_2]).unwrap();
        let r = (b - a) * 2.0 / PI;
        assert_vec(tip.position_mm, [0.0, -r - a, r]);
        // Rot(x̂, 90°): the tip's tangent (third column) points along −y.
        let want = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
        for (row, want_row) in tip.rotation.iter().zip(want) {
            assert_vec(*row, want_row);
        }
        let half = core::f64::consts::FRAC_1_SQRT_2;
        for (q, w) in tip.quaternion.iter().zip([half, half, 0.0, 0.0]) {
            assert_relative_eq!(*q, w, epsilon = 1e-15);
        }
    }

    /// The straight robot lies along z, and the base is at the most proximal x_end.
    #[test]
    fn straight_robot_is_the_tube() {
        let k = Kinematics::new(&[section(30.0, 1.0, 5.0), section(120.0, 7.0, 16.0)]).unwrap();
        assert_eq!(k.length_mm(), 16.0);
        assert_vec(k.tip(&[0.0, 0.0]).unwrap().position_mm, [0.0, 0.0, 16.0]);
        let mut points = [[f64::NAN; 3]; 5];
        k.backbone(&[0.0, 0.0], &mut points).unwrap();
        for (i, p) in points.iter().enumerate() {
            assert_vec(*p, [0.0, 0.0, 4.0 * i as f64]);
        }
    }

    /// A positive angle of a joint at rotation 90° bends toward −y_j = +x.
    #[test]
    fn rotation_turns_the_bending_plane() {
        let k = Kinematics::new(&[section(90.0, 0.0, 10.0)]).unwrap();
        let tip = k.tip(&[FRAC_PI_2]).unwrap();
        let r = 20.0 / PI;
        assert_vec(tip.position_mm, [r, 0.0, r]);
    }

    #[test]
    fn refusals_name_joint_value_and_limit() {
        extern crate std;
        use std::string::ToString;
        let cases: [(&[BendingSection], KinematicsError, &str); 5] = [
            (&[], KinematicsError::NoJoints, "at least 1 joint"),
            (
                &[section(0.0, -1.0, 5.0)],
                KinematicsError::BeforeTip { x_start_mm: -1.0 },
                "x_start_mm = -1 must be at least 0",
            ),
            (
                &[section(0.0, 5.0, 5.0)],
                KinematicsError::EmptySection {
                    joint: 1,
                    x_start_mm: 5.0,
                    x_end_mm: 5.0,
                },
                "x_end_mm = 5 must be greater than x_start_mm = 5",
            ),
            (
                &[section(0.0, 0.0, 5.0), section(0.0, 4.0, 8.0)],
                KinematicsError::Overlap {
                    joint: 2,
                    x_start_mm: 4.0,
                    previous_x_end_mm: 5.0,
                },
                "joint 2: x_start_mm = 4 must be at least joint 1's x_end_mm = 5",
            ),
            (
                &[section(f64::NAN, 0.0, 5.0)],
                KinematicsError::NotFinite {
                    joint: 1,
                    name: "rotation_rad",
                    value: f64::NAN,
                },
                "rotation_rad = NaN",
            ),
        ];
        for (sections, want, text) in cases {
            let got = Kinematics::new(sections).unwrap_err();
            // NaN != NaN: compare the messages, which carry every field.
            assert_eq!(got.to_string(), want.to_string());
            assert!(got.to_string().contains(text), "{got}");
        }
        let nine = [section(0.0, 0.0, 1.0); 9];
        assert_eq!(
            Kinematics::new(&nine).unwrap_err(),
            KinematicsError::TooManyJoints { count: 9, max: 8 }
        );
        let k = Kinematics::new(&[section(0.0, 0.0, 5.0)]).unwrap();
        assert_eq!(
            k.tip(&[0.1, 0.2]).unwrap_err(),
            KinematicsError::AngleCount {
                given: 2,
                joints: 1
            }
        );
        let mut points = [[7.0; 3]; 3];
        assert!(k.backbone(&[f64::INFINITY], &mut points).is_err());
        assert_eq!(points, [[7.0; 3]; 3], "untouched on error");
    }

    /// The series branch and libm agree where they meet.
    #[test]
    fn sinc_is_continuous_at_the_series_switch() {
        let below = sinc_cos(SINC_SERIES_BELOW_RAD * (1.0 - 1e-12));
        let above = sinc_cos(SINC_SERIES_BELOW_RAD * (1.0 + 1e-12));
        assert_relative_eq!(below.0, above.0, epsilon = 1e-16);
        assert_relative_eq!(below.1, above.1, epsilon = 1e-16);
        assert_eq!(sinc_cos(0.0), (1.0, 1.0));
    }
}
