//! Programs from the AeroBasic post (the `aerotech-aerobasic` profile).
//!
//! No AeroBasic interpreter or controller is available here, so this parses the program's own
//! syntax — `G0`/`G1` with `X A Z F` words, `G71 G76 G90`, the profile's `$DO[0].X` beam gate
//! and `$GLOBAL[n]` laser settings, the settle (`DWELL s`, `M1`, `M0`), `//` comments — refusing any line it does not know, and
//! runs the same physical checks as the LinuxCNC tests on the parsed moves (`canon/checks.rs`).
//! Feeds follow RS-274 semantics in units per second (`G76`): `F` is the X speed on a move with
//! X motion, the rotary speed on a pure rotation. Coordinates are read at the program's full
//! precision (A with 6 decimals).

use crate::canon;
use crate::common;
use common::designs as common_designs;
use common::dlw;

use std::path::Path;

use canon::checks::{check, expected};
use canon::{Canon, CanonMove, Pose};

/// Reads an AeroBasic program from the shipped Aerotech profile into moves.
fn parse_aerobasic(text: &str) -> Canon {
    let mut c = Canon::default();
    let mut pos: Pose = [0.0; 6];
    let mut beam = false;
    let mut globals = [f64::NAN; 3];
    let (mut operation, mut path) = (String::new(), String::new());
    let mut segment = None;
    let (mut metric, mut per_second, mut absolute, mut ended) = (false, false, false, false);
    for (n, raw) in text.lines().enumerate() {
        let line = raw.trim();
        assert!(!ended, "line {}: text after END PROGRAM: {raw}", n + 1);
        if line.is_empty() {
            continue;
        }
        if let Some(comment) = line.strip_prefix("// ") {
            let op = comment
                .strip_prefix("operation ")
                .and_then(|r| r.split_once(':'))
                .map(|(name, _)| name)
                .filter(|name| !name.contains(' '));
            if let Some(name) = op {
                operation = name.to_string();
                c.operations.push(operation.clone());
            } else if let Some((label, _)) = comment.split_once(':') {
                path = label.to_string();
            }
            c.comments.push(comment.to_string());
            continue;
        }
        let code = line.split("//").next().unwrap().trim();
        match code {
            "G71" => metric = true,
            "G76" => per_second = true,
            "G90" => absolute = true,
            "ENABLE X A Z" => {}
            "END PROGRAM" => ended = true,
            "$DO[0].X = 1" => {
                beam = true;
                segment = Some(c.spindle_starts);
                c.spindle_starts += 1;
            }
            "$DO[0].X = 0" => {
                beam = false;
                segment = None;
            }
            "M0" | "M1" => c.waits.push(canon::Wait {
                kind: if code == "M0" {
                    canon::WaitKind::Stop
                } else {
                    canon::WaitKind::OptionalStop
                },
                spindle_on: beam,
                spindle_speed: globals[0],
                aux: [globals[1], globals[2]],
                operation: operation.clone(),
                before_move: c.moves.len(),
            }),
            _ if code.starts_with("DWELL ") => c.waits.push(canon::Wait {
                kind: canon::WaitKind::Dwell(
                    code["DWELL ".len()..]
                        .parse()
                        .unwrap_or_else(|_| panic!("line {}: bad dwell time: {raw}", n + 1)),
                ),
                spindle_on: beam,
                spindle_speed: globals[0],
                aux: [globals[1], globals[2]],
                operation: operation.clone(),
                before_move: c.moves.len(),
            }),
            _ if code.starts_with("$GLOBAL[") => {
                let (k, v) = code.split_once("] = ").unwrap();
                globals[k["$GLOBAL[".len()..].parse::<usize>().unwrap()] = v.parse().unwrap();
            }
            _ if code.starts_with("G0 ") || code.starts_with("G1 ") => {
                assert!(
                    metric && per_second && absolute,
                    "line {}: motion before G71 G76 G90",
                    n + 1
                );
                let feed = code.starts_with("G1");
                let mut to = pos;
                let mut f = None;
                for word in code[3..].split_whitespace() {
                    let (letter, value) = word.split_at(1);
                    let v: f64 = value
                        .parse()
                        .unwrap_or_else(|_| panic!("line {}: bad number in {word}", n + 1));
                    match letter {
                        "X" => to[0] = v,
                        "Z" => to[2] = v,
                        "A" => to[3] = v,
                        "F" => f = Some(v),
                        _ => panic!("line {}: unknown word {word}", n + 1),
                    }
                }
                assert_eq!(
                    feed,
                    f.is_some(),
                    "line {}: G1 needs F, G0 has none: {raw}",
                    n + 1
                );
                c.moves.push(CanonMove {
                    feed,
                    from: pos,
                    to,
                    // Units per second, RS-274 semantics → per minute, as rs274 reports rates.
                    feed_rate: f.unwrap_or(0.0) * 60.0,
                    inverse_time: false,
                    spindle_on: beam,
                    spindle_speed: globals[0],
                    aux: [globals[1], globals[2]],
                    operation: operation.clone(),
                    path: path.clone(),
                    segment,
                });
                pos = to;
            }
            _ => panic!(
                "line {}: not an AeroBasic line this post writes: {raw}",
                n + 1
            ),
        }
    }
    assert!(ended, "the program does not end with END PROGRAM");
    c
}

/// Writes the AeroBasic program for `design` through the binary and returns its text.
fn aerobasic_program(design: &Path, what: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("job.pgm");
    let o = dlw(&[
        "program".as_ref(),
        design.as_os_str(),
        "--machine".as_ref(),
        "aerotech-aerobasic".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(
        o.status.success(),
        "{what}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    std::fs::read_to_string(&out).unwrap()
}

fn run(design: &Path, what: &str) {
    let moves = parse_aerobasic(&aerobasic_program(design, what));
    let mut e = expected(design, Some("aerotech-aerobasic"));
    e.a_print_deg = 0.5e-6;
    e.inverse_time = false;
    check(&moves, &e, what);
}

#[test]
fn shipped_designs_pass_the_checks() {
    for design in common_designs::shipped() {
        run(&design, &design.file_name().unwrap().to_string_lossy());
    }
}

/// A robot's one program (docs/robots.md) in AeroBasic: the same checks, notches named by
/// joint.
#[test]
fn shipped_robots_pass_the_checks() {
    for robot in common_designs::robots() {
        run(&robot, &robot.file_name().unwrap().to_string_lossy());
    }
}

#[test]
fn designs_outside_the_paper_pass_the_checks() {
    let dir = tempfile::tempdir().unwrap();
    for (i, text) in [common_designs::BSN_WIDE, common_designs::UAN_THREE]
        .iter()
        .enumerate()
    {
        let path = dir.path().join(format!("outside-{i}.toml"));
        std::fs::write(&path, text).unwrap();
        run(&path, &format!("outside-{i}"));
    }
}

/// The settle in AeroBasic: `DWELL` by default, `M1` for an optional stop, each after the
/// notch set's `$GLOBAL` values and before the first notch move.
#[test]
fn settle_between_sets() {
    let design = &common_designs::shipped()[2];
    let text = aerobasic_program(design, "settle");
    assert_eq!(
        text.lines()
            .filter(|l| l.starts_with("DWELL 5.000"))
            .count(),
        1
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("machines")).unwrap();
    let copy = dir.path().join("joint-c.toml");
    std::fs::copy(design, &copy).unwrap();
    let profile = include_str!("../designs/machines/aerotech-aerobasic.toml")
        .replace("mode = \"dwell\"", "mode = \"optional-stop\"");
    std::fs::write(dir.path().join("machines/m1.toml"), profile).unwrap();
    let out = dir.path().join("job.pgm");
    let o = dlw(&[
        "program".as_ref(),
        copy.as_os_str(),
        "--machine".as_ref(),
        "m1".as_ref(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&out).unwrap();
    let canon = parse_aerobasic(&text);
    assert_eq!(
        canon.waits.iter().map(|w| w.kind).collect::<Vec<_>>(),
        [canon::WaitKind::OptionalStop]
    );
    let mut e = expected(&copy, Some("m1"));
    e.a_print_deg = 0.5e-6;
    e.inverse_time = false;
    check(&canon, &e, "optional stop");
}

#[test]
fn the_parser_and_checks_catch_broken_programs() {
    let design = &common_designs::shipped()[2];
    let good = aerobasic_program(design, "broken-program baseline");
    let mut e = expected(design, Some("aerotech-aerobasic"));
    e.a_print_deg = 0.5e-6;
    e.inverse_time = false;
    let fails = |text: &str| {
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            check(&parse_aerobasic(text), &e, "mutant")
        }))
        .is_err()
    };
    assert!(!fails(&good));
    let g1 = good.lines().find(|l| l.starts_with("G1 X")).unwrap();
    let (head, f) = g1.rsplit_once(" F").unwrap();
    let slow = format!("{head} F{:.6}", f.parse::<f64>().unwrap() * 0.99);
    for (what, text) in [
        ("1 % slow", good.replacen(g1, &slow, 1)),
        ("beam on over a rapid", {
            // The second gate closing before a rapid (the first is the preamble's).
            let at = good.match_indices("$DO[0].X = 0\nG0").nth(1).unwrap().0;
            format!("{}{}", &good[..at], &good[at + "$DO[0].X = 0\n".len()..])
        }),
        ("unknown line", good.replacen("G90", "G91", 1)),
        ("a G1 without F", good.replacen(g1, head, 1)),
        (
            "31 passes",
            good.replacen("$DO[0].X = 1", "$DO[0].X = 0", 1),
        ),
    ] {
        assert_ne!(text, good, "{what}: the mutation applied");
        assert!(fails(&text), "{what} is caught");
    }
}

/// Helical moves: `F` is the X component of the speed, and the surface speed still holds.
#[test]
fn helical_moves_keep_the_surface_speed() {
    let (design, mut e) = canon::checks::sheared_joint_a(Some("aerotech-aerobasic"));
    let job = dlw::job::make_job(&design, &e.layout, &e.sets, &e.profile, "helix.pgm").unwrap();
    let moves = parse_aerobasic(&job.program);
    let helical = moves
        .moves
        .iter()
        .filter(|m| m.feed && m.from[0] != m.to[0] && m.from[3] != m.to[3])
        .count();
    assert!(helical >= 10, "only {helical} helical moves");
    e.a_print_deg = 0.5e-6;
    e.inverse_time = false;
    check(&moves, &e, "sheared joint A, AeroBasic");
}
