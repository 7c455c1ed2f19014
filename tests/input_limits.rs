//! Inputs `dlw` refuses at the edge (issue 17, sections 2 and 3): endless or oversized files,
//! messages that would echo a huge input, a sample rate the time column contradicts, cycle
//! counts that only fill memory, machine coordinates past any travel, G-code templates that
//! smuggle a second line, design names that break XML; and the warning when a config's joint is
//! not the recording's design. Each refusal names the value and the limit, exits non-zero and
//! writes nothing.

use crate::common;
use common::{arg, dlw, dlw_ok, shipped_design};

use std::path::Path;

fn refused(args: &[&str], says: &[&str], not_written: &Path) -> String {
    let o = dlw(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "{args:?} succeeded");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    for s in says {
        assert!(err.contains(s), "{args:?}: {err:?} does not say {s:?}");
    }
    assert!(
        !not_written.exists(),
        "{args:?} wrote {}",
        not_written.display()
    );
    err
}

/// A 5 s random recording of a shipped design at `rec`.
fn simulate_random(design: &str, rec: &Path) {
    dlw_ok(&[
        "simulate",
        "--design",
        &shipped_design(design),
        "--protocol",
        "random",
        "--duration-s",
        "5",
        "-o",
        &arg(rec),
    ]);
}

/// A linear Joint A estimator config (the paper's GF and R₀) in `dir`.
fn joint_a_config(dir: &Path) -> std::path::PathBuf {
    let config = dir.join("a.toml");
    dlw_ok(&[
        "estimator-config",
        &shipped_design("joint-a.toml"),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&config),
    ]);
    config
}

fn edited(shipped: &str, from: &str, to: &str, dest: &Path) -> String {
    let text = std::fs::read_to_string(shipped).unwrap();
    assert!(text.contains(from), "{shipped} has no {from:?}");
    std::fs::write(dest, text.replacen(from, to, 1)).unwrap();
    arg(dest)
}

/// A design linked to `/dev/zero` was read until memory ran out; a recording's 200 MB header
/// line was echoed whole in the error.
#[test]
fn endless_and_oversized_inputs_are_refused_naming_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    let zero = dir.path().join("zero.toml");
    std::os::unix::fs::symlink("/dev/zero", &zero).unwrap();
    let out = dir.path().join("out");
    refused(
        &["inspect", &arg(&zero)],
        &["zero.toml", "not a regular file"],
        &out,
    );
    refused(
        &["build", &arg(&zero), "-o", &arg(&out)],
        &["zero.toml", "not a regular file"],
        &out,
    );
    // A regular file past the limit (sparse: 65 MiB of zeros on no disk space).
    let big = dir.path().join("big.toml");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(65 << 20)
        .unwrap();
    refused(
        &["inspect", &arg(&big)],
        &["big.toml", "64 MiB limit"],
        &out,
    );

    // A recording whose data.csv header is one 1 MB line.
    let rec = dir.path().join("rec");
    simulate_random("joint-a.toml", &rec);
    let data = rec.join("data.csv");
    let text = std::fs::read_to_string(&data).unwrap();
    let body = text.split_once('\n').unwrap().1;
    std::fs::write(&data, format!("{}\n{body}", "h".repeat(1 << 20))).unwrap();
    let config = joint_a_config(dir.path());
    let est = dir.path().join("est.csv");
    let err = refused(
        &[
            "estimate",
            "--config",
            &arg(&config),
            &arg(&rec),
            "-o",
            &arg(&est),
        ],
        &["header is", "more characters"],
        &est,
    );
    assert!(err.len() < 1000, "the error quotes {} bytes", err.len());

    // A TOML parser quotes the line it failed on: a 100 kB line is cut.
    let long = dir.path().join("long.toml");
    std::fs::write(&long, format!("name = \"{}\" junk\n", "x".repeat(100_000))).unwrap();
    let err = refused(&["inspect", &arg(&long)], &["long.toml"], &out);
    assert!(err.len() < 1000, "the error quotes {} bytes", err.len());
}

/// `sample_hz` was never checked against the time column.
#[test]
fn a_sample_rate_the_time_column_contradicts_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("rec");
    simulate_random("joint-a.toml", &rec);
    let rig = rec.join("rig.toml");
    let text = std::fs::read_to_string(&rig).unwrap();
    assert!(text.contains("sample_hz = 500.0"), "{text}");
    let config = joint_a_config(dir.path());
    let est = dir.path().join("est.csv");
    let estimate = [
        "estimate",
        "--config",
        &arg(&config),
        &arg(&rec),
        "-o",
        &arg(&est),
    ];
    // Within 1 % is accepted ...
    std::fs::write(&rig, text.replace("sample_hz = 500.0", "sample_hz = 504.0")).unwrap();
    dlw_ok(&estimate);
    std::fs::remove_file(&est).unwrap();
    // ... 2 % is not.
    std::fs::write(&rig, text.replace("sample_hz = 500.0", "sample_hz = 510.0")).unwrap();
    refused(
        &estimate,
        &["sample_hz = 510 Hz", "500.000000 Hz", "within 1 %"],
        &est,
    );
}

/// 2e7 characterization cycles took 1.9 GB for a 60 s run.
#[test]
fn cycle_counts_past_the_limit_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("s.toml");
    let rec = dir.path().join("rec");
    for (table, text, says) in [
        (
            "characterization",
            "cycles = 20000000",
            "characterization.cycles",
        ),
        ("relaxation", "levels = 5000", "relaxation.levels"),
        (
            "random",
            "min_ramp_s = 0.000001\nmax_ramp_s = 1.0",
            "random.min_ramp_s",
        ),
    ] {
        std::fs::write(
            &scenario,
            format!("protocol = \"{table}\"\n[protocols.{table}]\n{text}\n"),
        )
        .unwrap();
        refused(
            &[
                "simulate",
                "--design",
                &shipped_design("joint-a.toml"),
                "--scenario",
                &arg(&scenario),
                "--duration-s",
                "60",
                "-o",
                &arg(&rec),
            ],
            &[says],
            &rec,
        );
    }
}

/// `z_axis_mm = 1e308` wrote a 309-digit Z into the G-code; a newline in a laser template
/// injected a move past the X travel.
#[test]
fn machine_profiles_keep_coordinates_in_travel_and_templates_on_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = format!(
        "{}/designs/machines/linuxcnc-reference.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let out = dir.path().join("a.ngc");
    let cases = [
        (
            "z_axis_mm = 0.0",
            "z_axis_mm = 1e308",
            "focus.z_axis_mm",
            "±10000 mm",
        ),
        (
            "x_max_mm = 150.0",
            "x_max_mm = 1e9",
            "limits.x_max_mm",
            "±10000 mm",
        ),
        (
            "beam_on = \"M3\"",
            "beam_on = \"M3\\nG0 X900\"",
            "laser.beam_on",
            "U+000A",
        ),
    ];
    for (from, to, key, limit) in cases {
        let machine = edited(&shipped, from, to, &dir.path().join("m.toml"));
        refused(
            &[
                "program",
                &shipped_design("joint-a.toml"),
                "--machine",
                &machine,
                "-o",
                &arg(&out),
            ],
            &[key, limit],
            &out,
        );
    }
}

/// A NUL in a design's name made SVGs that were not valid XML; markup characters are escaped.
#[test]
fn design_names_are_printable_and_escaped() {
    let dir = tempfile::tempdir().unwrap();
    let shipped = shipped_design("joint-a.toml");
    let out = dir.path().join("out");
    let nul = edited(
        &shipped,
        "name = \"Joint A\"",
        "name = \"Joint \\u0000 A\"",
        &dir.path().join("nul.toml"),
    );
    refused(
        &["build", &nul, "-o", &arg(&out)],
        &["U+0000", "printable"],
        &out,
    );

    let markup = edited(
        &shipped,
        "name = \"Joint A\"",
        "name = \"Joint <A> & \\\"B\\\"\"",
        &dir.path().join("markup.toml"),
    );
    dlw_ok(&["build", &markup, "-o", &arg(&out)]);
    let svg = std::fs::read_to_string(out.join("markup-layout.svg")).unwrap();
    assert!(!svg.contains("<A>"), "the name's markup is written raw");
    assert!(svg.contains("&lt;A&gt; &amp;"), "the name is not escaped");
}

/// A Joint A config ran on a Joint C recording without a word.
#[test]
fn a_config_for_another_design_draws_a_warning_naming_both() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("rec");
    simulate_random("joint-c.toml", &rec);
    let config = |design: &str, name: &str| {
        let path = dir.path().join(name);
        dlw_ok(&[
            "estimator-config",
            &shipped_design(design),
            "--gauge-factor",
            "1.3",
            "--r0-ohm",
            "26e3",
            "-o",
            &arg(&path),
        ]);
        arg(&path)
    };
    let estimate = |config: &str, out: &str| {
        let o = dlw_ok(&[
            "estimate",
            "--config",
            config,
            &arg(&rec),
            "-o",
            &arg(&dir.path().join(out)),
        ]);
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let wrong = estimate(&config("joint-a.toml", "a.toml"), "a.csv");
    assert!(
        wrong.contains(
            "warning: the estimator config's joint is not the recording's design \"Joint C\""
        ) && wrong.contains("checksum")
            && wrong.contains("style uan vs bsn"),
        "{wrong}"
    );
    let right = estimate(&config("joint-c.toml", "c.toml"), "c.csv");
    assert!(!right.contains("joint is not"), "{right}");
}

/// Runs `dlw args` with a deadline: `None` when it had not finished after `seconds` (then it is
/// killed), else its output.
fn dlw_within(args: &[&str], seconds: u64) -> Option<std::process::Output> {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let start = std::time::Instant::now();
    while start.elapsed() < std::time::Duration::from_secs(seconds) {
        if child.try_wait().unwrap().is_some() {
            return Some(child.wait_with_output().unwrap());
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// Issue 30: `--daq /dev/zero`, `--tracker /dev/zero` and `dlw explore /dev/zero` read gigabytes
/// before failing on memory, and a FIFO with no writer blocked forever. Every reader refuses
/// anything that is not a regular file, or a pipe that has data within a second, naming it.
#[test]
fn devices_and_silent_pipes_are_refused_by_every_reader() {
    let dir = tempfile::tempdir().unwrap();
    let bench = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/bench");
    let (daq, aurora) = (arg(&bench.join("daq.csv")), arg(&bench.join("aurora.csv")));
    let rec = dir.path().join("rec");
    let import = |daq: &str, tracker: &str| {
        vec![
            "import-recording".to_string(),
            "--daq".into(),
            daq.into(),
            "--voltage".into(),
            "AI0".into(),
            "--divider-ohm".into(),
            "99.6e3".into(),
            "--supply-v".into(),
            "5".into(),
            "--stroke".into(),
            "AI2".into(),
            "--stroke-mm-per-v".into(),
            "0.5".into(),
            "--tracker".into(),
            tracker.into(),
            "-o".into(),
            arg(&rec),
        ]
    };
    let out = dir.path().join("out");
    let fifo = dir.path().join("silent.fifo");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let fifo = arg(&fifo);
    let cases: Vec<(Vec<String>, &str)> = vec![
        (import("/dev/zero", &aurora), "/dev/zero"),
        (import(&daq, "/dev/zero"), "/dev/zero"),
        (
            vec!["explore".into(), "/dev/zero".into(), "-o".into(), arg(&out)],
            "/dev/zero",
        ),
        (vec!["inspect".into(), "/dev/zero".into()], "/dev/zero"),
        (import(&fifo, &aurora), "silent.fifo"),
        (import(&daq, &fifo), "silent.fifo"),
        (vec!["inspect".into(), fifo.clone()], "silent.fifo"),
    ];
    for (args, names) in cases {
        let a: Vec<&str> = args.iter().map(String::as_str).collect();
        let started = std::time::Instant::now();
        let o = dlw_within(&a, 20).unwrap_or_else(|| panic!("{a:?} still reading after 20 s"));
        let err = String::from_utf8_lossy(&o.stderr);
        eprintln!("{:.1} s: {err}", started.elapsed().as_secs_f64());
        assert!(!o.status.success(), "{a:?} succeeded");
        assert!(!err.contains("panicked"), "{a:?}: {err}");
        assert!(err.contains(names), "{a:?}: {err}");
        assert!(
            err.contains("not a regular file") || err.contains("no data within"),
            "{a:?}: {err}"
        );
        assert!(!rec.exists() && !out.exists(), "{a:?} wrote");
    }
    // A pipe that has data is read: a design through a FIFO with a writer.
    let design = std::fs::read_to_string(shipped_design("joint-a.toml")).unwrap();
    let writer = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::write(fifo, design).unwrap())
    };
    let o = dlw_within(&["inspect", &fifo], 20).expect("inspect through a FIFO finished");
    writer.join().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
