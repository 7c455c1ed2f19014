//! `dlw discover` on the third generator (`tests/common/third_generator.rs`, issue 31): forms
//! neither the simulator nor the other generators have (a relaxation and a creep with a spread
//! of time constants, Preisach hysteresis, a saturation that is not odd, a random-walk drift,
//! a random-walk gain and a gain cycling at a random period), at sizes ×0.5 to ×8, with
//! coloured noise (white + four AR(1) terms, 0.2-12.8 s), on a UAN joint (A, 300 s) and a BSN
//! joint (C, 3000 s).
//!
//! Asserted in CI: no wrong name; `ambiguous` only on the right channel with the true name among
//! the contenders; the plant's relaxation never names or flags a sensor; clean recordings named
//! or flagged in ≤ 1 % (`discover_names_nothing_wrong_on_the_third_generator`); and the issue's
//! detection figures above each effect's MEASURED detection size, [`DETECTION`]: the right
//! effect first on the right channel in ≥ 95 %, the gains flagged or named `gain_drift` in
//! ≥ 80 % (`discover_meets_the_detection_figures_on_the_third_generator`). The two tests share
//! one run of the cases. Most effects have no detection size up to ×8 (docs/discovery.md,
//! "Detection against size"). CI runs Joint A's effects at ×1 and at ×2 or their detection size,
//! and three of Joint C's; `DLW_DISCOVER_FULL=1 cargo test --release --test
//! discover_third_generator -- --nocapture` runs three seeds of every effect at ×0.5, ×1, ×2 on
//! both joints and at ×4 and ×8 where physical, with their clean twins and more controls, 100
//! clean recordings per joint. There, a name on a channel the effect is not on that the clean
//! twin (same seed: the same noise, stroke pattern and sensors, no effect) gives too is the
//! noise's, not the effect's: it is listed apart and counted once, as the twin's, against the
//! clean rate. One such name is known: the plant relaxation ×4 of seed 15003 and its clean
//! twin both name `drift` on sensor 2, whose residual wanders most over 120 s of 38 clean
//! Joint C recordings measured (docs/discovery.md, "A false name from the noise, traced"). The
//! ignored `measure_detection` is the measurement behind [`DETECTION`] and the clean controls'
//! rate (its docs give the command).

mod common;
use common::discovery::{judge, try_discover_json, Judgement, Truth};
use common::shipped_design;
use common::third_generator::{self, Bench, Effect, Size};

use rayon::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// The detection size per effect (a multiple of the generator's constants), on Joint A and on
/// Joint C: the smallest size measured from which every larger size measured was right on
/// every seed (the right effect named first on the right channel, no wrong name; a gain flagged
/// or named `gain_drift` there), measured in release by `measure_detection`: Joint A on
/// 2026-11-27 after the hinges, a change in time as the richer form of `drift` and
/// `gain_drift`, and the one-nat rival screen (seeds 1-12 at ×0.5, ×1, ×2, ×4, ×8 on sensor
/// 1); Joint C on 2026-11-27 (seeds 1-3 on sensor 2 at ×0.5, ×1, ×2, and at ×4, ×8 where
/// physical, on sensor 1 at ×0.5-×2, and seeds 4-6 of the relaxation and the creep at
/// ×0.5-×2; the creep and the hysteresis again after the change, seeds 1-3 on sensor 2;
/// docs/discovery.md, "Detection against size"), and its drift, saturation and cycling gain at
/// ×4 and ×8 on 2026-11-28 (seeds 1-12 on sensor 2, 1-6 on sensor 1; the drift's size is the
/// one exception to the rule, its comment says why). `INFINITY`: not right on every seed at
/// any size up to the largest measured, so nothing is asserted (the shares are in the docs).
/// Above it the 95 % (80 % for the gains) is asserted on the CI cases.
const DETECTION: [(Effect, f64, f64); 7] = [
    // Joint A: 12/12 at ×1 to ×8, 11/12 at ×0.5, since the relaxation's spread form
    // (2026-11-27; before it seed 3 was never named, flagged `unexplained` on plant, 11/12).
    // Joint C: 3/3 at each size after it too.
    // Joint C: right at every size from ×0.5 to ×8 (seeds 1-3; seeds 4-6 at ×0.5-×2 too).
    (Effect::Relaxation, 1.0, 0.5),
    // Joint A: 9/12 at ×2 (11/12 with 10 blocks), 11/12 at ×4, 10/12 at ×8, none wrong.
    // Joint C: at ×2 9/9 (seeds 1-6 on sensor 2, 1-3 on sensor 1; ×2.5 is the largest
    // physical size there); at ×1 8/9 (seed 6 on sensor 2 flagged, not named).
    (Effect::Creep, f64::INFINITY, 2.0),
    // Joint A: 12/12 at ×2, ×4 and ×8 (11/12 at ×2 before the hinges). Joint C: 2/3 at ×2 on
    // sensor 2 (3/3 on sensor 1), ×2 the largest physical size.
    (Effect::Hysteresis, 2.0, f64::INFINITY),
    // Joint A: 12/12 at ×1 to ×8 (at ×4 one wrong `ambiguous` before the hinges). Joint C:
    // sensor 2 2/3 at ×1, 1/3 at ×2, 0/3 at ×4 and ×8 (with 11 blocks 0/3 at ×0.5-×2; with
    // blocks no longer than half a knot 0/3, 0/3, 1/3; 2026-11-28, seeds 1-12, 0/12 at ×4 and
    // at ×8: the stronger the saturation, the flatter the compression sensor's response and
    // the less of it a line does not fit); sensor 1 (seeds 1-6) 5/6 at ×4, 0/6 at ×8, flagged
    // `unexplained` (a curve).
    (Effect::Saturation, 1.0, f64::INFINITY),
    // Joint A: 1/12 at ×0.5, 4/12 at ×1, 5/12 at ×2 and ×4, 6/12 at ×8 since the wandering
    // baseline (2026-11-27; before it 1/12 at ×0.5 to ×4, 2/12 at ×8); 7/12 at ×16 and 6/12 at
    // ×32 (2026-11-28): no size is large enough, as the walk also runs through the rest the
    // noise model is frozen from. Joint C: 0/3, 0/3, 2/3 at ×0.5-×2 with blocks no longer than
    // half a knot (1/3 at ×2 before); from ×4 (2026-11-28, seeds 1-12) 24/24 on sensor 2 and
    // (seeds 1-6) 11/12 on sensor 1, whose ×8 of seed 1 is flagged `unexplained`: 35 of 36,
    // 97 %, the size from which the 95 % holds (not every seed, as for the others).
    (Effect::Drift, f64::INFINITY, 4.0),
    // Joint A: 10/12 at ×2 and ×4, the largest physical size (9/12 with 10 blocks). Joint C:
    // 0/18 at ×0.5-×2 until its blocks were no longer than half a knot, then 0/6, 2/6, 4/6
    // (seeds 1-6; ×1 is its largest physical size).
    (Effect::GainWalk, f64::INFINITY, f64::INFINITY),
    // Joint A: 12/12 at ×2, ×4 and ×8 (on the way, seed 2 was named `hysteresis` after its
    // `gain_drift` at ×2 and ×4, until the change-in-time rule and the one-nat rival screen).
    // At ×8 it failed on seed 3 before the range check (its `gain_drift`'s fade, 26.9 /h, out
    // of the scenario's range; now declined and flagged). Joint C: 0/3 at ×0.5-×4 until its
    // held-out blocks were 273 s long; with blocks no longer than half a knot (2026-11-28)
    // 6/6 at ×1 and ×2 (seeds 1-6), 3/3 at ×4 (6/6 later that day), 0/6 at ×0.5.
    (Effect::GainCycle, 2.0, 1.0),
];

/// The detection size of `e` on `design` ([`DETECTION`]).
fn detection(design: &str, e: Effect) -> f64 {
    DETECTION
        .iter()
        .find(|(x, ..)| *x == e)
        .map_or(f64::INFINITY, |d| {
            if design == "joint-c.toml" {
                d.2
            } else {
                d.1
            }
        })
}

/// One recording.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Case {
    design: &'static str,
    effect: Option<(Effect, Size, usize)>,
    seed: u64,
}

impl Case {
    fn duration_s(&self) -> f64 {
        if self.design == "joint-c.toml" {
            3000.0
        } else {
            300.0
        }
    }

    fn name(&self) -> String {
        format!(
            "{}-{}-{}",
            self.design.trim_end_matches(".toml"),
            self.effect.map_or("clean".to_owned(), |(e, s, k)| format!(
                "{}-x{}-s{k}",
                e.tag(),
                s.0
            )),
            self.seed
        )
    }

    fn channel(&self) -> Option<String> {
        self.effect.map(|(e, _, k)| {
            if e.is_plant() {
                "plant".to_owned()
            } else {
                format!("sensor{k}")
            }
        })
    }

    fn truth(&self) -> Truth {
        match (self.effect, self.channel()) {
            (Some((e, ..)), Some(channel)) => match e.name() {
                Some(name) => Truth::Library {
                    effect: name.to_owned(),
                    channel,
                },
                None => Truth::OutsideGain { channel },
            },
            _ => Truth::Clean,
        }
    }

    fn twin(&self) -> Case {
        Case {
            effect: None,
            ..*self
        }
    }
}

fn run(dir: &Path, case: &Case) -> serde_json::Value {
    try_run(dir, case).unwrap_or_else(|e| panic!("discover {} failed: {e}", case.name()))
}

/// The report of `dlw discover --json` on `case`, or its error message when it fails.
fn try_run(dir: &Path, case: &Case) -> Result<serde_json::Value, String> {
    let design = shipped_design(case.design);
    let rec = dir.join(case.name());
    let bench = Bench {
        effect: case.effect,
        duration_s: case.duration_s(),
        seed: case.seed,
    };
    third_generator::write_recording(Path::new(&design), &bench, &rec);
    let json = try_discover_json(&design, &rec, &dir.join(format!("{}-out", case.name())));
    // The recordings are large (Joint C: 1.5 M rows); only the result is kept.
    let _ = std::fs::remove_dir_all(&rec);
    json
}

/// One case's run: the case, its judgement, what the report said, and what it named.
type Outcome = (Case, Judgement, String, Vec<(String, String)>);

/// What one run of the cases found.
struct Summary {
    wrong: Vec<(String, String)>,
    /// Names on a channel without the effect that the clean twin gives too (full size only).
    noise_names: Vec<(String, String)>,
    alarms: Vec<String>,
    clean: usize,
    library: usize,
    library_right: usize,
    gains: usize,
    gains_right: usize,
}

/// The cases run once for both tests (they run in parallel threads of one binary).
fn summary() -> &'static Summary {
    static SUMMARY: OnceLock<Summary> = OnceLock::new();
    SUMMARY.get_or_init(run_cases)
}

/// CI: no wrong name, `ambiguous` only with the true name on its channel, a plant effect never
/// on a sensor (but for a name its clean twin gives too, counted as the twin's), clean
/// recordings within the stated rate (issue 31).
#[test]
fn discover_names_nothing_wrong_on_the_third_generator() {
    let s = summary();
    assert!(s.wrong.is_empty(), "wrong names or flags: {:#?}", s.wrong);
    assert!(
        s.alarms.len() * 100 <= s.clean,
        "clean recordings named or flagged: {:?} of {} (and on their effect cases: {:?})",
        s.alarms,
        s.clean,
        s.noise_names
    );
}

/// The detection figures above the measured detection sizes ([`DETECTION`]): the right
/// effect on the right channel in ≥ 95 % of the library cases at or above them, the gains
/// flagged or named `gain_drift` in ≥ 80 %. Fails when a case at or above its size is missed.
/// Of the gains only Joint A's cycling gain has a detection size (×2, since 2026-11-27).
#[test]
fn discover_meets_the_detection_figures_on_the_third_generator() {
    let s = summary();
    assert!(s.wrong.is_empty(), "wrong names or flags: {:#?}", s.wrong);
    assert!(
        s.library > 0,
        "no library case at or above its detection size"
    );
    let gain_sizes = DETECTION
        .iter()
        .filter(|d| d.0.name().is_none() && (d.1.is_finite() || d.2.is_finite()));
    assert!(
        s.gains > 0 || gain_sizes.count() == 0,
        "no gain case at or above its detection size"
    );
    assert!(
        s.library_right as f64 >= 0.95 * s.library as f64,
        "{} of {} library effects at or above their detection size named right",
        s.library_right,
        s.library
    );
    assert!(
        s.gains_right * 5 >= s.gains * 4,
        "{} of {} gains at or above their detection size flagged or named gain_drift",
        s.gains_right,
        s.gains
    );
}

/// Two wrong names found by the detection measurement in docs/discovery.md (Joint A, seeds of
/// that measurement), not in the CI cases: a random-walk drift at ×0.5 (seed 1) named
/// `gain_drift` (24.7 nats, `drift` 17.7, under the screen and so never simulated as the rival
/// that could produce what was seen), and a cycling gain at ×0.5 (seed 5) named `creep` (26.6
/// nats; at ×1 left ambiguous between `creep` and `drift`, at ×2 `creep` again). Found
/// 2026-11-27; fixed by the copies' slow wander, the family's rivals under the screen and the
/// test against a change in time (docs/discovery.md, "A wandering baseline or gain"): the drift
/// is now left `ambiguous` between `gain_drift`, `drift` and `creep`, the cycling gain declined
/// and flagged `unexplained`. Fails on the code before (both names given).
#[test]
fn a_wandering_baseline_or_gain_is_never_named_another_effect() {
    let dir = tempfile::tempdir().unwrap();
    for (effect, seed) in [(Effect::Drift, 1), (Effect::GainCycle, 5)] {
        let case = Case {
            design: "joint-a.toml",
            effect: Some((effect, Size(0.5), 1)),
            seed,
        };
        let json = run(dir.path(), &case);
        let j = judge(&json, &case.truth());
        assert!(j.wrong.is_empty(), "{}: {:?}", case.name(), j.wrong);
    }
}

/// The wrong names the detection measurement of 2026-11-27 found on Joint A (docs/discovery.md,
/// "Detection against size"), seeds of that measurement, none in the CI cases, that are now
/// fixed: a creep with a spread of time constants named `hysteresis` at ×1 (seed 12), ×4 and
/// ×8 (seed 3), and named right and then followed by `drift` (×4) and by `drift` and `rate`
/// (×8, seed 10). Fixed 2026-11-27 by a creep's richer form (a Prony series, `Term::flexible`)
/// that a later name must beat and that a rival is simulated in, and by rivals under the
/// screen simulated for every name (docs/discovery.md, "A creep of many time constants"). On
/// the code before, all five are wrong.
#[test]
fn a_creep_of_many_time_constants_gets_no_wrong_name() {
    let dir = tempfile::tempdir().unwrap();
    let found = [
        (Effect::Creep, 1.0, 12),
        (Effect::Creep, 4.0, 3),
        (Effect::Creep, 8.0, 3),
        (Effect::Creep, 4.0, 10),
        (Effect::Creep, 8.0, 10),
    ];
    let wrong = wrong_names(dir.path(), &found);
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// A saturation that is not odd, at ×4 (seed 2): named right, then its channel was left
/// `ambiguous` between `gain_drift`, `drift` and `hysteresis`, a wrong verdict, found by the
/// detection measurement of 2026-11-27. The hysteresis's test against the gain drift read
/// −3907 nats: the memoryless curve of any shape was drawn with hats, which share the offset
/// and lose it where a held-out block's strain leaves the training blocks' range. With hinges
/// (`terms::hinges`) the `gain_drift` is declined (it does not beat the null over the
/// saturation's richer form) and the channel is flagged `unexplained` (curve), which is what
/// a saturation the library's tanh does not draw is. Fails on the code before.
#[test]
fn a_saturation_that_is_not_odd_gets_no_wrong_name_after_it() {
    let dir = tempfile::tempdir().unwrap();
    let wrong = wrong_names(dir.path(), &[(Effect::Saturation, 4.0, 2)]);
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// A gain cycling in time at ×2 and ×4 (seed 2): named `gain_drift`, then `hysteresis` beside
/// it, a wrong name, once the memoryless curve was drawn with hinges (the hats' step had hidden
/// the plays' evidence). The `gain_drift` had passed its test against a change in time on
/// rounding (0.0004 nats against a bound of 0.00007 at ×2): with the rival screen at one nat it
/// is refused (a change in time after it: 67.6 nats at ×2, 564.9 at ×4) and the channel is
/// flagged `unexplained` (time). In between, the rule that a candidate after a `gain_drift`
/// must beat the null over a change in time of any smooth form had declined the ×4's
/// hysteresis (−144.1 nats over the spline); on the final code the screen decides both sizes
/// first, so this test does not exercise that rule. Fails on the code before the screen.
#[test]
fn a_cycling_gain_named_gain_drift_gets_no_hysteresis_after_it() {
    let dir = tempfile::tempdir().unwrap();
    let wrong = wrong_names(
        dir.path(),
        &[(Effect::GainCycle, 4.0, 2), (Effect::GainCycle, 2.0, 2)],
    );
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// A wrong name of the detection measurement (2026-11-27): the cycling gain ×0.5 of seed 9
/// (under its detection size) was left `ambiguous` between `drift` and `creep`, neither its
/// name. Neither beats a sensitivity changing in time of any smooth form (the time spline times
/// the input: drift −78.0 nats over it; creep 2.9 nats, its world's bound 8.4), so the
/// ambiguity is now declined and the channel flagged `unexplained` (time). Fails on the code
/// before (the ambiguity).
#[test]
fn a_gain_left_ambiguous_between_drift_and_creep_is_flagged_instead() {
    let dir = tempfile::tempdir().unwrap();
    let wrong = wrong_names(dir.path(), &[(Effect::GainCycle, 0.5, 9)]);
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// The wrong names of the detection measurement that the 10-block split gave:
/// - the random-walk gain ×0.5 of seed 9 was left `ambiguous` between `drift` (33.3 nats) and
///   `creep` (20.7): the drift beat the sensitivity spline there;
/// - the cycling gain ×1 of seed 2 was named `gain_drift` and then left `ambiguous` between
///   `hysteresis` (22.2 nats) and `creep` (7.2).
///
/// Both went through the time spline, which ran into the last block, held out, and extrapolated
/// its curvature there: for the cycling gain it lost 16.4 nats in that block alone while
/// gaining in every other held-out block. Holding it flat past the last training sample fixed
/// both but gave the cycling gain ×2 of the same seed a `hysteresis` after its `gain_drift`, so
/// that case is here too. With 11 blocks (the last trains) the first is flagged `unexplained`,
/// the second named `gain_drift` alone, the third flagged (docs/discovery.md, "11 blocks, with
/// the relaxation's spread"). Fails with 10 blocks (the first two).
#[test]
fn the_last_held_out_blocks_wrong_names_are_not_given() {
    let dir = tempfile::tempdir().unwrap();
    let found = [
        (Effect::GainWalk, 0.5, 9),
        (Effect::GainCycle, 1.0, 2),
        (Effect::GainCycle, 2.0, 2),
    ];
    let wrong = wrong_names(dir.path(), &found);
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// That `json` names `case`'s true effect on its true channel and nothing wrong.
fn assert_right(json: &serde_json::Value, case: &Case) {
    let j = judge(json, &case.truth());
    assert!(
        j.right && j.wrong.is_empty(),
        "{}: {}",
        case.name(),
        said(json)
    );
}

/// `case` written by the third generator into `dir` and discovered there, asserted right (the
/// true name on the true channel, nothing wrong): the report, the recording and the output
/// folder.
fn discovered_right(
    dir: &Path,
    design_path: &str,
    case: &Case,
) -> (serde_json::Value, std::path::PathBuf, std::path::PathBuf) {
    let rec = dir.join(case.name());
    let bench = Bench {
        effect: case.effect,
        duration_s: case.duration_s(),
        seed: case.seed,
    };
    third_generator::write_recording(Path::new(design_path), &bench, &rec);
    let out = dir.join(format!("{}-out", case.name()));
    let json = try_discover_json(design_path, &rec, &out).unwrap();
    assert_right(&json, case);
    (json, rec, out)
}

/// That the report of `case` leaves nothing `ambiguous`.
fn assert_nothing_ambiguous(json: &serde_json::Value, case: &Case) {
    assert!(
        json["ambiguous"].as_array().unwrap().is_empty(),
        "{}: {}",
        case.name(),
        json["ambiguous"]
    );
}

/// The wrong names `dlw discover` gives on Joint A's sensor 1 for each `(effect, size, seed)`.
fn wrong_names(dir: &Path, found: &[(Effect, f64, u64)]) -> Vec<(String, Vec<String>)> {
    found
        .par_iter()
        .map(|&(effect, size, seed)| {
            let case = Case {
                design: "joint-a.toml",
                effect: Some((effect, Size(size), 1)),
                seed,
            };
            let j = judge(&run(dir, &case), &case.truth());
            (case.name(), j.wrong)
        })
        .filter(|(_, w)| !w.is_empty())
        .collect()
}

/// A random-walk drift (Joint A, seed 1, ×2 and ×8): the library's linear `drift` reads 25.3 and
/// 22.7 nats, under its copies, and the channel was flagged `unexplained` (time) with no name at
/// every size from ×1 (the detection measurement of 2026-11-27: drift right in 1/12 at ×0.5 to
/// ×4). It is now named `drift` in its wandering form (`Term::Wander`, src/discover/wander.rs):
/// a baseline spline in time beats copies of the model without it, beats what the input's
/// structure (a curve, memory, history) explains, leads a sensitivity wandering in time by more
/// than copies of that world reach, and a wandering sensitivity adds nothing after it. Checked
/// the way a user meets it: the held-out gap falls by more than half, and the scenario's drift
/// has a random walk within a factor of three of the generator's (75 Ω/√s at ×1,
/// tests/common/third_generator.rs). Fails on the code before (not named).
#[test]
fn a_random_walk_drift_is_named_drift_and_its_scenario_wanders() {
    let dir = tempfile::tempdir().unwrap();
    let design_path = shipped_design("joint-a.toml");
    for size in [2.0, 8.0] {
        let case = Case {
            design: "joint-a.toml",
            effect: Some((Effect::Drift, Size(size), 1)),
            seed: 1,
        };
        let (json, _, out) = discovered_right(dir.path(), &design_path, &case);
        let named = &json["discovered"][0];
        assert_eq!(named["effect"], "drift", "{}", case.name());
        assert_eq!(named["calibration"]["passed"], true, "{}", case.name());
        let time = &named["time"];
        assert_eq!(time["rival"], "sensitivity", "{}: {time}", case.name());
        assert_eq!(time["lead"], true, "{}: {time}", case.name());
        assert_eq!(time["verdict"], "named", "{}: {time}", case.name());
        let gap = json["gaps"]
            .as_array()
            .unwrap()
            .iter()
            .find(|g| g["channel"] == "sensor1")
            .unwrap();
        let (before, after) = (
            gap["before"].as_f64().unwrap(),
            gap["after"].as_f64().unwrap(),
        );
        assert!(
            after < 0.5 * before,
            "{}: gap {before} → {after}",
            case.name()
        );
        let text = std::fs::read_to_string(out.join("scenario.toml")).unwrap();
        let scenario: dlw::sim::Scenario = toml::from_str(&text).unwrap();
        let drift = &scenario.sensor1.drift;
        let walk = drift.random_walk_ohm_per_sqrt_s.unwrap_or(0.0);
        let truth = 75.0 * size;
        eprintln!(
            "{}: gap {before:.1} → {after:.1} Ω, random walk {walk:.1} Ω/√s (generator {truth})",
            case.name()
        );
        assert!(drift.enabled, "{}: {drift:?}", case.name());
        assert!(
            (truth / 3.0..truth * 3.0).contains(&walk),
            "{}: random walk {walk} against {truth}",
            case.name()
        );
    }
}

/// A random-walk drift whose wander a slow lag and a loop each drew part of: the full-size
/// run's two wrong verdicts (the ×2 of seed 10142, `ambiguous` between `creep` 25.3 and
/// `hysteresis` 22.5; the ×1 of seed 10241, `creep` 40.4 and `hysteresis` 29.5), neither the
/// truth. An ambiguity with a name a change in time imitates now stands only when one of its
/// contenders shows what a change in time cannot produce (src/discover/decide.rs); here none
/// does, the ambiguity is declined with that test, and the wandering baseline is named
/// `drift`. Fails on the code before (both `ambiguous`). Since the creep is scored as a Prony
/// series against a loop (2026-11-28), the ×2 of 10142 is no longer a tie: `creep` leads the
/// `hysteresis` and is itself refused by the change in time (the creep after the spline 3.5
/// nats, bound 26.4; the spline after the creep 27.3, bound 18.1). Either way the name a change
/// in time explains is declined with that test, and `drift` is named.
#[test]
fn a_random_walk_drift_is_not_left_ambiguous_between_two_other_names() {
    let dir = tempfile::tempdir().unwrap();
    let design_path = shipped_design("joint-a.toml");
    for (size, seed) in [(2.0, 10_142), (1.0, 10_241)] {
        let case = Case {
            design: "joint-a.toml",
            effect: Some((Effect::Drift, Size(size), 1)),
            seed,
        };
        let (json, ..) = discovered_right(dir.path(), &design_path, &case);
        let declined = json["declined"].as_array().unwrap();
        assert!(
            declined.iter().any(|d| d["time"]["rival"] == "time"
                && (d["time"]["verdict"] == "rival"
                    || (d["time"]["verdict"] == "neither"
                        && !d["time"]["among"].as_array().map_or(true, Vec::is_empty)))),
            "{}: declined {declined:?}",
            case.name()
        );
        assert_nothing_ambiguous(&json, &case);
    }
}

/// A named effect's misfit is not named a wandering `drift` after it (2026-11-27): a Preisach
/// hysteresis at ×8 (Joint A, seed 1), named `hysteresis` and then `drift` (28.3 nats) by the
/// first version of the wandering baseline, because the loop's misfit follows the input's slow
/// history and a spline in time fitted some of it; fixed by the test over the input's structure
/// (5.9 nats against copies reaching 14.9). And a creep of six time constants at ×8 (seed
/// 10214, found by the five-seed run), named `creep` and then `drift` (22.6 nats; 30.6 over
/// the input's structure, bound 6.5): fixed by putting the named creep's richer form (a Prony
/// series, `Term::flexible`) in that structure, as every later name must beat it. Both stay
/// flagged `unexplained`. Each fails without its fix.
#[test]
fn a_named_effects_misfit_is_not_named_a_wandering_drift() {
    let dir = tempfile::tempdir().unwrap();
    let wrong = wrong_names(
        dir.path(),
        &[(Effect::Hysteresis, 8.0, 1), (Effect::Creep, 8.0, 10214)],
    );
    assert!(wrong.is_empty(), "wrong names: {wrong:#?}");
}

/// A creep of six time constants (2 s to 200 s) on Joint A, seed 3, at ×2, ×4 and ×8 was left
/// `ambiguous` with the `hysteresis` its lags draw on a cycling strain (×4: `hysteresis` 32.8
/// nats, `creep` 27.2). Against a curve or a loop the creep was already simulated as a Prony
/// series, but scored in its one- and two-term forms: after the loop it read −6.8 nats, and
/// neither name was excluded. Scored as the Prony series it is simulated as, it now shows what
/// the loop cannot produce, and `creep` is named (src/discover/decide.rs, `rival`). At ×8 its
/// one-term form read 17.5 nats, under the screen: a rival under the screen, it excluded the
/// `hysteresis` and was never tried as a name itself; it now is, when it excludes every
/// credible candidate, and its calibration says so (the rivals' one-nat screen, passed), with
/// the test that excluded the loop among its rivals. Fails on the code before (each
/// `ambiguous`).
#[test]
fn a_creep_of_many_time_constants_is_told_from_the_loop_its_lags_draw() {
    let dir = tempfile::tempdir().unwrap();
    let design_path = shipped_design("joint-a.toml");
    let cases: Vec<Case> = [2.0, 4.0, 8.0]
        .into_iter()
        .map(|size| Case {
            design: "joint-a.toml",
            effect: Some((Effect::Creep, Size(size), 1)),
            seed: 3,
        })
        .collect();
    let results: Vec<serde_json::Value> = cases
        .par_iter()
        .map(|case| discovered_right(dir.path(), &design_path, case).0)
        .collect();
    for (case, json) in cases.iter().zip(&results) {
        let named = json["discovered"].as_array().unwrap();
        let creep = named
            .iter()
            .find(|d| d["effect"] == "creep" && d["channel"] == "sensor1")
            .unwrap_or_else(|| panic!("{}: named {named:?}", case.name()));
        let calibration = &creep["calibration"];
        assert_eq!(
            calibration["passed"],
            true,
            "{}: {calibration}",
            case.name()
        );
        // The report says why the loop is not the name: its world cannot produce the creep.
        let rivals = creep["rivals"].as_array().unwrap();
        assert!(
            rivals
                .iter()
                .any(|r| r["rival"] == "hysteresis" && r["verdict"] == "named"),
            "{}: rivals {rivals:?}",
            case.name()
        );
        assert_nothing_ambiguous(json, case);
    }
}

/// A relaxation with a spread of time constants (the generator's eight Prony terms, 0.3 s to
/// 300 s) on Joint A, seed 3, at ×1 and ×4: the library's one time constant fitted it poorly
/// (13.9 nats at ×4, under the screen) and the plant was flagged `unexplained` at every size
/// from ×1 instead (456 nats at ×4). It is now named in its spread form
/// (`Term::RelaxationSpread`), and the scenario `discover` writes holds that Prony series: the
/// simulator's plant, run on the recording's stroke with it, follows the measured angle closer
/// than the same plant without it, by more than half at ×4. Fails on the code before (not
/// named; no series in the scenario).
#[test]
fn a_relaxation_with_a_spread_of_time_constants_is_named_and_simulated() {
    let dir = tempfile::tempdir().unwrap();
    let design_path = shipped_design("joint-a.toml");
    let joint = dlw::design::Design::load(Path::new(&design_path))
        .unwrap()
        .joint;
    for size in [1.0, 4.0] {
        let case = Case {
            design: "joint-a.toml",
            effect: Some((Effect::Relaxation, Size(size), 1)),
            seed: 3,
        };
        let (json, rec, out) = discovered_right(dir.path(), &design_path, &case);
        // The bootstrap scores the spread as the search does (its signs too): the evidence it
        // calibrates is the evidence named. It read 1056.6 against 728.4 at ×4 when the
        // copies' solver left the signs free.
        let named = &json["discovered"][0];
        let (evidence, observed) = (
            named["evidence"].as_f64().unwrap(),
            named["calibration"]["observed"].as_f64().unwrap(),
        );
        assert!(
            (evidence - observed).abs() <= 1e-6 * evidence.abs().max(1.0),
            "{}: named at {evidence}, calibrated at {observed}",
            case.name()
        );
        let text = std::fs::read_to_string(out.join("scenario.toml")).unwrap();
        let scenario: dlw::sim::Scenario = toml::from_str(&text).unwrap();
        let relaxation = &scenario.plant.relaxation;
        assert!(
            relaxation.enabled && relaxation.terms.len() > 1,
            "{}: {relaxation:?}",
            case.name()
        );
        let csv = std::fs::read_to_string(rec.join("data.csv")).unwrap();
        let rows: Vec<(f64, f64)> = csv
            .lines()
            .skip(1)
            .map(|l| {
                let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                (v[1], v[2])
            })
            .collect();
        let misfit = |plant: &dlw::sim::PlantParams| {
            let mut p = dlw::sim::Plant::new(plant, &joint, 1.0 / scenario.sample_hz);
            let ss: f64 = rows
                .iter()
                .map(|&(stroke, angle)| (p.step(stroke).to_degrees() - angle).powi(2))
                .sum();
            (ss / rows.len() as f64).sqrt()
        };
        let with = misfit(&scenario.plant);
        let mut without = scenario.plant.clone();
        without.relaxation.enabled = false;
        let without = misfit(&without);
        eprintln!(
            "{}: angle misfit {without:.4}° without the relaxation, {with:.4}° with it",
            case.name()
        );
        assert!(with < without, "{}: {with} ≥ {without}", case.name());
        if size >= 4.0 {
            assert!(with < 0.5 * without, "{}: {with} vs {without}", case.name());
        }
    }
}

/// A cycling gain at ×8 (amplitude 0.4, a physical size; Joint A, seed 3): `dlw discover`
/// exited with an error (the `gain_drift` it named fades 26.9 /h, outside the scenario's
/// ±10 /h) instead of a report. Found by the detection measurement of 2026-11-27; fixed the
/// same day: a fitted value the simulator refuses declines the name (`declined`, with the value
/// and the limit), and the channel is tested for what the library cannot explain, which flags
/// it. Fails on the code before (the error). Since the split has 11 blocks (every held-out block
/// between training ones) the `gain_drift` is refused by the change in time first (185.6 nats
/// after it), before its range is checked; either decline gives the report.
#[test]
fn a_large_cycling_gain_gets_a_report_not_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let case = Case {
        design: "joint-a.toml",
        effect: Some((Effect::GainCycle, Size(8.0), 1)),
        seed: 3,
    };
    let json = try_run(dir.path(), &case).unwrap_or_else(|e| panic!("{}: {e}", case.name()));
    assert_right(&json, &case);
    let declined = json["declined"].as_array().unwrap();
    assert!(
        declined.iter().any(|d| d["effect"] == "gain_drift"
            && (d["out_of_range"]["key"] == "gain_drift.fade_per_hour"
                || d["time"]["verdict"] == "rival")),
        "{}: declined {declined:?}",
        case.name()
    );
}

fn run_cases() -> Summary {
    let full = std::env::var("DLW_DISCOVER_FULL").is_ok();
    let mut cases: Vec<Case> = Vec::new();
    if full {
        for seed in 0..3u64 {
            for (i, effect) in Effect::ALL.into_iter().enumerate() {
                // Both joints also at the larger sizes where they are physical (Joint C's
                // sensor effects are already ×4 the constants there, so fewer are); the three
                // sizes of the tests on both, physical or not.
                for (j, size) in Size::ALL.into_iter().chain(Size::LARGE).enumerate() {
                    let s = 10_000 + 100 * seed + 10 * i as u64 + j as u64;
                    if size.0 <= effect.largest_physical(false) {
                        cases.push(Case {
                            design: "joint-a.toml",
                            effect: Some((effect, size, 1)),
                            seed: s,
                        });
                    }
                    if j >= Size::ALL.len() && size.0 > effect.largest_physical(true) {
                        continue;
                    }
                    cases.push(Case {
                        design: "joint-c.toml",
                        effect: Some((effect, size, 1 + (i + j + seed as usize) % 2)),
                        seed: s + 5000,
                    });
                }
            }
        }
        let twins: Vec<Case> = cases.iter().map(Case::twin).collect();
        cases.extend(twins);
        // 100 clean recordings per joint: the twins and more.
        for design in ["joint-a.toml", "joint-c.toml"] {
            let have = cases
                .iter()
                .filter(|c| c.design == design && c.effect.is_none())
                .count();
            for k in 0..100usize.saturating_sub(have) {
                cases.push(Case {
                    design,
                    effect: None,
                    seed: 20_000 + k as u64,
                });
            }
        }
    } else {
        for (i, effect) in Effect::ALL.into_iter().enumerate() {
            // ×1, and ×2 or the effect's detection size when it has one (measured on other
            // seeds), so the detection figures are asserted on a case.
            let d = detection("joint-a.toml", effect);
            let larger = Size(if d.is_finite() { d.max(2.0) } else { 2.0 });
            for size in [Size(1.0), larger] {
                cases.push(Case {
                    design: "joint-a.toml",
                    effect: Some((effect, size, 1)),
                    seed: 10_000 + i as u64,
                });
            }
        }
        cases.push(Case {
            design: "joint-c.toml",
            effect: Some((Effect::Hysteresis, Size(2.0), 2)),
            seed: 15_002,
        });
        cases.push(Case {
            design: "joint-c.toml",
            effect: Some((Effect::GainCycle, Size(2.0), 1)),
            seed: 15_006,
        });
        // Joint C's drift at its detection size, on the compression sensor.
        cases.push(Case {
            design: "joint-c.toml",
            effect: Some((
                Effect::Drift,
                Size(detection("joint-c.toml", Effect::Drift)),
                2,
            )),
            seed: 15_004,
        });
        for seed in 0..3 {
            cases.push(Case {
                design: "joint-a.toml",
                effect: None,
                seed: 20_000 + seed,
            });
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let results: Vec<Outcome> = cases
        .par_iter()
        .map(|case| {
            let json = run(dir.path(), case);
            let j = judge(&json, &case.truth());
            (*case, j, said(&json), common::discovery::named(&json))
        })
        .collect();
    // What each clean recording named: an effect case's twin has the same noise, stroke pattern
    // and sensors, without the effect.
    let twin_named = |case: &Case| -> Option<&Vec<(String, String)>> {
        let twin = case.twin();
        results.iter().find(|r| r.0 == twin).map(|r| &r.3)
    };
    let (mut wrong, mut noise_names) = (Vec::new(), Vec::new());
    let (mut clean, mut alarms) = (0, Vec::new());
    // Per effect and size: (right, cases).
    let mut table: Vec<(Effect, f64, usize, usize)> = Vec::new();
    let (mut library, mut library_right, mut gains, mut gains_right) = (0, 0, 0, 0);
    for (case, j, said, named) in &results {
        eprintln!(
            "{}: {said}{}",
            case.name(),
            if j.right { "" } else { "  (missed)" }
        );
        for w in &j.wrong {
            // A name on a channel the effect is not on, which the clean twin gives too: the
            // noise's, not the effect's (the twin is counted against the clean rate).
            let from_noise = named.iter().any(|(e, ch)| {
                *w == format!("named {e} on {ch}")
                    && Some(ch) != case.channel().as_ref()
                    && twin_named(case).is_some_and(|t| t.contains(&(e.clone(), ch.clone())))
            });
            let list = if from_noise {
                &mut noise_names
            } else {
                &mut wrong
            };
            list.push((case.name(), w.clone()));
        }
        let Some((effect, size, _)) = case.effect else {
            clean += 1;
            if j.alarm {
                alarms.push(case.name());
            }
            continue;
        };
        match table
            .iter_mut()
            .find(|(e, s, ..)| *e == effect && *s == size.0)
        {
            Some(row) => {
                row.2 += usize::from(j.right);
                row.3 += 1;
            }
            None => table.push((effect, size.0, usize::from(j.right), 1)),
        }
        if size.0 >= detection(case.design, effect) {
            if effect.name().is_some() {
                library += 1;
                library_right += usize::from(j.right);
            } else {
                gains += 1;
                gains_right += usize::from(j.right);
            }
        }
    }
    for (e, s, right, n) in &table {
        eprintln!("third generator: {} ×{s}: {right}/{n} right", e.tag());
    }
    eprintln!(
        "third generator: library effects at or above detection {library_right}/{library}, gains {gains_right}/{gains}, wrong {}, clean named or flagged {}/{clean}, names the clean twin gives too {noise_names:?}",
        wrong.len(),
        alarms.len()
    );
    Summary {
        wrong,
        noise_names,
        alarms,
        clean,
        library,
        library_right,
        gains,
        gains_right,
    }
}

/// Writes one recording per effect and size (Joint A; Joint C's sensor 2) and a clean one
/// into `$THIRD_DIR`, to look at: `THIRD_DIR=/tmp/third cargo test --test
/// discover_third_generator -- --ignored write_samples` (`THIRD_SEED`, `THIRD_JOINTS` =
/// `joint-a.toml,joint-c.toml`, `THIRD_SIZES` = `0.5,1,2` by default, `THIRD_ONLY` = a part of
/// the case names).
#[test]
#[ignore = "writes sample recordings for inspection"]
fn write_samples() {
    let dir = std::env::var("THIRD_DIR").expect("THIRD_DIR is set");
    let seed: u64 = std::env::var("THIRD_SEED").map_or(1, |s| s.parse().unwrap());
    let joints: Vec<&str> = std::env::var("THIRD_JOINTS").map_or(vec!["joint-a.toml"], |s| {
        s.split(',')
            .map(|j| Box::leak(j.to_owned().into_boxed_str()) as &str)
            .collect()
    });
    let dir = Path::new(&dir);
    for design in joints {
        let mut effects: Vec<Option<(Effect, Size, usize)>> = vec![None];
        for e in Effect::ALL {
            for s in env_list("THIRD_SIZES", "0.5,1,2") {
                let s = Size(s);
                effects.push(Some((e, s, if design == "joint-c.toml" { 2 } else { 1 })));
            }
        }
        let only = std::env::var("THIRD_ONLY").ok();
        for effect in effects {
            let case = Case {
                design,
                effect,
                seed,
            };
            if only
                .as_ref()
                .is_some_and(|o| !case.name().contains(o.as_str()))
            {
                continue;
            }
            let bench = Bench {
                effect,
                duration_s: case.duration_s(),
                seed,
            };
            third_generator::write_recording(
                Path::new(&shipped_design(design)),
                &bench,
                &dir.join(case.name()),
            );
        }
    }
}

/// What a report named, left ambiguous and flagged, in one line.
fn said(json: &serde_json::Value) -> String {
    let ambiguous: Vec<String> = json["ambiguous"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| {
            let contenders: Vec<String> = a["contenders"]
                .as_array()
                .unwrap()
                .iter()
                .map(|c| format!("{} {:.1}", c[0].as_str().unwrap(), c[1].as_f64().unwrap()))
                .collect();
            format!(
                "{} [{}]",
                a["channel"].as_str().unwrap(),
                contenders.join(", ")
            )
        })
        .collect();
    format!(
        "named {:?}, ambiguous [{}], unexplained {}",
        common::discovery::named(json),
        ambiguous.join("; "),
        json["unexplained"]
            .as_array()
            .unwrap()
            .iter()
            .map(|u| u["channel"].as_str().unwrap())
            .collect::<Vec<_>>()
            .join(",")
    )
}

/// A list of numbers from the environment: `1-6`, `1,3,5` or `20000-20099`.
fn env_list(key: &str, default: &str) -> Vec<f64> {
    let text = std::env::var(key).unwrap_or_else(|_| default.to_owned());
    text.split(',')
        .flat_map(|part| match part.split_once('-') {
            Some((a, b)) => {
                let (a, b): (u64, u64) = (a.trim().parse().unwrap(), b.trim().parse().unwrap());
                (a..=b).map(|k| k as f64).collect::<Vec<_>>()
            }
            None => vec![part.trim().parse().unwrap()],
        })
        .collect()
}

/// Measures detection against size (docs/discovery.md, "Detection against size"): each effect
/// of `THIRD_EFFECTS` (tags, comma-separated, `clean` for clean recordings; default every
/// effect) at each size of `THIRD_SIZES` (default `0.5,1,2,4,8`) on the seeds `THIRD_SEEDS`
/// (default `1-6`), on `THIRD_JOINT` (default `joint-a.toml`), sensor `THIRD_SENSOR` (default 1
/// on Joint A, 2 on Joint C, as `write_samples` puts them). Prints a line per case as it ends,
/// then per effect and size the cases right and wrong, and the smallest size from which every
/// larger size measured was right on every seed:
/// `nice -n 5 cargo test --release --test discover_third_generator -- --ignored
/// measure_detection --nocapture`.
#[test]
#[ignore = "a measurement: minutes on Joint A, hours on Joint C"]
fn measure_detection() {
    let design: &'static str = Box::leak(
        std::env::var("THIRD_JOINT")
            .unwrap_or_else(|_| "joint-a.toml".to_owned())
            .into_boxed_str(),
    );
    let bsn = design == "joint-c.toml";
    let sensor =
        std::env::var("THIRD_SENSOR").map_or(if bsn { 2 } else { 1 }, |s| s.parse().unwrap());
    let seeds: Vec<u64> = env_list("THIRD_SEEDS", "1-6")
        .into_iter()
        .map(|s| s as u64)
        .collect();
    let mut sizes: Vec<Size> = env_list("THIRD_SIZES", "0.5,1,2,4,8")
        .into_iter()
        .map(Size)
        .collect();
    sizes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let wanted = std::env::var("THIRD_EFFECTS").ok();
    let wants = |tag: &str| {
        wanted
            .as_ref()
            .is_none_or(|w| w.split(',').any(|x| x.trim() == tag))
    };
    let mut effects: Vec<Option<Effect>> = Effect::ALL
        .into_iter()
        .filter(|e| wants(e.tag()))
        .map(Some)
        .collect();
    if wants("clean") {
        effects.push(None);
    }
    let mut cases = Vec::new();
    for effect in &effects {
        for &seed in &seeds {
            match effect {
                Some(e) => cases.extend(sizes.iter().map(|&size| Case {
                    design,
                    effect: Some((*e, size, sensor)),
                    seed,
                })),
                None => cases.push(Case {
                    design,
                    effect: None,
                    seed,
                }),
            }
        }
    }
    eprintln!("measure_detection: {} cases on {design}", cases.len());
    let dir = tempfile::tempdir().unwrap();
    // A case whose discovery failed is kept with its error: neither right nor wrong.
    let results: Vec<(Case, Judgement, bool)> = cases
        .par_iter()
        .map(|case| {
            let start = std::time::Instant::now();
            let past = case
                .effect
                .filter(|(e, s, _)| s.0 > e.largest_physical(bsn))
                .map_or("", |_| " (past physical)");
            let json = match try_run(dir.path(), case) {
                Ok(json) => json,
                Err(e) => {
                    eprintln!(
                        "{}{past}: ERROR in {:.1} s: {e}",
                        case.name(),
                        start.elapsed().as_secs_f64()
                    );
                    return (*case, Judgement::default(), true);
                }
            };
            let j = judge(&json, &case.truth());
            eprintln!(
                "{}{past}: {} in {:.1} s: {}{}",
                case.name(),
                match (j.right, j.wrong.is_empty()) {
                    (_, false) => "wrong",
                    (true, true) => "right",
                    (false, true) => "missed",
                },
                start.elapsed().as_secs_f64(),
                said(&json),
                if j.wrong.is_empty() {
                    String::new()
                } else {
                    format!("  WRONG {:?}", j.wrong)
                }
            );
            (*case, j, false)
        })
        .collect();
    for effect in &effects {
        let mine: Vec<&(Case, Judgement, bool)> = results
            .iter()
            .filter(|(c, ..)| c.effect.map(|(e, ..)| e) == *effect)
            .collect();
        let errors = |at: &[&(Case, Judgement, bool)]| at.iter().filter(|r| r.2).count();
        let Some(e) = effect else {
            let alarms: Vec<String> = mine
                .iter()
                .filter(|(_, j, _)| j.alarm)
                .map(|(c, ..)| c.name())
                .collect();
            eprintln!(
                "clean on {design}: {} of {} named or flagged {alarms:?}, {} failed",
                alarms.len(),
                mine.len(),
                errors(&mine)
            );
            continue;
        };
        // Per size: (right, wrong, failed, cases).
        let rows: Vec<(f64, usize, usize, usize, usize)> = sizes
            .iter()
            .map(|size| {
                let at: Vec<&(Case, Judgement, bool)> = mine
                    .iter()
                    .filter(|(c, ..)| c.effect.is_some_and(|(_, s, _)| s == *size))
                    .copied()
                    .collect();
                let right = at.iter().filter(|(_, j, _)| j.right && j.wrong.is_empty());
                let wrong = at.iter().filter(|(_, j, _)| !j.wrong.is_empty());
                (size.0, right.count(), wrong.count(), errors(&at), at.len())
            })
            .collect();
        let detection = rows
            .iter()
            .enumerate()
            .find(|(k, _)| rows[*k..].iter().all(|r| r.1 == r.4))
            .map_or(f64::INFINITY, |(_, r)| r.0);
        let cells: Vec<String> = rows
            .iter()
            .map(|(s, right, wrong, failed, n)| {
                format!("×{s} {right}/{n} (wrong {wrong}, failed {failed})")
            })
            .collect();
        eprintln!(
            "{} on {design} sensor {sensor}: {}; detection size ×{detection}",
            e.tag(),
            cells.join(", ")
        );
        if matches!(e, Effect::Drift | Effect::GainWalk) {
            eprintln!(
                "{} on {design} sensor {sensor}, by realized size: {}",
                e.tag(),
                by_realized_size(&mine)
            );
        }
    }
}

/// A random-walk effect's cases by their realized size ([`third_generator::realized_size`]),
/// in octaves: per octave the cases right (and wrong) of those whose walk wandered that far.
fn by_realized_size(results: &[&(Case, Judgement, bool)]) -> String {
    let mut octaves: std::collections::BTreeMap<i32, (usize, usize, usize)> = Default::default();
    for (case, j, _) in results {
        let bench = Bench {
            effect: case.effect,
            duration_s: case.duration_s(),
            seed: case.seed,
        };
        let Some(r) = third_generator::realized_size(&bench) else {
            continue;
        };
        let cell = octaves.entry(r.log2().floor() as i32).or_default();
        cell.0 += usize::from(j.right && j.wrong.is_empty());
        cell.1 += usize::from(!j.wrong.is_empty());
        cell.2 += 1;
    }
    octaves
        .iter()
        .map(|(k, (right, wrong, n))| {
            format!(
                "×{}-{} {right}/{n} (wrong {wrong})",
                2f64.powi(*k),
                2f64.powi(*k + 1)
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}
