//! A robot's import (issue 34 §1): one tracker tool per joint becomes per-joint angles in a
//! robot recording (`recording::robot`). Joint `k`'s angle is the joint import's bending angle
//! ([`angle::bending_angles`]) of tool `k` taken in the frame of tool `k + 1` (joint 1 is the
//! distal one, so tool `k + 1` sits just proximal of joint `k` and its frame moves with every
//! joint but `k`), the most proximal joint's in the reference tool's frame, or against its own
//! rest axis without one. Everything else is the joint import's, called, not copied: the option
//! and value checks ([`values`](super::values)), the clocks (aligned once, on joint 1's angle
//! against sensor 1, [`clocks`](super::clocks)), the check after the alignment, the
//! resampling, the placement of each joint's angle on the DAQ's rows
//! ([`place`](super::place)), the sign rule (pulling a joint's tendon bends it positive) and
//! the provenance. A row any joint's angle cannot vouch for gets `tracker_valid = 0`.
//!
//! The recording is checked by the robot recording's reader's rules before it is returned
//! ([`RobotRecording::check`]).
//!
//! A tip tool alone is refused by the caller: its positions cannot be put in the robot's base
//! frame without the base's pose in the tracker's frame ([`TIP_TOOL_REFUSAL`]).

use std::path::Path;

use crate::recording::robot::{RobotRecording, RobotSamples};
use crate::recording::Rig;

use super::align::Signal;
use super::angle::{self, BendingAngles};
use super::{
    check, clocks, place, provenance, pulls_positive, read_daq, read_tracker, refuse_jumps,
    resample, stretch, summary, values, DaqColumns, ImportError, ImportRequest, ImportSummary,
};

/// Why `--tip-tool` is refused.
pub const TIP_TOOL_REFUSAL: &str = "--tip-tool: a tip tool's positions are in the tracker's frame, and putting them in the robot's base frame (tip_x_mm, tip_y_mm, tip_z_mm) needs the base's pose in the tracker's frame (a base tool at a known offset from the base, or a registration step), which the log does not hold; give one tool per joint with --joint-tool K=TOOL instead";

/// A robot import: the joint import's request for everything the two share, and the robot's
/// own lists.
#[derive(Debug, Clone)]
pub struct RobotImportRequest<'a> {
    /// The shared settings. `voltage_channels` and `divider_ohm` hold every sensor's, in the
    /// robot's sensor order; `stroke` is joint 1's; `tool` is joint 1's tool and
    /// `reference_tool` the robot's reference tool.
    pub base: ImportRequest<'a>,
    /// Each joint's stroke channel and its scale (mm per V), joint 1 first.
    pub strokes: Vec<(String, f64)>,
    /// Each joint's tool (1-based, in the log's order), joint 1 first.
    pub joint_tools: Vec<usize>,
    /// The robot's sensor count.
    pub sensors: usize,
}

/// One joint's side of a robot import, in the JSON.
#[derive(Debug, Clone, serde::Serialize)]
pub struct JointImportJson {
    /// The joint (1-based, 1 distal).
    pub joint: usize,
    /// Its tool.
    pub tool: usize,
    /// The frame its angle is taken in: `tool N`, `reference tool N` or `rest axis`.
    pub frame: String,
    /// Frames with its tool (or its frame's tool) missing.
    pub missing_frames: usize,
    /// Out-of-plane RMS (°).
    pub out_of_plane_rms_deg: f64,
    /// Out-of-plane maximum (°).
    pub out_of_plane_max_deg: f64,
    /// Rows this joint's angle cannot vouch for.
    pub invalid_rows: usize,
}

/// What a robot import found: the joint import's summary (clocks, check, tracker; its
/// `invalid_rows` counts the rows any joint cannot vouch for) and each joint's.
#[derive(Debug, Clone, serde::Serialize)]
pub struct RobotImportSummary {
    /// The shared summary.
    #[serde(flatten)]
    pub import: ImportSummary,
    /// Per joint, joint 1 first.
    pub joints: Vec<JointImportJson>,
}

impl RobotImportSummary {
    /// The lines `dlw import-recording --design ROBOT` prints, from the summary's numbers.
    pub fn summary(&self) -> String {
        let mut out = self.import.summary();
        for j in &self.joints {
            out.push_str(&format!(
                "joint {}: tool {} in the frame of {}; {} frames missing, out of plane {:.2}° RMS ({:.2}° at most); {} rows without its angle\n",
                j.joint,
                j.tool,
                j.frame,
                j.missing_frames,
                j.out_of_plane_rms_deg,
                j.out_of_plane_max_deg,
                j.invalid_rows
            ));
        }
        out
    }
}

/// The tool named `name` in a tracker log: a number is the tool's place in the log's order
/// (as `--tool`); in NDI's own layout (no map), a name is the port handle a tool block's
/// `PortHandle` column holds on the log's first data row (`Port:3`). A map's tools have no
/// names.
///
/// # Errors
/// [`ImportError::Options`] naming the name and the handles the log holds.
pub fn tool_by_name(
    tracker_text: &str,
    map: Option<&super::TrackerMap>,
    name: &str,
) -> Result<usize, ImportError> {
    let name = name.trim();
    if let Ok(n) = name.parse::<usize>() {
        return Ok(n);
    }
    if map.is_some() {
        return Err(ImportError::Options(format!(
            "tool {name:?}: a tracker map's tools have no names; give the tool's number (its [[tool]] table's place, from 1)"
        )));
    }
    let mut lines = tracker_text.lines().filter(|l| !l.trim().is_empty());
    let cells = |line: Option<&str>| -> Vec<String> {
        line.unwrap_or("")
            .split(',')
            .map(|c| c.trim().to_owned())
            .collect()
    };
    let (header, first) = (cells(lines.next()), cells(lines.next()));
    let handles: Vec<&str> = header
        .iter()
        .enumerate()
        .filter(|(_, h)| h.eq_ignore_ascii_case("PortHandle"))
        .map(|(i, _)| first.get(i).map_or("", String::as_str))
        .collect();
    handles
        .iter()
        .position(|h| h.eq_ignore_ascii_case(name))
        .map(|i| i + 1)
        .ok_or_else(|| {
            ImportError::Options(format!(
                "tool {name:?} is not in the tracker log: its first row's PortHandle columns hold {handles:?} (or give the tool's number, from 1)"
            ))
        })
}

/// Checks the robot's lists against the robot: one voltage per sensor, one stroke and one tool
/// per joint, no tool named twice.
fn check_lists(req: &RobotImportRequest<'_>) -> Result<(), ImportError> {
    let bad = |message: String| Err(ImportError::Options(message));
    let joints = req.joint_tools.len();
    if req.base.voltage_channels.len() != req.sensors {
        return bad(format!(
            "--voltage names {} channels; the robot has {} sensors (one --voltage per sensor, in `dlw inspect`'s sensor order)",
            req.base.voltage_channels.len(),
            req.sensors
        ));
    }
    if req.base.divider_ohm.len() != req.sensors {
        return bad(format!(
            "--divider-ohm gives {} resistors; the robot has {} sensors",
            req.base.divider_ohm.len(),
            req.sensors
        ));
    }
    if req.strokes.len() != joints {
        return bad(format!(
            "--stroke names {} channels; the robot has {joints} joints (one --stroke per joint, joint 1 first)",
            req.strokes.len()
        ));
    }
    let mut tools: Vec<(String, usize)> = req
        .joint_tools
        .iter()
        .enumerate()
        .map(|(k, &t)| (format!("joint {}", k + 1), t))
        .collect();
    tools.extend(
        req.base
            .reference_tool
            .map(|t| ("--reference-tool".into(), t)),
    );
    for (i, (who, t)) in tools.iter().enumerate() {
        if let Some((first, _)) = tools[..i].iter().find(|(_, u)| u == t) {
            return bad(format!(
                "tool {t} is named twice ({first} and {who}): each joint needs its own tool, and the reference tool is none of them"
            ));
        }
    }
    for &(_, k) in &req.strokes {
        if !(k.is_finite() && k != 0.0) {
            return bad(format!(
                "--stroke-mm-per-v {} is not a scale (finite and not 0)",
                crate::limits::short(k)
            ));
        }
    }
    Ok(())
}

/// Runs a robot import: the recording (not yet written) and its summary.
///
/// # Errors
/// [`ImportError`]; a joint's angle that cannot be found as [`ImportError::Joint`].
pub fn import_robot(
    req: &RobotImportRequest<'_>,
) -> Result<(RobotRecording, RobotImportSummary), ImportError> {
    let base = &req.base;
    check_lists(req)?;
    values::check_settings(base)?;
    let strokes: Vec<&str> = req.strokes.iter().map(|(c, _)| c.as_str()).collect();
    let scales: Vec<f64> = req.strokes.iter().map(|&(_, k)| k).collect();
    let columns = DaqColumns::of(base, &strokes);
    let daq = read_daq(base, &columns.names).map_err(|source| ImportError::Daq {
        path: base.daq.0.to_owned(),
        source,
    })?;
    values::check_daq(base, &daq, &columns.names, &scales)?;
    values::check_rate(base, &daq)?;
    let stretches = stretch::stretches(&daq.time_s)?;
    let mut tools = req.joint_tools.clone();
    tools.extend(base.reference_tool);
    let log = read_tracker(base, &tools, columns.sync_column)?;
    refuse_jumps(base, &log, daq.time_s[daq.time_s.len() - 1])?;
    let (angles, frames) = joint_angles(req, &log)?;
    let alignment = clocks(base, &log, &angles[0], &daq, &stretches)?;
    let check = check::check(
        &place::aligned_frames(&log, &angles[0], &alignment.stretches),
        &Signal {
            time_s: &daq.time_s,
            values: &daq.channels[0],
            period_s: stretches.period_s,
        },
    )?;
    let (daq, rate_hz) = match base.rate_hz {
        Some(hz) => (resample::resample(&daq, hz)?, hz),
        None => {
            let hz = daq.rate_hz();
            (daq, hz)
        }
    };
    let stroke_mm: Vec<Vec<f64>> = scales
        .iter()
        .enumerate()
        .map(|(k, scale)| {
            daq.channels[columns.stroke_at + k]
                .iter()
                .map(|v| v * scale)
                .collect()
        })
        .collect();
    let mut angle_deg = Vec::with_capacity(angles.len());
    let mut joint_valid = Vec::with_capacity(angles.len());
    let mut signs = Vec::with_capacity(angles.len());
    for (k, a) in angles.iter().enumerate() {
        let (mut deg, valid) = place::angle_on_daq(&daq.time_s, &log, a, &alignment.stretches);
        let sign = if pulls_positive(&deg, &valid, &stroke_mm[k]) {
            1.0
        } else {
            -1.0
        };
        deg.iter_mut().for_each(|a| *a *= sign);
        angle_deg.push(deg);
        joint_valid.push(valid);
        signs.push(sign);
    }
    let valid: Vec<bool> = (0..daq.time_s.len())
        .map(|i| joint_valid.iter().all(|v| v[i]))
        .collect();
    let invalid_rows = valid.iter().filter(|v| !**v).count();
    let shared = summary(
        &daq.time_s,
        &log,
        &angles[0],
        signs[0],
        &alignment,
        check,
        invalid_rows,
    );
    let joints = joint_summaries(req, &angles, &frames, &joint_valid);
    let missing = most_missing(&joints);
    let mut info = provenance(base, &alignment, shared.tracker.frames, missing);
    info.joint_tools = req.joint_tools.iter().map(|&t| t as u32).collect();
    let rig = Rig {
        sample_hz: rate_hz,
        supply_v: base.supply_v,
        divider_ohm: base.divider_ohm.clone(),
        notes: None,
        protocol: None,
        simulation: None,
        design: None,
        scenario: None,
        import: Some(info),
    };
    let samples = RobotSamples {
        volts: daq.channels[..columns.stroke_at].to_vec(),
        time_s: daq.time_s,
        stroke_mm,
        angle_deg,
        tip_mm: None,
        tracker_valid: if invalid_rows > 0 { valid } else { Vec::new() },
    };
    let recording = RobotRecording { rig, samples };
    recording.check()?;
    let mut import = shared;
    import.tracker.missing_frames = missing;
    import.warnings.extend(super::refused_by_analyses(
        recording.check_measured(Path::new(super::IMPORTED)),
    ));
    Ok((recording, RobotImportSummary { import, joints }))
}

/// The most frames any joint misses.
fn most_missing(joints: &[JointImportJson]) -> usize {
    joints.iter().map(|j| j.missing_frames).max().unwrap_or(0)
}

/// Each joint's bending angles: tool `k` in the frame of tool `k + 1`, the last in the
/// reference tool's (or against its rest axis), and the frames' names. `log.tools` holds the
/// joints' tools, then the reference tool.
fn joint_angles(
    req: &RobotImportRequest<'_>,
    log: &super::TrackerLog,
) -> Result<(Vec<BendingAngles>, Vec<String>), ImportError> {
    let n = req.joint_tools.len();
    let mut angles = Vec::with_capacity(n);
    let mut frames = Vec::with_capacity(n);
    for k in 0..n {
        // log.tools[n] is the reference tool, when there is one.
        let (frame_tool, frame) = if k + 1 < n {
            (Some(k + 1), format!("tool {}", req.joint_tools[k + 1]))
        } else {
            match req.base.reference_tool {
                Some(t) => (Some(n), format!("reference tool {t}")),
                None => (None, "rest axis".to_owned()),
            }
        };
        let a = angle::bending_angles(
            &log.tools[k],
            frame_tool.map(|f| log.tools[f].as_slice()),
            &log.tau_s,
            req.base.rest_s,
        )
        .map_err(|source| ImportError::Joint {
            joint: k + 1,
            tool: req.joint_tools[k],
            frame: frame.clone(),
            source,
        })?;
        angles.push(a);
        frames.push(frame);
    }
    Ok((angles, frames))
}

/// Each joint's JSON.
fn joint_summaries(
    req: &RobotImportRequest<'_>,
    angles: &[BendingAngles],
    frames: &[String],
    valid: &[Vec<bool>],
) -> Vec<JointImportJson> {
    angles
        .iter()
        .enumerate()
        .map(|(k, a)| JointImportJson {
            joint: k + 1,
            tool: req.joint_tools[k],
            frame: frames[k].clone(),
            missing_frames: a.angle_deg.iter().filter(|x| x.is_none()).count(),
            out_of_plane_rms_deg: a.out_of_plane_rms_deg,
            out_of_plane_max_deg: a.out_of_plane_max_deg,
            invalid_rows: valid[k].iter().filter(|v| !**v).count(),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const LOG: &str = "#Tools,ToolInfo,Frame#,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,#Markers,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz\n\
        2,Aurora,1,Port:7,0,OK,1,0,0,0,3,Port:2,0,Missing,,,,\n";

    #[test]
    fn tools_are_found_by_number_or_by_the_logs_port_handle() {
        assert_eq!(tool_by_name(LOG, None, "2").unwrap(), 2);
        assert_eq!(tool_by_name(LOG, None, "Port:7").unwrap(), 1);
        assert_eq!(tool_by_name(LOG, None, " port:2 ").unwrap(), 2);
        let e = tool_by_name(LOG, None, "Port:1").unwrap_err().to_string();
        assert!(e.contains(r#"hold ["Port:7", "Port:2"]"#), "{e}");
        let map = crate::import::TrackerMap::from_toml(
            "header_line = 1\nframe = \"Frame#\"\n[[tool]]\nquaternion = [\"Q0\", \"Qx\", \"Qy\", \"Qz\"]\nmissing = \"empty\"\n",
        )
        .unwrap();
        let e = tool_by_name(LOG, Some(&map), "Port:7")
            .unwrap_err()
            .to_string();
        assert!(e.contains("have no names"), "{e}");
    }
}
