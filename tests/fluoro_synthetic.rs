//! `dlw::fluoro` on synthetic frames with a known answer: a pin rendered at known angles with
//! blur, Poisson-like noise, a brightness gradient and a smaller distracting blob.

use dlw::fluoro::render::PinShape;
use dlw::fluoro::{
    analyze_frame, render_frame, AngleSeries, BaselineRule, Crop, PinScene, SeriesSettings,
    Settings, Skip, Threshold,
};

/// The pin's recovered raw angle must lie this close to the rendered one (°).
const ANGLE_TOL_DEG: f64 = 0.5;

/// A sweep from −150° to 150°, past both ±90°, through `AngleSeries`: the unwrapped raw angles
/// follow the rendered ones up to the one multiple of 180° fixed by the first frame.
fn sweep(scene: &PinScene, settings: &Settings) {
    let truth: Vec<f64> = (0..=40).map(|k| -150.0 + 7.5 * f64::from(k)).collect();
    let fits: Vec<_> = truth
        .iter()
        .enumerate()
        .map(|(k, &a)| analyze_frame(&render_frame(scene, a, k as u64), settings))
        .collect();
    let series = AngleSeries::from_fits(
        &fits,
        &SeriesSettings {
            fps: 2.0,
            start_s: 0.0,
            smooth: 1,
            baseline: BaselineRule::Off,
        },
        settings.min_area_px,
        settings.min_axis_ratio,
    )
    .unwrap();
    // −150° is the axis at 30°.
    let offset = 180.0;
    for (row, t) in series.rows.iter().zip(&truth) {
        let raw = row
            .raw_deg
            .unwrap_or_else(|| panic!("frame at {t}° skipped: {:?}", row.flags));
        assert!(
            (raw - t - offset).abs() < ANGLE_TOL_DEG,
            "rendered {t}°, recovered {raw}° (expected {}°)",
            t + offset
        );
        assert_eq!(row.angle_deg, Some(raw));
    }
}

#[test]
fn a_rectangle_pin_is_recovered_over_a_sweep_past_90_degrees() {
    sweep(&PinScene::standard(200), &Settings::default());
}

#[test]
fn an_ellipse_pin_in_an_8_bit_frame_is_recovered_off_centre() {
    let mut scene = PinScene::standard(240);
    scene.shape = PinShape::Ellipse;
    scene.bits = 8;
    scene.center_x = 100.0;
    scene.center_y = 140.0;
    scene.photons = 5_000.0;
    sweep(&scene, &Settings::default());
}

#[test]
fn the_distracting_blob_is_not_taken_for_the_pin() {
    // The blob is far darker than the pin; only its size tells them apart.
    let mut scene = PinScene::standard(200);
    scene.distractor = Some((40.0, 40.0, 12.0));
    scene.contrast = 0.4;
    let frame = render_frame(&scene, 33.0, 3);
    let fit = analyze_frame(&frame, &Settings::default());
    let e = fit.ellipse.unwrap();
    assert!(
        (e.center_x - 100.0).abs() < 1.0 && (e.center_y - 100.0).abs() < 1.0,
        "{e:?}"
    );
    assert!((e.angle_deg - 33.0).abs() < ANGLE_TOL_DEG, "{e:?}");
    // With the pin gone on an even background, the blob is the largest component and too
    // round to count.
    let mut blob_only = scene;
    blob_only.length_px = 0.0;
    blob_only.gradient = 0.0;
    let fit = analyze_frame(&render_frame(&blob_only, 0.0, 3), &Settings::default());
    assert_eq!(fit.skip, Some(Skip::TooRound), "{fit:?}");
    assert_eq!(fit.angle_deg(), None);
    // With the gradient, Otsu splits the background, whose dark half is elongated but touches
    // the frame's border: skipped, not taken for a pin.
    blob_only.gradient = 0.2;
    let fit = analyze_frame(&render_frame(&blob_only, 0.0, 3), &Settings::default());
    assert_eq!(fit.skip, Some(Skip::Edge), "{fit:?}");
}

#[test]
fn otsu_needs_the_crop_when_the_frame_has_a_dark_border() {
    let mut scene = PinScene::standard(200);
    scene.collimator_px = 60.0;
    let frame = render_frame(&scene, 20.0, 5);
    // Over the whole frame Otsu separates the collimator band from the rest: the largest dark
    // component is the band (with the pin, if they touch), not the pin.
    let whole = analyze_frame(&frame, &Settings::default());
    let wrong = whole.angle_deg().map_or(true, |a| (a - 20.0).abs() > 5.0);
    assert!(wrong, "{whole:?}");
    let cropped = Settings {
        crop: Some(Crop {
            x: 64,
            y: 40,
            w: 120,
            h: 120,
        }),
        ..Settings::default()
    };
    let fit = analyze_frame(&frame, &cropped);
    let a = fit.angle_deg().unwrap();
    assert!((a - 20.0).abs() < ANGLE_TOL_DEG, "{fit:?}");
    // The centre is reported in frame coordinates, not the crop's.
    let e = fit.ellipse.unwrap();
    assert!(
        (e.center_x - 100.0).abs() < 1.0 && (e.center_y - 100.0).abs() < 1.0,
        "{e:?}"
    );
}

#[test]
fn a_fixed_threshold_and_an_inverted_pin() {
    let mut scene = PinScene::standard(200);
    scene.distractor = None;
    let frame = render_frame(&scene, -40.0, 1);
    // Background ≈ 0.6-0.72 of 65535, pin ≈ half of it: 30000 lies between.
    let fixed = Settings {
        threshold: Threshold::Value(30_000),
        ..Settings::default()
    };
    let a = analyze_frame(&frame, &fixed).angle_deg().unwrap();
    assert!((a + 40.0).abs() < ANGLE_TOL_DEG, "{a}");
    // A bright pin on a dark background: negate the scene's contrast.
    let mut bright = scene;
    bright.background = 0.3;
    bright.contrast = -1.0;
    let frame = render_frame(&bright, 70.0, 2);
    let inverted = Settings {
        invert: true,
        ..Settings::default()
    };
    let a = analyze_frame(&frame, &inverted).angle_deg().unwrap();
    assert!((a - 70.0).abs() < ANGLE_TOL_DEG, "{a}");
    // Without --invert the dark background is taken for the pin, and it is too round.
    let fit = analyze_frame(&frame, &Settings::default());
    assert_ne!(fit.skip, None, "{fit:?}");
}

/// The paper's treatment of a sequence: rest at an offset (the pin's mounting angle), a bend,
/// a hold; an 8-frame moving average and the mean before bending subtracted.
#[test]
fn a_sequence_reproduces_the_smoothing_and_the_baseline() {
    let scene = PinScene::standard(200);
    let offset = 12.0;
    // 2 Hz: 6 frames at rest, a 10 s ramp to 40°, 8 frames held, a frame with no pin.
    let mut joint: Vec<f64> = vec![0.0; 6];
    joint.extend((1..=20).map(|k| 2.0 * f64::from(k)));
    joint.extend([40.0; 8]);
    let mut fits: Vec<_> = joint
        .iter()
        .enumerate()
        .map(|(k, &a)| {
            analyze_frame(
                &render_frame(&scene, offset + a, 100 + k as u64),
                &Settings::default(),
            )
        })
        .collect();
    // A blank frame (the shutter closed): nothing to threshold.
    let mut empty = scene;
    empty.length_px = 0.0;
    empty.distractor = None;
    empty.gradient = 0.0;
    empty.photons = 0.0;
    empty.blur_px = 0.0;
    empty.contrast = 0.0;
    fits.insert(
        30,
        analyze_frame(&render_frame(&empty, 0.0, 9), &Settings::default()),
    );
    let settings = SeriesSettings {
        fps: 2.0,
        start_s: 10.0,
        smooth: 8,
        baseline: BaselineRule::UntilMotion { threshold_deg: 3.0 },
    };
    let series = AngleSeries::from_fits(&fits, &settings, 20, 1.5).unwrap();
    assert_eq!(series.rows.len(), 35);
    assert_eq!(series.rows[1].time_s, 10.5);
    let gap = &series.rows[30];
    assert_eq!((gap.angle_deg, gap.raw_deg), (None, None));
    assert_eq!(gap.flags, ["no_pin"]);
    // Motion: the first frame more than 3° from the first, frame 7 (joint at 4°).
    assert_eq!(series.baseline.end_s, Some(13.5));
    assert_eq!(series.baseline.frames, 7);
    assert!(
        (series.baseline.mean_deg - offset - 2.0 / 7.0).abs() < 0.2,
        "{:?}",
        series.baseline
    );

    // The expected series from the rendered angles, computed here independently: the centred
    // 2×8 average (weights ½,1,…,1,½ over 9 frames, renormalized at the ends) over the fitted
    // frames, less the mean of the rendered angles before motion.
    let rendered: Vec<f64> = joint.iter().map(|a| offset + a).collect();
    let base = rendered[..7].iter().sum::<f64>() / 7.0;
    let fitted_rows: Vec<_> = series.rows.iter().filter(|r| r.raw_deg.is_some()).collect();
    assert_eq!(fitted_rows.len(), rendered.len());
    for (k, row) in fitted_rows.iter().enumerate() {
        let (mut sum, mut w) = (0.0, 0.0);
        let lo = k.saturating_sub(4);
        let hi = (k + 4).min(rendered.len() - 1);
        for (j, r) in rendered.iter().enumerate().take(hi + 1).skip(lo) {
            let wj = if j.abs_diff(k) == 4 { 0.5 } else { 1.0 };
            sum += wj * r;
            w += wj;
        }
        let expected = sum / w - base;
        let got = row.angle_deg.unwrap();
        assert!(
            (got - expected).abs() < ANGLE_TOL_DEG,
            "frame {k}: {got} vs {expected}"
        );
        assert!((row.raw_deg.unwrap() - rendered[k]).abs() < ANGLE_TOL_DEG);
    }
    // The middle of the ramp is not delayed by the smoothing.
    let mid = fitted_rows[16].angle_deg.unwrap();
    assert!((mid - 22.0).abs() < ANGLE_TOL_DEG, "{mid}");

    // A fixed window: the first 2 s (frames at 10.0 … 11.5 s).
    let fixed = SeriesSettings {
        baseline: BaselineRule::Seconds(2.0),
        ..settings
    };
    let s = AngleSeries::from_fits(&fits, &fixed, 20, 1.5).unwrap();
    assert_eq!((s.baseline.frames, s.baseline.end_s), (4, Some(12.0)));
    assert!(
        (s.baseline.mean_deg - offset).abs() < 0.2,
        "{:?}",
        s.baseline
    );
}
