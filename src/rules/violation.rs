use dlw_geometry::GeometryError;

use crate::layout::LayoutError;

/// A design rule a design breaks. Every message names the parameter (or feature), its value and
/// the limit it must keep.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Violation {
    /// A length, strain or clearance that must be a positive, finite number is not.
    #[error("{name} = {value} must be a finite number greater than 0")]
    NotPositive {
        /// Key as written in the design file.
        name: &'static str,
        /// The value given.
        value: f64,
    },
    /// The inner radius is not smaller than the outer radius.
    #[error("inner_radius_mm = {inner_mm} must be smaller than outer_radius_mm = {outer_mm}")]
    InnerRadius {
        /// r_i (mm).
        inner_mm: f64,
        /// r_o (mm).
        outer_mm: f64,
    },
    /// A UAN notch takes the whole circumference.
    #[error(
        "notch_arc_mm = {notch_arc_mm} must be less than the circumference 2π·r_o = {circumference_mm:.4} mm"
    )]
    NotchArc {
        /// s_n (mm).
        notch_arc_mm: f64,
        /// 2π·r_o (mm).
        circumference_mm: f64,
    },
    /// The two notches of a BSN pair overlap.
    #[error(
        "notch_arc_mm = {notch_arc_mm} makes the BSN notch pair overlap: each notch must be shorter than half the circumference π·r_o = {half_mm:.4} mm"
    )]
    PairOverlap {
        /// s_n (mm).
        notch_arc_mm: f64,
        /// π·r_o (mm).
        half_mm: f64,
    },
    /// The sensor's arms would not sit on the backbone.
    #[error(
        "sensor_arc_mm = {sensor_arc_mm} must lie strictly between {min_mm:.4} and {max_mm:.4} mm so both arms sit on the backbone"
    )]
    SensorArc {
        /// s_s (mm).
        sensor_arc_mm: f64,
        /// Exclusive lower limit (mm).
        min_mm: f64,
        /// Exclusive upper limit (mm).
        max_mm: f64,
    },
    /// A count that must be at least 1 is 0.
    #[error("{name} = 0 must be at least 1")]
    Zero {
        /// Key as written in the design file.
        name: &'static str,
    },
    /// A count is above its limit.
    #[error("{name} = {value} must be at most {max}")]
    TooMany {
        /// Key as written in the design file.
        name: &'static str,
        /// The value given.
        value: u32,
        /// The limit.
        max: u32,
    },
    /// The pads are too big to fit round the tube.
    #[error("pads of pad_turns = {turns} at pad_pitch_mm = {pitch_mm} are {size_mm:.4} mm wide (2·turns·pitch); {count} of them with pad_gap_mm between must fit round the circumference 2π·r_o = {circumference_mm:.4} mm, so each may be at most {max_mm:.4} mm")]
    PadSize {
        /// Spiral turns.
        turns: u32,
        /// Spiral pitch (mm).
        pitch_mm: f64,
        /// Pad size (mm).
        size_mm: f64,
        /// Pads round the tube.
        count: u32,
        /// Circumference (mm).
        circumference_mm: f64,
        /// Largest pad that fits (mm).
        max_mm: f64,
    },
    /// A notch or the rib between two notches is no wider than the laser's kerf.
    #[error("{name} = {value_mm} must be larger than the kerf kerf_mm = {kerf_mm}")]
    NarrowerThanKerf {
        /// Key as written in the design file.
        name: &'static str,
        /// The value given (mm).
        value_mm: f64,
        /// The kerf (mm).
        kerf_mm: f64,
    },
    /// The joint length does not match the notch pattern.
    #[error(
        "joint_length_mm = {length_mm} does not match N·h + (N−1)·c = {expected_mm:.4} mm from notch_count, notch_width_mm and notch_spacing_mm (must agree to {tolerance_mm} mm)"
    )]
    Length {
        /// L as given (mm).
        length_mm: f64,
        /// N·h + (N−1)·c (mm).
        expected_mm: f64,
        /// Allowed absolute difference (mm).
        tolerance_mm: f64,
    },
    /// The pad spiral's turns are closer than one trace width, so they overlap.
    #[error(
        "pad_pitch_mm = {pitch_mm} must be at least the trace width trace_width_mm = {width_mm}"
    )]
    Pitch {
        /// Spiral pitch (mm).
        pitch_mm: f64,
        /// Trace width (mm).
        width_mm: f64,
    },
    /// A written trace comes closer than the clearance to a cut or to another trace.
    #[error("{}", clearance_message(what, *x_mm, *s_mm, *gap_mm, *crossing, other, *required_mm))]
    Clearance {
        /// The trace, e.g. `sensor 1 arm`.
        what: String,
        /// Axial position of its closest point (mm).
        x_mm: f64,
        /// Arc-length position of its closest point, in the drawing's window (mm).
        s_mm: f64,
        /// Edge-to-edge gap (mm); negative when the written lines overlap.
        gap_mm: f64,
        /// The centre line touches or crosses the other feature, so the gap says nothing more.
        crossing: bool,
        /// The other feature, e.g. `notch 4`.
        other: String,
        /// The clearance in force (mm).
        required_mm: f64,
    },
    /// A notch reaches past the free end or the parting line.
    #[error("{what} reaches x = {x_mm:.4} mm, {past_mm:.4} mm past {beyond} (every cut must lie inside the joint, between the free end x = 0 and the parting line x = {length_mm:.4} mm)")]
    OutsideJoint {
        /// The notch, e.g. `notch 1`.
        what: String,
        /// Its farthest point, x (mm).
        x_mm: f64,
        /// The edge it passes, e.g. `the free end x = 0`.
        beyond: String,
        /// How far past (mm).
        past_mm: f64,
        /// The joint's length, free end to parting line (mm).
        length_mm: f64,
    },
    /// Two notches touch or overlap.
    #[error("{what} overlaps {other} at x = {x_mm:.4} mm, s = {s_mm:.4} mm: notches must be separate cuts with a web wider than the kerf between them")]
    NotchOverlap {
        /// One notch.
        what: String,
        /// The other.
        other: String,
        /// Where, x (mm).
        x_mm: f64,
        /// Where, s (mm).
        s_mm: f64,
    },
    /// The web between two notches is no wider than the kerf.
    #[error("the web between {what} and {other} at x = {x_mm:.4} mm, s = {s_mm:.4} mm is {web_mm:.4} mm wide; it must be wider than the kerf kerf_mm = {kerf_mm}")]
    NotchWeb {
        /// One notch.
        what: String,
        /// The other.
        other: String,
        /// Where, x (mm).
        x_mm: f64,
        /// Where, s (mm).
        s_mm: f64,
        /// The web (mm).
        web_mm: f64,
        /// The kerf (mm).
        kerf_mm: f64,
    },
    /// A drawing does not match the design it is to be cut with.
    #[error("the drawing's {quantity} is {drawing} but the design's is {design}: this drawing is not of this design")]
    DrawingMismatch {
        /// What differs, e.g. `notch style`.
        quantity: &'static str,
        /// As drawn.
        drawing: String,
        /// As designed.
        design: String,
    },
    /// The cross-section itself is not physical (caught by the geometry crate).
    #[error("{0}")]
    Geometry(GeometryError),
    /// The fabrication values cannot be laid out.
    #[error("{0}")]
    Layout(LayoutError),
    /// The tube wall is thinner than a cutting set cuts cleanly.
    #[error(
        "tube wall r_o − r_i = {wall_mm:.4} mm (outer_radius_mm = {outer_mm}, inner_radius_mm = {inner_mm}) is thinner than min_wall_mm = {min_mm} mm of process set {set:?} ({operation}), the thinnest wall it cuts cleanly: use a thicker tube, or a set made and tested for thin walls"
    )]
    WallTooThin {
        /// `r_o − r_i` (mm).
        wall_mm: f64,
        /// r_o (mm).
        outer_mm: f64,
        /// r_i (mm).
        inner_mm: f64,
        /// The set's `min_wall_mm` (mm).
        min_mm: f64,
        /// The set's name.
        set: String,
        /// What the set cuts: `notches` or `parting`.
        operation: &'static str,
    },
    /// Any other reason the design was refused, as its message.
    #[error("{0}")]
    Other(String),
}

fn clearance_message(
    what: &str,
    x: f64,
    s: f64,
    gap: f64,
    crossing: bool,
    other: &str,
    required: f64,
) -> String {
    if crossing {
        format!("{what} at x = {x:.2} mm, s = {s:.2} mm touches or crosses {other} (clearance {required:.3} mm required)")
    } else if gap < 0.0 {
        format!(
            "{what} at x = {x:.2} mm, s = {s:.2} mm overlaps {other} by {:.3} mm (clearance {required:.3} mm required)",
            -gap
        )
    } else {
        format!(
            "{what} at x = {x:.2} mm, s = {s:.2} mm is {gap:.3} mm from {other} (clearance {required:.3} mm required)"
        )
    }
}

/// Something a designer should know that does not stop the design being made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Warning {
    /// The sensor saturates before the notches close.
    #[error(
        "sensor strain reaches {strain_pct:.2} % at the notch-closing angle {closing_deg:.1}°, past sensor_saturation_strain = {limit_pct:.2} %: the sensor saturates from {from_deg:.1}° on"
    )]
    SensorSaturates {
        /// Sensor strain at the closing angle (%).
        strain_pct: f64,
        /// Notch-closing angle (°).
        closing_deg: f64,
        /// Saturation strain (%).
        limit_pct: f64,
        /// Bending angle at which saturation starts (°).
        from_deg: f64,
    },
    /// The backbone strains past its limit before the notches close.
    #[error(
        "backbone strain reaches {strain_pct:.2} % ({side}) at the notch-closing angle {closing_deg:.1}°, past backbone_strain_limit = {limit_pct:.2} %: the backbone passes its limit from {from_deg:.1}° on"
    )]
    BackboneStrain {
        /// Peak backbone strain at the closing angle (%).
        strain_pct: f64,
        /// Where the farthest fibre is (`FibreSide::describe`).
        side: &'static str,
        /// Notch-closing angle (°).
        closing_deg: f64,
        /// Backbone strain limit (%).
        limit_pct: f64,
        /// Bending angle at which the limit is reached (°).
        from_deg: f64,
    },
}
