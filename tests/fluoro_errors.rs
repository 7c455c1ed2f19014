//! Bad input to `dlw fluoro`, `dlw fluoro-render` and `dlw estimate --truth`: a clear error that
//! names the value and the limit, a non-zero exit, and no output file or folder (not even a
//! partial one or a staging folder).

use crate::common;
use common::dlw;

use std::path::Path;

use dlw::fluoro::render::png_bytes;
use dlw::fluoro::{render_frame, PinScene};

/// Writes `n` small frames of a pin at 10° steps into `dir` (created).
fn frames(dir: &Path, n: usize, size: u32) {
    std::fs::create_dir_all(dir).unwrap();
    for k in 0..n {
        let f = render_frame(&PinScene::standard(size), 10.0 * k as f64, k as u64);
        std::fs::write(dir.join(format!("f_{k:03}.png")), png_bytes(&f).unwrap()).unwrap();
    }
}

/// Runs `dlw args`, expects a failure whose message contains every needle, and checks that
/// `out` (the folder holding every output) holds only `keep`.
fn fails(args: &[&str], needles: &[&str], out: &Path, keep: &[&str]) {
    let o = dlw(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "dlw {args:?} succeeded");
    for n in needles {
        assert!(err.contains(n), "dlw {args:?}: {err:?} lacks {n:?}");
    }
    let mut left: Vec<String> = std::fs::read_dir(out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left, keep, "dlw {args:?} left files behind");
}

#[test]
fn fluoro_refuses_bad_frame_folders_and_writes_nothing() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let csv = out.join("angles.csv").display().to_string();
    let overlay = out.join("overlay").display().to_string();
    let run = |frames: &Path, extra: &[&str], needles: &[&str]| {
        let mut args = vec![
            "fluoro",
            frames.to_str().unwrap(),
            "-o",
            &csv,
            "--overlay",
            &overlay,
        ];
        args.extend_from_slice(extra);
        fails(&args, needles, &out, &[]);
    };

    let empty = root.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    run(&empty, &[], &["empty", "has no PNG or TIFF frames"]);
    run(
        &root.path().join("missing"),
        &[],
        &["cannot list frames folder", "missing"],
    );

    let stranger = root.path().join("stranger");
    frames(&stranger, 3, 64);
    std::fs::write(stranger.join("notes.txt"), "pin at 10°").unwrap();
    run(
        &stranger,
        &[],
        &["notes.txt", "is not a frame", ".png, .tif or .tiff"],
    );

    let fake = root.path().join("fake");
    frames(&fake, 3, 64);
    std::fs::write(fake.join("f_001.png"), "not a PNG").unwrap();
    run(&fake, &[], &["cannot decode frame", "f_001.png"]);

    // The third frame is larger: found after two frames were analyzed and drawn.
    let mixed = root.path().join("mixed");
    frames(&mixed, 2, 64);
    let big = render_frame(&PinScene::standard(80), 0.0, 0);
    std::fs::write(mixed.join("f_002.png"), png_bytes(&big).unwrap()).unwrap();
    run(
        &mixed,
        &[],
        &["f_002.png is 80×80 px", "first frame f_000.png is 64×64 px"],
    );

    let good = root.path().join("good");
    frames(&good, 3, 64);
    run(
        &good,
        &["--crop", "10,10,60,20"],
        &[
            "crop x=10, y=10, w=60, h=20",
            "64×64 px frame",
            "x + w ≤ 64",
        ],
    );
    run(
        &good,
        &["--crop", "10,10,60"],
        &["crop \"10,10,60\" is not x,y,w,h"],
    );
    run(&good, &["--fps", "0"], &["--fps 0 is out of range"]);
    run(&good, &["--smooth", "0"], &["--smooth = 0 is out of range"]);
    run(
        &good,
        &["--baseline-s", "-1"],
        &["--baseline-s -1 is out of range"],
    );
    run(
        &good,
        &["--min-axis-ratio", "0.5"],
        &["--min-axis-ratio = 0.5"],
    );
    // A threshold below every pixel: no frame has a pin.
    run(
        &good,
        &["--threshold", "0"],
        &["no frame of 3 has a plausible pin"],
    );
    run(
        &good,
        &["--threshold", "lots"],
        &["neither `otsu` nor a grey level"],
    );

    // An output CSV in a missing folder is found before any overlay is drawn.
    let lost = out.join("no/such/angles.csv").display().to_string();
    fails(
        &[
            "fluoro",
            good.to_str().unwrap(),
            "-o",
            &lost,
            "--overlay",
            &overlay,
        ],
        &["folder", "no/such", "does not exist"],
        &out,
        &[],
    );

    // The 8-bit range.
    let eight = root.path().join("eight");
    std::fs::create_dir(&eight).unwrap();
    let mut scene = PinScene::standard(64);
    scene.bits = 8;
    let f = render_frame(&scene, 0.0, 0);
    std::fs::write(eight.join("a.png"), png_bytes(&f).unwrap()).unwrap();
    run(
        &eight,
        &["--threshold", "300"],
        &["threshold 300 is beyond the 8-bit frames' range 0..=255"],
    );

    // An occupied overlay folder is kept unless --force.
    std::fs::create_dir(&overlay).unwrap();
    std::fs::write(Path::new(&overlay).join("mine.txt"), "x").unwrap();
    fails(
        &[
            "fluoro",
            good.to_str().unwrap(),
            "-o",
            &csv,
            "--overlay",
            &overlay,
        ],
        &["already exists and is not empty", "--force"],
        &out,
        &["overlay"],
    );
    // And then it works, replacing it.
    let o = dlw(&[
        "fluoro",
        good.to_str().unwrap(),
        "-o",
        &csv,
        "--overlay",
        &overlay,
        "--force",
        "--smooth",
        "1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&overlay)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["f_000.png", "f_001.png", "f_002.png"]);
    let text = std::fs::read_to_string(&csv).unwrap();
    assert_eq!(text.lines().count(), 4);
    assert!(
        text.starts_with("time_s,angle_deg,raw_deg,area_px,axis_ratio,flags\n0.000000,"),
        "{text}"
    );
}

#[test]
fn estimate_truth_and_render_refuse_bad_input() {
    let root = tempfile::tempdir().unwrap();
    let rec = root.path().join("rec");
    std::fs::create_dir(&rec).unwrap();
    std::fs::write(
        rec.join("rig.toml"),
        "sample_hz = 500.0\nsupply_v = 5.0\ndivider_ohm = [99600.0]\n",
    )
    .unwrap();
    std::fs::write(
        rec.join("data.csv"),
        "time_s,stroke_mm,angle_deg,v1_V\n0,0,,3.4\n0.002,0,,3.41\n0.004,0,,3.42\n",
    )
    .unwrap();
    let cfg = root.path().join("d.toml");
    let o = dlw(&[
        "estimator-config",
        &common::shipped_design("joint-d.toml"),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        cfg.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    let truth = root.path().join("angles.csv");
    let estimate = |truth_text: &str, needles: &[&str]| {
        std::fs::write(&truth, truth_text).unwrap();
        fails(
            &[
                "estimate",
                "--config",
                cfg.to_str().unwrap(),
                rec.to_str().unwrap(),
                "--truth",
                truth.to_str().unwrap(),
            ],
            needles,
            &rec,
            &["data.csv", "rig.toml"],
        );
    };
    estimate(
        "time_s,angle_deg\n5,1\n6,2\n",
        &[
            "no ground-truth frame",
            "0..0.004 s",
            "2 frame(s) from 5 s to 6 s",
        ],
    );
    estimate("time_s,angle\n0,1\n", &["has no angle_deg column"]);
    estimate(
        "time_s,angle_deg\n0,1\n0,2\n",
        &["line 3: time_s = 0 does not increase"],
    );
    estimate("time_s,angle_deg\n0,\n", &["has no frame with an angle"]);
    // A good truth file works on the same recording, and writes the estimates.
    std::fs::write(&truth, "time_s,angle_deg\n0.001,0.0\n0.003,0.1\n").unwrap();
    let o = dlw(&[
        "estimate",
        "--config",
        cfg.to_str().unwrap(),
        rec.to_str().unwrap(),
        "--truth",
        truth.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let est = std::fs::read_to_string(rec.join("estimates.csv")).unwrap();
    assert!(
        est.lines().nth(1).unwrap().starts_with("0.000000,,"),
        "{est}"
    );
    std::fs::remove_file(rec.join("estimates.csv")).unwrap();

    // A column empty in some rows only is refused by every reader.
    std::fs::write(
        rec.join("data.csv"),
        "time_s,stroke_mm,angle_deg,v1_V\n0,0,,3.4\n0.002,0,1.5,3.41\n",
    )
    .unwrap();
    estimate(
        "time_s,angle_deg\n0.001,0\n",
        &["line 3: angle_deg is a number but line 2 has it empty"],
    );

    // fluoro-render needs the angle, and sane settings; it leaves no folder on failure.
    let frames = root.path().join("frames").display().to_string();
    let render = |extra: &[&str], needles: &[&str]| {
        let mut args = vec![
            "fluoro-render",
            "--recording",
            rec.to_str().unwrap(),
            "-o",
            &frames,
        ];
        args.extend_from_slice(extra);
        fails(
            &args,
            needles,
            root.path(),
            &["angles.csv", "d.toml", "rec"],
        );
    };
    render(&[], &["angle_deg is a number but line 2 has it empty"]);
    std::fs::write(
        rec.join("data.csv"),
        "time_s,stroke_mm,angle_deg,v1_V\n0,0,,3.4\n0.002,0,,3.41\n",
    )
    .unwrap();
    render(&[], &["angle_deg column is empty"]);
    render(
        &["--size", "8"],
        &["--size 8 is out of range (32 to 8192 px)"],
    );
    render(&["--bits", "12"], &["--bits 12 is out of range (8 or 16)"]);
    render(&["--fps", "-2"], &["--fps -2 is out of range"]);
}
