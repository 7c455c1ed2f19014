//! The safety invariants every plan must hold before any post-processor sees it.
//!
//! - Power never exceeds the machine's maximum.
//! - The focus never goes deeper than the tube wall (Z step × passes).
//! - Every move, rapid or cut, stays inside the X travel.
//! - Every beam-on move keeps its set's surface speed within the stage's X and A limits: a move
//!   that cannot is refused, never slowed down.
//! - No cutting path, widened by half the kerf, touches a written line widened by half its
//!   width.
//!
//! The beam being off on every rapid is structural: a plan has no beam-on rapids, and every
//! post-processor closes the gate before each rapid (checked on the programs in the tests).

use std::f64::consts::PI;

use geo::Coord;

use super::offset::segment_distance;
use super::plan::{MoveKind, OperationKind, Path, Plan, Point};
use super::ToolpathError;
use crate::layout::Layout;
use crate::machine::MachineProfile;

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
                return Err(ToolpathError::Speed {
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
                });
            }
        }
    }
    check_clearance(plan, layout)
}

/// No cut (kerf-offset outline with its lead-in, or the parting cut) may come within
/// `kerf/2 + trace width/2` of a written line's centre line.
fn check_clearance(plan: &Plan, layout: &Layout) -> Result<(), ToolpathError> {
    let r_o = plan.outer_radius_mm;
    let c = layout.circumference_mm;
    let needed_mm = plan.kerf_mm / 2.0 + plan.trace_width_mm / 2.0;
    let written: Vec<&Path> = plan
        .operations
        .iter()
        .filter(|o| o.kind == OperationKind::Sensor)
        .flat_map(|o| o.paths.iter())
        .collect();
    let cuts = plan
        .operations
        .iter()
        .filter(|o| o.kind != OperationKind::Sensor)
        .flat_map(|o| o.paths.iter());
    for cut in cuts {
        let cut_xs: Vec<Vec<Coord<f64>>> = [Some(&cut.forward), cut.reverse.as_ref()]
            .into_iter()
            .flatten()
            .map(|pts| to_xs(pts, r_o))
            .collect();
        for line in &written {
            let line_xs = to_xs(&line.forward, r_o);
            for cut_line in &cut_xs {
                let d = periodic_distance(cut_line, &line_xs, c);
                if d < needed_mm {
                    return Err(ToolpathError::Clearance {
                        cut: cut.feature.to_string(),
                        line: line.feature.to_string(),
                        distance_mm: d,
                        needed_mm,
                    });
                }
            }
        }
    }
    Ok(())
}

fn to_xs(points: &[Point], r_o: f64) -> Vec<Coord<f64>> {
    points
        .iter()
        .map(|p| Coord {
            x: p.x_mm,
            y: p.a_rad * r_o,
        })
        .collect()
}

/// Least distance between two polylines on the unrolled surface, trying the shifts by whole
/// circumferences that could bring them together.
fn periodic_distance(a: &[Coord<f64>], b: &[Coord<f64>], c: f64) -> f64 {
    let mean = |l: &[Coord<f64>]| l.iter().map(|p| p.y).sum::<f64>() / l.len().max(1) as f64;
    let base = ((mean(b) - mean(a)) / c).round();
    [-1.0, 0.0, 1.0]
        .into_iter()
        .map(|k| {
            let shift = (base + k) * c;
            let moved: Vec<Coord<f64>> = a
                .iter()
                .map(|p| Coord {
                    x: p.x,
                    y: p.y + shift,
                })
                .collect();
            polyline_distance(&moved, b)
        })
        .fold(f64::INFINITY, f64::min)
}

fn polyline_distance(a: &[Coord<f64>], b: &[Coord<f64>]) -> f64 {
    let segs = |l: &[Coord<f64>]| -> Vec<(Coord<f64>, Coord<f64>)> {
        if l.len() == 1 {
            vec![(l[0], l[0])]
        } else {
            l.windows(2).map(|w| (w[0], w[1])).collect()
        }
    };
    let mut best = f64::INFINITY;
    for (p, q) in segs(a) {
        for (r, s) in segs(b) {
            best = best.min(segment_segment(p, q, r, s));
        }
    }
    best
}

fn segment_segment(p: Coord<f64>, q: Coord<f64>, r: Coord<f64>, s: Coord<f64>) -> f64 {
    let cross = |o: Coord<f64>, a: Coord<f64>, b: Coord<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let (d1, d2, d3, d4) = (
        cross(p, q, r),
        cross(p, q, s),
        cross(r, s, p),
        cross(r, s, q),
    );
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return 0.0;
    }
    segment_distance(p, q, r)
        .min(segment_distance(p, q, s))
        .min(segment_distance(r, s, p))
        .min(segment_distance(r, s, q))
}

fn describe(p: Point) -> String {
    format!("(x {:.4} mm, a {:.4}°)", p.x_mm, p.a_rad * 180.0 / PI)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_distance_sees_across_the_seam() {
        let c = 10.0;
        let a = [Coord { x: 0.0, y: 9.9 }, Coord { x: 1.0, y: 9.9 }];
        let b = [Coord { x: 0.0, y: 0.1 }, Coord { x: 1.0, y: 0.1 }];
        assert!((periodic_distance(&a, &b, c) - 0.2).abs() < 1e-12);
        let crossing = [Coord { x: 0.5, y: -1.0 }, Coord { x: 0.5, y: 1.0 }];
        assert_eq!(periodic_distance(&crossing, &b, c), 0.0);
    }
}
