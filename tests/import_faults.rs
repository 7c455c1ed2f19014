//! Issue 30: `dlw import-recording` on the faults a real bench produces, each of which it used
//! to answer with confidence (exit 0, a wrong angle): a DAQ that dropped a second of samples,
//! a tracker log with frames absent or a frame counter that jumps two hours, a rest window
//! that is not still, values its own readers refuse, clocks beyond what the search can see.
//! Each is made from the bench of `tests/common/bench.rs` (a known truth); the import must
//! either recover the angle to the bench's accuracy or refuse, saying where and by how much,
//! with nothing written.

use crate::common;
use common::bench::*;
use common::{arg, dlw};

use std::path::Path;

/// `dlw import-recording --json` on `dir`'s `daq` and `tracker`, output `dir/rec` unless `-o`
/// is among `extra`.
fn import_files(dir: &Path, daq: &str, tracker: &str, extra: &[&str]) -> std::process::Output {
    let mut args: Vec<String> = [
        "import-recording",
        "--daq",
        &arg(&dir.join(daq)),
        "--stroke-mm-per-v",
        &MM_PER_V.to_string(),
        "--tracker",
        &arg(&dir.join(tracker)),
        "--stroke",
        "AI2",
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    if !extra.contains(&"-o") {
        args.extend(["-o".into(), arg(&dir.join("rec"))]);
    }
    if !extra.contains(&"--supply-v") {
        args.extend(["--supply-v".into(), SUPPLY_V.to_string()]);
    }
    if !extra.contains(&"--voltage") {
        args.extend(["--voltage".into(), "AI0".into()]);
    }
    if !extra.contains(&"--divider-ohm") {
        args.extend(["--divider-ohm".into(), DIVIDER.to_string()]);
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    dlw(&args)
}

fn import(dir: &Path, extra: &[&str]) -> std::process::Output {
    import_files(dir, "daq.csv", "aurora.csv", extra)
}

/// The import succeeded: its JSON.
fn accepted(o: &std::process::Output) -> serde_json::Value {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    eprintln!("{j}");
    j
}

/// The import was refused, saying each of `says`, with nothing at `dir/rec`: its message.
fn refused(dir: &Path, o: &std::process::Output, says: &[&str]) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    eprintln!("{err}");
    assert!(!o.status.success(), "accepted: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for s in says {
        assert!(err.contains(s), "{err:?} does not say {s:?}");
    }
    assert!(!dir.join("rec").exists(), "a recording was written");
    err
}

/// The imported angle's RMS and largest error against the truth over the valid rows (°).
fn angle_errors(rec: &Path, truth: &Truth) -> (f64, f64) {
    let rec = dlw::recording::Recording::read(rec).unwrap();
    let s = &rec.samples;
    let rows = s.valid_angle_rows();
    let errors: Vec<f64> = rows
        .iter()
        .map(|&i| (s.angle_deg[i] - truth.angle_deg(s.time_s[i])).abs())
        .collect();
    let rmse = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    (rmse, errors.iter().copied().fold(0.0, f64::max))
}

/// Rewrites `dir/name` line by line: `edit(index, line)` gives the lines to write instead
/// (none drops it); the header is line 0.
fn rewrite(dir: &Path, name: &str, mut edit: impl FnMut(usize, &str) -> Option<String>) {
    let text = std::fs::read_to_string(dir.join(name)).unwrap();
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        if let Some(l) = edit(i, line) {
            out.push_str(&l);
            out.push('\n');
        }
    }
    std::fs::write(dir.join(name), out).unwrap();
}

/// A DAQ row's time (its first field).
fn daq_time(line: &str) -> f64 {
    line.split(',').next().unwrap().parse().unwrap()
}

/// A tracker row's frame number (its third field).
fn frame(line: &str) -> i64 {
    line.split(',').nth(2).unwrap().parse().unwrap()
}

/// A DAQ that dropped 1 s of samples, its time column jumping (120 s to 121 s): imported with
/// exit 0 and every row valid, angle RMSE 6.2° (worst 39°), drift −22 878 ppm, because the
/// alignment took the samples as evenly spaced. Now the clock's stretches are found and each
/// is aligned on its own; the angle is as accurate as the clean bench's.
#[test]
fn a_daq_that_dropped_a_second_is_aligned_per_stretch() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_5DOF);
    rewrite(dir.path(), "daq.csv", |i, l| {
        (i == 0 || !(120.0..121.0).contains(&daq_time(l))).then(|| l.to_string())
    });
    // The samples counted at a stated rate disagree with the time column: refused as such.
    refused(
        dir.path(),
        &import(dir.path(), &["--daq-rate-hz", "500"]),
        &["lost samples", "--daq-rate-hz 500"],
    );
    let j = accepted(&import(dir.path(), &[]));
    let stretches = j["alignment"]["stretches"].as_array().expect("stretches");
    assert_eq!(stretches.len(), 2, "{j}");
    // Each stretch is half the bench: its clocks are known to its own standard errors (the
    // offset is extrapolated to τ = 0), within three of which the truth must lie.
    for s in stretches {
        let f = |k: &str| s[k].as_f64().unwrap();
        let (offset, offset_se) = (f("offset_s"), f("offset_uncertainty_s"));
        let (drift, drift_se) = (f("drift_ppm"), f("drift_uncertainty_ppm"));
        assert!((offset - OFFSET_S).abs() < 3.0 * offset_se, "{s}");
        assert!((drift - DRIFT_PPM).abs() < 3.0 * drift_se, "{s}");
    }
    let (rmse, worst) = angle_errors(&dir.path().join("rec"), &truth);
    eprintln!("angle RMSE {rmse}°, worst {worst}°");
    assert!(rmse < 0.3 && worst < 1.5, "RMSE {rmse}°, worst {worst}°");
    // No row was invented in the second the DAQ did not record.
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    assert!(!rec
        .samples
        .time_s
        .iter()
        .any(|t| (120.001..120.999).contains(t)));
}

/// The same dropped second in a DAQ file whose time column does not show it (written as
/// `i / rate`): nothing in the DAQ file can tell, so the check after the alignment must: the
/// angle predicted from the sensor disagrees with the tracker's after 120 s. Refused, saying
/// where.
#[test]
fn a_dropped_second_the_time_column_hides_is_refused_where_it_fails() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_5DOF);
    let mut kept = 0usize;
    rewrite(dir.path(), "daq.csv", |i, l| {
        if i == 0 {
            return Some(l.to_string());
        }
        if (120.0..121.0).contains(&daq_time(l)) {
            return None;
        }
        let rest = l.split_once(',').unwrap().1;
        let t = kept as f64 / DAQ_HZ;
        kept += 1;
        Some(format!("{t:.4},{rest}"))
    });
    let err = refused(dir.path(), &import(dir.path(), &[]), &[]);
    assert!(
        err.contains("window") || err.contains("edge"),
        "the refusal says where: {err}"
    );
}

/// A tracker log with 10 s of frames absent (rows missing, `Frame#` jumping from 100 s to
/// 110 s): 4 777 rows inside the hole were interpolated across 10 s and marked valid. Rows
/// between two frames more than 1.5 periods apart are now `tracker_valid = 0`.
#[test]
fn frames_absent_from_the_log_are_gaps() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_5DOF);
    let (first, last) = (
        1000 + 100 * TRACKER_HZ as i64,
        1000 + 110 * TRACKER_HZ as i64,
    );
    rewrite(dir.path(), "aurora.csv", |i, l| {
        (i == 0 || !(first..last).contains(&frame(l))).then(|| l.to_string())
    });
    let j = accepted(&import(dir.path(), &[]));
    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    let s = &rec.samples;
    // The hole in DAQ time: τ 100..110 s, 0.437 s later.
    let inside: Vec<usize> = (0..s.len())
        .filter(|&i| (OFFSET_S + 100.05..OFFSET_S + 109.95).contains(&s.time_s[i]))
        .collect();
    assert!(inside.len() > 4900, "{}", inside.len());
    let valid_inside = inside.iter().filter(|&&i| s.angle_valid(i)).count();
    assert_eq!(valid_inside, 0, "rows inside the hole marked valid");
    assert!(j["invalid_rows"].as_u64().unwrap() as usize >= inside.len());
    let (rmse, _) = angle_errors(&dir.path().join("rec"), &truth);
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
}

/// A `Frame#` that jumps two hours (a logger restarted, a counter that wrapped): imported with
/// exit 0, angle RMSE 10.8°. A jump longer than the DAQ's whole recording cannot be a gap in
/// one bench run: refused, naming the row and the jump.
#[test]
fn a_frame_jump_longer_than_the_recording_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_5DOF);
    let jump = 2 * 3600 * TRACKER_HZ as i64;
    rewrite(dir.path(), "aurora.csv", |i, l| {
        if i == 0 || frame(l) < 1000 + 4000 {
            return Some(l.to_string());
        }
        let fields: Vec<String> = l
            .split(',')
            .enumerate()
            .map(|(k, f)| {
                if k == 2 {
                    (frame(l) + jump).to_string()
                } else {
                    f.to_string()
                }
            })
            .collect();
        Some(fields.join(","))
    });
    refused(dir.path(), &import(dir.path(), &[]), &["jump", "7200"]);
}

/// `--rest-s 100` on a log whose still start is 5 s: every angle was shifted (RMSE 21.6° on
/// the bench). The rest window must lie inside the log and be still; the refusal says
/// how long the still start is. A window inside the still start is accepted.
#[test]
fn a_rest_window_that_moves_or_overruns_the_log_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_5DOF);
    let err = refused(
        dir.path(),
        &import(dir.path(), &["--rest-s", "100"]),
        &["--rest-s 100", "still"],
    );
    // Still, as the refusal says, means within 0.5° of the mean before: the first frame past
    // that in the truth, at the tracker's time.
    let moves_s = (0..100_000)
        .map(|i| f64::from(i) * 1e-3)
        .find(|&t| truth.angle_deg(t).abs() > 0.5)
        .unwrap()
        - OFFSET_S;
    let still_s: f64 = err
        .split("still for the first ")
        .nth(1)
        .and_then(|r| r.split(" s").next())
        .and_then(|v| v.parse().ok())
        .unwrap_or_else(|| panic!("no 'still for the first N s' in {err}"));
    assert!(
        (still_s - moves_s).abs() < 0.15,
        "still for {still_s} s; the truth moves 0.5° at {moves_s} s"
    );
    assert!(still_s > REST_S - OFFSET_S - 0.1, "{still_s}");
    refused(
        dir.path(),
        &import(dir.path(), &["--rest-s", "1000"]),
        &["--rest-s 1000", "log"],
    );
    accepted(&import(dir.path(), &["--rest-s", "4"]));
    let (rmse, _) = angle_errors(&dir.path().join("rec"), &truth);
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
}

/// Values the recording's own reader refuses: a DAQ row at 999 V, 1e300 V or −0.5 V,
/// `--divider-ohm NaN` or `0`, `--supply-v 1` under the sensor's voltage. Each was imported
/// with exit 0, then `dlw fit` refused the result. Now each is refused, naming the row and the
/// channel (or the option), with nothing written.
#[test]
fn values_a_reader_refuses_are_never_written() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    let clean = std::fs::read_to_string(dir.path().join("daq.csv")).unwrap();
    for (value, says) in [("999", "999"), ("1e300", "1e300"), ("-0.5", "-0.5")] {
        std::fs::write(dir.path().join("daq.csv"), &clean).unwrap();
        // DAQ data row 25000 (file line 25 002), t = 50 s.
        rewrite(dir.path(), "daq.csv", |i, l| {
            if i != 25_001 {
                return Some(l.to_string());
            }
            let mut f: Vec<&str> = l.split(',').collect();
            f[1] = value;
            Some(f.join(","))
        });
        refused(
            dir.path(),
            &import(dir.path(), &[]),
            &[says, "AI0", "25001"],
        );
    }
    std::fs::write(dir.path().join("daq.csv"), &clean).unwrap();
    for (option, value, says) in [
        ("--divider-ohm", "NaN", "--divider-ohm NaN"),
        ("--divider-ohm", "0", "--divider-ohm 0"),
        ("--supply-v", "1", "AI0"),
    ] {
        refused(dir.path(), &import(dir.path(), &[option, value]), &[says]);
    }
}

/// `--report rep` with `-o` under a regular file: the import failed, and the report folder was
/// left behind. The report is written only when the import succeeds.
#[test]
fn a_failed_import_writes_no_report() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    let plain = dir.path().join("plain.txt");
    std::fs::write(&plain, b"x").unwrap();
    let report = dir.path().join("rep");
    let o = import(
        dir.path(),
        &["-o", &arg(&plain.join("rec")), "--report", &arg(&report)],
    );
    assert!(!o.status.success());
    assert!(
        !report.exists(),
        "the report of a failed import was written"
    );
}

/// The smaller items: a UTF-8 BOM before the DAQ's header gave "no time column"; `Qx, Qy, Qz`
/// were read by position after `Q0`, not by name; `--rate-hz` at exactly 10 times the DAQ's
/// was refused by "at most 10"; `-o -` made a folder named `-`.
#[test]
fn a_bom_quaternion_columns_by_name_ten_times_the_rate_and_dash() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_6DOF);
    let reference = {
        let j = accepted(&import(dir.path(), &["-o", &arg(&dir.path().join("ref"))]));
        j["alignment"]["offset_s"].as_f64().unwrap()
    };
    // The BOM.
    let daq = std::fs::read_to_string(dir.path().join("daq.csv")).unwrap();
    std::fs::write(dir.path().join("bom.csv"), format!("\u{feff}{daq}")).unwrap();
    let j = accepted(&import_files(dir.path(), "bom.csv", "aurora.csv", &[]));
    assert_eq!(j["alignment"]["offset_s"].as_f64().unwrap(), reference);
    std::fs::remove_dir_all(dir.path().join("rec")).unwrap();
    // Each tool's Qx, Qy, Qz written in the order Qz, Qy, Qx (the header says so).
    let swap = |l: &str| {
        let mut f: Vec<String> = l.split(',').map(str::to_string).collect();
        for q0 in [6, 17] {
            f.swap(q0 + 1, q0 + 3);
        }
        f.join(",")
    };
    rewrite(dir.path(), "aurora.csv", |_, l| Some(swap(l)));
    let header = std::fs::read_to_string(dir.path().join("aurora.csv")).unwrap();
    assert!(
        header.starts_with("#Tools,ToolInfo,Frame#,PortHandle,Face#,TransformStatus,Q0,Qz,Qy,Qx,")
    );
    let j = accepted(&import(dir.path(), &[]));
    assert!((j["alignment"]["offset_s"].as_f64().unwrap() - reference).abs() < 1e-9);
    let (rmse, _) = angle_errors(&dir.path().join("rec"), &truth);
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
    std::fs::remove_dir_all(dir.path().join("rec")).unwrap();
    // Exactly 10 times the DAQ's 500 Hz.
    let j = accepted(&import(dir.path(), &["--rate-hz", "5000"]));
    assert!(j["samples"].as_u64().unwrap() > 1_000_000);
    // `-o -`, run where a folder named `-` would show.
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args([
            "import-recording",
            "--daq",
            &arg(&dir.path().join("daq.csv")),
            "--voltage",
            "AI0",
            "--divider-ohm",
            "99.6e3",
            "--supply-v",
            "5",
            "--stroke",
            "AI2",
            "--stroke-mm-per-v",
            "0.5",
            "--tracker",
            &arg(&dir.path().join("aurora.csv")),
            "-o",
            "-",
        ])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot hold a folder"));
    assert!(!dir.path().join("-").exists());
}

/// The clock search refuses what it cannot see: an offset beyond the ±10 s it searches (the
/// best lag sits at the edge; the message says what to pass to widen it, and passing it
/// works), a drift beyond ±1000 ppm (as `--sync` already refused), and a sensor that answers
/// the other way in part of the recording (its best correlation there is negative).
#[test]
fn the_clock_search_refuses_what_it_cannot_see() {
    let dir = tempfile::tempdir().unwrap();
    // The tracker started 12 s before the DAQ (its clock is 12 s ahead).
    write_bench_with(dir.path(), STILL_6DOF, DURATION_S, -12.0, DRIFT_PPM);
    let err = refused(
        dir.path(),
        &import(dir.path(), &[]),
        &["edge", "--max-offset-s"],
    );
    eprintln!("{err}");
    let j = accepted(&import(dir.path(), &["--max-offset-s", "15"]));
    let offset = j["alignment"]["offset_s"].as_f64().unwrap();
    assert!((offset + 12.0).abs() < 0.002, "offset {offset} s");
    std::fs::remove_dir_all(dir.path().join("rec")).unwrap();

    write_bench_with(dir.path(), STILL_6DOF, DURATION_S, OFFSET_S, 3000.0);
    refused(dir.path(), &import(dir.path(), &[]), &["1000 ppm"]);

    // The sensor's divider wired the other way round after 150 s: V → supply − V.
    write_bench(dir.path(), STILL_6DOF);
    rewrite(dir.path(), "daq.csv", |i, l| {
        if i == 0 || daq_time(l) < 150.0 {
            return Some(l.to_string());
        }
        let mut f: Vec<String> = l.split(',').map(str::to_string).collect();
        let v: f64 = f[1].parse().unwrap();
        f[1] = format!("{:.6}", SUPPLY_V - v);
        Some(f.join(","))
    });
    refused(dir.path(), &import(dir.path(), &[]), &["negative"]);
}
