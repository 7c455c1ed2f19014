//! `dlw discover` on clean recordings with the artefacts a real DAQ adds: mains hum, isolated
//! spikes (two of them inside the rest the noise model is frozen from), and the steps of a
//! 12-bit converter. None is an effect of the joint or of its sensor, so none may be named,
//! flagged `unexplained` or left `ambiguous`. A step in the sensor's baseline half way through
//! (a connector knocked) is a change in time: it may be named `drift` or flagged as a change in
//! time on the sensor, and nothing else.
//!
//! And the ways another lab's logger differs from the generator's, none of which discovery was
//! built next to: noise with heavy tails (Student's t with 3 degrees of freedom) or a 1/f
//! spectrum down to the record's length, a logger at 100 Hz instead of 500 Hz, a tracker that
//! reports to 0.1°, a stroke read through an analog channel (1 µm of noise). On a clean
//! recording each names, flags and leaves ambiguous nothing; on a
//! hysteresis ×2 (its detection size) each still names `hysteresis` first on the sensor, with
//! no other name.
//!
//! The recordings are the third generator's clean ones (coloured noise close to 1/f), with the
//! artefact added to the divider voltage afterwards, as a logger would record it.

mod common;
use common::discovery::{contenders, named, try_discover_json};
use common::rng::Rng;
use common::shipped_design;
use common::third_generator::{self, Bench, Effect, Size};

use rayon::prelude::*;
use std::path::Path;

/// The clean recordings' seeds (Joint A, 300 s).
const SEEDS: [u64; 2] = [3, 4];
/// The seeds of the hysteresis recordings (Joint A, 300 s), other than the clean ones'.
const EFFECT_SEEDS: [u64; 2] = [21_001, 21_002];

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

/// Heavy-tailed noise of the noise's spread: Student's t with 3 degrees of freedom (variance 3),
/// scaled.
fn heavy_tails(_: &[f64], v: &mut [f64], sigma: f64) {
    let mut rng = Rng::new(0x7A11);
    for v in v.iter_mut() {
        let chi2: f64 = (0..3).map(|_| rng.normal().powi(2)).sum();
        *v += sigma / 3f64.sqrt() * rng.normal() / (chi2 / 3.0).sqrt();
    }
}

/// 1/f noise of the noise's spread, from 0.01 s to the record's length: twelve AR(1) terms with
/// correlation times spaced evenly in log, of equal variance (a flicker noise's spectrum).
fn flicker(t: &[f64], v: &mut [f64], sigma: f64) {
    let mut rng = Rng::new(0xF11C);
    let dt = t[1] - t[0];
    let (lo, hi) = (0.01_f64, t[t.len() - 1]);
    let terms = 12;
    let spread = sigma / (terms as f64).sqrt();
    let mut states: Vec<(f64, f64)> = (0..terms)
        .map(|k| {
            let tau = lo * (hi / lo).powf(k as f64 / (terms - 1) as f64);
            ((-dt / tau).exp(), spread * rng.normal())
        })
        .collect();
    for v in v.iter_mut() {
        for (phi, state) in &mut states {
            *state = *phi * *state + (1.0 - *phi * *phi).sqrt() * spread * rng.normal();
            *v += *state;
        }
    }
}

/// A recording's columns, to change as another logger would have written them.
struct Rows {
    header: String,
    columns: Vec<Vec<f64>>,
    sample_hz: f64,
}

/// A change to a recording: an artefact on its voltage, or one to its rows.
#[derive(Clone, Copy)]
enum Change {
    Voltage(Artefact),
    Rows(fn(&mut Rows)),
}

/// A logger at 100 Hz: the means of five samples, stamped at the first.
fn at_100_hz(r: &mut Rows) {
    for (k, column) in r.columns.iter_mut().enumerate() {
        *column = column
            .chunks_exact(5)
            .map(|c| {
                if k == 0 {
                    c[0]
                } else {
                    c.iter().sum::<f64>() / 5.0
                }
            })
            .collect();
    }
    r.sample_hz /= 5.0;
}

/// A tracker that reports to 0.1°.
fn tracker_to_a_tenth(r: &mut Rows) {
    for a in &mut r.columns[2] {
        *a = (*a * 10.0).round() / 10.0;
    }
}

/// A stroke read through an analog channel: white noise of `sd_mm` on the 0.74 mm stroke (1 µm
/// is a 16-bit DAQ's millivolt on a 1 mm/V sensor).
fn analog_stroke(r: &mut Rows, sd_mm: f64) {
    let mut rng = Rng::new(0x57_0CE);
    for x in &mut r.columns[1] {
        *x += sd_mm * rng.normal();
    }
}

fn analog_stroke_1um(r: &mut Rows) {
    analog_stroke(r, 0.001);
}

fn analog_stroke_5um(r: &mut Rows) {
    analog_stroke(r, 0.005);
}

/// A tracker whose angle reaches the recording `rows` samples late.
fn tracker_late(r: &mut Rows, rows: usize) {
    let a = &mut r.columns[2];
    let first = a[0];
    a.rotate_right(rows);
    a[..rows].fill(first);
}

fn tracker_20_ms_late(r: &mut Rows) {
    tracker_late(r, 10);
}

fn tracker_50_ms_late(r: &mut Rows) {
    tracker_late(r, 25);
}

fn tracker_200_ms_late(r: &mut Rows) {
    tracker_late(r, 100);
}

/// Writes the recording of `seed` (clean, or with `effect`) into `rec` with `change` made.
fn write_with(rec: &Path, seed: u64, effect: Option<(Effect, Size, usize)>, change: Change) {
    let bench = Bench {
        effect,
        duration_s: 300.0,
        seed,
    };
    third_generator::write_recording(Path::new(&shipped_design("joint-a.toml")), &bench, rec);
    let csv = rec.join("data.csv");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_owned();
    assert_eq!(header, "time_s,stroke_mm,angle_deg,v1_V");
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let mut r = Rows {
        header,
        columns: (0..4)
            .map(|k| rows.iter().map(|row| row[k]).collect())
            .collect(),
        sample_hz: third_generator::SAMPLE_HZ,
    };
    match change {
        Change::Voltage(artefact) => {
            let v = &r.columns[3];
            // The noise's spread from the differences of successive samples (the signal is
            // slow).
            let diffs: Vec<f64> = v.windows(2).map(|w| w[1] - w[0]).collect();
            let mean = diffs.iter().sum::<f64>() / diffs.len() as f64;
            let var = diffs.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / diffs.len() as f64;
            let sigma = (var / 2.0).sqrt();
            let (t, rest) = r.columns.split_at_mut(3);
            artefact(&t[0], &mut rest[0], sigma);
        }
        Change::Rows(change) => change(&mut r),
    }
    let mut out = r.header.clone();
    out.push('\n');
    for i in 0..r.columns[0].len() {
        let c = |k: usize| r.columns[k][i];
        out.push_str(&format!(
            "{:.6},{:.6},{:.4},{:.6}\n",
            c(0),
            c(1),
            c(2),
            c(3)
        ));
    }
    std::fs::write(&csv, out).unwrap();
    let rig = rec.join("rig.toml");
    let text = std::fs::read_to_string(&rig).unwrap();
    let hz = format!("sample_hz = {:.1}", third_generator::SAMPLE_HZ);
    assert!(text.contains(&hz), "{text}");
    std::fs::write(
        &rig,
        text.replace(&hz, &format!("sample_hz = {:.1}", r.sample_hz)),
    )
    .unwrap();
}

/// `dlw discover --json` on each seed's clean recording with `artefact`.
fn reports(name: &str, artefact: Artefact) -> Vec<(String, serde_json::Value)> {
    reports_of(name, &SEEDS, None, Change::Voltage(artefact))
}

/// `dlw discover --json` on each of `seeds`' recordings (clean, or with `effect`) with `change`.
fn reports_of(
    name: &str,
    seeds: &[u64],
    effect: Option<(Effect, Size, usize)>,
    change: Change,
) -> Vec<(String, serde_json::Value)> {
    let dir = tempfile::tempdir().unwrap();
    seeds
        .par_iter()
        .map(|&seed| {
            let case = format!("{name}-{seed}");
            let rec = dir.path().join(&case);
            write_with(&rec, seed, effect, change);
            let out = dir.path().join(format!("{case}-out"));
            let json = try_discover_json(&shipped_design("joint-a.toml"), &rec, &out)
                .unwrap_or_else(|e| panic!("{case}: {e}"));
            (case, json)
        })
        .collect()
}

/// Every report names nothing, flags nothing and leaves nothing ambiguous.
fn assert_quiet(name: &str, artefact: Artefact) {
    assert_quiet_with(name, Change::Voltage(artefact));
}

/// As [`assert_quiet`], for any change.
fn assert_quiet_with(name: &str, change: Change) {
    for (case, json) in reports_of(name, &SEEDS, None, change) {
        assert_said_nothing(&case, &json);
    }
}

/// `json` names nothing, flags nothing and leaves nothing ambiguous.
fn assert_said_nothing(case: &str, json: &serde_json::Value) {
    assert!(named(json).is_empty(), "{case}: named {:?}", named(json));
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

#[test]
fn heavy_tailed_or_flicker_noise_is_not_an_effect() {
    assert_quiet("heavy-tails", heavy_tails);
    assert_quiet("flicker", flicker);
}

#[test]
fn a_slower_logger_or_a_coarser_tracker_is_not_an_effect() {
    assert_quiet_with("100-hz", Change::Rows(at_100_hz));
    assert_quiet_with("tracker-0.1", Change::Rows(tracker_to_a_tenth));
}

/// A noisy stroke: discovery takes the stroke as exact, and a plant candidate that filters it
/// (a backlash's play) earns evidence by removing its noise. So a recording either names
/// nothing or is refused for the stroke's noise, with the bound; never a name, and never
/// refused for want of a rest it has. Before (2026-11-28), 1 µm ended the 10 s rest after
/// 2.8 s and the recording was refused for that; with the rest found, 5 µm named `backlash`
/// on 2 of 3 clean recordings (seeds 21001-21003).
#[test]
fn a_noisy_stroke_names_nothing_or_is_refused_for_its_noise() {
    refused_or_quiet(
        &[
            ("stroke-1um", analog_stroke_1um, false),
            ("stroke-5um", analog_stroke_5um, true),
        ],
        &["the stroke is noisy", "20-nat screen"],
    );
}

/// A case of [`refused_or_quiet`]: a name, a change to the clean recordings of [`SEEDS`], and
/// whether it must be refused.
type Case<'a> = (&'a str, fn(&mut Rows), bool);

/// Each of `cases` names nothing or is refused with every one of `reason`, with nothing
/// written.
fn refused_or_quiet(cases: &[Case<'_>], reason: &[&str]) {
    let design = shipped_design("joint-a.toml");
    for &(name, change, refused) in cases {
        let dir = tempfile::tempdir().unwrap();
        for seed in SEEDS {
            let case = format!("{name}-{seed}");
            let rec = dir.path().join(&case);
            write_with(&rec, seed, None, Change::Rows(change));
            let out = dir.path().join(format!("{case}-out"));
            match try_discover_json(&design, &rec, &out) {
                Ok(json) => {
                    assert!(!refused, "{case}: not refused");
                    assert_said_nothing(&case, &json);
                }
                Err(e) => {
                    assert!(reason.iter().all(|r| e.contains(r)), "{case}: {e}");
                    assert!(!out.exists(), "{case}: output written");
                }
            }
        }
    }
}

/// A tracker late against the DAQ is refused with its delay against both the stroke and the
/// voltage, where 50 ms named `backlash` on the plant (seed 3) and 200 ms `rate` and `creep` on
/// the sensor (seeds 3 and 4) before, with exit 0 (`discover::clock`). At 20 ms, which the
/// delays cannot tell from zero on seed 3, it names nothing.
#[test]
fn a_late_tracker_is_refused_not_named() {
    refused_or_quiet(
        &[
            ("late-20ms", tracker_20_ms_late, false),
            ("late-50ms", tracker_50_ms_late, true),
            ("late-200ms", tracker_200_ms_late, true),
        ],
        &["angle is late", "against the stroke"],
    );
}

/// A hysteresis at its detection size is still named first on its sensor, and nothing else is
/// named, whatever the logger: `ambiguous` only on the sensor with `hysteresis` among the
/// contenders (the rule).
#[test]
fn a_hysteresis_is_still_named_under_another_loggers_noise_and_rate() {
    let hysteresis = Some((Effect::Hysteresis, Size(2.0), 1));
    let truth = ("hysteresis".to_owned(), "sensor1".to_owned());
    for (name, change) in [
        ("hysteresis-heavy-tails", Change::Voltage(heavy_tails)),
        ("hysteresis-100-hz", Change::Rows(at_100_hz)),
    ] {
        for (case, json) in reports_of(name, &EFFECT_SEEDS, hysteresis, change) {
            let names = named(&json);
            assert_eq!(names.first(), Some(&truth), "{case}: named {names:?}");
            assert!(names.iter().all(|n| *n == truth), "{case}: named {names:?}");
            for a in json["ambiguous"].as_array().unwrap() {
                assert!(
                    a["channel"] == "sensor1" && contenders(a).contains(&truth.0),
                    "{case}: ambiguous {a}"
                );
            }
        }
    }
}
