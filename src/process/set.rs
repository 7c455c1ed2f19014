//! One laser parameter set, read from TOML and checked once.

use serde::{Deserialize, Serialize};

use super::ProcessError;

/// One laser parameter set: a column of the paper's Table II.
///
/// Read with [`ProcessSet::from_toml`], which refuses unknown keys and checks every value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ProcessSet {
    /// The set's name (its file stem); not a key of the file.
    #[serde(skip)]
    pub name: String,
    /// One line saying what the set is for.
    #[serde(default)]
    pub description: Option<String>,
    /// Laser wavelength (nm); fixed by the source on most stations, printed for the operator.
    pub wavelength_nm: f64,
    /// Average power at the work (mW).
    pub power_mw: f64,
    /// Speed of the focus over the tube's outer surface (mm/s).
    pub scan_speed_mm_s: f64,
    /// Pulse repetition frequency (kHz).
    pub pulse_frequency_khz: f64,
    /// Pulse width (fs).
    pub pulse_width_fs: f64,
    /// Passes over every path.
    pub repetitions: u32,
    /// Focus lowered by this much after each pass (mm); `None` keeps the focus on the surface.
    #[serde(default)]
    pub z_step_mm: Option<f64>,
    /// Thinnest tube wall `r_o − r_i` (mm) this set cuts cleanly when it cuts through the wall
    /// (notches, parting); a thinner wall is refused by the design rules
    /// ([`crate::rules::check_wall`]). Default [`DEFAULT_MIN_WALL_MM`].
    #[serde(default = "default_min_wall_mm")]
    pub min_wall_mm: f64,
}

/// Default of `min_wall_mm` (mm): about half the thinnest wall the paper cut with its notch
/// set (0.19 mm, Joints B-D). Below it the set's dose (2 W × 32 passes for Table II (b)) is far
/// more than the wall needs, and the edges melt and char and the mandrel is marked. A margin
/// on what was shown to work, not a measured limit: cut test tubes and set it for your process.
pub const DEFAULT_MIN_WALL_MM: f64 = 0.1;

fn default_min_wall_mm() -> f64 {
    DEFAULT_MIN_WALL_MM
}

impl ProcessSet {
    /// Parses and checks a set named `name` from TOML text.
    ///
    /// # Errors
    /// [`ProcessError::Parse`] for malformed TOML, a missing or unknown key;
    /// [`ProcessError::Value`] for a value that is not finite and positive (the Z step may be 0).
    pub fn from_toml(name: &str, text: &str) -> Result<Self, ProcessError> {
        let mut set: Self = toml::from_str(text).map_err(|e| ProcessError::Parse {
            name: name.to_string(),
            message: crate::limits::parser_message(&e),
        })?;
        set.name = name.to_string();
        set.validate()?;
        Ok(set)
    }

    /// The focus lowering per pass (mm), 0 when the set has none.
    pub fn z_step_or_zero_mm(&self) -> f64 {
        self.z_step_mm.unwrap_or(0.0)
    }

    fn validate(&self) -> Result<(), ProcessError> {
        let value = |key, value, limit| ProcessError::Value {
            name: self.name.clone(),
            key,
            value,
            limit,
        };
        for (key, v) in [
            ("wavelength_nm", self.wavelength_nm),
            ("power_mw", self.power_mw),
            ("scan_speed_mm_s", self.scan_speed_mm_s),
            ("pulse_frequency_khz", self.pulse_frequency_khz),
            ("pulse_width_fs", self.pulse_width_fs),
            ("min_wall_mm", self.min_wall_mm),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(value(key, v, "must be finite and > 0"));
            }
        }
        if self.repetitions == 0 {
            return Err(value("repetitions", 0.0, "must be at least 1"));
        }
        if let Some(z) = self.z_step_mm {
            if !(z.is_finite() && z >= 0.0) {
                return Err(value("z_step_mm", z, "must be finite and >= 0"));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SENSOR: &str = include_str!("../../designs/process/sensor.toml");
    const NOTCHES: &str = include_str!("../../designs/process/notches.toml");

    #[test]
    fn shipped_sets_are_table_two() {
        let a = ProcessSet::from_toml("sensor", SENSOR).unwrap();
        let b = ProcessSet::from_toml("notches", NOTCHES).unwrap();
        // (wavelength nm, power mW, speed mm/s, frequency kHz, width fs, repetitions)
        let row = |s: &ProcessSet| {
            (
                s.wavelength_nm,
                s.power_mw,
                s.scan_speed_mm_s,
                s.pulse_frequency_khz,
                s.pulse_width_fs,
                s.repetitions,
            )
        };
        assert_eq!(row(&a), (1030.0, 160.0, 1.0, 200.0, 550.0, 1));
        assert_eq!(row(&b), (1030.0, 2000.0, 25.0, 60.0, 215.0, 32));
        assert_eq!(a.z_step_mm, None);
        assert_eq!(b.min_wall_mm, DEFAULT_MIN_WALL_MM);
        let thin = ProcessSet::from_toml("t", &format!("{NOTCHES}\nmin_wall_mm = 0.02\n")).unwrap();
        assert_eq!(thin.min_wall_mm, 0.02);
        let err = ProcessSet::from_toml("t", &format!("{NOTCHES}\nmin_wall_mm = 0\n")).unwrap_err();
        assert!(
            err.to_string()
                .contains("min_wall_mm = 0 must be finite and > 0"),
            "{err}"
        );
        assert_eq!(b.name, "notches");
    }

    #[test]
    fn refuses_unknown_keys_and_bad_values() {
        let err = ProcessSet::from_toml("x", &format!("{SENSOR}\npower_w = 2\n")).unwrap_err();
        assert!(err.to_string().contains("power_w"), "{err}");
        let err = ProcessSet::from_toml("x", &SENSOR.replace("power_mw = 160", "power_mw = -1"))
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "process set \"x\": power_mw = -1 must be finite and > 0"
        );
        let err = ProcessSet::from_toml("x", &SENSOR.replace("repetitions = 1", "repetitions = 0"))
            .unwrap_err();
        assert!(err.to_string().contains("repetitions = 0"), "{err}");
        let err =
            ProcessSet::from_toml("x", &format!("{SENSOR}\nz_step_mm = -0.01\n")).unwrap_err();
        assert!(err.to_string().contains("z_step_mm = -0.01"), "{err}");
        let missing = SENSOR.replace("pulse_width_fs = 550", "");
        let err = ProcessSet::from_toml("x", &missing).unwrap_err();
        assert!(err.to_string().contains("pulse_width_fs"), "{err}");
    }
}
