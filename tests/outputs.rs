//! The output policy (docs/outputs.md), once per command: a table of commands, each run against
//! every output case, asserting what is refused, what is written, and that nothing else in the
//! surrounding folder changed. Adding a command is one row in [`commands`].

use crate::common;
use common::{arg, dlw, shipped_design};

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What a command writes at `-o`.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    /// One file: `-o -`, FIFOs and symlinks apply.
    File,
    /// A folder.
    Folder,
}

/// One row: a command, what it writes, and its arguments for an output path, given the fixture.
struct Row {
    name: &'static str,
    kind: Kind,
    /// Arguments without `--force`; `out` is the output path.
    args: fn(&Fixture, &str) -> Vec<String>,
    /// The input that the "input itself" case points the output at.
    input: fn(&Fixture) -> PathBuf,
}

/// Inputs shared by every row, made once, outside the folders the cases look at.
struct Fixture {
    _root: tempfile::TempDir,
    design: PathBuf,
    recording: PathBuf,
    config: PathBuf,
}

fn fixture() -> Fixture {
    let root = tempfile::tempdir().unwrap();
    let design = root.path().join("joint-c.toml");
    std::fs::copy(shipped_design("joint-c.toml"), &design).unwrap();
    let recording = root.path().join("rec");
    // Long enough for `fit` to see the resistance rise with strain (the first cycle).
    let o = dlw(&simulate_args(&design, &recording, "60"));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The example bench's DAQ export and tracker log, for import-recording.
    let bench = root.path().join("bench");
    std::fs::create_dir(&bench).unwrap();
    for name in ["daq.csv", "aurora.csv"] {
        let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/bench");
        std::fs::copy(shipped.join(name), bench.join(name)).unwrap();
    }
    let config = root.path().join("c.toml");
    let mut a = vec!["estimator-config".to_string(), arg(&design)];
    a.extend(common::JOINT_C_TABLE_V.iter().map(|s| s.to_string()));
    a.extend(["-o".into(), arg(&config)]);
    let o = dlw(&a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    Fixture {
        _root: root,
        design,
        recording,
        config,
    }
}

/// A small exploration spec beside the fixture's design (written on first use).
fn explore_spec(f: &Fixture) -> PathBuf {
    let path = f.design.with_file_name("explore.toml");
    if !path.exists() {
        let tubes = shipped_design("tubes.toml");
        let text = format!(
            "base = \"joint-c.toml\"\ntubes = \"{}\"\ngauge_factor = 5.0\nr0_ohm = 1e5\n\
             [vary]\nnotch_count = [8, 10]\n[objectives]\nmaximize = [\"range_deg\"]\n",
            tubes
        );
        std::fs::write(&path, text).unwrap();
    }
    path
}

fn simulate_args(design: &Path, out: &Path, duration_s: &str) -> Vec<String> {
    [
        "simulate",
        "--design",
        &arg(design),
        "--protocol",
        "characterization",
    ]
    .iter()
    .map(|s| s.to_string())
    .chain([
        "--duration-s".into(),
        duration_s.into(),
        "-o".into(),
        arg(out),
    ])
    .collect()
}

fn strings(a: &[&str]) -> Vec<String> {
    a.iter().map(|s| s.to_string()).collect()
}

/// Every command that writes; one row each.
fn commands() -> Vec<Row> {
    vec![
        Row {
            name: "simulate",
            kind: Kind::Folder,
            args: |f, out| simulate_args(&f.design, Path::new(out), "2"),
            input: |f| f.design.clone(),
        },
        Row {
            name: "estimate",
            kind: Kind::File,
            args: |f, out| {
                strings(&[
                    "estimate",
                    "--config",
                    &arg(&f.config),
                    &arg(&f.recording),
                    "-o",
                    out,
                ])
            },
            input: |f| f.recording.join("data.csv"),
        },
        Row {
            name: "estimator-config",
            kind: Kind::File,
            args: |f, out| {
                let mut a = strings(&["estimator-config", &arg(&f.design), "-o", out]);
                a.extend(common::JOINT_C_TABLE_V.iter().map(|s| s.to_string()));
                a
            },
            input: |f| f.design.clone(),
        },
        Row {
            name: "program",
            kind: Kind::File,
            args: |f, out| strings(&["program", &arg(&f.design), "-o", out]),
            input: |f| f.design.clone(),
        },
        Row {
            name: "explore",
            kind: Kind::Folder,
            args: |f, out| strings(&["explore", &arg(&explore_spec(f)), "-o", out]),
            input: explore_spec,
        },
        Row {
            name: "build",
            kind: Kind::Folder,
            args: |f, out| strings(&["build", &arg(&f.design), "-o", out]),
            input: |f| f.design.clone(),
        },
        Row {
            name: "fluoro-render",
            kind: Kind::Folder,
            args: |f, out| {
                strings(&[
                    "fluoro-render",
                    "--recording",
                    &arg(&f.recording),
                    "--fps",
                    "2",
                    "--size",
                    "64",
                    "-o",
                    out,
                ])
            },
            input: |f| f.recording.clone(),
        },
        Row {
            name: "fit",
            kind: Kind::File,
            args: |f, out| {
                strings(&[
                    "fit",
                    "--design",
                    &arg(&f.design),
                    &arg(&f.recording),
                    "--model",
                    "linear",
                    "-o",
                    out,
                ])
            },
            input: |f| f.recording.join("data.csv"),
        },
        Row {
            name: "characterize",
            kind: Kind::Folder,
            args: |f, out| {
                strings(&[
                    "characterize",
                    "--design",
                    &arg(&f.design),
                    &arg(&f.recording),
                    "--kind",
                    "loops",
                    "-o",
                    out,
                ])
            },
            input: |f| f.recording.clone(),
        },
        Row {
            name: "control",
            kind: Kind::Folder,
            args: |f, out| {
                strings(&[
                    "control",
                    "--design",
                    &arg(&f.design),
                    "--config",
                    &arg(&f.config),
                    "--protocol",
                    "random",
                    "--duration-s",
                    "5",
                    "-o",
                    out,
                ])
            },
            input: |f| f.config.clone(),
        },
        Row {
            name: "import-recording",
            kind: Kind::Folder,
            args: |f, out| {
                let bench = f.design.with_file_name("bench");
                strings(&[
                    "import-recording",
                    "--daq",
                    &arg(&bench.join("daq.csv")),
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
                    &arg(&bench.join("aurora.csv")),
                    "-o",
                    out,
                ])
            },
            input: |f| f.design.with_file_name("bench").join("aurora.csv"),
        },
        Row {
            name: "draw",
            kind: Kind::File,
            args: |f, out| strings(&["draw", &arg(&f.design), "--dxf", out]),
            input: |f| f.design.clone(),
        },
    ]
}

/// Every file under `dir` (symlinks not followed) with its bytes, or `<fifo>`, `<link → …>`.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            let p = e.path();
            let t = std::fs::symlink_metadata(&p).unwrap().file_type();
            let v = if t.is_symlink() {
                format!("<link → {}>", std::fs::read_link(&p).unwrap().display())
            } else if t.is_dir() {
                stack.push(p.clone());
                "<dir>".into()
            } else if t.is_file() {
                String::from_utf8_lossy(&std::fs::read(&p).unwrap()).into_owned()
            } else {
                "<special>".into()
            };
            out.insert(p.strip_prefix(dir).unwrap().to_path_buf(), v);
        }
    }
    out
}

fn run(row: &Row, f: &Fixture, out: &str, force: bool) -> std::process::Output {
    let mut a = (row.args)(f, out);
    if force {
        a.push("--force".into());
    }
    dlw(&a)
}

fn refused(row: &Row, o: &std::process::Output, needle: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{}: accepted", row.name);
    assert!(err.contains(needle), "{}: {err}", row.name);
}

#[test]
fn every_command_follows_the_output_policy() {
    let f = fixture();
    for row in commands() {
        let work = tempfile::tempdir().unwrap();
        let w = work.path();

        // An existing file: refused without --force, untouched; with it, replaced.
        let existing = w.join("existing.toml");
        std::fs::write(&existing, b"keep me").unwrap();
        if row.kind == Kind::Folder {
            // A non-empty folder.
            std::fs::create_dir(w.join("full")).unwrap();
            std::fs::write(w.join("full/thesis.tex"), b"keep me").unwrap();
        }
        let before = snapshot(w);
        let target = if row.kind == Kind::Folder {
            w.join("full")
        } else {
            existing.clone()
        };
        refused(&row, &run(&row, &f, &arg(&target), false), "already exists");
        assert_eq!(snapshot(w), before, "{}: the folder changed", row.name);
        let o = run(&row, &f, &arg(&target), true);
        assert!(
            o.status.success(),
            "{}: {}",
            row.name,
            String::from_utf8_lossy(&o.stderr)
        );
        let after = snapshot(w);
        let changed: Vec<_> = after
            .iter()
            .filter(|(k, v)| {
                before.get(*k) != Some(*v) && !k.starts_with(target.strip_prefix(w).unwrap())
            })
            .collect();
        assert!(changed.is_empty(), "{}: also changed {changed:?}", row.name);
        let gone: Vec<_> = before
            .keys()
            .filter(|k| !after.contains_key(*k) && !k.starts_with(target.strip_prefix(w).unwrap()))
            .collect();
        assert!(gone.is_empty(), "{}: removed {gone:?}", row.name);

        // The input itself: refused even with --force, and the input is unchanged.
        let input = (row.input)(&f);
        let input_before = std::fs::read(if input.is_dir() {
            input.join("data.csv")
        } else {
            input.clone()
        })
        .ok();
        let o = run(&row, &f, &arg(&input), true);
        refused(&row, &o, "refused even with --force");
        assert!(
            String::from_utf8_lossy(&o.stderr).contains(&arg(&input)),
            "{}",
            row.name
        );
        let input_after = std::fs::read(if input.is_dir() {
            input.join("data.csv")
        } else {
            input.clone()
        })
        .ok();
        assert_eq!(input_before, input_after, "{}: the input changed", row.name);

        if row.kind == Kind::File {
            file_cases(&row, &f, w);
        } else {
            folder_to_stdout_case(&row, &f, w);
        }
        read_only_case(&row, &f, w);

        // No staging or temporary files are left anywhere in the folder.
        let leftovers: Vec<_> = snapshot(w)
            .into_keys()
            .filter(|k| k.to_string_lossy().contains(".dlw-staging-"))
            .collect();
        assert!(leftovers.is_empty(), "{}: {leftovers:?}", row.name);
    }
}

/// An output inside a folder that cannot be written: a clear error naming the output, no panic,
/// and the folder unchanged. As root (CI), permissions do not stop a write, so the folder is
/// also made immutable (`chattr +i`).
fn read_only_case(row: &Row, f: &Fixture, w: &Path) {
    use std::os::unix::fs::PermissionsExt;
    let ro = w.join("read-only");
    std::fs::create_dir(&ro).unwrap();
    std::fs::write(ro.join("kept.txt"), b"keep me").unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    let immutable = std::process::Command::new("chattr")
        .arg("+i")
        .arg(&ro)
        .status()
        .is_ok_and(|s| s.success());
    let probe = std::fs::write(ro.join("probe"), b"");
    if probe.is_ok() {
        eprintln!(
            "{}: cannot make a read-only folder here; case skipped",
            row.name
        );
        std::fs::remove_file(ro.join("probe")).unwrap();
    } else {
        let before = snapshot(&ro);
        let out = ro.join(if row.kind == Kind::Folder {
            "out"
        } else {
            "out.toml"
        });
        let o = run(row, f, &arg(&out), false);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success(),
            "{}: wrote into a read-only folder",
            row.name
        );
        assert!(!err.contains("panicked"), "{}: {err}", row.name);
        assert!(
            err.contains("read-only"),
            "{}: the error does not name the folder: {err}",
            row.name
        );
        assert_eq!(
            snapshot(&ro),
            before,
            "{}: the read-only folder changed",
            row.name
        );
    }
    if immutable {
        std::process::Command::new("chattr")
            .arg("-i")
            .arg(&ro)
            .status()
            .unwrap();
    }
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).unwrap();
    std::fs::remove_dir_all(&ro).unwrap();
}

/// `-o -` for a command that writes a folder: refused with a message (issue 30: it made a
/// folder named `-`), run in `w` so that such a folder would show.
fn folder_to_stdout_case(row: &Row, f: &Fixture, w: &Path) {
    let before = snapshot(w);
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args((row.args)(f, "-"))
        .current_dir(w)
        .output()
        .unwrap();
    refused(row, &o, "cannot hold a folder");
    assert_eq!(snapshot(w), before, "{}: wrote into the folder", row.name);
}

/// `-o -`, a symlink and a FIFO, for commands that write one file.
fn file_cases(row: &Row, f: &Fixture, w: &Path) {
    // `-o -`: written to standard output, no file named `-`.
    let before = snapshot(w);
    let cwd_dash = Path::new("-").exists();
    let o = run(row, f, "-", false);
    assert!(
        o.status.success(),
        "{}: {}",
        row.name,
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(o.stdout.len() > 20, "{}: nothing on stdout", row.name);
    assert_eq!(
        Path::new("-").exists(),
        cwd_dash,
        "{}: wrote a file named -",
        row.name
    );
    assert_eq!(snapshot(w), before);

    // A symlink: followed with --force; the link stays, its target is replaced.
    let target = w.join("target.toml");
    std::fs::write(&target, b"old").unwrap();
    let link = w.join("link.toml");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    refused(row, &run(row, f, &arg(&link), false), "already exists");
    let o = run(row, f, &arg(&link), true);
    assert!(
        o.status.success(),
        "{}: {}",
        row.name,
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink(),
        "{}",
        row.name
    );
    assert_ne!(std::fs::read(&target).unwrap(), b"old", "{}", row.name);

    // A FIFO: written to directly, and still a FIFO afterwards.
    let fifo = w.join("pipe.toml");
    let c = std::ffi::CString::new(fifo.as_os_str().as_encoded_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o644) }, 0);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).unwrap())
    };
    let o = run(row, f, &arg(&fifo), false);
    assert!(
        o.status.success(),
        "{}: {}",
        row.name,
        String::from_utf8_lossy(&o.stderr)
    );
    let got = reader.join().unwrap();
    assert!(
        got.len() > 20,
        "{}: {} bytes through the FIFO",
        row.name,
        got.len()
    );
    use std::os::unix::fs::FileTypeExt;
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo(),
        "{}",
        row.name
    );
}

#[test]
fn two_simulate_runs_with_one_output_one_wins() {
    let work = tempfile::tempdir().unwrap();
    let design = work.path().join("joint-c.toml");
    std::fs::copy(shipped_design("joint-c.toml"), &design).unwrap();
    let out = work.path().join("rec");
    let spawn = || {
        std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
            .args(simulate_args(&design, &out, "20"))
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap()
    };
    let (a, b) = (spawn(), spawn());
    let results = [a.wait_with_output().unwrap(), b.wait_with_output().unwrap()];
    let ok = results.iter().filter(|o| o.status.success()).count();
    assert_eq!(
        ok,
        1,
        "{:?}",
        results
            .iter()
            .map(|o| String::from_utf8_lossy(&o.stderr).into_owned())
            .collect::<Vec<_>>()
    );
    let loser = results.iter().find(|o| !o.status.success()).unwrap();
    let err = String::from_utf8_lossy(&loser.stderr);
    assert!(
        err.contains("appeared while this run was writing") || err.contains("already exists"),
        "{err}"
    );
    let names: Vec<_> = std::fs::read_dir(work.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn sigterm_during_simulate_leaves_no_staging_folder() {
    let work = tempfile::tempdir().unwrap();
    let design = work.path().join("joint-c.toml");
    std::fs::copy(shipped_design("joint-c.toml"), &design).unwrap();
    let out = work.path().join("rec");
    for wait_ms in [50, 200, 400, 800] {
        let child = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
            .args(simulate_args(&design, &out, "3000"))
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(wait_ms));
        // SAFETY: signalling the child we spawned.
        unsafe { libc::kill(child.id() as i32, libc::SIGTERM) };
        let o = child.wait_with_output().unwrap();
        let names: Vec<_> = std::fs::read_dir(work.path())
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        assert!(
            !names.iter().any(|n| n.starts_with(".dlw-staging-")),
            "after {wait_ms} ms: {names:?}, {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let _ = std::fs::remove_dir_all(&out);
    }
}

#[test]
fn a_stale_staging_folder_is_removed_and_reported() {
    let work = tempfile::tempdir().unwrap();
    let design = work.path().join("joint-c.toml");
    std::fs::copy(shipped_design("joint-c.toml"), &design).unwrap();
    let stale = work.path().join(".dlw-staging-2147483646-xyz");
    std::fs::create_dir(&stale).unwrap();
    std::fs::write(stale.join("data.csv"), b"x").unwrap();
    let o = dlw(&simulate_args(&design, &work.path().join("rec"), "2"));
    assert!(o.status.success());
    assert!(!stale.exists());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("2147483646"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn program_refuses_a_sheet_over_the_program() {
    let work = tempfile::tempdir().unwrap();
    let p = arg(&work.path().join("x.ngc"));
    let o = dlw(&[
        "program",
        &shipped_design("joint-c.toml"),
        "-o",
        &p,
        "--sheet",
        &p,
    ]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("same file"));
    assert_eq!(std::fs::read_dir(work.path()).unwrap().count(), 0);
}

/// Issue 30: `dlw explore SPEC -o D --force`, with the spec's `base` design and `tubes`
/// catalogue inside `D`, deleted both; `dlw build` and `dlw program` replaced the process sets
/// a design includes from its `process/` folder. Every file a command reads is an input the
/// output policy protects, even with --force.
#[test]
fn files_a_spec_or_a_design_names_are_inputs_too() {
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    let d = w.join("D");
    std::fs::create_dir(&d).unwrap();
    std::fs::copy(shipped_design("joint-c.toml"), d.join("joint-c.toml")).unwrap();
    std::fs::copy(shipped_design("tubes.toml"), d.join("tubes.toml")).unwrap();
    let spec = w.join("spec.toml");
    std::fs::write(
        &spec,
        "base = \"D/joint-c.toml\"\ntubes = \"D/tubes.toml\"\ngauge_factor = 5.0\nr0_ohm = 1e5\n\
         [vary]\ntube = [\"paper-2.5\"]\nnotch_count = [8, 10]\n\
         [objectives]\nmaximize = [\"range_deg\"]\n",
    )
    .unwrap();
    let before = snapshot(w);
    for (what, args) in [
        (
            "base",
            vec!["explore", &arg(&spec), "-o", &arg(&d), "--force"],
        ),
        (
            "tubes",
            vec![
                "explore",
                &arg(&spec),
                "-o",
                &arg(&d.join("tubes.toml")),
                "--force",
            ],
        ),
    ] {
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{what}: accepted");
        assert!(err.contains("refused even with --force"), "{what}: {err}");
        assert_eq!(snapshot(w), before, "{what}: an input changed");
    }
    // A design's process sets: `process/NAME.toml` beside it.
    let process = d.join("process");
    std::fs::create_dir(&process).unwrap();
    let sensor = std::fs::read_to_string(format!(
        "{}/designs/process/sensor.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    std::fs::write(process.join("sensor.toml"), &sensor).unwrap();
    let design = arg(&d.join("joint-c.toml"));
    let before = snapshot(w);
    for args in [
        vec!["build", &design, "-o", &arg(&process), "--force"],
        vec![
            "program",
            &design,
            "-o",
            &arg(&process.join("sensor.toml")),
            "--force",
        ],
    ] {
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}: accepted");
        assert!(
            err.contains("refused even with --force") && err.contains("sensor.toml"),
            "{args:?}: {err}"
        );
        assert_eq!(snapshot(w), before, "{args:?}: an input changed");
    }
}

/// The joint designs a robot file names are inputs of every command given the robot: with
/// `--force`, an output on one of them is refused and nothing changes (before, `control`,
/// `simulate`, `build` and `estimator-config` replaced `joint-b.toml` with their output).
#[test]
fn the_joint_designs_a_robot_names_are_inputs_too() {
    let work = tempfile::tempdir().unwrap();
    let w = work.path();
    for name in ["robot-bdb.toml", "joint-b.toml", "joint-d.toml"] {
        std::fs::copy(shipped_design(name), w.join(name)).unwrap();
    }
    let robot = arg(&w.join("robot-bdb.toml"));
    let config = w.join("cfg.toml");
    let o = dlw(&[
        "estimator-config",
        &robot,
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&config),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (b, d, cfg) = (
        arg(&w.join("joint-b.toml")),
        arg(&w.join("joint-d.toml")),
        arg(&config),
    );
    let before = snapshot(w);
    for args in [
        vec![
            "control",
            "--design",
            &robot,
            "--config",
            &cfg,
            "--duration-s",
            "2",
            "-o",
            &b,
        ],
        vec![
            "simulate",
            "--design",
            &robot,
            "--duration-s",
            "2",
            "-o",
            &d,
        ],
        vec![
            "estimator-config",
            &robot,
            "--gauge-factor",
            "15",
            "--r0-ohm",
            "2e5",
            "-o",
            &b,
        ],
        vec!["build", &robot, "-o", &d],
        vec!["program", &robot, "-o", &b],
        vec!["draw", &robot, "--svg", &d],
    ] {
        let mut args = args;
        args.push("--force");
        let o = dlw(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}: accepted");
        assert!(
            err.contains("refused even with --force") && err.contains("joint-"),
            "{args:?}: {err}"
        );
        assert_eq!(snapshot(w), before, "{args:?}: an input changed");
    }
}
