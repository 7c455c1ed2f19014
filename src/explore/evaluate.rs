//! Scoring one candidate: the geometry crate's section, joint and mechanics, the sensing model
//! and the constraints. The hot loop of the search: no allocation, no strings.

use dlw_geometry::{CrossSection, Joint, Mechanics, RangeLimit};

use super::grid::Params;
use super::spec::{Constraints, Metric};

/// What a candidate is scored with: the sensing model and the limits, from the spec and the
/// base design.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Model {
    /// Gauge factor `GF`.
    pub gauge_factor: f64,
    /// Unstrained resistance `R₀` (Ω).
    pub r0_ohm: f64,
    /// The sensor's saturation strain (base design's `sensor_saturation_strain`).
    pub saturation_strain: f64,
    /// The backbone's strain limit (base design's `backbone_strain_limit`).
    pub material_strain_limit: f64,
    /// Young's modulus of the tube (Pa).
    pub youngs_modulus_pa: f64,
    /// The base design's explicit tendon offset, or `None` for `r_i − 0.14 mm` on each tube.
    pub tendon_offset_mm: Option<f64>,
    /// The spec's constraints.
    pub min_range_deg: f64,
    /// Whether the material limit counts toward the range and must hold at `min_range_deg`.
    pub material_within_limit: bool,
    /// Whether saturation counts toward the range and must not happen before `min_range_deg`.
    pub no_saturation: bool,
    /// Largest stroke per degree (mm/°), or infinity.
    pub max_stroke_per_deg_mm: f64,
    /// Largest tendon force per degree (N/°), or infinity.
    pub max_tendon_force_per_deg_n: f64,
    /// Smallest sensitivity (Ω/°), or 0.
    pub min_sensitivity_ohm_per_deg: f64,
}

impl Model {
    /// The constraint numbers of `c`.
    pub fn with_constraints(mut self, c: &Constraints) -> Self {
        self.min_range_deg = c.min_range_deg;
        self.material_within_limit = c.material_within_limit;
        self.no_saturation = c.no_saturation;
        self.max_stroke_per_deg_mm = c.max_stroke_per_deg_mm.unwrap_or(f64::INFINITY);
        self.max_tendon_force_per_deg_n = c.max_tendon_force_per_deg_n.unwrap_or(f64::INFINITY);
        self.min_sensitivity_ohm_per_deg = c.min_sensitivity_ohm_per_deg.unwrap_or(0.0);
        self
    }
}

/// A candidate's numbers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DesignMetrics {
    /// Resistance change per degree, `R₀·GF·Δy/L·π/180` (Ω/°).
    pub sensitivity_ohm_per_deg: f64,
    /// Usable range (°).
    pub range_deg: f64,
    /// What ends it.
    pub range_limited_by: RangeLimit,
    /// Tendon force per degree (N/°).
    pub tendon_force_per_deg_n: f64,
    /// Tendon stroke per degree (mm/°).
    pub stroke_per_deg_mm: f64,
    /// Notch-closing angle (°).
    pub closing_deg: f64,
    /// Angle at the material's strain limit (°).
    pub material_limit_deg: f64,
    /// Angle at which the sensor saturates (°).
    pub saturation_limit_deg: f64,
    /// The twin's predicted accuracy: only for the front's candidates, when the spec asks.
    pub predicted: Option<super::Predicted>,
}

impl DesignMetrics {
    /// The value of `metric`.
    pub fn get(&self, metric: Metric) -> f64 {
        match metric {
            Metric::SensitivityOhmPerDeg => self.sensitivity_ohm_per_deg,
            Metric::RangeDeg => self.range_deg,
            Metric::TendonForcePerDegN => self.tendon_force_per_deg_n,
            Metric::StrokePerDegMm => self.stroke_per_deg_mm,
            // Not predicted (or the prediction failed): the worst, so it never wins.
            Metric::PredictedRmseDeg => self
                .predicted
                .map_or(f64::INFINITY, |p| p.linear_rmse_deg.min(p.pi_rmse_deg)),
            Metric::PredictedClosedLoopRmseDeg => self
                .predicted
                .map_or(f64::INFINITY, |p| p.closed_loop_rmse_deg),
        }
    }
}

/// A constraint of the spec, one bit in a failure mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Constraint {
    /// The notches stay open up to `min_range_deg`.
    NotchesOpen,
    /// The backbone stays within the material's strain limit up to `min_range_deg`.
    MaterialWithinLimit,
    /// The sensor does not saturate before `min_range_deg`.
    NoSaturation,
    /// Stroke per degree at most the spec's maximum.
    MaxStroke,
    /// Tendon force per degree at most the spec's maximum.
    MaxForce,
    /// Sensitivity at least the spec's minimum.
    MinSensitivity,
}

impl Constraint {
    /// Every constraint, in bit order.
    pub const ALL: [Constraint; 6] = [
        Constraint::NotchesOpen,
        Constraint::MaterialWithinLimit,
        Constraint::NoSaturation,
        Constraint::MaxStroke,
        Constraint::MaxForce,
        Constraint::MinSensitivity,
    ];

    /// The constraint's name as in specs.
    pub fn key(self) -> &'static str {
        match self {
            Self::NotchesOpen => "notches_open",
            Self::MaterialWithinLimit => "material_within_limit",
            Self::NoSaturation => "no_saturation",
            Self::MaxStroke => "max_stroke_per_deg_mm",
            Self::MaxForce => "max_tendon_force_per_deg_n",
            Self::MinSensitivity => "min_sensitivity_ohm_per_deg",
        }
    }

    /// This constraint's bit.
    pub fn bit(self) -> u8 {
        1 << (self as u8)
    }

    /// The candidate's value this constraint tests.
    pub fn value(self, m: &DesignMetrics) -> f64 {
        match self {
            Self::NotchesOpen => m.closing_deg,
            Self::MaterialWithinLimit => m.material_limit_deg,
            Self::NoSaturation => m.saturation_limit_deg,
            Self::MaxStroke => m.stroke_per_deg_mm,
            Self::MaxForce => m.tendon_force_per_deg_n,
            Self::MinSensitivity => m.sensitivity_ohm_per_deg,
        }
    }

    /// The limit the spec sets for this constraint's quantity.
    pub fn limit(self, model: &Model) -> f64 {
        match self {
            Self::NotchesOpen | Self::MaterialWithinLimit | Self::NoSaturation => {
                model.min_range_deg
            }
            Self::MaxStroke => model.max_stroke_per_deg_mm,
            Self::MaxForce => model.max_tendon_force_per_deg_n,
            Self::MinSensitivity => model.min_sensitivity_ohm_per_deg,
        }
    }

    /// How far `best` falls short of the limit, relative to it (0 when it meets it).
    pub fn shortfall(self, best: f64, model: &Model) -> f64 {
        let limit = self.limit(model);
        let gap = if self.larger_is_better() {
            limit - best
        } else {
            best - limit
        };
        if gap > 0.0 && limit > 0.0 {
            gap / limit
        } else {
            0.0
        }
    }

    /// Whether a larger value is closer to meeting the constraint.
    pub fn larger_is_better(self) -> bool {
        !matches!(self, Self::MaxStroke | Self::MaxForce)
    }

    /// The better of two values of this constraint's quantity.
    pub fn better(self, a: f64, b: f64) -> f64 {
        if (a >= b) == self.larger_is_better() {
            a
        } else {
            b
        }
    }

    /// The constraint in words with its limit, as the spec sets it.
    pub fn describe(self, model: &Model) -> String {
        let r = model.min_range_deg;
        match self {
            Self::NotchesOpen => format!("notches open up to min_range_deg = {r}° (the notch-closing angle)"),
            Self::MaterialWithinLimit => format!(
                "material strain within backbone_strain_limit = {} up to min_range_deg = {r}° (the angle at the material limit)",
                model.material_strain_limit
            ),
            Self::NoSaturation => format!(
                "no sensor saturation (sensor_saturation_strain = {}) up to min_range_deg = {r}° (the saturation angle)",
                model.saturation_strain
            ),
            Self::MaxStroke => format!(
                "max_stroke_per_deg_mm = {} (the stroke per degree)",
                model.max_stroke_per_deg_mm
            ),
            Self::MaxForce => format!(
                "max_tendon_force_per_deg_n = {} (the tendon force per degree)",
                model.max_tendon_force_per_deg_n
            ),
            Self::MinSensitivity => format!(
                "min_sensitivity_ohm_per_deg = {} (the sensitivity)",
                model.min_sensitivity_ohm_per_deg
            ),
        }
    }
}

/// Scores a candidate: its metrics and the mask of constraints it fails, or `None` when the
/// geometry crate refuses its section, joint or tendon (the design rules would too).
#[inline]
pub fn evaluate(p: &Params, model: &Model) -> Option<(DesignMetrics, u8)> {
    let section = CrossSection::new(
        p.style,
        p.outer_radius_mm,
        p.inner_radius_mm,
        p.notch_arc_mm,
        p.sensor_arc_mm,
    )
    .ok()?;
    let joint = Joint::new(
        section,
        p.notch_width_mm,
        p.notch_spacing_mm,
        p.notch_count,
        p.joint_length_mm(),
    )
    .ok()?;
    let tendon_mm = model
        .tendon_offset_mm
        .unwrap_or_else(|| Mechanics::default_tendon_offset_mm(p.inner_radius_mm));
    let mech = Mechanics::new(joint, tendon_mm).ok()?;
    let closing_deg = mech.closing_angle_rad().to_degrees();
    let material_limit_deg = mech
        .angle_at_material_strain_rad(model.material_strain_limit)
        .to_degrees();
    let saturation_limit_deg = joint
        .angle_at_strain(model.saturation_strain)
        .abs()
        .to_degrees();
    let (mut range_deg, mut range_limited_by) = (closing_deg, RangeLimit::NotchClosing);
    if model.material_within_limit && material_limit_deg < range_deg {
        (range_deg, range_limited_by) = (material_limit_deg, RangeLimit::Material);
    }
    if model.no_saturation && saturation_limit_deg < range_deg {
        (range_deg, range_limited_by) = (saturation_limit_deg, RangeLimit::SensorSaturation);
    }
    let metrics = DesignMetrics {
        sensitivity_ohm_per_deg: model.r0_ohm
            * joint.resistance_ratio_per_deg(model.gauge_factor).abs(),
        range_deg,
        range_limited_by,
        tendon_force_per_deg_n: mech.tendon_force_per_deg_n(model.youngs_modulus_pa),
        stroke_per_deg_mm: mech.stroke_per_deg_mm(),
        closing_deg,
        material_limit_deg,
        saturation_limit_deg,
        predicted: None,
    };
    Some((metrics, failures(&metrics, model)))
}

/// The mask of constraints `m` fails.
#[inline]
fn failures(m: &DesignMetrics, model: &Model) -> u8 {
    let r = model.min_range_deg;
    let checks = [
        m.closing_deg < r,
        model.material_within_limit && m.material_limit_deg < r,
        model.no_saturation && m.saturation_limit_deg < r,
        m.stroke_per_deg_mm > model.max_stroke_per_deg_mm,
        m.tendon_force_per_deg_n > model.max_tendon_force_per_deg_n,
        m.sensitivity_ohm_per_deg < model.min_sensitivity_ohm_per_deg,
    ];
    checks.iter().zip(Constraint::ALL).fold(
        0,
        |mask, (&fails, c)| if fails { mask | c.bit() } else { mask },
    )
}
