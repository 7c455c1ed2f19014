//! `dlw discover` on clean recordings with the artefacts a real DAQ adds: mains hum, isolated
//! spikes (two of them inside the rest the noise model is frozen from), and the steps of a
//! 12-bit converter. None is an effect of the joint or of its sensor, so none may be named,
//! flagged `unexplained` or left `ambiguous`. A step in the sensor's baseline half way through
//! (a connector knocked) is a change in time: it may be named `drift` or flagged as a change in
//! time on the sensor, and nothing else.
//!
//! The recordings are the third generator's clean ones (coloured noise close to 1/f), with the
//! artefact added to the divider voltage afterwards, as a logger would record it.

mod common;
use common::discovery::{contenders, named, try_discover_json};
use common::shipped_design;
use common::third_generator::{self, Bench};

use rayon::prelude::*;
use std::path::Path;

/// The clean recordings' seeds (Joint A, 300 s).
const SEEDS: [u64; 2] = [3, 4];

/// An artefact added to the divider voltage `v` (V) at the times `t` (s), given the noise's
/// per-sample spread `sigma` (V).
type Artefact = fn(t: &[f64], v: &mut [f64], sigma: f64);

/// Mains hum at `hz`, five times the noise's spread.
fn hum(t: &[f64], v: &mut [f64], sigma: f64, hz: f64) {
    for (v, t) in v.iter_mut().zip(t) {
        *v += 5.0 * sigma * (2.0 * std::f64::consts::PI * hz * t + 0.3).sin();
    }
}

fn hum_50(t: &[f64], v: &mut [f64], sigma: f64) {
    hum(t, v, sigma, 50.0);
}

fn hum_60(t: &[f64], v: &mut [f64], sigma: f64) {
    hum(t, v, sigma, 60.0);
}

/// Ten spikes of fifty times the noise over the run, and two inside the 10 s rest.
fn spikes(t: &[f64], v: &mut [f64], sigma: f64) {
    let n = v.len();
    for k in 0..10 {
        let sign = if k % 2 == 0 { -1.0 } else { 1.0 };
        v[n * (10 * k + 4) / 100] += sign * 50.0 * sigma;
    }
    for (at_s, sign) in [(2.5, 1.0), (7.1, -1.0)] {
        let i = t.partition_point(|x| *x < at_s);
        v[i] += sign * 50.0 * sigma;
    }
}

/// A 12-bit converter over 5 V: steps of 1.22 mV, about two-thirds of the noise's spread.
fn quantized(_: &[f64], v: &mut [f64], _: f64) {
    let lsb = 5.0 / 4096.0;
    for v in v.iter_mut() {
        *v = (*v / lsb).round() * lsb;
    }
}

/// The baseline steps by five times the noise half way through.
fn step(t: &[f64], v: &mut [f64], sigma: f64) {
    let half = 0.5 * t[t.len() - 1];
    for (v, t) in v.iter_mut().zip(t) {
        if *t > half {
            *v += 5.0 * sigma;
        }
    }
}

/// Writes the clean recording of `seed` into `rec` with `artefact` added to its voltage.
fn write_with(rec: &Path, seed: u64, artefact: Artefact) {
    let bench = Bench {
        effect: None,
        duration_s: 300.0,
        seed,
    };
    third_generator::write_recording(Path::new(&shipped_design("joint-a.toml")), &bench, rec);
    let csv = rec.join("data.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_owned();
    assert_eq!(header, "time_s,stroke_mm,angle_deg,v1_V");
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    let column = |k: usize| -> Vec<f64> { rows.iter().map(|r| r[k].parse().unwrap()).collect() };
    let t = column(0);
    let mut v = column(3);
    // The noise's spread from the differences of successive samples (the signal is slow).
    let diffs: Vec<f64> = v.windows(2).map(|w| w[1] - w[0]).collect();
    let mean = diffs.iter().sum::<f64>() / diffs.len() as f64;
    let var = diffs.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / diffs.len() as f64;
    let sigma = (var / 2.0).sqrt();
    artefact(&t, &mut v, sigma);
    let mut out = header;
    out.push('\n');
    for (r, v) in rows.iter().zip(&v) {
        out.push_str(&format!("{},{},{},{v:.6}\n", r[0], r[1], r[2]));
    }
    std::fs::write(&csv, out).unwrap();
}

/// `dlw discover --json` on each seed's clean recording with `artefact`.
fn reports(name: &str, artefact: Artefact) -> Vec<(String, serde_json::Value)> {
    let dir = tempfile::tempdir().unwrap();
    SEEDS
        .par_iter()
        .map(|&seed| {
            let case = format!("{name}-{seed}");
            let rec = dir.path().join(&case);
            write_with(&rec, seed, artefact);
            let out = dir.path().join(format!("{case}-out"));
            let json = try_discover_json(&shipped_design("joint-a.toml"), &rec, &out)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            (case, json)
        })
        .collect()
}

/// Every report names nothing, flags nothing and leaves nothing ambiguous.
fn assert_quiet(name: &str, artefact: Artefact) {
    for (case, json) in reports(name, artefact) {
        assert!(named(&json).is_empty(), "{case}: named {:?}", named(&json));
        assert_eq!(
            json["unexplained"].as_array().unwrap().len(),
            0,
            "{case}: {}",
            json["unexplained"]
        );
        assert_eq!(
            json["ambiguous"].as_array().unwrap().len(),
            0,
            "{case}: {}",
            json["ambiguous"]
        );
    }
}

#[test]
fn mains_hum_is_not_an_effect() {
    assert_quiet("hum-50", hum_50);
    assert_quiet("hum-60", hum_60);
}

#[test]
fn spikes_are_not_an_effect_even_in_the_rest() {
    assert_quiet("spikes", spikes);
}

#[test]
fn a_converters_steps_are_not_an_effect() {
    assert_quiet("quantized", quantized);
}

/// A step in the baseline is a change in time on the sensor: `drift` there, or the sensor
/// flagged for a change in time; never a name or a flag on the plant, never another name.
#[test]
fn a_step_in_the_baseline_is_a_change_in_time_on_the_sensor() {
    for (case, json) in reports("step", step) {
        let names = named(&json);
        assert!(
            names
                .iter()
                .all(|n| *n == ("drift".to_owned(), "sensor1".to_owned())),
            "{case}: named {names:?}"
        );
        let flags = json["unexplained"].as_array().unwrap();
        assert!(
            flags
                .iter()
                .all(|f| f["channel"] == "sensor1" && f["kind"] == "time"),
            "{case}: {flags:?}"
        );
        assert!(
            !names.is_empty() || !flags.is_empty(),
            "{case}: the step went unseen"
        );
        let open: Vec<Vec<String>> = json["ambiguous"]
            .as_array()
            .unwrap()
            .iter()
            .map(contenders)
            .collect();
        assert!(open.is_empty(), "{case}: ambiguous {open:?}");
    }
}
