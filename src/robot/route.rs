//! The router: every joint's notches and U-traces as its design draws them, rotated and placed
//! along `x`, and every sensor's two leads from its arm ends to the pad section after the last
//! joint (`docs/robots.md`).
//!
//! Along the tube, from the distal end:
//! 1. over joint `j` every lead from a more distal joint runs along the tube in a lane of
//!    `j`'s corridors (`lanes`), as near `j`'s neutral plane as its backbone allows;
//! 2. in the gap before joint `j` (between the arms' ends of joint `j − 1` and the bridge of
//!    joint `j`) the leads move round the tube to those lanes (`jogs`), never over a notched
//!    section;
//! 3. after the last joint its own leads go to its own pads (row 0, where its design puts
//!    them) and the other leads to lanes between those pads; after row 0 they move to the
//!    terminals of their pads in the rows that follow (`pads`);
//! 4. the proximal margin, then the parting cut.
//!
//! Where a rule cannot be kept the router says which and by how much, and draws nothing.

use geo::Coord;

use crate::layout::{square_spiral, NotchRect, PadSide, Polyline, Unrolled};

use super::assemble::{Robot, RobotJoint};
use super::error::RobotViolation;
use super::jogs::{self, Jogs};
use super::lanes::{lanes_near, plan_lanes, LanePlan};
use super::pads;
use super::sensors::{list_leads, Arm, LeadName};

/// A routed robot, before its seam is chosen.
#[derive(Debug, Clone)]
pub(crate) struct Routed {
    /// Every feature, `s` unwrapped.
    pub unrolled: Unrolled,
    /// The name of each lead, in the order of `unrolled.leads` (and of its pads).
    pub lead_names: Vec<LeadName>,
    /// Rows of pads after row 0.
    pub pad_rows: usize,
}

/// The spacing rules the router keeps.
#[derive(Debug, Clone, Copy)]
struct Pitch {
    /// Circumference (mm).
    c: f64,
    /// Centre to centre between two leads, and from a lead to a pad's outer line: trace width
    /// plus clearance (mm).
    lead_mm: f64,
    /// From a lead's centre to a notch: half a trace width plus the clearance, and never less
    /// than half a trace width plus half the kerf (mm).
    cut_mm: f64,
}

/// A lead being routed: its name and its centre line so far.
struct Lead {
    name: LeadName,
    points: Vec<Coord>,
}

impl Lead {
    fn s(&self) -> f64 {
        self.points.last().map_or(0.0, |p| p.y)
    }
}

/// Routes `robot`.
///
/// # Errors
/// Every robot rule the routing breaks (a backbone too narrow, a gap too short, a pad section
/// that does not fit, leads that would cross).
pub(crate) fn route(robot: &Robot) -> Result<Routed, Vec<RobotViolation>> {
    let first = robot.joints[0].design();
    let fab = &first.file.fabrication;
    let w = fab.trace_width_mm;
    let clearance = robot.clearance_mm();
    let pitch = Pitch {
        c: first.joint.section().circumference_mm(),
        lead_mm: w + clearance,
        cut_mm: w / 2.0 + clearance.max(fab.kerf_mm / 2.0),
    };
    let mut violations = Vec::new();
    let Placed {
        notches,
        sensors,
        mut leads,
        own_pads,
        joint_leads,
    } = place_joints(robot)?;
    let own_sums = own_sums(robot, &sensors);
    let passing = route_over_joints(
        robot,
        &mut leads,
        &joint_leads,
        &own_sums,
        pitch,
        &mut violations,
    )?;
    let ended = route_to_pads(
        robot,
        &mut leads,
        passing,
        &joint_leads,
        &own_pads,
        pitch,
        &mut violations,
    )?;
    if !violations.is_empty() {
        return Err(violations);
    }
    let last = robot.last();
    let fab = &last.design().file.fabrication;
    let length_mm = if ended.pad_rows == 0 && ended.pad_shift == 0.0 {
        last.x(last.stations.parting_x_mm)
    } else {
        ended.end_x + fab.proximal_margin_mm
    };
    let (lead_lines, pad_lines, lead_names) = lead_and_pad_lines(leads, ended.pads)?;
    Ok(Routed {
        unrolled: Unrolled {
            name: robot.name.clone(),
            outer_radius_mm: first.file.outer_radius_mm,
            circumference_mm: pitch.c,
            trace_width_mm: w,
            kerf_mm: fab.kerf_mm,
            length_mm,
            notches,
            sensors,
            leads: lead_lines,
            pads: pad_lines,
        },
        lead_names,
        pad_rows: ended.pad_rows,
    })
}

/// Every joint's notches and U-traces on the robot, a lead starting at each trace's ends, and
/// the last joint's own pads.
struct Placed {
    notches: Vec<NotchRect>,
    sensors: Vec<Polyline>,
    leads: Vec<Lead>,
    own_pads: Vec<Polyline>,
    /// Each joint's own leads (indices into `leads`).
    joint_leads: Vec<Vec<usize>>,
}

/// Places each joint's own features on the robot.
fn place_joints(robot: &Robot) -> Result<Placed, Vec<RobotViolation>> {
    let multi = robot.joints.len() > 1;
    let mut notches: Vec<NotchRect> = Vec::new();
    let mut sensors: Vec<Polyline> = Vec::new();
    let mut leads: Vec<Lead> = Vec::new();
    let mut own_pads: Vec<Polyline> = Vec::new();
    let mut joint_leads: Vec<Vec<usize>> = Vec::new();
    let robot_sensors = robot.sensors();
    for (ji, joint) in robot.joints.iter().enumerate() {
        let own = Unrolled::from_design(joint.design())
            .map_err(|e| vec![RobotViolation::Unsafe(e.to_string())])?;
        let place = |c: &Coord| Coord {
            x: joint.x(c.x),
            y: joint.s(c.y),
        };
        notches.extend(own.notches.iter().map(|r| NotchRect {
            joint: multi.then_some(ji),
            x0_mm: joint.x(r.x0_mm),
            x1_mm: joint.x(r.x1_mm),
            s0_mm: joint.s(r.s0_mm),
            s1_mm: joint.s(r.s1_mm),
            ..*r
        }));
        let mut mine = Vec::new();
        for u in &own.sensors {
            let sensor = *robot_sensors
                .iter()
                .find(|s| s.joint == ji && s.sensor == u.sensor)
                .ok_or_else(|| vec![RobotViolation::Unsafe("a sensor without a number".into())])?;
            let points: Vec<Coord> = u.points.iter().map(place).collect();
            for (arm, end) in [(Arm::A, points[0]), (Arm::B, points[points.len() - 1])] {
                mine.push(leads.len());
                leads.push(Lead {
                    name: LeadName { sensor, arm },
                    points: vec![end],
                });
            }
            sensors.push(Polyline {
                sensor: sensor.index,
                points,
            });
        }
        if ji + 1 == robot.joints.len() {
            own_pads = own
                .pads
                .iter()
                .map(|p| Polyline {
                    sensor: p.sensor,
                    points: p.points.iter().map(place).collect(),
                })
                .collect();
        }
        joint_leads.push(mine);
    }

    Ok(Placed {
        notches,
        sensors,
        leads,
        own_pads,
        joint_leads,
    })
}

/// What each sensor's U-trace reads of its own joint: the crosstalk's denominator.
fn own_sums(robot: &Robot, sensors: &[Polyline]) -> Vec<f64> {
    let r_o = robot.joints[0].design().file.outer_radius_mm;
    let robot_sensors = robot.sensors();
    sensors
        .iter()
        .map(|u| {
            let j = &robot.joints[robot_sensors[u.sensor].joint];
            let height = |s: f64| r_o * (s / r_o - j.rotation_rad()).cos() - j.neutral_axis_mm();
            height(u.points[0].y) + height(u.points[u.points.len() - 1].y)
        })
        .collect()
}

/// Over each joint after the first: the leads from every joint before it. Returns the leads
/// that pass the last joint; a gap too short is added to `violations`, a backbone too narrow
/// or leads that would cross end the routing.
fn route_over_joints(
    robot: &Robot,
    leads: &mut [Lead],
    joint_leads: &[Vec<usize>],
    own_sums: &[f64],
    pitch: Pitch,
    violations: &mut Vec<RobotViolation>,
) -> Result<Vec<usize>, Vec<RobotViolation>> {
    let mut active: Vec<usize> = Vec::new();
    for ji in 1..robot.joints.len() {
        active.extend(&joint_leads[ji - 1]);
        let (prev, joint) = (&robot.joints[ji - 1], &robot.joints[ji]);
        let names: Vec<LeadName> = active.iter().map(|&i| leads[i].name).collect();
        let plan = match plan_lanes(joint, active.len(), pitch.lead_mm, pitch.cut_mm) {
            Ok(plan) => plan,
            Err(no) => {
                violations.push(backbone(ji, joint, &names, no.room, &no.widths, pitch));
                return Err(std::mem::take(violations));
            }
        };
        let from: Vec<f64> = active.iter().map(|&i| leads[i].s()).collect();
        let sensor_of: Vec<usize> = names.iter().map(|n| n.sensor.index).collect();
        let jogs = match choose_lanes(&plan, joint, &from, &sensor_of, own_sums, pitch) {
            Ok(j) => j,
            Err((a, b)) => {
                violations.push(crossing(
                    format!("before joint {}", ji + 1),
                    ji,
                    &names,
                    a,
                    b,
                ));
                return Err(std::mem::take(violations));
            }
        };
        let x0 = prev.x(prev.stations.arm_end_x_mm);
        let x1 = joint.x(joint.stations.bridge_x_mm);
        let needed = (jogs.steps + 1) as f64 * pitch.lead_mm;
        if x1 - x0 < needed - 1e-9 {
            let moving: Vec<LeadName> = (0..active.len())
                .filter(|&k| jogs.step[k].is_some())
                .map(|k| names[k])
                .collect();
            let gap_mm = joint.gap_mm.unwrap_or(0.0);
            violations.push(RobotViolation::Gap {
                joint: ji + 1,
                name: joint.design().file.name.clone(),
                gap_mm,
                leads: list_leads(&moving),
                steps: jogs.steps,
                prev_half_mm: prev.stations.arm_end_x_mm - prev.stations.notched_end_x_mm,
                half_mm: joint.stations.first_notch_x_mm - joint.stations.bridge_x_mm,
                pitch_mm: pitch.lead_mm,
                needed_mm: gap_mm + needed - (x1 - x0),
            });
        }
        apply(leads, &active, &jogs, x0, x1);
    }

    Ok(active)
}

/// Where the leads end: each lead's pad, the x past the last pad row, the rows of pads, and
/// how far the last joint's own pads moved along x.
struct Ended {
    pads: Vec<Option<Polyline>>,
    end_x: f64,
    pad_rows: usize,
    pad_shift: f64,
}

/// After the last joint: its own leads to its own pads (row 0), the others (`passing`) between
/// them and on to rows of pads of their own.
fn route_to_pads(
    robot: &Robot,
    leads: &mut [Lead],
    passing: Vec<usize>,
    joint_leads: &[Vec<usize>],
    own_pads: &[Polyline],
    pitch: Pitch,
    violations: &mut Vec<RobotViolation>,
) -> Result<Ended, Vec<RobotViolation>> {
    let last_index = robot.joints.len() - 1;
    let last = robot.last();
    let mut active = passing.clone();
    active.extend(&joint_leads[last_index]);
    let own = &joint_leads[last_index];
    let from: Vec<f64> = active.iter().map(|&i| leads[i].s()).collect();
    let terminals: Vec<Coord> = own_pads.iter().map(|p| p.points[0]).collect();
    let to = match row_zero_targets(&active, own, &from, own_pads, leads, pitch) {
        Ok(to) => to,
        Err(v) => {
            violations.push(v);
            return Err(std::mem::take(violations));
        }
    };
    let names: Vec<LeadName> = active.iter().map(|&i| leads[i].name).collect();
    let jogs = match jogs::order(&from, &to, pitch.c, pitch.lead_mm) {
        Ok(j) => j,
        Err((a, b)) => {
            violations.push(crossing("before the pads".into(), last_index, &names, a, b));
            return Err(std::mem::take(violations));
        }
    };
    let x0 = last.x(last.stations.arm_end_x_mm);
    let lead_mm = last.stations.pad_x_mm - last.stations.arm_end_x_mm;
    let pad_x = if lead_mm >= (jogs.steps + 1) as f64 * pitch.lead_mm {
        last.x(last.stations.pad_x_mm)
    } else {
        x0 + (jogs.steps + 1) as f64 * pitch.lead_mm
    };
    apply(leads, &active, &jogs, x0, pad_x);
    let pad_shift = pad_x - last.x(last.stations.pad_x_mm);
    let mut pads: Vec<Option<Polyline>> = (0..leads.len()).map(|_| None).collect();
    for (k, &i) in own.iter().enumerate() {
        let t = Coord {
            x: terminals[k].x + pad_shift,
            y: jogs.to[passing.len() + k],
        };
        leads[i].points.push(t);
        let turn = t.y - terminals[k].y;
        pads[i] = Some(Polyline {
            sensor: leads[i].name.sensor.index,
            points: own_pads[k]
                .points
                .iter()
                .map(|p| Coord {
                    x: p.x + pad_shift,
                    y: p.y + turn,
                })
                .collect(),
        });
    }
    let fab = &last.design().file.fabrication;
    let pad_mm = last.stations.pad_size_mm;
    let mut end_x = pad_x + pad_mm;
    let mut pad_rows = 0;
    if !passing.is_empty() {
        let x0 = pad_x + pad_mm;
        match rows(&passing, leads, fab, pad_mm, x0, pitch) {
            Ok((rows_end, list, count)) => {
                for (i, pad) in list {
                    pads[i] = Some(pad);
                }
                end_x = rows_end;
                pad_rows = count;
            }
            Err(v) => {
                violations.push(v);
                return Err(std::mem::take(violations));
            }
        }
    }
    Ok(Ended {
        pads,
        end_x,
        pad_rows,
        pad_shift,
    })
}

/// The leads and their pads as polylines, with the leads' names; an error for a lead that
/// reached no pad.
#[allow(clippy::type_complexity)]
fn lead_and_pad_lines(
    leads: Vec<Lead>,
    pads: Vec<Option<Polyline>>,
) -> Result<(Vec<Polyline>, Vec<Polyline>, Vec<LeadName>), Vec<RobotViolation>> {
    let mut lead_lines = Vec::with_capacity(leads.len());
    let mut pad_lines = Vec::with_capacity(leads.len());
    let mut lead_names = Vec::with_capacity(leads.len());
    for (lead, pad) in leads.into_iter().zip(pads) {
        let Some(pad) = pad else {
            return Err(vec![RobotViolation::Unsafe(format!(
                "{} was routed to no pad",
                lead.name
            ))]);
        };
        lead_lines.push(Polyline {
            sensor: lead.name.sensor.index,
            points: lead.points,
        });
        pad_lines.push(pad);
        lead_names.push(lead.name);
    }
    Ok((lead_lines, pad_lines, lead_names))
}

/// The lanes over `joint` and which lead takes which: each corridor's block of lanes is moved
/// through its candidate places, one corridor at a time, and the place kept where the leads'
/// crosstalk onto the joint, `Σ_sensors (Σ_leads (y − ȳ) / own)²`, is least (squared, so no
/// one sensor takes it all), then their `Σ |y − ȳ|`. Leads of one sensor on either side of
/// the neutral plane cancel; a lone lead is best on it.
fn choose_lanes(
    plan: &LanePlan,
    joint: &RobotJoint,
    from: &[f64],
    sensor_of: &[usize],
    own: &[f64],
    pitch: Pitch,
) -> Result<Jogs, jogs::Crossing> {
    let r_o = joint.design().file.outer_radius_mm;
    let (rot, y_bar) = (joint.rotation_rad(), joint.neutral_axis_mm());
    let height = |t: f64| r_o * (t / r_o - rot).cos() - y_bar;
    let score = |to: &[f64]| -> f64 {
        let mut sums = vec![0.0; own.len()];
        for (k, t) in to.iter().enumerate() {
            sums[sensor_of[k]] += height(*t);
        }
        sums.iter().zip(own).map(|(s, o)| (s / o).powi(2)).sum()
    };
    let near = |to: &[f64]| to.iter().map(|t| height(*t).abs()).sum::<f64>();
    let evaluate = |starts: &[f64], bound: f64| -> Result<(f64, f64, Jogs), jogs::Crossing> {
        let lanes = plan.lanes(starts);
        let j = jogs::assign(from, &lanes, pitch.c, pitch.lead_mm, &score, bound)?;
        Ok((score(&j.to), near(&j.to), j))
    };
    let better = |a: &(f64, f64, Jogs), b: &(f64, f64, Jogs)| {
        a.0 < b.0 - 1e-12 || (a.0 <= b.0 + 1e-12 && a.1 < b.1 - 1e-12)
    };
    let mut starts = plan.starts.clone();
    let mut best = evaluate(&starts, f64::INFINITY);
    for _round in 0..3 {
        let mut improved = false;
        for i in (0..plan.corridors.len()).filter(|&i| plan.counts[i] > 0) {
            for &u in &plan.candidates[i] {
                let mut trial = starts.clone();
                trial[i] = u;
                let bound = best.as_ref().map_or(f64::INFINITY, |b| b.0);
                let Ok(found) = evaluate(&trial, bound) else {
                    continue;
                };
                if best.as_ref().map_or(true, |b| better(&found, b)) {
                    best = Ok(found);
                    starts = trial;
                    improved = true;
                }
            }
        }
        if !improved {
            break;
        }
    }
    best.map(|(_, _, j)| j)
}

/// Adds each jog of `jogs` to its lead: along the tube to its step's `x`, round to its lane.
fn apply(leads: &mut [Lead], active: &[usize], jogs: &Jogs, x0: f64, x1: f64) {
    for (k, &i) in active.iter().enumerate() {
        if let Some(step) = jogs.step[k] {
            let x = jogs::step_x(x0, x1, step, jogs.steps);
            let from = leads[i].s();
            leads[i].points.push(Coord { x, y: from });
            leads[i].points.push(Coord { x, y: jogs.to[k] });
        }
    }
}

/// Where each lead goes after the last joint: its own pad's terminal for the last joint's own
/// leads (listed last in `active`), and for the others a lane in the gap between the own pads
/// they arrive between, as near where they arrive as the pitch allows.
// A violation is built once per refused robot; boxing it would touch every constructor.
#[allow(clippy::result_large_err)]
fn row_zero_targets(
    active: &[usize],
    own: &[usize],
    from: &[f64],
    own_pads: &[Polyline],
    leads: &[Lead],
    pitch: Pitch,
) -> Result<Vec<f64>, RobotViolation> {
    let c = pitch.c;
    let n_pass = active.len() - own.len();
    let mut to = from.to_vec();
    // Own leads: the terminal, the same turn as the arm (the joint's own numbers kept).
    let mut own_t = Vec::with_capacity(own.len());
    for (k, pad) in own_pads.iter().enumerate() {
        let f = from[n_pass + k];
        let t = pad.points[0].y;
        let t = t + c * ((f - t) / c).round();
        to[n_pass + k] = t;
        let (lo, hi) = pad
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.y), hi.max(p.y))
            });
        own_t.push((f, t, lo - pad.points[0].y, hi - pad.points[0].y));
    }
    if n_pass == 0 {
        return Ok(to);
    }
    // Own leads in order round the tube; passing leads grouped by the own lead before them.
    let mut own_order: Vec<usize> = (0..own.len()).collect();
    own_order.sort_by(|&a, &b| {
        own_t[a]
            .0
            .rem_euclid(c)
            .total_cmp(&own_t[b].0.rem_euclid(c))
    });
    for (o, &a) in own_order.iter().enumerate() {
        let b = own_order[(o + 1) % own_order.len()];
        let fa = own_t[a].0.rem_euclid(c);
        let mut fb = own_t[b].0.rem_euclid(c);
        if fb <= fa {
            fb += c;
        }
        // Passing leads arriving between a and b, unwrapped after a.
        let mut group: Vec<(f64, usize)> = (0..n_pass)
            .filter_map(|k| {
                let mut f = from[k].rem_euclid(c);
                if f < fa {
                    f += c;
                }
                (f < fb).then_some((f, k))
            })
            .collect();
        if group.is_empty() {
            continue;
        }
        group.sort_by(|p, q| p.0.total_cmp(&q.0));
        // Terminals of a and b unwrapped next to their arrivals.
        let ta = own_t[a].1 + c * ((fa - own_t[a].0) / c).round();
        let tb = own_t[b].1 + c * ((fb - own_t[b].0) / c).round();
        let lo = ta + own_t[a].3 + pitch.lead_mm;
        let hi = tb + own_t[b].2 - pitch.lead_mm;
        let arrivals: Vec<f64> = group.iter().map(|g| g.0).collect();
        let Some(lanes) = lanes_near(&arrivals, lo, hi, pitch.lead_mm) else {
            let names: Vec<LeadName> = group.iter().map(|g| leads[active[g.1]].name).collect();
            let room = if hi >= lo {
                ((hi - lo) / pitch.lead_mm + 1e-9).floor() as usize + 1
            } else {
                0
            };
            return Err(RobotViolation::PadSection {
                leads: list_leads(&names),
                reason: format!(
                    "they must pass between the last joint's own pads of {} and {}, which leave {:.3} mm for lead centres, room for {room} lead{} at {:.3} mm pitch; {} too many",
                    leads[active[n_pass + a]].name,
                    leads[active[n_pass + b]].name,
                    (hi - lo).max(0.0),
                    if room == 1 { "" } else { "s" },
                    pitch.lead_mm,
                    group.len() - room
                ),
            });
        };
        for ((f, k), lane) in group.iter().zip(lanes) {
            to[*k] = from[*k] + (lane - f);
        }
    }
    Ok(to)
}

/// The rows after row 0 for the `passing` leads, which run between row 0's pads: the leads
/// move round the tube to their terminals after row 0, then run along it to their row. Returns
/// the proximal edge of the last row, the pads, and the number of rows.
#[allow(clippy::type_complexity)]
#[allow(clippy::result_large_err)]
fn rows(
    passing: &[usize],
    leads: &mut [Lead],
    fab: &crate::design::Fabrication,
    pad_mm: f64,
    x0: f64,
    pitch: Pitch,
) -> Result<(f64, Vec<(usize, Polyline)>, usize), RobotViolation> {
    let c = pitch.c;
    let names: Vec<LeadName> = passing.iter().map(|&i| leads[i].name).collect();
    let mut by_s: Vec<usize> = (0..passing.len()).collect();
    by_s.sort_by(|&a, &b| {
        leads[passing[a]]
            .s()
            .rem_euclid(c)
            .total_cmp(&leads[passing[b]].s().rem_euclid(c))
    });
    let packed = pads::pack(passing.len(), c, pad_mm, fab.pad_gap_mm, pitch.lead_mm).map_err(
        |no| RobotViolation::PadSection {
            leads: list_leads(&names),
            reason: format!(
                "{} pads of {pad_mm:.3} mm with the leads between them need at least {:.3} mm round the tube in any number of rows, more than the circumference {c:.3} mm",
                passing.len(),
                no.needed_mm
            ),
        },
    )?;
    let from: Vec<f64> = by_s.iter().map(|&k| leads[passing[k]].s()).collect();
    let g: Vec<f64> = from.iter().map(|f| f.rem_euclid(c)).collect();
    // Turn the packed terminals as a whole: first so the largest move is least, then so each
    // lead lands where it is; the first whose jogs can be ordered wins.
    let unwrap = |offset: f64| -> Vec<f64> {
        let mut prev = f64::NEG_INFINITY;
        packed
            .s
            .iter()
            .zip(&g)
            .map(|(t, gi)| {
                let mut v = t + offset;
                v += c * ((gi - v) / c).round();
                if v <= prev {
                    v += c;
                }
                prev = v;
                v
            })
            .collect()
    };
    let diffs: Vec<f64> = packed.s.iter().zip(&g).map(|(t, gi)| gi - t).collect();
    let mid = {
        let (lo, hi) = diffs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                (lo.min(*d), hi.max(*d))
            });
        (lo + hi) / 2.0
    };
    let mut tried = vec![mid];
    tried.extend(diffs.iter().copied());
    let mut found: Option<Jogs> = None;
    let mut last_err = (0, 0);
    for offset in tried {
        let mut targets = unwrap(offset);
        // The same winding for every lead: bring the whole set to within half a turn.
        let mean: f64 =
            targets.iter().zip(&g).map(|(t, gi)| t - gi).sum::<f64>() / targets.len() as f64;
        let k = (mean / c).round();
        for t in &mut targets {
            *t -= k * c;
        }
        let to: Vec<f64> = targets
            .iter()
            .zip(&g)
            .zip(&from)
            .map(|((t, gi), f)| f + (t - gi))
            .collect();
        match jogs::order(&from, &to, c, pitch.lead_mm) {
            Ok(j) => {
                found = Some(j);
                break;
            }
            Err(e) => last_err = e,
        }
    }
    let Some(jogs) = found else {
        let sorted: Vec<LeadName> = by_s.iter().map(|&k| names[k]).collect();
        return Err(RobotViolation::Crossing {
            place: "after the last joint's pads".into(),
            lead: sorted[last_err.0].to_string(),
            other: sorted[last_err.1].to_string(),
            advice: "a larger pad_gap_mm or fewer pad turns leaves them more room".into(),
        });
    };
    let row_gap = fab.pad_gap_mm.max(pitch.lead_mm);
    let x1 = x0 + row_gap.max((jogs.steps + 1) as f64 * pitch.lead_mm);
    let order: Vec<usize> = by_s.iter().map(|&k| passing[k]).collect();
    apply(leads, &order, &jogs, x0, x1);
    let mut out = Vec::with_capacity(order.len());
    let mut end = x1;
    for (k, &i) in order.iter().enumerate() {
        let row_x = x1 + (packed.row[k] - 1) as f64 * (pad_mm + row_gap);
        let terminal = Coord {
            x: row_x,
            y: jogs.to[k],
        };
        leads[i].points.push(terminal);
        out.push((
            i,
            Polyline {
                sensor: leads[i].name.sensor.index,
                points: square_spiral(terminal, fab.pad_pitch_mm, fab.pad_turns, PadSide::Above),
            },
        ));
        end = end.max(row_x + pad_mm);
    }
    Ok((end, out, packed.count))
}

/// The message for a joint whose backbone cannot carry its leads.
fn backbone(
    ji: usize,
    joint: &RobotJoint,
    names: &[LeadName],
    room: usize,
    widths: &[f64],
    pitch: Pitch,
) -> RobotViolation {
    let corridors = match widths.len() {
        0 => "no corridor: its notches and sensors leave no room at all".to_string(),
        1 => format!("1 corridor {:.3} mm wide", widths[0]),
        n => format!(
            "{n} corridors {} mm wide",
            widths
                .iter()
                .map(|w| format!("{w:.3}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    RobotViolation::Backbone {
        joint: ji + 1,
        name: joint.design().file.name.clone(),
        style: joint.style_name(),
        rotation_deg: joint.rotation_deg,
        own_sensors: joint.sensor_count(),
        count: names.len(),
        leads: list_leads(names),
        room,
        corridors,
        pitch_mm: pitch.lead_mm,
        short: names.len().saturating_sub(room),
    }
}

/// The message for two leads that cannot move without crossing.
fn crossing(place: String, ji: usize, names: &[LeadName], a: usize, b: usize) -> RobotViolation {
    RobotViolation::Crossing {
        place,
        lead: names[a].to_string(),
        other: names[b].to_string(),
        advice: format!(
            "another rotation_deg for joint {} changes where the leads must go",
            ji + 1
        ),
    }
}
