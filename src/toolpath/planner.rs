//! Building the plan from a layout: the sensor's lines, the kerf-offset notches with lead-ins
//! in the scrap, and the parting cut, each operation ordered to keep travel short.

use std::f64::consts::TAU;

use geo::Coord;

use super::offset::{inside, offset_inward, ring_distance};
use super::order::{given_order, nearest_neighbour};
use super::plan::{Feature, Operation, OperationKind, Path, Plan, Point, TraceKind, Travel};
use super::seam::{chain_lines, join_outline};
use super::{check, ToolpathError};
use crate::design::Design;
use crate::layout::Layout;
use crate::machine::MachineProfile;
use crate::process::ProcessSets;

/// The planner's tolerances and lengths; every one is explicit.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanOptions {
    /// Length of the lead-in in the scrap before each cut (mm). Shortened (halved up to three
    /// times) where a notch is too small for it.
    pub lead_in_mm: f64,
    /// Line ends closer than this are the same point, when joining the layout's pieces (mm).
    pub join_tolerance_mm: f64,
    /// Most a flattened arc may deviate from the true offset at a reflex notch corner (mm).
    pub arc_tolerance_mm: f64,
    /// Longest rotation of one move (rad): longer ones are split, so that no controller can
    /// take a move of half a turn or more the other way round.
    pub max_rotation_per_move_rad: f64,
}

impl Default for PlanOptions {
    fn default() -> Self {
        Self {
            lead_in_mm: 0.1,
            join_tolerance_mm: 1e-4,
            arc_tolerance_mm: 1e-4,
            max_rotation_per_move_rad: TAU / 4.0,
        }
    }
}

/// What a plan is of, besides its layout: the name and checksum its program and sheet carry,
/// the numbers they print, and any lines the header adds. A joint's design gives them
/// ([`Part::of`]); a robot gives its own (`crate::build::robot_job`), so the planner need not know
/// which it plans.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// The name ([`Plan::design_name`]).
    pub name: String,
    /// The checksum ([`Plan::design_checksum`]).
    pub checksum: String,
    /// Inner radius `r_i` (mm).
    pub inner_radius_mm: f64,
    /// Bending length (mm) ([`Plan::bending_length_mm`]).
    pub bending_length_mm: f64,
    /// Lines the program header prints after the checksum ([`Plan::notes`]).
    pub notes: Vec<String>,
}

impl Part {
    /// A joint design's part.
    pub fn of(design: &Design) -> Self {
        Self {
            name: design.file.name.clone(),
            checksum: design.checksum.clone(),
            inner_radius_mm: design.file.inner_radius_mm,
            bending_length_mm: design.file.joint_length_mm,
            notes: Vec::new(),
        }
    }
}

/// Plans the whole job: sensor (set a) → notches (set b) → parting, then checks every safety
/// invariant against the machine profile.
///
/// # Errors
/// [`ToolpathError`] for a layout the planner cannot use (a notch that does not join across the
/// seam or is too narrow for the kerf, no parting line) and for any broken invariant: power
/// above the machine's maximum, a move outside travel, a speed the stage cannot reach, a cut
/// touching a written line.
pub fn plan(
    design: &Design,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    options: &PlanOptions,
) -> Result<Plan, ToolpathError> {
    let violations = crate::rules::check_wall(&design.file, sets);
    if !violations.is_empty() {
        return Err(crate::rules::RulesError {
            name: design.file.name.clone(),
            violations,
        }
        .into());
    }
    plan_part(&Part::of(design), layout, sets, profile, options)
}

/// [`plan`] for any part (the caller has checked the wall against the sets,
/// [`crate::rules::check_wall`]).
///
/// # Errors
/// As [`plan`].
pub fn plan_part(
    part: &Part,
    layout: &Layout,
    sets: &ProcessSets,
    profile: &MachineProfile,
    options: &PlanOptions,
) -> Result<Plan, ToolpathError> {
    let r_o = layout.outer_radius_mm;
    let c = layout.circumference_mm;
    if !(r_o.is_finite() && r_o > 0.0 && (c - TAU * r_o).abs() <= 1e-6 * c.max(1.0)) {
        return Err(ToolpathError::Layout(format!(
            "outer radius {r_o} mm and circumference {c} mm do not agree (2π·r_o = {} mm)",
            TAU * r_o
        )));
    }
    let to_point = |c: &Coord<f64>| Point::new(c.x, c.y / r_o);
    let home = Point::new(0.0, 0.0);
    let mut operations = Vec::new();
    let mut travel = Vec::new();

    // Sensor: every written line, pieces that meet joined into one continuous line.
    let written = written_ways(layout, options, &to_point);
    let reps = sets.sensor.repetitions;
    let (_, _, before) = given_order(&written, home, reps, r_o);
    let (paths, mut at, after) = nearest_neighbour(&written, home, reps, r_o);
    operations.push(Operation {
        kind: OperationKind::Sensor,
        process: sets.sensor.clone(),
        paths,
    });
    travel.push(Travel {
        layout_order_mm: before,
        planned_mm: after,
    });

    // Notches: outlines offset inward by half the kerf, entered from a lead-in in the scrap.
    let mut notch_ways = Vec::with_capacity(layout.notches.len());
    for notch in &layout.notches {
        let feature = Feature::Notch {
            joint: notch.joint,
            level: notch.level,
            side: notch.side,
        };
        let ring = join_outline(&notch.outline, c).map_err(|e| ToolpathError::Outline {
            feature: feature.to_string(),
            reason: e.to_string(),
        })?;
        let cut =
            offset_inward(&ring, layout.kerf_mm / 2.0, options.arc_tolerance_mm).map_err(|e| {
                ToolpathError::Outline {
                    feature: feature.to_string(),
                    reason: format!("kerf {} mm: {e}", layout.kerf_mm),
                }
            })?;
        notch_ways.push(contour_ways(&feature, &cut, options, &to_point)?);
    }
    let reps = sets.notches.repetitions;
    let (_, _, before) = given_order(&notch_ways, at, reps, r_o);
    let (paths, end, after) = nearest_neighbour(&notch_ways, at, reps, r_o);
    at = end;
    operations.push(Operation {
        kind: OperationKind::Notches,
        process: sets.notches.clone(),
        paths,
    });
    travel.push(Travel {
        layout_order_mm: before,
        planned_mm: after,
    });

    // Parting: all the way round at the parting line moved half a kerf into the stock, so the
    // joint keeps its length; started where the notches ended.
    let x_line = parting_x(layout, options)?;
    let parting = parting_path(x_line + layout.kerf_mm / 2.0, at.a_rad, options);
    let lead_to = parting.start();
    let d = super::order::rapid_distance_mm(at, lead_to, r_o);
    operations.push(Operation {
        kind: OperationKind::Parting,
        process: sets.parting.clone(),
        paths: vec![parting],
    });
    travel.push(Travel {
        layout_order_mm: d,
        planned_mm: d,
    });

    let plan = Plan {
        design_name: part.name.clone(),
        design_checksum: part.checksum.clone(),
        notes: part.notes.clone(),
        outer_radius_mm: r_o,
        inner_radius_mm: part.inner_radius_mm,
        kerf_mm: layout.kerf_mm,
        trace_width_mm: layout.trace_width_mm,
        joint_length_mm: x_line,
        bending_length_mm: part.bending_length_mm,
        surface_z_mm: profile.surface_z_mm(r_o),
        home,
        operations,
        travel,
        provenance: None,
    };
    check::check_plan(&plan, layout, profile)?;
    Ok(plan)
}

/// The written lines, each with its two ways in (either end first).
fn written_ways(
    layout: &Layout,
    options: &PlanOptions,
    to_point: &dyn Fn(&Coord<f64>) -> Point,
) -> Vec<Vec<Path>> {
    let groups = [
        (TraceKind::Sensor, &layout.sensors),
        (TraceKind::Lead, &layout.leads),
        (TraceKind::Pad, &layout.pads),
    ];
    let sensors = groups
        .iter()
        .flat_map(|(_, traces)| traces.iter().map(|t| t.sensor))
        .max()
        .map_or(0, |m| m + 1);
    let mut ways = Vec::new();
    for sensor in 0..sensors {
        let lines: Vec<(TraceKind, Vec<Coord<f64>>)> = groups
            .iter()
            .flat_map(|(kind, traces)| {
                traces
                    .iter()
                    .filter(move |t| t.sensor == sensor)
                    .flat_map(move |t| t.pieces.iter().map(move |p| (*kind, p.0.clone())))
            })
            .collect();
        for (parts, line) in chain_lines(lines, layout.circumference_mm, options.join_tolerance_mm)
        {
            let pts: Vec<Point> = dedup(&line, 1e-3 * options.join_tolerance_mm)
                .iter()
                .map(to_point)
                .collect();
            let pts = densify(&pts, options.max_rotation_per_move_rad);
            if pts.len() < 2 {
                continue;
            }
            let feature = Feature::Written { sensor, parts };
            let back: Vec<Point> = pts.iter().rev().copied().collect();
            let way = |f: Vec<Point>, r: Vec<Point>| Path {
                feature: feature.clone(),
                forward: f,
                reverse: Some(r),
                lead_in: false,
            };
            ways.push(vec![way(pts.clone(), back.clone()), way(back, pts)]);
        }
    }
    ways
}

/// The ways into a closed cut outline (counter-clockwise, in `(x, s)`): one per edge, from a
/// lead-in that starts inside the outline (the scrap) and meets the edge at its midpoint.
fn contour_ways(
    feature: &Feature,
    ring: &[Coord<f64>],
    options: &PlanOptions,
    to_point: &dyn Fn(&Coord<f64>) -> Point,
) -> Result<Vec<Path>, ToolpathError> {
    let n = ring.len();
    let mut lead_mm = options.lead_in_mm;
    for _ in 0..4 {
        let mut ways = Vec::new();
        for i in 0..n {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            let len = (b.x - a.x).hypot(b.y - a.y);
            if len <= options.join_tolerance_mm {
                continue;
            }
            let mid = Coord {
                x: (a.x + b.x) / 2.0,
                y: (a.y + b.y) / 2.0,
            };
            // Left of a counter-clockwise edge is inside.
            let start = Coord {
                x: mid.x - lead_mm * (b.y - a.y) / len,
                y: mid.y + lead_mm * (b.x - a.x) / len,
            };
            if !inside(ring, start) || ring_distance(ring, start) < 0.5 * lead_mm {
                continue;
            }
            let mut pts = vec![to_point(&start), to_point(&mid)];
            pts.extend((1..=n).map(|k| to_point(&ring[(i + k) % n])));
            pts.push(to_point(&mid));
            ways.push(Path {
                feature: feature.clone(),
                forward: densify(&pts, options.max_rotation_per_move_rad),
                reverse: None,
                lead_in: true,
            });
        }
        if !ways.is_empty() {
            return Ok(ways);
        }
        lead_mm /= 2.0;
    }
    Err(ToolpathError::NoLeadIn {
        feature: feature.to_string(),
        lead_in_mm: options.lead_in_mm,
    })
}

/// The parting line's `x`, checked to be one line all the way round.
fn parting_x(layout: &Layout, options: &PlanOptions) -> Result<f64, ToolpathError> {
    let coords: Vec<Coord<f64>> = layout
        .parting
        .iter()
        .flat_map(|l| l.0.iter().copied())
        .collect();
    let Some(first) = coords.first() else {
        return Err(ToolpathError::Layout(
            "the layout has no parting line".into(),
        ));
    };
    let x = first.x;
    if let Some(off) = coords
        .iter()
        .find(|c| (c.x - x).abs() > options.join_tolerance_mm)
    {
        return Err(ToolpathError::Layout(format!(
            "the parting line is not at one x: {x} mm and {} mm",
            off.x
        )));
    }
    let around: f64 = layout
        .parting
        .iter()
        .map(|l| l.0.windows(2).map(|w| (w[1].y - w[0].y).abs()).sum::<f64>())
        .sum();
    let tol = options.join_tolerance_mm * (1 + layout.parting.len()) as f64;
    if (around - layout.circumference_mm).abs() > tol {
        return Err(ToolpathError::Layout(format!(
            "the parting line covers {around} mm of the {} mm circumference; it must go all the way round",
            layout.circumference_mm
        )));
    }
    Ok(x)
}

/// One full turn at `x_cut_mm` from `a0_rad`, entered by a lead-in from the stock side; odd
/// passes turn back, entered from the stock side at the other end.
fn parting_path(x_cut_mm: f64, a0_rad: f64, options: &PlanOptions) -> Path {
    let x_lead = x_cut_mm + options.lead_in_mm;
    let turn = |from: f64, to: f64| {
        densify(
            &[
                Point::new(x_lead, from),
                Point::new(x_cut_mm, from),
                Point::new(x_cut_mm, to),
            ],
            options.max_rotation_per_move_rad,
        )
    };
    Path {
        feature: Feature::Parting,
        forward: turn(a0_rad, a0_rad + TAU),
        reverse: Some(turn(a0_rad + TAU, a0_rad)),
        lead_in: true,
    }
}

/// Drops points that repeat their predecessor (closer than `tolerance_mm`, in `(x, s)`).
fn dedup(points: &[Coord<f64>], tolerance_mm: f64) -> Vec<Coord<f64>> {
    let mut out: Vec<Coord<f64>> = Vec::with_capacity(points.len());
    for &p in points {
        if out
            .last()
            .map_or(true, |l| (p.x - l.x).hypot(p.y - l.y) > tolerance_mm)
        {
            out.push(p);
        }
    }
    out
}

/// Splits moves that rotate more than `max_rad` into equal parts on the same helix.
fn densify(points: &[Point], max_rad: f64) -> Vec<Point> {
    let mut out = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        if let Some(prev) = i.checked_sub(1).map(|j| points[j]) {
            let parts = ((p.a_rad - prev.a_rad).abs() / max_rad).ceil().max(1.0) as usize;
            for k in 1..parts {
                let t = k as f64 / parts as f64;
                out.push(Point::new(
                    prev.x_mm + t * (p.x_mm - prev.x_mm),
                    prev.a_rad + t * (p.a_rad - prev.a_rad),
                ));
            }
        }
        out.push(*p);
    }
    out
}

#[cfg(test)]
mod tests {
    use geo::{polygon, LineString};

    use super::*;
    use crate::layout::{Notch, Trace};
    use crate::machine::MachineLibrary;
    use crate::process::ProcessLibrary;
    use crate::toolpath::{MoveKind, ToolpathError};

    const R_O: f64 = 0.8;

    fn design() -> Design {
        Design::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/designs/joint-b.toml"
        )))
        .unwrap()
    }

    /// A hand-built layout on r_o = 0.8 mm with the seam at s = 0: one notch split at the
    /// seam (centred at s = 0), one whole notch, a sensor line that crosses the seam in two
    /// pieces, and the parting line in two pieces.
    fn layout() -> Layout {
        let c = TAU * R_O;
        let line = |pts: &[(f64, f64)]| LineString::from(pts.to_vec());
        Layout {
            name: "hand-built".into(),
            outer_radius_mm: R_O,
            circumference_mm: c,
            seam_s_mm: 0.0,
            trace_width_mm: 0.05,
            kerf_mm: 0.03,
            length_mm: 6.0,
            notches: vec![
                Notch {
                    joint: None,
                    level: 0,
                    side: 1,
                    outline: vec![
                        polygon![(x: 1.0, y: 0.0), (x: 1.5, y: 0.0), (x: 1.5, y: 0.6), (x: 1.0, y: 0.6)],
                        polygon![(x: 1.0, y: c - 0.6), (x: 1.5, y: c - 0.6), (x: 1.5, y: c), (x: 1.0, y: c)],
                    ],
                },
                Notch {
                    joint: None,
                    level: 1,
                    side: 0,
                    outline: vec![
                        polygon![(x: 2.0, y: 2.0), (x: 2.5, y: 2.0), (x: 2.5, y: 3.0), (x: 2.0, y: 3.0)],
                    ],
                },
            ],
            sensors: vec![Trace {
                sensor: 0,
                pieces: vec![
                    line(&[(4.0, c - 0.3), (4.0, c)]),
                    line(&[(4.0, 0.0), (4.0, 0.3), (5.0, 0.3)]),
                ],
            }],
            leads: vec![],
            pads: vec![],
            parting: vec![
                line(&[(6.0, 0.0), (6.0, 1.0)]),
                line(&[(6.0, 1.0), (6.0, c)]),
            ],
        }
    }

    fn inputs() -> (Design, ProcessSets, MachineProfile) {
        let sets = ProcessLibrary::default()
            .resolve(&crate::design::ProcessChoice::default())
            .unwrap();
        (
            design(),
            sets,
            MachineLibrary::default().find(None).unwrap(),
        )
    }

    #[test]
    fn long_rotations_are_split() {
        let pts = densify(&[Point::new(0.0, 0.0), Point::new(1.0, TAU)], TAU / 4.0);
        assert_eq!(pts.len(), 5);
        assert!((pts[2].x_mm - 0.5).abs() < 1e-12 && (pts[2].a_rad - TAU / 2.0).abs() < 1e-12);
    }

    #[test]
    fn parting_turns_once_and_back() {
        let p = parting_path(9.515, 0.3, &PlanOptions::default());
        assert_eq!(p.forward[0], Point::new(9.615, 0.3));
        assert_eq!(p.forward[1], Point::new(9.515, 0.3));
        assert!((p.forward.last().unwrap().a_rad - (0.3 + TAU)).abs() < 1e-12);
        let r = p.reverse.as_ref().unwrap();
        assert!((r[0].a_rad - (0.3 + TAU)).abs() < 1e-12 && r[0].x_mm == 9.615);
        assert!((r.last().unwrap().a_rad - 0.3).abs() < 1e-12);
        assert_eq!(p.forward.len(), 6);
    }

    #[test]
    fn seam_split_features_are_cut_in_one_go_with_a_continuous() {
        let (d, sets, m) = inputs();
        let plan = plan(&d, &layout(), &sets, &m, &PlanOptions::default()).unwrap();
        let sensor = &plan.operations[0];
        assert_eq!(sensor.paths.len(), 1, "the two pieces are one line");
        let notches = &plan.operations[1];
        assert_eq!(notches.paths.len(), 2);
        for path in sensor.paths.iter().chain(&notches.paths) {
            for w in path.forward.windows(2) {
                let ds = (w[1].a_rad - w[0].a_rad).abs() * R_O;
                // Edges here are at most 1.17 mm long; a seam jump would be most of a turn.
                assert!(ds < 1.5, "{}: a jump of {ds} mm in s", path.feature);
            }
        }
        // The split notch, offset by half the kerf, exactly: x 1.015..1.485, s −0.585..0.585
        // (modulo the circumference).
        let split = notches
            .paths
            .iter()
            .find(|p| {
                p.feature
                    == Feature::Notch {
                        joint: None,
                        level: 0,
                        side: 1,
                    }
            })
            .unwrap();
        let cut = &split.forward[1..];
        let (mut x0, mut x1, mut s0, mut s1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in cut {
            x0 = x0.min(p.x_mm);
            x1 = x1.max(p.x_mm);
            s0 = s0.min(p.a_rad * R_O);
            s1 = s1.max(p.a_rad * R_O);
        }
        let c = TAU * R_O;
        let shift = c * ((-0.585 - s0) / c).round();
        for (got, want) in [
            (x0, 1.015),
            (x1, 1.485),
            (s0 + shift, -0.585),
            (s1 + shift, 0.585),
        ] {
            assert!((got - want).abs() < 1e-9, "{got} vs {want}");
        }
        // Rapids never turn more than half a turn.
        for mv in plan.moves().iter().filter(|m| m.kind == MoveKind::Rapid) {
            assert!((mv.to.a_rad - mv.from.a_rad).abs() <= PI_PLUS, "{mv:?}");
        }
        // Nearest neighbour does not travel more than the layout's order.
        for t in &plan.travel {
            assert!(t.planned_mm <= t.layout_order_mm + 1e-9, "{t:?}");
        }
    }

    const PI_PLUS: f64 = std::f64::consts::PI + 1e-9;

    #[test]
    fn refuses_a_cut_that_touches_a_written_line() {
        let (d, sets, m) = inputs();
        let mut l = layout();
        // A sensor line 0.02 mm from the whole notch's edge: the kerf (0.015) plus half the
        // line (0.025) reaches over it.
        l.leads.push(Trace {
            sensor: 0,
            pieces: vec![LineString::from(vec![(2.52, 2.2), (2.52, 2.8)])],
        });
        let err = plan(&d, &l, &sets, &m, &PlanOptions::default()).unwrap_err();
        assert!(matches!(err, ToolpathError::Clearance { .. }), "{err}");
        let text = err.to_string();
        assert!(
            text.contains("notch 2") && text.contains("sensor 1"),
            "{text}"
        );
        // 0.05 mm away it is clear (0.015 + 0.025 = 0.04 needed).
        l.leads[0].pieces[0] = LineString::from(vec![(2.55, 2.2), (2.55, 2.8)]);
        assert!(plan(&d, &l, &sets, &m, &PlanOptions::default()).is_ok());
    }

    #[test]
    fn refuses_broken_layouts_with_the_feature_named() {
        let (d, sets, m) = inputs();
        let mut l = layout();
        l.parting.pop();
        let err = plan(&d, &l, &sets, &m, &PlanOptions::default())
            .unwrap_err()
            .to_string();
        assert!(err.contains("must go all the way round"), "{err}");
        let mut l = layout();
        l.notches[1].outline = vec![
            polygon![(x: 2.0, y: 2.0), (x: 2.02, y: 2.0), (x: 2.02, y: 3.0), (x: 2.0, y: 3.0)],
        ];
        let err = plan(&d, &l, &sets, &m, &PlanOptions::default())
            .unwrap_err()
            .to_string();
        assert!(
            err.starts_with("notch 2 (side 0): kerf 0.03 mm") && err.contains("narrower"),
            "{err}"
        );
    }

    #[test]
    fn every_rapid_is_beam_off_and_every_feed_within_limits() {
        let (d, sets, m) = inputs();
        let l = Layout::from_design(&d).unwrap();
        let plan = plan(&d, &l, &sets, &m, &PlanOptions::default()).unwrap();
        let moves = plan.moves();
        assert!(moves.iter().any(|mv| mv.kind == MoveKind::Rapid));
        for mv in &moves {
            assert!(mv.from.x_mm >= m.limits.x_min_mm && mv.to.x_mm <= m.limits.x_max_mm);
        }
        // Every pass starts with a rapid (or starts where the last ended) and the plan holds no
        // beam-on rapids by construction: a Move is Rapid or Feed, and the posts gate on that.
        let feeds = moves.iter().filter(|mv| mv.kind == MoveKind::Feed).count();
        let expected: usize = plan
            .operations
            .iter()
            .map(|op| {
                op.paths
                    .iter()
                    .map(|p| {
                        (0..op.process.repetitions)
                            .map(|k| p.pass(k).len() - 1)
                            .sum::<usize>()
                    })
                    .sum::<usize>()
            })
            .sum();
        assert_eq!(feeds, expected);
    }
}
