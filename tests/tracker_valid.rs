//! Rows the tracker did not measure (`tracker_valid = 0`, `docs/recording-format.md`) are no
//! angle observations for `dlw fit`, `dlw characterize` and `dlw discover`: a simulated
//! recording with a long stretch marked invalid gives the same results whatever number its
//! `angle_deg` holds there, the true angle or garbage (a recording's writer may put anything
//! there; the importer writes 0).

use crate::common;
use common::{arg, dlw_ok, shipped_design};

use std::path::{Path, PathBuf};

/// The stretch marked unmeasured (s of recording time): long against every filter window.
const GAP_S: (f64, f64) = (40.0, 52.0);
/// A second, short stretch, as a dropped tracker burst.
const BURST_S: (f64, f64) = (90.3, 90.45);

/// `dlw simulate` of Joint A with `protocol` for `seconds`, realistic noise, into `dir/name`.
fn simulate(dir: &Path, name: &str, protocol: &str, seconds: &str) -> PathBuf {
    let out = dir.join(name);
    dlw_ok(&[
        "simulate",
        "--design",
        &shipped_design("joint-a.toml"),
        "--protocol",
        protocol,
        "--duration-s",
        seconds,
        "--seed",
        "11",
        "--noise",
        "realistic",
        "-o",
        &arg(&out),
    ]);
    out
}

/// Copies `rec` to `dir/name` with the rows in [`GAP_S`] and [`BURST_S`] marked
/// `tracker_valid = 0` and their angle replaced by `angle(row)`.
fn mark_unmeasured(rec: &Path, dir: &Path, name: &str, angle: impl Fn(usize) -> f64) -> PathBuf {
    let mut r = dlw::recording::Recording::read(rec).unwrap();
    let s = &mut r.samples;
    let inside = |t: f64| (GAP_S.0..GAP_S.1).contains(&t) || (BURST_S.0..BURST_S.1).contains(&t);
    s.tracker_valid = s.time_s.iter().map(|&t| !inside(t)).collect();
    for i in 0..s.time_s.len() {
        if !s.tracker_valid[i] {
            s.angle_deg[i] = angle(i);
        }
    }
    let out = dir.join(name);
    r.write(&out, false).unwrap();
    out
}

/// The recording's twin pair: the true angle and garbage on the same unmeasured rows.
fn twins(rec: &Path, dir: &Path) -> (PathBuf, PathBuf) {
    let truth = dlw::recording::Recording::read(rec)
        .unwrap()
        .samples
        .angle_deg;
    let honest = mark_unmeasured(rec, dir, "honest", |i| truth[i]);
    // Garbage: what a held or zeroed tracker angle looks like, and worse.
    let garbage = mark_unmeasured(rec, dir, "garbage", |i| {
        if (i / 97) % 2 == 0 {
            0.0
        } else {
            60.0
        }
    });
    (honest, garbage)
}

/// `dlw <command> ... REC -o OUT --json` for `rec`, its JSON with the paths taken out.
fn run_json(command: &str, rec: &Path, out: &Path, extra: &[&str]) -> serde_json::Value {
    let design = shipped_design("joint-a.toml");
    let (rec_s, out_s) = (arg(rec), arg(out));
    let mut args = vec![command, "--design", &design, &rec_s, "-o", &out_s, "--json"];
    args.extend_from_slice(extra);
    let o = dlw_ok(&args);
    let mut j: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    scrub(&mut j);
    j
}

/// Removes what differs between two runs on equal data: paths and timings.
fn scrub(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(map) => {
            map.retain(|k, _| {
                !(k.contains("timing")
                    || k.contains("seconds")
                    || k.ends_with("_s_wall")
                    || matches!(
                        k.as_str(),
                        "config" | "output" | "recording" | "report" | "scenario"
                    ))
            });
            map.values_mut().for_each(scrub);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(scrub),
        _ => {}
    }
}

/// `dlw fit` (linear and PI) and `dlw characterize` on a characterization run: equal results
/// on the honest and the garbage twin.
#[test]
fn fit_and_characterize_ignore_the_angle_on_unmeasured_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let rec = simulate(d, "rec", "characterization", "150");
    let (honest, garbage) = twins(&rec, d);
    for model in ["linear", "pi"] {
        let a = run_json(
            "fit",
            &honest,
            &d.join(format!("h-{model}.toml")),
            &["--model", model],
        );
        let b = run_json(
            "fit",
            &garbage,
            &d.join(format!("g-{model}.toml")),
            &["--model", model],
        );
        assert_eq!(a, b, "fit --model {model}");
    }
    let a = run_json("characterize", &honest, &d.join("h-char"), &[]);
    let b = run_json("characterize", &garbage, &d.join("g-char"), &[]);
    assert_eq!(a, b, "characterize");
}

/// `dlw discover` on a random-protocol run: equal results on the honest and the garbage twin.
#[test]
fn discover_ignores_the_angle_on_unmeasured_rows() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let rec = simulate(d, "rec", "random", "240");
    let (honest, garbage) = twins(&rec, d);
    let a = run_json("discover", &honest, &d.join("h-disc"), &[]);
    let b = run_json("discover", &garbage, &d.join("g-disc"), &[]);
    assert_eq!(a, b, "discover");
}
