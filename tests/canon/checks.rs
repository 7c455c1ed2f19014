//! The checks on a job's moves, whichever program they were read from (rs274's
//! canonical output, or a parsed AeroBasic program): order, beam, travel, power and pulse
//! settings, surface speed, passes, where each notch and the parting cut are cut, the written
//! lines.
//!
//! Tolerances: speeds within 0.5 % (the figure). Positions within 1 µm plus what the
//! printed rotary coordinate can hide, `r_o·a_print_deg` (rs274 prints `A` in degrees with 4
//! decimals: 1.1 nm per mm of radius); `X` is written with 4 decimals, so it prints exactly.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;

use dlw::design::DesignFile;
use dlw::layout::Layout;
use dlw::machine::{MachineLibrary, MachineProfile};
use dlw::process::{ProcessLibrary, ProcessSets};
use dlw::rules;

use super::{Canon, CanonMove, WaitKind};

pub struct Expected {
    /// The layout the program must cut.
    pub layout: Layout,
    /// The design's process sets.
    pub sets: ProcessSets,
    /// The machine profile.
    pub profile: MachineProfile,
    /// Outer radius (mm).
    pub r_o: f64,
    /// Half the resolution of the printed rotary coordinate (deg): 0.5e-4 for rs274's
    /// canonical output, 0.5e-6 for a program's own 6 decimals.
    pub a_print_deg: f64,
    /// Every feed must be in inverse-time mode (LinuxCNC).
    pub inverse_time: bool,
}

/// What a program for `design` (a joint design or a robot file) on `machine` must do.
pub fn expected(design: &Path, machine: Option<&str>) -> Expected {
    if dlw::robot::is_robot_file(design) {
        let robot = dlw::robot::CheckedRobot::load(design).unwrap();
        let sets = ProcessLibrary::beside(design)
            .resolve(&robot.robot.joints[0].design().file.process)
            .unwrap();
        return Expected {
            r_o: robot.robot.outer_radius_mm(),
            layout: robot.layout,
            sets,
            profile: MachineLibrary::beside(design).find(machine).unwrap(),
            a_print_deg: 0.5e-4,
            inverse_time: true,
        };
    }
    let checked = rules::check_file(DesignFile::read(design).unwrap()).unwrap();
    let sets = ProcessLibrary::beside(design)
        .resolve(&checked.design.file.process)
        .unwrap();
    let profile = MachineLibrary::beside(design).find(machine).unwrap();
    Expected {
        r_o: checked.design.file.outer_radius_mm,
        layout: checked.layout,
        sets,
        profile,
        a_print_deg: 0.5e-4,
        inverse_time: true,
    }
}

/// `s` interval of the notch's pieces, unwrapped across the seam, and its `x` interval; a
/// robot's notches are told apart by their joint.
fn notch_box(
    layout: &Layout,
    joint: Option<usize>,
    level: usize,
    side: usize,
) -> ([f64; 2], [f64; 2]) {
    let notch = layout
        .notches
        .iter()
        .find(|n| n.joint == joint && n.level == level && n.side == side)
        .unwrap_or_else(|| panic!("the layout has no notch {level} side {side} of {joint:?}"));
    let c = layout.circumference_mm;
    let mut xs = [f64::INFINITY, f64::NEG_INFINITY];
    let mut ss: Option<[f64; 2]> = None;
    for piece in &notch.outline {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in piece.exterior().coords() {
            xs = [xs[0].min(p.x), xs[1].max(p.x)];
            lo = lo.min(p.y);
            hi = hi.max(p.y);
        }
        ss = Some(match ss {
            None => [lo, hi],
            Some([a, b]) => {
                // Shift the piece by whole turns to sit next to what we have.
                let k = [-1.0, 0.0, 1.0]
                    .into_iter()
                    .min_by(|p, q| {
                        let gap = |k: f64| (lo + k * c - b).max(a - (hi + k * c)).max(0.0);
                        gap(*p).total_cmp(&gap(*q))
                    })
                    .unwrap();
                [a.min(lo + k * c), b.max(hi + k * c)]
            }
        });
    }
    (xs, ss.unwrap())
}

/// Least distance from `(x, s)` to any written line of the layout, round the cylinder.
fn distance_to_lines(layout: &Layout, x: f64, s: f64) -> f64 {
    let c = layout.circumference_mm;
    let mut best = f64::INFINITY;
    for t in layout
        .sensors
        .iter()
        .chain(&layout.leads)
        .chain(&layout.pads)
    {
        for piece in &t.pieces {
            for w in piece.0.windows(2) {
                for k in [-1.0, 0.0, 1.0] {
                    let (ax, ay, bx, by) = (w[0].x, w[0].y + k * c, w[1].x, w[1].y + k * c);
                    let (dx, dy) = (bx - ax, by - ay);
                    let sw = s - c * ((s - (ay + by) / 2.0) / c).round();
                    let len2 = dx * dx + dy * dy;
                    let t = if len2 > 0.0 {
                        (((x - ax) * dx + (sw - ay) * dy) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    best = best.min((ax + t * dx - x).hypot(ay + t * dy - sw));
                }
            }
        }
    }
    best
}

/// The settle the profile asks for: one wait after the laser is set for an operation whose
/// laser parameters differ from the previous one's, before any move of that operation, with the
/// beam off and the new set's power and pulse settings already in force; no other wait.
pub fn check_settle(canon: &Canon, e: &Expected, what: &str) {
    use dlw::machine::SettleMode;
    let sets = [&e.sets.sensor, &e.sets.notches, &e.sets.parting];
    let names = ["sensor", "notches", "parting"];
    let mut want = Vec::new();
    for i in 1..3 {
        if e.profile.settle.needed(Some(sets[i - 1]), sets[i]) {
            want.push(i);
        }
    }
    assert_eq!(
        canon.waits.len(),
        want.len(),
        "{what}: waits {:?}, expected one before each of {:?}",
        canon.waits,
        want.iter().map(|i| names[*i]).collect::<Vec<_>>()
    );
    for (w, &i) in canon.waits.iter().zip(&want) {
        let set = sets[i];
        assert_eq!(w.operation, names[i], "{what}: wait in the wrong operation");
        assert!(!w.spindle_on, "{what}: wait with the beam on: {w:?}");
        assert_eq!(
            (w.spindle_speed, w.aux),
            (set.power_mw, [set.pulse_frequency_khz, set.pulse_width_fs]),
            "{what}: the wait must come after the {} set is commanded",
            names[i]
        );
        let first = canon
            .moves
            .iter()
            .position(|m| m.operation == names[i])
            .unwrap_or(canon.moves.len());
        assert!(
            w.before_move <= first,
            "{what}: the wait comes after the {} operation's first move",
            names[i]
        );
        let s = &e.profile.settle;
        let expected = match s.mode {
            SettleMode::Dwell => WaitKind::Dwell(s.dwell_s),
            SettleMode::OptionalStop => WaitKind::OptionalStop,
            SettleMode::Stop => WaitKind::Stop,
            SettleMode::None => unreachable!("no wait is wanted"),
        };
        match (w.kind, expected) {
            (WaitKind::Dwell(got), WaitKind::Dwell(want)) => assert!(
                (got - want).abs() < 1e-3,
                "{what}: dwell {got} s, profile says {want} s"
            ),
            (got, want) => assert_eq!(got, want, "{what}: kind of wait"),
        }
    }
}

/// Every check of the issue, on one program's canonical output.
pub fn check(canon: &Canon, e: &Expected, what: &str) {
    check_settle(canon, e, what);
    let r_o = e.r_o;
    let kerf = e.layout.kerf_mm;
    let c = e.layout.circumference_mm;
    let s_of = |a_deg: f64| a_deg.to_radians() * r_o;
    let tol_x = 1e-3 + 0.5e-4;
    let tol_s = 1e-3 + r_o * e.a_print_deg.to_radians();

    // Order: sensor → notches → parting, and every move belongs to one of them in that order.
    assert_eq!(
        canon.operations,
        ["sensor", "notches", "parting"],
        "{what}: operation order"
    );
    let rank = |op: &str| {
        ["sensor", "notches", "parting"]
            .iter()
            .position(|o| *o == op)
    };
    let mut last = 0;
    for m in canon.moves.iter().filter(|m| m.feed) {
        let r = rank(&m.operation)
            .unwrap_or_else(|| panic!("{what}: feed outside any operation: {m:?}"));
        assert!(
            r >= last,
            "{what}: {} move after a later operation",
            m.operation
        );
        last = r;
    }

    // Beam: off on every rapid, on for every feed; inverse time on every feed.
    for m in &canon.moves {
        if m.feed {
            assert!(m.spindle_on, "{what}: feed with the beam off: {m:?}");
            assert!(
                !e.inverse_time || m.inverse_time,
                "{what}: feed not in inverse time: {m:?}"
            );
        } else {
            assert!(!m.spindle_on, "{what}: rapid with the beam on: {m:?}");
        }
    }

    // Travel.
    let lim = &e.profile.limits;
    for m in &canon.moves {
        for x in [m.from[0], m.to[0]] {
            assert!(
                x >= lim.x_min_mm && x <= lim.x_max_mm,
                "{what}: X{x} outside travel"
            );
        }
    }

    // Power, pulse settings and surface speed per operation.
    let set_of = |op: &str| match op {
        "sensor" => &e.sets.sensor,
        "notches" => &e.sets.notches,
        _ => &e.sets.parting,
    };
    let mut worst: f64 = 0.0;
    for m in canon.moves.iter().filter(|m| m.feed) {
        let set = set_of(&m.operation);
        assert_eq!(
            m.spindle_speed, set.power_mw,
            "{what}: power in {}",
            m.operation
        );
        assert_eq!(
            m.aux,
            [set.pulse_frequency_khz, set.pulse_width_fs],
            "{what}: pulse settings in {}",
            m.operation
        );
        assert!(set.power_mw <= lim.max_power_mw);
        let v = m.surface_speed_mm_s(r_o);
        let err = (v / set.scan_speed_mm_s - 1.0).abs();
        worst = worst.max(err);
        assert!(
            err <= 0.005,
            "{what}: {} move {:?} -> {:?} at {v} mm/s, set {} mm/s",
            m.operation,
            m.from,
            m.to,
            set.scan_speed_mm_s
        );
    }
    // Feeds are computed from the coordinates as written, so the error is only F's rounding.
    assert!(worst < 1e-4, "{what}: worst speed error {worst}");

    // Segments (one pass each) per path.
    let mut segments: BTreeMap<(String, String), BTreeMap<usize, Vec<&CanonMove>>> =
        BTreeMap::new();
    for m in canon.moves.iter().filter(|m| m.feed) {
        segments
            .entry((m.operation.clone(), m.path.clone()))
            .or_default()
            .entry(m.segment.unwrap())
            .or_default()
            .push(m);
    }

    // Sensor: one pass per written line, every point on the design's lines.
    for ((op, path), segs) in segments.iter().filter(|((op, _), _)| op == "sensor") {
        assert_eq!(
            segs.len() as u32,
            e.sets.sensor.repetitions,
            "{what}: {op} {path} passes"
        );
        for m in segs.values().flatten() {
            for p in [m.from, m.to] {
                let d = distance_to_lines(&e.layout, p[0], s_of(p[3]));
                assert!(
                    d <= tol_s.max(tol_x),
                    "{what}: written point {p:?} is {d} mm off the drawn lines"
                );
            }
        }
    }

    // Notches: 32 passes each; the cut outline widened by half the kerf is the drawn notch.
    let notch_paths: Vec<_> = segments
        .iter()
        .filter(|((op, _), _)| op == "notches")
        .collect();
    assert_eq!(
        notch_paths.len(),
        e.layout.notches.len(),
        "{what}: one path per notch"
    );
    for ((_, path), segs) in notch_paths {
        assert_eq!(
            segs.len() as u32,
            e.sets.notches.repetitions,
            "{what}: {path} passes"
        );
        // "notch 3 [side 0]", or a robot's "joint 2 notch 3 [side 0]"
        let nums: Vec<usize> = path
            .split(|ch: char| !ch.is_ascii_digit())
            .filter(|s| !s.is_empty())
            .map(|s| s.parse().unwrap())
            .collect();
        let (joint, level, side) = match nums.as_slice() {
            [j, l, s] => (Some(j - 1), l - 1, *s),
            _ => (None, nums[0] - 1, nums[1]),
        };
        let (xs, ss) = notch_box(&e.layout, joint, level, side);
        for seg in segs.values() {
            let lead = seg[0];
            let cut = &seg[1..];
            let mut bx = [f64::INFINITY, f64::NEG_INFINITY];
            let mut bs = [f64::INFINITY, f64::NEG_INFINITY];
            for m in cut {
                for p in [m.from, m.to] {
                    bx = [bx[0].min(p[0]), bx[1].max(p[0])];
                    bs = [bs[0].min(s_of(p[3])), bs[1].max(s_of(p[3]))];
                }
            }
            let shift = c * ((ss[0] - (bs[0] - kerf / 2.0)) / c).round();
            let got = [
                bx[0] - kerf / 2.0,
                bx[1] + kerf / 2.0,
                bs[0] - kerf / 2.0 + shift,
                bs[1] + kerf / 2.0 + shift,
            ];
            let want = [xs[0], xs[1], ss[0], ss[1]];
            for (i, (g, w)) in got.iter().zip(want).enumerate() {
                let tol = if i < 2 { tol_x } else { tol_s };
                assert!(
                    (g - w).abs() <= tol,
                    "{what}: {path} cut {got:?} vs drawn {want:?} (index {i})"
                );
            }
            // The lead-in starts inside the cut outline: in the scrap.
            let (lx, ls) = (lead.from[0], s_of(lead.from[3]));
            assert!(
                lx > bx[0] && lx < bx[1] && ls > bs[0] && ls < bs[1],
                "{what}: {path} lead-in starts outside the notch"
            );
            // The pass closes on itself.
            let (first, last) = (cut[0].from, cut[cut.len() - 1].to);
            assert!(
                (first[0] - last[0]).abs() < 1e-9 && (first[3] - last[3]).abs() < 1e-9,
                "{what}: {path} does not close"
            );
        }
    }

    // Parting: 32 passes, all the way round, half a kerf into the stock.
    let parting: Vec<_> = segments
        .iter()
        .filter(|((op, _), _)| op == "parting")
        .collect();
    assert_eq!(parting.len(), 1, "{what}: one parting path");
    let x_cut = e.layout.length_mm + kerf / 2.0;
    for segs in parting.iter().map(|(_, s)| s) {
        assert_eq!(
            segs.len() as u32,
            e.sets.parting.repetitions,
            "{what}: parting passes"
        );
        for seg in segs.values() {
            assert!(
                seg[0].from[0] > x_cut,
                "{what}: parting lead-in not on the stock side"
            );
            let turned: f64 = seg[1..].iter().map(|m| (m.to[3] - m.from[3]).abs()).sum();
            assert!(
                (turned - 360.0).abs() < 2e-4,
                "{what}: parting turns {turned}°"
            );
            for m in &seg[1..] {
                assert!(
                    (m.to[0] - x_cut).abs() <= 0.5e-4 + 1e-12,
                    "{what}: parting at X{}",
                    m.to[0]
                );
                assert!(
                    (m.to[3] - m.from[3]).abs() <= 90.0 + 1e-9,
                    "{what}: a rotation over 90°"
                );
            }
        }
    }
}

/// Joint A's layout with every written line sheared, `s += 0.02·x`, so that every written move
/// turns and travels at once (a helix): the case where RS-274's plain `F` would be wrong.
/// Notches are left as drawn. Returns the design and the sheared layout's expectation.
pub fn sheared_joint_a(machine: Option<&str>) -> (dlw::design::Design, Expected) {
    use geo::MapCoordsInPlace;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let mut e = expected(&path, machine);
    for t in e
        .layout
        .sensors
        .iter_mut()
        .chain(&mut e.layout.leads)
        .chain(&mut e.layout.pads)
    {
        for piece in &mut t.pieces {
            piece.map_coords_in_place(|c| geo::Coord {
                x: c.x,
                y: c.y + 0.02 * c.x,
            });
        }
    }
    let design = dlw::design::Design::load(&path).unwrap();
    (design, e)
}
