//! The explorer's screen: every candidate of a 1 310 720-candidate grid scored with the
//! mechanics and the sensing model and tested against the constraints, in parallel (rayon).
//! The target (issue 21) is at least 1 M candidates per second on the 2-core CI machine.
//! The design rules on the screen's survivors are timed separately (`rules_per_survivor`).
//!
//! `cargo bench --bench explore`; results in `docs/performance.md`.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use dlw::explore::Exploration;

fn spec(dir: &std::path::Path) -> std::path::PathBuf {
    let designs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("designs");
    // 5 tubes × 2 styles × 64 s_n × 4 s_s × 16 N × 8 h × 4 c = 1 310 720 candidates.
    let text = format!(
        r#"base = "{base}"
tubes = "{tubes}"
gauge_factor = 15.3
r0_ohm = 215e3
[vary]
tube = ["paper-1.6", "paper-2.5", "od1.2-id1.0", "od2.0-id1.6", "od3.0-id2.5"]
style = ["uan", "bsn"]
notch_arc_mm = {{ from = 0.5, to = 6.8, step = 0.1 }}
sensor_arc_mm = [0.3, 0.4, 0.5, 2.0]
notch_count = {{ from = 5, to = 20, step = 1 }}
notch_width_mm = {{ from = 0.3, to = 1.0, step = 0.1 }}
notch_spacing_mm = [0.4, 0.5, 0.6, 0.7]
[constraints]
min_range_deg = 60
max_tendon_force_per_deg_n = 0.05
[objectives]
maximize = ["sensitivity_ohm_per_deg", "range_deg"]
minimize = ["tendon_force_per_deg_n"]
"#,
        base = designs.join("joint-d.toml").display(),
        tubes = designs.join("tubes.toml").display(),
    );
    let path = dir.join("bench-spec.toml");
    std::fs::write(&path, text).expect("temp folder is writable");
    path
}

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().expect("temp folder");
    let x = Exploration::load(&spec(dir.path()), &dir.path().join("out/best-1.toml"))
        .expect("the bench spec loads");
    let n = x.candidate_count();
    assert_eq!(n, 1_310_720);
    let screen = x.screen(&|_| {});
    assert_eq!(screen.evaluated, n);
    eprintln!(
        "screen: {} candidates, {} refused by the geometry, {} survivors",
        n,
        screen.geometry_refused,
        screen.survivors.len()
    );
    let mut g = c.benchmark_group("explore");
    g.sample_size(10);
    g.throughput(Throughput::Elements(n));
    g.bench_function("screen_1310720", |b| b.iter(|| x.screen(&|_| {})));
    let some: Vec<_> = screen.survivors.iter().take(64).map(|c| c.params).collect();
    g.throughput(Throughput::Elements(some.len() as u64));
    g.bench_function("rules_per_survivor", |b| {
        b.iter(|| some.iter().filter(|p| x.rule_check(p).is_ok()).count())
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
