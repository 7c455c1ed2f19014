//! Fitting PI (N = 10) to a 3000 s, 500 Hz characterization recording (1.5 M samples) of a
//! simulated PI sensor (Joint A), with `dlw fit`'s default options (prefilter `ma:100`, automatic
//! decimation to at most `MAX_FIT_SAMPLES`). `fit_sensor` fits every model (linear, generalized
//! PI, continuous PI), as `dlw fit` does; the target (issue 7) is ≤ 3 s.
//!
//! `cargo bench --bench fit`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::design::Design;
use dlw::fit::{fit_sensor, FitOptions, ModelKind, Prefilter};
use dlw::sim::{plan, ProtocolKind, Recording, Scenario, SensorModelKind};
use dlw_estimator::SensorPlane;

fn bench(c: &mut Criterion) {
    let design =
        Design::from_toml(include_str!("../designs/joint-a.toml")).expect("joint-a.toml is valid");
    let mut scenario = Scenario {
        protocol: Some(ProtocolKind::Characterization),
        duration_s: Some(3000.0),
        seed: 1,
        ..Scenario::default()
    };
    scenario.sensor1.model = SensorModelKind::Pi;
    let p = plan(&design, scenario, None).expect("scenario is valid");
    assert_eq!(p.samples, 1_500_000);
    let recording = Recording {
        rig: p.rig(),
        samples: p.run().expect("runs").samples,
    };
    let options = FitOptions {
        model: ModelKind::Pi,
        order: 10,
        prefilter: Prefilter::MovingAverage(100),
        decimation: None,
    };
    let mut g = c.benchmark_group("fit");
    g.sample_size(10);
    g.bench_function("pi_n10_3000s", |b| {
        b.iter(|| {
            fit_sensor(
                &recording,
                &design.joint,
                SensorPlane::PlusYs,
                &options,
                &|_| {},
            )
            .expect("fits")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
