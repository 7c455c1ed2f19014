//! The setup sheet's laser-safety section: a class 4 femtosecond source, its eyewear, the
//! interlocks and the fumes of ablated polyimide.
//!
//! The sheet states what the eyewear must be rated for, from the job's own numbers, but not an
//! optical density figure of its own: the OD follows from the source's maximum output and beam
//! (ANSI Z136.1: `OD = log10(H₀/MPE)`; EN 207: the scale number `LB` for the pulse mode), which
//! only the station's laser safety officer knows.

use crate::machine::format_number;
use crate::toolpath::Plan;

/// The section's lines (Markdown), heading included.
pub fn safety_lines(plan: &Plan) -> Vec<String> {
    let sets: Vec<_> = plan.operations.iter().map(|o| &o.process).collect();
    let mut wavelengths: Vec<f64> = sets.iter().map(|s| s.wavelength_nm).collect();
    wavelengths.sort_by(f64::total_cmp);
    wavelengths.dedup();
    let wl = wavelengths
        .iter()
        .map(|w| format!("{} nm", format_number(*w)))
        .collect::<Vec<_>>()
        .join(" and ");
    let strongest = sets
        .iter()
        .max_by(|a, b| a.power_mw.total_cmp(&b.power_mw))
        .copied();
    let mut l = vec![
        "## Laser safety (read before switching the source on)".to_string(),
        String::new(),
    ];
    l.push(format!(
        "The station's femtosecond source is a **class 4 laser** (IEC 60825-1) at {wl}, near infrared and invisible: the direct beam, its reflections (the steel mandrel shows through every notch) and diffuse reflections can all injure eyes and skin."
    ));
    l.push(String::new());
    if let Some(p) = strongest {
        // Pulse energy E = P/f: mW / kHz = µJ.
        let energy_uj = p.power_mw / p.pulse_frequency_khz;
        l.push(format!(
            "- **Eyewear:** everyone in the laser area wears laser safety eyewear marked for {wl}, with an optical density at {wl} that meets OD ≥ log₁₀(H₀/MPE) (ANSI Z136.1), or marked with the EN 207 scale number LB for pulse type M (mode-locked) at {wl}. Specify it for the laser's actual maximum output and pulse parameters, not only for this job: this program asks for up to {} mW average (set `{}`), {} µJ per pulse at {} kHz, {} fs pulses. Eyewear for other wavelengths (532 nm, 800 nm) gives no protection; eyewear for 1064 nm protects only if its marking covers {wl}. Eyewear is the last line of defence, not a way to watch the cut.",
            format_number(p.power_mw),
            p.name,
            format_number((energy_uj * 1e3).round() / 1e3),
            format_number(p.pulse_frequency_khz),
            format_number(p.pulse_width_fs)
        ));
    }
    l.push("- **Interlocks:** run only with the enclosure closed and its door interlock, key switch, emergency stop and laser-on warning light working. Never bypass an interlock to watch or adjust the cut; watch on the camera. Open the shutter only after the dry run, and close it before opening the enclosure.".into());
    l.push("- **Fume extraction:** ablating polyimide (and writing the graphene sensor) releases fine particles and gases such as carbon monoxide and hydrogen cyanide. Run the fume extractor (HEPA and activated-carbon filters) at the work for every operation, keep it running a few minutes after the parting cut, and open the enclosure only then.".into());
    l.push(String::new());
    l
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_wavelength_the_od_rule_and_the_pulse_energy() {
        let design = crate::design::DesignFile::read(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/designs/joint-c.toml"
        )))
        .unwrap();
        let checked = crate::rules::check_file(design).unwrap();
        let path =
            std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/designs/joint-c.toml"));
        let sets = crate::process::ProcessLibrary::beside(path)
            .resolve(&checked.design.file.process)
            .unwrap();
        let profile = crate::machine::MachineLibrary::beside(path)
            .find(None)
            .unwrap();
        let plan = crate::toolpath::plan(
            &checked.design,
            &checked.layout,
            &sets,
            &profile,
            &crate::toolpath::PlanOptions::default(),
        )
        .unwrap();
        let text = safety_lines(&plan).join("\n");
        for want in [
            "class 4",
            "1030 nm",
            "OD ≥ log₁₀(H₀/MPE)",
            "EN 207",
            "ANSI Z136.1",
            "actual maximum output",
            // 2000 mW at 60 kHz is 33.333 µJ per pulse.
            "33.333 µJ per pulse at 60 kHz",
            "interlock",
            "polyimide",
            "fume extractor",
        ] {
            assert!(text.contains(want), "missing {want:?} in\n{text}");
        }
    }
}
