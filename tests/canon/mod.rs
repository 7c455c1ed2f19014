//! Running LinuxCNC's standalone interpreter (`rs274 -g FILE`) and reading its canonical output
//! (`mod canon;` in an integration test).
//!
//! `rs274 -g` prints one canonical call per line, e.g.
//! `   40 N..... STRAIGHT_TRAVERSE(12.4000, 0.0000, 1.2400, -27.7238, 0.0000, 0.0000)`, with the
//! `o… repeat` loops already expanded. Quirks handled here: after `G93` it prints the comment
//! `interpreter: feed mode set to inverse time` but then `SET_FEED_MODE(0, 0)` anyway, so the
//! feed mode is taken from that comment; and in inverse-time mode it does not print the
//! program's `F` but the equivalent rate per minute it hands to motion, measured the RS-274
//! way: over the XYZ length when the move has any, else over the rotary length (degrees). So a
//! move's time is `length/F` minutes with that length ([`CanonMove::minutes`]) — the
//! interpreter's own reading of the inverse-time word. Coordinates are printed with 4 decimals.
#![allow(dead_code)]

pub mod checks;

use std::path::Path;
use std::process::Command;

/// Axis values as rs274 prints them: x, y, z, a, b, c.
pub type Pose = [f64; 6];

/// A motion the interpreter commanded.
#[derive(Debug, Clone, PartialEq)]
pub struct CanonMove {
    /// `STRAIGHT_FEED` (true) or `STRAIGHT_TRAVERSE` (false).
    pub feed: bool,
    /// Where it started.
    pub from: Pose,
    /// Where it ended.
    pub to: Pose,
    /// The feed rate in force (`SET_FEED_RATE`).
    pub feed_rate: f64,
    /// Inverse-time mode in force.
    pub inverse_time: bool,
    /// Spindle (the beam gate) on.
    pub spindle_on: bool,
    /// Spindle speed (the power, mW).
    pub spindle_speed: f64,
    /// Analog outputs 0 and 1 (pulse frequency kHz, pulse width fs).
    pub aux: [f64; 2],
    /// The last `operation NAME:` comment before the move.
    pub operation: String,
    /// The last path comment (`notch 3 [side 0]: …`) before the move: the text before `:`.
    pub path: String,
    /// Index of the beam-on segment (spindle start … stop) the move belongs to, if any.
    pub segment: Option<usize>,
}

/// How a program waits (`DWELL`, `OPTIONAL_PROGRAM_STOP`, `PROGRAM_STOP`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WaitKind {
    /// A dwell of so many seconds.
    Dwell(f64),
    /// `M1`.
    OptionalStop,
    /// `M0`.
    Stop,
}

/// A wait, with the machine's state when it happens.
#[derive(Debug, Clone, PartialEq)]
pub struct Wait {
    /// What kind.
    pub kind: WaitKind,
    /// Spindle (the beam gate) on during the wait.
    pub spindle_on: bool,
    /// Spindle speed (the power, mW) in force.
    pub spindle_speed: f64,
    /// Analog outputs 0 and 1 in force (pulse frequency kHz, pulse width fs).
    pub aux: [f64; 2],
    /// The operation it happens in.
    pub operation: String,
    /// How many moves came before it.
    pub before_move: usize,
}

/// The interpreter's output, read.
#[derive(Debug, Clone, Default)]
pub struct Canon {
    /// Every dwell and stop, in order.
    pub waits: Vec<Wait>,
    /// Every motion, in order.
    pub moves: Vec<CanonMove>,
    /// `operation` comments in order.
    pub operations: Vec<String>,
    /// Every comment, in order.
    pub comments: Vec<String>,
    /// Spindle starts seen.
    pub spindle_starts: usize,
}

/// Runs `rs274 -g FILE`; panics with a clear message if rs274 is missing, exits non-zero or
/// reports an error.
///
/// Each run gets its own `HOME`: rs274 truncates and maps `$HOME/.tool.mmap` shared, so two
/// runs at once (parallel tests, or another user's) crash each other with SIGBUS.
pub fn run_rs274(file: &Path) -> String {
    let home = tempfile::tempdir().expect("a temporary HOME for rs274");
    let out = Command::new("rs274")
        .arg("-g")
        .arg(file)
        .env("HOME", home.path())
        .output()
        .unwrap_or_else(|e| {
            panic!(
            "cannot run rs274 ({e}): install LinuxCNC's standalone interpreter (Debian package \
             linuxcnc-uspace; scripts/test.sh installs it)"
        )
        });
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let noise: Vec<&str> = stderr
        .lines()
        .filter(|l| !l.trim().is_empty() && l.trim() != "executing")
        .collect();
    assert!(
        out.status.success() && noise.is_empty(),
        "rs274 -g {} failed ({}):\n{}\n--- last output lines ---\n{}",
        file.display(),
        out.status,
        noise.join("\n"),
        stdout.lines().rev().take(8).collect::<Vec<_>>().join("\n")
    );
    stdout
}

/// Reads canonical output.
pub fn parse(text: &str) -> Canon {
    let mut c = Canon::default();
    let mut pos: Pose = [0.0; 6];
    let mut feed_rate = 0.0;
    let mut inverse_time = false;
    let mut spindle_on = false;
    let mut spindle_speed = 0.0;
    let mut aux = [f64::NAN; 2];
    let mut operation = String::new();
    let mut path = String::new();
    let mut segment: Option<usize> = None;
    for line in text.lines() {
        let Some(start) = line.find("N..... ") else {
            continue;
        };
        let call = &line[start + 7..];
        let (name, args) = match call.find('(') {
            Some(i) => (
                &call[..i],
                call[i + 1..].strip_suffix(')').unwrap_or(&call[i + 1..]),
            ),
            None => (call, ""),
        };
        let nums = || -> Vec<f64> {
            args.split([',', ' '])
                .filter(|s| !s.is_empty())
                .filter_map(|s| s.parse().ok())
                .collect()
        };
        match name {
            "COMMENT" => {
                let text = args.trim_matches('"').to_string();
                if text == "interpreter: feed mode set to inverse time" {
                    inverse_time = true;
                } else if text.starts_with("interpreter: feed mode set to") {
                    inverse_time = false;
                }
                // `operation NAME: …` (one word before the colon; the header's table heading
                // also starts with "operation").
                let op = text
                    .strip_prefix("operation ")
                    .and_then(|rest| rest.split_once(':'))
                    .map(|(name, _)| name)
                    .filter(|name| !name.is_empty() && !name.contains(' '));
                if let Some(name) = op {
                    operation = name.to_string();
                    c.operations.push(operation.clone());
                    path.clear();
                } else if !text.starts_with("interpreter:") {
                    if let Some((label, _)) = text.split_once(':') {
                        path = label.to_string();
                    }
                }
                c.comments.push(text);
            }
            "SET_FEED_RATE" => feed_rate = nums()[0],
            "SET_SPINDLE_SPEED" => spindle_speed = nums()[1],
            "START_SPINDLE_CLOCKWISE" => {
                spindle_on = true;
                segment = Some(c.spindle_starts);
                c.spindle_starts += 1;
            }
            "STOP_SPINDLE_TURNING" => {
                spindle_on = false;
                segment = None;
            }
            "SET_AUX_OUTPUT_VALUE" => {
                let v = nums();
                aux[v[0] as usize] = v[1];
            }
            "STRAIGHT_FEED" | "STRAIGHT_TRAVERSE" => {
                let v = nums();
                let to: Pose = [v[0], v[1], v[2], v[3], v[4], v[5]];
                c.moves.push(CanonMove {
                    feed: name == "STRAIGHT_FEED",
                    from: pos,
                    to,
                    feed_rate,
                    inverse_time,
                    spindle_on,
                    spindle_speed,
                    aux,
                    operation: operation.clone(),
                    path: path.clone(),
                    segment,
                });
                pos = to;
            }
            "DWELL" | "OPTIONAL_PROGRAM_STOP" | "PROGRAM_STOP" => {
                let kind = match name {
                    "DWELL" => WaitKind::Dwell(nums()[0]),
                    "OPTIONAL_PROGRAM_STOP" => WaitKind::OptionalStop,
                    _ => WaitKind::Stop,
                };
                c.waits.push(Wait {
                    kind,
                    spindle_on,
                    spindle_speed,
                    aux,
                    operation: operation.clone(),
                    before_move: c.moves.len(),
                });
            }
            "ARC_FEED" => panic!("unexpected arc in a dlw program: {line}"),
            _ => {}
        }
    }
    c
}

impl CanonMove {
    /// Surface distance of the move on a tube of radius `r_o`: `sqrt(Δx² + (r_o·ΔA)²)`, A in degrees.
    pub fn surface_mm(&self, r_o: f64) -> f64 {
        let dx = self.to[0] - self.from[0];
        let da = (self.to[3] - self.from[3]).to_radians();
        dx.hypot(r_o * da)
    }

    /// The move's time (min) as the interpreter commands it: its RS-274 length (XYZ if any,
    /// else ABC) over the printed rate.
    pub fn minutes(&self) -> f64 {
        let d = |i: usize| self.to[i] - self.from[i];
        let linear = (d(0).powi(2) + d(1).powi(2) + d(2).powi(2)).sqrt();
        let rotary = (d(3).powi(2) + d(4).powi(2) + d(5).powi(2)).sqrt();
        let length = if linear > 0.0 { linear } else { rotary };
        length / self.feed_rate
    }

    /// Surface speed (mm/s): surface distance over the commanded time.
    pub fn surface_speed_mm_s(&self, r_o: f64) -> f64 {
        self.surface_mm(r_o) / (60.0 * self.minutes())
    }
}

#[test]
fn parses_a_small_canonical_output() {
    let text = r#"
    7 N..... COMMENT("operation sensor: set sensor")
    8 N..... COMMENT("interpreter: feed mode set to inverse time")
    9 N..... SET_FEED_MODE(0, 0)
   10 N..... SET_SPINDLE_SPEED(0, 160.0000)
   11 N..... SET_AUX_OUTPUT_VALUE(0,200.000000)
   12 N..... COMMENT("sensor 1 line [trace]: 1 pass[es]")
   13 N..... STRAIGHT_TRAVERSE(1.0000, 0.0000, 1.2400, 0.0000, 0.0000, 0.0000)
   14 N..... START_SPINDLE_CLOCKWISE(0)
   15 N..... SET_FEED_RATE(60.0000)
   16 N..... STRAIGHT_FEED(2.0000, 0.0000, 1.2400, 0.0000, 0.0000, 0.0000)
   17 N..... SET_FEED_RATE(2772.3763)
   18 N..... STRAIGHT_FEED(2.0000, 0.0000, 1.2400, 4.6206, 0.0000, 0.0000)
   19 N..... STOP_SPINDLE_TURNING(0)
"#;
    let c = parse(text);
    assert_eq!(c.moves.len(), 3);
    // 4.6206° on r_o = 1.24 mm is 0.1 mm of surface, in 4.6206/2772.3763 min = 0.1 s.
    assert!((c.moves[2].surface_speed_mm_s(1.24) - 1.0).abs() < 1e-4);
    let f = &c.moves[1];
    assert!(f.feed && f.spindle_on && f.inverse_time);
    assert_eq!(
        (f.spindle_speed, f.aux[0], f.segment),
        (160.0, 200.0, Some(0))
    );
    assert_eq!(
        (f.operation.as_str(), f.path.as_str()),
        ("sensor", "sensor 1 line [trace]")
    );
    assert!((f.surface_speed_mm_s(1.24) - 1.0).abs() < 1e-12);
    assert!(!c.moves[0].spindle_on && !c.moves[0].feed);
}
