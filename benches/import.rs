//! `dlw import-recording` (issue 18: 3000 s at 500 Hz, 1.5 M DAQ samples and 120 k tracker
//! frames, in at most 3 s): a DAQ CSV export and an NDI Aurora log generated here in memory,
//! then
//!
//! - `import/3000s`: [`dlw::import::import`] from the files' bytes: both parsed, the bending
//!   angle, `--sync auto`, the angle onto the DAQ's samples;
//! - `import_and_write/3000s`: the same, then the recording folder written (a temporary one),
//!   as the command does.
//!
//! The bench: a stroke of smooth ramps between pseudo-random levels, a linear sensor through a
//! divider, a 40 Hz tracker 0.437 s late and 250 ppm fast, with bursts of missing frames.
//! `cargo bench --bench import`; results in `docs/performance.md`.

use std::f64::consts::PI;
use std::fmt::Write as _;

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::import::{import, DaqFormat, ImportRequest, SyncMethod};

const DURATION_S: f64 = 3000.0;
const DAQ_HZ: f64 = 500.0;
const TRACKER_HZ: f64 = 40.0;
const OFFSET_S: f64 = 0.437;
const DRIFT_PPM: f64 = 250.0;
const DIVIDER_OHM: f64 = 99.6e3;
const SUPPLY_V: f64 = 5.0;
const R0_OHM: f64 = 215e3;
/// Resistance per degree of bending (Ω/°): a linear sensor, GF·R₀·strain per degree.
const OHM_PER_DEG: f64 = 1200.0;
const GAIN_DEG_PER_MM: f64 = 33.0;
const MM_PER_V: f64 = 0.5;

/// A small deterministic generator (xorshift).
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The stroke (mm) at DAQ time `t`: 5 s at rest, then a cosine ramp to a new level every
/// 3 s, the levels from `levels`.
fn stroke_mm(levels: &[f64], t: f64) -> f64 {
    let u = ((t - 5.0) / 3.0).max(0.0);
    let k = (u as usize).min(levels.len() - 2);
    let f = (u - k as f64).min(1.0);
    levels[k] + (levels[k + 1] - levels[k]) * (1.0 - (PI * f).cos()) / 2.0
}

/// The DAQ CSV (`Time,AI0,AI2`) and the NDI log of the bench.
fn bench_files() -> (String, String) {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let mut levels = vec![0.0];
    levels.extend((0..(DURATION_S / 3.0) as usize + 2).map(|_| 1.1 * rng.uniform()));
    let divider_v = |ohm: f64| SUPPLY_V * ohm / (ohm + DIVIDER_OHM);
    let n = (DURATION_S * DAQ_HZ) as usize;
    let mut daq = String::with_capacity(n * 32);
    daq.push_str("Time,AI0,AI2\n");
    for i in 0..n {
        let t = i as f64 / DAQ_HZ;
        let angle = GAIN_DEG_PER_MM * stroke_mm(&levels, t - 0.03);
        let v = divider_v(R0_OHM + OHM_PER_DEG * angle) + 0.0005 * (rng.uniform() - 0.5);
        let _ = writeln!(daq, "{t:.4},{v:.6},{:.6}", stroke_mm(&levels, t) / MM_PER_V);
    }
    let frames = ((DURATION_S - OFFSET_S - 1.0) * TRACKER_HZ) as usize;
    let mut ndi = String::with_capacity(frames * 100);
    ndi.push_str("Frame#,PortHandle,Face#,TransformStatus,Q0,Qx,Qy,Qz,Tx,Ty,Tz,Error\n");
    let mut missing = 0usize;
    for k in 0..frames {
        let t = OFFSET_S + k as f64 / TRACKER_HZ * (1.0 + DRIFT_PPM * 1e-6);
        if missing == 0 && k > 300 && rng.uniform() < 0.004 {
            missing = 1 + (rng.uniform() * 5.0) as usize;
        }
        if missing > 0 {
            missing -= 1;
            let _ = writeln!(ndi, "{},Port:1,0,Missing,,,,,,,,", 1000 + k);
            continue;
        }
        let half = (GAIN_DEG_PER_MM * stroke_mm(&levels, t - 0.03)).to_radians() / 2.0;
        let _ = writeln!(
            ndi,
            "{},Port:1,0,OK,{:.7},0.0000000,{:.7},0.0000000,10.0,20.0,30.0,0.12",
            1000 + k,
            half.cos(),
            half.sin()
        );
    }
    (daq, ndi)
}

fn bench(c: &mut Criterion) {
    let (daq, ndi) = bench_files();
    let request = ImportRequest {
        daq: ("daq.csv", daq.as_bytes()),
        daq_format: DaqFormat::Csv,
        voltage_channels: vec!["AI0".into()],
        divider_ohm: vec![DIVIDER_OHM],
        supply_v: SUPPLY_V,
        stroke: ("AI2".into(), MM_PER_V),
        time_column: None,
        daq_rate_hz: None,
        tracker: ("aurora.csv", &ndi),
        tracker_map: None,
        tool: 1,
        reference_tool: None,
        tracker_hz: Some(TRACKER_HZ),
        rest_s: 2.0,
        sync: SyncMethod::Auto,
        max_offset_s: dlw::import::align::MAX_OFFSET_S,
        rate_hz: None,
    };
    let (recording, summary) = import(&request).expect("the bench imports");
    assert_eq!(recording.samples.time_s.len(), 1_500_000);
    assert!(
        summary.tracker.frames >= 119_000,
        "{}",
        summary.tracker.frames
    );
    assert!(
        (summary.alignment.offset_s - OFFSET_S).abs() < 0.002
            && (summary.alignment.drift_ppm - DRIFT_PPM).abs() < 30.0,
        "{:?}",
        summary.alignment
    );
    let dir = tempfile::tempdir().expect("a temporary folder");
    let mut g = c.benchmark_group("import");
    g.sample_size(10);
    g.bench_function("3000s", |b| {
        b.iter(|| import(&request).expect("the bench imports"))
    });
    g.bench_function("and_write_3000s", |b| {
        b.iter(|| {
            let (recording, _) = import(&request).expect("the bench imports");
            recording
                .write(&dir.path().join("rec"), true)
                .expect("the recording is written");
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
