use core::f64::consts::PI;

use crate::error::{positive, GeometryError};

/// How the notches are cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
pub enum NotchStyle {
    /// Unidirectional asymmetric notch: one notch per level, centred at `φ = π`; one sensor on
    /// the uncut backbone, centred at `φ = 0`.
    Uan,
    /// Bidirectional symmetric notch: a pair of notches per level, centred at `φ = 0` and
    /// `φ = π`; two sensors on the backbones between them, sensor 1 straddling `φ = 0` (plane
    /// `+y_s`) and sensor 2 straddling `φ = π` (plane `−y_s`).
    Bsn,
}

impl NotchStyle {
    /// Notches cut at one axial level: 1 for UAN, 2 for BSN.
    pub fn notches_per_level(self) -> u32 {
        match self {
            Self::Uan => 1,
            Self::Bsn => 2,
        }
    }

    /// Sensors written on the joint: 1 for UAN, 2 for BSN.
    pub fn sensor_count(self) -> u32 {
        self.notches_per_level()
    }
}

/// The cross-section through a notch level, with the sensor plane(s).
///
/// Built by [`CrossSection::new`], which checks that the section is physical; every accessor
/// then returns a finite value.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CrossSection {
    style: NotchStyle,
    outer_radius_mm: f64,
    inner_radius_mm: f64,
    notch_arc_mm: f64,
    sensor_arc_mm: f64,
}

impl CrossSection {
    /// A cross-section from the paper's Table I quantities: style, outer radius `r_o`, inner
    /// radius `r_i`, notch arc `s_n` (one notch, on the outer surface) and sensor arc `s_s`
    /// (between the two arms of one sensor).
    ///
    /// # Errors
    /// A value that is not finite or not positive, `r_i ≥ r_o`, notches that take the whole
    /// circumference, a sensor whose arms would lie on a notch, or a sensor on the neutral plane.
    pub fn new(
        style: NotchStyle,
        outer_radius_mm: f64,
        inner_radius_mm: f64,
        notch_arc_mm: f64,
        sensor_arc_mm: f64,
    ) -> Result<Self, GeometryError> {
        positive("outer_radius_mm", outer_radius_mm)?;
        positive("inner_radius_mm", inner_radius_mm)?;
        positive("notch_arc_mm", notch_arc_mm)?;
        positive("sensor_arc_mm", sensor_arc_mm)?;
        if inner_radius_mm >= outer_radius_mm {
            return Err(GeometryError::InnerRadiusTooLarge {
                inner_mm: inner_radius_mm,
                outer_mm: outer_radius_mm,
            });
        }
        let circumference_mm = 2.0 * PI * outer_radius_mm;
        let total_arc_mm = notch_arc_mm * f64::from(style.notches_per_level());
        if total_arc_mm >= circumference_mm {
            return Err(GeometryError::NotchTooLong {
                total_arc_mm,
                circumference_mm,
            });
        }
        let (min_mm, max_mm) = match style {
            NotchStyle::Uan => (0.0, circumference_mm - notch_arc_mm),
            NotchStyle::Bsn => (notch_arc_mm, PI * outer_radius_mm),
        };
        if sensor_arc_mm <= min_mm || sensor_arc_mm >= max_mm {
            return Err(GeometryError::SensorArcOutOfRange {
                sensor_arc_mm,
                min_mm,
                max_mm,
            });
        }
        let section = Self {
            style,
            outer_radius_mm,
            inner_radius_mm,
            notch_arc_mm,
            sensor_arc_mm,
        };
        let offset_mm = section.offset_mm();
        // Δy is a difference of two O(r_o) numbers; below a few ulps of r_o it is noise.
        if offset_mm.abs() <= 4.0 * f64::EPSILON * outer_radius_mm {
            return Err(GeometryError::ZeroOffset { offset_mm });
        }
        Ok(section)
    }

    /// Notch style.
    pub fn style(&self) -> NotchStyle {
        self.style
    }

    /// Outer radius `r_o` (mm).
    pub fn outer_radius_mm(&self) -> f64 {
        self.outer_radius_mm
    }

    /// Inner radius `r_i` (mm).
    pub fn inner_radius_mm(&self) -> f64 {
        self.inner_radius_mm
    }

    /// Arc length of one notch on the outer surface, `s_n` (mm).
    pub fn notch_arc_mm(&self) -> f64 {
        self.notch_arc_mm
    }

    /// Arc between the two arms of one sensor, `s_s` (mm).
    pub fn sensor_arc_mm(&self) -> f64 {
        self.sensor_arc_mm
    }

    /// Outer circumference `2π·r_o` (mm).
    pub fn circumference_mm(&self) -> f64 {
        2.0 * PI * self.outer_radius_mm
    }

    /// Angle subtended by one notch, `φ_n = s_n / r_o` (rad).
    pub fn notch_angle_rad(&self) -> f64 {
        self.notch_arc_mm / self.outer_radius_mm
    }

    /// Angle between the arms of one sensor, `φ_s = s_s / r_o` (rad).
    pub fn sensor_angle_rad(&self) -> f64 {
        self.sensor_arc_mm / self.outer_radius_mm
    }

    /// Sensor plane `y_s = r_o·cos(φ_s/2)` (Eq. 1), in mm from the tube axis.
    ///
    /// For BSN this is sensor 1's plane; sensor 2's is `−y_s`.
    pub fn sensor_plane_mm(&self) -> f64 {
        self.outer_radius_mm * libm::cos(self.sensor_angle_rad() / 2.0)
    }

    /// Neutral plane `ȳ` (Eq. 2), in mm from the tube axis: the centroid of the annulus left
    /// after the notch, an annular sector of half-angle `α = π − s_n/(2 r_o)`:
    ///
    /// `ȳ = 2·sin α·(r_o³ − r_i³) / (3·α·(r_o² − r_i²))`, which is the paper's
    /// `4·sin(π − s_n/(2r_o))(r_o³ − r_i³) / (3(2π − s_n/r_o)(r_o² − r_i²))`.
    ///
    /// A BSN section is symmetric, so `ȳ = 0`.
    pub fn neutral_axis_mm(&self) -> f64 {
        match self.style {
            NotchStyle::Bsn => 0.0,
            NotchStyle::Uan => {
                let (ro, ri) = (self.outer_radius_mm, self.inner_radius_mm);
                let alpha = PI - self.notch_angle_rad() / 2.0;
                2.0 * libm::sin(alpha) * (ro * ro * ro - ri * ri * ri)
                    / (3.0 * alpha * (ro * ro - ri * ri))
            }
        }
    }

    /// `Δy = y_s − ȳ` (Eq. 3): distance from the neutral plane to the sensor plane (mm).
    pub fn offset_mm(&self) -> f64 {
        self.sensor_plane_mm() - self.neutral_axis_mm()
    }

    /// Distance between the two BSN sensor planes, `Δy^(1,2) = 2·y_s` (mm); `None` for UAN.
    pub fn two_sensor_offset_mm(&self) -> Option<f64> {
        match self.style {
            NotchStyle::Uan => None,
            NotchStyle::Bsn => Some(2.0 * self.sensor_plane_mm()),
        }
    }

    /// Distance from the neutral plane to the farthest fibre on the notched (compressed) side,
    /// `ȳ + r_o`: the notch faces touch there first.
    pub fn notch_side_reach_mm(&self) -> f64 {
        self.neutral_axis_mm() + self.outer_radius_mm
    }

    /// Distance from the neutral plane to the farthest fibre on the stretched side (mm): `r_o − ȳ`
    /// for UAN (the backbone's crest), `r_o·cos(φ_n/2)` for BSN (the notch corners).
    pub fn backbone_reach_mm(&self) -> f64 {
        match self.style {
            NotchStyle::Uan => self.outer_radius_mm - self.neutral_axis_mm(),
            NotchStyle::Bsn => self.outer_radius_mm * libm::cos(self.notch_angle_rad() / 2.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn joint_a() -> CrossSection {
        CrossSection::new(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4).unwrap()
    }

    #[test]
    fn eq2_matches_paper_form() {
        let s = joint_a();
        let (ro, ri, sn) = (1.24f64, 0.875f64, 5.61f64);
        let paper = 4.0 * (PI - sn / (2.0 * ro)).sin() * (ro.powi(3) - ri.powi(3))
            / (3.0 * (2.0 * PI - sn / ro) * (ro * ro - ri * ri));
        assert_relative_eq!(s.neutral_axis_mm(), paper, max_relative = 1e-14);
    }

    #[test]
    fn eq1_sensor_plane() {
        let s = joint_a();
        assert_relative_eq!(
            s.sensor_plane_mm(),
            1.24 * (0.2f64 / 1.24).cos(),
            max_relative = 1e-15
        );
        assert!(s.offset_mm() > 0.28 && s.offset_mm() < 0.29);
    }

    #[test]
    fn bsn_is_symmetric() {
        let c = CrossSection::new(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13).unwrap();
        assert_eq!(c.neutral_axis_mm(), 0.0);
        assert_relative_eq!(c.two_sensor_offset_mm().unwrap(), 2.0 * c.sensor_plane_mm());
        assert_eq!(joint_a().two_sensor_offset_mm(), None);
    }

    #[test]
    fn refuses_unphysical_sections() {
        let table = [
            (NotchStyle::Uan, 1.0, 1.0, 1.0, 0.4), // r_i = r_o
            (NotchStyle::Uan, 1.0, 0.5, 6.3, 0.4), // notch beyond circumference
            (NotchStyle::Bsn, 1.0, 0.5, 3.2, 0.4), // BSN pair overlaps
            (NotchStyle::Uan, 1.0, 0.5, 5.0, 1.5), // arms on the notch
            (NotchStyle::Bsn, 1.0, 0.5, 1.0, 0.9), // BSN arms inside notch 1
            (NotchStyle::Bsn, 1.0, 0.5, 1.0, PI),  // BSN planes coincide
            (NotchStyle::Uan, f64::NAN, 0.5, 1.0, 0.4),
            (NotchStyle::Uan, 1.0, -0.5, 1.0, 0.4),
        ];
        for (style, ro, ri, sn, ss) in table {
            assert!(
                CrossSection::new(style, ro, ri, sn, ss).is_err(),
                "{style:?} {ro} {ri} {sn} {ss}"
            );
        }
    }
}
