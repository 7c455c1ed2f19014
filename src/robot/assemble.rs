//! A robot file made into a [`Robot`]: every joint's design read and checked by its own design
//! rules, the joints checked to share one tube and one set of laser settings, and placed along
//! `x` (joint 1 at the distal end, each next one `gap_mm` after the last notch of the one
//! before).

use std::path::{Path, PathBuf};

use crate::design::{Design, DesignFile};
use crate::layout::Stations;
use crate::rules::{self, Checked};

use super::error::{RobotError, RobotViolation};
use super::file::RobotFile;
use super::sensors::RobotSensor;

/// Largest `|rotation_deg|` accepted.
const MAX_ROTATION_DEG: f64 = 360.0;

/// Two radii closer than this are the same tube (mm).
const SAME_RADIUS_MM: f64 = 1e-9;

/// A validated robot: its joints' checked designs, placed on one tube.
#[derive(Debug, Clone)]
pub struct Robot {
    /// The robot's name.
    pub name: String,
    /// The robot file it was read from.
    pub path: PathBuf,
    /// A checksum of the robot (FNV-1a 64, hex), printed in program headers: of its name and,
    /// per joint, the design's checksum, rotation and gap. A robot of one joint at 0° makes
    /// exactly its joint's part, and carries its joint's checksum.
    pub checksum: String,
    /// The joints, distal first.
    pub joints: Vec<RobotJoint>,
}

/// One joint of a robot, placed on the robot's tube.
#[derive(Debug, Clone)]
pub struct RobotJoint {
    /// The design file, resolved against the robot file's folder.
    pub design_path: PathBuf,
    /// The design, checked by its own rules, with its own layout and warnings.
    pub checked: Checked,
    /// Its bending plane about the tube axis (°), as written.
    pub rotation_deg: f64,
    /// The gap before it (mm); `None` for joint 1.
    pub gap_mm: Option<f64>,
    /// Where each of its features sits along its own `x` ([`Stations`]).
    pub stations: Stations,
    /// Where its own `x = 0` lies on the robot's tube (mm).
    pub offset_mm: f64,
}

impl RobotJoint {
    /// The joint's design.
    pub fn design(&self) -> &Design {
        &self.checked.design
    }

    /// Its rotation (rad).
    pub fn rotation_rad(&self) -> f64 {
        self.rotation_deg.to_radians()
    }

    /// Where its `+y` (its `s = 0`) lies on the robot's tube: `s = r_o·rotation` (mm).
    pub fn rotation_s_mm(&self) -> f64 {
        self.design().file.outer_radius_mm * self.rotation_rad()
    }

    /// Distal edge of its first notch on the robot's tube, the start of its notched (bending)
    /// section (mm).
    pub fn x_start_mm(&self) -> f64 {
        self.offset_mm + self.stations.first_notch_x_mm
    }

    /// Proximal edge of its last notch on the robot's tube (mm).
    pub fn x_end_mm(&self) -> f64 {
        self.offset_mm + self.stations.notched_end_x_mm
    }

    /// Length of its notched section, `L_j = x_end − x_start` (mm).
    pub fn section_length_mm(&self) -> f64 {
        self.x_end_mm() - self.x_start_mm()
    }

    /// Its notched section as the kinematics take it (`docs/robot-runtime.md`).
    pub fn bending_section(&self) -> dlw_geometry::BendingSection {
        dlw_geometry::BendingSection {
            rotation_rad: self.rotation_rad(),
            x_start_mm: self.x_start_mm(),
            x_end_mm: self.x_end_mm(),
        }
    }

    /// Its neutral plane `ȳ` in its own frame (mm).
    pub fn neutral_axis_mm(&self) -> f64 {
        self.design().joint.section().neutral_axis_mm()
    }

    /// Its sensors: 1 (UAN) or 2 (BSN).
    pub fn sensor_count(&self) -> usize {
        self.design().joint.style().sensor_count() as usize
    }

    /// Its style as people write it.
    pub fn style_name(&self) -> &'static str {
        match self.design().joint.style() {
            dlw_geometry::NotchStyle::Uan => "UAN",
            dlw_geometry::NotchStyle::Bsn => "BSN",
        }
    }

    /// A robot `x` from the joint's own (mm); the joint at the distal end keeps its numbers.
    pub(crate) fn x(&self, local_mm: f64) -> f64 {
        if self.offset_mm == 0.0 {
            local_mm
        } else {
            local_mm + self.offset_mm
        }
    }

    /// A robot `s` from the joint's own (mm); a joint at 0° keeps its numbers.
    pub(crate) fn s(&self, local_mm: f64) -> f64 {
        if self.rotation_deg == 0.0 {
            local_mm
        } else {
            local_mm + self.rotation_s_mm()
        }
    }
}

impl Robot {
    /// Reads a robot file and every joint design it names, and checks them.
    ///
    /// # Errors
    /// [`RobotError`] naming the file, the joint and the rule.
    pub fn load(path: &Path) -> Result<Self, RobotError> {
        let file = RobotFile::read(path)?;
        Self::from_file(file, path)
    }

    /// Checks a robot file already read from `path` (the designs are found relative to it).
    ///
    /// # Errors
    /// [`RobotError`] naming the joint and the rule.
    pub fn from_file(file: RobotFile, path: &Path) -> Result<Self, RobotError> {
        let base = path.parent().unwrap_or(Path::new(""));
        let mut violations = Vec::new();
        for (i, entry) in file.joints.iter().enumerate() {
            let r = entry.rotation_deg;
            if !(r.is_finite() && r.abs() <= MAX_ROTATION_DEG) {
                violations.push(RobotViolation::Rotation {
                    joint: i + 1,
                    value: r,
                });
            }
            match (i, entry.gap_mm) {
                (0, Some(gap_mm)) => violations.push(RobotViolation::GapOnFirst { gap_mm }),
                (_, Some(gap_mm)) if !(gap_mm.is_finite() && gap_mm > 0.0) => {
                    violations.push(RobotViolation::BadGap {
                        joint: i + 1,
                        gap_mm,
                    })
                }
                _ => {}
            }
        }
        let mut joints = Vec::with_capacity(file.joints.len());
        for (i, entry) in file.joints.iter().enumerate() {
            let design_path = base.join(&entry.design);
            let design_file =
                DesignFile::read(&design_path).map_err(|source| RobotError::Design {
                    robot: file.name.clone(),
                    joint: i + 1,
                    path: design_path.clone(),
                    source,
                })?;
            let checked =
                rules::check_file(design_file).map_err(|source| RobotError::JointRules {
                    robot: file.name.clone(),
                    joint: i + 1,
                    path: design_path.clone(),
                    source,
                })?;
            if i > 0 && entry.gap_mm.is_none() {
                violations.push(RobotViolation::NoGap {
                    joint: i + 1,
                    name: checked.design.file.name.clone(),
                });
            }
            let stations = Stations::from_design(&checked.design).map_err(|e| {
                // check_file has laid the design out already, so this cannot fail; say so if
                // it does rather than panic.
                RobotError::JointRules {
                    robot: file.name.clone(),
                    joint: i + 1,
                    path: design_path.clone(),
                    source: rules::RulesError {
                        name: checked.design.file.name.clone(),
                        violations: vec![rules::Violation::Layout(e)],
                    },
                }
            })?;
            joints.push(RobotJoint {
                design_path,
                checked,
                rotation_deg: entry.rotation_deg,
                gap_mm: entry.gap_mm,
                stations,
                offset_mm: 0.0,
            });
        }
        violations.extend(same_tube(&joints));
        if !violations.is_empty() {
            return Err(RobotError::Rules {
                robot: file.name,
                violations,
            });
        }
        place(&mut joints);
        let checksum = checksum(&file.name, &joints);
        Ok(Self {
            name: file.name,
            path: path.to_path_buf(),
            checksum,
            joints,
        })
    }

    /// The robot's sensors, by joint, then sensor 1 before 2.
    pub fn sensors(&self) -> Vec<RobotSensor> {
        let mut out = Vec::new();
        for (joint, j) in self.joints.iter().enumerate() {
            for sensor in 0..j.sensor_count() {
                out.push(RobotSensor {
                    index: out.len(),
                    joint,
                    sensor,
                });
            }
        }
        out
    }

    /// The tube's outer radius (mm), shared by every joint.
    pub fn outer_radius_mm(&self) -> f64 {
        self.joints[0].design().file.outer_radius_mm
    }

    /// The tube's inner radius (mm).
    pub fn inner_radius_mm(&self) -> f64 {
        self.joints[0].design().file.inner_radius_mm
    }

    /// The most proximal joint, whose fabrication table governs the pad section.
    pub fn last(&self) -> &RobotJoint {
        &self.joints[self.joints.len() - 1]
    }

    /// The clearance the robot keeps between traces and cuts and between traces (mm): the
    /// joints' (they must agree).
    pub fn clearance_mm(&self) -> f64 {
        self.joints[0].design().file.fabrication.clearance_mm()
    }
}

/// Every joint on joint 1's tube and with joint 1's laser settings.
fn same_tube(joints: &[RobotJoint]) -> Vec<RobotViolation> {
    let mut out = Vec::new();
    let Some(first) = joints.first() else {
        return out;
    };
    let f = &first.design().file;
    for (i, j) in joints.iter().enumerate().skip(1) {
        let d = &j.design().file;
        let tube =
            |quantity: &'static str, value: String, first_value: String| RobotViolation::Tube {
                joint: i + 1,
                name: d.name.clone(),
                first: f.name.clone(),
                quantity,
                value,
                first_value,
            };
        if (d.outer_radius_mm - f.outer_radius_mm).abs() > SAME_RADIUS_MM {
            out.push(tube(
                "outer radius",
                format!("{} mm", d.outer_radius_mm),
                format!("{} mm", f.outer_radius_mm),
            ));
        }
        if (d.inner_radius_mm - f.inner_radius_mm).abs() > SAME_RADIUS_MM {
            out.push(tube(
                "inner radius",
                format!("{} mm", d.inner_radius_mm),
                format!("{} mm", f.inner_radius_mm),
            ));
        }
        if d.materials.tube != f.materials.tube {
            out.push(tube(
                "material",
                d.materials.tube.name().into(),
                f.materials.tube.name().into(),
            ));
        }
        let laser =
            |quantity: &'static str, value: String, first_value: String| RobotViolation::Laser {
                joint: i + 1,
                name: d.name.clone(),
                first: f.name.clone(),
                quantity,
                value,
                first_value,
            };
        let (df, ff) = (&d.fabrication, &f.fabrication);
        for (quantity, a, b) in [
            ("trace_width_mm", df.trace_width_mm, ff.trace_width_mm),
            ("kerf_mm", df.kerf_mm, ff.kerf_mm),
            ("clearance", df.clearance_mm(), ff.clearance_mm()),
        ] {
            if a != b {
                out.push(laser(quantity, format!("{a} mm"), format!("{b} mm")));
            }
        }
        if d.process != f.process {
            out.push(laser(
                "the process sets",
                format!("{:?}", d.process),
                format!("{:?}", f.process),
            ));
        }
    }
    out
}

/// Places the joints: joint 1's own `x = 0` at the tube's end, each next one so that its first
/// notch lies `gap_mm` after the previous joint's last notch.
fn place(joints: &mut [RobotJoint]) {
    let mut prev_end: Option<f64> = None;
    for j in joints.iter_mut() {
        if let (Some(end), Some(gap)) = (prev_end, j.gap_mm) {
            j.offset_mm = end + gap - j.stations.first_notch_x_mm;
        }
        prev_end = Some(j.x_end_mm());
    }
}

/// The robot's checksum (see [`Robot::checksum`]).
fn checksum(name: &str, joints: &[RobotJoint]) -> String {
    if let [only] = joints {
        if only.rotation_deg == 0.0 {
            return only.design().checksum.clone();
        }
    }
    let mut text = format!("robot {name:?}\n");
    for j in joints {
        text.push_str(&format!(
            "joint {} rotation_deg {} gap_mm {:?}\n",
            j.design().checksum,
            j.rotation_deg,
            j.gap_mm
        ));
    }
    format!("{:016x}", crate::design::fnv1a64(text.as_bytes()))
}
