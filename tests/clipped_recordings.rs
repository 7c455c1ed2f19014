//! A recording one of whose columns the instrument did not measure throughout is refused by
//! every analysis that fits a model to it, naming the column, the value, how many rows hold it
//! and the first line:
//! - clipped by its range (a DAQ input range set too narrow, a tracker reporting its limit):
//!   before, `discover` named `saturation` on Joint A's clean recording with its voltage
//!   clipped at the 90th percentile, and `fit` wrote a gauge factor 3 % low, both with exit 0
//!   (`src/recording/clipping.rs`);
//! - frozen while the joint moved (a tracker holding its last reading, a stalled DAQ): before,
//!   three 4 s holds of the angle named `hysteresis` and `rate` on sensor 1
//!   (`src/recording/frozen.rs`).
//!
//! A sensor that saturates physically, and a hold marked `tracker_valid = 0`, are not refused.

use crate::common;
use common::dlw;
use common::third_generator::{self, Bench, Effect, Size};

use std::path::{Path, PathBuf};

/// Joint A's third-generator recording of `effect` (seed 3, 120 s), written into `root/name`.
fn recording(root: &Path, name: &str, effect: Option<(Effect, Size, usize)>) -> PathBuf {
    recording_of(root, name, effect, 120.0)
}

/// [`recording`], `duration_s` long.
fn recording_of(
    root: &Path,
    name: &str,
    effect: Option<(Effect, Size, usize)>,
    duration_s: f64,
) -> PathBuf {
    let dir = root.join(name);
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let bench = Bench {
        effect,
        duration_s,
        seed: 3,
    };
    third_generator::write_recording(&design, &bench, &dir);
    dir
}

/// `from`'s header and rows, split into fields.
type Table = (String, Vec<Vec<String>>);

/// A copy of the recording `from` as `root/name`, its `data.csv` rewritten by `edit` from
/// `from`'s header and rows.
fn copy_edited(from: &Path, root: &Path, name: &str, edit: impl FnOnce(Table) -> Table) -> PathBuf {
    let dir = root.join(name);
    std::fs::create_dir(&dir).unwrap();
    std::fs::copy(from.join("rig.toml"), dir.join("rig.toml")).unwrap();
    let text = std::fs::read_to_string(from.join("data.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_owned();
    let rows = lines
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    let (header, rows) = edit((header, rows));
    let mut out = header + "\n";
    for row in rows {
        out.push_str(&row.join(","));
        out.push('\n');
    }
    std::fs::write(dir.join("data.csv"), out).unwrap();
    dir
}

/// A copy of `from` as `root/name` whose column `column` (0-based in `data.csv`) is held at the
/// `percentile`-th percentile of its values from above (`top`) or below: a clip.
fn clipped(
    from: &Path,
    root: &Path,
    name: &str,
    column: usize,
    percentile: f64,
    top: bool,
) -> PathBuf {
    copy_edited(from, root, name, |(header, mut rows)| {
        let mut values: Vec<f64> = rows.iter().map(|r| r[column].parse().unwrap()).collect();
        values.sort_by(f64::total_cmp);
        let at = ((percentile / 100.0) * (values.len() - 1) as f64).round() as usize;
        // The limit as the column writes it, so that every clipped row reads the same value.
        let limit_text = rows
            .iter()
            .find(|r| r[column].parse::<f64>().unwrap() == values[at])
            .unwrap()[column]
            .clone();
        let limit: f64 = limit_text.parse().unwrap();
        for row in &mut rows {
            let v: f64 = row[column].parse().unwrap();
            if (top && v > limit) || (!top && v < limit) {
                row[column] = limit_text.clone();
            }
        }
        (header, rows)
    })
}

/// A copy of `from` as `root/name` whose column `column` holds its value for `seconds` from
/// each of `starts` (s): a frozen reading; with `mark`, the held rows marked `tracker_valid = 0`.
fn frozen(
    from: &Path,
    root: &Path,
    name: &str,
    column: usize,
    starts: &[f64],
    seconds: f64,
    mark: bool,
) -> PathBuf {
    copy_edited(from, root, name, |(mut header, mut rows)| {
        if mark {
            header.push_str(",tracker_valid");
        }
        let mut held: Option<String> = None;
        for row in &mut rows {
            let t: f64 = row[0].parse().unwrap();
            let inside = starts.iter().any(|s| t >= *s && t < s + seconds);
            if inside {
                row[column] = held.get_or_insert_with(|| row[column].clone()).clone();
            } else {
                held = None;
            }
            if mark {
                row.push(if inside { "0" } else { "1" }.to_owned());
            }
        }
        (header, rows)
    })
}

/// Runs `dlw` with `args` and asserts it refused the recording: non-zero exit, a message naming
/// the column, `what` was wrong (the end of a clip, or `stopped updating`), a share and the
/// line, and nothing written at `output`.
fn assert_refused(args: &[&str], output: &Path, column: &str, what: &str) {
    let o = dlw(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} accepted a clipped recording");
    for part in [column, what, "%", "line"] {
        assert!(err.contains(part), "{args:?}: {part:?} not in {err}");
    }
    assert!(!output.exists(), "{args:?} wrote {}", output.display());
}

#[test]
fn a_clipped_or_frozen_voltage_or_angle_is_refused_by_fit_discover_and_characterize() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let design = design.to_str().unwrap();
    let clean = recording(root, "clean", None);
    // The clean recording is accepted: what is refused below is the clip.
    let config = root.join("clean.toml");
    let o = dlw(&[
        "fit",
        "--design",
        design,
        clean.to_str().unwrap(),
        "-o",
        config.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));

    // data.csv's columns: time_s, stroke_mm, angle_deg, v1_V.
    let volts = clipped(&clean, root, "volts", 3, 90.0, true);
    let angle = clipped(&clean, root, "angle", 2, 5.0, false);
    let held_angle = frozen(&clean, root, "held-angle", 2, &[40.0, 80.0], 4.0, false);
    let held_volts = frozen(&clean, root, "held-volts", 3, &[60.0], 2.0, false);
    for (dir, column, end) in [
        (&volts, "v1_V", "largest"),
        (&angle, "angle_deg", "smallest"),
        (&held_angle, "angle_deg", "stopped updating"),
        (&held_volts, "v1_V", "stopped updating"),
    ] {
        let dir = dir.to_str().unwrap();
        let commands: [(&[&str], &str); 3] = [
            (&["fit"], "fit.toml"),
            (&["discover", "--fast"], "discover"),
            (&["characterize", "--kind", "loops"], "loops"),
        ];
        for (command, output) in commands {
            let out = root.join(format!("{column}-{output}"));
            let out_text = out.to_str().unwrap();
            let mut args = command.to_vec();
            args.extend(["--design", design, dir, "-o", out_text]);
            assert_refused(&args, &out, column, end);
        }
    }
    // As a held-out recording beside a good one too.
    let out = root.join("validate.toml");
    assert_refused(
        &[
            "fit",
            "--design",
            design,
            clean.to_str().unwrap(),
            "--validate",
            volts.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        &out,
        "v1_V",
        "largest",
    );
}

/// Asserts that `dlw fit` accepts the recording `dir` of Joint A.
fn assert_fits(root: &Path, dir: &Path) {
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let config = root.join("accepted.toml");
    let o = dlw(&[
        "fit",
        "--design",
        design.to_str().unwrap(),
        dir.to_str().unwrap(),
        "-o",
        config.to_str().unwrap(),
        "--force",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn a_hold_marked_invalid_is_not_refused() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    let clean = recording(root, "clean", None);
    assert_fits(
        root,
        &frozen(&clean, root, "marked", 2, &[40.0, 80.0], 4.0, true),
    );
}

#[test]
fn a_sensor_that_saturates_is_not_a_clip() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    // The third generator's saturation at ×8 flattens the response's top into a plateau
    // carrying the noise: no value piles up.
    let saturating = Some((Effect::Saturation, Size(8.0), 1));
    assert_fits(root, &recording(root, "saturation", saturating));
}

/// A copy of `from` as `root/name` whose angle is `rows` rows late: a tracker's clock behind
/// the DAQ's (the first value held over the rows shifted in).
fn late(from: &Path, root: &Path, name: &str, rows: usize) -> PathBuf {
    copy_edited(from, root, name, |(header, mut table)| {
        let angle: Vec<String> = table.iter().map(|r| r[2].clone()).collect();
        for (i, row) in table.iter_mut().enumerate() {
            row[2] = angle[i.saturating_sub(rows)].clone();
        }
        (header, table)
    })
}

/// A tracker 200 ms behind the DAQ is refused by `fit`, `discover` and `characterize`, naming
/// both delays (`src/recording/clock.rs`); before, `fit` wrote a gauge factor 1 % low and a
/// Prandtl-Ishlinskii loop the sensor does not have. 20 ms late, under what the recording can
/// time, is accepted. 300 s: the 120 s recording the other tests use is accepted even 200 ms
/// late (measured; its eleven blocks are too short to time the angle: "cannot tell").
#[test]
fn a_late_tracker_is_refused_by_fit_discover_and_characterize() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let design = design.to_str().unwrap();
    let clean = recording_of(root, "clean", None, 300.0);
    let rows_per_ms = third_generator::SAMPLE_HZ / 1000.0;
    let late_200 = late(&clean, root, "late-200", (200.0 * rows_per_ms) as usize);
    let commands: [(&[&str], &str); 3] = [
        (&["fit"], "fit.toml"),
        (&["discover", "--fast"], "discover"),
        (&["characterize", "--kind", "loops"], "loops"),
    ];
    for (command, output) in commands {
        let out = root.join(output);
        let mut args = command.to_vec();
        args.extend(["--design", design, late_200.to_str().unwrap()]);
        args.extend(["-o", out.to_str().unwrap()]);
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} accepted a late tracker");
        for part in [
            "angle is late",
            "against the stroke",
            "against the sensors' voltages",
            "ms",
        ] {
            assert!(err.contains(part), "{args:?}: {part:?} not in {err}");
        }
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
    assert_fits(
        root,
        &late(&clean, root, "late-20", (20.0 * rows_per_ms) as usize),
    );
}

/// A joint with slack in its tendon (a play of 0.03 mm on a 0.7 mm stroke) whose angle is read
/// by an encoder (0.01° steps, no noise), 200 s at 500 Hz after a 10 s rest, written by this
/// test's own generator into `dir`; `edit` changes each row's angle (given its time).
fn encoder_with_slack(dir: &Path, edit: impl Fn(f64, f64) -> f64) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("rig.toml"),
        "sample_hz = 500.0\nsupply_v = 5.0\ndivider_ohm = [99600.0]\nnotes = \"encoder with slack, test generator\"\n",
    )
    .unwrap();
    let mut out = String::from("time_s,stroke_mm,angle_deg,v1_V\n");
    let (mut play, mut state) = (0.0_f64, 11_u64);
    let half_width = 0.03;
    for i in 0..100_000 {
        let t = i as f64 / 500.0;
        let u = (t - 10.0).max(0.0);
        let tau = std::f64::consts::TAU;
        let stroke =
            0.35 * (1.0 - (tau * u / 20.0).cos()) * (0.6 + 0.4 * (tau * u / 97.0).sin().powi(2));
        if stroke - play > half_width {
            play = stroke - half_width;
        } else if play - stroke > half_width {
            play = stroke + half_width;
        }
        let angle = 35.0 * play.max(0.0);
        let reading = edit(t, (angle / 0.01).round() * 0.01);
        let ohm = 180e3 * (1.0 + 14.0 * 0.0035 * angle.to_radians());
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let noise = 1e-3 * ((state >> 11) as f64 / (1u64 << 53) as f64 - 0.5);
        let volts = 5.0 * ohm / (ohm + 99.6e3) + noise;
        out.push_str(&format!("{t:.6},{stroke:.6},{reading:.4},{volts:.6}\n"));
    }
    std::fs::write(dir.join("data.csv"), out).unwrap();
}

/// An encoder holds its value exactly through a rest and while the slack is taken up after each
/// turn: neither is a clip nor a frozen reading, and `fit` accepts it (before, it was refused
/// as clipped at the rest's 0° and at the largest turn's 23.45°). The same encoder clipped at
/// 20°, or holding one value for 2 s mid-way through a motion, is refused.
#[test]
fn an_encoder_holding_through_a_rest_and_the_slack_is_not_refused() {
    let root = tempfile::tempdir().unwrap();
    let root = root.path();
    let slack = root.join("slack");
    encoder_with_slack(&slack, |_, a| a);
    assert_fits(root, &slack);
    let clipped = root.join("clipped");
    encoder_with_slack(&clipped, |_, a| a.min(20.0));
    let held = root.join("held");
    // 64-66 s: the stroke rises through the middle of its cycle.
    encoder_with_slack(
        &held,
        |t, a| if (64.0..66.0).contains(&t) { 11.45 } else { a },
    );
    let design = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    // Clipped from below at 5°: the rest's hold at the clip's value starts at the stroke's
    // turn and is not counted, so the message points past the rest (line 5002) at the first
    // stretch the stroke went past the clip and came back.
    let low = root.join("clipped-low");
    encoder_with_slack(&low, |_, a| a.max(5.0));
    let o = dlw(&[
        "fit",
        "--design",
        design.to_str().unwrap(),
        low.to_str().unwrap(),
        "-o",
        root.join("low.toml").to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("smallest value, 5,"),
        "{err}"
    );
    let line: usize = err
        .split(" line ")
        .nth(1)
        .and_then(|rest| rest.split(':').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no line in {err}"));
    assert!(line > 5002, "line {line}: {err}");
    for (dir, what) in [(&clipped, "largest"), (&held, "stopped updating")] {
        let out = root.join("refused.toml");
        assert_refused(
            &[
                "fit",
                "--design",
                design.to_str().unwrap(),
                dir.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
            ],
            &out,
            "angle_deg",
            what,
        );
    }
}
