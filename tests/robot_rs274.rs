//! A robot's one program through LinuxCNC's own interpreter (`rs274 -g`), with the checks every
//! joint's program passes (`canon/checks.rs`): sensor, notches, parting in that order, the beam
//! on only while feeding, each operation's power, pulse settings and surface speed (the sensor
//! set's 160 mW at 1 mm/s for every sensor and lead), 32 passes per notch, every notch of every
//! joint cut where the robot's layout draws it, every written point on a drawn line, the parting
//! cut all the way round. rs274 must be installed (`scripts/test.sh`); without it this fails.

use crate::canon;
use crate::common;
use common::designs as common_designs;
use common::{arg, dlw_ok};

use canon::checks::{check, expected};
use canon::{parse, run_rs274};

#[test]
fn shipped_robots_run_in_rs274_and_cut_what_they_draw() {
    for robot in common_designs::robots() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("robot.ngc");
        dlw_ok(&["program", &arg(&robot), "-o", &arg(&out)]);
        let canon = parse(&run_rs274(&out));
        let e = expected(&robot, None);
        let what = robot.file_name().unwrap().to_string_lossy().into_owned();
        check(&canon, &e, &what);
        // Every sensor and lead at the sensor set: 160 mW, 1 mm/s (Table II (a)).
        assert_eq!(e.sets.sensor.power_mw, 160.0, "{what}");
        assert_eq!(e.sets.sensor.scan_speed_mm_s, 1.0, "{what}");
        let sensor_paths: std::collections::BTreeSet<&str> = canon
            .moves
            .iter()
            .filter(|m| m.feed && m.operation == "sensor")
            .map(|m| m.path.as_str())
            .collect();
        let sensors = e.layout.sensor_count();
        assert_eq!(
            sensor_paths.len(),
            sensors,
            "{what}: one written line per sensor"
        );
        // Every joint's notches are cut, named by joint.
        let joints = dlw::robot::CheckedRobot::load(&robot)
            .unwrap()
            .robot
            .joints
            .len();
        for j in 1..=joints {
            assert!(
                canon.moves.iter().any(|m| m.operation == "notches"
                    && m.path.starts_with(&format!("joint {j} notch "))),
                "{what}: no notch of joint {j}"
            );
        }
    }
}
