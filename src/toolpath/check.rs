//! The safety invariants every plan must hold before any post-processor sees it.
//!
//! - Power never exceeds the machine's maximum.
//! - The focus never goes deeper than the tube wall (Z step × passes).
//! - Every move, rapid or cut, stays inside the X travel.
//! - Every beam-on move keeps its set's surface speed within the stage's X and A limits: a move
//!   that cannot is refused, never slowed down.
//! - No cutting path, widened by half the kerf, touches a written line widened by half its
//!   width (the design rules' clearance check, run on the cutting paths).
//!
//! The beam being off on every rapid is structural: a plan has no beam-on rapids, and every
//! post-processor closes the gate before each rapid (checked on the programs in the tests).

use std::f64::consts::PI;

use geo::Coord;

use geo::{LineString, Polygon};

use super::plan::{Feature, MoveKind, OperationKind, Plan, Point};
use super::{SpeedViolation, ToolpathError};
use crate::layout::{Layout, Notch};
use crate::machine::MachineProfile;
use crate::rules::{self, Violation};

/// Checks every invariant of `plan` against `profile`.
///
/// # Errors
/// The first broken invariant, naming the operation, path, move and limit.
pub fn check_plan(
    plan: &Plan,
    layout: &Layout,
    profile: &MachineProfile,
) -> Result<(), ToolpathError> {
    let limits = &profile.limits;
    for op in &plan.operations {
        let set = &op.process;
        if set.power_mw > limits.max_power_mw {
            return Err(ToolpathError::Power {
                operation: op.kind.name(),
                set: set.name.clone(),
                power_mw: set.power_mw,
                max_mw: limits.max_power_mw,
            });
        }
        let depth_mm = f64::from(set.repetitions.saturating_sub(1)) * set.z_step_or_zero_mm();
        let wall_mm = plan.outer_radius_mm - plan.inner_radius_mm;
        if depth_mm > wall_mm {
            return Err(ToolpathError::FocusDepth {
                set: set.name.clone(),
                depth_mm,
                wall_mm,
            });
        }
    }
    for (index, mv) in plan.moves().iter().enumerate() {
        let op = &plan.operations[mv.operation];
        let path = &op.paths[mv.path];
        for p in [mv.from, mv.to] {
            if p.x_mm < limits.x_min_mm || p.x_mm > limits.x_max_mm {
                return Err(ToolpathError::Travel {
                    operation: op.kind.name(),
                    feature: path.feature.to_string(),
                    x_mm: p.x_mm,
                    min_mm: limits.x_min_mm,
                    max_mm: limits.x_max_mm,
                });
            }
        }
        if mv.kind != MoveKind::Feed {
            continue;
        }
        let d = mv.from.surface_distance_mm(&mv.to, plan.outer_radius_mm);
        if d == 0.0 {
            continue;
        }
        let seconds = d / op.process.scan_speed_mm_s;
        let x_speed = (mv.to.x_mm - mv.from.x_mm).abs() / seconds;
        let a_speed = (mv.to.a_rad - mv.from.a_rad).abs().to_degrees() / seconds;
        for (axis, needed, limit, unit) in [
            (
                profile.axes.linear,
                x_speed,
                limits.x_speed_max_mm_s,
                "mm/s",
            ),
            (
                profile.axes.rotary,
                a_speed,
                limits.a_speed_max_deg_s,
                "deg/s",
            ),
        ] {
            if needed > limit * (1.0 + 1e-12) {
                return Err(ToolpathError::Speed(Box::new(SpeedViolation {
                    operation: op.kind.name(),
                    feature: path.feature.to_string(),
                    pass: mv.pass,
                    index,
                    from: describe(mv.from),
                    to: describe(mv.to),
                    axis,
                    needed,
                    limit,
                    unit,
                    surface_mm_s: op.process.scan_speed_mm_s,
                })));
            }
        }
    }
    check_clearance(plan, layout)
}

/// No cut may touch a written line: the design rules' clearance check
/// ([`crate::rules::check_layout`]) run on a layout whose notches are the kerf-offset cut
/// outlines (their lead-ins lie inside) and whose parting line is the parting cut's centre line
/// and lead-in, with the written lines as the design drew them, at a clearance of `kerf/2`:
/// the rule then demands `d − w/2 ≥ kerf/2`, i.e. the kerf's edge stays off the line's edge.
fn check_clearance(plan: &Plan, layout: &Layout) -> Result<(), ToolpathError> {
    let r_o = plan.outer_radius_mm;
    let to_xs = |pts: &[Point]| -> Vec<Coord<f64>> {
        pts.iter()
            .map(|p| Coord {
                x: p.x_mm,
                y: p.a_rad * r_o,
            })
            .collect()
    };
    let mut notches = Vec::new();
    let mut parting = Vec::new();
    for op in plan
        .operations
        .iter()
        .filter(|o| o.kind != OperationKind::Sensor)
    {
        for path in &op.paths {
            for pts in [Some(&path.forward), path.reverse.as_ref()]
                .into_iter()
                .flatten()
                .filter(|pts| pts.len() >= 2)
            {
                match path.feature {
                    Feature::Notch { joint, level, side } => {
                        let skip = usize::from(path.lead_in);
                        notches.push(Notch {
                            joint,
                            level,
                            side,
                            outline: vec![Polygon::new(
                                LineString::new(to_xs(&pts[skip..])),
                                vec![],
                            )],
                        });
                        parting.push(LineString::new(to_xs(&pts[..=skip])));
                    }
                    _ => parting.push(LineString::new(to_xs(pts))),
                }
            }
        }
    }
    let cuts = Layout {
        notches,
        parting,
        ..layout.clone()
    };
    let needed_mm = plan.kerf_mm / 2.0;
    let found: Vec<String> = rules::check_layout(&cuts, needed_mm)
        .into_iter()
        .filter(|v| matches!(v, Violation::Clearance { .. }))
        .filter(|v| !v.to_string().contains("the distal end"))
        .map(|v| v.to_string())
        .collect();
    if found.is_empty() {
        Ok(())
    } else {
        Err(ToolpathError::Clearance {
            kerf_mm: plan.kerf_mm,
            found,
        })
    }
}

fn describe(p: Point) -> String {
    format!("(x {:.4} mm, a {:.4}°)", p.x_mm, p.a_rad * 180.0 / PI)
}
