//! Simulating 3000 s at 500 Hz (1.5 M samples), the paper's longest protocols.
//!
//! - `simulate/run_3000s_*`: generating the samples in memory (`Plan::run`), the number the
//!   0.3 s target is about;
//! - `simulate/csv_bytes_3000s`: formatting them as `data.csv` in memory;
//! - `simulate/write_3000s`: writing the whole recording folder (rig.toml + data.csv, atomic).
//!
//! `cargo bench --bench simulate`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::design::Design;
use dlw::sim::{plan, ProtocolKind, Recording, Scenario, SensorModelKind};

fn design() -> Design {
    Design::from_toml(include_str!("../designs/joint-d.toml")).expect("joint-d.toml is valid")
}

fn scenario(edit: impl FnOnce(&mut Scenario)) -> Scenario {
    let mut s = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(3000.0),
        seed: 1,
        ..Scenario::default()
    };
    edit(&mut s);
    s
}

fn bench(c: &mut Criterion) {
    let design = design();
    let mut g = c.benchmark_group("simulate");
    g.sample_size(10);
    let cases = [
        // The default: linear sensor, ADC and tracker noise.
        ("run_3000s_linear_default", scenario(|_| {})),
        // The same with correlated ADC and tracker noise (`--noise realistic`).
        (
            "run_3000s_linear_realistic_noise",
            scenario(|s| {
                s.adc.correlated.enabled = true;
                s.tracker.correlated.enabled = true;
            }),
        ),
        // PI sensor (N = 10) with every plant and sensor effect on.
        (
            "run_3000s_pi_all_effects",
            scenario(|s| {
                s.plant.backlash.enabled = true;
                s.plant.relaxation.enabled = true;
                s.plant.notch_limit.enabled = true;
                let p = &mut s.sensor1;
                p.model = SensorModelKind::Pi;
                p.saturation.enabled = true;
                p.drift.enabled = true;
                p.rate.enabled = true;
                p.creep.enabled = true;
            }),
        ),
    ];
    for (name, sc) in cases {
        let p = plan(&design, sc, None).expect("scenario is valid");
        assert_eq!(p.samples, 1_500_000);
        g.bench_function(name, |b| b.iter(|| p.run().expect("runs")));
    }
    let p = plan(&design, scenario(|_| {}), None).expect("scenario is valid");
    let recording = Recording {
        rig: p.rig(),
        samples: p.run().expect("runs").samples,
    };
    g.bench_function("csv_bytes_3000s", |b| b.iter(|| recording.csv_bytes()));
    let dir = tempfile::tempdir().expect("temp dir");
    let dest = dir.path().join("rec");
    g.bench_function("write_3000s", |b| {
        b.iter(|| recording.write(&dest, true).expect("writes"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
