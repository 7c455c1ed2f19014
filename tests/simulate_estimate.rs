//! simulate → estimator-config → estimate, through the binary: with a linear sensor and only
//! ADC and tracker noise, the nominal linear config recovers the angle to within the noise; with
//! a sensor effect switched on, the same config is measurably worse.

use crate::common;
use common::shipped_design as design_path;

use std::path::Path;
use std::process::{Command, Output};

use dlw::design::Design;

fn dlw(args: &[&str]) -> Output {
    let o = Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .output()
        .expect("the dlw binary runs");
    assert!(
        o.status.success(),
        "dlw {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// The noise of a test scenario (written into its scenario file).
#[derive(Clone, Copy)]
struct Noise {
    /// ADC noise, RMS (V).
    volts: f64,
    /// EM tracker noise, RMS (°).
    tracker_deg: f64,
}

/// The simulator's default noise.
const DEFAULT_NOISE: Noise = Noise {
    volts: 0.005,
    tracker_deg: 0.3,
};
/// A quiet bench, so that a model error stands out.
const LOW_NOISE: Noise = Noise {
    volts: 0.001,
    tracker_deg: 0.05,
};
const ADC_BITS: i32 = 16;
const ADC_SPAN_V: f64 = 20.0;
const SUPPLY_V: f64 = 5.0;
/// The protocols' peak strain (the simulator's default amplitude).
const PEAK_STRAIN: f64 = 0.015;

/// A white-noise-only scenario (linear sensor, no plant or sensor effect, no correlated noise:
/// its tables are absent, so off) plus `extra` TOML.
fn scenario(noise: Noise, extra: &str) -> String {
    format!(
        "seed = 11\n[adc]\nenabled = true\nbits = {ADC_BITS}\nmin_v = -10.0\nmax_v = 10.0\nnoise_v = {}\n[tracker]\nenabled = true\nnoise_deg = {}\n{extra}",
        noise.volts, noise.tracker_deg
    )
}

/// One linear sensor: gauge factor, R0 (Ω), divider R_k (Ω), and the sign of its strain
/// (+1 for sensor 1, −1 for BSN sensor 2).
struct LinearSensor {
    gf: f64,
    r0: f64,
    rk: f64,
    sign: f64,
}

/// Bounds on the RMSE of `estimate − recorded angle`, derived from the configured noise.
///
/// Per sample, with true angle θ: the recorded angle is `θ + n_t`, `n_t ~ N(0, σ_t²)`, and each
/// voltage is `V(θ) + n_v + n_q` with ADC noise `n_v ~ N(0, σ_v²)` and quantization `n_q`,
/// uniform over one LSB `q = span/(2^bits − 1)` (variance `q²/12`); all independent. With the
/// true model in the config, the estimator inverts Eq. 4 and Eq. 5 exactly, so to first order
/// in the voltage error the strain error of sensor k is `(n_v + n_q)/(dV_k/dε_k)`, with
///
/// `dV/dε = dV/dR · dR/dε = V+·R_k/(R + R_k)² · R0·GF`, at `R = R0·(1 + GF·ε_k)`.
///
/// One sensor (Eq. 3): `θ = ε·L/Δy`, so `var(θ̂ − θ) = (L/Δy)²·(σ_v² + q²/12)/(dV/dε)²`.
/// Two sensors (Eq. 6): `θ = L·(ε₁ − ε₂)/Δy⁽¹²⁾`, so the two sensors' strain variances add,
/// scaled by `(L/Δy⁽¹²⁾)²`. In degrees, times `(180/π)²`. Then
///
/// `var(e(θ)) = σ_t² + var(θ̂ − θ)`,
///
/// and the RMSE² is the mean of `var(e(θ))` over the samples' angles, which lie in
/// `[0, θ_peak]` (the protocols stroke between 0 and the amplitude that reaches 1.5 % strain).
/// So `min_θ var ≤ RMSE² ≤ max_θ var` up to sampling error. With 20 000 samples the relative
/// standard error of an RMS is about `1/√(2n)` = 0.6 %, and the second-order terms of the
/// inverse are of order `σ_v/V ≈ 0.2 %`; the bounds get a 10 % margin for both.
fn rmse_bounds(design: &Design, sensors: &[LinearSensor], noise: Noise) -> (f64, f64) {
    let joint = &design.joint;
    let q = ADC_SPAN_V / (2f64.powi(ADC_BITS) - 1.0);
    let voltage_var = noise.volts * noise.volts + q * q / 12.0;
    let strain_to_deg = match sensors.len() {
        1 => joint.length_mm() / joint.section().offset_mm(),
        _ => joint.length_mm() / joint.section().two_sensor_offset_mm().unwrap(),
    }
    .to_degrees();
    let peak_deg = joint.angle_at_strain(PEAK_STRAIN).to_degrees();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for i in 0..=1000 {
        let theta = peak_deg * i as f64 / 1000.0;
        let strain = joint.strain(theta.to_radians());
        let strain_var: f64 = sensors
            .iter()
            .map(|s| {
                let r = s.r0 * (1.0 + s.gf * s.sign * strain);
                let dv_dr = SUPPLY_V * s.rk / ((r + s.rk) * (r + s.rk));
                let dv_de = dv_dr * s.r0 * s.gf;
                voltage_var / (dv_de * dv_de)
            })
            .sum();
        let var =
            noise.tracker_deg * noise.tracker_deg + strain_to_deg * strain_to_deg * strain_var;
        lo = lo.min(var);
        hi = hi.max(var);
    }
    (0.9 * lo.sqrt(), 1.1 * hi.sqrt())
}

/// Simulates 40 s of the random protocol (10 s at rest, then 30 s of motion) with
/// `scenario_text`, writes the nominal config with `config_args` and returns `estimate --json`'s
/// report.
fn simulate_and_estimate(
    dir: &Path,
    design: &str,
    scenario_text: &str,
    config_args: &[&str],
) -> serde_json::Value {
    let scenario = dir.join("scenario.toml");
    std::fs::write(&scenario, scenario_text).unwrap();
    let rec = dir.join("rec");
    let rec_s = rec.display().to_string();
    dlw(&[
        "simulate",
        "--design",
        design,
        "--protocol",
        "random",
        "--duration-s",
        "40",
        "--scenario",
        &scenario.display().to_string(),
        "-o",
        &rec_s,
        "--force",
    ]);
    let config = dir.join("config.toml").display().to_string();
    let mut args = vec!["estimator-config", design];
    args.extend_from_slice(config_args);
    args.extend_from_slice(&["-o", &config]);
    dlw(&args);
    let o = dlw(&["estimate", "--config", &config, &rec_s, "--json"]);
    let report: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(report["samples"], 20_000);
    let csv = std::fs::read_to_string(rec.join("estimates.csv")).unwrap();
    assert_eq!(csv.lines().count(), 20_001);
    report
}

fn joint_a_sensor() -> [LinearSensor; 1] {
    [LinearSensor {
        gf: 15.3,
        r0: 215e3,
        rk: 99.6e3,
        sign: 1.0,
    }]
}

#[test]
fn nominal_config_recovers_the_angle_to_within_the_noise() {
    let dir = tempfile::tempdir().unwrap();
    let design = design_path("joint-a.toml");
    let d = Design::load(Path::new(&design)).unwrap();
    let (lo, hi) = rmse_bounds(&d, &joint_a_sensor(), DEFAULT_NOISE);
    let report = simulate_and_estimate(
        dir.path(),
        &design,
        &scenario(
            DEFAULT_NOISE,
            "[sensor1]\ngauge_factor = 15.3\nr0_ohm = 215e3\n",
        ),
        &["--gauge-factor", "15.3", "--r0-ohm", "215e3"],
    );
    let rmse = report["rmse_deg"].as_f64().unwrap();
    eprintln!("RMSE {rmse:.3}° within the noise bounds [{lo:.3}, {hi:.3}]°?");
    assert!(
        rmse <= hi && rmse >= lo,
        "RMSE {rmse}° outside the noise bounds [{lo}, {hi}]°"
    );
    assert_eq!(report["flagged_samples"], 0);
}

#[test]
fn two_sensor_config_recovers_the_angle_to_within_the_noise() {
    let dir = tempfile::tempdir().unwrap();
    let design = design_path("joint-c.toml");
    let d = Design::load(Path::new(&design)).unwrap();
    let sensors = [
        LinearSensor {
            gf: 1.28,
            r0: 74.0e3,
            rk: 99.6e3,
            sign: 1.0,
        },
        LinearSensor {
            gf: 0.680,
            r0: 88.9e3,
            rk: 102.5e3,
            sign: -1.0,
        },
    ];
    let (lo, hi) = rmse_bounds(&d, &sensors, DEFAULT_NOISE);
    let report = simulate_and_estimate(
        dir.path(),
        &design,
        &scenario(DEFAULT_NOISE, ""),
        &common::JOINT_C_TABLE_V,
    );
    let rmse = report["rmse_deg"].as_f64().unwrap();
    eprintln!("RMSE {rmse:.3}° within the noise bounds [{lo:.3}, {hi:.3}]°?");
    assert!(
        rmse <= hi && rmse >= lo,
        "RMSE {rmse}° outside the noise bounds [{lo}, {hi}]°"
    );
    assert_eq!(report["warnings"].as_array().unwrap().len(), 0);
}

/// On a quiet bench the nominal config stays within the noise bound; each sensor effect pushes
/// the error well past it. (At the default noise, 0.7° of noise and the PI model's ~0.9° of
/// hysteresis error add in quadrature, so the effect would be measurable but not by a wide
/// margin.)
#[test]
fn a_sensor_effect_makes_the_nominal_estimate_measurably_worse() {
    let design = design_path("joint-a.toml");
    let d = Design::load(Path::new(&design)).unwrap();
    let (lo, hi) = rmse_bounds(&d, &joint_a_sensor(), LOW_NOISE);
    let cases = [
        ("no effect", ""),
        ("PI hysteresis", "[sensor1]\nmodel = \"pi\"\n"),
        (
            "saturation at 1 %",
            "[sensor1.saturation]\nenabled = true\nstrain = 0.01\n",
        ),
        (
            "drift",
            "[sensor1.drift]\nenabled = true\nrate_ohm_per_s = 100.0\n",
        ),
    ];
    for (name, extra) in cases {
        let dir = tempfile::tempdir().unwrap();
        let report = simulate_and_estimate(
            dir.path(),
            &design,
            &scenario(LOW_NOISE, extra),
            &["--gauge-factor", "15.3", "--r0-ohm", "215e3"],
        );
        let rmse = report["rmse_deg"].as_f64().unwrap();
        if extra.is_empty() {
            assert!(
                rmse <= hi && rmse >= lo,
                "RMSE {rmse}° outside [{lo}, {hi}]°"
            );
        } else {
            assert!(
                rmse > 2.0 * hi,
                "{name}: RMSE {rmse}° is not measurably above the noise bound {hi}°"
            );
        }
        eprintln!("{name}: RMSE {rmse:.3}° (noise bound {hi:.3}°)");
    }
}
