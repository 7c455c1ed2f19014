//! Discovery on a 3000 s, 500 Hz recording (1.5 M samples) of Joint C (BSN: the plant and two
//! sensor channels, every candidate on every channel), random protocol, correlated noise, with
//! a drift hidden in sensor 1: with the names calibrated by the bootstrap (the default, issue
//! 31: the drift's calibration and its rival test against `gain_drift`, the `unexplained`
//! test's) and with `--fast` (no bootstrap). The target (issues 9 and 31) is ≤ 30 s.
//!
//! `cargo bench --bench discover`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::design::Design;
use dlw::discover::{discover, discover_with, Options};
use dlw::sim::{plan, ProtocolKind, Recording, Scenario};

fn bench(c: &mut Criterion) {
    let design =
        Design::from_toml(include_str!("../designs/joint-c.toml")).expect("joint-c.toml is valid");
    let mut scenario = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(3000.0),
        seed: 1,
        ..Scenario::default()
    };
    scenario.set_correlated_noise(true);
    scenario.sensor1.drift.enabled = true;
    scenario.sensor1.drift.rate_ohm_per_s = 0.5;
    scenario.sensor1.drift.random_walk_ohm_per_sqrt_s = Some(0.0);
    let p = plan(&design, scenario, None).expect("scenario is valid");
    assert_eq!(p.samples, 1_500_000);
    let recording = Recording {
        rig: p.rig(),
        samples: p.run().expect("runs").samples,
    };
    let found = discover(&recording, None, &design.joint, &Vec::new(), &|_| {}).expect("runs");
    assert_eq!(
        found.discovered.first().map(|d| d.effect.name()),
        Some("drift")
    );
    assert!(found.discovered[0].calibration.is_some());
    let mut g = c.benchmark_group("discover");
    g.sample_size(10);
    g.bench_function("joint_c_3000s", |b| {
        b.iter(|| discover(&recording, None, &design.joint, &Vec::new(), &|_| {}).expect("runs"))
    });
    g.bench_function("joint_c_3000s_fast", |b| {
        b.iter(|| {
            discover_with(
                &recording,
                None,
                &design.joint,
                &Vec::new(),
                Options { fast: true },
                &|_| {},
            )
            .expect("runs")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
