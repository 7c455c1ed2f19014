//! Nothing non-finite leaves `dlw` (issue 17, section 2): inputs that could only produce an
//! overflow are refused at the edge with the value and the limit named, a non-zero exit and no
//! output; and `--json` never prints `null` for a NaN or an infinity (`dlw::finite`, unit
//! tested there).

use crate::common;
use common::{arg, dlw, dlw_ok, shipped_design};

use std::path::Path;

/// A short Joint D recording and a linear config for it, in `dir`.
fn recording(dir: &Path) {
    dlw_ok(&[
        "simulate",
        "--design",
        &shipped_design("joint-d.toml"),
        "--protocol",
        "random",
        "--duration-s",
        "20",
        "-o",
        &arg(&dir.join("rec")),
    ]);
    dlw_ok(&[
        "estimator-config",
        &shipped_design("joint-d.toml"),
        "--gauge-factor",
        "15.3",
        "--r0-ohm",
        "215e3",
        "-o",
        &arg(&dir.join("d.toml")),
    ]);
}

fn refused(args: &[&str], says: &[&str], not_written: &Path) {
    let o = dlw(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    for s in says {
        assert!(err.contains(s), "{args:?}: {err:?} does not say {s:?}");
    }
    assert!(
        !not_written.exists(),
        "{args:?} wrote {}",
        not_written.display()
    );
    assert!(
        o.stdout.is_empty(),
        "{args:?} printed {:?}",
        String::from_utf8_lossy(&o.stdout)
    );
}

/// An angle of 1e308° made "RMSE inf°" and a 309-digit maximum error; a low-pass of 1e308
/// samples a filter delay of "inf samples"; a frame rate of 1e308 a panic in fluoro-render and
/// 1e-320 an `inf` time in fluoro's CSV. Each is refused, naming the value and the limit.
#[test]
fn inputs_that_only_overflow_are_refused_at_the_edge() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    recording(d);
    let (rec, config) = (arg(&d.join("rec")), arg(&d.join("d.toml")));

    let out = d.join("e.csv");
    refused(
        &[
            "estimate",
            "--config",
            &config,
            &rec,
            "--filter",
            "lp:1e308",
            "-o",
            &arg(&out),
        ],
        &["lp:T 1e308", "10000000"],
        &out,
    );
    refused(
        &[
            "fluoro-render",
            "--recording",
            &rec,
            "--fps",
            "1e308",
            "-o",
            &arg(&d.join("fr")),
        ],
        &["--fps 1e308", "0.001 to 10000"],
        &d.join("fr"),
    );
    dlw_ok(&[
        "fluoro-render",
        "--recording",
        &rec,
        "--fps",
        "2",
        "-o",
        &arg(&d.join("frames")),
    ]);
    refused(
        &[
            "fluoro",
            &arg(&d.join("frames")),
            "--fps",
            "1e-320",
            "-o",
            &arg(&d.join("a.csv")),
        ],
        &["--fps 1e-320", "0.001 to 10000"],
        &d.join("a.csv"),
    );
    refused(
        &[
            "fluoro",
            &arg(&d.join("frames")),
            "--start-s",
            "1e308",
            "-o",
            &arg(&d.join("a.csv")),
        ],
        &["--start-s 1e308"],
        &d.join("a.csv"),
    );

    // The angle column: 1e308° at one row.
    let data = d.join("rec/data.csv");
    let text = std::fs::read_to_string(&data).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let at = lines[0].split(',').position(|c| c == "angle_deg").unwrap();
    let mut row: Vec<String> = lines[500].split(',').map(str::to_owned).collect();
    row[at] = "1e308".into();
    lines[500] = row.join(",");
    std::fs::write(&data, lines.join("\n") + "\n").unwrap();
    let out = d.join("e2.csv");
    refused(
        &[
            "estimate",
            "--config",
            &config,
            &rec,
            "--json",
            "-o",
            &arg(&out),
        ],
        &["line 501", "angle_deg = 1e308", "±360"],
        &out,
    );
}

/// A DXF vertex at 1e308 made "notch area NaN mm²" in `import-dxf` and a 309-digit rule
/// message in `program --from-dxf`; it is refused when read, naming the entity and the limit.
#[test]
fn a_drawing_vertex_past_the_limit_is_refused_when_read() {
    let dir = tempfile::tempdir().unwrap();
    let dxf = dir.path().join("a.dxf");
    dlw_ok(&["draw", &shipped_design("joint-a.toml"), "--dxf", &arg(&dxf)]);
    let text = std::fs::read_to_string(&dxf).unwrap();
    // The first LWPOLYLINE's first x (group code 10), whatever the line endings.
    let mut lines: Vec<&str> = text.split('\n').collect();
    let entity = lines.iter().position(|l| l.trim() == "LWPOLYLINE").unwrap();
    let code = (entity..lines.len())
        .find(|&n| lines[n].trim() == "10")
        .unwrap();
    let big_text = {
        let ending = if lines[code + 1].ends_with('\r') {
            "\r"
        } else {
            ""
        };
        let replaced = format!("1e308{ending}");
        lines[code + 1] = &replaced;
        lines.join("\n")
    };
    let big = dir.path().join("big.dxf");
    std::fs::write(&big, big_text).unwrap();
    let o = dlw(&["import-dxf", &arg(&big)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    assert!(err.contains("1e308") && err.contains("±1000 mm"), "{err}");
    assert!(!String::from_utf8_lossy(&o.stdout).contains("NaN"));
    let out = dir.path().join("big.ngc");
    refused(
        &[
            "program",
            "--from-dxf",
            &arg(&big),
            "--design",
            &shipped_design("joint-a.toml"),
            "-o",
            &arg(&out),
        ],
        &["1e308", "±1000 mm"],
        &out,
    );
}
