//! `dlw build` for a five-joint robot, in process: the robot file and its five joint designs
//! read and checked by their own rules, the leads routed, the router's own check and the layout
//! rules on the routed robot, the crosstalk, then the DXF, the robot sheet, five section sheets,
//! the program (planned, checked, posted) and the setup sheet. Only writing the folder is left
//! out. Target (issue 33): within 200 ms.
//!
//! The robot: five copies of Joint A (the paper's 2.5 mm tube) turned 0°, 72°, 144°, 216° and
//! 288°, 3 mm apart; eight leads cross the last joint.
//!
//! `cargo bench --bench robot`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::machine::MachineLibrary;
use dlw::process::ProcessLibrary;
use dlw::robot::CheckedRobot;

/// Writes the five-joint robot file into `dir` and returns its path.
fn robot_file(dir: &std::path::Path) -> std::path::PathBuf {
    let a = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/joint-a.toml");
    let mut text = String::from("name = \"Five A\"\n");
    for (i, rotation) in [0.0, 72.0, 144.0, 216.0, 288.0].iter().enumerate() {
        text.push_str(&format!(
            "[[joint]]\ndesign = {:?}\nrotation_deg = {rotation}\n",
            a.display().to_string()
        ));
        if i > 0 {
            text.push_str("gap_mm = 3.0\n");
        }
    }
    let path = dir.join("five.toml");
    std::fs::write(&path, text).expect("temp folder is writable");
    path
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp folder");
    let path = robot_file(dir.path());
    let designs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("designs/robot-bc.toml");
    let profile = MachineLibrary::beside(&designs)
        .find(None)
        .expect("profile");
    let build = || {
        let robot = CheckedRobot::load(&path).expect("the five-joint robot routes");
        let sets = ProcessLibrary::beside(&designs)
            .resolve(&robot.robot.joints[0].design().file.process)
            .expect("process sets");
        dlw::build::robot_files::build_files(&robot, "five", &sets, &profile).expect("files")
    };
    let files = build();
    eprintln!(
        "five-joint robot: {} files, {} bytes",
        files.len(),
        files.iter().map(|(_, b)| b.len()).sum::<usize>()
    );
    let robot = CheckedRobot::load(&path).expect("routes");
    c.bench_function("robot_build_five_joints", |b| b.iter(build));
    c.bench_function("robot_route_and_check_five_joints", |b| {
        b.iter(|| CheckedRobot::from_robot(robot.robot.clone()).expect("routes"))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
