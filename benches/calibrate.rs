//! The calibrated twin's costs: one short-sized evaluation of `dlw calibrate` (Tables III-VI
//! with every protocol once at the paper's timings, Joints A-D) and one front candidate of
//! `dlw explore`'s predicted accuracy (Joint A's design on the shipped twin: characterization,
//! linear and PI fits, the random pattern estimated, and the closed loop on Joint D's plant).
//!
//! `cargo bench --bench calibrate`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion};
use dlw::calibrate::{Calibration, Options, Space};
use dlw::explore::Predictor;

fn bench(c: &mut Criterion) {
    let calibration =
        Calibration::new(Space::paper(), Options::default()).expect("the default options");
    let ideal = calibration.space.ideal();
    let design = dlw::design::Design::from_toml(include_str!("../designs/joint-a.toml"))
        .expect("the shipped design");
    let predictor = Predictor::paper(15.3).expect("the shipped twin");
    let mut g = c.benchmark_group("calibrate");
    g.sample_size(10);
    g.bench_function("evaluation_short_sized", |b| {
        b.iter(|| calibration.run(&ideal, 1).expect("the ideal bench runs"))
    });
    g.bench_function("predict_front_candidate", |b| {
        b.iter(|| predictor.predict(&design).expect("Joint A predicts"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
