//! Notched-tube mechanics: tendon stroke, curvature and angle, the farthest fibre's strain, the
//! notched section's second moment of area, and the tendon force.
//!
//! The kinematics are the asymmetric-notch wrist model of York, Swaney and colleagues (York,
//! Swaney, Gilbert, Webster, "A wrist for needle-sized surgical robots", ICRA 2015), and the
//! same equations with `ȳ = 0` for symmetric notches (Rucker and Webster's tendon-driven notch
//! joints). Every equation
//! is written out in `docs/mechanics.md`.
//!
//! Assumptions (the model's, not the paper's data): bending happens only in the `N` notched
//! segments, each the same; the tendon runs straight at a fixed offset `r_t` from the tube axis
//! on the notch side; the material is linear-elastic and the stroke is shared equally among the
//! notches. **Friction between tendon and tube is ignored**, as are tendon stretch and axial
//! compression of the tube.
//!
//! Lengths in mm, angles in rad, forces in N, moduli in Pa.

use core::f64::consts::PI;

use crate::error::{positive, GeometryError};
use crate::joint::Joint;
use crate::section::NotchStyle;

/// Half the diameter of the paper's tendon (0.28 mm nylon, Section III): the default tendon
/// offset is the inner wall less this much, `r_t = r_i − 0.14 mm`.
pub const DEFAULT_TENDON_HALF_DIAMETER_MM: f64 = 0.14;

/// Pascals in one N/mm² (one MPa): forces come out in N from lengths in mm.
const PA_PER_N_PER_MM2: f64 = 1.0e6;

/// Where the backbone's farthest fibre from the neutral plane lies, and so which side of the
/// notched section reaches a strain limit first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum FibreSide {
    /// UAN: the backbone's outer crest at `y = r_o`, `d = r_o − ȳ`, in tension (York's form).
    BackboneCrest,
    /// UAN with `cos α > 0`: the backbone's edges at the notch, inner corner
    /// `y = r_i·cos α`, `d = ȳ − r_i·cos α`, in compression.
    NotchInnerEdge,
    /// UAN with `cos α ≤ 0` (notch shorter than half the circumference): the backbone's edges at
    /// the notch, outer corner `y = r_o·cos α`, `d = ȳ − r_o·cos α`, in compression.
    NotchOuterEdge,
    /// BSN: the notch corners at `r_o·sin β`, `β = π/2 − s_n/(2r_o)`; tension on one side,
    /// compression on the other, the same distance.
    NotchCorners,
}

impl FibreSide {
    /// The side in words, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Self::BackboneCrest => "backbone crest, tension",
            Self::NotchInnerEdge => "backbone edge at the notch (inner corner), compression",
            Self::NotchOuterEdge => "backbone edge at the notch (outer corner), compression",
            Self::NotchCorners => "notch corners, tension and compression",
        }
    }
}

/// What ends a joint's usable range first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum RangeLimit {
    /// The notch faces touch.
    NotchClosing,
    /// The backbone's farthest fibre reaches the material's strain limit.
    Material,
    /// The sensor reaches its saturation strain.
    SensorSaturation,
}

impl RangeLimit {
    /// The limit in words, for reports.
    pub fn describe(self) -> &'static str {
        match self {
            Self::NotchClosing => "notch closing",
            Self::Material => "material strain",
            Self::SensorSaturation => "sensor saturation",
        }
    }
}

/// The mechanics of a tendon-driven notched joint.
///
/// Built by [`Mechanics::new`] from a validated [`Joint`] and the tendon offset; every method
/// then returns a finite number for finite input within the joint's range.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Mechanics {
    joint: Joint,
    tendon_offset_mm: f64,
}

impl Mechanics {
    /// The mechanics of `joint` pulled by a tendon at `tendon_offset_mm` (`r_t`) from the tube
    /// axis, on the notch side (for BSN, one tendon on each side at the same offset).
    ///
    /// # Errors
    /// A tendon offset that is not finite, not positive, or outside the lumen (`r_t > r_i`).
    pub fn new(joint: Joint, tendon_offset_mm: f64) -> Result<Self, GeometryError> {
        positive("tendon_offset_mm", tendon_offset_mm)?;
        let inner_mm = joint.section().inner_radius_mm();
        if tendon_offset_mm > inner_mm {
            return Err(GeometryError::TendonOutsideLumen {
                tendon_offset_mm,
                inner_mm,
            });
        }
        Ok(Self {
            joint,
            tendon_offset_mm,
        })
    }

    /// The default tendon offset for a tube of inner radius `inner_radius_mm`: at the inner wall
    /// less half the paper's tendon, `r_i − 0.14 mm`.
    pub fn default_tendon_offset_mm(inner_radius_mm: f64) -> f64 {
        inner_radius_mm - DEFAULT_TENDON_HALF_DIAMETER_MM
    }

    /// The joint.
    pub fn joint(&self) -> &Joint {
        &self.joint
    }

    /// Tendon offset `r_t` from the tube axis (mm).
    pub fn tendon_offset_mm(&self) -> f64 {
        self.tendon_offset_mm
    }

    fn y_bar(&self) -> f64 {
        self.joint.section().neutral_axis_mm()
    }

    fn h(&self) -> f64 {
        self.joint.notch_width_mm()
    }

    fn n(&self) -> f64 {
        f64::from(self.joint.notch_count())
    }

    /// The tendon's moment arm about the neutral plane, `r_t + ȳ` (mm).
    pub fn moment_arm_mm(&self) -> f64 {
        self.tendon_offset_mm + self.y_bar()
    }

    /// Curvature of each notched segment for a total tendon stroke `Δl` (1/mm), the stroke
    /// shared equally, `δ = Δl/N`: `κ = δ/(h·(r_t + ȳ) − δ·ȳ)`.
    pub fn curvature_per_mm(&self, stroke_mm: f64) -> f64 {
        let delta = stroke_mm / self.n();
        delta / (self.h() * self.moment_arm_mm() - delta * self.y_bar())
    }

    /// Arc length of the neutral plane through one notch at curvature `κ`, `s = h/(1 + ȳ·κ)` (mm).
    pub fn arc_length_mm(&self, curvature_per_mm: f64) -> f64 {
        self.h() / (1.0 + self.y_bar() * curvature_per_mm)
    }

    /// Joint angle for a tendon stroke `Δl` (rad): `θ = N·κ·s`. Algebraically this is
    /// `Δl/(r_t + ȳ)`; the three steps are kept so the code reads as the model.
    pub fn angle_from_stroke_rad(&self, stroke_mm: f64) -> f64 {
        let kappa = self.curvature_per_mm(stroke_mm);
        self.n() * kappa * self.arc_length_mm(kappa)
    }

    /// Tendon stroke per radian of joint angle, `r_t + ȳ` (mm/rad): the model is exactly linear.
    pub fn stroke_per_rad_mm(&self) -> f64 {
        self.moment_arm_mm()
    }

    /// Tendon stroke that bends the straight joint by 1° (mm).
    pub fn stroke_per_deg_mm(&self) -> f64 {
        self.stroke_per_rad_mm() * PI / 180.0
    }

    /// Curvature of each notched segment at joint angle `θ` (1/mm), the inverse of
    /// [`Mechanics::angle_from_stroke_rad`]: with `θ_n = θ/N`, `κ = θ_n/(h − θ_n·ȳ)`.
    pub fn curvature_at_angle_per_mm(&self, angle_rad: f64) -> f64 {
        let per_notch = angle_rad / self.n();
        per_notch / (self.h() - per_notch * self.y_bar())
    }

    /// Notch-closing limit per notch, `θ_max = h/(r_o + ȳ)` (rad).
    pub fn closing_angle_per_notch_rad(&self) -> f64 {
        self.h() / (self.joint.section().outer_radius_mm() + self.y_bar())
    }

    /// Notch-closing limit of the joint, `N·h/(r_o + ȳ)` (rad); the same as
    /// [`Joint::closing_angle_rad`].
    pub fn closing_angle_rad(&self) -> f64 {
        self.n() * self.closing_angle_per_notch_rad()
    }

    /// The backbone's farthest fibre from the neutral plane: its distance `d` (mm) and side.
    ///
    /// UAN: the larger of the crest `r_o − ȳ` (tension) and the notch-side edge of the annular
    /// sector of half-angle `α = π − s_n/(2r_o)`, whose lowest point is `r_i·cos α` when
    /// `cos α > 0` and `r_o·cos α` otherwise (compression). BSN: `r_o·sin β`,
    /// `β = π/2 − s_n/(2r_o)`.
    pub fn farthest_fibre(&self) -> (f64, FibreSide) {
        let section = self.joint.section();
        let (ro, ri) = (section.outer_radius_mm(), section.inner_radius_mm());
        let half_notch_rad = section.notch_angle_rad() / 2.0;
        match section.style() {
            NotchStyle::Bsn => {
                let beta = PI / 2.0 - half_notch_rad;
                (ro * libm::sin(beta), FibreSide::NotchCorners)
            }
            NotchStyle::Uan => {
                let y_bar = self.y_bar();
                let cos_alpha = libm::cos(PI - half_notch_rad);
                let crest = ro - y_bar;
                let (edge, side) = if cos_alpha > 0.0 {
                    (y_bar - ri * cos_alpha, FibreSide::NotchInnerEdge)
                } else {
                    (y_bar - ro * cos_alpha, FibreSide::NotchOuterEdge)
                };
                if edge > crest {
                    (edge, side)
                } else {
                    (crest, FibreSide::BackboneCrest)
                }
            }
        }
    }

    /// Peak material strain at joint angle `θ`: `ε_max = κ·d/(1 + ȳ·κ)` at the farthest fibre,
    /// `κ` from [`Mechanics::curvature_at_angle_per_mm`]. Equal to `d·θ/(N·h)`.
    pub fn material_strain(&self, angle_rad: f64) -> f64 {
        let kappa = self.curvature_at_angle_per_mm(angle_rad);
        let (d, _) = self.farthest_fibre();
        kappa * d / (1.0 + self.y_bar() * kappa)
    }

    /// Joint angle at which the farthest fibre reaches `strain_limit` (rad):
    /// `θ = N·h·ε_limit/d`.
    pub fn angle_at_material_strain_rad(&self, strain_limit: f64) -> f64 {
        let (d, _) = self.farthest_fibre();
        self.n() * self.h() * strain_limit / d
    }

    /// The usable range (rad) and what ends it: the smallest of the notch-closing angle, the
    /// angle at which the farthest fibre reaches `material_strain_limit`, and the angle at which
    /// the sensor reaches `saturation_strain` (Eq. 3). Ties go to the earlier in that order.
    pub fn usable_range_rad(
        &self,
        saturation_strain: f64,
        material_strain_limit: f64,
    ) -> (f64, RangeLimit) {
        let limits = [
            (self.closing_angle_rad(), RangeLimit::NotchClosing),
            (
                self.angle_at_material_strain_rad(material_strain_limit),
                RangeLimit::Material,
            ),
            (
                libm::fabs(self.joint.angle_at_strain(saturation_strain)),
                RangeLimit::SensorSaturation,
            ),
        ];
        limits.into_iter().fold(
            limits[0],
            |best, next| if next.0 < best.0 { next } else { best },
        )
    }

    /// Area of the notched section (mm²): the annular sector `α·(r_o² − r_i²)` for UAN, two
    /// sectors `2β·(r_o² − r_i²)` for BSN.
    pub fn section_area_mm2(&self) -> f64 {
        let (ro, ri, half_rad) = self.ring_and_half_angle();
        // One sector for UAN, two (one between each pair of notches) for BSN.
        let sectors = f64::from(self.joint.style().notches_per_level());
        sectors * half_rad * (ro * ro - ri * ri)
    }

    /// Second moment of area of the notched section about its neutral axis (mm⁴).
    ///
    /// UAN, about the tube axis: `I₀ = (r_o⁴ − r_i⁴)/4·(α + sin α·cos α)`, then
    /// `I = I₀ − A·ȳ²`. BSN, two sectors of half-angle `β` centred on the `x` axis:
    /// `I = (r_o⁴ − r_i⁴)/2·(β − sin β·cos β)`.
    pub fn second_moment_mm4(&self) -> f64 {
        let (ro, ri, half_rad) = self.ring_and_half_angle();
        let quartic = ro * ro * ro * ro - ri * ri * ri * ri;
        let (s, c) = (libm::sin(half_rad), libm::cos(half_rad));
        match self.joint.style() {
            NotchStyle::Uan => {
                let about_axis = quartic / 4.0 * (half_rad + s * c);
                let y_bar = self.y_bar();
                about_axis - self.section_area_mm2() * y_bar * y_bar
            }
            NotchStyle::Bsn => quartic / 2.0 * (half_rad - s * c),
        }
    }

    /// `(r_o, r_i, half-angle)`: `α = π − s_n/(2r_o)` for UAN, `β = π/2 − s_n/(2r_o)` for BSN.
    fn ring_and_half_angle(&self) -> (f64, f64, f64) {
        let section = self.joint.section();
        let half_notch_rad = section.notch_angle_rad() / 2.0;
        let half = match section.style() {
            NotchStyle::Uan => PI - half_notch_rad,
            NotchStyle::Bsn => PI / 2.0 - half_notch_rad,
        };
        (section.outer_radius_mm(), section.inner_radius_mm(), half)
    }

    /// Bending moment that holds the joint at angle `θ` (N·mm), linear form: each notch is a
    /// beam of length `h`, `M = E·I·θ_n/h` with `θ_n = θ/N`.
    pub fn moment_nmm(&self, angle_rad: f64, youngs_modulus_pa: f64) -> f64 {
        let e_n_per_mm2 = youngs_modulus_pa / PA_PER_N_PER_MM2;
        e_n_per_mm2 * self.second_moment_mm4() * angle_rad / (self.n() * self.h())
    }

    /// Tendon force that holds the joint at angle `θ` (N): `F = M/(ȳ + r_t)`, that is
    /// `E·I·θ_n/(h·(ȳ + r_t))`. Friction ignored.
    pub fn tendon_force_n(&self, angle_rad: f64, youngs_modulus_pa: f64) -> f64 {
        self.moment_nmm(angle_rad, youngs_modulus_pa) / self.moment_arm_mm()
    }

    /// Tendon force per degree of joint angle (N/°).
    pub fn tendon_force_per_deg_n(&self, youngs_modulus_pa: f64) -> f64 {
        self.tendon_force_n(PI / 180.0, youngs_modulus_pa)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::section::CrossSection;
    use approx::assert_relative_eq;

    fn mech(style: NotchStyle, ro: f64, ri: f64, sn: f64, ss: f64) -> Mechanics {
        let joint = Joint::new(
            CrossSection::new(style, ro, ri, sn, ss).unwrap(),
            0.5,
            0.5,
            10,
            9.5,
        )
        .unwrap();
        Mechanics::new(joint, ri - 0.14).unwrap()
    }

    fn joint_d() -> Mechanics {
        mech(NotchStyle::Uan, 0.8, 0.61, 3.52, 0.4)
    }

    /// Joint D by hand: α = π − 2.2 = 0.941593, ȳ = 0.609011 mm (Eq. 2), r_t = 0.47 mm, so
    /// r_t + ȳ = 1.079011 mm/rad = 0.018832 mm/° (53.10 °/mm).
    #[test]
    fn joint_d_stroke_per_degree_by_hand() {
        let m = joint_d();
        assert_relative_eq!(
            m.joint().section().neutral_axis_mm(),
            0.609011,
            epsilon = 1e-6
        );
        assert_relative_eq!(m.stroke_per_deg_mm(), 0.018832, epsilon = 1e-6);
        assert_relative_eq!(1.0 / m.stroke_per_deg_mm(), 53.10, epsilon = 0.01);
    }

    #[test]
    fn stroke_model_is_linear_and_inverts() {
        for m in [joint_d(), mech(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13)] {
            for stroke in [0.01, 0.2, 0.9] {
                let th = m.angle_from_stroke_rad(stroke);
                assert_relative_eq!(th, stroke / m.moment_arm_mm(), max_relative = 1e-12);
                let kappa = m.curvature_at_angle_per_mm(th);
                assert_relative_eq!(kappa, m.curvature_per_mm(stroke), max_relative = 1e-12);
            }
        }
    }

    #[test]
    fn closing_limit_is_todays_closing_angle() {
        for m in [joint_d(), mech(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13)] {
            assert_relative_eq!(
                m.closing_angle_rad(),
                m.joint().closing_angle_rad(),
                max_relative = 1e-14
            );
        }
    }

    /// Joint D: cos α = 0.588501 > 0, the notch-side edge is 0.609011 − 0.61·0.588501 =
    /// 0.250025 mm from ȳ, farther than the crest 0.190989 mm.
    #[test]
    fn farthest_fibre_on_joint_d_is_the_notch_edge() {
        let (d, side) = joint_d().farthest_fibre();
        assert_eq!(side, FibreSide::NotchInnerEdge);
        assert_relative_eq!(d, 0.250025, epsilon = 1e-6);
        // A short notch leaves the crest and the outer corner to compete.
        let (_, side) = mech(NotchStyle::Uan, 1.0, 0.9, 0.6, 0.4).farthest_fibre();
        assert_eq!(side, FibreSide::NotchOuterEdge);
    }

    #[test]
    fn material_strain_is_linear_in_angle() {
        let m = joint_d();
        let lim = m.angle_at_material_strain_rad(0.03);
        assert_relative_eq!(m.material_strain(lim), 0.03, max_relative = 1e-12);
        let (d, _) = m.farthest_fibre();
        assert_relative_eq!(m.material_strain(0.4), d * 0.4 / 5.0, max_relative = 1e-12);
    }

    /// Joint D by hand: A = α·(r_o² − r_i²) = 0.941593·0.2679 = 0.252253 mm²,
    /// I₀ = (r_o⁴ − r_i⁴)/4·(α + sin α·cos α) and I = I₀ − A·ȳ² = 0.00251961 mm⁴; with
    /// E = 2.5 GPa, F per degree = 2500·I·(π/1800)/(0.5·1.079011) = 0.0203777 N.
    #[test]
    fn joint_d_section_and_force_by_hand() {
        let m = joint_d();
        assert_relative_eq!(m.section_area_mm2(), 0.252253, epsilon = 1e-6);
        assert_relative_eq!(m.second_moment_mm4(), 0.00251961, epsilon = 1e-8);
        assert_relative_eq!(m.tendon_force_per_deg_n(2.5e9), 0.0203777, epsilon = 1e-7);
    }

    #[test]
    fn full_ring_has_the_annulus_moment() {
        // BSN with vanishing notches tends to the whole annulus, π(r_o⁴ − r_i⁴)/4.
        let m = mech(NotchStyle::Bsn, 1.0, 0.8, 1e-9, 0.5);
        assert_relative_eq!(
            m.second_moment_mm4(),
            PI * (1.0 - 0.8f64.powi(4)) / 4.0,
            max_relative = 1e-8
        );
    }

    #[test]
    fn refuses_a_tendon_outside_the_lumen() {
        let j = *joint_d().joint();
        assert!(Mechanics::new(j, 0.0).is_err());
        assert!(Mechanics::new(j, f64::NAN).is_err());
        assert!(matches!(
            Mechanics::new(j, 0.7),
            Err(GeometryError::TendonOutsideLumen { .. })
        ));
    }
}
