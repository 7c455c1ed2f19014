//! `dlw discover` on recordings from a generator with other functional forms than the
//! simulator's (`tests/common/other_forms.rs`): soft backlash, Prony relaxation, Bouc-Wen
//! hysteresis, rational saturation, a square-root signed rate response, two-term creep and an
//! exponential warm-up drift, with white + AR(1) noise of other correlation times. Discovery must
//! name the right effect on the right channel, and nothing on clean recordings, although none
//! of these forms is the simulator's: the acceptance figures, asserted at CI size and
//! measured at full size with `DLW_DISCOVER_FULL=1 cargo test --release --test
//! discover_other_forms -- --nocapture`.

mod common;
use common::discovery::{above, discover_json, gaps, judge, named, Judgement, Truth};
use common::other_forms::{self, Bench, Effect};
use common::shipped_design;

use rayon::prelude::*;
use std::path::Path;

/// Recording length (s): Joint A's; Joint C's insensitive sensor (GF 1.28) gets the paper's
/// 3000 s random run, as in `tests/discover_matrix.rs`.
fn duration_s(design: &str) -> f64 {
    if design == "joint-c.toml" {
        3000.0
    } else {
        300.0
    }
}

/// Runs `dlw discover --json` on a generated recording; returns the JSON.
fn discover(dir: &Path, design: &str, bench: &Bench, name: &str) -> serde_json::Value {
    let rec = dir.join(name);
    other_forms::write_recording(Path::new(&shipped_design(design)), bench, &rec);
    discover_json(
        &shipped_design(design),
        &rec,
        &dir.join(format!("{name}-out")),
    )
}

/// One recording: the design, the effect with its sensor (none: a clean control), the seed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Case {
    design: &'static str,
    effect: Option<(Effect, usize)>,
    seed: u64,
}

impl Case {
    fn name(&self) -> String {
        format!(
            "{}-{}-{}",
            self.design.trim_end_matches(".toml"),
            self.effect.map_or("clean", |(e, _)| e.name()),
            self.seed
        )
    }

    /// The channel the effect acts on.
    fn channel(&self) -> Option<String> {
        self.effect.map(|(e, sensor)| {
            if e.is_plant() {
                "plant".to_owned()
            } else {
                format!("sensor{sensor}")
            }
        })
    }

    /// The same seed without the effect: the generator's noise is drawn identically (the
    /// effects draw no random numbers), so its held-out RMSE is the floor no model removes.
    fn twin(&self) -> Case {
        Case {
            effect: None,
            ..*self
        }
    }
}

/// What discovery said about one case.
struct Seen {
    named: Vec<(String, String)>,
    flagged: bool,
    /// The rules on names, flags and ambiguity ([`judge`]).
    judged: Judgement,
    /// Per channel, the held-out RMSE before and after.
    gaps: Vec<(String, f64, f64)>,
}

fn seen(dir: &Path, case: &Case) -> Seen {
    let bench = Bench {
        effects: case.effect.into_iter().collect(),
        duration_s: duration_s(case.design),
        seed: case.seed,
        ..Bench::default()
    };
    let report = discover(dir, case.design, &bench, &case.name());
    let truth = match (case.effect, case.channel()) {
        (Some((e, _)), Some(channel)) => Truth::Library {
            effect: e.name().to_owned(),
            channel,
        },
        _ => Truth::Clean,
    };
    Seen {
        judged: judge(&report, &truth),
        named: named(&report),
        flagged: !report["unexplained"].as_array().unwrap().is_empty(),
        gaps: gaps(&report),
    }
}

impl Seen {
    fn gap(&self, channel: &str) -> (f64, f64) {
        self.gaps
            .iter()
            .find(|g| g.0 == channel)
            .map(|g| (g.1, g.2))
            .unwrap()
    }
}

/// The acceptance figures on recordings from a generator discovery was not built on
/// (other functional forms, white + AR(1) noise of other correlation times): each effect alone
/// on Joint A (UAN) and, for the sensor effects, on Joint C's sensor 2, with the clean twin of
/// every effect case and more clean controls. Asserted: the right effect first on the right
/// channel in ≥ 95 % of the effect cases, no wrong name, a name or an `unexplained` flag on
/// ≤ 1 % of the clean recordings, and a median held-out gap shrink ≥ 50 % above the twin's
/// floor. CI runs one seed per case, Joint C's sensor 2 only with hysteresis and drift, and 2
/// more controls on Joint A and 1 on Joint C (Joint C's 3000 s runs cost about six of Joint
/// A's); `DLW_DISCOVER_FULL=1` runs 5 seeds, every sensor effect on Joint C, and 20 more
/// controls per joint.
#[test]
fn discover_meets_the_acceptance_figures_on_other_functional_forms() {
    let full = std::env::var("DLW_DISCOVER_FULL").is_ok();
    let (seeds, controls) = if full { (5u64, 20u64) } else { (1, 2) };
    let mut cases: Vec<Case> = Vec::new();
    for s in 0..seeds {
        for (i, effect) in Effect::ALL.into_iter().enumerate() {
            let seed = 100 * (s + 1) + i as u64;
            cases.push(Case {
                design: "joint-a.toml",
                effect: Some((effect, 1)),
                seed,
            });
            // Joint C's 3000 s runs cost about six of Joint A's: CI runs two of its sensor
            // effects (hysteresis and drift), the full size all five.
            let on_c = full || matches!(effect, Effect::Hysteresis | Effect::Drift);
            if !effect.is_plant() && on_c {
                cases.push(Case {
                    design: "joint-c.toml",
                    effect: Some((effect, 2)),
                    seed: seed + 50,
                });
            }
        }
    }
    let twins: Vec<Case> = cases.iter().map(Case::twin).collect();
    cases.extend(twins);
    for s in 0..controls {
        for design in ["joint-a.toml", "joint-c.toml"] {
            if !full && design == "joint-c.toml" && s > 0 {
                continue;
            }
            cases.push(Case {
                design,
                effect: None,
                seed: 5000 + s,
            });
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let results: Vec<(Case, Seen)> = cases
        .par_iter()
        .map(|case| (*case, seen(dir.path(), case)))
        .collect();
    let twin = |case: &Case| {
        results
            .iter()
            .find(|(c, _)| *c == case.twin())
            .map(|(_, s)| s)
            .unwrap()
    };
    let (mut effects, mut right, mut wrong, mut clean, mut alarms) =
        (0, 0, Vec::new(), 0, Vec::new());
    let mut shrinks = Vec::new();
    for (case, s) in &results {
        let Some(channel) = case.channel() else {
            clean += 1;
            eprintln!(
                "{}: discovered {:?}, flagged {}",
                case.name(),
                s.named,
                s.flagged
            );
            if !s.named.is_empty() || s.flagged {
                alarms.push(case.name());
            }
            continue;
        };
        effects += 1;
        let truth = (case.effect.unwrap().0.name().to_owned(), channel.clone());
        if s.named.first() == Some(&truth) {
            right += 1;
        }
        wrong.extend(s.judged.wrong.iter().map(|w| (case.name(), w.clone())));
        let (before, after) = s.gap(&channel);
        let floor = twin(case).gap(&channel).0;
        let shrink = 1.0 - above(after, floor) / above(before, floor);
        shrinks.push(shrink);
        eprintln!(
            "{}: discovered {:?}, {channel} RMSE {before:.4} → {after:.4} (floor {floor:.4}): gap shrink {:.0} %",
            case.name(),
            s.named,
            100.0 * shrink
        );
    }
    shrinks.sort_by(f64::total_cmp);
    let median = shrinks[shrinks.len() / 2];
    eprintln!(
        "other forms: right effect on the right channel {right}/{effects} ({:.0} %), wrong names {}, clean recordings with a name or a flag {}/{clean}, median held-out gap shrink {:.0} % above the floor",
        100.0 * right as f64 / effects as f64,
        wrong.len(),
        alarms.len(),
        100.0 * median
    );
    assert!(wrong.is_empty(), "wrong names: {wrong:?}");
    assert!(
        alarms.len() * 100 <= clean,
        "clean recordings named or flagged: {alarms:?} of {clean}"
    );
    // Measured: CI 9/9 (12/12 before Joint C's sensor effects were cut to two, 2026-11-26),
    // median gap shrink 79 %; full size 57/60 (95 %, 2026-11-26), with no margin: Joint A's
    // two-term creep is missed on seeds 305 and 405 and Joint C's drift on 556, never named
    // wrong (docs/discovery.md, "Other functional forms").
    assert!(
        right as f64 >= 0.95 * effects as f64,
        "{right} of {effects} effect cases named right"
    );
    assert!(median >= 0.5, "median gap shrink {median}");
}

/// The wrong name the five-seed run (`DLW_DISCOVER_FULL=1`, 2026-11-27, the first on the issue-31
/// code) found: Joint A's hysteresis, seed 502, was named `creep` (31.7 nats) and then
/// `hysteresis` (562.8). In round 0 the hysteresis had 897.1 nats but its memory test (the
/// plays over a memoryless curve of any shape) gave −249.9, so it was left out of the round
/// and the creep won it. The cause: that curve was drawn with hats, which add up to one, so
/// the fit shared the offset among them; on a held-out block whose strain dipped below the
/// training blocks' range the share fell away, and both models of the test missed that block
/// by the offset. The curve is now drawn with hinges that leave the offset and the slope at
/// zero to the design (`terms::hinges`): the memory reads 1128.1 and `hysteresis` is named
/// alone. Fails on the code before.
#[test]
fn a_hysteresis_whose_memory_test_fails_gets_no_creep() {
    let dir = tempfile::tempdir().unwrap();
    let case = Case {
        design: "joint-a.toml",
        effect: Some((Effect::Hysteresis, 1)),
        seed: 502,
    };
    let seen = seen(dir.path(), &case);
    assert!(
        seen.judged.wrong.is_empty(),
        "{}: {:?}",
        case.name(),
        seen.judged.wrong
    );
}

/// Writes one recording per effect (Joint A; the sensor effects also on Joint C's sensor 2) and
/// a clean one into `$OTHER_FORMS_DIR`, to look at:
/// `OTHER_FORMS_DIR=/tmp/of cargo test --test discover_other_forms -- --ignored write_samples`.
#[test]
#[ignore = "writes sample recordings for inspection"]
fn write_samples() {
    let dir = std::env::var("OTHER_FORMS_DIR").expect("OTHER_FORMS_DIR is set");
    let seed: u64 = std::env::var("OTHER_FORMS_SEED").map_or(1, |s| s.parse().unwrap());
    let dir = Path::new(&dir);
    let mut cases = vec![("joint-a.toml", None), ("joint-c.toml", None)];
    for e in Effect::ALL {
        cases.push(("joint-a.toml", Some((e, 1))));
        cases.push(("joint-c.toml", Some((e, 2))));
    }
    for (design, effect) in cases {
        let bench = Bench {
            effects: effect.into_iter().collect(),
            duration_s: duration_s(design),
            seed,
            ..Bench::default()
        };
        let name = format!(
            "{}-{}",
            design.trim_end_matches(".toml"),
            effect.map_or("clean", |(e, _)| e.name())
        );
        other_forms::write_recording(Path::new(&shipped_design(design)), &bench, &dir.join(name));
    }
}
