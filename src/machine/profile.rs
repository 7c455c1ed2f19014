//! A machine profile, read from TOML and checked once.

use serde::{Deserialize, Serialize};

use super::{MachineError, Settle, Template};

/// The largest magnitude of a machine coordinate in a profile (mm): travel limits, the focus
/// height and the collet's grip. A laser station's stages travel hundreds of millimetres; a
/// value past this is a typo, and would be written into every move (`z_axis_mm = 1e308` wrote a
/// 309-digit Z).
pub const MAX_ABS_COORDINATE_MM: f64 = 10_000.0;

/// Which post-processor writes the program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Dialect {
    /// LinuxCNC RS-274/NGC, inverse-time feeds (`G93`), `o… repeat` loops.
    Linuxcnc,
    /// Aerotech AeroBasic (A3200), per-move feeds in units per second.
    Aerobasic,
}

/// How repeated passes are written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RepeatMode {
    /// A loop in the controller's language, one body per path.
    Loop,
    /// Every pass written out.
    Unroll,
}

/// Units of the rotary axis words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RotaryUnits {
    /// Degrees: `A = s/r_o·180/π`.
    Deg,
    /// Revolutions: `A = s/(2π·r_o)`.
    Rev,
}

impl RotaryUnits {
    /// Rotary units per radian.
    pub fn per_rad(self) -> f64 {
        match self {
            Self::Deg => 180.0 / std::f64::consts::PI,
            Self::Rev => 0.5 / std::f64::consts::PI,
        }
    }

    /// The unit's symbol for headers and sheets.
    pub fn symbol(self) -> &'static str {
        match self {
            Self::Deg => "deg",
            Self::Rev => "rev",
        }
    }
}

/// Axis letters and rotary units (`[axes]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axes {
    /// The linear axis along the tube.
    pub linear: char,
    /// The rotary axis turning the collet.
    pub rotary: char,
    /// The focus axis.
    pub focus: char,
    /// Units of the rotary axis words.
    pub rotary_units: RotaryUnits,
}

/// Travel, speed and power limits (`[limits]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Limits {
    /// Lowest X the program may reach (mm, program frame).
    pub x_min_mm: f64,
    /// Highest X the program may reach (mm, program frame).
    pub x_max_mm: f64,
    /// Fastest X speed the stage follows with the beam on (mm/s); also the rapid speed used
    /// for time estimates.
    pub x_speed_max_mm_s: f64,
    /// Fastest A speed the stage follows with the beam on (deg/s); also the rapid speed used
    /// for time estimates.
    pub a_speed_max_deg_s: f64,
    /// Most average power a program may ask for (mW).
    pub max_power_mw: f64,
}

/// Where the focus sits (`[focus]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Focus {
    /// Z with the focus on the rotation axis (mm); the tube's surface is `r_o` above it.
    pub z_axis_mm: f64,
}

/// The fixture (`[fixture]`, optional).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Fixture {
    /// Length of stock the collet holds (mm), for the stock length on the setup sheet.
    pub collet_grip_mm: f64,
}

impl Default for Fixture {
    fn default() -> Self {
        Self {
            collet_grip_mm: 10.0,
        }
    }
}

/// The laser commands as written in `[laser]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct LaserFile {
    beam_on: String,
    beam_off: String,
    power: String,
    pulse_frequency: String,
    pulse_width: String,
    #[serde(default)]
    wavelength: String,
}

/// How each laser parameter is set, as checked templates.
#[derive(Debug, Clone, PartialEq)]
pub struct LaserCommands {
    /// Opens the beam gate.
    pub beam_on: Template,
    /// Closes the beam gate.
    pub beam_off: Template,
    /// Sets the average power: `{power_mw}`, `{power_w}` or `{power_percent}` (of the maximum).
    pub power: Template,
    /// Sets the pulse frequency: `{pulse_frequency_khz}` or `{pulse_frequency_hz}`.
    pub pulse_frequency: Template,
    /// Sets the pulse width: `{pulse_width_fs}` or `{pulse_width_ps}`.
    pub pulse_width: Template,
    /// Selects the wavelength: `{wavelength_nm}`; usually empty (fixed by the source).
    pub wavelength: Template,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ProfileFile {
    name: String,
    dialect: Dialect,
    repetitions: RepeatMode,
    axes: Axes,
    limits: Limits,
    focus: Focus,
    laser: LaserFile,
    #[serde(default)]
    fixture: Fixture,
    #[serde(default)]
    settle: Settle,
}

/// A checked machine profile.
#[derive(Debug, Clone, PartialEq)]
pub struct MachineProfile {
    /// Where it came from: a path, or `built-in NAME`.
    pub source: String,
    /// Human-readable name, printed in program headers.
    pub name: String,
    /// Which post-processor writes the program.
    pub dialect: Dialect,
    /// Loops or unrolled passes.
    pub repetitions: RepeatMode,
    /// Axis letters and rotary units.
    pub axes: Axes,
    /// Travel, speed and power limits.
    pub limits: Limits,
    /// Focus position.
    pub focus: Focus,
    /// Laser commands.
    pub laser: LaserCommands,
    /// Fixture dimensions.
    pub fixture: Fixture,
    /// How the program waits for the source to settle between operations with different
    /// laser parameters (`[settle]`, optional).
    pub settle: Settle,
}

impl MachineProfile {
    /// Parses and checks a profile; `source` names it in messages.
    ///
    /// # Errors
    /// [`MachineError::Parse`] for malformed TOML, unknown or missing keys, an unknown dialect;
    /// [`MachineError::Value`] for a limit out of range, a bad axis letter or template.
    pub fn from_toml(source: &str, text: &str) -> Result<Self, MachineError> {
        let file: ProfileFile = toml::from_str(text).map_err(|e| MachineError::Parse {
            name: source.to_string(),
            message: crate::limits::parser_message(&e),
        })?;
        let bad = |key: &str, value: String, limit: String| MachineError::Value {
            name: source.to_string(),
            key: key.to_string(),
            value,
            limit,
        };
        check_numbers(&file, &bad)?;
        check_axis_letters(&file.axes, &bad)?;
        let laser = laser_commands(&file.laser, &bad)?;
        Ok(Self {
            source: source.to_string(),
            name: file.name,
            dialect: file.dialect,
            repetitions: file.repetitions,
            axes: file.axes,
            limits: file.limits,
            focus: file.focus,
            laser,
            fixture: file.fixture,
            settle: file.settle,
        })
    }

    /// Z of the focus on the tube's outer surface: the rotation axis plus `r_o`.
    pub fn surface_z_mm(&self, outer_radius_mm: f64) -> f64 {
        self.focus.z_axis_mm + outer_radius_mm
    }
}

/// Builds the error for a key whose value is out of its limit: `(key, value, limit)`.
type Bad<'a> = &'a dyn Fn(&str, String, String) -> MachineError;

/// Checks the profile's numbers: speeds and power above 0, coordinates within a machine's
/// travel, the travel the right way round, the collet grip not negative, the settle dwell.
fn check_numbers(file: &ProfileFile, bad: Bad<'_>) -> Result<(), MachineError> {
    let l = &file.limits;
    for (key, v) in [
        ("limits.x_speed_max_mm_s", l.x_speed_max_mm_s),
        ("limits.a_speed_max_deg_s", l.a_speed_max_deg_s),
        ("limits.max_power_mw", l.max_power_mw),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(bad(key, v.to_string(), "must be finite and > 0".into()));
        }
    }
    for (key, v) in [
        ("limits.x_min_mm", l.x_min_mm),
        ("limits.x_max_mm", l.x_max_mm),
        ("focus.z_axis_mm", file.focus.z_axis_mm),
        ("fixture.collet_grip_mm", file.fixture.collet_grip_mm),
    ] {
        if !(v.is_finite() && v.abs() <= MAX_ABS_COORDINATE_MM) {
            return Err(bad(
                key,
                crate::limits::short(v),
                format!(
                    "must be finite and within ±{MAX_ABS_COORDINATE_MM} mm (a machine's travel)"
                ),
            ));
        }
    }
    if !(l.x_min_mm.is_finite() && l.x_max_mm.is_finite() && l.x_min_mm < l.x_max_mm) {
        return Err(bad(
            "limits.x_max_mm",
            l.x_max_mm.to_string(),
            format!("must be finite and above limits.x_min_mm = {}", l.x_min_mm),
        ));
    }
    if !file.focus.z_axis_mm.is_finite() {
        return Err(bad(
            "focus.z_axis_mm",
            file.focus.z_axis_mm.to_string(),
            "must be finite".into(),
        ));
    }
    if !(file.fixture.collet_grip_mm.is_finite() && file.fixture.collet_grip_mm >= 0.0) {
        return Err(bad(
            "fixture.collet_grip_mm",
            file.fixture.collet_grip_mm.to_string(),
            "must be finite and >= 0".into(),
        ));
    }
    file.settle
        .check()
        .map_err(|(value, limit)| bad("settle.dwell_s", value, limit))
}

/// Checks that each axis letter is a G-code axis word and that no two axes share one.
fn check_axis_letters(axes: &Axes, bad: Bad<'_>) -> Result<(), MachineError> {
    let letters = [
        ("axes.linear", axes.linear),
        ("axes.rotary", axes.rotary),
        ("axes.focus", axes.focus),
    ];
    for (i, (key, c)) in letters.iter().enumerate() {
        if !"XYZABCUVW".contains(*c) {
            return Err(bad(
                key,
                format!("{c:?}"),
                "must be one of X Y Z A B C U V W".into(),
            ));
        }
        if letters[..i].iter().any(|(_, d)| d == c) {
            return Err(bad(
                key,
                format!("{c:?}"),
                "is already used by another axis".into(),
            ));
        }
    }
    Ok(())
}

/// The laser's command templates, each parsed against the placeholders it may use; the beam
/// and power commands must not be empty.
fn laser_commands(f: &LaserFile, bad: Bad<'_>) -> Result<LaserCommands, MachineError> {
    let template = |key: &str, text: &str, allowed: &[&str], required: bool| {
        let t = Template::parse(text, allowed)
            .map_err(|limit| bad(&format!("laser.{key}"), format!("{text:?}"), limit))?;
        if required && t.is_empty() {
            return Err(bad(
                &format!("laser.{key}"),
                format!("{text:?}"),
                "must not be empty: the program cannot run without it".into(),
            ));
        }
        Ok(t)
    };
    Ok(LaserCommands {
        beam_on: template("beam_on", &f.beam_on, &[], true)?,
        beam_off: template("beam_off", &f.beam_off, &[], true)?,
        power: template(
            "power",
            &f.power,
            &["power_mw", "power_w", "power_percent"],
            true,
        )?,
        pulse_frequency: template(
            "pulse_frequency",
            &f.pulse_frequency,
            &["pulse_frequency_khz", "pulse_frequency_hz"],
            false,
        )?,
        pulse_width: template(
            "pulse_width",
            &f.pulse_width,
            &["pulse_width_fs", "pulse_width_ps"],
            false,
        )?,
        wavelength: template("wavelength", &f.wavelength, &["wavelength_nm"], false)?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const REFERENCE: &str = include_str!("../../designs/machines/linuxcnc-reference.toml");
    const AEROTECH: &str = include_str!("../../designs/machines/aerotech-aerobasic.toml");

    #[test]
    fn shipped_profiles_read() {
        let p = MachineProfile::from_toml("ref", REFERENCE).unwrap();
        assert_eq!(p.dialect, Dialect::Linuxcnc);
        assert_eq!(p.repetitions, RepeatMode::Loop);
        assert_eq!(
            (p.axes.linear, p.axes.rotary, p.axes.focus),
            ('X', 'A', 'Z')
        );
        assert_eq!(p.laser.power.as_str(), "S{power_mw}");
        assert!(p.laser.wavelength.is_empty());
        assert!((p.surface_z_mm(1.24) - 1.24).abs() < 1e-12);
        let a = MachineProfile::from_toml("aero", AEROTECH).unwrap();
        assert_eq!(a.dialect, Dialect::Aerobasic);
        assert_eq!(a.repetitions, RepeatMode::Unroll);
    }

    #[test]
    fn refuses_unknown_keys_and_bad_values() {
        let err = MachineProfile::from_toml(
            "p",
            &REFERENCE.replace("[focus]", "[focus]\nz_offset_mm = 1"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("z_offset_mm") && err.contains("machine profile \"p\""),
            "{err}"
        );
        let err = MachineProfile::from_toml(
            "p",
            &REFERENCE.replace("dialect = \"linuxcnc\"", "dialect = \"fanuc\""),
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("fanuc"), "{err}");
        let err = MachineProfile::from_toml(
            "p",
            &REFERENCE.replace("x_max_mm = 150.0", "x_max_mm = -10.0"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("limits.x_max_mm = -10") && err.contains("x_min_mm = -5"),
            "{err}"
        );
        let err = MachineProfile::from_toml("p", &REFERENCE.replace("S{power_mw}", "S{power}"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("laser.power") && err.contains("{power}"),
            "{err}"
        );
        let err =
            MachineProfile::from_toml("p", &REFERENCE.replace("rotary = \"A\"", "rotary = \"X\""))
                .unwrap_err()
                .to_string();
        assert!(
            err.contains("axes.rotary") && err.contains("already used"),
            "{err}"
        );
        let err = MachineProfile::from_toml(
            "p",
            &REFERENCE.replace("beam_on = \"M3\"", "beam_on = \"\""),
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("laser.beam_on"), "{err}");
    }
}
