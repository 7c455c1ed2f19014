//! `dlw discover` on forms the other-forms generator did not have before (issue 19): memoryless
//! saturations of four shapes, asymmetric soft backlash, relaxation and backlash at several
//! sizes with nothing on the sensor, a drift that grows as √t, and a rate with a drift. Every
//! case asserts the exact set of names: a wrong name is the failure that costs a researcher
//! most, and a name on a channel the effect is not on is a wrong name.

mod common;
use common::other_forms::{self, Bench, Effect, Forms, Saturation};
use common::shipped_design;

use std::collections::BTreeSet;
use std::path::Path;

/// Recording length (s) on Joint A.
const DURATION_S: f64 = 300.0;

/// Runs `dlw discover --json` on a generated recording; returns the set of (effect, channel).
fn names(dir: &Path, bench: &Bench, name: &str) -> BTreeSet<(String, String)> {
    let report = discover_json(dir, bench, name);
    // A saturation is written in the library's one form; the scenario says how much a curve
    // of any shape would fit better, and the JSON carries both RMSEs.
    for d in report["discovered"].as_array().unwrap() {
        if d["effect"] == "saturation" {
            let (library, any) = (
                d["form"]["library_rmse"].as_f64().unwrap(),
                d["form"]["any_shape_rmse"].as_f64().unwrap(),
            );
            assert!(library.is_finite() && any.is_finite() && any > 0.0, "{d}");
            let scenario =
                std::fs::read_to_string(dir.join(format!("{name}-out/scenario.toml"))).unwrap();
            assert!(
                scenario.contains("saturation on sensor1: written in the library's form"),
                "{scenario}"
            );
        }
    }
    report["discovered"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["effect"].as_str().unwrap().to_owned(),
                d["channel"].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

/// Runs `dlw discover --json` on a generated recording of Joint A; returns the JSON.
fn discover_json(dir: &Path, bench: &Bench, name: &str) -> serde_json::Value {
    let design = shipped_design("joint-a.toml");
    let rec = dir.join(name);
    other_forms::write_recording(Path::new(&design), bench, &rec);
    let out = dir.join(format!("{name}-out"));
    let o = common::dlw(&[
        "discover".as_ref(),
        "--design".as_ref(),
        design.as_ref(),
        rec.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ]);
    assert!(
        o.status.success(),
        "discover {name} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

fn expect(pairs: &[(&str, &str)]) -> BTreeSet<(String, String)> {
    pairs
        .iter()
        .map(|(e, c)| ((*e).to_owned(), (*c).to_owned()))
        .collect()
}

/// Runs every case; prints all before asserting. A name outside a case's expected set is a
/// wrong name and fails at once; a case whose set comes back incomplete is a miss, and at most
/// `max_misses` are allowed (each test states which case misses and why).
/// A case: its name, the bench, the names expected.
type Case = (String, Bench, BTreeSet<(String, String)>);

fn run(cases: Vec<Case>, max_misses: usize) {
    let dir = tempfile::tempdir().unwrap();
    let (mut wrong, mut missed) = (Vec::new(), Vec::new());
    for (name, bench, want) in cases {
        let got = names(dir.path(), &bench, &name);
        eprintln!("{name}: discovered {got:?}, expected {want:?}");
        if !got.is_subset(&want) {
            wrong.push((name, got, want));
        } else if got != want {
            missed.push(name);
        }
    }
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
    assert!(
        missed.len() <= max_misses,
        "missed {missed:?} (at most {max_misses})"
    );
}

fn bench(effects: &[(Effect, usize)], seed: u64, forms: Forms) -> Bench {
    Bench {
        effects: effects.to_vec(),
        duration_s: DURATION_S,
        seed,
        forms,
    }
}

/// A memoryless curve of any shape whose sensitivity falls with strain is `saturation`,
/// never `hysteresis`: memory is named only when the data shows a loop no memoryless curve
/// draws.
#[test]
fn memoryless_curves_of_every_shape_are_saturation() {
    let cases = [
        Saturation::Rational,
        Saturation::Algebraic,
        Saturation::Power,
        Saturation::Piecewise,
    ]
    .into_iter()
    .enumerate()
    .map(|(i, shape)| {
        let forms = Forms {
            saturation: shape,
            ..Forms::default()
        };
        (
            format!("saturation-{shape:?}"),
            bench(&[(Effect::Saturation, 1)], 500 + i as u64, forms),
            expect(&[("saturation", "sensor1")]),
        )
    })
    .collect();
    // Measured: the power law (no knee, sensitivity falling as ε^−0.2) is missed: the tanh of
    // the library's saturation does not draw it well enough to clear the threshold, and its
    // memoryless curve no longer lets the plays win. A miss, never `hysteresis`.
    run(cases, 1);
}

/// A plant effect, at half, once and twice its size, and a backlash wider on one side, names
/// the plant effect and nothing on the sensor.
#[test]
fn plant_effects_name_no_sensor_effect() {
    let mut cases = Vec::new();
    for (effect, name) in [
        (Effect::Backlash, "backlash"),
        (Effect::Relaxation, "relaxation"),
    ] {
        for (k, scale) in [0.5, 1.0, 2.0].into_iter().enumerate() {
            let forms = Forms {
                plant_scale: Some(scale),
                ..Forms::default()
            };
            cases.push((
                format!("{name}-x{scale}"),
                bench(&[(effect, 0)], 600 + 10 * k as u64 + effect as u64, forms),
                expect(&[(name, "plant")]),
            ));
        }
    }
    let forms = Forms {
        backlash_asymmetry: Some(2.5),
        ..Forms::default()
    };
    cases.push((
        "backlash-asymmetric".into(),
        bench(&[(Effect::Backlash, 0)], 640, forms),
        expect(&[("backlash", "plant")]),
    ));
    // Measured: relaxation at half size (fractions 0.02 and 0.025) is missed, below the
    // evidence threshold on 300 s; never a sensor name.
    run(cases, 1);
}

/// A drift of another form (√t) is `drift`; a rate with a drift is both, and not `creep`.
#[test]
fn drift_is_time_not_history() {
    let sqrt = Forms {
        drift_sqrt: true,
        ..Forms::default()
    };
    run(
        vec![
            (
                "drift-sqrt".into(),
                bench(&[(Effect::Drift, 1)], 700, sqrt),
                expect(&[("drift", "sensor1")]),
            ),
            (
                "rate-and-drift".into(),
                bench(
                    &[(Effect::Rate, 1), (Effect::Drift, 1)],
                    710,
                    Forms::default(),
                ),
                expect(&[("rate", "sensor1"), ("drift", "sensor1")]),
            ),
        ],
        0,
    );
}

/// Effects outside the library: a sensitivity that fades exponentially (the library's
/// `gain_drift` is linear in time) and a sensor that stiffens (its sensitivity rises with
/// strain, which no effect of the library draws). Never one of the seven library names; the
/// channel is flagged `unexplained`, or the fade is named `gain_drift`.
#[test]
fn effects_outside_the_library_are_flagged_not_named() {
    let dir = tempfile::tempdir().unwrap();
    let library = [
        "hysteresis",
        "saturation",
        "rate",
        "creep",
        "drift",
        "relaxation",
        "backlash",
    ];
    let cases = [
        (
            "gain-fade",
            Forms {
                gain_fade: true,
                ..Forms::default()
            },
        ),
        (
            "stiffening",
            Forms {
                stiffening: true,
                ..Forms::default()
            },
        ),
    ];
    let mut failures = Vec::new();
    for (i, (name, forms)) in cases.into_iter().enumerate() {
        let report = discover_json(dir.path(), &bench(&[], 800 + i as u64, forms), name);
        let named: Vec<String> = report["discovered"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| format!("{}@{}", d["effect"], d["channel"]))
            .collect();
        let flagged: Vec<String> = report["unexplained"]
            .as_array()
            .unwrap()
            .iter()
            .map(|u| u["channel"].as_str().unwrap().to_owned())
            .collect();
        eprintln!("{name}: named {named:?}, unexplained on {flagged:?}");
        let wrong = named
            .iter()
            .any(|n| library.iter().any(|l| n.starts_with(&format!("\"{l}\""))));
        let gain_drift = named.iter().any(|n| n == "\"gain_drift\"@\"sensor1\"");
        let flagged_right = flagged == ["sensor1"];
        if wrong || !(flagged_right || gain_drift) {
            failures.push((name, named, flagged));
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The simulator's own `gain_drift` (the sensitivity fading 2 per hour, 17 % over 300 s) is
/// named on the right channel, and the scenario written carries it.
#[test]
fn the_simulators_gain_drift_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let design = shipped_design("joint-a.toml");
    let scenario = dir.path().join("fade.toml");
    std::fs::write(&scenario, "[sensor1.gain_drift]\nfade_per_hour = 2.0\n").unwrap();
    let rec = dir.path().join("rec");
    let o = common::dlw(&[
        "simulate".as_ref(),
        "--design".as_ref(),
        design.as_ref(),
        "--protocol".as_ref(),
        "random".as_ref(),
        "--duration-s".as_ref(),
        "300".as_ref(),
        "--seed".as_ref(),
        "5".as_ref(),
        "--noise".as_ref(),
        "realistic".as_ref(),
        "--scenario".as_ref(),
        scenario.as_os_str(),
        "-o".as_ref(),
        rec.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = dir.path().join("out");
    let o = common::dlw(&[
        "discover".as_ref(),
        "--design".as_ref(),
        design.as_ref(),
        rec.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--json".as_ref(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let named: Vec<(String, String)> = report["discovered"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["effect"].as_str().unwrap().to_owned(),
                d["channel"].as_str().unwrap().to_owned(),
            )
        })
        .collect();
    assert_eq!(
        named,
        [("gain_drift".to_owned(), "sensor1".to_owned())],
        "{report}"
    );
    let fade = report["discovered"][0]["parameters"]["fade_per_hour"]
        .as_f64()
        .unwrap();
    assert!((fade - 2.0).abs() < 0.5, "fade_per_hour {fade}");
    let written = std::fs::read_to_string(out.join("scenario.toml")).unwrap();
    assert!(written.contains("[sensor1.gain_drift]"), "{written}");
}
