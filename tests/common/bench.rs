//! The bench of the import tests, written from a known truth with this module's own generator:
//! a DAQ's CSV export (time, a linear sensor's voltage, a noise channel, a stroke voltage, a PI
//! sensor's voltage) and an NDI Aurora log (CSV, NDI Track's columns with `ToolInfo`, `Port:1`
//! handles and `Missing` frames): a stroke pattern, an angle that follows it with a 30 ms lag,
//! a linear sensor and a hysteretic (PI) one, a tracker at 40 Hz whose clock is 0.437 s late
//! and runs 250 ppm fast, 1.1 % of its frames missing in bursts, a tracker frame turned against
//! the joint's, a 5-DOF tip tool (its roll is noise) and a 6-DOF reference tool on the base
//! that moves. `tests/import_recording.rs` holds the acceptance figures; the faults of issue 30
//! are made from it in `tests/import_faults.rs`.
#![allow(dead_code)]

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

use dlw::design::Design;
use dlw_geometry::Divider;

use super::shipped_design;

pub const DAQ_HZ: f64 = 500.0;
pub const TRACKER_HZ: f64 = 40.0;
pub const OFFSET_S: f64 = 0.437;
pub const DRIFT_PPM: f64 = 250.0;
pub const DURATION_S: f64 = 240.0;
pub const REST_S: f64 = 5.0;
pub const GF: f64 = 15.3;
pub const R0: f64 = 215e3;
pub const DIVIDER: f64 = 99.6e3;
pub const SUPPLY_V: f64 = 5.0;
pub const MM_PER_V: f64 = 0.5;
pub const GAIN_DEG_PER_MM: f64 = 33.0;
pub const LAG_S: f64 = 0.03;
/// The PI sensor (channel AI3): its unstrained resistance (Ω), and the gauge factor that
/// scales its hysteretic strain response.
pub const PI_R0: f64 = 180e3;
pub const PI_GF: f64 = 12.0;
/// The PI sensor's response, in strain: `PI_LINEAR_WEIGHT·ε + Σ wᵢ·playᵢ(ε)` with the play
/// radii as shares of [`PI_RADIUS_STRAIN`] and their weights.
pub const PI_LINEAR_WEIGHT: f64 = 0.5;
pub const PI_PLAYS: [(f64, f64); 3] = [(0.15, 0.25), (0.35, 0.15), (0.6, 0.1)];
/// The strain the play radii are shares of (about a third of the bench's strain range).
pub const PI_RADIUS_STRAIN: f64 = 0.004;

/// The bench's tools: whether the tip is a 5-DOF sensor (its roll about z is arbitrary: here
/// a random angle each frame) and whether the base, with the 6-DOF reference tool, sways.
#[derive(Clone, Copy)]
pub struct Tools {
    /// The tip tool is 5-DOF: its roll about z is a random angle every frame.
    pub tip_5dof: bool,
    /// The base (with the reference tool) sways by 3°.
    pub reference_moves: bool,
}

/// A 6-DOF tip on a still base.
pub const STILL_6DOF: Tools = Tools {
    tip_5dof: false,
    reference_moves: false,
};
/// A 5-DOF tip on a still base.
pub const STILL_5DOF: Tools = Tools {
    tip_5dof: true,
    reference_moves: false,
};

/// A hysteretic sensor: the strain through a linear term and play operators, each
/// `y ← clamp(y, ε − r, ε + r)`.
struct PiSensor {
    plays: Vec<f64>,
}
impl PiSensor {
    fn new() -> Self {
        PiSensor {
            plays: vec![0.0; PI_PLAYS.len()],
        }
    }
    /// The resistance (Ω) at the next strain.
    fn ohm(&mut self, strain: f64) -> f64 {
        let mut response = PI_LINEAR_WEIGHT * strain;
        for (y, (share, weight)) in self.plays.iter_mut().zip(PI_PLAYS) {
            let r = share * PI_RADIUS_STRAIN;
            *y = y.clamp(strain - r, strain + r);
            response += weight * *y;
        }
        PI_R0 * (1.0 + PI_GF * response)
    }
}
/// A small deterministic generator (xorshift), independent of the simulator's.
pub struct Rng(pub u64);
impl Rng {
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform().max(1e-12), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

/// The true angle (°) at DAQ time `t`: rest, then smooth ramps between random levels.
pub struct Truth {
    knots: Vec<(f64, f64)>,
}
impl Truth {
    fn new(rng: &mut Rng) -> Self {
        let mut knots = vec![(0.0, 0.0), (REST_S, 0.0)];
        let mut t = REST_S;
        while t < DURATION_S + 10.0 {
            t += 1.5 + 4.0 * rng.uniform();
            knots.push((
                t,
                1.2 * (1.0 - 0.0) * 30.0 * rng.uniform() / GAIN_DEG_PER_MM,
            ));
            t += 2.0 * rng.uniform();
            let level = knots.last().unwrap().1;
            knots.push((t, level));
        }
        Truth { knots }
    }
    /// Stroke (mm) at `t`, cosine-eased between knots.
    pub fn stroke(&self, t: f64) -> f64 {
        let i = self
            .knots
            .partition_point(|k| k.0 <= t)
            .clamp(1, self.knots.len() - 1);
        let ((t0, a), (t1, b)) = (self.knots[i - 1], self.knots[i]);
        let f = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        a + (b - a) * (1.0 - (PI * f).cos()) / 2.0
    }
    /// The joint's angle: the stroke's, `LAG_S` later.
    pub fn angle_deg(&self, t: f64) -> f64 {
        GAIN_DEG_PER_MM * self.stroke(t - LAG_S)
    }
}

/// Unit quaternion of a rotation by `angle` about unit `axis`.
pub fn quat(axis: [f64; 3], angle: f64) -> [f64; 4] {
    let (s, c) = (angle / 2.0).sin_cos();
    [c, axis[0] * s, axis[1] * s, axis[2] * s]
}

pub fn mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ]
}

/// Writes `daq.csv` and `aurora.csv` of [`DURATION_S`] into `dir`; returns the truth.
pub fn write_bench(dir: &Path, tools: Tools) -> Truth {
    write_bench_for(dir, tools, DURATION_S)
}

/// Writes `daq.csv` and `aurora.csv` of `duration_s` (at most [`DURATION_S`]) into `dir`;
/// returns the truth.
pub fn write_bench_for(dir: &Path, tools: Tools, duration_s: f64) -> Truth {
    write_bench_with(dir, tools, duration_s, OFFSET_S, DRIFT_PPM)
}

/// [`write_bench_for`] with the tracker's clock `offset_s` late and `drift_ppm` fast.
pub fn write_bench_with(
    dir: &Path,
    tools: Tools,
    duration_s: f64,
    offset_s: f64,
    drift_ppm: f64,
) -> Truth {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    // The PI sensor's noise and the 5-DOF roll draw from their own stream, so that the rest of
    // the bench is the same realization with them as without.
    let mut extra = Rng(0x5eed_5678_ef01_0002);
    let truth = Truth::new(&mut rng);
    let joint = Design::load(Path::new(&shipped_design("joint-a.toml")))
        .unwrap()
        .joint;
    let divider = Divider {
        fixed_ohm: DIVIDER,
        supply_v: SUPPLY_V,
    };
    let mut daq = String::from("Time,AI0,AI1,AI2,AI3\n");
    let n = (duration_s * DAQ_HZ) as usize;
    let mut pi = PiSensor::new();
    for i in 0..n {
        let t = i as f64 / DAQ_HZ;
        let strain = joint.strain(truth.angle_deg(t).to_radians());
        let v1 = divider.voltage(R0 * (1.0 + GF * strain)) + 0.0005 * rng.normal();
        let v_stroke = truth.stroke(t) / MM_PER_V + 0.0005 * rng.normal();
        let v_pi = divider.voltage(pi.ohm(strain)) + 0.0005 * extra.normal();
        // A channel the import does not use, between the two it does.
        writeln!(
            daq,
            "{t:.4},{v1:.6},{:.4},{v_stroke:.6},{v_pi:.6}",
            0.1 * rng.normal()
        )
        .unwrap();
    }
    // The tracker: its own clock; the joint bends about a tilted axis in a frame turned against
    // the tracker's; a reference tool on the base that, when asked, sways by up to 3°.
    let mount = quat([0.6, 0.0, 0.8], 0.7);
    let bend_axis = [0.0, 1.0, 0.0];
    let mut ndi = String::from(
        "#Tools,ToolInfo,Frame#,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error,\
         #Markers,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error\n",
    );
    let frames = ((duration_s - offset_s - 1.0) * TRACKER_HZ) as usize;
    let mut missing_left = 0usize;
    for k in 0..frames {
        let tau = k as f64 / TRACKER_HZ;
        let t = offset_s + tau * (1.0 + drift_ppm * 1e-6);
        if missing_left == 0 && k > 300 && rng.uniform() < 0.005 {
            missing_left = 1 + (rng.uniform() * 5.0) as usize;
        }
        let sway = if tools.reference_moves {
            3f64.to_radians() * (2.0 * PI * t / 37.0).sin()
        } else {
            0.0
        };
        let base = mul(quat([1.0, 0.0, 0.0], sway), mount);
        let angle = (truth.angle_deg(t) + 0.05 * rng.normal()).to_radians();
        let mut tip = mul(base, quat(bend_axis, angle));
        if tools.tip_5dof {
            // A 5-DOF sensor has no roll: what the log holds about z is arbitrary.
            tip = mul(tip, quat([0.0, 0.0, 1.0], 2.0 * PI * extra.uniform()));
        }
        let block = |q: [f64; 4], port: u32, missing: bool| {
            if missing {
                format!("Port:{port},0,Missing,,,,,,,,")
            } else {
                format!(
                    "Port:{port},0,OK,{:.7},{:.7},{:.7},{:.7},10.0,20.0,30.0,0.12",
                    q[0], q[1], q[2], q[3]
                )
            }
        };
        let gone = missing_left > 0;
        missing_left = missing_left.saturating_sub(1);
        writeln!(
            ndi,
            "2,Aurora,{},{},3,{}",
            1000 + k,
            block(tip, 1, gone),
            block(base, 2, false)
        )
        .unwrap();
    }
    std::fs::write(dir.join("daq.csv"), daq).unwrap();
    std::fs::write(dir.join("aurora.csv"), ndi).unwrap();
    truth
}
