//! Which sensor and which lead: the robot's typed identities. Sensors are numbered robot-wide
//! by joint, then sensor 1 before 2 (the order of `dlw inspect ROBOT --json`'s `sensors`, and
//! the sensor number in the DXF's XDATA); people read them 1-based.

use std::fmt;

use serde::Serialize;

/// One sensor of the robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct RobotSensor {
    /// Robot-wide index, 0-based (the layout's `Trace::sensor`).
    pub index: usize,
    /// Its joint, 0-based (joint 0 is the distal one).
    pub joint: usize,
    /// Within its joint, 0-based: 0 for the `+y_s` sensor, 1 for BSN's `−y_s` sensor.
    pub sensor: usize,
}

impl fmt::Display for RobotSensor {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "joint {} sensor {}", self.joint + 1, self.sensor + 1)
    }
}

/// Which arm of its sensor a lead leaves from: A at the smaller `s`, B at the larger.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum Arm {
    /// Arm A (smaller `s`), whose pad lies below in a joint's own layout.
    A,
    /// Arm B (larger `s`).
    B,
}

/// One lead of the robot: from a sensor's arm end to its pad.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub struct LeadName {
    /// Its sensor.
    pub sensor: RobotSensor,
    /// Its arm.
    pub arm: Arm,
}

impl fmt::Display for LeadName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let arm = match self.arm {
            Arm::A => "A",
            Arm::B => "B",
        };
        write!(f, "{} lead {arm}", self.sensor)
    }
}

/// Names a list of leads for a message: `joint 1 sensor 1 leads A and B, joint 2 sensor 1 lead A`.
pub(crate) fn list_leads(leads: &[LeadName]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < leads.len() {
        let l = leads[i];
        let pair = leads
            .get(i + 1)
            .filter(|m| m.sensor == l.sensor && m.arm != l.arm);
        if pair.is_some() {
            parts.push(format!("{} leads A and B", l.sensor));
            i += 2;
        } else {
            parts.push(l.to_string());
            i += 1;
        }
    }
    parts.join(", ")
}
