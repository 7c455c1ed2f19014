//! Cross-section and strain math of a notched-tube sensing joint.
//!
//! A sensing joint is a polyimide tube with notches cut by a femtosecond laser and a graphene
//! strain gauge written on its outer surface by direct laser writing (DLW). This crate holds the
//! math that ties the joint's design to the sensor's signal, from the paper
//! "Shape Sensing of Continuum Robots using Direct Laser Writing" (Rothe, Malhotra, Desai):
//!
//! - [`CrossSection`]: the sensor plane `y_s` (Eq. 1), the neutral plane `ȳ` (Eq. 2) and their
//!   offset `Δy`;
//! - [`Joint`]: strain `ε = Δy·θ/L` (Eq. 3) and its inverse, the two-sensor angle (Eq. 7), the
//!   angle at which the notches close;
//! - [`Mechanics`]: tendon stroke per degree, the notch-closing limit, the farthest fibre's
//!   strain, the second moment of area and the tendon force (`docs/mechanics.md`);
//! - [`Divider`]: the voltage divider that reads the sensor (Eq. 4);
//! - [`Kinematics`]: a robot of several joints on one tube, from its joint angles to the tip's
//!   [`Pose`] and points along the backbone (constant-curvature arcs, `docs/robot-runtime.md`).
//!
//! The planner (`dlw`) and the runtime estimator (`dlw-estimator`) both use it, so a joint is
//! read with exactly the geometry it was cut with.
//!
//! The crate is `no_std`, never allocates and depends only on `libm` and `nalgebra` (without
//! its `std`, for rotations; and `serde` behind the `serde` feature). Lengths are in millimetres and angles in radians; degrees only appear in
//! names that say so (`..._per_deg`).
//!
//! # Frames
//! The cross-section frame has its origin on the tube axis. `y` lies in the bending plane and
//! points at the uncut backbone of a UAN joint (the side that carries the sensor). The angle `φ`
//! around the tube is measured from `+y`, and `s = r_o·φ` is arc length on the outer surface.
//! Notches of a UAN joint are centred at `φ = π`; a BSN joint has notches centred at `φ = 0`
//! and `φ = π`. A positive bending angle `θ` closes the notches at `φ = π`, so the material at
//! `y > ȳ` is stretched: a sensor at `+y_s` reads positive strain.
//!
//! # Examples
//! ```
//! use dlw_geometry::{CrossSection, Joint, NotchStyle};
//!
//! // Joint A of the paper's Table I.
//! let section = CrossSection::new(NotchStyle::Uan, 1.24, 0.875, 5.61, 0.4)?;
//! let joint = Joint::new(section, 0.5, 0.5, 10, 9.5)?;
//! let strain = joint.strain(26f64.to_radians());
//! assert!((strain - 0.0138).abs() < 5e-5);
//! assert!((joint.angle_from_strain(strain) - 26f64.to_radians()).abs() < 1e-12);
//! # Ok::<(), dlw_geometry::GeometryError>(())
//! ```
//!
//! # Errors
//! Constructors validate their inputs and return [`GeometryError`], which names the value and
//! the limit it broke. Once built, every method is total: it returns a finite number for finite
//! input.
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod divider;
mod error;
mod joint;
mod kinematics;
mod mechanics;
mod section;

/// The voltage divider that reads a sensor (Eq. 4).
pub use divider::Divider;
/// Why a geometry value was refused.
pub use error::GeometryError;
/// Strain and angle along a whole joint (Eqs. 3 and 7, notch closing).
pub use joint::Joint;
/// A robot's joint angles to its tip's pose and backbone points.
pub use kinematics::{BendingSection, Kinematics, KinematicsError, Pose, MAX_JOINTS};
/// Tendon stroke, material strain, bending stiffness and tendon force (York, Swaney et al.).
pub use mechanics::{FibreSide, Mechanics, RangeLimit, DEFAULT_TENDON_HALF_DIAMETER_MM};
/// The notched cross-section (Eqs. 1 and 2).
pub use section::{CrossSection, NotchStyle};
