//! `dlw simulate` through the binary: every protocol writes a recording folder in the bench
//! format, runs are deterministic per seed, and failures leave nothing behind.

use crate::common;
use common::{dlw, shipped_design as design};

use std::path::{Path, PathBuf};
use std::process::Output;

fn simulate(design_file: &str, protocol: &str, out: &Path, extra: &[&str]) -> Output {
    let out = out.display().to_string();
    let mut args = vec![
        "simulate",
        "--design",
        design_file,
        "--protocol",
        protocol,
        "-o",
        &out,
    ];
    args.extend_from_slice(extra);
    dlw(&args)
}

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "dlw failed: {}\n{}",
        String::from_utf8_lossy(&o.stderr),
        String::from_utf8_lossy(&o.stdout)
    );
}

/// Checks the folder holds a recording with `channels` voltage columns and `rows` samples at
/// 500 Hz, with strictly increasing time; returns data.csv's text.
fn check_recording(dir: &Path, channels: usize, rows: usize) -> String {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["data.csv", "rig.toml"]);
    let text = std::fs::read_to_string(dir.join("data.csv")).unwrap();
    let mut lines = text.lines();
    let header = if channels == 2 {
        "time_s,stroke_mm,angle_deg,v1_V,v2_V"
    } else {
        "time_s,stroke_mm,angle_deg,v1_V"
    };
    assert_eq!(lines.next(), Some(header));
    let mut previous = f64::NEG_INFINITY;
    let mut count = 0;
    for line in lines {
        let fields: Vec<f64> = line.split(',').map(|f| f.parse().unwrap()).collect();
        assert_eq!(fields.len(), 3 + channels, "{line}");
        assert!(fields[0] > previous, "time not increasing at {line}");
        assert!(fields[3..].iter().all(|v| *v > 0.0 && *v < 5.0), "{line}");
        previous = fields[0];
        count += 1;
    }
    assert_eq!(count, rows);
    assert!((previous - (rows - 1) as f64 / 500.0).abs() < 1e-9);
    let rig: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join("rig.toml")).unwrap()).unwrap();
    assert_eq!(rig["sample_hz"].as_float(), Some(500.0));
    assert_eq!(rig["supply_v"].as_float(), Some(5.0));
    assert_eq!(rig["divider_ohm"].as_array().unwrap().len(), channels);
    assert!(rig["design"].get("notch_count").is_some());
    assert!(rig["scenario"].get("seed").is_some());
    text
}

#[test]
fn every_protocol_writes_a_recording() {
    let dir = tempfile::tempdir().unwrap();
    let profile = dir.path().join("profile.csv");
    std::fs::write(&profile, "time_s,stroke_mm\n0,0\n5,1.2\n10,0.4\n20,0\n").unwrap();
    let profile = profile.display().to_string();
    let cases: [(&str, &[&str]); 5] = [
        ("characterization", &[]),
        ("rate-dependence", &[]),
        ("relaxation", &[]),
        ("random", &[]),
        ("custom", &["--profile", &profile]),
    ];
    for (protocol, extra) in cases {
        for (design_file, channels) in [("joint-d.toml", 1), ("joint-c.toml", 2)] {
            let out = dir.path().join(format!("{protocol}-{design_file}"));
            let mut args = vec!["--duration-s", "12.5"];
            args.extend_from_slice(extra);
            ok(&simulate(&design(design_file), protocol, &out, &args));
            let text = check_recording(&out, channels, 6250);
            if protocol != "custom" {
                starts_at_rest(&text, 10.0);
            }
        }
    }
}

/// Every row up to `rest_s` has zero stroke, and the joint moves within a second after.
fn starts_at_rest(csv: &str, rest_s: f64) {
    let rows: Vec<(f64, f64)> = csv
        .lines()
        .skip(1)
        .map(|l| {
            let mut f = l.split(',').map(|x| x.parse::<f64>().unwrap());
            (f.next().unwrap(), f.next().unwrap())
        })
        .collect();
    let still = rows.iter().take_while(|(t, _)| *t <= rest_s);
    assert_eq!(still.clone().count(), (rest_s * 500.0) as usize + 1);
    assert!(
        still.clone().all(|(_, s)| *s == 0.0),
        "moves before {rest_s} s"
    );
    assert!(
        rows.iter()
            .any(|(t, s)| *t > rest_s && *t < rest_s + 1.0 && *s > 0.0),
        "does not move after {rest_s} s"
    );
}

/// `protocols.rest_start_s` sets the rest; 0 starts moving at once.
#[test]
fn the_rest_at_the_start_is_a_scenario_key() {
    let dir = tempfile::tempdir().unwrap();
    for rest in [0.0, 3.0, 25.0] {
        let scenario = dir.path().join("s.toml");
        std::fs::write(&scenario, format!("[protocols]\nrest_start_s = {rest:?}\n")).unwrap();
        let out = dir.path().join(format!("rec-{rest}"));
        ok(&simulate(
            &design("joint-a.toml"),
            "relaxation",
            &out,
            &[
                "--scenario",
                &scenario.display().to_string(),
                "--duration-s",
                "30",
            ],
        ));
        let text = check_recording(&out, 1, 15_000);
        if rest > 0.0 {
            starts_at_rest(&text, rest);
        } else {
            let second_row = text.lines().nth(2).unwrap();
            let stroke: f64 = second_row.split(',').nth(1).unwrap().parse().unwrap();
            assert!(stroke > 0.0, "{second_row}");
        }
    }
}

#[test]
fn default_durations_are_the_protocols() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("char");
    let o = simulate(&design("joint-a.toml"), "characterization", &out, &[]);
    ok(&o);
    // The paper's 5 × 200 s after 10 s at rest.
    check_recording(&out, 1, 505_000);
    let text = std::fs::read_to_string(out.join("rig.toml")).unwrap();
    assert!(text.contains("duration_s = 1010.0"), "{text}");
    // A CSV profile runs to its last time.
    let profile = dir.path().join("p.csv");
    std::fs::write(&profile, "time_s,stroke_mm\n0,0\n3,1\n").unwrap();
    let out = dir.path().join("custom");
    ok(&simulate(
        &design("joint-a.toml"),
        "custom",
        &out,
        &["--profile", &profile.display().to_string()],
    ));
    check_recording(&out, 1, 1500);
}

#[test]
fn same_seed_same_bytes_other_seed_other_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, seed: &str| -> Vec<u8> {
        let out = dir.path().join(name);
        ok(&simulate(
            &design("joint-d.toml"),
            "random",
            &out,
            &["--seed", seed, "--duration-s", "20"],
        ));
        std::fs::read(out.join("data.csv")).unwrap()
    };
    let a = run("a", "42");
    let b = run("b", "42");
    let c = run("c", "43");
    assert_eq!(a, b);
    assert_ne!(a, c);
}

#[test]
fn scenario_file_switches_effects_and_is_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("s.toml");
    std::fs::write(
        &scenario,
        "seed = 5\n[plant.relaxation]\nenabled = true\nfraction = 0.1\n[sensor1]\nmodel = \"pi\"\n[tracker]\nenabled = false\n",
    )
    .unwrap();
    let out = dir.path().join("rec");
    let s = scenario.display().to_string();
    ok(&simulate(
        &design("joint-a.toml"),
        "relaxation",
        &out,
        &["--scenario", &s, "--duration-s", "10"],
    ));
    let rig = std::fs::read_to_string(out.join("rig.toml")).unwrap();
    let rig: toml::Table = toml::from_str(&rig).unwrap();
    let sc = &rig["scenario"];
    assert_eq!(sc["seed"].as_integer(), Some(5));
    assert_eq!(sc["plant"]["relaxation"]["fraction"].as_float(), Some(0.1));
    assert_eq!(sc["sensor1"]["model"].as_str(), Some("pi"));
    assert_eq!(sc["sensor1"]["pi"]["weights"].as_array().unwrap().len(), 10);
    // The recorded scenario and design are themselves a scenario and a design file that
    // reproduce the run.
    let again = dir.path().join("again.toml");
    std::fs::write(&again, toml::to_string(sc).unwrap()).unwrap();
    let design_again = dir.path().join("design.toml");
    std::fs::write(&design_again, toml::to_string(&rig["design"]).unwrap()).unwrap();
    let out2 = dir.path().join("rec2");
    ok(&dlw(&[
        "simulate",
        "--design",
        &design_again.display().to_string(),
        "--scenario",
        &again.display().to_string(),
        "-o",
        &out2.display().to_string(),
    ]));
    assert_eq!(
        std::fs::read(out.join("data.csv")).unwrap(),
        std::fs::read(out2.join("data.csv")).unwrap()
    );
}

fn entries(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    v.sort();
    v
}

#[test]
fn bad_input_fails_clearly_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let bad_scenario = dir.path().join("bad.toml");
    std::fs::write(&bad_scenario, "[plant.relaxation]\nfraction = 2.0\n").unwrap();
    let typo = dir.path().join("typo.toml");
    std::fs::write(&typo, "[adc]\nnoise_mv = 2.0\n").unwrap();
    let bad_profile = dir.path().join("p.csv");
    std::fs::write(&bad_profile, "time_s,stroke_mm\n0,0\n1,0.5\n0.5,0\n").unwrap();
    let before = entries(dir.path());
    let out = dir.path().join("out");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["--protocol".into(), "sinus".into()],
            "unknown protocol \"sinus\"",
        ),
        (vec![], "no protocol chosen"),
        (
            vec![
                "--protocol".into(),
                "random".into(),
                "--scenario".into(),
                bad_scenario.display().to_string(),
            ],
            "plant.relaxation.fraction = 2",
        ),
        (
            vec![
                "--protocol".into(),
                "random".into(),
                "--scenario".into(),
                typo.display().to_string(),
            ],
            "noise_mv",
        ),
        (
            vec!["--protocol".into(), "custom".into()],
            "needs a stroke profile",
        ),
        (
            vec![
                "--protocol".into(),
                "custom".into(),
                "--profile".into(),
                bad_profile.display().to_string(),
            ],
            "line 4: time_s = 0.5 does not increase",
        ),
        (
            vec![
                "--protocol".into(),
                "random".into(),
                "--duration-s=-3".into(),
            ],
            "duration_s = -3",
        ),
    ];
    for (extra, needle) in cases {
        let mut args: Vec<String> = vec![
            "simulate".into(),
            "--design".into(),
            design("joint-d.toml"),
            "-o".into(),
            out.display().to_string(),
        ];
        args.extend(extra);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert_eq!(entries(dir.path()), before, "{args:?} left files behind");
    }
}

#[test]
fn existing_output_is_kept_unless_forced() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("rec");
    ok(&simulate(
        &design("joint-d.toml"),
        "random",
        &out,
        &["--duration-s", "1", "--seed", "1"],
    ));
    let first = std::fs::read(out.join("data.csv")).unwrap();
    let o = simulate(
        &design("joint-d.toml"),
        "random",
        &out,
        &["--duration-s", "1", "--seed", "2"],
    );
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("already exists"));
    assert_eq!(std::fs::read(out.join("data.csv")).unwrap(), first);
    ok(&simulate(
        &design("joint-d.toml"),
        "random",
        &out,
        &["--duration-s", "1", "--seed", "2", "--force"],
    ));
    assert_ne!(std::fs::read(out.join("data.csv")).unwrap(), first);
    assert_eq!(entries(dir.path()), vec![out]);
}
