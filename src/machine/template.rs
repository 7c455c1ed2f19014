//! Laser command templates: a profile says how each parameter is set, e.g. `M68 E0 Q{pulse_frequency_khz}`.

use std::fmt::Write;

/// The values a template may name, all from one process set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LaserValues {
    /// Average power (mW).
    pub power_mw: f64,
    /// The profile's maximum power (mW), for `{power_percent}`.
    pub max_power_mw: f64,
    /// Pulse frequency (kHz).
    pub pulse_frequency_khz: f64,
    /// Pulse width (fs).
    pub pulse_width_fs: f64,
    /// Wavelength (nm).
    pub wavelength_nm: f64,
}

impl LaserValues {
    fn get(&self, placeholder: &str) -> Option<f64> {
        Some(match placeholder {
            "power_mw" => self.power_mw,
            "power_w" => self.power_mw / 1000.0,
            "power_percent" => 100.0 * self.power_mw / self.max_power_mw,
            "pulse_frequency_khz" => self.pulse_frequency_khz,
            "pulse_frequency_hz" => self.pulse_frequency_khz * 1000.0,
            "pulse_width_fs" => self.pulse_width_fs,
            "pulse_width_ps" => self.pulse_width_fs / 1000.0,
            "wavelength_nm" => self.wavelength_nm,
            _ => return None,
        })
    }
}

/// A checked command template: literal text with `{placeholder}` values, on one line.
///
/// An empty template means the program does not set that parameter; the header lists it for
/// the operator to set by hand.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Template {
    text: String,
}

impl Template {
    /// Checks `text` against the placeholders it may use.
    ///
    /// # Errors
    /// A message naming the unknown placeholder or the unclosed brace, and the allowed names.
    pub fn parse(text: &str, allowed: &[&str]) -> Result<Self, String> {
        if let Some((at, c)) = text.char_indices().find(|(_, c)| c.is_control()) {
            return Err(format!(
                "has the control character U+{:04X} at byte {at}: a template is one G-code line \
                 of printable text (a newline would let it add moves the program never checks)",
                u32::from(c)
            ));
        }
        let mut rest = text;
        while let Some(open) = rest.find('{') {
            let after = &rest[open + 1..];
            let close = after
                .find('}')
                .ok_or_else(|| format!("has an unclosed '{{' in {text:?}"))?;
            let name = &after[..close];
            if !allowed.contains(&name) {
                return Err(format!(
                    "uses {{{name}}}, which is not one of {{{}}}",
                    allowed.join("}, {")
                ));
            }
            rest = &after[close + 1..];
        }
        if rest.contains('}') {
            return Err(format!("has a stray '}}' in {text:?}"));
        }
        Ok(Self {
            text: text.to_string(),
        })
    }

    /// True when the program does not set this parameter.
    pub fn is_empty(&self) -> bool {
        self.text.trim().is_empty()
    }

    /// The template as written.
    pub fn as_str(&self) -> &str {
        &self.text
    }

    /// The command lines with the values filled in (numbers with at most 4 decimals).
    pub fn render(&self, values: &LaserValues) -> Vec<String> {
        let mut out = String::new();
        let mut rest = self.text.as_str();
        while let Some(open) = rest.find('{') {
            out.push_str(&rest[..open]);
            let after = &rest[open + 1..];
            let close = after.find('}').unwrap_or(after.len());
            // Placeholders were checked in `parse`, so `get` finds every one.
            let value = values.get(&after[..close]).unwrap_or(f64::NAN);
            let _ = write!(out, "{}", format_number(value));
            rest = after.get(close + 1..).unwrap_or("");
        }
        out.push_str(rest);
        out.lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .map(String::from)
            .collect()
    }
}

/// A number with at most 4 decimals and no trailing zeros: `160`, `0.16`, `2.5`.
pub fn format_number(value: f64) -> String {
    // `fixed` never writes `-0.0000`, so no trimmed `-0` can appear.
    let s = crate::fixed::fixed(value, 4);
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    const VALUES: LaserValues = LaserValues {
        power_mw: 160.0,
        max_power_mw: 2500.0,
        pulse_frequency_khz: 200.0,
        pulse_width_fs: 550.0,
        wavelength_nm: 1030.0,
    };

    #[test]
    fn numbers_lose_trailing_zeros_and_never_read_negative_zero() {
        assert_eq!(format_number(-0.00001), "0");
        assert_eq!(format_number(160.0), "160");
        assert_eq!(format_number(0.16), "0.16");
    }

    #[test]
    fn renders_placeholders_and_refuses_unknown_ones() {
        let t = Template::parse("S{power_mw}", &["power_mw", "power_w"]).unwrap();
        assert_eq!(t.render(&VALUES), vec!["S160"]);
        let t = Template::parse(
            "P={power_w} Q={power_percent}",
            &["power_w", "power_percent"],
        )
        .unwrap();
        assert_eq!(t.render(&VALUES), vec!["P=0.16 Q=6.4"]);
        // One G-code line: a newline (or any control character) could add an unchecked move.
        let err = Template::parse("M3\nG0 X900", &[]).unwrap_err();
        assert!(
            err.contains("U+000A") && err.contains("one G-code line"),
            "{err}"
        );
        assert!(Template::parse("M3\tS1", &[]).is_err());
        let err = Template::parse("S{power}", &["power_mw"]).unwrap_err();
        assert!(
            err.contains("{power}") && err.contains("{power_mw}"),
            "{err}"
        );
        assert!(Template::parse("S{power_mw", &["power_mw"]).is_err());
        assert!(Template::parse("", &[]).unwrap().is_empty());
    }

    #[test]
    fn numbers_are_short() {
        for (v, s) in [
            (160.0, "160"),
            (0.16, "0.16"),
            (2.5, "2.5"),
            (-0.0, "0"),
            (1.23456, "1.2346"),
        ] {
            assert_eq!(format_number(v), s);
        }
    }
}
