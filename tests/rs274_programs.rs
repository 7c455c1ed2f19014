//! Every generated LinuxCNC program, run through LinuxCNC's own interpreter (`rs274 -g`), and
//! the physics checked from its canonical output: beam on only while feeding, power, pulse
//! settings and surface speed per operation, repetitions, operation order, where each notch is
//! cut, the parting cut, the written lines, travel.
//!
//! Programs are made through the `dlw` binary (`dlw program`), for the four shipped designs and
//! for designs outside the paper. rs274 must be installed (Debian `linuxcnc-uspace`,
//! `scripts/test.sh` installs it); without it these tests fail, they never skip.
//!
//! The checks and their tolerances are in `canon/checks.rs`.

use crate::common;
use common::dlw;

use crate::canon;
use common::designs as common_designs;

use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use canon::checks::{check, expected};
use canon::{parse, run_rs274};

/// A design outside the paper: a 2.5 mm OD tube with a long UAN notch pattern and its own
/// fabrication table.
const UAN_LONG: &str = r#"
name = "UAN 2.5 mm, N = 14"
style = "uan"
outer_radius_mm = 1.25
inner_radius_mm = 1.0
notch_arc_mm = 5.0
notch_width_mm = 0.35
notch_spacing_mm = 0.45
notch_count = 14
joint_length_mm = 10.75
sensor_arc_mm = 0.6

[fabrication]
kerf_mm = 0.025
distal_margin_mm = 1.4
lead_length_mm = 1.5
"#;

/// Writes a program for `design` through the binary; returns its path.
fn program(design: &Path, dir: &Path, extra: &[&str]) -> PathBuf {
    let out = dir.join("job.ngc");
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "program".as_ref(),
        design.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        // Each case reruns into the same job.ngc once rs274 has read the previous one.
        "--force".as_ref(),
    ];
    args.extend(extra.iter().map(|s| std::ffi::OsStr::new(*s)));
    let o = dlw(&args);
    assert!(
        o.status.success(),
        "dlw program {} failed:\n{}",
        design.display(),
        String::from_utf8_lossy(&o.stderr)
    );
    out
}

fn run_case(design: &Path, what: &str) {
    let dir = tempfile::tempdir().unwrap();
    let file = program(design, dir.path(), &[]);
    let canon = parse(&run_rs274(&file));
    check(&canon, &expected(design, None), what);
}

#[test]
fn shipped_designs_pass_the_interpreter_checks() {
    for design in common_designs::shipped() {
        let what = design.file_name().unwrap().to_string_lossy().into_owned();
        run_case(&design, &what);
    }
}

#[test]
fn designs_outside_the_paper_pass_the_interpreter_checks() {
    let dir = tempfile::tempdir().unwrap();
    for (i, text) in [
        common_designs::BSN_WIDE,
        common_designs::UAN_THREE,
        UAN_LONG,
    ]
    .iter()
    .enumerate()
    {
        let path = dir.path().join(format!("outside-{i}.toml"));
        std::fs::write(&path, text).unwrap();
        run_case(&path, &format!("outside-{i}"));
    }
}

/// A Z step per pass, written both as a loop with a focus variable and unrolled: the focus
/// goes down by the step each pass, and nothing else changes.
#[test]
fn z_step_per_pass_in_loops_and_unrolled() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("process")).unwrap();
    std::fs::create_dir_all(dir.path().join("machines")).unwrap();
    let deep = include_str!("../designs/process/notches.toml")
        .replace("repetitions = 32", "repetitions = 5")
        .replace("# z_step_mm = 0.0", "z_step_mm = 0.004");
    std::fs::write(dir.path().join("process/deep.toml"), deep).unwrap();
    let unrolled = include_str!("../designs/machines/linuxcnc-reference.toml")
        .replace("repetitions = \"loop\"", "repetitions = \"unroll\"");
    std::fs::write(dir.path().join("machines/unrolled.toml"), unrolled).unwrap();
    let design = dir.path().join("deep.toml");
    let text = std::fs::read_to_string(&common_designs::shipped()[1]).unwrap();
    std::fs::write(&design, format!("{text}\n[process]\nnotches = \"deep\"\n")).unwrap();
    let mut texts = Vec::new();
    for machine in [None, Some("unrolled")] {
        let extra: Vec<&str> = machine.map(|m| vec!["--machine", m]).unwrap_or_default();
        let file = program(&design, dir.path(), &extra);
        let program_text = std::fs::read_to_string(&file).unwrap();
        assert_eq!(
            program_text.contains("repeat"),
            machine.is_none(),
            "loops only in loop mode"
        );
        let canon = parse(&run_rs274(&file));
        let e = expected(&design, machine);
        check(&canon, &e, &format!("deep {machine:?}"));
        // Per notch pass k the focus is at r_o − 0.004·k.
        let mut per_path: BTreeMap<String, Vec<f64>> = BTreeMap::new();
        for m in canon
            .moves
            .iter()
            .filter(|m| m.feed && m.operation == "notches")
        {
            let zs = per_path.entry(m.path.clone()).or_default();
            if zs.last() != Some(&m.to[2]) {
                zs.push(m.to[2]);
            }
        }
        for (path, zs) in &per_path {
            let want: Vec<f64> = (0..5)
                .map(|k| ((e.r_o - 0.004 * k as f64) * 1e4).round() / 1e4)
                .collect();
            assert_eq!(zs, &want, "{path}: focus per pass");
        }
        // The rapids differ (a loop moves the focus on its own line); the cuts must not.
        let feeds = canon
            .moves
            .iter()
            .filter(|m| m.feed)
            .map(|m| (m.from, m.to, m.feed_rate));
        texts.push(feeds.collect::<Vec<_>>());
    }
    assert!(
        texts[0] == texts[1],
        "loops and unrolled passes cut the same"
    );
}

/// A program made from the DXF that `dlw draw` wrote cuts the same notches as the drawing.
#[test]
fn program_from_a_dxf_cuts_the_drawn_notches() {
    let dir = tempfile::tempdir().unwrap();
    let design = &common_designs::shipped()[2];
    let dxf = dir.path().join("c.dxf");
    let o = dlw(&[
        "draw".as_ref(),
        design.as_os_str(),
        "--dxf".as_ref(),
        dxf.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = dir.path().join("from-dxf.ngc");
    let o = dlw(&[
        "program".as_ref(),
        "--from-dxf".as_ref(),
        dxf.as_os_str(),
        "--design".as_ref(),
        design.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let imported = dlw::drawing::layout_from_dxf(&std::fs::read(&dxf).unwrap()).unwrap();
    let mut e = expected(design, None);
    e.layout = imported.layout;
    check(&parse(&run_rs274(&out)), &e, "joint-c from its DXF");
}

#[test]
fn pure_rotations_and_mixed_moves_keep_the_surface_speed() {
    // Joint A's sensor has pure X moves, pure rotations (pads) and its notches long rotations;
    // check that all three kinds occur and pass (the speed check itself is in `check`).
    let dir = tempfile::tempdir().unwrap();
    let design = &common_designs::shipped()[0];
    let canon = parse(&run_rs274(&program(design, dir.path(), &[])));
    let feeds: Vec<_> = canon.moves.iter().filter(|m| m.feed).collect();
    let pure_x = feeds.iter().filter(|m| m.from[3] == m.to[3]).count();
    let pure_a = feeds.iter().filter(|m| m.from[0] == m.to[0]).count();
    assert!(
        pure_x > 0 && pure_a > 0,
        "{pure_x} pure X, {pure_a} pure A moves"
    );
    let r_o = 1.24;
    for m in &feeds {
        let v = m.surface_speed_mm_s(r_o);
        let set = if m.operation == "sensor" { 1.0 } else { 25.0 };
        assert!((v / set - 1.0).abs() <= 0.005, "{m:?}: {v}");
    }
    // A 90° rotation at 25 mm/s on r_o = 1.24 mm takes t = 1.24·π/2/25 s; rs274 hands motion
    // the inverse-time word as 90°/t per minute.
    let quarter = feeds
        .iter()
        .find(|m| m.operation == "parting" && (m.to[3] - m.from[3]).abs() > 89.9)
        .expect("a quarter turn in the parting cut");
    let t = 1.24 * PI / 2.0 / 25.0;
    assert!(
        (quarter.feed_rate / (90.0 * 60.0 / t) - 1.0).abs() < 1e-6,
        "F{}",
        quarter.feed_rate
    );
}

/// The checks above are not vacuous: each kind of broken program (or a notch drawn 2 µm from
/// where it is cut) makes them fail.
#[test]
fn the_checks_catch_broken_programs() {
    let dir = tempfile::tempdir().unwrap();
    let design = &common_designs::shipped()[0];
    let good = std::fs::read_to_string(program(design, dir.path(), &[])).unwrap();
    let fails = |text: &str, shift_notch_mm: f64| -> bool {
        let file = dir.path().join("mutant.ngc");
        std::fs::write(&file, text).unwrap();
        let canon = parse(&run_rs274(&file));
        let mut e = expected(design, None);
        for p in &mut e.layout.notches[3].outline {
            use geo::MapCoordsInPlace;
            p.map_coords_in_place(|c| geo::Coord {
                x: c.x + shift_notch_mm,
                y: c.y,
            });
        }
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| check(&canon, &e, "mutant")))
            .is_err()
    };
    assert!(!fails(&good, 0.0), "the good program passes");
    assert!(fails(&good, 0.002), "a notch 2 µm off is caught");
    let first_feed_f = good
        .lines()
        .find(|l| l.starts_with("G1") && l.contains(" F"))
        .unwrap();
    let (head, f) = first_feed_f.rsplit_once(" F").unwrap();
    let slower = format!("{head} F{:.4}", f.parse::<f64>().unwrap() * 0.9);
    let mutants = [
        (
            "beam left on over a rapid",
            good.replacen("M5\no100 endrepeat", "o100 endrepeat", 1),
        ),
        ("a feed 10 % slow", good.replacen(first_feed_f, &slower, 1)),
        (
            "31 notch passes",
            good.replacen("repeat [32]", "repeat [31]", 1),
        ),
        ("wrong notch power", good.replacen("S2000", "S2100", 1)),
        (
            "wrong pulse width",
            good.replacen("M68 E1 Q215", "M68 E1 Q250", 1),
        ),
        (
            "no settle before the notches",
            good.lines()
                .filter(|l| !l.starts_with("G4 P"))
                .map(|l| format!("{l}\n"))
                .collect::<String>(),
        ),
        ("the settle before the notch set is commanded", {
            let g4 = good.lines().find(|l| l.starts_with("G4 P")).unwrap();
            let t = good.replacen(&format!("{g4}\n"), "", 1);
            t.replacen("S2000\n", &format!("{g4}\nS2000\n"), 1)
        }),
        ("a 1 s dwell where the profile says 5 s", {
            let g4 = good.lines().find(|l| l.starts_with("G4 P")).unwrap();
            good.replacen(g4, "G4 P1.000", 1)
        }),
        ("parting before the notches", {
            let at = good.find("\n(operation parting").unwrap();
            let parting = &good[at..good.find("G94 (feed").unwrap()];
            let notches_at = good.find("\n(operation notches").unwrap();
            let mut t = good.replace(parting, "\n");
            t.insert_str(notches_at, parting);
            t
        }),
    ];
    // An interpreter error is caught too.
    let broken = good.replacen(first_feed_f, &format!("{first_feed_f}.5"), 1);
    let file = dir.path().join("broken.ngc");
    std::fs::write(&file, broken).unwrap();
    assert!(
        std::panic::catch_unwind(|| run_rs274(&file)).is_err(),
        "an interpreter error is caught"
    );
    for (what, text) in mutants {
        assert_ne!(text, good, "{what}: the mutation applied");
        assert!(fails(&text, 0.0), "{what} is caught");
    }
}

/// Every `[settle]` mode of the profile goes through the interpreter: a dwell of the profile's
/// length, an optional stop, a stop, or nothing, each after the notch set is commanded and
/// before the first notch move, with the beam off (`canon::checks::check_settle`).
#[test]
fn settle_between_sets_in_every_mode() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("machines")).unwrap();
    let design = dir.path().join("joint-c.toml");
    std::fs::copy(&common_designs::shipped()[2], &design).unwrap();
    let reference = include_str!("../designs/machines/linuxcnc-reference.toml");
    let cases = [
        ("dwell-2-5", "mode = \"dwell\"\ndwell_s = 2.5", "G4 P2.500"),
        ("optional", "mode = \"optional-stop\"", "M1 "),
        ("stop", "mode = \"stop\"", "M0 "),
        ("none", "mode = \"none\"", ""),
    ];
    for (name, table, word) in cases {
        let at = reference
            .find("[settle]")
            .expect("the profile has a [settle] table");
        let text = format!("{}[settle]\n{table}\n", &reference[..at]);
        std::fs::write(dir.path().join(format!("machines/{name}.toml")), text).unwrap();
        let file = program(&design, dir.path(), &["--machine", name]);
        let program_text = std::fs::read_to_string(&file).unwrap();
        let waits = program_text
            .lines()
            .filter(|l| l.starts_with("G4") || l.starts_with("M0") || l.starts_with("M1"))
            .collect::<Vec<_>>();
        if word.is_empty() {
            assert!(waits.is_empty(), "{name}: {waits:?}");
        } else {
            assert_eq!(waits.len(), 1, "{name}: {waits:?}");
            assert!(waits[0].starts_with(word), "{name}: {waits:?}");
        }
        let canon = parse(&run_rs274(&file));
        check(&canon, &expected(&design, Some(name)), name);
        assert_eq!(canon.waits.len(), usize::from(!word.is_empty()), "{name}");
    }
    // Without a [settle] table the profile dwells the documented default.
    let at = reference.find("\n[settle]").unwrap();
    std::fs::write(dir.path().join("machines/bare.toml"), &reference[..at]).unwrap();
    let file = program(&design, dir.path(), &["--machine", "bare"]);
    let canon = parse(&run_rs274(&file));
    assert_eq!(
        canon.waits.iter().map(|w| w.kind).collect::<Vec<_>>(),
        [canon::WaitKind::Dwell(dlw::machine::DEFAULT_DWELL_S)]
    );
    check(&canon, &expected(&design, Some("bare")), "bare");
}

/// Helical moves (X and A at once) keep the surface speed through the interpreter too.
#[test]
fn helical_moves_keep_the_surface_speed() {
    let (design, e) = canon::checks::sheared_joint_a(None);
    let job = dlw::job::make_job(&design, &e.layout, &e.sets, &e.profile, "helix.ngc").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("helix.ngc");
    std::fs::write(&file, &job.program).unwrap();
    let canon = parse(&run_rs274(&file));
    let helical = canon
        .moves
        .iter()
        .filter(|m| m.feed && m.from[0] != m.to[0] && m.from[3] != m.to[3])
        .count();
    assert!(helical >= 10, "only {helical} helical moves");
    check(&canon, &e, "sheared joint A");
}
