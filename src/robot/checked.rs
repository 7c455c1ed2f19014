//! The whole check every command runs on a robot: its file and its joints' own rules, the
//! router, the router's own check of what it drew, the design rules on the robot's layout,
//! the crosstalk and its warnings.

use std::path::Path;

use crate::layout::Layout;
use crate::rules;

use super::assemble::Robot;
use super::crosstalk::{self, CrosstalkFinding, SensorReport};
use super::error::{RobotError, RobotViolation};
use super::property::check_property;
use super::route::route;
use super::sensors::LeadName;
use super::suggest::suggestions;

/// A robot that passed every rule, with its layout, what each sensor reads, and warnings.
#[derive(Debug, Clone)]
pub struct CheckedRobot {
    /// The robot.
    pub robot: Robot,
    /// Its layout: every joint's notches and U-traces, the routed leads, the pad section,
    /// the parting line. Sensor numbers are robot-wide ([`Robot::sensors`]).
    pub layout: Layout,
    /// The name of each lead, in the order of `layout.leads` (and `layout.pads`).
    pub lead_names: Vec<LeadName>,
    /// Rows of pads after row 0 (the last joint's own).
    pub pad_rows: usize,
    /// What each sensor reads, in the order of [`Robot::sensors`].
    pub sensors: Vec<SensorReport>,
    /// Crosstalk above 5 %.
    pub findings: Vec<CrosstalkFinding>,
    /// Warnings to print: each joint's own (named with the joint), then one per crosstalk
    /// above 5 % (without the rotation search: [`Self::warnings_with_advice`]).
    pub warnings: Vec<String>,
}

impl CheckedRobot {
    /// Reads, checks and routes the robot file at `path`.
    ///
    /// # Errors
    /// [`RobotError`] naming the joint, sensor or lead and the rule.
    pub fn load(path: &Path) -> Result<Self, RobotError> {
        Self::from_robot(Robot::load(path)?)
    }

    /// Routes and checks a robot.
    ///
    /// # Errors
    /// [`RobotError::Rules`] listing every robot rule broken.
    pub fn from_robot(robot: Robot) -> Result<Self, RobotError> {
        let refuse = |violations| RobotError::Rules {
            robot: robot.name.clone(),
            violations,
        };
        let routed = route(&robot).map_err(refuse)?;
        let layout = routed.unrolled.wrap();
        // The router's own check: the property, then every layout rule at the robot's
        // clearance. Anything found is a fault of the router, and nothing is drawn.
        let mut found = check_property(&layout);
        found.extend(
            rules::check_layout(&layout, robot.clearance_mm())
                .iter()
                .map(ToString::to_string),
        );
        if !found.is_empty() {
            return Err(refuse(
                found.into_iter().map(RobotViolation::Unsafe).collect(),
            ));
        }
        let sensors = crosstalk::reports(&robot, &layout).map_err(|s| {
            refuse(vec![RobotViolation::Unsafe(format!(
                "{s}'s own U-trace reads no bending of its joint"
            ))])
        })?;
        let findings = crosstalk::findings(&sensors);
        let mut warnings: Vec<String> = Vec::new();
        for (i, j) in robot.joints.iter().enumerate() {
            for w in &j.checked.warnings {
                warnings.push(format!("joint {} ({}): {w}", i + 1, j.design().file.name));
            }
        }
        warnings.extend(suggestions(&robot, &layout, &findings, false));
        Ok(Self {
            robot,
            layout,
            lead_names: routed.lead_names,
            pad_rows: routed.pad_rows,
            sensors,
            findings,
            warnings,
        })
    }

    /// The warnings with, for each crosstalk above 5 %, the rotation that would lower it most
    /// (or that none does), found by routing the robot again with the joint concerned, and the
    /// sensor's own joint, turned in 15° steps: what `dlw inspect` prints. [`Self::warnings`]
    /// has the same findings without that search, which takes a route per joint and step.
    pub fn warnings_with_advice(&self) -> Vec<String> {
        let own: Vec<String> = self
            .warnings
            .iter()
            .take(self.warnings.len() - self.findings.len())
            .cloned()
            .collect();
        own.into_iter()
            .chain(suggestions(&self.robot, &self.layout, &self.findings, true))
            .collect()
    }

    /// The crosstalk matrix `C`: one row per sensor ([`Robot::sensors`]), one column per joint.
    pub fn crosstalk_matrix(&self) -> Vec<Vec<f64>> {
        self.sensors.iter().map(|s| s.crosstalk.clone()).collect()
    }

    /// The largest off-diagonal `|C[i][j]|`: the most any sensor reads of a joint not its own.
    pub fn largest_crosstalk(&self) -> f64 {
        self.crosstalk_matrix()
            .iter()
            .zip(self.robot.sensors())
            .flat_map(|(row, s)| {
                row.iter()
                    .enumerate()
                    .filter(move |(j, _)| *j != s.joint)
                    .map(|(_, v)| v.abs())
            })
            .fold(0.0, f64::max)
    }
}
