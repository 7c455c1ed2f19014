//! The warning for a crosstalk above 5 %: which joint and which lead, where the lead runs and
//! why it is not on the neutral plane, and a rotation that would lower it, found by routing
//! the robot again with that joint (or the sensor's own joint) turned in 15° steps.

use std::collections::HashMap;

use crate::layout::Layout;

use super::assemble::Robot;
use super::crosstalk::{reports_unrolled, CrosstalkFinding, CROSSTALK_WARNING};
use super::lanes::corridors;
use super::route::route;
use super::sensors::Arm;

/// The rotations tried: every 15°.
const ROTATION_STEP_DEG: f64 = 15.0;

/// A rotation is suggested only when it lowers the crosstalk by at least this share (0.5 %):
/// less is within what another route changes anyway.
const WORTH: f64 = 0.005;

/// The crosstalk matrices of the robot with one joint turned to another rotation, routed on
/// demand and kept: `(joint, rotation) → C` (`None` where it does not route).
#[derive(Default)]
pub(crate) struct Turns {
    routed: HashMap<(usize, u32), Option<Vec<Vec<f64>>>>,
}

impl Turns {
    /// `C` of `robot` with joint `j` at `k` rotation steps.
    fn matrix(&mut self, robot: &Robot, j: usize, k: u32) -> Option<&Vec<Vec<f64>>> {
        self.routed
            .entry((j, k))
            .or_insert_with(|| {
                let mut turned = robot.clone();
                turned.joints[j].rotation_deg = f64::from(k) * ROTATION_STEP_DEG;
                let routed = route(&turned).ok()?;
                let reports = reports_unrolled(&turned, &routed.unrolled).ok()?;
                Some(reports.into_iter().map(|r| r.crosstalk).collect())
            })
            .as_ref()
    }
}

/// The warnings for `findings`, each with where its lead runs and, when `advise`, what would
/// lower it (routing the robot again with joints turned: `dlw inspect` does, the other commands
/// say where to look).
pub(crate) fn suggestions(
    robot: &Robot,
    layout: &Layout,
    findings: &[CrosstalkFinding],
    advise: bool,
) -> Vec<String> {
    let mut turns = Turns::default();
    findings
        .iter()
        .map(|f| {
            let head = describe(robot, layout, f);
            if advise {
                format!("{head}. {}", rotation_advice(robot, f, &mut turns))
            } else {
                format!("{head}; dlw inspect names a rotation that would lower it, if one does")
            }
        })
        .collect()
}

/// Which sensor reads how much of which joint through which lead, where that lead runs and
/// why it is not on the neutral plane.
fn describe(robot: &Robot, layout: &Layout, f: &CrosstalkFinding) -> String {
    let joint = &robot.joints[f.joint];
    let r_o = robot.outer_radius_mm();
    let y_bar = joint.neutral_axis_mm();
    let (x0, x1) = (joint.x_start_mm(), joint.x_end_mm());
    // Where the lead runs over the joint: its longest axial piece there.
    let arm = usize::from(f.lead.arm == Arm::B);
    let lead = layout
        .leads
        .iter()
        .filter(|t| t.sensor == f.sensor.index)
        .nth(arm);
    let axial_over = |t: &crate::layout::Trace| -> Vec<(f64, f64)> {
        t.pieces
            .iter()
            .flat_map(|p| p.0.windows(2))
            .filter(|w| (w[1].y - w[0].y).abs() <= 1e-9)
            .map(|w| {
                let (a, b) = (w[0].x.min(w[1].x), w[0].x.max(w[1].x));
                ((b.min(x1) - a.max(x0)).max(0.0), w[0].y)
            })
            .filter(|(over, _)| *over > 0.0)
            .collect()
    };
    let y = lead
        .and_then(|t| {
            axial_over(t)
                .into_iter()
                .max_by(|a, b| a.0.total_cmp(&b.0))
                .map(|(_, s)| r_o * (s / r_o - joint.rotation_rad()).cos())
        })
        .unwrap_or(y_bar);
    let sharing = layout
        .leads
        .iter()
        .filter(|t| !axial_over(t).is_empty())
        .count();
    // Whether any corridor reaches the neutral plane.
    let fab = &joint.design().file.fabrication;
    let pitch = fab.trace_width_mm + robot.clearance_mm();
    let cut = fab.trace_width_mm / 2.0 + robot.clearance_mm().max(fab.kerf_mm / 2.0);
    let phi = (y_bar / r_o).clamp(-1.0, 1.0).acos();
    let c = joint.design().joint.section().circumference_mm();
    let reaches = corridors(joint, pitch, cut).iter().any(|k| {
        [r_o * phi, -r_o * phi, r_o * phi + c, -r_o * phi + c]
            .iter()
            .any(|s| *s >= k.lo && *s <= k.hi)
    });
    let why = if reaches {
        format!(
            "{sharing} leads share joint {}'s corridors, so not all can run on y = ȳ",
            f.joint + 1
        )
    } else {
        format!(
            "joint {}'s backbone does not reach y = ȳ beside its sensor{} with the clearance",
            f.joint + 1,
            if joint.sensor_count() == 1 { "" } else { "s" }
        )
    };
    format!(
        "{} reads {:.1} % of joint {}'s bending (crosstalk {:+.4}), {:.1} % of it through {}, which runs over joint {} at y = {:.3} mm, {:.3} mm {} its neutral plane ȳ = {:.3} mm ({why})",
        f.sensor,
        f.value.abs() * 100.0,
        f.joint + 1,
        f.value,
        f.lead_value.abs() * 100.0,
        f.lead,
        f.joint + 1,
        y,
        (y - y_bar).abs(),
        if y >= y_bar { "above" } else { "below" },
        y_bar
    )
}

/// Routes the robot with one joint turned at a time and says which turn lowers the finding's
/// crosstalk most.
fn rotation_advice(robot: &Robot, f: &CrosstalkFinding, turns: &mut Turns) -> String {
    let mut candidates = vec![f.joint];
    if f.sensor.joint != f.joint {
        candidates.push(f.sensor.joint);
    }
    let mut best: Option<(f64, usize, f64)> = None;
    for &j in &candidates {
        let now = robot.joints[j].rotation_deg.rem_euclid(360.0);
        for k in 0..(360.0 / ROTATION_STEP_DEG) as u32 {
            let rotation = f64::from(k) * ROTATION_STEP_DEG;
            if (rotation - now).abs() < 1e-9 {
                continue;
            }
            let Some(matrix) = turns.matrix(robot, j, k) else {
                continue;
            };
            let value = matrix[f.sensor.index][f.joint];
            if best.map_or(true, |(b, _, _)| value.abs() < b.abs()) {
                best = Some((value, j, rotation));
            }
        }
    }
    match best {
        Some((value, j, rotation)) if value.abs() <= f.value.abs() - WORTH => format!(
            "Rotating joint {} to {rotation}° would lower it to {:.1} %{}.",
            j + 1,
            value.abs() * 100.0,
            if value.abs() <= CROSSTALK_WARNING {
                ""
            } else {
                " (still above 5 %)"
            }
        ),
        Some((value, j, rotation)) => format!(
            "No rotation of joint {} in {ROTATION_STEP_DEG}° steps lowers it (the least is {:.1} %, joint {} at {rotation}°): fewer leads over joint {} (fewer sensors before it), or a backbone that reaches ȳ with room for them, would.",
            candidates
                .iter()
                .map(|j| (j + 1).to_string())
                .collect::<Vec<_>>()
                .join(" or joint "),
            value.abs() * 100.0,
            j + 1,
            f.joint + 1
        ),
        None => format!(
            "No other rotation of joint {} routes: fewer leads over it (fewer sensors before it) would lower it.",
            f.joint + 1
        ),
    }
}
