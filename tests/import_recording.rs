//! `dlw import-recording` on files written the way a bench writes them: a DAQ's CSV export
//! (time, a linear sensor's voltage, a noise channel, a stroke voltage, a PI sensor's voltage)
//! and an NDI Aurora log (CSV, NDI Track's columns with `ToolInfo`, `Port:1` handles and
//! `Missing` frames), built by this test from a known truth with its own generator: a stroke
//! pattern, an angle that follows it with a 30 ms lag, a linear sensor and a hysteretic (PI)
//! one, a tracker at 40 Hz whose clock is 0.437 s late and runs 250 ppm fast, 1.1 % of its
//! frames missing in bursts, a tracker frame turned against the joint's, a 5-DOF tip tool
//! (its roll is noise) and a 6-DOF reference tool on the base that moves. The generator is
//! `tests/common/bench.rs`.

mod common;
use common::bench::*;
use common::{arg, dlw, shipped_design};

use std::fmt::Write as _;
use std::path::Path;

fn import(dir: &Path, extra: &[&str]) -> std::process::Output {
    import_daq(dir, "daq.csv", extra)
}

/// `dlw import-recording` with the DAQ file `daq` of `dir`.
fn import_daq(dir: &Path, daq: &str, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "import-recording".to_owned(),
        "--daq".into(),
        arg(&dir.join(daq)),
        "--supply-v".into(),
        SUPPLY_V.to_string(),
        "--stroke-mm-per-v".into(),
        MM_PER_V.to_string(),
        "--tracker".into(),
        arg(&dir.join("aurora.csv")),
        "--json".into(),
    ];
    if !extra.contains(&"-o") {
        args.extend(["-o".to_owned(), arg(&dir.join("rec"))]);
    }
    if !extra.contains(&"--voltage") {
        args.extend(["--voltage".to_owned(), "AI0".to_owned()]);
    }
    if !extra.contains(&"--divider-ohm") {
        args.extend(["--divider-ohm".to_owned(), DIVIDER.to_string()]);
    }
    if !extra.contains(&"--stroke") {
        args.extend(["--stroke".to_owned(), "AI2".to_owned()]);
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    dlw(&args)
}

/// The imported angle matches the truth to 0.3° RMSE, the offset is found within 2 ms and the
/// drift within 30 ppm, and `dlw fit` recovers the gauge factor within 1 %.
#[test]
fn a_bench_import_recovers_the_angle_the_clocks_and_the_gauge_factor() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_5DOF);
    let o = import(dir.path(), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let a = &j["alignment"];
    let offset = a["offset_s"].as_f64().unwrap();
    let drift = a["drift_ppm"].as_f64().unwrap();
    eprintln!("{j}");
    assert!((offset - OFFSET_S).abs() < 0.002, "offset {offset} s");
    assert!((drift - DRIFT_PPM).abs() < 30.0, "drift {drift} ppm");
    assert!(j["tracker"]["missing_frames"].as_u64().unwrap() > 0, "{j}");

    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    let s = &rec.samples;
    let (mut ss, mut n) = (0.0, 0);
    for i in s.valid_angle_rows() {
        let e = s.angle_deg[i] - truth.angle_deg(s.time_s[i]);
        ss += e * e;
        n += 1;
    }
    let rmse = (ss / n as f64).sqrt();
    assert!(rmse < 0.3, "angle RMSE {rmse}° over {n} rows");
    assert!(
        s.invalid_angle_rows() > 0,
        "the gaps and the ends are marked"
    );
    assert!(rec.rig.import.is_some());

    let cfg = dir.path().join("fit.toml");
    let o = dlw(&[
        "fit",
        "--design",
        &shipped_design("joint-a.toml"),
        &arg(&dir.path().join("rec")),
        "--model",
        "linear",
        "-o",
        &arg(&cfg),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&cfg).unwrap();
    let gf: f64 = text
        .lines()
        .find_map(|l| l.trim().strip_prefix("gauge_factor = "))
        .and_then(|v| v.parse().ok())
        .expect("a gauge_factor line");
    eprintln!("linear sensor: GF {gf} against {GF}");
    assert!((gf - GF).abs() < 0.01 * GF, "GF {gf} against {GF}");

    // Discovery reads an imported recording (no simulated scenario in it).
    let o = dlw(&[
        "discover",
        "--design",
        &shipped_design("joint-a.toml"),
        &arg(&dir.path().join("rec")),
        "-o",
        &arg(&dir.path().join("discovered")),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A field of the `dlw fit --compare --json` output: `key` of the entry of `list` whose
/// `model` is `model`.
fn model_figure(json: &serde_json::Value, model: &str, key: &str) -> f64 {
    json.as_array()
        .and_then(|l| l.iter().find(|m| m["model"] == model))
        .and_then(|m| m[key].as_f64())
        .unwrap_or_else(|| panic!("no {key} for {model} in {json}"))
}

/// The PI sensor (AI3) beside the linear one (AI0): imported as sensor 2, the clocks aligned on
/// the linear sensor 1, then taken alone as a one-sensor recording (joint A has one sensor
/// plane), `dlw fit --compare` finds the PI model explains its resistance far better than the
/// line, and the runtime estimator with the fitted PI config follows the angle within 0.7°
/// (measured 0.46° PI, 1.22° linear; 20 Ω against 960 Ω residual).
#[test]
fn a_pi_sensor_is_fitted_better_by_the_pi_model_than_by_the_line() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_5DOF);
    let divider = format!("{DIVIDER},{DIVIDER}");
    let o = import(
        dir.path(),
        &["--voltage", "AI0,AI3", "--divider-ohm", &divider],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let offset = j["alignment"]["offset_s"].as_f64().unwrap();
    assert!((offset - OFFSET_S).abs() < 0.002, "offset {offset} s");
    let mut rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    assert_eq!(rec.samples.volts.len(), 2);
    rec.samples.volts.remove(0);
    rec.rig.divider_ohm.remove(0);
    let pi_rec = dir.path().join("rec_pi");
    rec.write(&pi_rec, false).unwrap();
    let o = dlw(&[
        "fit",
        "--design",
        &shipped_design("joint-a.toml"),
        &arg(&pi_rec),
        "--compare",
        "--model",
        "pi",
        "--validate",
        &arg(&pi_rec),
        "-o",
        &arg(&dir.path().join("pi.toml")),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let models = &j["sensors"][0]["models"];
    let (line_ohm, pi_ohm) = (
        model_figure(models, "linear", "rmse_ohm"),
        model_figure(models, "pi", "rmse_ohm"),
    );
    let (line_deg, pi_deg) = (
        model_figure(&j["validation"], "linear", "rmse_deg"),
        model_figure(&j["validation"], "pi", "rmse_deg"),
    );
    eprintln!("PI sensor: residual {pi_ohm} Ω (PI) against {line_ohm} Ω (line); angle RMSE {pi_deg}° (PI) against {line_deg}° (line)");
    assert!(pi_ohm < 0.1 * line_ohm, "PI {pi_ohm} Ω, line {line_ohm} Ω");
    assert!(pi_deg < 0.7, "PI config's angle RMSE {pi_deg}°");
    assert!(pi_deg < 0.6 * line_deg, "PI {pi_deg}°, line {line_deg}°");
}

/// With a reference tool on a base that sways by 3°, the angle relative to it still matches.
#[test]
fn a_reference_tool_cancels_the_base_motion() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(
        dir.path(),
        Tools {
            tip_5dof: true,
            reference_moves: true,
        },
    );
    let o = import(dir.path(), &["--reference-tool", "2"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    let s = &rec.samples;
    let rows = s.valid_angle_rows();
    let rmse = (rows
        .iter()
        .map(|&i| (s.angle_deg[i] - truth.angle_deg(s.time_s[i])).powi(2))
        .sum::<f64>()
        / rows.len() as f64)
        .sqrt();
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
}

/// `--report DIR`: the page and its four figures (lag, before, after, angle), each SVG that
/// parses, the page naming the alignment's figures; a failing import writes neither the
/// report nor the recording, and an existing report folder is not replaced without --force.
#[test]
fn the_report_shows_the_clocks_and_the_gaps() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_5DOF);
    let report = dir.path().join("report");
    let o = import(dir.path(), &["--report", &arg(&report)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let html = std::fs::read_to_string(report.join("report.html")).unwrap();
    for name in ["lag", "before", "after", "angle"] {
        let file = format!("{name}.svg");
        assert!(
            html.contains(&format!("src=\"{file}\"")),
            "{file} not in the page"
        );
        let svg = std::fs::read_to_string(report.join(&file)).unwrap();
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{file}: {e}"));
    }
    let offset_ms = j["alignment"]["offset_s"].as_f64().unwrap() * 1e3;
    assert!(
        html.contains(&format!("{offset_ms:.2}")),
        "the offset in the page"
    );
    let invalid = j["invalid_rows"].as_u64().unwrap();
    assert!(
        html.contains(&format!("the {invalid} rows without a tracker angle")),
        "{html}"
    );
    assert!(!html.contains("NaN"));

    // Failure: nothing written. An existing report folder: refused without --force.
    let (rec2, report2) = (dir.path().join("rec2"), dir.path().join("report2"));
    let o = import(
        dir.path(),
        &[
            "--voltage",
            "AI9",
            "-o",
            &arg(&rec2),
            "--report",
            &arg(&report2),
        ],
    );
    assert!(!o.status.success());
    assert!(!rec2.exists() && !report2.exists());
    let o = import(dir.path(), &["-o", &arg(&rec2), "--report", &arg(&report)]);
    assert!(!o.status.success(), "an existing report was replaced");
    assert!(!rec2.exists());
}

/// The README tour's example bench (`examples/bench/`): the first 60 s of this test's bench
/// (5-DOF tip, still base). Run by hand to regenerate it:
/// `DLW_WRITE_EXAMPLE_BENCH=1 cargo test --test import_recording -- --ignored example_bench`.
/// Without the variable it checks that the shipped files are what the generator writes.
#[test]
#[ignore = "writes examples/bench/ when asked; see its doc"]
fn example_bench() {
    let dir = tempfile::tempdir().unwrap();
    write_bench_for(dir.path(), STILL_5DOF, EXAMPLE_BENCH_S);
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/bench");
    for name in ["daq.csv", "aurora.csv"] {
        let made = std::fs::read(dir.path().join(name)).unwrap();
        if std::env::var_os("DLW_WRITE_EXAMPLE_BENCH").is_some() {
            std::fs::write(shipped.join(name), &made).unwrap();
        } else {
            assert!(
                std::fs::read(shipped.join(name)).ok() == Some(made),
                "examples/bench/{name} is not what the generator writes"
            );
        }
    }
}

/// The example bench's length (s).
const EXAMPLE_BENCH_S: f64 = 60.0;

/// Bad input: a missing channel, a still recording, an output that exists; nothing written.
#[test]
fn bad_input_is_refused_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    let o = import(dir.path(), &["--voltage", "AI9"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("AI9") && err.contains("Time,AI0"), "{err}");
    assert!(!dir.path().join("rec").exists());
    let o = import(dir.path(), &["--daq-format", "tdms"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("not the TDMS tag"), "{err}");
    assert!(!dir.path().join("rec").exists());
    let o = import(dir.path(), &["--daq-format", "xlsx"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("\"xlsx\" is not one of csv, tdms, lvm"),
        "{err}"
    );
    assert!(!dir.path().join("rec").exists());
}

/// Converts the bench's `daq.csv` into `daq.tdms` with npTDMS (`tests/scripts/tdms_fixture.py
/// bench`): four segments; AI0 as i16 counts with a linear scale, AI1 f64, AI2 f32; time from
/// `wf_increment`.
fn write_bench_tdms(dir: &Path) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts/tdms_fixture.py");
    let out = std::process::Command::new("python3")
        .arg(script)
        .args(["bench", &arg(&dir.join("daq.csv")), &arg(&dir.join("daq.tdms")), "4"])
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 ({e}): this test needs python3 with npTDMS (scripts/test.sh installs it)"));
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The imported angle's RMSE against the truth over the valid rows (°).
fn angle_rmse(rec: &Path, truth: &Truth) -> f64 {
    let rec = dlw::recording::Recording::read(rec).unwrap();
    let s = &rec.samples;
    let rows = s.valid_angle_rows();
    (rows
        .iter()
        .map(|&i| (s.angle_deg[i] - truth.angle_deg(s.time_s[i])).powi(2))
        .sum::<f64>()
        / rows.len() as f64)
        .sqrt()
}

/// The same bench with its DAQ side as a TDMS file written by npTDMS (format chosen from the
/// extension, channels named bare and as Group/Channel): the same acceptance as the CSV.
#[test]
fn a_tdms_bench_import_recovers_the_angle_and_the_clocks() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_6DOF);
    write_bench_tdms(dir.path());
    let o = import_daq(dir.path(), "daq.tdms", &["--stroke", "daq/AI2"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    eprintln!("{j}");
    let offset = j["alignment"]["offset_s"].as_f64().unwrap();
    let drift = j["alignment"]["drift_ppm"].as_f64().unwrap();
    assert!((offset - OFFSET_S).abs() < 0.002, "offset {offset} s");
    assert!((drift - DRIFT_PPM).abs() < 30.0, "drift {drift} ppm");
    assert_eq!(j["samples"].as_u64(), Some((DURATION_S * DAQ_HZ) as u64));
    let rmse = angle_rmse(&dir.path().join("rec"), &truth);
    eprintln!("angle RMSE {rmse}°");
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    assert!(
        (rec.rig.sample_hz - DAQ_HZ).abs() < 1e-6,
        "{}",
        rec.rig.sample_hz
    );
}

/// Bad TDMS input: a file cut mid-segment, a channel that is not there, DAQmx raw data; an
/// error that says so, and nothing written.
#[test]
fn bad_tdms_is_refused_with_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    write_bench_tdms(dir.path());
    let bytes = std::fs::read(dir.path().join("daq.tdms")).unwrap();
    let refused = |daq: &str, extra: &[&str], wanted: &[&str]| {
        let o = import_daq(dir.path(), daq, extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{daq} {extra:?} was accepted");
        for w in wanted {
            assert!(err.contains(w), "{daq} {extra:?}: {err:?} lacks {w:?}");
        }
        assert!(!dir.path().join("rec").exists(), "{daq} {extra:?} wrote");
    };
    std::fs::write(dir.path().join("cut.tdms"), &bytes[..bytes.len() * 3 / 8]).unwrap();
    refused("cut.tdms", &[], &["truncated mid-segment"]);
    refused(
        "daq.tdms",
        &["--voltage", "AI9"],
        &["AI9", "daq/AI0, daq/AI1, daq/AI2"],
    );
    // DAQmx raw data: AI0's raw data index made DAQmx's format-changing scaler header.
    let path = b"/'daq'/'AI0'";
    let at = bytes
        .windows(path.len())
        .position(|w| w == path)
        .expect("AI0's path")
        + path.len();
    let mut daqmx = bytes.clone();
    daqmx[at..at + 4].copy_from_slice(&0x6912_0000u32.to_le_bytes());
    std::fs::write(dir.path().join("daqmx.tdms"), daqmx).unwrap();
    refused("daqmx.tdms", &[], &["DAQmx raw data", "export scaled data"]);
}

/// Converts the bench's `daq.csv` into a LabVIEW measurement file `name`: separator `sep`
/// (`Tab` or `Comma`), decimal separator `decimal`, `segments` segments each with its header,
/// and the time in an `X_Value` column, or (with `x_column` false) empty `X_Value` fields and
/// the time from each segment's `X0` and `Delta_X`.
fn write_bench_lvm(
    dir: &Path,
    name: &str,
    sep: &str,
    decimal: char,
    x_column: bool,
    segments: usize,
) {
    let csv = std::fs::read_to_string(dir.join("daq.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let s = if sep == "Tab" { "\t" } else { "," };
    let num = |v: &str| v.replace('.', &decimal.to_string());
    let mut out = format!(
        "LabVIEW Measurement{s}\nWriter_Version{s}2\nReader_Version{s}2\nSeparator{s}{sep}\n\
         Decimal_Separator{s}{decimal}\nMulti_Headings{s}Yes\nX_Columns{s}{}\n\
         Time_Pref{s}Relative\nOperator{s}bench\nDate{s}2026/11/25\nTime{s}18:00:00\n\
         ***End_of_Header***{s}\n{s}\n",
        if x_column { "One" } else { "No" }
    );
    let per = rows.len().div_ceil(segments);
    for chunk in rows.chunks(per) {
        let x0 = num(chunk[0][0]);
        let dx = num(&format!("{}", 1.0 / DAQ_HZ));
        writeln!(out, "Channels{s}3{s}{s}{s}").unwrap();
        let n = chunk.len();
        writeln!(out, "Samples{s}{n}{s}{n}{s}{n}{s}").unwrap();
        writeln!(out, "Date{s}2026/11/25{s}2026/11/25{s}2026/11/25{s}").unwrap();
        writeln!(out, "X_Dimension{s}Time{s}Time{s}Time{s}").unwrap();
        writeln!(out, "X0{s}{x0}{s}{x0}{s}{x0}{s}").unwrap();
        writeln!(out, "Delta_X{s}{dx}{s}{dx}{s}{dx}{s}").unwrap();
        writeln!(out, "***End_of_Header***{s}{s}{s}{s}").unwrap();
        writeln!(out, "X_Value{s}AI0{s}AI1{s}AI2{s}Comment").unwrap();
        for r in chunk {
            let t = if x_column { num(r[0]) } else { String::new() };
            writeln!(out, "{t}{s}{}{s}{}{s}{}", num(r[1]), num(r[2]), num(r[3])).unwrap();
        }
    }
    std::fs::write(dir.join(name), out).unwrap();
}

/// The bench's DAQ side as LabVIEW measurement files written here by hand: tab-separated with
/// a decimal point and an X column; comma-separated with a decimal point, two segments; tab-
/// separated with a decimal comma, no X column (time from X0 and Delta_X), three segments.
/// Each imports to the CSV's acceptance.
#[test]
fn lvm_bench_imports_recover_the_angle_and_the_clocks() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_6DOF);
    for (k, (sep, decimal, x, segments)) in [
        ("Tab", '.', true, 1),
        ("Comma", '.', true, 2),
        ("Tab", ',', false, 3),
    ]
    .into_iter()
    .enumerate()
    {
        let name = format!("daq{k}.lvm");
        write_bench_lvm(dir.path(), &name, sep, decimal, x, segments);
        let rec = format!("rec{k}");
        let o = import_daq(dir.path(), &name, &["-o", &arg(&dir.path().join(&rec))]);
        let what = format!("{sep} {decimal:?} X column {x}, {segments} segment(s)");
        assert!(
            o.status.success(),
            "{what}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        let offset = j["alignment"]["offset_s"].as_f64().unwrap();
        let drift = j["alignment"]["drift_ppm"].as_f64().unwrap();
        let rmse = angle_rmse(&dir.path().join(&rec), &truth);
        eprintln!("{what}: offset {offset} s, drift {drift} ppm, angle RMSE {rmse}°");
        assert!(
            (offset - OFFSET_S).abs() < 0.002,
            "{what}: offset {offset} s"
        );
        assert!(
            (drift - DRIFT_PPM).abs() < 30.0,
            "{what}: drift {drift} ppm"
        );
        assert!(rmse < 0.3, "{what}: angle RMSE {rmse}°");
        assert_eq!(
            j["samples"].as_u64(),
            Some((DURATION_S * DAQ_HZ) as u64),
            "{what}"
        );
    }
    // An unknown channel lists the columns there are; nothing is written.
    let o = import_daq(
        dir.path(),
        "daq2.lvm",
        &["--voltage", "AI9", "-o", &arg(&dir.path().join("bad"))],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("AI9") && err.contains("AI0, AI1, AI2"),
        "{err}"
    );
    assert!(!dir.path().join("bad").exists());
}

/// The TTL level (0 or 1) of a sync pulse train at DAQ time `t`: 0.4 s pulses at irregular
/// intervals (4.6 to 7.6 s), the first at 2 s, after both logs have started.
fn sync_level(t: f64) -> f64 {
    let mut start = 2.0;
    for k in 0..1000 {
        if t < start {
            return 0.0;
        }
        if t < start + 0.4 {
            return 1.0;
        }
        start += 6.1 + 1.5 * (1.3 * f64::from(k)).sin();
    }
    0.0
}

/// Adds the sync pulse to the bench's files: a `SYNC` column (0/5 V) to `daq.csv`, and a `Sync`
/// column (the level at each frame's time) to `aurora.csv`, as a lab's own logger would.
fn add_sync_pulse(dir: &Path) {
    add_sync_pulse_latency(dir, 0.0);
}

/// [`add_sync_pulse`], the tracker logging each pose `latency_s` after the pulse level it
/// writes beside it (a tracker's own processing latency, which a pulse cannot show).
fn add_sync_pulse_latency(dir: &Path, latency_s: f64) {
    let daq = std::fs::read_to_string(dir.join("daq.csv")).unwrap();
    let mut out = String::new();
    for (i, line) in daq.lines().enumerate() {
        if i == 0 {
            writeln!(out, "{line},SYNC").unwrap();
        } else {
            let t: f64 = line.split(',').next().unwrap().parse().unwrap();
            writeln!(out, "{line},{:.3}", 5.0 * sync_level(t)).unwrap();
        }
    }
    std::fs::write(dir.join("daq.csv"), out).unwrap();
    let ndi = std::fs::read_to_string(dir.join("aurora.csv")).unwrap();
    let mut out = String::new();
    for (i, line) in ndi.lines().enumerate() {
        if i == 0 {
            writeln!(out, "{line},Sync").unwrap();
        } else {
            let frame: f64 = line.split(',').nth(2).unwrap().parse().unwrap();
            let tau = (frame - 1000.0) / TRACKER_HZ;
            let t = OFFSET_S + tau * (1.0 + DRIFT_PPM * 1e-6);
            writeln!(out, "{line},{}", sync_level(t + latency_s)).unwrap();
        }
    }
    std::fs::write(dir.join("aurora.csv"), out).unwrap();
}

/// `--sync SYNC --tracker-sync-column Sync`: the clocks from the pulse's edges. A tracker
/// frame only says the edge came since the last frame (25 ms at 40 Hz), so the offset is
/// known to about 2 ms here (its reported standard error), not better than auto; the test
/// holds the found values to three of their reported standard errors, and the angle to 0.3°.
#[test]
fn a_sync_pulse_aligns_the_clocks() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_6DOF);
    add_sync_pulse(dir.path());
    let o = import(
        dir.path(),
        &["--sync", "SYNC", "--tracker-sync-column", "Sync"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    eprintln!("{j}");
    let a = &j["alignment"];
    assert_eq!(a["method"], "pulse");
    let edges = a["sync_edges"].as_u64().unwrap();
    assert!(edges >= 30, "{edges} edges");
    let (offset, offset_se) = (
        a["offset_s"].as_f64().unwrap(),
        a["offset_uncertainty_s"].as_f64().unwrap(),
    );
    let (drift, drift_se) = (
        a["drift_ppm"].as_f64().unwrap(),
        a["drift_uncertainty_ppm"].as_f64().unwrap(),
    );
    assert!(offset_se < 0.005 && drift_se < 30.0, "{a}");
    assert!(
        (offset - OFFSET_S).abs() < 3.0 * offset_se,
        "offset {offset} s ± {offset_se}"
    );
    assert!(
        (drift - DRIFT_PPM).abs() < 3.0 * drift_se,
        "drift {drift} ppm ± {drift_se}"
    );
    let rmse = angle_rmse(&dir.path().join("rec"), &truth);
    eprintln!("angle RMSE {rmse}°");
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    assert_eq!(rec.rig.import.unwrap().alignment_method, "pulse");
    assert_eq!(
        rec.samples.volts.len(),
        1,
        "the sync channel is not a sensor"
    );

    // Without the tracker's column, or with one the log does not have: refused, nothing written.
    let out = dir.path().join("bad");
    let o = import(dir.path(), &["--sync", "SYNC", "-o", &arg(&out)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--tracker-sync-column"),
        "{err}"
    );
    let o = import(
        dir.path(),
        &[
            "--sync",
            "SYNC",
            "--tracker-sync-column",
            "TTL",
            "-o",
            &arg(&out),
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("\"TTL\"") && err.contains("Frame#"),
        "{err}"
    );
    // A DAQ channel with no pulse on it.
    let o = import(
        dir.path(),
        &[
            "--sync",
            "AI1",
            "--tracker-sync-column",
            "Sync",
            "-o",
            &arg(&out),
        ],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "noise on AI1 aligned");
    eprintln!("AI1 as the sync channel: {err}");
    assert!(!out.exists());
}

/// A tracker whose poses come 150 ms after the pulse level it logs beside them: the pulse
/// aligns the clocks it sees, and the angle would be 150 ms off the DAQ's channels. The
/// import's own check after the alignment refuses it (the angle predicted from sensor 1
/// departs from the tracker's, and the sensor shifted by the latency would not), with nothing
/// written; a recording written late by other means is refused by `fit` and `discover`
/// (`src/recording/clock.rs`, `tests/clipped_recordings.rs`).
#[test]
fn a_tracker_late_behind_its_sync_pulse_is_refused_by_the_import() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    add_sync_pulse_latency(dir.path(), -0.15);
    let o = import(
        dir.path(),
        &["--sync", "SYNC", "--tracker-sync-column", "Sync"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("the clocks do not line up") && err.contains("+0.15"),
        "{err}"
    );
    assert!(!dir.path().join("rec").exists());
}

/// A DAQ channel clipped by its input range (the linear sensor's voltage held at its 90th
/// percentile): the import writes it with a warning naming the column; `fit` refuses it.
#[test]
fn a_clipped_daq_channel_is_warned_of_and_refused_by_fit() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    let daq = std::fs::read_to_string(dir.path().join("daq.csv")).unwrap();
    let mut lines = daq.lines();
    let header = lines.next().unwrap();
    let at = header.split(',').position(|c| c == "AI0").unwrap();
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    let mut values: Vec<f64> = rows.iter().map(|r| r[at].parse().unwrap()).collect();
    values.sort_by(f64::total_cmp);
    let limit = values[values.len() * 9 / 10];
    let mut out = format!("{header}\n");
    for mut r in rows {
        if r[at].parse::<f64>().unwrap() > limit {
            r[at] = limit.to_string();
        }
        writeln!(out, "{}", r.join(",")).unwrap();
    }
    std::fs::write(dir.path().join("daq.csv"), out).unwrap();
    let o = import(dir.path(), &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    eprintln!("{err}");
    assert!(
        err.contains("warning:")
            && err.contains("v1_V holds its largest value")
            && err.contains("will refuse it"),
        "{err}"
    );
    let o = dlw(&[
        "fit",
        "--design",
        &shipped_design("joint-a.toml"),
        &arg(&dir.path().join("rec")),
        "-o",
        &arg(&dir.path().join("fit.toml")),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("v1_V holds its largest value"),
        "{err}"
    );
}

/// `--rate-hz 100` on the 500 Hz bench: 100 rows a second, each sensor voltage the mean of the
/// DAQ's five samples around it, the angle still within 0.3°; rates out of bounds refused with
/// nothing written.
#[test]
fn rate_hz_resamples_the_daq() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_6DOF);
    let o = import(dir.path(), &["--rate-hz", "100"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    assert_eq!(rec.rig.sample_hz, 100.0);
    let s = &rec.samples;
    assert_eq!(s.time_s.len(), (DURATION_S * 100.0) as usize);
    let daq: Vec<(f64, f64)> = std::fs::read_to_string(dir.path().join("daq.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| {
            let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (f[0], f[1])
        })
        .collect();
    for j in [1, 777, 12_345, 23_998] {
        let t = j as f64 / 100.0;
        let inside: Vec<f64> = daq
            .iter()
            .filter(|(u, _)| *u >= t - 0.005 - 1e-9 && *u < t + 0.005 - 1e-9)
            .map(|(_, v)| *v)
            .collect();
        assert_eq!(inside.len(), 5, "row {j}");
        let mean = inside.iter().sum::<f64>() / 5.0;
        assert!(
            (s.volts[0][j] - mean).abs() < 1e-6,
            "row {j}: {} against {mean}",
            s.volts[0][j]
        );
    }
    let rmse = angle_rmse(&dir.path().join("rec"), &truth);
    eprintln!("angle RMSE at 100 Hz {rmse}°");
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
    let out = dir.path().join("bad");
    for (hz, says) in [
        ("0", "not a rate"),
        ("5001", "at most 10 times"),
        ("0.1", "leaves 24 samples"),
    ] {
        let o = import(dir.path(), &["--rate-hz", hz, "-o", &arg(&out)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains(says),
            "--rate-hz {hz}: {err}"
        );
        assert!(!out.exists());
    }
}
