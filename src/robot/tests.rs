use std::path::{Path, PathBuf};

use super::*;

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

#[test]
fn robots_route_and_print() {
    for f in ["robot-bc.toml", "robot-bdb.toml"] {
        let r = CheckedRobot::load(&designs().join(f)).unwrap();
        let i = RobotInspection::of(&r);
        println!("{}", serde_json::to_string_pretty(&i).unwrap());
        for l in &r.layout.leads {
            println!("lead sensor {}: {:?}", l.sensor, l.pieces);
        }
    }
}

/// A robot of one joint at 0° lays out exactly as the joint: the router's own leads, the pads
/// and the parting line reduce to the joint's (the files are compared byte for byte in
/// `tests/robot_cli.rs`).
#[test]
fn a_one_joint_robot_lays_out_as_its_joint() {
    for j in ["a", "b", "c", "d"] {
        let path = designs().join(format!("joint-{j}.toml"));
        let dir = tempfile::tempdir().unwrap();
        let robot = dir.path().join("one.toml");
        std::fs::write(
            &robot,
            format!(
                "name = \"one\"\n[[joint]]\ndesign = {:?}\nrotation_deg = 0.0\n",
                path.display().to_string()
            ),
        )
        .unwrap();
        let r = CheckedRobot::load(&robot).unwrap();
        let mut own = r.robot.joints[0].checked.layout.clone();
        own.name = "one".into();
        assert!(
            r.layout == own,
            "joint {j}: {:?}",
            r.layout.max_difference_mm(&own)
        );
        assert_eq!(r.robot.checksum, r.robot.joints[0].design().checksum);
    }
}

/// A one-joint robot turned by 90° is its joint turned: every `s` moved by `r_o·π/2`.
#[test]
fn a_turned_one_joint_robot_is_its_joint_turned() {
    let path = designs().join("joint-c.toml");
    let dir = tempfile::tempdir().unwrap();
    let robot = dir.path().join("one.toml");
    std::fs::write(
        &robot,
        format!(
            "name = \"one\"\n[[joint]]\ndesign = {:?}\nrotation_deg = 90.0\n",
            path.display().to_string()
        ),
    )
    .unwrap();
    let r = CheckedRobot::load(&robot).unwrap();
    let own = &r.robot.joints[0].checked.layout;
    let c = own.circumference_mm;
    let shift = 0.8 * std::f64::consts::FRAC_PI_2;
    let centre = |t: &crate::layout::Trace| {
        let p = t.pieces[0].0[0];
        (p.x, p.y)
    };
    for (a, b) in r.layout.sensors.iter().zip(&own.sensors) {
        let ((xa, sa), (xb, sb)) = (centre(a), centre(b));
        assert!((xa - xb).abs() < 1e-12);
        let ds = (sa - sb - shift).rem_euclid(c);
        assert!(ds < 1e-9 || c - ds < 1e-9, "{sa} {sb}");
    }
    assert_ne!(r.robot.checksum, r.robot.joints[0].design().checksum);
}
