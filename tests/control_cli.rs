//! `dlw control` through the binary: closed loop beats open loop on a relaxing plant, a wrong
//! sensor config makes closed loop worse (the estimator is in the loop), the outputs are
//! complete and consistent, and bad input is refused with a clear error and no output.

use crate::common;
use common::{dlw, shipped_design};

use std::path::{Path, PathBuf};

/// Joint D's bench with relaxation and backlash (the drift the paper's open loop shows) and the
/// default noise and linear sensor (GF 15.3, R₀ 215 kΩ).
const RELAXING: &str = "seed = 2\n[plant.relaxation]\nenabled = true\nfraction = 0.15\n\
[plant.backlash]\nenabled = true\nwidth_mm = 0.1\n";

struct Setup {
    dir: tempfile::TempDir,
}

impl Setup {
    fn new() -> Self {
        let s = Self {
            dir: tempfile::tempdir().unwrap(),
        };
        std::fs::write(s.path("relaxing.toml"), RELAXING).unwrap();
        s.config("d.toml", 15.3);
        s
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn p(&self, name: &str) -> String {
        self.path(name).display().to_string()
    }

    /// A nominal linear config for Joint D with gauge factor `gf`.
    fn config(&self, name: &str, gf: f64) {
        let o = dlw(&[
            "estimator-config",
            &shipped_design("joint-d.toml"),
            "--gauge-factor",
            &gf.to_string(),
            "--r0-ohm",
            "215e3",
            "-o",
            &self.p(name),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }

    /// `dlw control` on Joint D with `config`, `extra` arguments, into `out`.
    fn control(&self, config: &str, out: &str, extra: &[&str]) -> std::process::Output {
        let design = shipped_design("joint-d.toml");
        let (config, out) = (self.p(config), self.p(out));
        let mut args = vec![
            "control", "--design", &design, "--config", &config, "-o", &out,
        ];
        args.extend_from_slice(extra);
        dlw(&args)
    }

    /// Runs `control --json` and returns the parsed report.
    fn json(&self, config: &str, out: &str, extra: &[&str]) -> serde_json::Value {
        let mut args = vec!["--json"];
        args.extend_from_slice(extra);
        let o = self.control(config, out, &args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    }
}

fn rmse(report: &serde_json::Value, scheme: &str, key: &str) -> f64 {
    report[scheme][key]
        .as_f64()
        .unwrap_or_else(|| panic!("{scheme}.{key} in {report}"))
}

const RANDOM_150S: [&str; 8] = [
    "--scenario",
    "",
    "--protocol",
    "random",
    "--duration-s",
    "150",
    "--filter",
    "ma:50",
];

fn random_150s(s: &Setup) -> Vec<String> {
    let mut v: Vec<String> = RANDOM_150S.iter().map(|a| a.to_string()).collect();
    v[1] = s.p("relaxing.toml");
    v
}

#[test]
fn closed_loop_reduces_tracking_error_on_a_relaxing_plant() {
    let s = Setup::new();
    let args = random_150s(&s);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let r = s.json("d.toml", "out", &args);
    let open = rmse(&r, "open_loop", "actual_vs_desired_rmse_deg");
    let closed = rmse(&r, "closed_loop", "actual_vs_desired_rmse_deg");
    assert!(
        open > 1.5,
        "the relaxing plant should drift in open loop: {r}"
    );
    assert!(closed < 0.5 * open, "closed {closed}° vs open {open}°: {r}");
    assert!(
        rmse(&r, "closed_loop", "sensed_vs_desired_rmse_deg")
            < rmse(&r, "open_loop", "sensed_vs_desired_rmse_deg")
    );
    assert_eq!(r["samples"], 75_000);
    assert_eq!(r["mt_deg_per_mm"], 35.49);
    assert_eq!(r["mt_source"], "plant_gain");
    assert_eq!(r["gains"]["kp_mm_per_deg"], 0.1);
    assert_eq!(r["gains"]["ki_mm_per_deg_s"], 0.1);
    assert_eq!(r["gains"]["kd_mm_s_per_deg"], 0.0);
    assert_eq!(
        r["paper"]["closed_loop"]["actual_vs_desired_rmse_deg"],
        2.92
    );

    // The CSV's columns give back the reported RMSEs.
    let text = std::fs::read_to_string(s.path("out/control.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time_s,desired_deg,open_actual_deg,open_sensed_deg,open_stroke_mm,\
         closed_actual_deg,closed_sensed_deg,closed_stroke_mm"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|f| f.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 75_000);
    let col_rmse = |a: usize, b: usize| {
        (rows.iter().map(|r| (r[a] - r[b]).powi(2)).sum::<f64>() / rows.len() as f64).sqrt()
    };
    // Four decimals in the file: agreement to 1e-3°.
    assert!((col_rmse(2, 1) - open).abs() < 1e-3);
    assert!((col_rmse(5, 1) - closed).abs() < 1e-3);
    assert!((col_rmse(6, 5) - rmse(&r, "closed_loop", "sensed_vs_actual_rmse_deg")).abs() < 1e-3);
    // Open loop commands θ_d/m_t exactly.
    for r in rows.iter().step_by(997) {
        assert!((r[4] - r[1] / 35.49).abs() < 2e-6, "{r:?}");
    }

    // The report: the page, Fig. 10 (a) and (b), and Table VI's numbers as printed.
    let html = std::fs::read_to_string(s.path("out/report.html")).unwrap();
    for want in [
        "Table VI",
        "fig10a-open-loop.svg",
        "fig10b-closed-loop.svg",
        "tracking-error.svg",
        &format!("<td>{open:.2}</td>"),
        &format!("<td>{closed:.2}</td>"),
        "<td>8.14</td>",
    ] {
        assert!(html.contains(want), "report.html lacks {want}");
    }
    for svg in [
        "fig10a-open-loop.svg",
        "fig10b-closed-loop.svg",
        "stroke.svg",
    ] {
        let text = std::fs::read_to_string(s.path("out").join(svg)).unwrap();
        let doc = roxmltree::Document::parse(&text).unwrap();
        let labels: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .map(str::trim)
            .collect();
        assert!(labels.contains(&"time (s)"), "{svg}: {labels:?}");
    }
}

#[test]
fn a_config_with_the_gauge_factor_30_percent_off_makes_closed_loop_worse() {
    let s = Setup::new();
    s.config("wrong.toml", 15.3 * 1.3);
    let args = random_150s(&s);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let right = s.json("d.toml", "right", &args);
    let wrong = s.json("wrong.toml", "wrong", &args);
    let r = rmse(&right, "closed_loop", "actual_vs_desired_rmse_deg");
    let w = rmse(&wrong, "closed_loop", "actual_vs_desired_rmse_deg");
    assert!(w > 3.0 * r, "right config {r}°, wrong config {w}°");
    // The wrong sensor reads low, so the loop drives the joint past the desired angle while
    // the sensed angle follows the desired one.
    assert!(rmse(&wrong, "closed_loop", "sensed_vs_desired_rmse_deg") < 1.0);
    // Open loop never reads the sensor: its tracking is the same with either config.
    assert_eq!(
        right["open_loop"]["actual_vs_desired_rmse_deg"],
        wrong["open_loop"]["actual_vs_desired_rmse_deg"]
    );
}

#[test]
fn desired_profile_csv_and_custom_gains() {
    let s = Setup::new();
    std::fs::write(
        s.path("desired.csv"),
        "time_s,angle_deg\n0,0\n5,30\n20,30\n25,10\n40,10\n",
    )
    .unwrap();
    let (profile, scenario) = (s.p("desired.csv"), s.p("relaxing.toml"));
    let r = s.json(
        "d.toml",
        "out",
        &[
            "--profile",
            &profile,
            "--scenario",
            &scenario,
            "--gains",
            "0.05,0.2,0",
            "--filter",
            "lp:25",
        ],
    );
    assert_eq!(r["samples"], 20_000);
    assert_eq!(r["gains"]["ki_mm_per_deg_s"], 0.2);
    let text = std::fs::read_to_string(s.path("out/control.csv")).unwrap();
    let row = |t: &str| -> Vec<f64> {
        let line = text.lines().find(|l| l.starts_with(t)).unwrap();
        line.split(',').map(|f| f.parse().unwrap()).collect()
    };
    assert_eq!(row("2.500000,")[1], 15.0);
    assert_eq!(row("19.000000,")[1], 30.0);
    // At the end of a 15 s hold the relaxed open loop has lost most of 15 % of 30°; the
    // closed loop holds the angle.
    let end = row("19.998000,");
    assert!(end[2] < 27.5, "open loop at 20 s: {}°", end[2]);
    assert!(
        (end[5] - 30.0).abs() < 1.5,
        "closed loop at 20 s: {}°",
        end[5]
    );
}

/// The paper's gains on an unfiltered sensed angle: the static simulated plant and the
/// one-sample delay make the loop diverge, and the user is told so (not refused: it is what
/// the simulation shows).
#[test]
fn an_unstable_loop_is_reported() {
    let s = Setup::new();
    let r = s.json(
        "d.toml",
        "out",
        &["--protocol", "random", "--duration-s", "20"],
    );
    let warnings = r["warnings"].to_string();
    assert!(warnings.contains("K_p·m_t = 3.55"), "{warnings}");
    assert!(warnings.contains("at its limit"), "{warnings}");
    assert!(
        rmse(&r, "closed_loop", "actual_vs_desired_rmse_deg") > 10.0,
        "{r}"
    );
    let html = std::fs::read_to_string(s.path("out/report.html")).unwrap();
    assert!(html.contains("Warning: K_p·m_t = 3.55"));
    let filtered = s.json(
        "d.toml",
        "filtered",
        &[
            "--protocol",
            "random",
            "--duration-s",
            "20",
            "--filter",
            "ma:50",
        ],
    );
    assert_eq!(
        filtered["warnings"].as_array().unwrap().len(),
        0,
        "{filtered}"
    );
}

/// Every bad input: a non-zero exit, an error naming the problem, and no output folder.
#[test]
fn bad_input_is_refused_and_writes_nothing() {
    let s = Setup::new();
    std::fs::write(s.path("bad.csv"), "time_s,angle_deg\n0,0\n1,NaN\n").unwrap();
    std::fs::write(s.path("stroke.csv"), "time_s,stroke_mm\n0,0\n1,1\n").unwrap();
    std::fs::write(s.path("empty.csv"), "time_s,angle_deg\n").unwrap();
    let bsn = dlw(&[
        "estimator-config",
        &shipped_design("joint-c.toml"),
        "--gauge-factor",
        "1.28",
        "--r0-ohm",
        "74e3",
        "-o",
        &s.p("c.toml"),
    ]);
    assert!(bsn.status.success());
    let (bad, stroke, empty) = (s.p("bad.csv"), s.p("stroke.csv"), s.p("empty.csv"));
    let cases: Vec<(&str, Vec<&str>, &[&str])> = vec![
        (
            "missing.toml",
            vec!["--protocol", "random"],
            &["missing.toml", "cannot read"],
        ),
        (
            "c.toml",
            vec!["--protocol", "random"],
            &["reads 2 sensors", "Joint D", "carries 1"],
        ),
        (
            "d.toml",
            vec!["--protocol", "random", "--gains", "NaN,0.1,0"],
            &["kp = NaN", "not a finite number"],
        ),
        (
            "d.toml",
            vec!["--protocol", "random", "--gains", "0.1,-0.1,0"],
            &["ki = -0.1", "at least 0"],
        ),
        (
            "d.toml",
            vec!["--protocol", "random", "--gains", "0.1,0.1"],
            &["three numbers kp,ki,kd"],
        ),
        (
            "d.toml",
            vec!["--profile", &bad],
            &["bad.csv line 3", "angle_deg = NaN"],
        ),
        (
            "d.toml",
            vec!["--profile", &stroke],
            &["stroke.csv line 1", "expected \"time_s,angle_deg\""],
        ),
        (
            "d.toml",
            vec!["--profile", &empty],
            &["empty.csv has no data rows"],
        ),
        (
            "d.toml",
            vec![],
            &["no desired angle", "--profile", "--protocol"],
        ),
        (
            "d.toml",
            vec!["--protocol", "random", "--mt-deg-per-mm=-3"],
            &["m_t = -3", "greater than 0"],
        ),
        (
            "d.toml",
            vec!["--protocol", "random", "--duration-s", "0"],
            &["duration_s = 0"],
        ),
    ];
    for (config, args, needles) in cases {
        let o = s.control(config, "out", &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{config} {args:?} succeeded");
        for n in needles {
            assert!(err.contains(n), "{config} {args:?}: {err} lacks {n}");
        }
        assert!(!err.contains("panicked"), "{err}");
        assert!(!s.path("out").exists(), "{config} {args:?} wrote output");
    }
    // An existing, non-empty output folder is kept unless --force.
    std::fs::create_dir(s.path("out")).unwrap();
    std::fs::write(s.path("out/keep.txt"), "mine").unwrap();
    let o = s.control(
        "d.toml",
        "out",
        &["--protocol", "random", "--duration-s", "1"],
    );
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--force"));
    assert!(Path::new(&s.path("out/keep.txt")).exists());
    let o = s.control(
        "d.toml",
        "out",
        &["--protocol", "random", "--duration-s", "1", "--force"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!s.path("out/keep.txt").exists());
    assert!(s.path("out/control.csv").exists());
}

/// A BSN joint read through both sensors (Eq. 7): the closed loop works the same way.
#[test]
fn two_sensor_joint_closes_the_loop_on_both_sensors() {
    let s = Setup::new();
    let design = shipped_design("joint-c.toml");
    let out = s.p("c.toml");
    let mut args = vec!["estimator-config", &design];
    args.extend(common::JOINT_C_TABLE_V);
    args.extend(["-o", &out]);
    let o = dlw(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (design, config, out, scenario) = (
        shipped_design("joint-c.toml"),
        s.p("c.toml"),
        s.p("out"),
        s.p("relaxing.toml"),
    );
    let o = dlw(&[
        "control",
        "--design",
        &design,
        "--config",
        &config,
        "--scenario",
        &scenario,
        "--protocol",
        "random",
        "--duration-s",
        "150",
        "--filter",
        "ma:200",
        "-o",
        &out,
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(r["design"], "Joint C");
    assert_eq!(r["warnings"].as_array().unwrap().len(), 0, "{r}");
    let open = rmse(&r, "open_loop", "actual_vs_desired_rmse_deg");
    let closed = rmse(&r, "closed_loop", "actual_vs_desired_rmse_deg");
    assert!(closed < 0.7 * open, "closed {closed}° vs open {open}°: {r}");
}
