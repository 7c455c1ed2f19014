use dlw_geometry::{Kinematics, Pose, MAX_JOINTS};

use super::config::RobotEstimatorConfig;
use super::error::RobotError;
use super::unmix::{Unmixing, MAX_SENSORS};
use crate::estimator::Estimator;
use crate::flags::Flags;

/// A sensor's one-joint estimator. With `std` each lives on the heap (an [`Estimator`] holds
/// its moving-average buffers inline, about 100 KiB), so a robot estimator is a few KiB;
/// without `std` they are inline and the robot estimator belongs in a `static`.
#[cfg(feature = "std")]
type Chain = std::boxed::Box<Estimator>;
#[cfg(not(feature = "std"))]
type Chain = Estimator;

/// One sample's estimate of every joint. Always finite: a joint whose angle cannot be computed
/// keeps its last good angle, flagged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotEstimate {
    joints: usize,
    sensors: usize,
    angles_rad: [f64; MAX_JOINTS],
    flags: [Flags; MAX_JOINTS],
    mixed_rad: [f64; MAX_SENSORS],
    sensor_flags: [Flags; MAX_SENSORS],
    residual_rad: f64,
}

impl RobotEstimate {
    fn straight(joints: usize, sensors: usize) -> Self {
        Self {
            joints,
            sensors,
            angles_rad: [0.0; MAX_JOINTS],
            flags: [Flags::empty(); MAX_JOINTS],
            mixed_rad: [0.0; MAX_SENSORS],
            sensor_flags: [Flags::empty(); MAX_SENSORS],
            residual_rad: 0.0,
        }
    }

    /// The joint angles `θ` (rad), joint 1 first.
    pub fn angles_rad(&self) -> &[f64] {
        &self.angles_rad[..self.joints]
    }

    /// Joint `joint`'s angle (0-based) in degrees.
    pub fn angle_deg(&self, joint: usize) -> f64 {
        self.angles_rad[joint].to_degrees()
    }

    /// Each joint's flags: the union of the flags of every sensor its angle depends on (the
    /// nonzero entries of its row of `C⁺`), plus [`Flags::NON_FINITE`] and [`Flags::HELD`] if
    /// its angle overflowed and the last one was kept. [`Flags::HELD`] from a sensor means that
    /// sensor's last good mixed angle was used.
    pub fn flags(&self) -> &[Flags] {
        &self.flags[..self.joints]
    }

    /// Each sensor's mixed angle `a_i = Σ_j C[i][j]·θ_j` (rad), from its own model's inverse.
    pub fn mixed_rad(&self) -> &[f64] {
        &self.mixed_rad[..self.sensors]
    }

    /// Each sensor's flags from its one-joint estimator.
    pub fn sensor_flags(&self) -> &[Flags] {
        &self.sensor_flags[..self.sensors]
    }

    /// Root mean square of the least-squares residual `a − C·θ` (rad): 0 with as many sensors
    /// as joints (the solution is exact); with more sensors than joints, how far they disagree.
    pub fn residual_rad(&self) -> f64 {
        self.residual_rad
    }

    /// The union of every joint's flags.
    pub fn any_flags(&self) -> Flags {
        self.flags()
            .iter()
            .fold(Flags::empty(), |all, flags| all | *flags)
    }
}

/// Divider voltages of every sensor in, every joint's angle out: the robot's runtime estimator.
///
/// Per sample, each sensor's one-joint [`Estimator`] (divider, input filter, its linear or PI
/// model, its joint's geometry, output filter) turns its voltage into its mixed angle
/// `a_i = Σ_j C[i][j]·θ_j`; then `θ = C⁺·a`, with the pseudo-inverse `C⁺` precomputed
/// ([`Unmixing`]). That is exact under the sensing model of `docs/robot-runtime.md` (each
/// sensor's hysteresis acts on its own mixed strain), so no iteration over the joints is
/// needed; the only iterative step is the continuous PI model's per-sensor root search,
/// bounded and flagged ([`Flags::NOT_CONVERGED`]).
///
/// It never allocates per sample and never returns NaN or ∞.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotEstimator {
    chains: [Option<Chain>; MAX_SENSORS],
    unmixing: Unmixing,
    kinematics: Kinematics,
    joints: usize,
    sensors: usize,
    last: RobotEstimate,
}

impl RobotEstimator {
    /// A robot estimator for `config`.
    ///
    /// # Errors
    /// Whatever [`RobotEstimatorConfig::validate`] refuses.
    pub fn new(config: &RobotEstimatorConfig) -> Result<Self, RobotError> {
        let resolved = config.resolve()?;
        let mut chains: [Option<Chain>; MAX_SENSORS] = core::array::from_fn(|_| None);
        for (i, (slot, c)) in chains.iter_mut().zip(resolved.chains.iter()).enumerate() {
            let estimator = Estimator::new(c).map_err(|error| RobotError::Sensor {
                sensor: i + 1,
                error,
            })?;
            *slot = Some(Chain::from(estimator));
        }
        let (joints, sensors) = (config.joint_count(), config.sensor_count());
        Ok(Self {
            chains,
            unmixing: resolved.unmixing,
            kinematics: resolved.kinematics,
            joints,
            sensors,
            last: RobotEstimate::straight(joints, sensors),
        })
    }

    /// Joints `N`.
    pub fn joint_count(&self) -> usize {
        self.joints
    }

    /// Sensors `M`: the voltages each sample.
    pub fn sensor_count(&self) -> usize {
        self.sensors
    }

    /// The crosstalk matrix, its pseudo-inverse and condition number.
    pub fn unmixing(&self) -> &Unmixing {
        &self.unmixing
    }

    /// The robot's kinematics.
    pub fn kinematics(&self) -> &Kinematics {
        &self.kinematics
    }

    /// Sensor `sensor`'s (0-based) one-joint estimator.
    pub fn sensor_estimator(&self, sensor: usize) -> Option<&Estimator> {
        let chain = self.chains.get(sensor)?.as_ref()?;
        Some(core::borrow::Borrow::<Estimator>::borrow(chain))
    }

    /// The last estimate returned (or the initial one: straight robot).
    pub fn last(&self) -> &RobotEstimate {
        &self.last
    }

    /// Estimates every joint's angle from the sensors' divider voltages `volts` (V), in the
    /// order of the config's sensors. A missing voltage (`volts` shorter than
    /// [`RobotEstimator::sensor_count`]) counts as NaN, so that sensor is held and flagged;
    /// extra voltages are ignored.
    #[inline]
    pub fn step(&mut self, volts: &[f64]) -> RobotEstimate {
        // Built in place over the last estimate: a joint that cannot be computed keeps it.
        let estimate = &mut self.last;
        for (i, chain) in self.chains[..self.sensors].iter_mut().enumerate() {
            if let Some(chain) = chain {
                let e = chain.step(volts.get(i).copied().unwrap_or(f64::NAN));
                estimate.mixed_rad[i] = e.angle_rad;
                estimate.sensor_flags[i] = e.flags;
            }
        }
        let mut angles = [0.0; MAX_JOINTS];
        self.unmixing.solve(&estimate.mixed_rad, &mut angles);
        for (j, angle) in angles[..self.joints].iter().enumerate() {
            let mut flags = Flags::empty();
            let mut uses = self.unmixing.uses(j);
            while uses != 0 {
                flags |= estimate.sensor_flags[uses.trailing_zeros() as usize];
                uses &= uses - 1;
            }
            if angle.is_finite() {
                estimate.angles_rad[j] = *angle;
            } else {
                flags |= Flags::NON_FINITE | Flags::HELD;
            }
            estimate.flags[j] = flags;
        }
        // With as many sensors as joints the least squares is exact: its residual is 0.
        if self.sensors > self.joints {
            let residual = self
                .unmixing
                .residual_rms(&estimate.mixed_rad, &estimate.angles_rad);
            if residual.is_finite() {
                estimate.residual_rad = residual;
            }
        }
        *estimate
    }

    /// The tip's pose at an estimate's angles.
    ///
    /// # Errors
    /// None for an estimate of this estimator (one finite angle per joint); as
    /// [`Kinematics::tip`] otherwise.
    pub fn tip(&self, estimate: &RobotEstimate) -> Result<Pose, RobotError> {
        Ok(self.kinematics.tip(estimate.angles_rad())?)
    }

    /// Returns every sensor's filters and model to their initial state and forgets past
    /// estimates.
    pub fn reset(&mut self) {
        for chain in self.chains.iter_mut().flatten() {
            chain.reset();
        }
        self.last = RobotEstimate::straight(self.joints, self.sensors);
    }
}
