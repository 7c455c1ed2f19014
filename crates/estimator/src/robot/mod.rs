//! The robot estimator: several sensing joints on one tube, every sensor's voltage in, every
//! joint's angle out, with the crosstalk of the leads undone (`docs/robot-runtime.md`).
//!
//! # The sensing model and why there is no iteration over the joints
//! Sensor `i` belongs to joint `J(i)`. Its leads cross other joints' notched sections, so it
//! reads the mixed angle `a_i = Σ_j C[i][j]·θ_j` (`C` the crosstalk matrix, `M` sensors × `N`
//! joints, `C[i][J(i)] = 1`) through its own joint's model: its strain is that joint's
//! `Δy·a_i/L` (Eq. 3), and its effects, the PI model's hysteresis among them, act on that one
//! lumped strain as they do for a single joint. Each sensor's model is invertible on its own
//! (Eq. 6 for the linear model; Eqs. 12-14, or the continuous model's root search, for PI),
//! so each sensor's one-joint [`crate::Estimator`] recovers `a_i` exactly, whatever the other
//! joints do; and `a = C·θ` is linear, so `θ = C⁺·a` solves it exactly for `M = N` and in the
//! least-squares sense for `M > N`.
//!
//! The issue asked, for PI sensors, to "iterate from the last sample's angles, with a stated
//! bound on iterations and a flag when it does not converge". Under this model that outer
//! iteration would converge in one step to the same answer, so it is not run: the bound on
//! joint-level iterations is 0. The only iterative step left is inside a sensor, the
//! continuous PI model's root search: at most [`crate::MAX_INVERSE_ITERATIONS`] steps, flagged
//! [`crate::Flags::NOT_CONVERGED`] when it stops short of its tolerance. (An outer iteration
//! would be needed if a sensor's hysteresis acted on each joint's share of its strain
//! separately, `Σ_j C[i][j]·H_i(θ_j)`; that is not the model dlw simulates or fits.)
//!
//! # Flags
//! Each joint's flags are the union of the flags of the sensors its angle depends on (the
//! nonzero entries of its row of `C⁺`): a rail, a hold, a clamp, a reversal or a
//! non-convergence of any of them.

mod config;
mod error;
mod estimator;
mod unmix;

pub use config::{RobotEstimatorConfig, RobotJointConfig, RobotSensorConfig};
pub use error::RobotError;
pub use estimator::{RobotEstimate, RobotEstimator};
pub use unmix::{Unmixing, DEFAULT_MAX_CONDITION_NUMBER, MAX_SENSORS};
