//! `dlw simulate`'s measurement noise through the binary: the white-noise streams of old seeds
//! are unchanged, the correlated (first-order autoregressive) noise has its stated spread and
//! autocorrelation, follows the seed, is off unless asked for, and a recording made with it is
//! reproduced byte for byte from its own `rig.toml`.

use crate::common;
use common::{dlw, shipped_design as design};

use std::path::{Path, PathBuf};
use std::process::Output;

fn ok(o: &Output) {
    assert!(
        o.status.success(),
        "dlw failed: {}\n{}",
        String::from_utf8_lossy(&o.stderr),
        String::from_utf8_lossy(&o.stdout)
    );
}

fn golden(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/sim-white-noise")
        .join(name)
}

/// Runs `dlw simulate` with `args` into `dir/name` and returns data.csv's bytes.
fn simulate(dir: &Path, name: &str, args: &[&str]) -> Vec<u8> {
    let out = dir.join(name);
    let out_s = out.display().to_string();
    let mut all = vec!["simulate", "-o", &out_s, "--force"];
    all.extend_from_slice(args);
    ok(&dlw(&all));
    std::fs::read(out.join("data.csv")).unwrap()
}

/// Column `col` of a data.csv as numbers.
fn column(csv: &[u8], col: usize) -> Vec<f64> {
    std::str::from_utf8(csv)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect()
}

/// Sample standard deviation and autocorrelation at `lag` (mean removed).
fn sd_and_autocorrelation(x: &[f64], lag: usize) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n;
    let cov = x
        .windows(lag + 1)
        .map(|w| (w[0] - mean) * (w[lag] - mean))
        .sum::<f64>()
        / n;
    (var.sqrt(), cov / var)
}

/// A stroke profile that holds zero stroke for `seconds`.
fn still_profile(dir: &Path, seconds: f64) -> String {
    let p = dir.join("still.csv");
    std::fs::write(&p, format!("time_s,stroke_mm\n0,0\n{seconds},0\n")).unwrap();
    p.display().to_string()
}

/// Recordings made before correlated noise existed come out byte for byte the same: the ADC,
/// tracker, drift and random-pattern streams are unchanged (see the folder's README).
#[test]
fn old_seeds_give_the_same_white_noise() {
    let dir = tempfile::tempdir().unwrap();
    let profile = golden("profile.csv").display().to_string();
    let drift = golden("drift.toml").display().to_string();
    let c = simulate(
        dir.path(),
        "c",
        &[
            "--design",
            &design("joint-c.toml"),
            "--protocol",
            "custom",
            "--profile",
            &profile,
            "--scenario",
            &drift,
            "--duration-s",
            "2",
        ],
    );
    assert!(
        c == std::fs::read(golden("custom-joint-c-drift.csv")).unwrap(),
        "the ADC, tracker or drift streams changed"
    );
    let no_rest = dir.path().join("no-rest.toml");
    std::fs::write(&no_rest, "[protocols]\nrest_start_s = 0.0\n").unwrap();
    let d = simulate(
        dir.path(),
        "d",
        &[
            "--design",
            &design("joint-d.toml"),
            "--protocol",
            "random",
            "--seed",
            "5",
            "--duration-s",
            "2",
            "--scenario",
            &no_rest.display().to_string(),
        ],
    );
    assert!(
        d == std::fs::read(golden("random-joint-d.csv")).unwrap(),
        "the random pattern, the ADC or the tracker stream changed"
    );
}

/// The tracker's correlated error alone, on a joint at rest for 600 s: standard deviation σ and
/// lag-m autocorrelation e^(−m·Δt/τ).
///
/// σ = 0.2°, τ = 1 s = 500 samples, n = 300 000: the variance's relative standard error is
/// √(2(1 + φ²)/(n(1 − φ²))) ≈ 4 %, so the standard deviation's ≈ 2 %; the lag-1
/// autocorrelation's standard error is √((1 − φ²)/n) ≈ 1.6·10⁻⁴ and the lag-500 one's (Bartlett)
/// ≈ 0.016. Tolerances are about five standard errors. The angle is written to 1e-4°, which adds
/// 3·10⁻⁵° of rounding.
#[test]
fn correlated_tracker_error_has_its_spread_and_correlation_time() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("s.toml");
    std::fs::write(
        &scenario,
        "seed = 21\n[adc]\nenabled = false\n[tracker]\nnoise_deg = 0.0\n[tracker.correlated]\nsigma_deg = 0.2\ntau_s = 1.0\n",
    )
    .unwrap();
    let profile = still_profile(dir.path(), 600.0);
    let csv = simulate(
        dir.path(),
        "rec",
        &[
            "--design",
            &design("joint-d.toml"),
            "--protocol",
            "custom",
            "--profile",
            &profile,
            "--scenario",
            &scenario.display().to_string(),
        ],
    );
    let angle = column(&csv, 2);
    assert_eq!(angle.len(), 300_000);
    let phi = (-0.002f64).exp();
    let (sd, r1) = sd_and_autocorrelation(&angle, 1);
    let (_, r500) = sd_and_autocorrelation(&angle, 500);
    eprintln!("sd {sd:.4}°, lag-1 {r1:.5} (φ = {phi:.5}), lag-500 {r500:.3} (1/e = 0.368)");
    assert!((sd / 0.2 - 1.0).abs() < 0.1, "sd {sd}");
    assert!((r1 - phi).abs() < 1e-3, "lag-1 {r1} vs {phi}");
    assert!((r500 - (-1.0f64).exp()).abs() < 0.08, "lag-500 {r500}");
}

/// `--noise realistic` on the ADC: white 5 mV plus correlated 2 mV (τ = 2 s) on a sensor at rest.
/// The variance is σ_w² + σ_c² + q²/12 and the lag-1 autocorrelation σ_c²·φ/(that), about 0.14;
/// white alone gives 0. Over 600 s (300 correlation times) the correlated part's variance has a
/// relative standard error of about 8 %, so the autocorrelation gets a 30 % tolerance and the
/// total spread (mostly white) 5 %.
#[test]
fn realistic_adc_noise_is_white_plus_correlated() {
    let dir = tempfile::tempdir().unwrap();
    let profile = still_profile(dir.path(), 600.0);
    let run = |name: &str, noise: &str| {
        let csv = simulate(
            dir.path(),
            name,
            &[
                "--design",
                &design("joint-d.toml"),
                "--protocol",
                "custom",
                "--profile",
                &profile,
                "--seed",
                "8",
                "--noise",
                noise,
            ],
        );
        column(&csv, 3)
    };
    let q2 = (20.0 / 65535.0f64).powi(2) / 12.0;
    let total = 0.005f64.powi(2) + 0.002f64.powi(2) + q2;
    let (sd, r1) = sd_and_autocorrelation(&run("realistic", "realistic"), 1);
    let expected_r1 = 0.002f64.powi(2) * (-0.001f64).exp() / total;
    eprintln!("realistic: sd {sd:.5} V, lag-1 {r1:.4} (expected {expected_r1:.4})");
    assert!((sd / total.sqrt() - 1.0).abs() < 0.05, "sd {sd}");
    assert!((r1 / expected_r1 - 1.0).abs() < 0.3, "lag-1 {r1}");
    let (sd, r1) = sd_and_autocorrelation(&run("white", "white"), 1);
    eprintln!("white: sd {sd:.5} V, lag-1 {r1:.4}");
    assert!(
        (sd / (0.005f64.powi(2) + q2).sqrt() - 1.0).abs() < 0.02,
        "{sd}"
    );
    // White: standard error 1/√n = 0.002.
    assert!(r1.abs() < 0.01, "lag-1 {r1}");
}

/// Correlated noise is off by default, follows the seed when on, and the shipped scenario
/// `designs/scenarios/realistic-noise.toml` is the same as `--noise realistic`; `--noise white`
/// switches off what a scenario switched on.
#[test]
fn correlated_noise_is_off_by_default_seeded_and_switchable() {
    let dir = tempfile::tempdir().unwrap();
    let base = [
        "--design",
        &design("joint-c.toml"),
        "--protocol",
        "random",
        "--duration-s",
        "20",
    ]
    .map(String::from);
    let run = |name: &str, extra: &[&str]| {
        let mut args: Vec<&str> = base.iter().map(String::as_str).collect();
        args.extend_from_slice(extra);
        simulate(dir.path(), name, &args)
    };
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("designs/scenarios/realistic-noise.toml")
        .display()
        .to_string();
    let default = run("default", &["--seed", "3"]);
    let white = run("white", &["--seed", "3", "--noise", "white"]);
    let realistic = run("realistic", &["--seed", "3", "--noise", "realistic"]);
    let again = run("again", &["--seed", "3", "--noise", "realistic"]);
    let other = run("other", &["--seed", "4", "--noise", "realistic"]);
    let file = run("file", &["--seed", "3", "--scenario", &shipped]);
    let file_white = run(
        "file-white",
        &["--seed", "3", "--scenario", &shipped, "--noise", "white"],
    );
    assert!(default == white, "correlated noise is on by default");
    assert!(realistic != white);
    assert!(realistic == again, "same seed, different bytes");
    assert!(realistic != other);
    assert!(
        file == realistic,
        "the shipped scenario is not --noise realistic"
    );
    assert!(file_white == white);
    // The stroke is the same with and without: only the measurement changed.
    assert_eq!(column(&realistic, 1), column(&white, 1));
    // The correlated part is what differs: the tracker's difference is smooth (lag-1 ≈ φ).
    let diff: Vec<f64> = column(&realistic, 2)
        .iter()
        .zip(column(&white, 2))
        .map(|(a, b)| a - b)
        .collect();
    let (sd, r1) = sd_and_autocorrelation(&diff, 1);
    assert!(sd > 0.05 && r1 > 0.99, "sd {sd}, lag-1 {r1}");
}

/// A recording with correlated noise, a signed rate effect and presence-enabled tables is
/// reproduced byte for byte from its own `[scenario]` and `[design]`.
#[test]
fn recorded_scenario_reproduces_correlated_noise_and_new_effects() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("s.toml");
    std::fs::write(
        &scenario,
        "seed = 12\n[plant.backlash]\n[sensor1.rate]\nform = \"signed\"\n[sensor2.creep]\nfraction = 0.05\n[adc.correlated]\n[tracker.correlated]\ntau_s = 3.0\n[protocols]\nrest_start_s = 4.0\n",
    )
    .unwrap();
    let first = simulate(
        dir.path(),
        "rec",
        &[
            "--design",
            &design("joint-c.toml"),
            "--protocol",
            "rate-dependence",
            "--duration-s",
            "30",
            "--scenario",
            &scenario.display().to_string(),
        ],
    );
    let rig = std::fs::read_to_string(dir.path().join("rec/rig.toml")).unwrap();
    let rig: toml::Table = toml::from_str(&rig).unwrap();
    let sc = &rig["scenario"];
    assert_eq!(sc["plant"]["backlash"]["enabled"].as_bool(), Some(true));
    assert_eq!(sc["plant"]["relaxation"]["enabled"].as_bool(), Some(false));
    assert_eq!(sc["sensor1"]["rate"]["form"].as_str(), Some("signed"));
    assert_eq!(sc["sensor2"]["creep"]["enabled"].as_bool(), Some(true));
    assert_eq!(sc["adc"]["correlated"]["enabled"].as_bool(), Some(true));
    assert_eq!(sc["adc"]["correlated"]["sigma_v"].as_float(), Some(0.002));
    assert_eq!(sc["tracker"]["correlated"]["tau_s"].as_float(), Some(3.0));
    assert_eq!(sc["protocols"]["rest_start_s"].as_float(), Some(4.0));
    let again = dir.path().join("again.toml");
    std::fs::write(&again, toml::to_string(sc).unwrap()).unwrap();
    let design_again = dir.path().join("design.toml");
    std::fs::write(&design_again, toml::to_string(&rig["design"]).unwrap()).unwrap();
    let second = simulate(
        dir.path(),
        "rec2",
        &[
            "--design",
            &design_again.display().to_string(),
            "--scenario",
            &again.display().to_string(),
        ],
    );
    assert!(
        first == second,
        "the recorded scenario does not reproduce the run"
    );
    // The same scenario without the signed rate effect differs: the effect does something.
    let plain = dir.path().join("plain.toml");
    std::fs::write(
        &plain,
        toml::to_string(sc)
            .unwrap()
            .replace("form = \"signed\"", "form = \"log\""),
    )
    .unwrap();
    let third = simulate(
        dir.path(),
        "rec3",
        &[
            "--design",
            &design_again.display().to_string(),
            "--scenario",
            &plain.display().to_string(),
        ],
    );
    assert!(first != third);
}

#[test]
fn bad_noise_values_fail_clearly_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "[adc.correlated]\ntau_s = 0.0\n",
            "adc.correlated.tau_s = 0",
        ),
        (
            "[tracker.correlated]\nsigma_deg = -0.1\n",
            "tracker.correlated.sigma_deg = -0.1",
        ),
        ("[tracker.correlated]\ntau = 1.0\n", "unknown field `tau`"),
        (
            "[protocols]\nrest_start_s = -2.0\n",
            "protocols.rest_start_s = -2",
        ),
        (
            "[sensor1.rate]\nform = \"square\"\n",
            "unknown variant `square`",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let scenario = dir.path().join(format!("s{i}.toml"));
        std::fs::write(&scenario, text).unwrap();
        let out = dir.path().join("out");
        let o = dlw(&[
            "simulate",
            "--design",
            &design("joint-d.toml"),
            "--protocol",
            "random",
            "--scenario",
            &scenario.display().to_string(),
            "-o",
            &out.display().to_string(),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{text} succeeded");
        assert!(err.contains(needle), "{text}: {err}");
        assert!(!out.exists(), "{text} left an output folder");
    }
    let o = dlw(&[
        "simulate",
        "--design",
        &design("joint-d.toml"),
        "--protocol",
        "random",
        "--noise",
        "pink",
        "-o",
        &dir.path().join("out").display().to_string(),
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("realistic"));
}
