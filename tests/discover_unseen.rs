//! `dlw discover` on forms the other-forms generator did not have before (issue 19): memoryless
//! saturations of four shapes, asymmetric soft backlash, relaxation and backlash at several
//! sizes with nothing on the sensor, a drift that grows as √t, a rate with a drift, and eight
//! effects outside the library on Joint A and on both sensors of Joint C, and a creep of two
//! time constants against a rate. Every case of a
//! library effect asserts the exact set of names: a wrong name is the failure that costs a
//! researcher most, and a name on a channel the effect is not on is a wrong name.
//!
//! CI size runs one seed per out-of-library case; `DLW_DISCOVER_FULL=1` runs three.

mod common;
use common::discovery::{self, named};
use common::other_forms::{self, Bench, Effect, Forms, Outside, Saturation};
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
    pairs(&report)
}

/// Runs `dlw discover --json` on a generated recording of Joint A; returns the JSON.
fn discover_json(dir: &Path, bench: &Bench, name: &str) -> serde_json::Value {
    discover_on(dir, "joint-a.toml", bench, name)
}

/// Runs `dlw discover --json` on a generated recording of the shipped `design`.
fn discover_on(dir: &Path, design: &str, bench: &Bench, name: &str) -> serde_json::Value {
    let design = shipped_design(design);
    let rec = dir.join(name);
    other_forms::write_recording(Path::new(&design), bench, &rec);
    discovery::discover_json(&design, &rec, &dir.join(format!("{name}-out")))
}

/// The (effect, channel) pairs a report names.
fn pairs(report: &serde_json::Value) -> BTreeSet<(String, String)> {
    named(report).into_iter().collect()
}

fn expect(pairs: &[(&str, &str)]) -> BTreeSet<(String, String)> {
    pairs
        .iter()
        .map(|(e, c)| ((*e).to_owned(), (*c).to_owned()))
        .collect()
}

/// A case: its name, the bench, the names expected.
type Case = (String, Bench, BTreeSet<(String, String)>);

/// Runs every case and prints all before asserting that each named exactly its expected set.
fn run(cases: Vec<Case>) {
    let dir = tempfile::tempdir().unwrap();
    let mut failed = Vec::new();
    for (name, bench, want) in cases {
        let got = names(dir.path(), &bench, &name);
        eprintln!("{name}: discovered {got:?}, expected {want:?}");
        if got != want {
            failed.push((name, got, want));
        }
    }
    assert!(failed.is_empty(), "not the expected names: {failed:#?}");
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
    run(cases);
}

/// A plant effect at several sizes, and a backlash wider on one side, names the plant effect
/// and nothing on the sensor. Relaxation is asserted from ¾ of its size up: at half its size
/// (Prony fractions 0.02 and 0.025) its evidence on 300 s measured 19.3, 15.5 and under 5 nats
/// on three seeds, below the 20-nat threshold (docs/discovery.md, "Detection limits"); those
/// sizes are checked in `plant_effects_below_detection_name_no_sensor_effect`.
#[test]
fn plant_effects_name_no_sensor_effect() {
    let mut cases = Vec::new();
    for (effect, name, scales) in [
        (Effect::Backlash, "backlash", [0.5, 1.0, 2.0]),
        (Effect::Relaxation, "relaxation", [0.75, 1.0, 2.0]),
    ] {
        for (k, scale) in scales.into_iter().enumerate() {
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
    run(cases);
}

/// Plant effects too small to name (a quarter and half the relaxation, a quarter of the
/// backlash) on Joint A, and both plant effects on Joint C's 3000 s: whatever the plant channel
/// shows, never a sensor name and never a flag on a sensor.
#[test]
fn plant_effects_below_detection_name_no_sensor_effect() {
    let dir = tempfile::tempdir().unwrap();
    let mut cases: Vec<(&str, String, Bench)> = Vec::new();
    for (effect, scale, seed) in [
        (Effect::Relaxation, 0.25, 651),
        (Effect::Relaxation, 0.5, 652),
        (Effect::Backlash, 0.25, 653),
    ] {
        let forms = Forms {
            plant_scale: Some(scale),
            ..Forms::default()
        };
        cases.push((
            "joint-a.toml",
            format!("{}-x{scale}", effect.name()),
            bench(&[(effect, 0)], seed, forms),
        ));
    }
    for (effect, seed) in [(Effect::Backlash, 661), (Effect::Relaxation, 662)] {
        cases.push((
            "joint-c.toml",
            format!("joint-c-{}", effect.name()),
            Bench {
                duration_s: 3000.0,
                ..bench(&[(effect, 0)], seed, Forms::default())
            },
        ));
    }
    let mut failed = Vec::new();
    for (design, name, bench) in cases {
        let report = discover_on(dir.path(), design, &bench, &name);
        let got = pairs(&report);
        let flagged = flagged(&report);
        eprintln!("{name}: discovered {got:?}, unexplained on {flagged:?}");
        let on_sensor =
            got.iter().any(|(_, c)| c != "plant") || flagged.iter().any(|c| c != "plant");
        if on_sensor {
            failed.push((name, got, flagged));
        }
    }
    assert!(failed.is_empty(), "a sensor named or flagged: {failed:?}");
}

/// The channels a report flags `unexplained`.
fn flagged(report: &serde_json::Value) -> Vec<String> {
    report["unexplained"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| u["channel"].as_str().unwrap().to_owned())
        .collect()
}

/// A drift of another form (√t) is `drift`; a rate with a drift is both, and not `creep`.
#[test]
fn drift_is_time_not_history() {
    let sqrt = Forms {
        drift_sqrt: true,
        ..Forms::default()
    };
    run(vec![(
        "drift-sqrt".into(),
        bench(&[(Effect::Drift, 1)], 700, sqrt),
        expect(&[("drift", "sensor1")]),
    )]);
    // A rate with a drift: both named, or (since 2026-11-27, when a rival of the time family
    // under the screen is simulated) `ambiguous` on sensor 1 between the true `drift` and the
    // family rivals its world cannot be told from, with nothing wrong named. Measured: drift
    // 25.9 nats, `creep` 17.0 and `gain_drift` 15.2 under the screen, ambiguous; before, drift
    // and rate named. The issue allows `ambiguous` only between the true name and its
    // calibrated rival, which this asserts. Since the sensitivity rule (later on 2026-11-27)
    // that ambiguity is declined when none of its names beats a sensitivity changing in time
    // (measured: drift 25.9 nats, then flagged `unexplained` on sensor 1, history 100.6): a
    // lost detection, not a wrong name; the declined test must then hold `drift` and only
    // names of its family.
    let dir = tempfile::tempdir().unwrap();
    let bench = bench(
        &[(Effect::Rate, 1), (Effect::Drift, 1)],
        710,
        Forms::default(),
    );
    // The names allowed beside the true `drift`: its family, which a change in time imitates.
    let drift_and_family = |names: &[String]| {
        names.iter().any(|c| c == "drift")
            && names
                .iter()
                .all(|c| ["drift", "creep", "gain_drift"].contains(&c.as_str()))
    };
    let report = discover_json(dir.path(), &bench, "rate-and-drift");
    let got = pairs(&report);
    let want = expect(&[("rate", "sensor1"), ("drift", "sensor1")]);
    eprintln!(
        "rate-and-drift: discovered {got:?}, ambiguous {}",
        report["ambiguous"]
    );
    assert!(got.is_subset(&want), "rate-and-drift: wrong names {got:?}");
    let declined_ambiguity: Vec<String> = report["declined"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["channel"] == "sensor1" && d["time"]["among"].is_array())
        .flat_map(|d| {
            std::iter::once(d["effect"].as_str().unwrap().to_owned()).chain(
                d["time"]["among"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|a| a[0].as_str().unwrap().to_owned()),
            )
        })
        .collect();
    if got.is_empty() && !declined_ambiguity.is_empty() {
        // Declined is no verdict: what it left must be the family a change in time imitates
        // (with 11 blocks, `drift` was refused by the change in time and `gain_drift` and
        // `creep` declined), and sensor 1, and only it, flagged (history, 148.4 nats).
        let family = ["drift", "creep", "gain_drift"];
        assert!(
            declined_ambiguity
                .iter()
                .all(|c| family.contains(&c.as_str())),
            "rate-and-drift: declined among {declined_ambiguity:?}"
        );
        let flags = report["unexplained"].as_array().unwrap();
        assert!(
            !flags.is_empty() && flags.iter().all(|f| f["channel"] == "sensor1"),
            "rate-and-drift: flagged {flags:?}"
        );
    } else if got == expect(&[("drift", "sensor1")]) && !declined_ambiguity.is_empty() {
        // Since the wandering baseline (2026-11-27, docs/discovery.md "A baseline wandering in
        // time"): after the declined ambiguity, the baseline wandering in time is tested and
        // named `drift` (35.0 nats; the held-out gap 1.63° → 1.02°), a right name; the rate
        // is left to the `unexplained` flag on sensor 1 (history, 58.3 nats), as before.
        let flags = report["unexplained"].as_array().unwrap();
        assert!(
            !flags.is_empty() && flags.iter().all(|f| f["channel"] == "sensor1"),
            "rate-and-drift: flagged {flags:?}"
        );
    } else if got != want {
        let ambiguous = report["ambiguous"].as_array().unwrap();
        assert!(
            ambiguous.len() == 1 && ambiguous[0]["channel"] == "sensor1",
            "rate-and-drift: {got:?} and not ambiguous on sensor1: {}",
            report["ambiguous"]
        );
        let contenders = discovery::contenders(&ambiguous[0]);
        assert!(
            drift_and_family(&contenders),
            "rate-and-drift: ambiguous among {contenders:?}"
        );
    }
}

/// A material that creeps with two time constants (the other-forms generator's 3 s and 40 s)
/// is `creep`, written with both; a rate response, a lag as fast as that creep's fast term, is
/// never `creep` (a two-term creep fits it as well as the rate does, by its fast lag, and is
/// named only when its slow lag clears the threshold on its own after the rate). Seed 505's
/// creep was left ambiguous against hysteresis with one time constant; seed 204's rate was
/// named `creep` by a two-term creep without the slow-lag test. The written scenario carries
/// both time constants and simulates. Ignored from calibrated discovery (issue 31), which
/// named seed 505's creep in one term, until 2026-11-28. That day seed 505 was named in two
/// terms only through the retry of a one-term tie with `hysteresis`; once the creep was scored
/// as a Prony series against the loop, it won in one term and was written with one (the
/// second read 10.2 nats, under the threshold). A second time constant under the threshold is
/// now named when it beats copies of the one-term model (`StageSearch::second_time_constant`).
#[test]
fn a_creep_of_two_time_constants_is_creep_and_a_rate_is_not() {
    let dir = tempfile::tempdir().unwrap();
    for (name, effect, seed, want) in [
        ("creep-505", Effect::Creep, 505, "creep"),
        ("rate-204", Effect::Rate, 204, "rate"),
    ] {
        let report = discover_json(
            dir.path(),
            &bench(&[(effect, 1)], seed, Forms::default()),
            name,
        );
        assert_eq!(pairs(&report), expect(&[(want, "sensor1")]), "{name}");
        if effect != Effect::Creep {
            continue;
        }
        // The generator's terms: fractions 0.05 (3 s) and 0.06 (40 s) of the change.
        let p = &report["discovered"][0]["parameters"];
        let [(fast_fraction, fast_tau), (fraction, tau)] = other_forms::CREEP;
        let got = |key: &str| p[key].as_f64().unwrap();
        assert!(
            (got("tau_s") / tau).ln().abs() < 2f64.ln()
                && (got("fast_tau_s") / fast_tau).ln().abs() < 3f64.ln(),
            "{name}: {p}"
        );
        for (key, truth) in [("fraction", fraction), ("fast_fraction", fast_fraction)] {
            assert!((got(key) / truth - 1.0).abs() < 0.3, "{name}: {key} in {p}");
        }
        let scenario = dir.path().join(format!("{name}-out/scenario.toml"));
        let text = std::fs::read_to_string(&scenario).unwrap();
        assert!(text.contains("fast_tau_s"), "{text}");
        let out = dir.path().join(format!("{name}-resimulated"));
        common::dlw_ok(&[
            "simulate".as_ref(),
            "--design".as_ref(),
            shipped_design("joint-a.toml").as_ref(),
            "--scenario".as_ref(),
            scenario.as_os_str(),
            "--protocol".as_ref(),
            "random".as_ref(),
            "--duration-s".as_ref(),
            "20".as_ref(),
            "-o".as_ref(),
            out.as_os_str(),
        ]);
    }
}

/// The seven library effects: an out-of-library case must never be named as one of them.
const LIBRARY: [&str; 7] = [
    "hysteresis",
    "saturation",
    "rate",
    "creep",
    "drift",
    "relaxation",
    "backlash",
];

/// Effects outside the library ([`Outside`]: a sensitivity that fades settling, in a step, by
/// cycles or with a temperature-like sinusoid; a sensor that stiffens, has a dead zone, a
/// quadratic term or an offset above a strain) on Joint A's sensor and on each of Joint C's
/// two sensors. Never one of the seven library names, never a name or a flag on another
/// channel; the right channel flagged `unexplained`, or a change of sensitivity named
/// `gain_drift`, in at least 80 % of the cases. One seed per case, Joint C on every other case
/// (its sensors taking turns); three seeds on every case and both of Joint C's sensors with
/// `DLW_DISCOVER_FULL=1`.
#[test]
fn effects_outside_the_library_are_flagged_not_named() {
    let dir = tempfile::tempdir().unwrap();
    let seeds: u64 = if std::env::var("DLW_DISCOVER_FULL").is_ok() {
        3
    } else {
        1
    };
    let mut cases: Vec<(&str, usize, Outside, u64)> = Vec::new();
    for seed in 0..seeds {
        for (i, outside) in Outside::ALL.into_iter().enumerate() {
            cases.push(("joint-a.toml", 1, outside, 800 + 10 * seed + i as u64));
            // Joint C's two sensors take turns on every other case (on every case, both
            // sensors, in the full run): its 3000 s runs cost about six of Joint A's.
            for sensor in [1, 2] {
                if seeds > 1 || (i % 2 == 0 && (i / 2 + sensor) % 2 == 0) {
                    cases.push(("joint-c.toml", sensor, outside, 900 + 10 * seed + i as u64));
                }
            }
        }
    }
    let (mut right, mut wrong, mut missed) = (0, Vec::new(), Vec::new());
    let total = cases.len();
    for (design, sensor, outside, seed) in cases {
        let joint_c = design == "joint-c.toml";
        let bench = Bench {
            duration_s: if joint_c { 3000.0 } else { DURATION_S },
            ..bench(
                &[],
                seed,
                Forms {
                    outside: Some(outside),
                    outside_sensor: sensor,
                    ..Forms::default()
                },
            )
        };
        let name = format!("{}-{outside:?}-sensor{sensor}-{seed}", &design[..7]);
        let report = discover_on(dir.path(), design, &bench, &name);
        let named = pairs(&report);
        let flagged = flagged(&report);
        eprintln!("{name}: named {named:?}, unexplained on {flagged:?}");
        let channel = format!("sensor{sensor}");
        let gain_change = matches!(
            outside,
            Outside::GainFade | Outside::GainStep | Outside::GainCycles | Outside::GainSine
        );
        let is_wrong = |(effect, ch): &(String, String)| {
            LIBRARY.contains(&effect.as_str()) || *ch != channel || !gain_change
        };
        if named.iter().any(is_wrong) || flagged.iter().any(|c| *c != channel) {
            wrong.push((name, named, flagged));
        } else if named.is_empty() && flagged.is_empty() {
            missed.push(name);
        } else {
            right += 1;
        }
    }
    eprintln!("out of library: {right}/{total} flagged or named gain_drift on the right channel, wrong {}, missed {missed:?}", wrong.len());
    assert!(wrong.is_empty(), "wrong names or channels: {wrong:#?}");
    assert!(
        right * 5 >= total * 4,
        "{right} of {total} flagged; missed {missed:?}"
    );
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
    let report = discovery::discover_json(&design, &rec, &out);
    assert_eq!(
        pairs(&report),
        expect(&[("gain_drift", "sensor1")]),
        "{report}"
    );
    let fade = report["discovered"][0]["parameters"]["fade_per_hour"]
        .as_f64()
        .unwrap();
    assert!((fade - 2.0).abs() < 0.5, "fade_per_hour {fade}");
    let written = std::fs::read_to_string(out.join("scenario.toml")).unwrap();
    assert!(written.contains("[sensor1.gain_drift]"), "{written}");
}
