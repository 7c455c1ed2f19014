//! The phantom demonstration (Section IV-D, Table VII) end to end through the binary: simulate a
//! Joint D recording, render fluoroscopy frames of its angle at 2 Hz, measure them with
//! `dlw fluoro`, and compare the sensor's estimates with that ground truth with
//! `dlw estimate --truth`, on a copy of the recording whose tracker column is empty.
//!
//! The simulated tracker is noise-free here, so its column is the true angle `θ` and the
//! tracker-based RMSE is the estimator's own error. The fluoroscopy truth `g` differs from `θ`
//! by the pin fit's error (and, smoothed, by the moving average's rounding of the corners), so
//! by the triangle inequality the two RMSEs differ by at most `RMSE(g − θ)` at the frame times.

use crate::common;
use common::{dlw, shipped_design};

use std::path::Path;

fn ok(args: &[&str]) -> String {
    let o = dlw(args);
    assert!(
        o.status.success(),
        "dlw {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

fn json(args: &[&str]) -> serde_json::Value {
    serde_json::from_str(&ok(args)).unwrap()
}

/// Columns `names` of a CSV, rows with an empty field in any of them left out.
fn columns(path: &Path, names: &[&str]) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let idx: Vec<usize> = names
        .iter()
        .map(|n| header.iter().position(|h| h == n).unwrap())
        .collect();
    let mut out = vec![Vec::new(); names.len()];
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        if idx.iter().any(|&i| f[i].is_empty()) {
            continue;
        }
        for (o, &i) in out.iter_mut().zip(&idx) {
            o.push(f[i].parse::<f64>().unwrap());
        }
    }
    out
}

/// Linear interpolation of `v` at `t` (inside `ts`).
fn interp(ts: &[f64], v: &[f64], t: f64) -> f64 {
    let i = ts.partition_point(|&x| x < t).clamp(1, ts.len() - 1);
    let w = (t - ts[i - 1]) / (ts[i] - ts[i - 1]);
    v[i - 1] + w * (v[i] - v[i - 1])
}

fn rmse(e: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = e.fold((0.0, 0usize), |(s, n), x| (s + x * x, n + 1));
    (s / n as f64).sqrt()
}

#[test]
fn fluoroscopy_truth_gives_the_tracker_rmse() {
    let dir = tempfile::tempdir().unwrap();
    let p = |name: &str| dir.path().join(name).display().to_string();
    // At rest for 6 s (the baseline), a 12 s bend to about 39°, a hold, back, at rest.
    std::fs::write(
        p("profile.csv"),
        "time_s,stroke_mm\n0,0\n6,0\n18,1.1\n24,1.1\n34,0\n40,0\n",
    )
    .unwrap();
    std::fs::write(p("scenario.toml"), "seed = 3\n[tracker]\nenabled = false\n").unwrap();
    ok(&[
        "simulate",
        "--design",
        &shipped_design("joint-d.toml"),
        "--protocol",
        "custom",
        "--profile",
        &p("profile.csv"),
        "--scenario",
        &p("scenario.toml"),
        "-o",
        &p("rec"),
    ]);
    // The pin is mounted at 25° to the joint in the image.
    ok(&[
        "fluoro-render",
        "--recording",
        &p("rec"),
        "--fps",
        "2",
        "--size",
        "256",
        "--offset-deg",
        "25",
        "-o",
        &p("frames"),
    ]);
    assert_eq!(std::fs::read_dir(p("frames")).unwrap().count(), 80);

    // The same recording without its tracker column.
    std::fs::create_dir(p("phantom")).unwrap();
    std::fs::copy(p("rec/rig.toml"), p("phantom/rig.toml")).unwrap();
    let data = std::fs::read_to_string(p("rec/data.csv")).unwrap();
    let blank: String = data
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == 0 {
                return format!("{l}\n");
            }
            let f: Vec<&str> = l.split(',').collect();
            format!("{},{},,{}\n", f[0], f[1], f[3])
        })
        .collect();
    std::fs::write(p("phantom/data.csv"), blank).unwrap();

    ok(&[
        "estimator-config",
        &shipped_design("joint-d.toml"),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &p("d.toml"),
    ]);
    let tracker = json(&["estimate", "--config", &p("d.toml"), &p("rec"), "--json"]);
    let tracker_rmse = tracker["rmse_deg"].as_f64().unwrap();
    // With a tracker column, --truth reports the tracker's RMSE as well, unchanged.
    ok(&["fluoro", &p("frames"), "-o", &p("angles.csv")]);
    let both = json(&[
        "estimate",
        "--config",
        &p("d.toml"),
        &p("rec"),
        "--truth",
        &p("angles.csv"),
        "--json",
        "--force",
    ]);
    assert_eq!(both["tracker"]["rmse_deg"], tracker["rmse_deg"], "{both}");
    assert_eq!(both["tracker"]["samples"], 20_000, "{both}");

    // Without --truth, a recording without the tracker angle is refused.
    let o = dlw(&["estimate", "--config", &p("d.toml"), &p("phantom")]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("angle_deg column is empty") && err.contains("--truth"),
        "{err}"
    );
    assert!(!Path::new(&p("phantom/estimates.csv")).exists());

    let truth_angles = columns(Path::new(&p("rec/data.csv")), &["time_s", "angle_deg"]);
    for (smooth, fit_tol_deg) in [("1", 0.3), ("8", 1.0)] {
        let angles = p(&format!("angles-{smooth}.csv"));
        let summary = json(&[
            "fluoro",
            &p("frames"),
            "--smooth",
            smooth,
            "-o",
            &angles,
            "--json",
        ]);
        assert_eq!(summary["fitted"], 80, "{summary}");
        // The baseline removes the mounting angle: the joint rests at 0°.
        let base = summary["baseline_deg"].as_f64().unwrap();
        assert!((base - 25.0).abs() < 0.3, "{summary}");

        // The fluoroscopy angle against the true angle at the frame times.
        let g = columns(Path::new(&angles), &["time_s", "angle_deg"]);
        let fit_rmse = rmse(
            g[0].iter()
                .zip(&g[1])
                .map(|(&t, &a)| a - interp(&truth_angles[0], &truth_angles[1], t)),
        );
        assert!(
            fit_rmse < fit_tol_deg,
            "--smooth {smooth}: RMSE(g − θ) = {fit_rmse}°"
        );

        let report = json(&[
            "estimate",
            "--config",
            &p("d.toml"),
            &p("phantom"),
            "--truth",
            &angles,
            "--json",
            // The second --smooth replaces the first run's estimates.csv.
            "--force",
        ]);
        let t = &report["truth"];
        assert_eq!(t["frames"], 80, "{report}");
        assert!(report["tracker"].is_null(), "{report}");
        let truth_rmse = t["rmse_deg"].as_f64().unwrap();

        // The same number from the estimates file, computed here.
        let est = columns(
            Path::new(&p("phantom/estimates.csv")),
            &["time_s", "estimate_deg"],
        );
        let own = rmse(
            g[0].iter()
                .zip(&g[1])
                .map(|(&t, &a)| interp(&est[0], &est[1], t) - a),
        );
        assert!((own - truth_rmse).abs() < 1e-3, "{own} vs {truth_rmse}");
        // The tracker-based RMSE at the frame times.
        let at_frames =
            rmse(g[0].iter().map(|&t| {
                interp(&est[0], &est[1], t) - interp(&truth_angles[0], &truth_angles[1], t)
            }));
        assert!(
            (truth_rmse - at_frames).abs() <= fit_rmse + 1e-6,
            "--smooth {smooth}: {truth_rmse}° vs {at_frames}° (fit {fit_rmse}°)"
        );
        // And over every sample: what Table VII would report with a tracker.
        assert!(
            (truth_rmse - tracker_rmse).abs() < fit_tol_deg + 0.3,
            "--smooth {smooth}: fluoroscopy RMSE {truth_rmse}°, tracker RMSE {tracker_rmse}°"
        );
        eprintln!(
            "--smooth {smooth}: fluoroscopy RMSE {truth_rmse:.3}°, tracker RMSE {tracker_rmse:.3}° ({at_frames:.3}° at the frames), RMSE(g − θ) {fit_rmse:.3}°"
        );
    }
}
