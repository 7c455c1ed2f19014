//! The second-moment ellipse of a component: the ellipse with the same area centroid and second
//! moments, whose major axis gives the pin's angle.
//!
//! With the component's central moments per pixel `μ20`, `μ11`, `μ02` (x right, y down), the
//! covariance `[[μ20, μ11], [μ11, μ02]]` has eigenvalues
//! `λ± = (μ20 + μ02)/2 ± √(((μ20 − μ02)/2)² + μ11²)`. A filled ellipse of semi-axes `a ≥ b` has
//! `λ+ = a²/4`, `λ− = b²/4`, so `a = 2√λ+`, `b = 2√λ−`. The major axis makes the angle
//! `φ = ½·atan2(2μ11, μ20 − μ02)` with +x measured towards +y, i.e. clockwise as displayed,
//! since image rows run downward. The angle reported is `−φ`: counter-clockwise positive as the
//! frame is displayed, 0 along +x, in (−90°, 90°] (an axis has no direction).

use super::Component;

/// An ellipse fitted to a pin, in frame pixel coordinates (x right, y down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipse {
    /// Centre x (px).
    pub center_x: f64,
    /// Centre y (px, downward).
    pub center_y: f64,
    /// Semi-major axis `a` (px).
    pub semi_major_px: f64,
    /// Semi-minor axis `b` (px).
    pub semi_minor_px: f64,
    /// The major axis's angle to +x, counter-clockwise positive as displayed, in (−90°, 90°].
    pub angle_deg: f64,
}

impl Ellipse {
    /// The second-moment ellipse of `c`, offset by the crop's corner `(x0, y0)` into frame
    /// coordinates.
    pub fn from_component(c: &Component, x0: f64, y0: f64) -> Self {
        let mean = (c.mu20 + c.mu02) / 2.0;
        let half_diff = (c.mu20 - c.mu02) / 2.0;
        let root = half_diff.hypot(c.mu11);
        let (major, minor) = (mean + root, (mean - root).max(0.0));
        let phi = 0.5 * (2.0 * c.mu11).atan2(c.mu20 - c.mu02);
        Self {
            center_x: c.mean_x + x0,
            center_y: c.mean_y + y0,
            semi_major_px: 2.0 * major.sqrt(),
            semi_minor_px: 2.0 * minor.sqrt(),
            angle_deg: axis_deg(-phi.to_degrees()),
        }
    }

    /// `a/b`, infinite for a one-pixel-wide component.
    pub fn axis_ratio(&self) -> f64 {
        if self.semi_minor_px > 0.0 {
            self.semi_major_px / self.semi_minor_px
        } else {
            f64::INFINITY
        }
    }
}

/// An axis angle folded into (−90°, 90°].
pub fn axis_deg(a: f64) -> f64 {
    let r = a.rem_euclid(180.0);
    if r > 90.0 {
        r - 180.0
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Moments of a filled ellipse with semi-axes a, b at displayed angle t.
    fn moments(a: f64, b: f64, t_deg: f64) -> Component {
        // In image coordinates the axis is at −t.
        let (s, c) = (-t_deg.to_radians()).sin_cos();
        let (la, lb) = (a * a / 4.0, b * b / 4.0);
        Component {
            area_px: 100,
            mean_x: 5.0,
            mean_y: 6.0,
            mu20: la * c * c + lb * s * s,
            mu11: (la - lb) * s * c,
            mu02: la * s * s + lb * c * c,
            touches_border: false,
        }
    }

    #[test]
    fn recovers_axes_and_displayed_angle() {
        for t in [-89.0, -45.0, -10.0, 0.0, 30.0, 60.0, 90.0] {
            let e = Ellipse::from_component(&moments(20.0, 4.0, t), 10.0, 1.0);
            assert_relative_eq!(e.semi_major_px, 20.0, epsilon = 1e-9);
            assert_relative_eq!(e.semi_minor_px, 4.0, epsilon = 1e-9);
            assert_relative_eq!(e.angle_deg, t, epsilon = 1e-9);
            assert_relative_eq!(e.axis_ratio(), 5.0, epsilon = 1e-9);
            assert_eq!((e.center_x, e.center_y), (15.0, 7.0));
        }
        // A pin drawn rising to the right (up the screen, rows decreasing) is positive.
        let rising = Component {
            mu11: -1.0,
            ..moments(10.0, 10.0, 0.0)
        };
        assert!(Ellipse::from_component(&rising, 0.0, 0.0).angle_deg > 0.0);
    }

    #[test]
    fn folds_axis_angles() {
        let table = [
            (0.0, 0.0),
            (90.0, 90.0),
            (-90.0, 90.0),
            (135.0, -45.0),
            (-100.0, 80.0),
            (270.0, 90.0),
        ];
        for (a, folded) in table {
            assert_relative_eq!(axis_deg(a), folded, epsilon = 1e-12);
        }
    }
}
