//! dlw's TDMS reader (`src/import/tdms/`) on files from another writer: Python's npTDMS
//! (`tests/scripts/tdms_fixture.py`, installed by `scripts/test.sh`) writes f64, f32, and i16
//! and i32 with linear scales over several segments, with waveform properties; the values
//! dlw reads must equal the ones written, and the ones npTDMS reads back. npTDMS cannot write
//! interleaved data, so that segment is built here by hand from NI's format description, and
//! npTDMS reading it back checks the hand-built file.

use std::path::Path;
use std::process::Command;

use dlw::import::tdms::{Property, TdmsFile, Timestamp};
use serde_json::{json, Value};

fn script() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/scripts/tdms_fixture.py")
}

/// Runs `tdms_fixture.py` with `args`.
fn python(args: &[&Path]) {
    let out = Command::new("python3")
        .arg(script())
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run python3 ({e}): these tests need python3 with npTDMS (scripts/test.sh installs it)"));
    assert!(
        out.status.success(),
        "tdms_fixture.py {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// What npTDMS reads from `file`: per `Group/Channel`, its scaled values.
fn nptdms_values(dir: &Path, file: &Path) -> Value {
    let out = dir.join("read.json");
    python(&[Path::new("read"), file, &out]);
    serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap()
}

fn assert_same(what: &str, got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!(
            (g - w).abs() <= 1e-12 * w.abs().max(1.0),
            "{what}[{i}]: read {g}, written {w}"
        );
    }
}

fn as_f64s(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

const I16_SLOPE: f64 = 0.001;
const I16_INTERCEPT: f64 = -1.5;
const I32_SLOPE: f64 = 2.5e-6;
const I32_INTERCEPT: f64 = 0.25;

/// Per segment, the raw values of each channel: f64, f32 (exact as f32), i16, i32.
fn segment_values(k: usize, n: usize) -> [Vec<f64>; 4] {
    let x = |i: usize| (k * 1000 + i) as f64;
    [
        (0..n)
            .map(|i| (0.37 * x(i)).sin() * 4.2 + 1e-9 * x(i))
            .collect(),
        (0..n)
            .map(|i| f64::from(((0.11 * x(i)).cos() * 3.3) as f32))
            .collect(),
        (0..n)
            .map(|i| ((x(i) * 97.0) % 65535.0 - 32767.0).round())
            .collect(),
        (0..n)
            .map(|i| ((x(i) * 7919.0 * 1e3) % 4.0e9 - 2.0e9).round())
            .collect(),
    ]
}

/// f64, f32, i16 and i32 with linear scales, in three segments of different lengths, with
/// waveform properties and a second group with a channel of the same name.
#[test]
fn values_equal_what_nptdms_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let lengths = [50usize, 1, 200];
    let mut segments = Vec::new();
    for (k, &n) in lengths.iter().enumerate() {
        let v = segment_values(k, n);
        let first = k == 0;
        let wf = if first {
            json!({"wf_increment": 0.001, "wf_samples": n,
                   "wf_start_time": {"timestamp": "2026-11-25T18:00:00.250"}})
        } else {
            json!({"wf_samples": n})
        };
        let scale = |slope: f64, intercept: f64| {
            if first {
                json!({"NI_Number_Of_Scales": 1, "NI_Scale[0]_Scale_Type": "Linear",
                       "NI_Scale[0]_Linear_Slope": slope,
                       "NI_Scale[0]_Linear_Y_Intercept": intercept})
            } else {
                json!({})
            }
        };
        segments.push(json!([
            {"group": null, "properties": {"title": "dlw test"}},
            {"group": "g", "channel": null, "properties": {"rig": "bench A"}},
            {"group": "g", "channel": "f64", "dtype": "float64", "values": v[0], "properties": wf},
            {"group": "g", "channel": "f32", "dtype": "float32", "values": v[1]},
            {"group": "g", "channel": "i16", "dtype": "int16", "values": v[2],
             "properties": scale(I16_SLOPE, I16_INTERCEPT)},
            {"group": "g", "channel": "i32", "dtype": "int32", "values": v[3],
             "properties": scale(I32_SLOPE, I32_INTERCEPT)},
            {"group": "h", "channel": "f64", "dtype": "float64", "values": v[0]},
        ]));
    }
    let spec = dir.path().join("spec.json");
    std::fs::write(&spec, json!({ "segments": segments }).to_string()).unwrap();
    let file = dir.path().join("written.tdms");
    python(&[Path::new("write"), &spec, &file]);

    let bytes = std::fs::read(&file).unwrap();
    let tdms = TdmsFile::parse(&bytes).unwrap();
    let mut want: [Vec<f64>; 4] = Default::default();
    for (k, &n) in lengths.iter().enumerate() {
        for (all, seg) in want.iter_mut().zip(segment_values(k, n)) {
            all.extend(seg);
        }
    }
    want[2] = want[2]
        .iter()
        .map(|c| c * I16_SLOPE + I16_INTERCEPT)
        .collect();
    want[3] = want[3]
        .iter()
        .map(|c| c * I32_SLOPE + I32_INTERCEPT)
        .collect();
    let theirs = nptdms_values(dir.path(), &file);
    for (name, want) in ["g/f64", "f32", "i16", "g/i32"].iter().zip(&want) {
        let id = tdms.find(name).unwrap();
        let got = tdms.values(id).unwrap();
        assert_same(name, &got, want);
        assert_same(
            &format!("npTDMS {name}"),
            &got,
            &as_f64s(&theirs[tdms.name(id)]["values"]),
        );
    }
    let wf = tdms.waveform(tdms.find("g/f64").unwrap());
    assert_eq!(wf.increment_s, Some(0.001));
    assert_eq!(
        wf.samples_per_write,
        Some(200),
        "the last segment's wf_samples"
    );
    assert_eq!(
        wf.start_time,
        Some(Timestamp {
            seconds: 3_878_474_400,
            fraction: 1 << 62
        })
    );
    // A bare name held by two groups is ambiguous; an unknown one lists what there is.
    let err = tdms.find("f64").unwrap_err().to_string();
    assert!(err.contains("g/f64") && err.contains("h/f64"), "{err}");
    let err = tdms.find("AI7").unwrap_err().to_string();
    assert!(err.contains("AI7") && err.contains("g/i16, g/i32"), "{err}");
    let plain = tdms.properties(tdms.find("h/f64").unwrap());
    assert!(plain.is_empty(), "{plain:?}");
    let props = tdms.properties(tdms.find("g/i16").unwrap());
    assert!(props.contains(&(
        "NI_Scale[0]_Scale_Type".to_owned(),
        Property::Text("Linear".into())
    )));
}

fn string(s: &str) -> Vec<u8> {
    let mut b = (s.len() as u32).to_le_bytes().to_vec();
    b.extend(s.as_bytes());
    b
}

/// A segment by hand (NI's "TDMS File Format Internal Structure"): lead-in, metadata, raw.
fn segment(toc: u32, meta: &[u8], raw: &[u8]) -> Vec<u8> {
    let mut s = b"TDSm".to_vec();
    s.extend(toc.to_le_bytes());
    s.extend(4713u32.to_le_bytes());
    s.extend(((meta.len() + raw.len()) as u64).to_le_bytes());
    s.extend((meta.len() as u64).to_le_bytes());
    s.extend(meta);
    s.extend(raw);
    s
}

const K_TOC_META_DATA: u32 = 1 << 1;
const K_TOC_NEW_OBJ_LIST: u32 = 1 << 2;
const K_TOC_RAW_DATA: u32 = 1 << 3;
const K_TOC_INTERLEAVED: u32 = 1 << 5;

/// An interleaved segment (f64, f32 and a scaled i16, 5 values each, written value by value
/// across the channels, two chunks), then one without metadata that reuses its layout. npTDMS
/// and dlw read the same values, equal to what was written.
#[test]
fn interleaved_segments_built_by_hand_read_as_nptdms_reads_them() {
    let dir = tempfile::tempdir().unwrap();
    let n = 5u64;
    let mut meta = 4u32.to_le_bytes().to_vec();
    meta.extend(string("/'daq'"));
    meta.extend(u32::MAX.to_le_bytes());
    meta.extend(0u32.to_le_bytes());
    for (name, code, props) in [
        ("a", 10u32, vec![]),
        ("b", 9, vec![]),
        (
            "c",
            2,
            vec![
                ("NI_Scale[0]_Linear_Slope", 0.01f64),
                ("NI_Scale[0]_Linear_Y_Intercept", 2.0),
            ],
        ),
    ] {
        meta.extend(string(&format!("/'daq'/'{name}'")));
        meta.extend(20u32.to_le_bytes());
        meta.extend(code.to_le_bytes());
        meta.extend(1u32.to_le_bytes());
        meta.extend(n.to_le_bytes());
        let typed = !props.is_empty();
        meta.extend((props.len() as u32 + 2 * u32::from(typed)).to_le_bytes());
        for (p, v) in props {
            meta.extend(string(p));
            meta.extend(10u32.to_le_bytes());
            meta.extend(v.to_le_bytes());
        }
        if typed {
            meta.extend(string("NI_Number_Of_Scales"));
            meta.extend(3u32.to_le_bytes());
            meta.extend(1i32.to_le_bytes());
            meta.extend(string("NI_Scale[0]_Scale_Type"));
            meta.extend(0x20u32.to_le_bytes());
            meta.extend(string("Linear"));
        }
    }
    let truth = |k: u64| -> (Vec<f64>, Vec<f32>, Vec<i16>) {
        (
            (0..n).map(|i| (k * n + i) as f64 * 1.25 - 3.0).collect(),
            (0..n).map(|i| (k * n + i) as f32 * -0.5).collect(),
            (0..n).map(|i| (k * n + i) as i16 * 300 - 1000).collect(),
        )
    };
    let rows = |k: u64| -> Vec<u8> {
        let (a, b, c) = truth(k);
        (0..n as usize)
            .flat_map(|i| {
                let mut r = a[i].to_le_bytes().to_vec();
                r.extend(b[i].to_le_bytes());
                r.extend(c[i].to_le_bytes());
                r
            })
            .collect()
    };
    let mut first_raw = rows(0);
    first_raw.extend(rows(1));
    let mut file = segment(
        K_TOC_META_DATA | K_TOC_NEW_OBJ_LIST | K_TOC_RAW_DATA | K_TOC_INTERLEAVED,
        &meta,
        &first_raw,
    );
    file.extend(segment(K_TOC_RAW_DATA | K_TOC_INTERLEAVED, &[], &rows(2)));
    let path = dir.path().join("interleaved.tdms");
    std::fs::write(&path, &file).unwrap();

    let (mut a, mut b, mut c) = (Vec::new(), Vec::new(), Vec::new());
    for k in 0..3 {
        let (x, y, z) = truth(k);
        a.extend(x);
        b.extend(y.iter().map(|&v| f64::from(v)));
        c.extend(z.iter().map(|&v| f64::from(v) * 0.01 + 2.0));
    }
    let theirs = nptdms_values(dir.path(), &path);
    let tdms = TdmsFile::parse(&file).unwrap();
    for (name, want) in [("daq/a", &a), ("daq/b", &b), ("daq/c", &c)] {
        let got = tdms.values(tdms.find(name).unwrap()).unwrap();
        assert_same(name, &got, want);
        assert_same(
            &format!("npTDMS {name}"),
            &as_f64s(&theirs[name]["values"]),
            want,
        );
    }
}

/// A file cut anywhere inside a segment is an error naming the truncation, never a panic.
#[test]
fn a_file_cut_mid_segment_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("spec.json");
    let seg = |k: usize| {
        json!([{"group": "g", "channel": "x", "dtype": "float64",
                "values": segment_values(k, 40)[0]}])
    };
    std::fs::write(&spec, json!({"segments": [seg(0), seg(1)]}).to_string()).unwrap();
    let file = dir.path().join("two.tdms");
    python(&[Path::new("write"), &spec, &file]);
    let bytes = std::fs::read(&file).unwrap();
    let tdms = TdmsFile::parse(&bytes).unwrap();
    assert_eq!(tdms.values(tdms.find("x").unwrap()).unwrap().len(), 80);
    let half = bytes.len() / 2;
    for cut in [10, 100, half - 7, half + 30, bytes.len() - 1] {
        let err = TdmsFile::parse(&bytes[..cut]).unwrap_err().to_string();
        assert!(err.contains("truncated"), "cut at {cut}: {err}");
    }
}

/// A segment its writer never closed (next segment offset all ones), its last chunk cut short
/// mid-value: dlw reads the values that are whole, and npTDMS reads the same ones.
#[test]
fn an_unclosed_segment_reads_as_nptdms_reads_it() {
    let dir = tempfile::tempdir().unwrap();
    let mut meta = 2u32.to_le_bytes().to_vec();
    for name in ["a", "b"] {
        meta.extend(string(&format!("/'g'/'{name}'")));
        meta.extend(20u32.to_le_bytes());
        meta.extend(10u32.to_le_bytes());
        meta.extend(1u32.to_le_bytes());
        meta.extend(2u64.to_le_bytes());
        meta.extend(0u32.to_le_bytes());
    }
    let values = [1.0f64, 2.0, 10.0, 20.0, 3.0, 4.0, 30.0, 40.0, 5.0, 6.0];
    let mut raw: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    raw.extend([0u8; 4]);
    let mut file = segment(
        K_TOC_META_DATA | K_TOC_NEW_OBJ_LIST | K_TOC_RAW_DATA,
        &meta,
        &raw,
    );
    file[12..20].copy_from_slice(&u64::MAX.to_le_bytes());
    let path = dir.path().join("unclosed.tdms");
    std::fs::write(&path, &file).unwrap();
    let theirs = nptdms_values(dir.path(), &path);
    let tdms = TdmsFile::parse(&file).unwrap();
    for (name, want) in [
        ("g/a", vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
        ("g/b", vec![10.0, 20.0, 30.0, 40.0]),
    ] {
        let got = tdms.values(tdms.find(name).unwrap()).unwrap();
        assert_same(name, &got, &want);
        assert_same(
            &format!("npTDMS {name}"),
            &as_f64s(&theirs[name]["values"]),
            &want,
        );
    }
}
