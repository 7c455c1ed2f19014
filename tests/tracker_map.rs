//! `--tracker-map MAP.toml` (issue 30): a lab's own Aurora logger, as a modified Combined API
//! sample writes it (public example: QUT's `ndi_tracker_project`, `CombinedAPISampleDlg.cpp`):
//! four lines of test date, a blank line, then
//! `Sample:,Hour,Minutes,Seconds,ms,Xa,Ya,Za,qoa,qxa,qya,qza,Xb,…` for four tools, fields
//! padded with spaces and each row ending in a comma, a lost tool written as zeros, and a last
//! line cut off mid-way. The log is written here from the bench's known truth
//! (`tests/common/bench.rs`: the same frames as its NDI log) with the host's clock crossing
//! midnight; imported through a map, it must meet the NDI layout's acceptance: offset within
//! 2 ms, drift within 30 ppm, angle RMSE under 0.3°, the linear sensor's gauge factor within
//! 1 %.

use crate::common;
use common::bench::*;
use common::{arg, dlw, shipped_design};

use std::fmt::Write as _;
use std::path::Path;

/// The map of the lab's logger, with the issue's keys.
const LAB_MAP: &str = r#"
header_line = 5
time = [["Hour", "h"], ["Minutes", "min"], ["Seconds", "s"], ["ms", "ms"]]
frame = "Sample:"

[[tool]]
quaternion = ["qoa", "qxa", "qya", "qza"]
position_mm = ["Xa", "Ya", "Za"]
missing = "all-zero"

[[tool]]
quaternion = ["qob", "qxb", "qyb", "qzb"]
position_mm = ["Xb", "Yb", "Zb"]
missing = "all-zero"

[[tool]]
quaternion = ["qoc", "qxc", "qyc", "qzc"]
position_mm = ["Xc", "Yc", "Zc"]
missing = "all-zero"

[[tool]]
quaternion = ["qod", "qxd", "qyd", "qzd"]
position_mm = ["Xd", "Yd", "Zd"]
missing = "all-zero"
"#;

/// Rewrites the bench's NDI log (`aurora.csv`: frame, then tip and reference blocks) as the lab
/// logger's `lab.csv`: tool a the tip, b the reference, c never seen (zeros), d a still tool
/// lost now and then. The host clock starts at 23:58:30.000 and ticks with the tracker's frames
/// with up to ±4 ms of jitter, written in whole milliseconds; the last line is cut.
fn write_lab_log(dir: &Path) {
    let ndi = std::fs::read_to_string(dir.join("aurora.csv")).unwrap();
    let mut out = String::from(
        "Test Date: \nday, month, year, hour, minute, second, milliseconds\n\
         25, 11, 2026, 23, 58 , 30 , 0 \n\n",
    );
    out.push_str("Sample:,Hour,Minutes,Seconds,ms");
    for t in ["a", "b", "c", "d"] {
        write!(out, ",X{t},Y{t},Z{t},qo{t},qx{t},qy{t},qz{t}").unwrap();
    }
    out.push('\n');
    let mut rng = Rng(0x001a_b10c_5eed);
    let block = |f: &[&str]| -> String {
        // NDI's block: PortHandle, Face#, TransformStatus, Q0, Qx, Qy, Qz, Tx, Ty, Tz, Error.
        if f[2] == "Missing" {
            return "0, 0, 0, 0, 0, 0, 0".to_owned();
        }
        format!(
            "{} , {} , {}, {} , {} , {}, {}",
            f[7], f[8], f[9], f[3], f[4], f[5], f[6]
        )
    };
    for (k, line) in ndi.lines().skip(1).enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        let frame: f64 = f[2].parse().unwrap();
        let tau = (frame - 1000.0) / TRACKER_HZ;
        let host_ms = ((23.0 * 3600.0 + 58.0 * 60.0 + 30.0 + tau) * 1e3
            + 8.0 * (rng.uniform() - 0.5))
            .round() as u64
            % 86_400_000;
        let (h, m, s, ms) = (
            host_ms / 3_600_000,
            host_ms / 60_000 % 60,
            host_ms / 1000 % 60,
            host_ms % 1000,
        );
        let lost_d = k % 97 < 4;
        writeln!(
            out,
            "{}, {h} , {m} , {s}, {ms},{}, {}, 0, 0, 0, 0, 0, 0, 0, {}, ",
            k + 1,
            block(&f[3..14]),
            block(&f[15..26]),
            if lost_d {
                "0, 0, 0, 0, 0, 0, 0".to_owned()
            } else {
                "99.5 , -18.3 , -286.5, 0.7980 , 0.3758 , 0.1238, 0.4544".to_owned()
            }
        )
        .unwrap();
    }
    // The logger stopped mid-line.
    let cut = out.trim_end().len() - 40;
    out.truncate(cut);
    std::fs::write(dir.join("lab.csv"), out).unwrap();
    std::fs::write(dir.join("lab-map.toml"), LAB_MAP).unwrap();
}

fn import(dir: &Path, tracker: &str, extra: &[&str]) -> std::process::Output {
    let mut args: Vec<String> = [
        "import-recording",
        "--daq",
        &arg(&dir.join("daq.csv")),
        "--voltage",
        "AI0",
        "--divider-ohm",
        &DIVIDER.to_string(),
        "--supply-v",
        &SUPPLY_V.to_string(),
        "--stroke",
        "AI2",
        "--stroke-mm-per-v",
        &MM_PER_V.to_string(),
        "--tracker",
        &arg(&dir.join(tracker)),
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    if !extra.contains(&"-o") {
        args.extend(["-o".into(), arg(&dir.join("rec"))]);
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    dlw(&args)
}

/// The lab's log through the map meets the NDI layout's acceptance, on the 5-DOF bench and
/// with the reference tool on a swaying base.
#[test]
fn a_lab_logger_layout_imports_through_a_map() {
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(dir.path(), STILL_5DOF);
    write_lab_log(dir.path());
    let map = arg(&dir.path().join("lab-map.toml"));

    // Without a map, the reader says what to do.
    let o = import(dir.path(), "lab.csv", &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--tracker-map"),
        "{err}"
    );

    let o = import(dir.path(), "lab.csv", &["--tracker-map", &map]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    eprintln!("{j}");
    let offset = j["alignment"]["offset_s"].as_f64().unwrap();
    let drift = j["alignment"]["drift_ppm"].as_f64().unwrap();
    assert!((offset - OFFSET_S).abs() < 0.002, "offset {offset} s");
    assert!((drift - DRIFT_PPM).abs() < 30.0, "drift {drift} ppm");
    // The rate from the host clock against the counter; the cut line dropped with a warning.
    let rate = j["tracker"]["rate_hz"].as_f64().unwrap();
    assert!((rate - TRACKER_HZ).abs() < 0.01, "rate {rate} Hz");
    let warnings = j["warnings"].to_string();
    assert!(warnings.contains("truncated"), "{warnings}");
    assert!(j["tracker"]["missing_frames"].as_u64().unwrap() > 0);

    let rec = dlw::recording::Recording::read(&dir.path().join("rec")).unwrap();
    let s = &rec.samples;
    let rows = s.valid_angle_rows();
    let rmse = (rows
        .iter()
        .map(|&i| (s.angle_deg[i] - truth.angle_deg(s.time_s[i])).powi(2))
        .sum::<f64>()
        / rows.len() as f64)
        .sqrt();
    eprintln!("lab logger: offset {offset} s, drift {drift} ppm, angle RMSE {rmse}°");
    assert!(rmse < 0.3, "angle RMSE {rmse}°");

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
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let gf: f64 = std::fs::read_to_string(&cfg)
        .unwrap()
        .lines()
        .find_map(|l| l.trim().strip_prefix("gauge_factor = "))
        .and_then(|v| v.parse().ok())
        .expect("a gauge_factor line");
    eprintln!("lab logger: GF {gf} against {GF}");
    assert!((gf - GF).abs() < 0.01 * GF, "GF {gf}");

    // Tool 3 is never seen: refused as no rest axis, naming the frames.
    let o = import(
        dir.path(),
        "lab.csv",
        &[
            "--tracker-map",
            &map,
            "--tool",
            "3",
            "-o",
            &arg(&dir.path().join("c")),
        ],
    );
    assert!(!o.status.success());
    assert!(!dir.path().join("c").exists());

    // The reference tool on a swaying base.
    let dir = tempfile::tempdir().unwrap();
    let truth = write_bench(
        dir.path(),
        Tools {
            tip_5dof: true,
            reference_moves: true,
        },
    );
    write_lab_log(dir.path());
    let map = arg(&dir.path().join("lab-map.toml"));
    let o = import(
        dir.path(),
        "lab.csv",
        &["--tracker-map", &map, "--reference-tool", "2"],
    );
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
    eprintln!("lab logger, reference tool: angle RMSE {rmse}°");
    assert!(rmse < 0.3, "angle RMSE {rmse}°");
}

/// A map that names a column the log lacks, or a unit it does not know, is refused naming it,
/// with nothing written.
#[test]
fn a_map_that_does_not_fit_the_log_is_refused_naming_the_column() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_6DOF);
    write_lab_log(dir.path());
    for (from, to, says) in [
        ("\"qxa\"", "\"QXA_\"", "QXA_"),
        ("[\"ms\", \"ms\"]", "[\"ms\", \"jiffies\"]", "jiffies"),
        (
            "header_line = 5",
            "header_line = 4",
            "no \"Sample:\" column",
        ),
    ] {
        let map = dir.path().join("bad.toml");
        std::fs::write(&map, LAB_MAP.replacen(from, to, 1)).unwrap();
        let o = import(dir.path(), "lab.csv", &["--tracker-map", &arg(&map)]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{to}: accepted");
        assert!(err.contains(says), "{to}: {err}");
        assert!(!dir.path().join("rec").exists());
    }
}

/// `dlw daq-info --tracker` (issue 30, section 4) lists what the lab's log holds, counted here
/// from the bench's own NDI log: the frames (the cut line dropped with a warning), each tool's
/// frames without it (the tip's `Missing` frames, tool c never seen, tool d lost 4 frames in
/// 97), the span and the rate the host clock gives; the NDI log itself through the built-in
/// map; and the DAQ side's columns.
#[test]
fn daq_info_lists_what_the_logs_hold() {
    let dir = tempfile::tempdir().unwrap();
    write_bench(dir.path(), STILL_5DOF);
    write_lab_log(dir.path());
    let ndi = std::fs::read_to_string(dir.path().join("aurora.csv")).unwrap();
    let rows: Vec<Vec<&str>> = ndi
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let whole = rows.len() - 1;
    let tip_missing = rows[..whole].iter().filter(|f| f[5] == "Missing").count();
    let reference_missing = rows[..whole].iter().filter(|f| f[17] == "Missing").count();
    assert!(tip_missing > 0);

    let info = |args: &[&str]| -> serde_json::Value {
        let mut all = vec!["daq-info", "--json"];
        all.extend(args);
        let o = dlw(&all);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let lab = arg(&dir.path().join("lab.csv"));
    let map = arg(&dir.path().join("lab-map.toml"));
    let j = info(&["--tracker", &lab, "--tracker-map", &map]);
    assert_eq!(j["format"], "map");
    assert_eq!(j["frames"].as_u64(), Some(whole as u64), "{j}");
    let missing: Vec<u64> = j["tools"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["missing"].as_u64().unwrap())
        .collect();
    let lost_d = (0..whole).filter(|k| k % 97 < 4).count() as u64;
    assert_eq!(
        missing,
        vec![
            tip_missing as u64,
            reference_missing as u64,
            whole as u64,
            lost_d
        ],
        "{j}"
    );
    let rate = j["rate_hz"].as_f64().unwrap();
    assert!((rate - TRACKER_HZ).abs() < 0.01, "rate {rate} Hz");
    assert_eq!(j["rate_source"], "measured");
    let span = j["span_s"].as_f64().unwrap();
    let want = (whole - 1) as f64 / TRACKER_HZ;
    assert!((span - want).abs() < 0.01, "span {span} s, want {want} s");
    assert!(j["warnings"].to_string().contains("truncated"), "{j}");
    assert_eq!(j["gaps"].as_array().map(Vec::len), Some(0), "{j}");

    // A hole of 400 frames cut from the NDI log is listed as a gap.
    let mut holed = String::new();
    for (k, line) in ndi.lines().enumerate() {
        if !(2001..2401).contains(&k) {
            holed.push_str(line);
            holed.push('\n');
        }
    }
    std::fs::write(dir.path().join("holed.csv"), holed).unwrap();
    let j = info(&["--tracker", &arg(&dir.path().join("holed.csv"))]);
    assert_eq!(j["format"], "ndi");
    assert_eq!(j["frames"].as_u64(), Some((rows.len() - 400) as u64), "{j}");
    let gaps = j["gaps"].as_array().unwrap();
    assert_eq!(gaps.len(), 1, "{j}");
    assert!(
        (gaps[0]["frames"].as_f64().unwrap() - 400.0).abs() < 0.5,
        "{j}"
    );
    assert!(
        (gaps[0]["seconds"].as_f64().unwrap() - 401.0 / TRACKER_HZ).abs() < 1e-3,
        "{j}"
    );
    assert_eq!(j["tools"].as_array().unwrap().len(), 2, "{j}");

    // The DAQ side: its columns, lengths, first and last values, sample interval.
    let daq = std::fs::read_to_string(dir.path().join("daq.csv")).unwrap();
    let lines: Vec<&str> = daq.lines().collect();
    let j = info(&[&arg(&dir.path().join("daq.csv"))]);
    assert_eq!(j["format"], "csv");
    let names: Vec<&str> = j["channels"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["Time", "AI0", "AI1", "AI2", "AI3"]);
    let ai0 = &j["channels"][1];
    assert_eq!(ai0["length"].as_u64(), Some(lines.len() as u64 - 1));
    let field = |line: &str| line.split(',').nth(1).unwrap().parse::<f64>().unwrap();
    assert_eq!(ai0["first"][0].as_f64(), Some(field(lines[1])));
    assert_eq!(ai0["last"][1].as_f64(), Some(field(lines[lines.len() - 1])));
    assert!((ai0["increment_s"].as_f64().unwrap() - 1.0 / DAQ_HZ).abs() < 1e-9);
    assert_eq!(j["warnings"].as_array().map(Vec::len), Some(0), "{j}");
}
