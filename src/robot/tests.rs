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
