use crate::error::{finite, positive, range, EstimatorError};

/// Largest magnitude any term of the controller may take, so that the sum of the three terms
/// stays finite whatever finite numbers come in.
const TERM_BOUND: f64 = f64::MAX / 4.0;

/// How the integral is kept from winding up while the output is saturated.
///
/// In TOML: `anti_windup = "clamping"` or `"none"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum AntiWindup {
    /// Conditional integration ("clamping", as Simulink's PID block calls it): a sample's
    /// error is not integrated when the output would be beyond a limit and the error pushes it
    /// further out; the integral term itself is also held within the output limits.
    #[default]
    Clamping,
    /// Always integrate (for comparison; the integral winds up while the output is saturated).
    None,
}

/// A [`Pid`]'s gains, sample time and limits.
///
/// Units follow the loop: with the error in units `E` and the output in units `U`, `kp` is in
/// `U/E`, `ki` in `U/(E·s)` and `kd` in `U·s/E`. The paper's joint controller (Section IV-C)
/// acts on the angle error in degrees and outputs tendon stroke in millimetres:
/// `kp = 0.1 mm/°`, `ki = 0.1 mm/(°·s)`, `kd = 0 mm·s/°`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct PidConfig {
    /// Proportional gain `K_p` (output per unit error), ≥ 0.
    pub kp: f64,
    /// Integral gain `K_i` (output per unit error and second), ≥ 0.
    pub ki: f64,
    /// Derivative gain `K_d` (output·s per unit error), ≥ 0; acts on the measurement only.
    pub kd: f64,
    /// Sample time `Δt` (s), > 0: the controller is stepped once per `dt_s`.
    pub dt_s: f64,
    /// Lowest output.
    pub output_min: f64,
    /// Highest output (greater than `output_min`).
    pub output_max: f64,
    /// Time constant `T_f` (s) of the first-order low-pass on the derivative, ≥ 0 (0: none).
    #[cfg_attr(feature = "serde", serde(default))]
    pub derivative_filter_s: f64,
    /// Anti-windup scheme (default clamping).
    #[cfg_attr(feature = "serde", serde(default))]
    pub anti_windup: AntiWindup,
}

impl PidConfig {
    /// The paper's joint controller (Section IV-C) at sample time `dt_s`, limited to
    /// `±limit`: `kp = 0.1`, `ki = 0.1`, `kd = 0`, clamping anti-windup, no derivative filter.
    pub fn paper(dt_s: f64, limit: f64) -> Self {
        Self {
            kp: 0.1,
            ki: 0.1,
            kd: 0.0,
            dt_s,
            output_min: -limit,
            output_max: limit,
            derivative_filter_s: 0.0,
            anti_windup: AntiWindup::Clamping,
        }
    }

    /// Checks every value.
    ///
    /// # Errors
    /// A gain or the derivative filter not finite or negative, `dt_s` not finite or not
    /// positive, or output limits not finite or not increasing.
    pub fn validate(&self) -> Result<(), EstimatorError> {
        non_negative("kp", self.kp)?;
        non_negative("ki", self.ki)?;
        non_negative("kd", self.kd)?;
        positive("dt_s", self.dt_s)?;
        non_negative("derivative_filter_s", self.derivative_filter_s)?;
        range("output_min", self.output_min, "output_max", self.output_max)
    }
}

fn non_negative(name: &'static str, value: f64) -> Result<f64, EstimatorError> {
    if finite(name, value)? < 0.0 {
        return Err(EstimatorError::Negative { name, value });
    }
    Ok(value)
}

/// Bounds a term: NaN (only from `0·∞`) becomes 0, anything else stays within ±`TERM_BOUND`.
#[inline]
fn bounded(x: f64) -> f64 {
    if x.is_nan() {
        0.0
    } else {
        x.clamp(-TERM_BOUND, TERM_BOUND)
    }
}

/// A discrete PID controller for a fixed sample time, with output limits, anti-windup and the
/// derivative on the measurement.
///
/// Per sample `k`, with error `e_k = r_k − y_k` (setpoint `r`, measurement `y`):
///
/// ```text
/// P_k = K_p·e_k
/// I_k = I_{k−1} + K_i·e_k·Δt            (skipped under clamping anti-windup, see below)
/// D_k = D_{k−1} + α·(−K_d·(y_k − y_{k−1})/Δt − D_{k−1}),   α = 1 − e^(−Δt/T_f)  (α = 1 if T_f = 0)
/// u_k = clamp(P_k + I_k + D_k, u_min, u_max)
/// ```
///
/// - **Derivative on the measurement**: a setpoint step does not kick the output; `D` is 0 on
///   the first sample after construction or [`Pid::reset`].
/// - **Anti-windup** ([`AntiWindup::Clamping`], conditional integration): the error of a sample
///   is not integrated when `P + I_{k−1} + K_i·e_k·Δt + D` lies beyond a limit and `e_k` has the
///   sign that pushes it further out, and `I` is held within `[u_min, u_max]` (widened to
///   include 0). When the
///   saturation ends, the integral has not stored the error accumulated meanwhile, so the
///   output leaves the limit at once instead of overshooting while the integral unwinds.
///
/// `step` never allocates and never returns NaN or ∞: for finite inputs every term is bounded
/// and the output is within the limits; a non-finite setpoint or measurement leaves the state
/// unchanged and returns the previous output.
///
/// # Examples
/// ```
/// use dlw_estimator::{Pid, PidConfig};
///
/// // The paper's gains on the angle error (°), stroke out (mm), at 500 Hz, ±1 mm.
/// let mut pid = Pid::new(&PidConfig::paper(0.002, 1.0))?;
/// let u = pid.step(10.0, 8.0); // 2° short: 0.1 mm/° · 2° + 0.1 mm/(°·s) · 2° · 0.002 s
/// assert!((u - 0.2004).abs() < 1e-12);
/// assert_eq!(pid.step(1000.0, 0.0), 1.0); // saturated at the limit
/// # Ok::<(), dlw_estimator::EstimatorError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pid {
    config: PidConfig,
    /// `K_i·Δt`, precomputed.
    ki_dt: f64,
    /// `K_d/Δt`, precomputed.
    kd_per_dt: f64,
    /// Smoothing factor of the derivative filter.
    alpha: f64,
    integral: f64,
    derivative: f64,
    previous_measurement: Option<f64>,
    output: f64,
}

impl Pid {
    /// A controller for `config`, at rest (zero integral, no previous measurement).
    ///
    /// # Errors
    /// Whatever [`PidConfig::validate`] refuses.
    pub fn new(config: &PidConfig) -> Result<Self, EstimatorError> {
        config.validate()?;
        let alpha = if config.derivative_filter_s > 0.0 {
            1.0 - libm::exp(-config.dt_s / config.derivative_filter_s)
        } else {
            1.0
        };
        let mut pid = Self {
            config: *config,
            ki_dt: bounded(config.ki * config.dt_s),
            kd_per_dt: bounded(config.kd / config.dt_s),
            alpha,
            integral: 0.0,
            derivative: 0.0,
            previous_measurement: None,
            output: 0.0,
        };
        pid.reset();
        Ok(pid)
    }

    /// The configuration it was built from.
    pub fn config(&self) -> &PidConfig {
        &self.config
    }

    /// The integral term `I` (output units).
    pub fn integral(&self) -> f64 {
        self.integral
    }

    /// The last output (initially the value nearest 0 within the limits).
    pub fn output(&self) -> f64 {
        self.output
    }

    /// Forgets the integral, the derivative and the previous measurement.
    pub fn reset(&mut self) {
        self.integral = 0.0;
        self.derivative = 0.0;
        self.previous_measurement = None;
        self.output = 0.0f64.clamp(self.config.output_min, self.config.output_max);
    }

    /// One sample: the output for `setpoint` and `measurement`.
    #[inline]
    pub fn step(&mut self, setpoint: f64, measurement: f64) -> f64 {
        self.step_with(setpoint, measurement, true)
    }

    /// One sample whose measurement sits at the end of the sensor's range (the estimator
    /// flagged [`crate::Flags::RESISTANCE_CLAMPED`]): the proportional and derivative terms act
    /// on it as on any measurement, but the integral is held. Beyond its range the sensor reads
    /// its end whatever the joint does, so the error it gives is not the joint's: integrating it
    /// winds the output up until the joint runs to its limit (Joint D's closed loop ran from a
    /// 45° setpoint to 91° with the estimate stuck at the characterized range's 43.5°).
    #[inline]
    pub fn step_out_of_range(&mut self, setpoint: f64, measurement: f64) -> f64 {
        self.step_with(setpoint, measurement, false)
    }

    #[inline]
    fn step_with(&mut self, setpoint: f64, measurement: f64, integrate: bool) -> f64 {
        if !(setpoint.is_finite() && measurement.is_finite()) {
            return self.output;
        }
        let c = &self.config;
        let error = bounded(setpoint - measurement);
        let p = bounded(c.kp * error);
        let raw_derivative = match self.previous_measurement {
            Some(prev) => bounded(-self.kd_per_dt * bounded(measurement - prev)),
            None => 0.0,
        };
        self.previous_measurement = Some(measurement);
        self.derivative =
            bounded(self.derivative + self.alpha * (raw_derivative - self.derivative));
        let increment = if integrate {
            bounded(self.ki_dt * error)
        } else {
            0.0
        };
        let candidate = bounded(self.integral + increment);
        self.integral = match c.anti_windup {
            AntiWindup::None => candidate,
            AntiWindup::Clamping => {
                let unlimited = p + candidate + self.derivative;
                let winding_up = (unlimited > c.output_max && increment > 0.0)
                    || (unlimited < c.output_min && increment < 0.0);
                if winding_up {
                    self.integral
                } else {
                    candidate.clamp(c.output_min.min(0.0), c.output_max.max(0.0))
                }
            }
        };
        self.output = (p + self.integral + self.derivative).clamp(c.output_min, c.output_max);
        self.output
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn config(kp: f64, ki: f64, kd: f64, limit: f64) -> PidConfig {
        PidConfig {
            kp,
            ki,
            kd,
            dt_s: 0.01,
            output_min: -limit,
            output_max: limit,
            derivative_filter_s: 0.0,
            anti_windup: AntiWindup::Clamping,
        }
    }

    /// A first-order plant `τ·ẏ = K·u − y`, exact discretization.
    struct Plant {
        y: f64,
        gain: f64,
        a: f64,
    }

    impl Plant {
        fn new(gain: f64, tau_s: f64, dt_s: f64) -> Self {
            Self {
                y: 0.0,
                gain,
                a: (-dt_s / tau_s).exp(),
            }
        }
        fn step(&mut self, u: f64) -> f64 {
            self.y = self.a * self.y + (1.0 - self.a) * self.gain * u;
            self.y
        }
    }

    #[test]
    fn terms_by_hand() {
        let mut pid = Pid::new(&config(2.0, 3.0, 0.5, 100.0)).unwrap();
        // First sample: P = 2·1, I = 3·1·0.01, D = 0 (no previous measurement).
        assert_relative_eq!(pid.step(1.0, 0.0), 2.03, epsilon = 1e-12);
        // Measurement rises by 0.5: D = −0.5·0.5/0.01 = −25; I = 0.03 + 3·0.5·0.01.
        assert_relative_eq!(pid.step(1.0, 0.5), 1.0 + 0.045 - 25.0, epsilon = 1e-12);
        assert_relative_eq!(pid.integral(), 0.045, epsilon = 1e-15);
        // A setpoint step does not kick the derivative.
        assert_relative_eq!(pid.step(11.0, 0.5), 21.0 + 0.045 + 0.315, epsilon = 1e-12);
        pid.reset();
        assert_eq!(pid.integral(), 0.0);
        assert_relative_eq!(pid.step(1.0, 0.0), 2.03, epsilon = 1e-12);
    }

    #[test]
    fn derivative_filter_is_a_first_order_lag() {
        let mut c = config(0.0, 0.0, 1.0, 1e9);
        c.derivative_filter_s = 0.1;
        let mut pid = Pid::new(&c).unwrap();
        pid.step(0.0, 0.0);
        // A ramp of −1 per second: raw D = +1; filtered, 1 − e^(−t/T_f) of it.
        let alpha = 1.0 - (-0.1f64).exp();
        let mut u = 0.0;
        for k in 1..=10 {
            u = pid.step(0.0, -0.01 * f64::from(k));
        }
        assert_relative_eq!(u, 1.0 - (1.0 - alpha).powi(10), epsilon = 1e-9);
    }

    #[test]
    fn first_order_plant_settles_without_steady_state_error() {
        let dt = 0.01;
        let mut pid = Pid::new(&config(0.5, 2.0, 0.0, 100.0)).unwrap();
        let mut plant = Plant::new(3.0, 0.5, dt);
        let (mut y, setpoint) = (0.0, 2.0);
        for _ in 0..3000 {
            let u = pid.step(setpoint, y);
            y = plant.step(u);
        }
        assert_relative_eq!(y, setpoint, epsilon = 1e-6);
        // The integral holds the output the plant needs: u = r/K.
        assert_relative_eq!(pid.integral(), setpoint / 3.0, epsilon = 1e-5);
        // P alone leaves the classic error r/(1 + K·K_p).
        let mut p_only = Pid::new(&config(0.5, 0.0, 0.0, 100.0)).unwrap();
        let mut plant = Plant::new(3.0, 0.5, dt);
        let mut y = 0.0;
        for _ in 0..3000 {
            y = plant.step(p_only.step(setpoint, y));
        }
        assert_relative_eq!(setpoint - y, setpoint / 2.5, epsilon = 1e-6);
    }

    /// A long saturation followed by a setpoint drop: without anti-windup the integral has
    /// stored the error and the plant overshoots the new setpoint for a long time.
    #[test]
    fn anti_windup_recovers_faster() {
        let run = |anti_windup| {
            let dt = 0.01;
            let mut c = config(0.5, 2.0, 0.0, 1.0);
            c.anti_windup = anti_windup;
            let mut pid = Pid::new(&c).unwrap();
            let mut plant = Plant::new(1.0, 0.5, dt);
            let mut y = 0.0;
            // 20 s at a setpoint the limited output cannot reach (needs u = 3).
            for _ in 0..2000 {
                y = plant.step(pid.step(3.0, y));
            }
            let wound = pid.integral();
            // Then a reachable setpoint: time until y stays within 0.05 of it.
            let mut last_out = 0;
            for k in 0..5000 {
                y = plant.step(pid.step(0.5, y));
                if (y - 0.5).abs() > 0.05 {
                    last_out = k;
                }
            }
            (f64::from(last_out) * dt, wound)
        };
        let (with, wound_with) = run(AntiWindup::Clamping);
        let (without, wound_without) = run(AntiWindup::None);
        assert!(wound_with <= 1.0, "{wound_with}");
        assert!(wound_without > 30.0, "{wound_without}");
        assert!(with < 4.0, "settles in {with} s with anti-windup");
        eprintln!("settling: {with} s with, {without} s without anti-windup");
        assert!(without > 5.0 * with, "{without} s without vs {with} s with");
    }

    #[test]
    fn refuses_bad_config_naming_the_value() {
        let table: [(PidConfig, EstimatorError); 5] = [
            (
                config(-0.1, 0.0, 0.0, 1.0),
                EstimatorError::Negative {
                    name: "kp",
                    value: -0.1,
                },
            ),
            (
                PidConfig {
                    dt_s: 0.0,
                    ..config(0.1, 0.1, 0.0, 1.0)
                },
                EstimatorError::NotPositive {
                    name: "dt_s",
                    value: 0.0,
                },
            ),
            (
                config(0.1, 0.1, 0.0, -1.0),
                EstimatorError::EmptyRange {
                    min_name: "output_min",
                    min: 1.0,
                    max_name: "output_max",
                    max: -1.0,
                },
            ),
            (
                PidConfig {
                    derivative_filter_s: -1.0,
                    ..config(0.1, 0.1, 0.0, 1.0)
                },
                EstimatorError::Negative {
                    name: "derivative_filter_s",
                    value: -1.0,
                },
            ),
            (
                PidConfig {
                    output_max: f64::INFINITY,
                    ..config(0.1, 0.1, 0.0, 1.0)
                },
                EstimatorError::NotFinite {
                    name: "output_max",
                    value: f64::INFINITY,
                },
            ),
        ];
        for (c, want) in table {
            assert_eq!(Pid::new(&c).unwrap_err(), want);
        }
        let ki_nan = config(0.1, f64::NAN, 0.0, 1.0);
        assert!(matches!(
            Pid::new(&ki_nan),
            Err(EstimatorError::NotFinite { name: "ki", .. })
        ));
    }

    #[test]
    fn non_finite_input_holds_the_output() {
        let mut pid = Pid::new(&config(1.0, 1.0, 1.0, 10.0)).unwrap();
        let u = pid.step(1.0, 0.0);
        let state = pid;
        assert_eq!(pid.step(f64::NAN, 0.0), u);
        assert_eq!(pid.step(1.0, f64::INFINITY), u);
        assert_eq!(pid, state);
    }

    /// TOML with the optional keys left out gets the documented defaults; unknown keys are
    /// refused.
    #[cfg(feature = "serde")]
    #[test]
    fn config_reads_from_toml() {
        let text =
            "kp = 0.1\nki = 0.1\nkd = 0.0\ndt_s = 0.002\noutput_min = -1.0\noutput_max = 1.0\n";
        let c: PidConfig = toml::from_str(text).unwrap();
        assert_eq!(c, PidConfig::paper(0.002, 1.0));
        let back: PidConfig = toml::from_str(&toml::to_string(&c).unwrap()).unwrap();
        assert_eq!(back, c);
        let none: PidConfig = toml::from_str(&format!("{text}anti_windup = \"none\"\n")).unwrap();
        assert_eq!(none.anti_windup, AntiWindup::None);
        assert!(toml::from_str::<PidConfig>(&format!("{text}k = 1.0\n")).is_err());
    }

    fn any_finite() -> impl Strategy<Value = f64> {
        prop_oneof![
            -1e3..1e3f64,
            any::<f64>().prop_filter("finite", |x| x.is_finite()),
        ]
    }

    fn any_config() -> impl Strategy<Value = PidConfig> {
        (
            (any_finite(), any_finite(), any_finite()),
            prop_oneof![1e-6..1.0f64, Just(f64::MIN_POSITIVE), Just(1e300)],
            (any_finite(), 0.0..1e6f64),
            (0.0..10.0f64, any::<bool>()),
        )
            .prop_map(|((kp, ki, kd), dt_s, (lo, span), (tf, clamp))| PidConfig {
                kp: kp.abs(),
                ki: ki.abs(),
                kd: kd.abs(),
                dt_s,
                output_min: lo,
                output_max: lo + span.max(lo.abs() * 1e-6 + 1e-3),
                derivative_filter_s: tf,
                anti_windup: if clamp {
                    AntiWindup::Clamping
                } else {
                    AntiWindup::None
                },
            })
            .prop_filter("valid", |c| c.validate().is_ok())
    }

    proptest! {
        /// Whatever the (valid) gains and finite inputs, the output is a number within the
        /// limits.
        #[test]
        fn output_is_finite_and_within_limits(
            c in any_config(),
            inputs in proptest::collection::vec((any_finite(), any_finite()), 1..60),
        ) {
            let mut pid = Pid::new(&c).unwrap();
            for (r, y) in inputs {
                let u = pid.step(r, y);
                prop_assert!(!u.is_nan());
                prop_assert!(u >= c.output_min && u <= c.output_max, "{} not in [{}, {}]", u, c.output_min, c.output_max);
                prop_assert!(pid.integral().is_finite());
            }
        }
    }

    /// A measurement at the end of the sensor's range moves the output through P but never
    /// the integral, whatever the error; back in range, integration resumes.
    #[test]
    fn out_of_range_measurements_hold_the_integral() {
        let mut pid = Pid::new(&PidConfig::paper(0.002, 10.0)).unwrap();
        pid.step(1.0, 0.0);
        let before = pid.integral();
        for _ in 0..10_000 {
            let u = pid.step_out_of_range(45.0, 43.5);
            assert_relative_eq!(u, 0.1 * 1.5 + before, epsilon = 1e-12);
        }
        assert_eq!(pid.integral(), before);
        pid.step(45.0, 43.5);
        assert!(pid.integral() > before);
    }
}
