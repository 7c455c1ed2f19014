//! `dlw characterize` through the binary, on short simulated recordings whose effects are known:
//! the loops' fits against the simulator's constants, the rate analysis with and without a
//! rate effect (and with and without drift), the relaxation time constant against the
//! scenario's, the estimation RMSE against `dlw estimate`'s, one- and two-sensor joints (Joint C
//! is BSN), and bad input (the wrong kind for a recording, no config, no holds) refused with a
//! clear message and nothing written.

use crate::common;
use common::shipped_design;

use std::path::{Path, PathBuf};

/// Fast protocol timings, so that every test recording is a few minutes long at most.
const FAST: &str = r#"
[protocols]
rest_start_s = 2.0
[protocols.characterization]
full_rise_s = 8.0
rest_s = 1.0
[protocols.rate-dependence]
rise_s = [2.0, 4.0, 6.0, 8.0, 10.0]
repeat_s = 72.0
[protocols.relaxation]
repeat_s = 120.0
ramp_s = 1.0
[protocols.random]
repeat_s = 60.0
"#;

use common::{arg as s, dlw_ok as ok};

/// `dlw simulate` of `design` with the fast timings plus `extra` scenario text.
fn simulate(
    dir: &Path,
    name: &str,
    design: &str,
    protocol: &str,
    secs: u32,
    extra: &str,
) -> PathBuf {
    let out = dir.join(name);
    let file = dir.join(format!("{name}.scenario.toml"));
    std::fs::write(&file, format!("{extra}\n{FAST}")).unwrap();
    ok(&[
        "simulate",
        "--design",
        &shipped_design(design),
        "--protocol",
        protocol,
        "--duration-s",
        &secs.to_string(),
        "--seed",
        "3",
        "--scenario",
        &s(&file),
        "-o",
        &s(&out),
    ]);
    out
}

/// `dlw characterize --json` with `extra` arguments into `out`.
fn characterize(design: &str, rec: &Path, out: &Path, extra: &[&str]) -> serde_json::Value {
    let design = shipped_design(design);
    let (rec, out) = (s(rec), s(out));
    let mut args = vec![
        "characterize",
        "--design",
        &design,
        &rec,
        "-o",
        &out,
        "--json",
    ];
    args.extend_from_slice(extra);
    let o = ok(&args);
    serde_json::from_slice(&o.stdout).expect("--json prints JSON")
}

fn f(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("{v} is not a number"))
}

/// The report's figures exist, are SVG and are referenced by the page.
fn check_report(dir: &Path, figures: &[&str]) -> String {
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    for name in figures {
        let file = format!("{name}.svg");
        assert!(
            html.contains(&format!("src=\"{file}\"")),
            "{file} not in the page"
        );
        let svg = std::fs::read_to_string(dir.join(&file)).unwrap();
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    assert!(!html.contains("NaN"), "NaN in the report");
    html
}

#[test]
fn loops_recover_the_simulated_gauge_factor_and_draw_fig_4() {
    let dir = tempfile::tempdir().unwrap();
    let rec = simulate(
        dir.path(),
        "char",
        "joint-a.toml",
        "characterization",
        100,
        "[sensor1]\nmodel = \"pi\"\n",
    );
    let out = dir.path().join("loops");
    // No --kind: the recorded protocol (characterization) chooses loops.
    let j = characterize("joint-a.toml", &rec, &out, &["--order", "3"]);
    assert_eq!(j["kind"], "loops");
    let s = &j["sensors"][0];
    assert_eq!(s["sensor"], "v1_V");
    // The simulator's PI sensor is Table III's Joint A: its characteristic points come back.
    let c = &s["characteristic"];
    assert!((f(&c["peak_ohm"]) / 250e3 - 1.0).abs() < 0.03, "{c}");
    assert!((f(&c["peak_strain"]) - 0.015).abs() < 0.001, "{c}");
    // 5 cycles per 40 s repetition, two repetitions and a half.
    assert!(s["cycles"].as_u64().unwrap() >= 8, "{s}");
    // The PI model fits the PI sensor better than the line does.
    assert!(f(&s["pi_rmse_ohm"]) < f(&s["linear_rmse_ohm"]), "{s}");
    let html = check_report(&out, &["stroke", "strain", "delta-r", "loops-v1"]);
    assert!(html.contains("Table III") || html.contains("Fig. 4"));
}

#[test]
fn rate_finds_no_effect_where_there_is_none_and_finds_one_where_there_is() {
    let dir = tempfile::tempdir().unwrap();
    let none = simulate(
        dir.path(),
        "flat",
        "joint-a.toml",
        "rate-dependence",
        290,
        "",
    );
    let j = characterize("joint-a.toml", &none, &dir.path().join("flat-r"), &[]);
    assert_eq!(j["kind"], "rate");
    let s = &j["sensors"][0];
    assert!(s["cycles"].as_array().unwrap().len() >= 15, "{s}");
    let change = f(&s["gf_relative_change"]);
    assert!(
        change.abs() < 0.005,
        "GF changes {change} without a rate effect"
    );
    // The rise times are the protocol's 2 to 10 s.
    let rises: Vec<f64> = s["cycles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| f(&c["rise_s"]))
        .collect();
    for want in [2.0, 4.0, 6.0, 8.0, 10.0] {
        assert!(
            rises.iter().any(|r| (r - want).abs() < 0.4),
            "{want} s not in {rises:?}"
        );
    }
    // A log rate effect of 0.5 per decade: faster cycles read a higher GF.
    let with = simulate(
        dir.path(),
        "fast",
        "joint-a.toml",
        "rate-dependence",
        290,
        "[sensor1.rate]\nper_decade = 0.5\n",
    );
    let j = characterize("joint-a.toml", &with, &dir.path().join("fast-r"), &[]);
    let s = &j["sensors"][0];
    let r = f(&s["gf_rise_correlation"]);
    assert!(r < -0.8, "correlation {r} with a rate effect");
    assert!(f(&s["gf_relative_change"]) < -0.03, "{s}");
    check_report(&dir.path().join("fast-r"), &["rate-gf-v1", "rate-r0-v1"]);
    // Drift spreads R₀ from cycle to cycle; without it R₀ barely moves.
    let drift = simulate(
        dir.path(),
        "drift",
        "joint-a.toml",
        "rate-dependence",
        290,
        "[sensor1.drift]\nrandom_walk_ohm_per_sqrt_s = 60.0\n",
    );
    let still = f(
        &characterize("joint-a.toml", &none, &dir.path().join("a"), &[])["sensors"][0]
            ["r0_std_ohm"],
    );
    let drifting = f(
        &characterize("joint-a.toml", &drift, &dir.path().join("b"), &[])["sensors"][0]
            ["r0_std_ohm"],
    );
    assert!(
        drifting > 5.0 * still,
        "R₀ spread {drifting} Ω with drift, {still} Ω without"
    );
}

#[test]
fn relaxation_recovers_the_time_constant_on_both_sensors_of_joint_c() {
    let dir = tempfile::tempdir().unwrap();
    let rec = simulate(
        dir.path(),
        "relax",
        "joint-c.toml",
        "relaxation",
        242,
        "[plant.relaxation]\nfraction = 0.2\ntau_s = 3.0\n",
    );
    let out = dir.path().join("r");
    let j = characterize("joint-c.toml", &rec, &out, &[]);
    assert_eq!(j["kind"], "relaxation");
    let sensors = j["sensors"].as_array().unwrap();
    assert_eq!(sensors.len(), 2, "a BSN recording analyses both sensors");
    for s in sensors {
        let holds = s["holds"].as_array().unwrap();
        // Four up and three down per 120 s repetition (the hold at zero stroke is a rest).
        assert_eq!(holds.len(), 14, "{s}");
        let tau = f(&s["median_tau_s"]);
        assert!(
            (tau - 3.0).abs() < 0.45,
            "median τ {tau} s, the scenario's 3 s"
        );
        // The angle decays while the stroke is held after a step up, and recovers after a step
        // down; the strain of the compression sensor moves the other way.
        let sign = if s["sensor"].as_str().unwrap().contains("compression") {
            -1.0
        } else {
            1.0
        };
        assert!(sign * f(&holds[0]["strain_decay"]) > 0.0, "{s}");
        assert!(sign * f(&holds[4]["strain_decay"]) < 0.0, "{s}");
        // The simulated sensor reads the relaxed strain, so ΔR follows Δε.
        assert!(f(&s["correlation"]) > 0.5, "{s}");
        let share = f(&s["followed_share"]);
        assert!((0.7..1.3).contains(&share), "share {share}");
    }
    check_report(
        &out,
        &[
            "relax-strain-v1",
            "relax-r-v1",
            "relax-strain-v2",
            "relax-r-v2",
        ],
    );
    // Without relaxation, the strain does not decay (with fraction 0.2 it decays by about 6e-4).
    let flat = simulate(dir.path(), "flat", "joint-a.toml", "relaxation", 122, "");
    let j = characterize("joint-a.toml", &flat, &dir.path().join("f"), &[]);
    for h in j["sensors"][0]["holds"].as_array().unwrap() {
        assert!(f(&h["strain_decay"]).abs() < 6e-5, "{h}");
    }
}

#[test]
fn estimation_matches_dlw_estimate_and_splits_a_two_sensor_config() {
    let dir = tempfile::tempdir().unwrap();
    let rec = simulate(dir.path(), "rand", "joint-a.toml", "random", 62, "");
    let config = |name: &str, gf: &str| {
        let p = dir.path().join(name);
        ok(&[
            "estimator-config",
            &shipped_design("joint-a.toml"),
            "--gauge-factor",
            gf,
            "--r0-ohm",
            "215e3",
            "-o",
            &s(&p),
        ]);
        p
    };
    let good = config("good.toml", "15.3");
    let wrong = config("wrong.toml", "19.9");
    let out = dir.path().join("est");
    let j = characterize(
        "joint-a.toml",
        &rec,
        &out,
        &["--config", &s(&good), "--config", &s(&wrong)],
    );
    assert_eq!(j["kind"], "estimation");
    let runs = j["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    let est = ok(&[
        "estimate",
        "--config",
        &s(&good),
        &s(&rec),
        "--json",
        "-o",
        &s(&dir.path().join("e.csv")),
    ]);
    let est: serde_json::Value = serde_json::from_slice(&est.stdout).unwrap();
    assert_eq!(f(&runs[0]["rmse_deg"]), f(&est["rmse_deg"]));
    assert!(
        f(&runs[1]["rmse_deg"]) > 3.0 * f(&runs[0]["rmse_deg"]),
        "{runs:?}"
    );
    check_report(&out, &["estimates"]);
    // The paper's processing: a 1000-sample average, 1 s of delay.
    let j = characterize(
        "joint-a.toml",
        &rec,
        &dir.path().join("p"),
        &["--config", &s(&good), "--paper-processing"],
    );
    assert_eq!(f(&j["runs"][0]["filter_delay_s"]), 0.999);

    // Joint C: tension alone, compression alone and both (Table V).
    let rec = simulate(dir.path(), "randc", "joint-c.toml", "random", 62, "");
    let two = dir.path().join("c.toml");
    let design = shipped_design("joint-c.toml");
    let out = s(&two);
    let mut args = vec!["estimator-config", &design];
    args.extend(common::JOINT_C_TABLE_V);
    args.extend(["-o", &out]);
    ok(&args);
    let j = characterize(
        "joint-c.toml",
        &rec,
        &dir.path().join("c"),
        &["--config", &s(&two), "--paper-processing"],
    );
    let runs = j["runs"].as_array().unwrap();
    let kinds: Vec<&str> = runs.iter().map(|r| r["role"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["tension", "compression", "both"]);
    let sensors: Vec<&str> = runs
        .iter()
        .map(|r| r["sensors"].as_str().unwrap())
        .collect();
    assert_eq!(sensors, ["sensor1", "sensor2", "both"]);
    let rmse: Vec<f64> = runs.iter().map(|r| f(&r["rmse_deg"])).collect();
    assert!(rmse.iter().all(|r| r.is_finite() && *r < 4.0), "{rmse:?}");
    assert!(rmse[2] <= rmse[0].max(rmse[1]), "{rmse:?}");
    // A wrong compression sensor spoils the compression-alone run and not the tension-alone one:
    // each run reads its own column.
    let bad = dir.path().join("c-bad.toml");
    let text = std::fs::read_to_string(&two).unwrap();
    let edited = text.replacen("gauge_factor = 0.68", "gauge_factor = 1.2", 1);
    assert_ne!(text, edited, "{text}");
    std::fs::write(&bad, edited).unwrap();
    let j = characterize(
        "joint-c.toml",
        &rec,
        &dir.path().join("c-bad"),
        &["--config", &s(&bad), "--paper-processing"],
    );
    let worse: Vec<f64> = j["runs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| f(&r["rmse_deg"]))
        .collect();
    assert_eq!(worse[0], rmse[0]);
    assert!(worse[1] > 2.0 * rmse[1], "{worse:?} against {rmse:?}");
}

#[test]
fn bad_input_is_refused_with_a_clear_message_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let char = simulate(
        dir.path(),
        "char",
        "joint-a.toml",
        "characterization",
        60,
        "",
    );
    let rand = simulate(dir.path(), "rand", "joint-a.toml", "random", 20, "");
    let design = shipped_design("joint-a.toml");
    let out = dir.path().join("out");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![s(&char), "--kind".into(), "relaxation".into()],
            "no holds longer than 5 s found",
        ),
        (
            vec![s(&char), "--kind".into(), "rate".into()],
            "the rate analysis needs",
        ),
        (
            vec![s(&rand)],
            "estimation needs at least one estimator config",
        ),
        (
            vec![
                s(&char),
                "--config".into(),
                s(&dir.path().join("none.toml")),
                "--kind".into(),
                "estimation".into(),
            ],
            "none.toml",
        ),
        (
            vec![s(&char), "--min-hold-s=-1".into()],
            "--min-hold-s -1 must be finite and greater than 0",
        ),
        (
            vec![
                s(&rand),
                "--kind".into(),
                "loops".into(),
                "--config".into(),
                s(&char),
            ],
            "--config is for --kind estimation",
        ),
    ];
    for (extra, needle) in cases {
        let mut args = vec![
            "characterize".to_owned(),
            "--design".into(),
            design.clone(),
            "-o".into(),
            s(&out),
        ];
        args.extend(extra);
        let o = common::dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
    // A recording whose rig.toml names no protocol (a real bench's) needs --kind.
    let rig = std::fs::read_to_string(char.join("rig.toml")).unwrap();
    let stripped: String = rig
        .lines()
        .filter(|l| !l.starts_with("protocol = "))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(rig, stripped);
    std::fs::write(char.join("rig.toml"), stripped).unwrap();
    let o = common::dlw(&[
        "characterize",
        "--design",
        &design,
        &s(&char),
        "-o",
        &s(&out),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("pass --kind loops|rate|relaxation|estimation"),
        "{err}"
    );
    assert!(!out.exists());
    ok(&[
        "characterize",
        "--design",
        &design,
        &s(&char),
        "--kind",
        "loops",
        "--order",
        "3",
        "-o",
        &s(&out),
    ]);
    assert!(out.join("report.html").exists());
    std::fs::remove_dir_all(&out).unwrap();
    // A two-column recording on a UAN design.
    let c = simulate(dir.path(), "c", "joint-c.toml", "relaxation", 60, "");
    let o = common::dlw(&["characterize", "--design", &design, &s(&c), "-o", &s(&out)]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("2 voltage column(s)"));
    assert!(!out.exists());
}
