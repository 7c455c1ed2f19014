//! `dlw control` for 3000 s at 500 Hz (1.5 M samples per scheme), the target being ≤ 2 s.
//!
//! - `control/run_3000s`: both schemes on the bench (`Control::run`): Joint D, random protocol,
//!   relaxation and backlash on, the linear estimator with a 50-sample moving average, the
//!   paper's gains;
//! - `control/files_3000s`: the report (charts through `plotters`) and `control.csv`, in memory;
//! - `control/end_to_end_3000s`: resolving, both schemes, the files and the atomic folder write.
//!
//! `cargo bench --bench control`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::control::{report, Control, DesiredSource, PAPER_GAINS};
use dlw::design::Design;
use dlw::output::write_folder_atomic;
use dlw::sim::{ProtocolKind, Scenario};
use dlw_estimator::{nominal_divider, EstimatorConfig, FilterConfig, JointConfig};

fn setup() -> (Design, Scenario, EstimatorConfig) {
    let design =
        Design::from_toml(include_str!("../designs/joint-d.toml")).expect("joint-d.toml is valid");
    let mut sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(3000.0),
        seed: 1,
        ..Scenario::default()
    };
    sc.plant.relaxation.enabled = true;
    sc.plant.relaxation.fraction = 0.15;
    sc.plant.backlash.enabled = true;
    sc.plant.backlash.width_mm = 0.1;
    let mut config = EstimatorConfig::nominal_linear(
        JointConfig::from_joint(&design.joint),
        15.3,
        215e3,
        nominal_divider(),
    )
    .expect("valid config");
    config.output_filter = FilterConfig::MovingAverage { samples: 50 };
    (design, sc, config)
}

fn bench(c: &mut Criterion) {
    let (design, sc, config) = setup();
    let build = || {
        Control::new(
            &design,
            sc.clone(),
            &DesiredSource::Protocol,
            config,
            PAPER_GAINS,
            None,
        )
        .expect("valid control")
    };
    let control = build();
    assert_eq!(control.desired.angle_deg.len(), 1_500_000);
    let mut g = c.benchmark_group("control");
    g.sample_size(10);
    g.bench_function("run_3000s", |b| b.iter(|| control.run().expect("runs")));
    let run = control.run().expect("runs");
    g.bench_function("files_3000s", |b| {
        b.iter(|| report::files(&control, &run).expect("draws"))
    });
    let dir = tempfile::tempdir().expect("temp dir");
    let dest = dir.path().join("out");
    g.bench_function("end_to_end_3000s", |b| {
        b.iter(|| {
            let control = build();
            let run = control.run().expect("runs");
            let files = report::files(&control, &run).expect("draws");
            write_folder_atomic(&dest, &files).expect("writes");
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
