//! The paper's Table I joints as estimator configs: the one copy of these fixtures, shared by
//! the crate's unit tests (`src/lib.rs`), its integration tests and its benchmarks through
//! `#[path]` module declarations at each target's root (which provides `JointConfig`).
#![allow(dead_code)]

use super::JointConfig;
use dlw_geometry::NotchStyle;

/// Joint A: UAN, r_o 1.24 mm.
pub fn joint_a() -> JointConfig {
    JointConfig {
        style: NotchStyle::Uan,
        outer_radius_mm: 1.24,
        inner_radius_mm: 0.875,
        notch_arc_mm: 5.61,
        notch_width_mm: 0.5,
        notch_spacing_mm: 0.5,
        notch_count: 10,
        joint_length_mm: 9.5,
        sensor_arc_mm: 0.4,
    }
}

/// Joint C: BSN, r_o 0.8 mm.
pub fn joint_c() -> JointConfig {
    JointConfig {
        style: NotchStyle::Bsn,
        outer_radius_mm: 0.8,
        inner_radius_mm: 0.61,
        notch_arc_mm: 1.65,
        sensor_arc_mm: 2.13,
        ..joint_a()
    }
}

/// Joint A for UAN, Joint C for BSN.
pub fn joint(style: NotchStyle) -> JointConfig {
    match style {
        NotchStyle::Uan => joint_a(),
        NotchStyle::Bsn => joint_c(),
    }
}
