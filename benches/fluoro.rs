//! One 1024×1024 16-bit fluoroscopy frame through `dlw fluoro`'s per-frame analysis (target:
//! ≤ 20 ms per frame).
//!
//! - `fluoro/analyze_1024_16bit`: Otsu over the whole frame, connected components, the
//!   second-moment ellipse (`analyze_frame`), the number the target is about;
//! - `fluoro/analyze_1024_16bit_crop512`: the same on a 512×512 crop around the pin;
//! - `fluoro/stage_mask_1024`, `fluoro/stage_components_1024`: the two stages of the first,
//!   the Otsu mask and the largest component with its moments;
//! - `fluoro/decode_png_and_analyze_1024_16bit`: decoding the frame's PNG first (`image`), as
//!   `dlw fluoro` does per file;
//! - `fluoro/decode_tiff_and_analyze_1024_16bit`: the same from an uncompressed TIFF.
//!
//! The frame is `PinScene::standard(1024)`: a pin at 30°, blur, Poisson-like noise, a
//! brightness gradient and a distracting blob. `cargo bench --bench fluoro`; results in
//! `docs/performance.md`.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use dlw::fluoro::frames::from_dynamic;
use dlw::fluoro::render::png_bytes;
use dlw::fluoro::{
    analyze_frame, largest_component, pin_mask, render_frame, Crop, PinScene, Settings, Threshold,
};

fn bench(c: &mut Criterion) {
    let frame = render_frame(&PinScene::standard(1024), 30.0, 1);
    let whole = Settings::default();
    let fit = analyze_frame(&frame, &whole);
    assert!(
        fit.angle_deg().is_some_and(|a| (a - 30.0).abs() < 0.5),
        "the benchmark frame is fitted: {fit:?}"
    );
    let cropped = Settings {
        crop: Some(Crop {
            x: 256,
            y: 256,
            w: 512,
            h: 512,
        }),
        ..Settings::default()
    };
    let png = png_bytes(&frame).expect("the frame encodes");
    let mut g = c.benchmark_group("fluoro");
    g.bench_function("analyze_1024_16bit", |b| {
        b.iter(|| analyze_frame(black_box(&frame), &whole))
    });
    g.bench_function("analyze_1024_16bit_crop512", |b| {
        b.iter(|| analyze_frame(black_box(&frame), &cropped))
    });
    // The stages, to see where the time goes.
    let crop = Crop::whole(1024, 1024);
    g.bench_function("stage_mask_1024", |b| {
        b.iter(|| pin_mask(black_box(&frame.image), crop, Threshold::Otsu, false))
    });
    let (mask, _) = pin_mask(&frame.image, crop, Threshold::Otsu, false);
    g.bench_function("stage_components_1024", |b| {
        b.iter(|| largest_component(black_box(&mask)))
    });
    g.bench_function("decode_png_and_analyze_1024_16bit", |b| {
        b.iter(|| {
            let img = image::load_from_memory(black_box(&png)).expect("decodes");
            let f = from_dynamic(img).expect("greyscale");
            analyze_frame(&f, &whole)
        })
    });
    let mut tiff = std::io::Cursor::new(Vec::new());
    frame
        .image
        .write_to(&mut tiff, image::ImageFormat::Tiff)
        .expect("the frame encodes");
    let tiff = tiff.into_inner();
    g.bench_function("decode_tiff_and_analyze_1024_16bit", |b| {
        b.iter(|| {
            let img = image::load_from_memory(black_box(&tiff)).expect("decodes");
            let f = from_dynamic(img).expect("greyscale");
            analyze_frame(&f, &whole)
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
