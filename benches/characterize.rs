//! `dlw characterize` on 3000 s, 500 Hz recordings (1.5 M samples) of Joint A with the PI
//! sensor and relaxation on, the target (issue 8) being ≤ 2 s per kind: the analysis and its
//! report page drawn in memory (`Page::files`, every SVG), as the command does before writing.
//!
//! - `characterize/loops_3000s`: the characterization protocol; every model fitted (`fit_sensor`);
//! - `characterize/rate_3000s`: the rate-dependence protocol, a linear fit per cycle;
//! - `characterize/relaxation_3000s`: the relaxation protocol, an exponential fit per hold;
//! - `characterize/estimation_3000s`: the random protocol, a linear and a PI config through the
//!   runtime estimator with the paper's 1000-sample average.
//!
//! `cargo bench --bench characterize`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::analysis::{Analysis, Placement};
use dlw::characterize::{estimate, loops, rate, relaxation, NamedConfig, Options};
use dlw::design::Design;
use dlw::report::Page;
use dlw::sim::{plan, ProtocolKind, Recording, Scenario, SensorModelKind, JOINT_A_PI};
use dlw_estimator::{nominal_divider, EstimatorConfig, JointConfig, ModelConfig, SensorPlane};

fn record(design: &Design, protocol: ProtocolKind) -> Recording {
    let mut sc = Scenario {
        protocol: Some(protocol),
        duration_s: Some(3000.0),
        seed: 1,
        ..Scenario::default()
    };
    sc.sensor1.model = SensorModelKind::Pi;
    sc.plant.relaxation.enabled = true;
    let p = plan(design, sc, None).expect("scenario is valid");
    assert_eq!(p.samples, 1_500_000);
    Recording {
        rig: p.rig(),
        samples: p.run().expect("runs").samples,
    }
}

fn bench(c: &mut Criterion) {
    let design =
        Design::from_toml(include_str!("../designs/joint-a.toml")).expect("joint-a.toml is valid");
    let j = &design.joint;
    let planes = [SensorPlane::PlusYs];
    let opts = Options::default();
    let mut g = c.benchmark_group("characterize");
    g.sample_size(10);

    let rec = record(&design, ProtocolKind::Characterization);
    g.bench_function("loops_3000s", |b| {
        b.iter(|| {
            let r = loops(&rec, j, &planes, &opts).expect("loops");
            let mut page = Page::new("loops");
            r.add_to_page(&mut page, Placement::ALONE);
            page.files().expect("draws")
        })
    });
    let rec = record(&design, ProtocolKind::RateDependence);
    g.bench_function("rate_3000s", |b| {
        b.iter(|| {
            let r = rate(&rec, j, &planes, &opts).expect("rate");
            let mut page = Page::new("rate");
            r.add_to_page(&mut page, Placement::ALONE);
            page.files().expect("draws")
        })
    });
    let rec = record(&design, ProtocolKind::Relaxation);
    g.bench_function("relaxation_3000s", |b| {
        b.iter(|| {
            let r = relaxation(&rec, j, &planes, &opts).expect("relaxation");
            let mut page = Page::new("relaxation");
            r.add_to_page(&mut page, Placement::ALONE);
            page.files().expect("draws")
        })
    });
    let rec = record(&design, ProtocolKind::Random);
    let linear =
        EstimatorConfig::nominal_linear(JointConfig::from_joint(j), 15.3, 215e3, nominal_divider())
            .expect("valid config");
    let mut pi = linear;
    pi.sensor.model = ModelConfig::Pi(JOINT_A_PI.to_config());
    let configs = [
        NamedConfig {
            name: "linear".into(),
            config: linear,
        },
        NamedConfig {
            name: "PI".into(),
            config: pi,
        },
    ];
    let paper = Options {
        paper_processing: true,
        ..opts
    };
    g.bench_function("estimation_3000s", |b| {
        b.iter(|| {
            let r = estimate(&rec, &configs, &paper).expect("estimation");
            let mut page = Page::new("estimation");
            r.add_to_page(&mut page, Placement::ALONE);
            page.files().expect("draws")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
