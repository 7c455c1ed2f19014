//! `dlw fit --design ROBOT REC` from a tracked tip alone (issue 34 §4): the joint angles by
//! inverse kinematics, each sample checked (identifiable, unambiguous, on the kinematics), then
//! the same closed-form fit as on recorded angles. On the simulator's robot and on a generator
//! written here (its own forward kinematics, isotropic tip noise, glitches), and the robots and
//! recordings the tip cannot identify refused by name.

// Index loops over joints and sensors read as the matrix formulas they check.
#![allow(clippy::needless_range_loop)]

use crate::common;

use std::path::{Path, PathBuf};

use common::{arg, dlw, dlw_ok, rng};

fn designs() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("designs")
}

/// Empties every `angleK_deg` field of a robot recording of `joints` joints, so that only the
/// tip remains.
fn blank_angles(rec: &Path, joints: usize) {
    let path = rec.join("data.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut out = String::with_capacity(text.len());
    for (i, line) in text.lines().enumerate() {
        if i == 0 {
            out.push_str(line);
        } else {
            let fields: Vec<&str> = line
                .split(',')
                .enumerate()
                .map(|(c, f)| {
                    if (1 + joints..1 + 2 * joints).contains(&c) {
                        ""
                    } else {
                        f
                    }
                })
                .collect();
            out.push_str(&fields.join(","));
        }
        out.push('\n');
    }
    std::fs::write(&path, out).unwrap();
}

fn fit_json(robot: &Path, rec: &Path, cfg: &Path) -> serde_json::Value {
    let o = dlw_ok(&[
        "fit",
        "--design",
        &arg(robot),
        &arg(rec),
        "--model",
        "linear",
        "-o",
        &arg(cfg),
        "--json",
    ]);
    serde_json::from_slice(&o.stdout).unwrap()
}

fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn simulate(robot: &Path, rec: &Path, seconds: &str) {
    dlw_ok(&[
        "simulate",
        "--design",
        &arg(robot),
        "--protocol",
        "random",
        "--duration-s",
        seconds,
        "-o",
        &arg(rec),
    ]);
}

/// The simulator's Robot BC (joints in perpendicular planes), its angle columns blanked: the
/// fit from the tip gives the fit from the recorded angles back, within the 1 % and 0.02 the
/// fit promises.
#[test]
fn the_tip_alone_fits_what_the_joint_angles_fit_on_the_simulated_robot() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bc.toml");
    let rec = d.join("rec");
    simulate(&robot, &rec, "30");
    let joints = fit_json(&robot, &rec, &d.join("joints.toml"));
    assert_eq!(joints["angles_from"], "joints", "{joints}");
    assert!(joints.get("tip_angles").is_none(), "{joints}");
    blank_angles(&rec, 2);
    let tip = fit_json(&robot, &rec, &d.join("tip.toml"));
    eprintln!("joints: {joints}\ntip: {tip}");
    assert_eq!(tip["angles_from"], "tip", "{tip}");
    let t = &tip["tip_angles"];
    let rows = t["rows"].as_u64().unwrap();
    let used = t["used"].as_u64().unwrap();
    let dropped: u64 = [
        "dropped_not_identifiable",
        "dropped_ambiguous",
        "dropped_off_kinematics",
    ]
    .iter()
    .map(|k| t[k].as_u64().unwrap())
    .sum();
    assert_eq!(used + dropped, rows, "{t}");
    assert!(used as f64 > 0.5 * rows as f64, "{t}");
    // The simulator's tip is the kinematics of its tracked angles: never off them.
    assert_eq!(t["dropped_off_kinematics"], 0, "{t}");
    assert_eq!(tip["samples_fitted"].as_u64().unwrap(), used);
    for (a, b) in joints["sensors"]
        .as_array()
        .unwrap()
        .iter()
        .zip(tip["sensors"].as_array().unwrap())
    {
        let (ga, gb) = (
            a["gauge_factor"].as_f64().unwrap(),
            b["gauge_factor"].as_f64().unwrap(),
        );
        assert!((gb / ga - 1.0).abs() < 0.01, "GF {gb} vs {ga}");
        for (ca, cb) in numbers(&a["crosstalk"])
            .iter()
            .zip(numbers(&b["crosstalk"]))
        {
            assert!((ca - cb).abs() < 0.02, "crosstalk {cb} vs {ca}");
        }
    }
    // The config written from the tip is one estimate runs.
    dlw_ok(&[
        "estimate",
        "--config",
        &arg(&d.join("tip.toml")),
        &arg(&rec),
    ]);
}

/// The test's own generator for Robot BC: angles as sums of sines, its own forward kinematics
/// (arcs composed from `dlw inspect`'s sections, rotations written out here), isotropic
/// Gaussian tip noise, a few tracker glitches, and sensors with gauge factors and crosstalk of
/// its own.
struct Generator {
    gauge_factor: [f64; 3],
    r0_ohm: [f64; 3],
    /// One row per sensor (joint 1's, then joint 2's sensors 1 and 2), one entry per joint.
    crosstalk: [[f64; 2]; 3],
}

const GENERATOR: Generator = Generator {
    gauge_factor: [14.6, 11.2, 9.7],
    r0_ohm: [205e3, 96e3, 121e3],
    crosstalk: [[1.0, 0.06], [-0.045, 1.0], [0.05, 1.0]],
};

/// A joint's section as `dlw inspect --json` reports it.
struct Section {
    rotation_rad: f64,
    x_start_mm: f64,
    x_end_mm: f64,
    strain_per_rad: f64,
}

fn sections(robot: &Path) -> Vec<Section> {
    let o = dlw_ok(&["inspect", &arg(robot), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    v["joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|j| Section {
            rotation_rad: j["rotation_deg"].as_f64().unwrap().to_radians(),
            x_start_mm: j["x_start_mm"].as_f64().unwrap(),
            x_end_mm: j["x_end_mm"].as_f64().unwrap(),
            strain_per_rad: j["strain_per_deg"].as_f64().unwrap().to_degrees(),
        })
        .collect()
}

type M3 = [[f64; 3]; 3];

fn mat_mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    c
}

fn apply(a: &M3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|k| a[i][k] * v[k]).sum())
}

/// Rodrigues' rotation by `angle` about the unit `axis`.
fn rotation(axis: [f64; 3], angle: f64) -> M3 {
    let (s, c) = angle.sin_cos();
    let [x, y, z] = axis;
    let t = 1.0 - c;
    [
        [c + x * x * t, x * y * t - z * s, x * z * t + y * s],
        [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
        [z * x * t - y * s, z * y * t + x * s, c + z * z * t],
    ]
}

/// The tip from the base (the most proximal x_end, z toward the tip): each arc of angle θ
/// bends toward −y_j, y_j = (−sin r, cos r, 0), turning the tangent about x_j = (cos r, sin r,
/// 0); straight tube between the arcs and after joint 1 to x = 0.
fn tip(sections: &[Section], theta: &[f64]) -> [f64; 3] {
    let mut p = [0.0; 3];
    let mut r: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for j in (0..sections.len()).rev() {
        let s = &sections[j];
        let (l, t) = (s.x_end_mm - s.x_start_mm, theta[j]);
        let y = [-s.rotation_rad.sin(), s.rotation_rad.cos(), 0.0];
        let (side, along) = if t.abs() < 1e-9 {
            (0.0, l)
        } else {
            (l * (1.0 - t.cos()) / t, l * t.sin() / t)
        };
        let local = [-y[0] * side, -y[1] * side, along];
        let moved = apply(&r, local);
        p = std::array::from_fn(|i| p[i] + moved[i]);
        r = mat_mul(
            &r,
            &rotation([s.rotation_rad.cos(), s.rotation_rad.sin(), 0.0], t),
        );
        let next_end = if j == 0 {
            0.0
        } else {
            sections[j - 1].x_end_mm
        };
        let straight = apply(&r, [0.0, 0.0, s.x_start_mm - next_end]);
        p = std::array::from_fn(|i| p[i] + straight[i]);
    }
    p
}

/// Writes the generator's recording of Robot BC: `noise_mm` of tip noise per coordinate, a
/// tip glitch of `glitch_mm` every 400th row, the tip shifted by `offset_mm` (a tracker not
/// registered to the base frame).
fn write_generated(dir: &Path, sections: &[Section], noise_mm: f64, offset_mm: [f64; 3]) {
    let mut rng = rng::Rng::new(341);
    let hz = 100.0;
    let rows = 4000;
    let divider = 99.6e3;
    let supply = 5.0;
    let mut csv = String::from(
        "time_s,stroke1_mm,stroke2_mm,angle1_deg,angle2_deg,v1_V,v2_V,v3_V,tip_x_mm,tip_y_mm,tip_z_mm\n",
    );
    // Sensor i's joint and sign (joint 2's sensor 2 is on the compression side).
    let own = [(0usize, 1.0f64), (1, 1.0), (1, -1.0)];
    for k in 0..rows {
        let t = k as f64 / hz;
        let tau = std::f64::consts::TAU;
        let theta = [
            0.38 * (tau * 0.11 * t).sin() + 0.14 * (tau * 0.53 * t + 1.0).sin(),
            0.32 * (tau * 0.17 * t + 2.0).sin() + 0.1 * (tau * 0.67 * t + 0.5).sin(),
        ];
        csv.push_str(&format!("{t:.6},{:.6},{:.6},,", theta[0], theta[1]));
        for i in 0..3 {
            let (j, sign) = own[i];
            let a: f64 = (0..2).map(|m| GENERATOR.crosstalk[i][m] * theta[m]).sum();
            let strain = sign * sections[j].strain_per_rad * a;
            let r = GENERATOR.r0_ohm[i] * (1.0 + GENERATOR.gauge_factor[i] * strain);
            let v = supply * r / (r + divider) + 1e-3 * (rng.uniform() - 0.5);
            csv.push_str(&format!(",{v:.6}"));
        }
        let p = tip(sections, &theta);
        let glitch = if k % 400 == 17 { 5.0 } else { 0.0 };
        for c in 0..3 {
            let value = p[c] + offset_mm[c] + noise_mm * rng.normal() + glitch;
            csv.push_str(&format!(",{value:.6}"));
        }
        csv.push('\n');
    }
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("data.csv"), csv).unwrap();
    std::fs::write(
        dir.join("rig.toml"),
        format!("sample_hz = {hz}\nsupply_v = {supply}\ndivider_ohm = [{divider}, {divider}, {divider}]\nnotes = \"written by the tip test's generator\"\n"),
    )
    .unwrap();
}

#[test]
fn the_tip_alone_recovers_another_generators_gauge_factors_and_crosstalk() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bc.toml");
    let sections = sections(&robot);
    let rec = d.join("rec");
    write_generated(&rec, &sections, 0.03, [0.0; 3]);
    let v = fit_json(&robot, &rec, &d.join("cfg.toml"));
    eprintln!("{v}");
    assert_eq!(v["angles_from"], "tip", "{v}");
    let t = &v["tip_angles"];
    // The ten glitches, and nothing else, are off the kinematics.
    assert_eq!(t["dropped_off_kinematics"], 10, "{t}");
    // The noise measured on the recording is the generator's (the motion adds a little).
    let noise = t["tip_noise_mm"].as_f64().unwrap();
    assert!((0.028..0.036).contains(&noise), "{noise}");
    for (i, s) in v["sensors"].as_array().unwrap().iter().enumerate() {
        let gf = s["gauge_factor"].as_f64().unwrap();
        let want = GENERATOR.gauge_factor[i];
        assert!(
            (gf / want - 1.0).abs() < 0.01,
            "sensor {}: GF {gf} vs {want}",
            i + 1
        );
        let r0 = s["r0_ohm"].as_f64().unwrap();
        assert!((r0 / GENERATOR.r0_ohm[i] - 1.0).abs() < 0.01, "R0 {r0}");
        for (j, c) in numbers(&s["crosstalk"]).iter().enumerate() {
            let want = GENERATOR.crosstalk[i][j];
            assert!(
                (c - want).abs() < 0.02,
                "sensor {} crosstalk[{j}] {c} vs {want}",
                i + 1
            );
        }
    }
    // A tracker 4 mm off the base frame: refused, naming the share off the kinematics.
    let shifted = d.join("shifted");
    write_generated(&shifted, &sections, 0.03, [4.0, 0.0, 0.0]);
    let cfg = d.join("shifted.toml");
    let o = dlw(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&shifted),
        "-o",
        &arg(&cfg),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("off the robot's kinematics") && err.contains("base frame"),
        "{err}"
    );
    assert!(!cfg.exists(), "no partial output");
}

/// Two joints bending in one plane (Joint B, and Joint C turned 180°): the tip cannot tell
/// their angles apart, and the fit says so before reading a sample.
#[test]
fn a_robot_whose_joints_bend_in_one_plane_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = d.join("robot-planar.toml");
    std::fs::write(
        &robot,
        format!(
            "name = \"Robot planar\"\n[[joint]]\ndesign = {:?}\nrotation_deg = 0.0\n[[joint]]\ndesign = {:?}\nrotation_deg = 180.0\ngap_mm = 3.0\n",
            designs().join("joint-b.toml"),
            designs().join("joint-c.toml"),
        ),
    )
    .unwrap();
    let rec = d.join("rec");
    simulate(&robot, &rec, "5");
    blank_angles(&rec, 2);
    let cfg = d.join("cfg.toml");
    let o = dlw(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&rec),
        "-o",
        &arg(&cfg),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("joints 1 and 2 bend in one plane (rotations 0° and 180°)")
            && err.contains("cannot tell their angles apart"),
        "{err}"
    );
    assert!(!cfg.exists(), "no partial output");
}

/// A recording with neither angles nor a tip has nothing to fit against.
#[test]
fn neither_angles_nor_a_tip_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bc.toml");
    let rec = d.join("rec");
    simulate(&robot, &rec, "2");
    blank_angles(&rec, 2);
    // Drop the three tip columns.
    let path = rec.join("data.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    let cut: String = text
        .lines()
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            format!("{}\n", f[..f.len() - 3].join(","))
        })
        .collect();
    std::fs::write(&path, cut).unwrap();
    let o = dlw(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&rec),
        "-o",
        &arg(&d.join("cfg.toml")),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("neither per-joint angles") && err.contains("tip_x_mm"),
        "{err}"
    );
}

/// Robot BDB's three joints, 120° apart: at the straight pose all three move the tip sideways
/// only (2 directions for 3 angles), and over the simulator's random motion (±50°) the tip
/// Jacobian's smallest singular value stays under a tenth of its largest, as the test's own
/// kinematics compute, so no row is identifiable and the fit refuses, with the numbers.
#[test]
fn robot_bdb_cannot_be_identified_from_its_tip_and_the_fit_says_why() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let robot = designs().join("robot-bdb.toml");
    let sections = sections(&robot);
    let rec = d.join("rec");
    simulate(&robot, &rec, "6");
    // The largest singular value ratio over the recorded angles, by the test's kinematics.
    let text = std::fs::read_to_string(rec.join("data.csv")).unwrap();
    let mut largest = 0.0f64;
    for line in text.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        let theta: Vec<f64> = f[4..7].iter().map(|a| a.to_radians()).collect();
        let mut j = nalgebra::Matrix3::zeros();
        for c in 0..3 {
            let (mut plus, mut minus) = (theta.clone(), theta.clone());
            plus[c] += 1e-6;
            minus[c] -= 1e-6;
            let (p, m) = (tip(&sections, &plus), tip(&sections, &minus));
            for r in 0..3 {
                j[(r, c)] = (p[r] - m[r]) / 2e-6;
            }
        }
        let sv = j.singular_values();
        largest = largest.max(sv.min() / sv.max());
    }
    assert!(largest < 0.1, "{largest}");
    blank_angles(&rec, 3);
    let cfg = d.join("cfg.toml");
    let o = dlw(&[
        "fit",
        "--design",
        &arg(&robot),
        &arg(&rec),
        "-o",
        &arg(&cfg),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    eprintln!("{err}");
    assert!(
        err.contains("0 of 3000 tracked rows gave usable angles, at least 40 needed"),
        "{err}"
    );
    assert!(err.contains("not identifiable"), "{err}");
    assert!(!cfg.exists(), "no partial output");
}
