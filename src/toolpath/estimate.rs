//! Estimated run time of each operation.
//!
//! Beam-on moves take `d/v` (surface distance over the set's scan speed, exact for a stage that
//! follows the program). Rapids take `max(|Δx|/v_x, |ΔA|/v_A)` at the profile's speed limits,
//! ignoring acceleration, so the rapid share is a lower bound. The profile's settle dwell
//! before an operation whose laser parameters differ from the previous one's is counted in
//! that operation (stops count 0: they last as long as the operator takes).

use super::plan::{MoveKind, OperationKind, Plan};
use crate::machine::MachineProfile;

/// Estimated time of one operation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperationTime {
    /// Which operation.
    pub kind: OperationKind,
    /// Time with the beam on (s).
    pub beam_s: f64,
    /// Time on rapids (s).
    pub rapid_s: f64,
    /// Length the beam travels over the surface, all passes (mm).
    pub beam_length_mm: f64,
    /// Dwell before the operation while the source settles (s).
    pub settle_s: f64,
}

impl OperationTime {
    /// Beam-on, rapid and settle time (s).
    pub fn total_s(&self) -> f64 {
        self.beam_s + self.rapid_s + self.settle_s
    }
}

/// Estimates each operation's time, in operation order.
pub fn estimate(plan: &Plan, profile: &MachineProfile) -> Vec<OperationTime> {
    let mut out: Vec<OperationTime> = plan
        .operations
        .iter()
        .enumerate()
        .map(|(i, op)| {
            let prev = i.checked_sub(1).map(|j| &plan.operations[j].process);
            let settle = &profile.settle;
            OperationTime {
                kind: op.kind,
                beam_s: 0.0,
                rapid_s: 0.0,
                beam_length_mm: 0.0,
                settle_s: if settle.needed(prev, &op.process) {
                    settle.estimated_s()
                } else {
                    0.0
                },
            }
        })
        .collect();
    for mv in plan.moves() {
        let op = &plan.operations[mv.operation];
        let t = &mut out[mv.operation];
        match mv.kind {
            MoveKind::Feed => {
                let d = mv.from.surface_distance_mm(&mv.to, plan.outer_radius_mm);
                t.beam_length_mm += d;
                t.beam_s += d / op.process.scan_speed_mm_s;
            }
            MoveKind::Rapid => {
                let tx = (mv.to.x_mm - mv.from.x_mm).abs() / profile.limits.x_speed_max_mm_s;
                let ta = (mv.to.a_rad - mv.from.a_rad).abs().to_degrees()
                    / profile.limits.a_speed_max_deg_s;
                t.rapid_s += tx.max(ta);
            }
        }
    }
    out
}

/// A duration for people: `42 s`, `3 min 05 s`, `1 h 02 min`.
pub fn format_duration(seconds: f64) -> String {
    let s = seconds.round().max(0.0) as u64;
    match s {
        0..=59 => format!("{s} s"),
        60..=3599 => format!("{} min {:02} s", s / 60, s % 60),
        _ => format!("{} h {:02} min", s / 3600, (s % 3600) / 60),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_well() {
        assert_eq!(format_duration(41.6), "42 s");
        assert_eq!(format_duration(185.0), "3 min 05 s");
        assert_eq!(format_duration(3720.0), "1 h 02 min");
    }
}
