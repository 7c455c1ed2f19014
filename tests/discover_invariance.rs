//! The sensor channel never sees the plant model (issue 31): a sensor's candidates, evidence,
//! calibration and verdict are bit-identical whatever the plant model holds. Discovery runs on
//! one recording with the plant's base model forced (through the base scenario's known effects)
//! to each library effect of the plant, to both and to none, and to random shapes of them; the
//! sensors' part of every result must be the same to the last bit, on a UAN joint and a BSN one.
//!
//! Until issue 31 the sensors' candidates were built on the plant model's angle, and a plant
//! effect the plant model lacked showed on a sensor as a lag or a loop.

use dlw::design::Design;
use dlw::discover::model::Stage;
use dlw::discover::terms::Term;
use dlw::discover::{discover, Known, Outcome};
use dlw::sim::{plan, ProtocolKind, Recording, Scenario};
use proptest::prelude::*;

/// A recording of `design` with a plant relaxation and a sensor creep (so the sensor has
/// candidates, a name and its calibration to compare), correlated noise.
fn recording(design: &Design, duration_s: f64, seed: u64) -> Recording {
    let mut scenario = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(duration_s),
        seed,
        ..Scenario::default()
    };
    scenario.set_correlated_noise(true);
    scenario.plant.relaxation.enabled = true;
    scenario.plant.relaxation.fraction = 0.08;
    scenario.plant.relaxation.tau_s = 20.0;
    scenario.sensor1.creep.enabled = true;
    scenario.sensor1.creep.fraction = if duration_s > 1000.0 { 0.5 } else { 0.12 };
    scenario.sensor1.creep.tau_s = 10.0;
    let p = plan(design, scenario, None).expect("the scenario is valid");
    Recording {
        rig: p.rig(),
        samples: p.run().expect("it runs").samples,
    }
}

/// Everything discovery says about the sensors, as text with every number's bits: candidates
/// (effect, shape, round, evidence, memory), names (evidence, parameters, calibration, rivals),
/// ambiguity, what was declined, what is unexplained, and the gaps.
fn sensors_part(o: &Outcome) -> String {
    let sensor = |c: &Stage| *c != Stage::Plant;
    let bits = |v: f64| format!("{:016x}", v.to_bits());
    let mut out = String::new();
    for c in o.candidates.iter().filter(|c| sensor(&c.channel)) {
        out += &format!(
            "candidate {:?} {:?} {} r{} {} {:?}\n",
            c.channel,
            c.effect,
            c.shape,
            c.round,
            bits(c.evidence),
            c.memory.map(bits)
        );
    }
    for d in o.discovered.iter().filter(|d| sensor(&d.channel)) {
        out += &format!(
            "named {:?} {:?} {} {:?} {:?}\n",
            d.channel,
            d.effect,
            bits(d.evidence),
            d.parameters
                .iter()
                .map(|(k, v)| (k, bits(*v)))
                .collect::<Vec<_>>(),
            d.term
        );
        out += &format!(
            "  calibration {}\n",
            serde_json::to_string(&d.calibration).unwrap()
        );
        out += &format!("  rivals {}\n", serde_json::to_string(&d.rivals).unwrap());
    }
    for a in o.ambiguous.iter().filter(|a| sensor(&a.channel)) {
        out += &format!("ambiguous {}\n", serde_json::to_string(a).unwrap());
    }
    for d in o.declined.iter().filter(|d| sensor(&d.channel)) {
        out += &format!("declined {}\n", serde_json::to_string(d).unwrap());
    }
    for u in o.unexplained.iter().filter(|u| sensor(&u.channel)) {
        out += &format!("unexplained {}\n", serde_json::to_string(u).unwrap());
    }
    for g in o.gaps.iter().filter(|g| sensor(&g.channel)) {
        out += &format!(
            "gap {:?} {} {} {:?}\n",
            g.channel,
            bits(g.before),
            bits(g.after),
            g.steps
                .iter()
                .map(|(e, v)| (e, bits(*v)))
                .collect::<Vec<_>>()
        );
    }
    out
}

/// The plant's base model forced to `terms`.
fn forced(terms: &[Term]) -> Known {
    terms.iter().map(|t| (Stage::Plant, t.clone())).collect()
}

fn run(design: &Design, rec: &Recording, known: &Known) -> String {
    let o = discover(rec, None, &design.joint, known, &|_| {}).expect("discovery runs");
    sensors_part(&o)
}

/// The plant forced to none, each library effect, and both.
fn each_plant_effect() -> Vec<Known> {
    vec![
        forced(&[]),
        forced(&[Term::Backlash { half_mm: 0.03 }]),
        forced(&[Term::Relaxation { tau_s: 20.0 }]),
        forced(&[
            Term::Backlash { half_mm: 0.01 },
            Term::Relaxation { tau_s: 4.0 },
        ]),
        forced(&[Term::RelaxationSpread {
            taus_s: vec![0.5, 2.0, 8.0, 32.0, 128.0],
        }]),
    ]
}

#[test]
fn a_uan_sensor_is_the_same_whatever_the_plant_model_holds() {
    let design = Design::from_toml(include_str!("../designs/joint-a.toml")).unwrap();
    let rec = recording(&design, 300.0, 11);
    let reference = run(&design, &rec, &forced(&[]));
    assert!(
        reference.contains("named"),
        "the sensor names its creep, so there is a verdict to compare:\n{reference}"
    );
    for known in each_plant_effect() {
        assert_eq!(
            run(&design, &rec, &known),
            reference,
            "plant forced to {known:?}"
        );
    }
}

#[test]
fn a_bsn_joints_sensors_are_the_same_whatever_the_plant_model_holds() {
    let design = Design::from_toml(include_str!("../designs/joint-c.toml")).unwrap();
    let rec = recording(&design, 600.0, 12);
    let reference = run(&design, &rec, &forced(&[]));
    assert!(reference.contains("Sensor(Two)"), "{reference}");
    for known in each_plant_effect() {
        assert_eq!(
            run(&design, &rec, &known),
            reference,
            "plant forced to {known:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 4, ..ProptestConfig::default() })]

    /// Any shape of the plant's effects, on Joint A.
    #[test]
    fn any_plant_shape_leaves_the_sensor_unchanged(
        half_mm in proptest::option::of(0.002f64..0.1),
        tau_s in proptest::option::of(0.5f64..100.0),
    ) {
        let design = Design::from_toml(include_str!("../designs/joint-a.toml")).unwrap();
        let rec = recording(&design, 300.0, 11);
        let reference = run(&design, &rec, &forced(&[]));
        let mut terms = Vec::new();
        if let Some(half_mm) = half_mm {
            terms.push(Term::Backlash { half_mm });
        }
        if let Some(tau_s) = tau_s {
            terms.push(Term::Relaxation { tau_s });
        }
        prop_assert_eq!(run(&design, &rec, &forced(&terms)), reference);
    }
}
