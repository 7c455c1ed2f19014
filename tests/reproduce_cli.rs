//! `dlw reproduce --short` through the binary: the report holds Tables III-VI with the paper's
//! numbers beside dlw's, every figure it references exists and is SVG, and every number is
//! finite.

mod common;

/// The angle RMSE (°) of the one-sensor run of `config` in a joint's JSON.
fn rmse(joint: &serde_json::Value, config: &str) -> f64 {
    joint["estimation"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["config"] == config)
        .unwrap()["rmse_deg"]
        .as_f64()
        .unwrap()
}

/// On the ideal bench (`--ideal`): at half the paper's durations, Joint C's fitted PI model flattens near the ends of its
/// range, and without the runtime's clamp to the characterized strain range its estimate of
/// the random run was 25.9° against 6.8° for linear (it read angles far beyond the joint's).
/// With the clamp, every joint's PI estimate stays within 1.5 times its linear one.
#[test]
fn half_size_pi_estimates_stay_near_linear() {
    let j = ideal_half_size();
    for x in j["joints"].as_array().unwrap() {
        eprintln!(
            "Joint {}: linear {:.2}°, PI {:.2}°",
            x["joint"],
            rmse(x, "linear"),
            rmse(x, "PI")
        );
        assert!(rmse(x, "PI") < 1.5 * rmse(x, "linear"), "{x}");
    }
}

#[test]
fn short_reproduction_writes_all_four_tables_and_the_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("repro");
    let o = common::dlw(&[
        "reproduce",
        "--short",
        "-o",
        &out.display().to_string(),
        "--json",
    ]);
    assert!(
        o.status.success(),
        "dlw reproduce failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    // The default bench is the calibrated twin (`--ideal` for the clean one).
    assert_eq!(j["bench"], "twin");
    assert_agreement_is_computed(&j);
    // Every number the command prints is finite (JSON has no NaN: serde writes null).
    fn walk(v: &serde_json::Value, path: &str) {
        match v {
            serde_json::Value::Null => {
                assert!(
                    path.ends_with("median_tau_s"),
                    "{path} is null (not finite)"
                )
            }
            serde_json::Value::Number(n) => {
                assert!(n.as_f64().is_some_and(f64::is_finite), "{path} = {n}")
            }
            serde_json::Value::Array(a) => {
                for (i, x) in a.iter().enumerate() {
                    walk(x, &format!("{path}[{i}]"));
                }
            }
            serde_json::Value::Object(m) => {
                for (k, x) in m {
                    walk(x, &format!("{path}.{k}"));
                }
            }
            _ => {}
        }
    }
    walk(&j, "");
    let joints = j["joints"].as_array().unwrap();
    let letters: Vec<&str> = joints
        .iter()
        .map(|x| x["joint"].as_str().unwrap())
        .collect();
    assert_eq!(letters, ["A", "B", "C"]);
    // The simulated sensors are Table III's: the fitted linear R₀ is near each joint's.
    for (x, r0) in joints.iter().zip([215e3, 77.2e3, 74.0e3]) {
        let fitted = x["r0_ohm"].as_f64().unwrap();
        assert!((fitted / r0 - 1.0).abs() < 0.05, "{x}");
    }
    // Joint C estimates with tension, compression and both sensors.
    let c: Vec<&str> = joints[2]["estimation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["role"].as_str().unwrap())
        .collect();
    assert_eq!(
        c,
        ["one sensor", "one sensor", "tension", "compression", "both"]
    );
    // The sensors each reads, by the one sensor identity.
    let sensors: Vec<&str> = joints[2]["estimation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r["sensors"].as_str().unwrap())
        .collect();
    assert_eq!(
        sensors,
        ["sensor1", "sensor1", "sensor1", "sensor2", "both"]
    );
    // No PI config runs far from its linear one on the default bench, the twin (PI over linear
    // 1.05, 0.98 and 1.04 for Joints A-C, measured at `--short`; on the ideal bench this held
    // with or without the PI inverse's strain clamp); `half_size_pi_estimates_stay_near_linear`
    // below is the run that needs the clamp.
    for x in joints {
        assert!(rmse(x, "PI") < 1.5 * rmse(x, "linear"), "{x}");
    }
    // Closed loop brings the sensed angle to the desired one.
    let sensed = |k: &str| j[k]["sensed_vs_desired_rmse_deg"].as_f64().unwrap();
    assert!(
        sensed("control_closed_loop") < sensed("control_open_loop"),
        "{j}"
    );

    let html = std::fs::read_to_string(out.join("report.html")).unwrap();
    for needle in [
        "Table III",
        "Table IV",
        "Table V",
        "Table VI",
        "Fig. 4",
        "Fig. 5",
        "Fig. 6",
        "Fig. 7",
        "Fig. 8",
        "Fig. 10",
        "754.0",
        "misplaced decimal point",
        "Why they differ",
    ] {
        assert!(html.contains(needle), "{needle} not in the report");
    }
    // The paper's numbers beside dlw's: Table IV's and Table VI's.
    for paper in [
        "2.76", "1.76", "3.51", "2.65", "5.25", "7.57", "8.14", "2.92", "3.13", "0.118",
    ] {
        assert!(
            html.contains(&format!("<td>{paper}</td>")),
            "paper's {paper} not in a table"
        );
    }
    assert!(
        !html.contains("NaN") && !html.contains("inf<"),
        "a non-finite number in the report"
    );
    let figures: Vec<&str> = html
        .split("src=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .collect();
    assert!(figures.len() >= 35, "{} figures", figures.len());
    for f in &figures {
        let svg = std::fs::read_to_string(out.join(f)).unwrap_or_else(|e| panic!("{f}: {e}"));
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{f}: {e}"));
    }
    for want in [
        "a-loops-loops-v1.svg",
        "c-loops-loops-v2.svg",
        "b-rate-gf-v1.svg",
        "a-relax-strain-v1.svg",
        "c-two-estimates.svg",
        "d-control-fig10b-closed-loop.svg",
    ] {
        assert!(figures.contains(&want), "{want} missing");
    }
}

/// The run's agreement with the paper (`"agreement"`): the ten headline numbers and the
/// twin's 21 Table III numbers, each outside exactly when its distance passes its limit, the
/// outside ones listed and each named in the finding with its distance; and what the
/// calibration moved, each parameter with its ideal value.
fn assert_agreement_is_computed(j: &serde_json::Value) {
    let checks = j["agreement"]["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 10 + 21);
    let mut outside = Vec::new();
    for c in checks {
        let paper = c["paper"].as_f64().unwrap();
        let dlw = c["dlw"].as_f64().unwrap();
        let limit = c["limit"].as_f64().unwrap();
        let off = (dlw / paper - 1.0).abs() > limit;
        assert_eq!(c["outside"].as_bool().unwrap(), off, "{c}");
        if off {
            outside.push(c["name"].as_str().unwrap());
        }
    }
    let listed: Vec<&str> = j["agreement"]["outside"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    assert_eq!(listed, outside);
    let finding = j["agreement"]["finding"].as_str().unwrap();
    assert!(
        finding.starts_with(&format!(
            "{} of 31 checked numbers are outside",
            outside.len()
        )) || (outside.is_empty() && finding.starts_with("All 31")),
        "{finding}"
    );
    for c in checks.iter().filter(|c| c["outside"] == true) {
        let what = c["what"].as_str().unwrap();
        assert!(finding.contains(&what[1..]), "{what} not in: {finding}");
        assert!(finding.contains("points outside"), "{finding}");
    }
    let moved = j["moved"].as_array().unwrap();
    assert_eq!(moved.len(), 21);
    assert!(moved.iter().all(|m| m["ideal"].is_number()), "{moved:?}");
}

#[test]
fn a_bad_duration_scale_is_refused_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("repro");
    for scale in ["0", "2", "nan"] {
        let o = common::dlw(&[
            "reproduce",
            "--duration-scale",
            scale,
            "-o",
            &out.display().to_string(),
        ]);
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("must lie in (0, 1]"), "{scale}: {err}");
        assert!(!out.exists());
    }
}

/// `dlw reproduce --ideal --duration-scale 0.5 --json`, run once for the two tests that read it.
fn ideal_half_size() -> &'static serde_json::Value {
    static HALF: std::sync::OnceLock<serde_json::Value> = std::sync::OnceLock::new();
    HALF.get_or_init(|| reproduce_json("0.5", "ideal"))
}

/// `dlw reproduce --json` at `duration_scale` on `bench` (`twin` or `ideal`), parsed.
fn reproduce_json(duration_scale: &str, bench: &str) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    let mut args = vec![
        "reproduce".to_owned(),
        "--duration-scale".to_owned(),
        duration_scale.to_owned(),
        "-o".to_owned(),
        common::arg(&out),
        "--json".to_owned(),
    ];
    args.push(format!("--{bench}"));
    let o = common::dlw_ok(&args);
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(j["bench"], bench);
    j
}

/// The names of the patterns whose verdict is `verdict` (`held`, `NOT held`, `cannot show`).
fn with_verdict<'a>(j: &'a serde_json::Value, verdict: &str) -> Vec<&'a str> {
    j["patterns"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| {
            let held = p["held"] == true;
            let cannot = p.get("cannot_show").is_some_and(|w| w.is_string());
            match verdict {
                "held" => held,
                "cannot show" => !held && cannot,
                _ => !held && !cannot,
            }
        })
        .map(|p| p["name"].as_str().unwrap())
        .collect()
}

/// Every failed pattern with the run's numbers, for a message.
fn failures(j: &serde_json::Value) -> String {
    format!(
        "{:#?}",
        j["patterns"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|p| p["held"] != true)
            .collect::<Vec<_>>()
    )
}

/// The pattern list is computed from the run: every one of the paper's 11 checks is there with
/// its numbers, and the Table VI check says held exactly when closed loop's actual-vs-desired
/// RMSE is below open loop's in the same JSON (the report claimed the paper's pattern next to
/// 4.22° → 8.72°).
#[test]
fn patterns_are_listed_and_agree_with_the_numbers() {
    let j = reproduce_json("0.1", "twin");
    let patterns = j["patterns"].as_array().unwrap();
    assert_eq!(j["bench"], "twin");
    assert_eq!(patterns.len(), 11, "{patterns:?}");
    for p in patterns {
        for key in ["name", "paper", "dlw"] {
            assert!(!p[key].as_str().unwrap().is_empty(), "{key} empty in {p}");
        }
        assert!(p["held"].is_boolean(), "{p}");
    }
    let open = j["control_open_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    let closed = j["control_closed_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    let vi = patterns
        .iter()
        .find(|p| p["name"].as_str().unwrap().contains("Table VI"))
        .unwrap();
    assert_eq!(vi["held"], closed < open, "{vi} against {open} → {closed}");
}

/// On the ideal bench (`--ideal`), at `--short` and at half size the patterns are asserted
/// too: every one holds except, at half size, the two the ideal joints cannot show (`KNOWN_CANNOT_SHOW`), so that a pattern that
/// breaks, or one that starts to hold, fails this test. At `--short` those two hold: with a
/// tenth of the data the PI fits' advantage is gone (Joint C: PI 7.28° against linear 7.19°)
/// and the sensors' errors are within √3 of each other.
///
/// The exceptions this list carried before were found and fixed at their cause:
/// - `--short`, Joint A's GF fell 7.9 % with the rise time (corr −0.78): the cycles were cut from
///   the turning point below the rest (a relaxed joint undershoots after unloading), so the
///   rest's noise entered the fast cycles' fits (`characterize::rate`).
/// - Half size, Joint B's GF correlation was −0.45 (bound 0.40): the rate analysis kept every
///   19th sample, about 25 per fast rise, and the kept samples' phase moved by one sample per
///   repetition, so the ends of a curved sensor's fit range moved with the cycle's number. It
///   now keeps every sample.
/// - Half size, Joint D's closed loop oscillated (12.8° against open loop's 3.7°): its N = 3 fit
///   had weights 1 : 454 : 67, an inverse with about 500 times its mean gain after every
///   reversal (`fit::pi::FIRST_WEIGHT_SHARE`).
#[test]
fn the_patterns_at_short_and_half_size() {
    for (scale, failing, cannot) in [
        ("0.1", Vec::<&str>::new(), Vec::<&str>::new()),
        ("0.5", vec![], KNOWN_CANNOT_SHOW.to_vec()),
    ] {
        let j = match scale {
            "0.5" => ideal_half_size().clone(),
            _ => reproduce_json(scale, "ideal"),
        };
        assert_eq!(
            with_verdict(&j, "NOT held"),
            failing,
            "scale {scale}: {}",
            failures(&j)
        );
        assert_eq!(
            with_verdict(&j, "cannot show"),
            cannot,
            "scale {scale}: {}",
            failures(&j)
        );
    }
}

/// At the paper's full durations (about 20 s in the dev profile), every pattern the ideal
/// joints can show holds: PI beats linear for Joints A and B (Table IV), GF does not follow the
/// rise time (Fig. 5), every relaxation τ comes back within 10 % (Fig. 6), and closed loop beats
/// open loop on actual vs desired (Table VI; 4.22° → 8.72° before Joint D's desired pattern was
/// kept inside the characterized range, `reproduce::CONTROL_RANGE_SHARE`). The two the ideal
/// joints cannot show, with the reason computed from the run, are `KNOWN_CANNOT_SHOW`; a change
/// in either list fails this test.
#[test]
fn the_simulated_joints_show_the_papers_patterns_at_full_size() {
    let j = reproduce_json("1", "ideal");
    assert!(with_verdict(&j, "NOT held").is_empty(), "{}", failures(&j));
    assert_eq!(
        with_verdict(&j, "cannot show"),
        KNOWN_CANNOT_SHOW,
        "{}",
        failures(&j)
    );
    let open = j["control_open_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    let closed = j["control_closed_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    // The paper: 8.14° → 2.92°. Closed loop at least halves open loop's error.
    assert!(closed < 0.5 * open, "open {open}° → closed {closed}°");
    insta::assert_snapshot!("headline_numbers_full_size", headline(&j));
}

/// The shipped twin of the paper's bench at the paper's full durations (`dlw reproduce
/// --twin`, about 45 s in release; with `DLW_TWIN_FULL=1`): the issue's acceptance, asserted as
/// measured (docs/experiments.md). The patterns it does not hold are `TWIN_NOT_HELD` and
/// `TWIN_CANNOT_SHOW` (none); the numbers of Tables IV-VI outside 25 % of the paper's are
/// `UNMET` (none); every Table III number is no further from the paper than the ideal
/// bench's plus 5 points except `TABLE_III_NOT_KEPT`; the explorer's short prediction of Joints
/// A-C is within 30 % of this full simulation. A changed headline number fails the snapshot, a
/// change in any list fails the test.
#[test]
fn the_twin_at_full_size() {
    if std::env::var_os("DLW_TWIN_FULL").is_none() {
        eprintln!("skipped: set DLW_TWIN_FULL=1 (the shipped twin at full size)");
        return;
    }
    let j = reproduce_json("1", "twin");
    assert_eq!(
        with_verdict(&j, "NOT held"),
        TWIN_NOT_HELD,
        "{}",
        failures(&j)
    );
    assert_eq!(
        with_verdict(&j, "cannot show"),
        TWIN_CANNOT_SHOW,
        "{}",
        failures(&j)
    );
    let open = j["control_open_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    let closed = j["control_closed_loop"]["actual_vs_desired_rmse_deg"]
        .as_f64()
        .unwrap();
    // The paper: 8.14° → 2.92°. Closed loop at least halves open loop's error.
    assert!(closed < 0.5 * open, "open {open}° → closed {closed}°");
    let mut unmet = Vec::new();
    for (name, twin, paper) in paper_numbers(&j) {
        let off = twin / paper - 1.0;
        eprintln!(
            "{name}: twin {twin:.2}, paper {paper:.2} ({:+.0} %)",
            100.0 * off
        );
        if off.abs() > 0.25 {
            unmet.push(name);
        }
    }
    assert_eq!(unmet, UNMET, "Tables IV-VI outside 25 % of the paper's");
    let mut not_kept = Vec::new();
    for (joint, ideal) in j["joints"].as_array().unwrap().iter().zip(IDEAL_TABLE_III) {
        let name = joint["joint"].as_str().unwrap();
        let c = &joint["characteristic"];
        let twin = [
            joint["gauge_factor"].as_f64().unwrap(),
            joint["r0_ohm"].as_f64().unwrap(),
            c["center_ohm"].as_f64().unwrap(),
            c["center_strain"].as_f64().unwrap(),
            c["center_slope_ohm"].as_f64().unwrap(),
            c["peak_ohm"].as_f64().unwrap(),
            c["peak_strain"].as_f64().unwrap(),
        ];
        let i = usize::from(name.as_bytes()[0] - b'A');
        for (k, ((t, id), paper)) in twin.iter().zip(ideal).zip(paper_table_iii(i)).enumerate() {
            let allowed = (id / paper - 1.0).abs() + 0.05;
            if (t / paper - 1.0).abs() > allowed {
                not_kept.push(format!("{name}.{}", TABLE_III_ROWS[k]));
            }
        }
    }
    assert_eq!(
        not_kept, TABLE_III_NOT_KEPT,
        "Table III further from the paper than allowed"
    );
    insta::assert_snapshot!("headline_numbers_twin_full_size", headline(&j));
    // The explorer's predicted accuracy of the paper's joints against this full run.
    let predictor = dlw::explore::Predictor::paper(15.3).unwrap();
    let predictor_b = dlw::explore::Predictor::paper(22.0).unwrap();
    for (joint, file, p) in [
        ("A", "joint-a.toml", &predictor),
        ("B", "joint-b.toml", &predictor_b),
        ("C", "joint-c.toml", &predictor),
    ] {
        let text = std::fs::read_to_string(common::shipped_design(file)).unwrap();
        let design = dlw::design::Design::from_toml(&text).unwrap();
        let predicted = p.predict(&design).unwrap();
        let x = j["joints"]
            .as_array()
            .unwrap()
            .iter()
            .find(|x| x["joint"] == joint)
            .unwrap();
        for (model, full, pred) in [
            ("linear", rmse(x, "linear"), predicted.linear_rmse_deg),
            ("PI", rmse(x, "PI"), predicted.pi_rmse_deg),
        ] {
            eprintln!("Joint {joint} {model}: predicted {pred:.2}°, full {full:.2}°");
            assert!(
                (pred / full - 1.0).abs() <= 0.30,
                "Joint {joint} {model}: predicted {pred:.2}°, full simulation {full:.2}°"
            );
        }
    }
}

/// The trade-offs the shipped twin records (`[[calibration.tradeoffs]]`, which the report's
/// finding reads) are what the simulator measures: each value of each parameter set on the
/// shipped bench, the parameter's joint run at full size with seed 0 (`reproduce::tables_of`, the same
/// numbers `dlw reproduce` prints), every recorded metric within 1e-6 of the recorded value.
/// Ten full-size runs of one joint, about a minute in release: with `DLW_TWIN_TRADEOFF=1`.
#[test]
fn the_twins_recorded_tradeoffs_are_measured() {
    use dlw::reproduce::{tables_of, Bench, Settings};
    if std::env::var_os("DLW_TWIN_TRADEOFF").is_none() {
        eprintln!("skipped: set DLW_TWIN_TRADEOFF=1 (the twin's trade-offs re-measured)");
        return;
    }
    let Bench::Twin(file) = Bench::paper().unwrap() else {
        panic!("the shipped bench is not a twin")
    };
    let tradeoffs = file.calibration.as_ref().unwrap().tradeoffs.clone();
    assert!(!tradeoffs.is_empty());
    for t in &tradeoffs {
        let letter = t.parameter.chars().next().unwrap();
        for (k, &v) in t.values.iter().enumerate() {
            let mut f = file.clone();
            let joint = f.joint.get_mut(&letter.to_string()).unwrap();
            match t.parameter.split_once('.').unwrap().1 {
                "sensor1.noise_ppm" => {
                    joint.sensor1.noise.enabled = v > 0.0;
                    if v > 0.0 {
                        joint.sensor1.noise.sigma_ppm = v;
                    }
                }
                "sensor1.noise_tau_s" => joint.sensor1.noise.tau_s = v,
                other => panic!("the test does not set {other}"),
            }
            let run = tables_of(&Settings::new(1.0, Bench::Twin(f)), &[letter]).unwrap();
            let all = dlw::calibrate::Metric::all();
            let values = dlw::calibrate::measure(&run);
            for (name, recorded) in &t.metrics {
                let i = all.iter().position(|m| m.name() == *name).unwrap();
                let measured = values[i].unwrap();
                eprintln!(
                    "{} = {v}: {name} {measured} (recorded {})",
                    t.parameter, recorded[k]
                );
                assert!(
                    (measured / recorded[k] - 1.0).abs() < 1e-6,
                    "{} = {v}: {name} measured {measured}, recorded {}",
                    t.parameter,
                    recorded[k]
                );
            }
        }
    }
}

/// Tables IV-VI's numbers of the issue: name, the twin's, the paper's.
fn paper_numbers(j: &serde_json::Value) -> Vec<(String, f64, f64)> {
    let joints = j["joints"].as_array().unwrap();
    let two = |role: &str| {
        joints[2]["estimation"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["role"] == role)
            .unwrap()["rmse_deg"]
            .as_f64()
            .unwrap()
    };
    let mut out = Vec::new();
    for (x, [lin, pi]) in joints
        .iter()
        .zip([[2.76, 1.76], [3.51, 2.65], [5.25, 7.57]])
    {
        let name = x["joint"].as_str().unwrap();
        out.push((
            format!("Table IV Joint {name} linear"),
            rmse(x, "linear"),
            lin,
        ));
        out.push((format!("Table IV Joint {name} PI"), rmse(x, "PI"), pi));
    }
    out.push(("Table V compression".into(), two("compression"), 3.84));
    out.push(("Table V both".into(), two("both"), 3.13));
    let ad = |k: &str| j[k]["actual_vs_desired_rmse_deg"].as_f64().unwrap();
    out.push(("Table VI open loop".into(), ad("control_open_loop"), 8.14));
    out.push((
        "Table VI closed loop".into(),
        ad("control_closed_loop"),
        2.92,
    ));
    out
}

/// Table III's numbers the paper prints for Joint `i` (0 = A), Joint C's `R_peak` read as
/// 75.4 kΩ: GF, R₀, R_c, ε_c, m_c, R_peak, ε_peak.
fn paper_table_iii(i: usize) -> [f64; 7] {
    [
        [15.3, 215e3, 224e3, 0.00307, 5136e3, 250e3, 0.0135],
        [22.0, 77.2e3, 87.9e3, 0.00531, 3090e3, 99.2e3, 0.0157],
        [1.28, 74.0e3, 74.7e3, 0.00804, 181e3, 75.4e3, 0.0137],
    ][i]
}

/// The ideal bench's Table III at full size (`dlw reproduce --ideal`, measured before the twin
/// existed, docs/experiments.md): the "current agreement" the twin must keep.
const IDEAL_TABLE_III: [[f64; 7]; 3] = [
    [
        13.868, 214502.0, 217317.0, 0.0014167, 4680742.0, 246869.0, 0.0145858,
    ],
    [
        21.506, 78508.0, 81449.0, 0.0024514, 1515709.0, 97892.0, 0.0145594,
    ],
    [
        1.1998, 73981.0, 74107.0, 0.0015411, 158271.0, 75360.0, 0.0145668,
    ],
];

/// Numbers of Tables IV-VI the shipped twin does not bring within 25 % of the paper's: Joint
/// C's PI error. The twin met it until the PI fit's radius was bounded (5288602): the 5.99°
/// came from a fit that failed; with the bounded fit no point the calibration measured puts
/// Joint C's PI above its line (docs/experiments.md, "The bounded PI fit and the twin on four
/// seeds"), and the report's finding says so from the recorded trade-off.
const UNMET: [&str; 1] = ["Table IV Joint C PI"];

/// The patterns the shipped twin does not hold: Joint C's, the same fact as its unmet PI error
/// ([`UNMET`]). (The first twin's correlated tracker error, 0.79° with a 10 s time constant,
/// spoiled Joints A-C's relaxation fits; it is held off now.)
const TWIN_NOT_HELD: [&str; 1] = ["linear beats PI for Joint C (Table IV)"];

/// The patterns the shipped twin cannot show: none (the first twin's Table V sensors erred 3.3
/// times apart; each sensor's own noise now makes them err comparably).
const TWIN_CANNOT_SHOW: [&str; 0] = [];

/// Table III's rows, as the twin test names them.
const TABLE_III_ROWS: [&str; 7] = ["GF", "R0", "R_c", "eps_c", "m_c", "R_peak", "eps_peak"];

/// Table III numbers of the shipped twin further from the paper than the ideal bench's plus 5
/// points: Joint A's steepest slope, which its sensor's noise inflates (docs/experiments.md).
const TABLE_III_NOT_KEPT: [&str; 1] = ["A.m_c"];

/// The headline numbers of a reproduction, one per line, rounded to what a reader compares:
/// every RMSE of Tables IV-V (per joint, model and sensors), the fitted GFs and R₀, Table VI's
/// three RMSEs per scheme. A change that moves one shows up as a snapshot diff in review
/// (`cargo insta review`, or `INSTA_UPDATE=always` to accept).
fn headline(j: &serde_json::Value) -> String {
    let mut out = String::new();
    for joint in j["joints"].as_array().unwrap() {
        let name = joint["joint"].as_str().unwrap();
        out += &format!(
            "Joint {name}: GF {:.3}, R0 {:.0} ohm\n",
            joint["gauge_factor"].as_f64().unwrap(),
            joint["r0_ohm"].as_f64().unwrap()
        );
        for e in joint["estimation"].as_array().unwrap() {
            out += &format!(
                "Joint {name} {} ({}): RMSE {:.2} deg\n",
                e["config"].as_str().unwrap(),
                e["role"].as_str().unwrap(),
                e["rmse_deg"].as_f64().unwrap()
            );
        }
    }
    for (scheme, key) in [
        ("open loop", "control_open_loop"),
        ("closed loop", "control_closed_loop"),
    ] {
        let m = &j[key];
        out += &format!(
            "Joint D {scheme}: sensed vs actual {:.2}, actual vs desired {:.2}, sensed vs desired {:.2} deg\n",
            m["sensed_vs_actual_rmse_deg"].as_f64().unwrap(),
            m["actual_vs_desired_rmse_deg"].as_f64().unwrap(),
            m["sensed_vs_desired_rmse_deg"].as_f64().unwrap()
        );
    }
    out
}

/// Patterns the simulated joints cannot show, by a property of theirs that the run measures
/// (`reproduce::patterns`): Joint C's simulated sensor is Table III's PI model (the line leaves
/// 3.4 times the PI fit's residual), and its two sensors' errors differ by more than √3 (the
/// simulated compression sensor is linear).
const KNOWN_CANNOT_SHOW: [&str; 2] = [
    "linear beats PI for Joint C (Table IV)",
    "both sensors beat each sensor alone (Joint C, Table V)",
];
