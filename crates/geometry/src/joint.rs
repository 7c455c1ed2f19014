use core::f64::consts::PI;

use crate::divider::Divider;
use crate::error::{positive, GeometryError};
use crate::section::{CrossSection, NotchStyle};

/// A whole sensing joint: its cross-section plus the notch pattern along the tube.
///
/// Bending is taken to happen only in the notched segments (the paper's assumption), and the
/// sensor runs the whole joint length `L`, so it reads the mean strain `ε = Δy·θ/L` (Eq. 3).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Joint {
    section: CrossSection,
    notch_width_mm: f64,
    notch_spacing_mm: f64,
    notch_count: u32,
    length_mm: f64,
}

impl Joint {
    /// A joint from its cross-section, notch width `h`, notch spacing `c`, notch count `N` (per
    /// side for BSN) and joint length `L`.
    ///
    /// Whether `L` agrees with `N·h + (N−1)·c` is a design rule of the planner, not checked
    /// here: the estimator only needs `L` as the sensor's gauge length.
    ///
    /// # Errors
    /// A length that is not finite or not positive, or `N = 0`.
    pub fn new(
        section: CrossSection,
        notch_width_mm: f64,
        notch_spacing_mm: f64,
        notch_count: u32,
        length_mm: f64,
    ) -> Result<Self, GeometryError> {
        positive("notch_width_mm", notch_width_mm)?;
        positive("notch_spacing_mm", notch_spacing_mm)?;
        positive("joint_length_mm", length_mm)?;
        if notch_count == 0 {
            return Err(GeometryError::NoNotches);
        }
        Ok(Self {
            section,
            notch_width_mm,
            notch_spacing_mm,
            notch_count,
            length_mm,
        })
    }

    /// The cross-section.
    pub fn section(&self) -> &CrossSection {
        &self.section
    }

    /// Notch style (shortcut for `section().style()`).
    pub fn style(&self) -> NotchStyle {
        self.section.style()
    }

    /// Notch width `h` along the tube (mm).
    pub fn notch_width_mm(&self) -> f64 {
        self.notch_width_mm
    }

    /// Uncut length `c` between neighbouring notches (mm).
    pub fn notch_spacing_mm(&self) -> f64 {
        self.notch_spacing_mm
    }

    /// Notch count `N` (per side for BSN).
    pub fn notch_count(&self) -> u32 {
        self.notch_count
    }

    /// Joint length `L` (mm).
    pub fn length_mm(&self) -> f64 {
        self.length_mm
    }

    /// Length the notch pattern spans, `N·h + (N−1)·c` (mm).
    pub fn notched_length_mm(&self) -> f64 {
        let n = f64::from(self.notch_count);
        n * self.notch_width_mm + (n - 1.0) * self.notch_spacing_mm
    }

    /// Strain per radian of bending, `Δy/L`.
    pub fn strain_per_rad(&self) -> f64 {
        self.section.offset_mm() / self.length_mm
    }

    /// Strain (as a fraction) per degree of bending: the sensor's geometric sensitivity.
    pub fn strain_per_deg(&self) -> f64 {
        self.strain_per_rad() * PI / 180.0
    }

    /// Sensor strain at bending angle `θ` (Eq. 3): `ε = Δy·θ/L`. For BSN this is sensor 1; sensor
    /// 2 reads `−ε`.
    pub fn strain(&self, angle_rad: f64) -> f64 {
        angle_rad * self.strain_per_rad()
    }

    /// Bending angle from sensor strain, the inverse of [`Joint::strain`]: `θ = ε·L/Δy`.
    pub fn angle_from_strain(&self, strain: f64) -> f64 {
        strain * self.length_mm / self.section.offset_mm()
    }

    /// Bending angle from both BSN sensors (Eq. 7), or `None` for UAN.
    ///
    /// Sign convention: sensor 1 lies in the plane `+y_s` and is stretched by a positive angle,
    /// sensor 2 lies at `−y_s` and is compressed, so `θ = L·(ε₁ − ε₂)/Δy^(1,2)`. The paper prints
    /// `ε₂ − ε₁`, which is the same equation with the sensors numbered the other way round.
    pub fn two_sensor_angle(&self, strain_1: f64, strain_2: f64) -> Option<f64> {
        self.section
            .two_sensor_offset_mm()
            .map(|dy12| self.length_mm * (strain_1 - strain_2) / dy12)
    }

    /// Bending angle at which the notch faces touch (rad): each notch closes once its width `h`
    /// is taken up at the farthest fibre, `ȳ + r_o` from the neutral plane, so
    /// `θ_close = N·h/(ȳ + r_o)`.
    pub fn closing_angle_rad(&self) -> f64 {
        f64::from(self.notch_count) * self.notch_width_mm / self.section.notch_side_reach_mm()
    }

    /// Sensor strain at the notch-closing angle.
    pub fn strain_at_closing(&self) -> f64 {
        self.strain(self.closing_angle_rad())
    }

    /// Peak strain in the backbone at bending angle `θ`. The bending is carried by the notched
    /// segments alone, `N·h` long, so the local curvature is `θ/(N·h)` and the farthest stretched
    /// fibre sees `reach·θ/(N·h)`.
    pub fn backbone_strain(&self, angle_rad: f64) -> f64 {
        let bent_length_mm = f64::from(self.notch_count) * self.notch_width_mm;
        self.section.backbone_reach_mm() * angle_rad / bent_length_mm
    }

    /// Bending angle at which the sensor strain reaches `strain` (rad), for limits such as
    /// the sensor's saturation strain.
    pub fn angle_at_strain(&self, strain: f64) -> f64 {
        self.angle_from_strain(strain)
    }

    /// Bending angle at which the backbone's peak strain reaches `strain` (rad).
    pub fn angle_at_backbone_strain(&self, strain: f64) -> f64 {
        strain * f64::from(self.notch_count) * self.notch_width_mm
            / self.section.backbone_reach_mm()
    }

    /// Expected relative resistance change `ΔR/R₀` per degree for a gauge factor `GF` (Eq. 5).
    pub fn resistance_ratio_per_deg(&self, gauge_factor: f64) -> f64 {
        gauge_factor * self.strain_per_deg()
    }

    /// Expected divider voltage change per degree around the straight joint (V/°), for a sensor
    /// of gauge factor `GF` and unstrained resistance `R₀` read through `divider`:
    /// `dV/dθ = dV/dR(R₀) · R₀·GF · dε/dθ`.
    pub fn voltage_per_deg(&self, gauge_factor: f64, r0_ohm: f64, divider: &Divider) -> f64 {
        divider.slope_v_per_ohm(r0_ohm) * r0_ohm * self.resistance_ratio_per_deg(gauge_factor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn joint(style: NotchStyle, ro: f64, ri: f64, sn: f64, ss: f64) -> Joint {
        Joint::new(
            CrossSection::new(style, ro, ri, sn, ss).unwrap(),
            0.5,
            0.5,
            10,
            9.5,
        )
        .unwrap()
    }

    /// The paper's Section IV-A numbers: Joint A at 26° and Joint C at 40° reach ~1.4% strain
    /// (1.3774% and 1.3949%; the paper's ε_peak, from measured
    /// angles, is 1.35% and 1.37%).
    #[test]
    fn paper_peak_strains() {
        let a = joint(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4);
        let c = joint(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13);
        assert_relative_eq!(a.strain(26f64.to_radians()) * 100.0, 1.38, epsilon = 0.006);
        assert_relative_eq!(c.strain(40f64.to_radians()) * 100.0, 1.40, epsilon = 0.006);
    }

    #[test]
    fn strain_inverse_round_trips() {
        let a = joint(NotchStyle::Uan, 0.8, 0.61, 3.52, 0.4);
        for deg in [-90.0, -1.0, 0.0, 0.3, 58.0, 400.0] {
            let th = f64::to_radians(deg);
            assert_relative_eq!(a.angle_from_strain(a.strain(th)), th, epsilon = 1e-14);
        }
        assert_relative_eq!(
            a.strain_per_deg(),
            a.strain(1f64.to_radians()),
            max_relative = 1e-15
        );
    }

    #[test]
    fn two_sensor_angle_recovers_theta() {
        let c = joint(NotchStyle::Bsn, 0.8, 0.61, 1.65, 2.13);
        let th = 0.3;
        let e1 = c.strain(th);
        assert_relative_eq!(c.two_sensor_angle(e1, -e1).unwrap(), th, epsilon = 1e-14);
        let a = joint(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4);
        assert_eq!(a.two_sensor_angle(0.01, 0.0), None);
    }

    #[test]
    fn closing_angle_closes_the_notch_at_the_far_fibre() {
        let a = joint(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4);
        let per_notch = a.closing_angle_rad() / 10.0;
        // The gap at the far fibre is h − reach·θ_notch: zero at closing.
        assert_relative_eq!(
            0.5 - a.section().notch_side_reach_mm() * per_notch,
            0.0,
            epsilon = 1e-15
        );
        assert_relative_eq!(a.strain_at_closing(), a.strain(a.closing_angle_rad()));
        let sat = a.angle_at_strain(0.02);
        assert_relative_eq!(a.strain(sat), 0.02, max_relative = 1e-14);
        let lim = a.angle_at_backbone_strain(0.03);
        assert_relative_eq!(a.backbone_strain(lim), 0.03, max_relative = 1e-14);
    }

    #[test]
    fn refuses_bad_joints() {
        let s = CrossSection::new(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4).unwrap();
        assert_eq!(
            Joint::new(s, 0.5, 0.5, 0, 9.5),
            Err(GeometryError::NoNotches)
        );
        assert!(Joint::new(s, 0.0, 0.5, 10, 9.5).is_err());
        assert!(Joint::new(s, 0.5, f64::INFINITY, 10, 9.5).is_err());
        assert!(Joint::new(s, 0.5, 0.5, 10, -1.0).is_err());
    }
}
