//! The robot's forward kinematics against closed forms (one joint at 90°, two joints in one
//! plane adding up, two at 90° giving the product of rotations) and, on random robots, against
//! an independent numerical integration of the backbone, with the properties that hold for any
//! robot: arc length is kept, the tip's orientation is the product of the joints' rotations,
//! and the pose is continuous through θ = 0.

use std::f64::consts::{FRAC_PI_2, PI};

use approx::assert_relative_eq;
use dlw_geometry::{BendingSection, Kinematics, Pose, MAX_JOINTS};
use nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};
use proptest::prelude::*;

fn section(rotation_deg: f64, x_start_mm: f64, x_end_mm: f64) -> BendingSection {
    BendingSection {
        rotation_rad: rotation_deg.to_radians(),
        x_start_mm,
        x_end_mm,
    }
}

fn rotation(pose: &Pose) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| pose.rotation[r][c])
}

fn position(pose: &Pose) -> Vector3<f64> {
    Vector3::from(pose.position_mm)
}

/// Two joints of the same rotation, adjacent and of equal curvature, are one arc of the summed
/// length and angle; with a gap between them the tip still turns by the sum, about the same axis.
#[test]
fn two_joints_in_one_plane_add_up() {
    for rotation_deg in [0.0, 37.0, 200.0] {
        let (t1, t2) = (0.3, 0.6); // curvature 0.1 rad/mm on both
        let split = Kinematics::new(&[
            section(rotation_deg, 1.0, 4.0),
            section(rotation_deg, 4.0, 10.0),
        ])
        .unwrap();
        let whole = Kinematics::new(&[section(rotation_deg, 1.0, 10.0)]).unwrap();
        let (a, b) = (
            split.tip(&[t1, t2]).unwrap(),
            whole.tip(&[t1 + t2]).unwrap(),
        );
        assert_relative_eq!(position(&a), position(&b), epsilon = 1e-12);
        assert_relative_eq!(rotation(&a), rotation(&b), epsilon = 1e-12);

        let gapped = Kinematics::new(&[
            section(rotation_deg, 1.0, 4.0),
            section(rotation_deg, 7.0, 13.0),
        ])
        .unwrap();
        let axis = Unit::new_normalize(Vector3::new(
            rotation_deg.to_radians().cos(),
            rotation_deg.to_radians().sin(),
            0.0,
        ));
        let want = Rotation3::from_axis_angle(&axis, t1 + t2);
        let tip = gapped.tip(&[t1, t2]).unwrap();
        assert_relative_eq!(rotation(&tip), *want.matrix(), epsilon = 1e-12);
        // The bend stays in the plane spanned by z and y_j: no component along x_j.
        assert_relative_eq!(position(&tip).dot(&axis), 0.0, epsilon = 1e-12);
    }
}

/// Joint 2 (proximal, rotation 90°) bends 90° toward +x, the gap runs along +x, joint 1
/// (rotation 0, its y still the base's y) bends 90° toward −y, and the tip's straight tube runs
/// along −y. Worked by hand: quarter circles of radius 2L/π.
#[test]
fn two_joints_at_ninety_degrees_give_the_product_of_rotations() {
    let (a, l1, g, l2) = (1.5, 8.0, 3.0, 10.0);
    let k = Kinematics::new(&[
        section(0.0, a, a + l1),
        section(90.0, a + l1 + g, a + l1 + g + l2),
    ])
    .unwrap();
    let tip = k.tip(&[FRAC_PI_2, FRAC_PI_2]).unwrap();
    let (r1, r2) = (2.0 * l1 / PI, 2.0 * l2 / PI);
    let want = Vector3::new(r2, 0.0, r2)
        + Vector3::new(g, 0.0, 0.0)
        + Vector3::new(r1, -r1, 0.0)
        + Vector3::new(0.0, -a, 0.0);
    assert_relative_eq!(position(&tip), want, epsilon = 1e-12);
    // Rot(ŷ, 90°)·Rot(x̂, 90°), multiplied out by hand.
    let about_y = Matrix3::new(0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0);
    let about_x = Matrix3::new(1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0);
    let product = Matrix3::new(0.0, 1.0, 0.0, 0.0, 0.0, -1.0, -1.0, 0.0, 0.0);
    assert_eq!(about_y * about_x, product);
    assert_relative_eq!(rotation(&tip), product, epsilon = 1e-12);
    // And not the other order: rotations about different axes do not commute.
    assert!((rotation(&tip) - about_x * about_y).abs().max() > 0.5);
}

/// A random robot of 1 to `MAX_JOINTS` joints: rotations, section lengths and gaps.
fn robot() -> impl Strategy<Value = (Vec<BendingSection>, Vec<f64>)> {
    (1..=MAX_JOINTS)
        .prop_flat_map(|n| {
            (
                0.0..5.0f64,
                prop::collection::vec((-PI..PI, 0.5..15.0f64, 0.0..6.0f64), n),
                prop::collection::vec(-PI..PI, n),
            )
        })
        .prop_map(|(distal, joints, angles)| {
            let mut x = distal;
            let sections = joints
                .into_iter()
                .map(|(rotation_rad, length, gap)| {
                    let s = BendingSection {
                        rotation_rad,
                        x_start_mm: x,
                        x_end_mm: x + length,
                    };
                    x += length + gap;
                    s
                })
                .collect();
            (sections, angles)
        })
}

/// The backbone by numerical integration of `dp/ds = R·z`, `dR/ds = R·[κ·x_j]×`, walking from
/// the base in steps of at most `step_mm`: each step turns `R` exactly and moves along the
/// tangent at the step's middle. Returns the position at arc lengths `at_mm` (increasing) and
/// the tip's rotation.
fn integrate(
    sections: &[BendingSection],
    angles: &[f64],
    step_mm: f64,
    at_mm: &[f64],
) -> (Vec<Vector3<f64>>, Rotation3<f64>) {
    // Curvature and axis as functions of the arc length from the base.
    let base = sections.last().unwrap().x_end_mm;
    let bend_at = |s: f64| -> (f64, Unit<Vector3<f64>>) {
        let x = base - s;
        for (j, sec) in sections.iter().enumerate() {
            if x > sec.x_start_mm && x < sec.x_end_mm {
                let axis = Vector3::new(sec.rotation_rad.cos(), sec.rotation_rad.sin(), 0.0);
                return (
                    angles[j] / (sec.x_end_mm - sec.x_start_mm),
                    Unit::new_normalize(axis),
                );
            }
        }
        (0.0, Vector3::x_axis())
    };
    // Step boundaries: the section ends (so no step straddles one) and the points asked for.
    let mut marks: Vec<f64> = sections
        .iter()
        .flat_map(|s| [base - s.x_start_mm, base - s.x_end_mm])
        .chain(at_mm.iter().copied())
        .chain([0.0, base])
        .collect();
    marks.sort_by(f64::total_cmp);
    let (mut p, mut r) = (Vector3::zeros(), Rotation3::identity());
    let mut out = Vec::new();
    let mut wanted = at_mm.iter().peekable();
    let mut s = 0.0;
    for &mark in &marks {
        let span = mark - s;
        let steps = (span / step_mm).ceil().max(1.0) as usize;
        let ds = span / steps as f64;
        for _ in 0..steps {
            if ds <= 0.0 {
                break;
            }
            let (kappa, axis) = bend_at(s + 0.5 * ds);
            let half = Rotation3::from_axis_angle(&axis, 0.5 * kappa * ds);
            p += (r * half) * Vector3::z() * ds;
            r = r * half * half;
            s += ds;
        }
        s = mark;
        while wanted.peek().is_some_and(|&&w| w <= mark) {
            out.push(p);
            wanted.next();
        }
    }
    (out, r)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The closed form matches a numerical integration of the same model to the midpoint
    /// rule's error bound, `S·(κ_max·ds)²/24`, at the tip and at every backbone point.
    #[test]
    fn closed_form_matches_numerical_integration((sections, angles) in robot(), count in 2usize..40) {
        let k = Kinematics::new(&sections).unwrap();
        let length = k.length_mm();
        let mut points = vec![[0.0; 3]; count];
        k.backbone(&angles, &mut points).unwrap();
        let at: Vec<f64> = (0..count).map(|i| length * i as f64 / (count - 1) as f64).collect();
        let step = 0.01;
        let (integrated, r) = integrate(&sections, &angles, step, &at);
        let kappa_max = sections
            .iter()
            .zip(&angles)
            .map(|(s, a)| a.abs() / (s.x_end_mm - s.x_start_mm))
            .fold(0.0, f64::max);
        let bound = length * (kappa_max * step).powi(2) / 24.0 + 1e-9;
        for (got, want) in points.iter().zip(&integrated) {
            prop_assert!((Vector3::from(*got) - want).norm() <= bound,
                "{got:?} vs {want:?} (bound {bound:e})");
        }
        let tip = k.tip(&angles).unwrap();
        prop_assert_eq!(tip.position_mm, points[count - 1]);
        prop_assert!((rotation(&tip) - r.matrix()).abs().max() <= 1e-9);
    }

    /// The tip's orientation is the product of the joints' rotations, proximal first; the
    /// matrix is a rotation and the quaternion is the same rotation, with w ≥ 0.
    #[test]
    fn tip_orientation_is_the_product_of_joint_rotations((sections, angles) in robot()) {
        let k = Kinematics::new(&sections).unwrap();
        let tip = k.tip(&angles).unwrap();
        let mut product = Matrix3::identity();
        for (s, a) in sections.iter().zip(&angles).rev() {
            let axis = Unit::new_normalize(Vector3::new(s.rotation_rad.cos(), s.rotation_rad.sin(), 0.0));
            product *= Rotation3::from_axis_angle(&axis, *a).matrix();
        }
        let m = rotation(&tip);
        prop_assert!((m - product).abs().max() <= 1e-12, "{m} vs {product}");
        prop_assert!((m.transpose() * m - Matrix3::identity()).abs().max() <= 1e-12);
        prop_assert!((m.determinant() - 1.0).abs() <= 1e-12);
        let [w, x, y, z] = tip.quaternion;
        prop_assert!(w >= 0.0);
        let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z));
        prop_assert!((q.to_rotation_matrix().matrix() - m).abs().max() <= 1e-12);
    }

    /// Arc length is kept: K equally spaced points are one spacing apart along the curve, so
    /// each chord is at most the spacing and at least the chord of that spacing on the most
    /// curved arc, `(2/κ_max)·sin(κ_max·Δs/2)`.
    #[test]
    fn arc_length_is_preserved((sections, angles) in robot(), count in 2usize..200) {
        let k = Kinematics::new(&sections).unwrap();
        let mut points = vec![[0.0; 3]; count];
        k.backbone(&angles, &mut points).unwrap();
        let spacing = k.length_mm() / (count - 1) as f64;
        let kappa_max = sections
            .iter()
            .zip(&angles)
            .map(|(s, a)| a.abs() / (s.x_end_mm - s.x_start_mm))
            .fold(0.0, f64::max);
        let shortest = if kappa_max * spacing < 1e-9 {
            spacing
        } else if kappa_max * spacing < PI {
            2.0 / kappa_max * (kappa_max * spacing / 2.0).sin()
        } else {
            0.0
        };
        prop_assert_eq!(points[0], [0.0, 0.0, 0.0]);
        for pair in points.windows(2) {
            let chord = (Vector3::from(pair[1]) - Vector3::from(pair[0])).norm();
            prop_assert!(chord <= spacing * (1.0 + 1e-12) + 1e-12, "chord {chord} > spacing {spacing}");
            prop_assert!(chord >= shortest * (1.0 - 1e-12) - 1e-12, "chord {chord} < {shortest}");
        }
    }

    /// Continuity through θ = 0 and across the series switch (at θ = 2e-3 for a whole arc):
    /// the pose moves by at most the
    /// distance to the tip (at most the backbone's length S) times the angle changed,
    /// `|p(a) − p(b)| ≤ S·Σ|a_j − b_j|`, and the straight robot is the tube along z.
    #[test]
    fn pose_is_continuous_through_zero((sections, direction) in robot(), scale in prop::sample::select(vec![0.0, 1e-14, 1e-9, 1e-6, 1.999999e-3, 2e-3, 2.000001e-3, 0.1])) {
        let k = Kinematics::new(&sections).unwrap();
        let length = k.length_mm();
        let straight = k.tip(&vec![0.0; sections.len()]).unwrap();
        prop_assert!((position(&straight) - Vector3::new(0.0, 0.0, length)).norm() <= 1e-12 * length);
        for sign in [1.0, -1.0] {
            let a: Vec<f64> = direction.iter().map(|d| sign * scale * d.signum()).collect();
            let b: Vec<f64> = a.iter().map(|x| x * (1.0 + 1e-7)).collect();
            let (pa, pb) = (position(&k.tip(&a).unwrap()), position(&k.tip(&b).unwrap()));
            let moved: f64 = a.iter().zip(&b).map(|(x, y)| (x - y).abs()).sum();
            prop_assert!((pa - pb).norm() <= length * moved * (1.0 + 1e-9) + 1e-13);
            let from_straight: f64 = a.iter().map(|x| x.abs()).sum();
            prop_assert!((pa - position(&straight)).norm() <= length * from_straight * (1.0 + 1e-9) + 1e-13);
        }
    }
}
