//! The simulated joints A-D: the shipped designs and a scenario for each that gives the
//! simulator's sensor the paper's Table III (its PI model built from the table's points) and
//! switches on the effects the paper's experiments look for.

use crate::design::Design;
use crate::sim::{
    PiCharacteristics, ProtocolKind, Scenario, SensorModelKind, SensorParams, JOINT_A_PI,
    JOINT_C_PI,
};

/// Joint B's (and D's, the same design) Table III points.
pub const JOINT_B_PI: PiCharacteristics = PiCharacteristics {
    center_strain: 0.00531,
    center_ohm: 87.9e3,
    center_slope_ohm: 3090e3,
    peak_ohm: 99.2e3,
    peak_strain: 0.0157,
};

/// One simulated joint.
#[derive(Debug, Clone)]
pub struct SimJoint {
    /// `A` … `D`.
    pub letter: char,
    /// The design.
    pub design: Design,
    /// The scenario without protocol and duration.
    pub scenario: Scenario,
}

/// Joints A-D. Every one has the PI sensor of its Table III points, the default ADC and
/// tracker noise, baseline drift sized to the paper's `R₀` spread over 3000 s, and the default
/// relaxation (5 %, τ = 20 s, illustrative); Joint D, the control joint, relaxes 15 % and has
/// 0.1 mm of backlash, as in `docs/experiments.md`'s control example.
pub fn joints() -> Vec<SimJoint> {
    let texts = [
        ('A', include_str!("../../designs/joint-a.toml")),
        ('B', include_str!("../../designs/joint-b.toml")),
        ('C', include_str!("../../designs/joint-c.toml")),
        ('D', include_str!("../../designs/joint-d.toml")),
    ];
    texts
        .iter()
        .map(|&(letter, text)| {
            // The shipped designs are checked by the design tests; a failure here is a bug.
            let design = Design::from_toml(text).unwrap_or_else(|e| panic!("{letter}: {e}"));
            let mut sc = Scenario::default();
            let (pi, gf, r0, walk) = match letter {
                'A' => (JOINT_A_PI, 15.3, 215e3, 20.0),
                'B' | 'D' => (JOINT_B_PI, 22.0, 77.2e3, 0.596e3 / 3000f64.sqrt()),
                _ => (JOINT_C_PI, 1.28, 74.0e3, 0.7),
            };
            sc.sensor1 = sensor(gf, r0, walk);
            sc.sensor1.model = SensorModelKind::Pi;
            sc.sensor1.pi = Some(pi.to_config());
            if letter == 'C' {
                // The compression sensor, fitted only linearly by the paper (Table V).
                sc.sensor2 = Some(sensor(0.680, 88.9e3, 0.7));
            }
            sc.plant.relaxation.enabled = true;
            if letter == 'D' {
                sc.plant.relaxation.fraction = 0.15;
                sc.plant.backlash.enabled = true;
                sc.plant.backlash.width_mm = 0.1;
            }
            SimJoint {
                letter,
                design,
                scenario: sc,
            }
        })
        .collect()
}

fn sensor(gf: f64, r0: f64, walk: f64) -> SensorParams {
    let mut s = SensorParams {
        gauge_factor: Some(gf),
        r0_ohm: Some(r0),
        ..SensorParams::default()
    };
    s.drift.enabled = true;
    s.drift.random_walk_ohm_per_sqrt_s = Some(walk);
    s
}

/// `scenario` running `protocol` with every protocol timing (and the relaxation time
/// constant) multiplied by `scale`; the repetitions stay the paper's five.
pub fn scaled(scenario: &Scenario, protocol: ProtocolKind, scale: f64, seed: u64) -> Scenario {
    let mut sc = scenario.clone();
    sc.protocol = Some(protocol);
    sc.seed = seed;
    let p = &mut sc.protocols;
    p.rest_start_s *= scale;
    p.characterization.full_rise_s *= scale;
    p.characterization.rest_s *= scale;
    for r in &mut p.rate_dependence.rise_s {
        *r *= scale;
    }
    p.rate_dependence.repeat_s *= scale;
    p.relaxation.repeat_s *= scale;
    p.relaxation.ramp_s *= scale;
    p.random.min_ramp_s *= scale;
    p.random.max_ramp_s *= scale;
    p.random.max_hold_s *= scale;
    p.random.repeat_s *= scale;
    sc.plant.relaxation.tau_s *= scale;
    sc
}
