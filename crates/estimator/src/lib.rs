//! Runtime estimator: turns a sensing joint's divider voltage into its bending angle.
//!
//! A sensing joint is a notched polyimide tube with a laser-written graphene strain gauge. Its
//! resistance, read through a voltage divider, follows the strain, and the strain follows the
//! bending angle through the joint's geometry. This crate runs that chain backwards, once per
//! sample, with the models of "Shape Sensing of Continuum Robots using Direct Laser Writing"
//! (Rothe, Malhotra, Desai), Sections III-B to III-D:
//!
//! - [`divider_resistance`]: divider voltage to resistance (Eq. 4), flagging the rails;
//! - [`LinearModel`]: the gauge-factor model (Eqs. 5-6), forward and inverse;
//! - [`PlayOperator`], [`PiOperator`], [`InversePiOperator`]: the play operator (Eqs. 8-9),
//!   the weighted sum of plays and its exact inverse (Eqs. 11-13, corrected, see below);
//! - [`TanhInput`], [`GeneralizedPi`], [`PiInverse`]: the paper's generalized PI model with a
//!   direction-switched tanh input (Eqs. 10-14);
//! - [`ContinuousPi`], [`ContinuousPiInverse`]: a continuous variant with loading and unloading
//!   envelopes inside the plays, which does not jump at reversals;
//! - [`MovingAverage`], [`LowPass`], [`Filter`]: streaming filters to trade noise for delay;
//! - [`Pid`]: a discrete PID controller with output limits, anti-windup and the derivative on
//!   the measurement, to close the loop on the estimated angle (Section IV-C);
//! - [`Estimator`]: all of it from an [`EstimatorConfig`], for one sensor (Eq. 3) or both
//!   sensors of a BSN joint (Eq. 7), returning an [`Estimate`] with [`Flags`];
//! - [`RobotEstimator`]: a robot of several joints on one tube, from a
//!   [`RobotEstimatorConfig`]: one [`Estimator`] per sensor gives each sensor's mixed angle,
//!   and the crosstalk of the leads is undone by least squares ([`Unmixing`]); with the
//!   robot's [`Kinematics`] (from `dlw-geometry`), the tip's [`Pose`] and the backbone
//!   (`docs/robot-runtime.md`).
//!
//! Strain ↔ angle is `dlw_geometry::Joint`, the code the planner cuts the joint with.
//!
//! # The inverse weights (a typo in the paper)
//! The paper prints the inverse weights (Eq. 13) as
//! `Qᵢ = −Pᵢ/((P₁ + Σ_{j≤i} Pⱼ)(P₁ + Σ_{j<i} Pⱼ))`, which counts `P₁` twice. The inverse of a
//! PI operator has `Qᵢ = −Pᵢ/(Sᵢ·Sᵢ₋₁)` with the partial sums `Sᵢ = Σ_{j≤i} Pⱼ` (and
//! `Q₁ = 1/P₁`, `ζᵢ = Σ_{j≤i} Pⱼ(ρᵢ − ρⱼ)`); see [`PiOperator::inverse`] for the derivation.
//! This crate uses the corrected form; its tests show that the printed form does not invert
//! the forward model. `docs/estimator.md` writes out every formula.
//!
//! # A robot's PI sensors need no iteration over the joints
//! Sensor `i` of a robot reads the mixed angle `a_i = Σ_j C[i][j]·θ_j` (`C` the crosstalk
//! matrix, `M × N`, `C[i][J(i)] = 1`) through its own joint's model, and its hysteresis acts on
//! that one lumped strain, as for a single joint (the sensing model of `docs/robot-runtime.md`).
//! Each sensor's model is invertible on its own, so its [`Estimator`] recovers `a_i` exactly
//! whatever the other joints do, and `a = C·θ` is linear: `θ = C⁺·a` is then the exact
//! solution (least squares for `M > N`). Issue 34 asked for PI sensors to "iterate from the
//! last sample's angles, with a stated bound on iterations and a flag when it does not
//! converge"; under this model that iteration converges in one step to the same answer, so the
//! bound on joint-level iterations is 0. The one iterative step left is a sensor's continuous
//! PI inverse: at most [`MAX_INVERSE_ITERATIONS`] steps per sample, flagged
//! [`Flags::NOT_CONVERGED`] when it stops short of its tolerance, a flag that reaches every
//! joint whose angle depends on that sensor. (A model whose hysteresis acted on each joint's
//! share of a sensor's strain separately would need the outer iteration; it is not the model
//! `dlw` simulates or fits.)
//!
//! # Examples
//! ```
//! use dlw_estimator::{nominal_divider, EstimatorConfig, Estimator, Flags, JointConfig};
//! use dlw_geometry::NotchStyle;
//!
//! // Joint A of the paper (Table I) with its linear model (Table II).
//! let joint = JointConfig {
//!     style: NotchStyle::Uan,
//!     outer_radius_mm: 1.24,
//!     inner_radius_mm: 0.875,
//!     notch_arc_mm: 5.61,
//!     notch_width_mm: 0.5,
//!     notch_spacing_mm: 0.5,
//!     notch_count: 10,
//!     joint_length_mm: 9.5,
//!     sensor_arc_mm: 0.4,
//! };
//! let config = EstimatorConfig::nominal_linear(joint, 15.3, 215.0e3, nominal_divider())?;
//! let mut estimator = Box::new(Estimator::new(&config)?);
//!
//! // 2.6 V across the sensor: R = 99.6 kΩ/(5/2.6 − 1) ≈ 107.9 kΩ, below R₀: bent backwards.
//! let estimate = estimator.step(2.6);
//! assert!(estimate.flags.is_empty());
//! assert!(estimate.angle_deg < 0.0);
//!
//! // A reading at the rail has no resistance: the last estimate is held and flagged.
//! let held = estimator.step(5.0);
//! assert_eq!(held.flags, Flags::RAIL | Flags::HELD);
//! assert_eq!(held.angle_rad, estimate.angle_rad);
//! # Ok::<(), dlw_estimator::EstimatorError>(())
//! ```
//!
//! # Errors
//! Constructors and `validate` methods return [`EstimatorError`], a `Copy` enum whose messages
//! name the offending value and the limit. Once built, nothing fails: every `step` returns a
//! finite value, and what went wrong with a sample is reported in its [`Flags`].
//!
//! # Features
//! `std` (default) adds `std::error::Error` for the error type. `serde` derives
//! `Serialize`/`Deserialize` for the configuration types (TOML and JSON in the tests). Without
//! features the crate is `no_std`, never allocates and depends on `dlw-geometry` and `libm`.
#![cfg_attr(not(feature = "std"), no_std)]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod coeffs;
mod config;
mod continuous_pi;
mod divider;
mod error;
mod estimator;
mod filter;
mod flags;
mod linear;
mod list;
mod low_pass;
mod moving_average;
mod pi;
mod pi_model;
mod pid;
mod play;
mod robot;
#[cfg(test)]
#[path = "../tests/common/table_one.rs"]
mod table_one;
mod tanh_input;

/// Fixed-capacity coefficient lists (`MAX_PLAYS` = 16 play operators).
pub use coeffs::{Coeffs, MAX_PLAYS};
/// Estimator configuration: joint geometry, sensors, models and filters.
pub use config::{
    nominal_divider, EstimatorConfig, JointConfig, ModelConfig, SensorConfig, SensorPlane,
    DEFAULT_DIVIDER_OHM, DEFAULT_SUPPLY_V,
};
/// The continuous generalized PI model (envelopes inside the plays) and its numerical inverse.
pub use continuous_pi::{
    ContinuousPi, ContinuousPiConfig, ContinuousPiInverse, MAX_INVERSE_ITERATIONS,
};
/// Divider voltage to sensor resistance (Eq. 4), flagging the rails.
pub use divider::divider_resistance;
/// The robot's kinematics (from `dlw-geometry`), re-exported for the robot estimator's users.
pub use dlw_geometry::{BendingSection, Kinematics, KinematicsError, Pose, MAX_JOINTS};
/// Why a configuration was refused.
pub use error::EstimatorError;
/// The runtime estimator and its per-sample output.
pub use estimator::{Estimate, Estimator};
/// A streaming filter chosen by configuration.
pub use filter::{Filter, FilterConfig};
/// What happened to a sample (rail, clamps, reversal, non-finite, held).
pub use flags::Flags;
/// The linear gauge-factor model (Eqs. 5-6).
pub use linear::LinearModel;
/// A fixed-capacity list stored inline (the robot config's joints, sensors, crosstalk rows).
pub use list::List;
/// First-order low-pass filter.
pub use low_pass::LowPass;
/// O(1) moving average with a fixed maximum window (`MAX_MOVING_AVERAGE` = 4096 samples).
pub use moving_average::{MovingAverage, MAX_MOVING_AVERAGE};
/// The PI operator (weighted sum of plays) and its exact inverse (Eqs. 11-13, corrected).
pub use pi::{InversePiOperator, PiOperator};
/// The paper's generalized PI model with tanh input, forward and inverse (Eqs. 10-14).
pub use pi_model::{GeneralizedPi, PiConfig, PiInverse};
/// A discrete PID controller (anti-windup, derivative on the measurement) and its settings.
pub use pid::{AntiWindup, Pid, PidConfig};
/// The play operator (Eqs. 8-9).
pub use play::PlayOperator;
/// The robot estimator: every sensor's voltage to every joint's angle, crosstalk undone.
pub use robot::{
    RobotError, RobotEstimate, RobotEstimator, RobotEstimatorConfig, RobotJointConfig,
    RobotSensorConfig, Unmixing, DEFAULT_MAX_CONDITION_NUMBER, MAX_SENSORS,
};
/// The direction-switched tanh input and its inverse (Eqs. 10 and 14).
pub use tanh_input::{TanhBranch, TanhInput, ATANH_BOUND};
