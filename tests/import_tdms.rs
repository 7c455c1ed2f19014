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
    // The ToC mask is little-endian; the version and the two offsets follow the segment's
    // byte order (as npTDMS reads them).
    let big = toc & K_TOC_BIG_ENDIAN != 0;
    let mut s = b"TDSm".to_vec();
    s.extend(toc.to_le_bytes());
    let (next, raw_at) = ((meta.len() + raw.len()) as u64, meta.len() as u64);
    if big {
        s.extend(4713u32.to_be_bytes());
        s.extend(next.to_be_bytes());
        s.extend(raw_at.to_be_bytes());
    } else {
        s.extend(4713u32.to_le_bytes());
        s.extend(next.to_le_bytes());
        s.extend(raw_at.to_le_bytes());
    }
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

/// TDMS metadata and raw data written by hand, in either byte order (a segment with
/// `kTocBigEndian` writes its metadata's and raw data's numbers big-endian, and its lead-in's
/// version and offsets; the ToC mask stays little-endian).
struct Writer {
    big: bool,
    bytes: Vec<u8>,
}

impl Writer {
    fn new(big: bool) -> Self {
        Writer {
            big,
            bytes: Vec::new(),
        }
    }
    fn u32(&mut self, v: u32) -> &mut Self {
        let b = if self.big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        };
        self.bytes.extend(b);
        self
    }
    fn u64(&mut self, v: u64) -> &mut Self {
        let b = if self.big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        };
        self.bytes.extend(b);
        self
    }
    fn i32(&mut self, v: i32) -> &mut Self {
        self.u32(v as u32)
    }
    fn f64(&mut self, v: f64) -> &mut Self {
        self.u64(v.to_bits())
    }
    fn i16(&mut self, v: i16) -> &mut Self {
        let b = if self.big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        };
        self.bytes.extend(b);
        self
    }
    fn string(&mut self, s: &str) -> &mut Self {
        self.u32(s.len() as u32);
        self.bytes.extend(s.as_bytes());
        self
    }
    /// An object with a raw data index of type `code` and `n` values (`None`: no raw data;
    /// `Some(None)`: "as in the last segment"), and properties (name, type, writer).
    #[allow(clippy::type_complexity)]
    fn object(
        &mut self,
        path: &str,
        index: Option<Option<(u32, u64)>>,
        text_bytes: Option<u64>,
        props: &[(&str, &dyn Fn(&mut Writer))],
    ) -> &mut Self {
        self.string(path);
        match index {
            None => {
                self.u32(u32::MAX);
            }
            Some(None) => {
                self.u32(0);
            }
            Some(Some((code, n))) => {
                self.u32(if text_bytes.is_some() { 28 } else { 20 });
                self.u32(code).u32(1).u64(n);
                if let Some(b) = text_bytes {
                    self.u64(b);
                }
            }
        }
        self.u32(props.len() as u32);
        for (name, write) in props {
            self.string(name);
            write(self);
        }
        self
    }
}

const K_TOC_BIG_ENDIAN: u32 = 1 << 6;

/// Strings as TDMS raw data: the end offsets, then the bytes.
fn text_raw(w: &mut Writer, strings: &[&str]) -> u64 {
    let start = w.bytes.len();
    let mut end = 0u32;
    for s in strings {
        end += s.len() as u32;
        w.u32(end);
    }
    for s in strings {
        w.bytes.extend(s.as_bytes());
    }
    (w.bytes.len() - start) as u64
}

/// Each channel of a hand-made file and the values written to it.
type Truth = Vec<(&'static str, Vec<String>)>;

/// The layouts LabVIEW writes, built by hand from NI's "TDMS File Format Internal Structure":
/// **incremental metadata** (a later segment without `kTocNewObjList` that lists only a new
/// channel and an old one "as before", then a segment with no metadata, then one where a
/// channel has no data), **`NI_ArrayColumn`** channels (a 2-D array written as columns),
/// **big-endian** segments (metadata, numbers and text), and **interleaved big-endian** data.
/// dlw's values, and `dlw daq-info`'s types, lengths and first and last values, equal what was
/// written and what npTDMS reads.
#[test]
fn labview_layouts_built_by_hand_read_as_nptdms_reads_them() {
    let dir = tempfile::tempdir().unwrap();
    let q = |i: usize| (i as i32) * 7 - 20;
    let r = |i: usize| (i as f64) * 0.125 - 1.0;
    let column = |k: i32| {
        move |w: &mut Writer| {
            w.u32(3).i32(k);
        }
    };
    let mut files: Vec<(&str, Vec<u8>, Truth)> = Vec::new();

    // Incremental metadata with NI_ArrayColumn, little-endian.
    {
        let mut file = Vec::new();
        let mut m = Writer::new(false);
        m.u32(3);
        m.object(
            "/",
            None,
            None,
            &[("name", &|w: &mut Writer| {
                w.u32(0x20).string("incremental");
            })],
        );
        m.object("/'array'", None, None, &[]);
        m.object(
            "/'array'/'col0'",
            Some(Some((3, 4))),
            None,
            &[("NI_ArrayColumn", &column(0))],
        );
        let mut raw = Writer::new(false);
        (0..4).for_each(|i| {
            raw.i32(q(i));
        });
        file.extend(segment(
            K_TOC_META_DATA | K_TOC_NEW_OBJ_LIST | K_TOC_RAW_DATA,
            &m.bytes,
            &raw.bytes,
        ));
        // No kTocNewObjList: col0 as before, col1 appended.
        let mut m = Writer::new(false);
        m.u32(2);
        m.object("/'array'/'col0'", Some(None), None, &[]);
        m.object(
            "/'array'/'col1'",
            Some(Some((10, 4))),
            None,
            &[("NI_ArrayColumn", &column(1))],
        );
        let mut raw = Writer::new(false);
        (4..8).for_each(|i| {
            raw.i32(q(i));
        });
        (0..4).for_each(|i| {
            raw.f64(r(i));
        });
        file.extend(segment(
            K_TOC_META_DATA | K_TOC_RAW_DATA,
            &m.bytes,
            &raw.bytes,
        ));
        // No metadata: the same layout.
        let mut raw = Writer::new(false);
        (8..12).for_each(|i| {
            raw.i32(q(i));
        });
        (4..8).for_each(|i| {
            raw.f64(r(i));
        });
        file.extend(segment(K_TOC_RAW_DATA, &[], &raw.bytes));
        // col1 without data in this segment.
        let mut m = Writer::new(false);
        m.u32(1);
        m.object("/'array'/'col1'", None, None, &[]);
        let mut raw = Writer::new(false);
        (12..16).for_each(|i| {
            raw.i32(q(i));
        });
        file.extend(segment(
            K_TOC_META_DATA | K_TOC_RAW_DATA,
            &m.bytes,
            &raw.bytes,
        ));
        files.push((
            "incremental.tdms",
            file,
            vec![
                ("array/col0", (0..16).map(|i| q(i).to_string()).collect()),
                ("array/col1", (0..8).map(|i| r(i).to_string()).collect()),
            ],
        ));
    }

    // Big-endian: an i16, an f64 and a text channel, then a segment of raw data only.
    {
        // Each segment's three strings are 10 bytes, as the index the raw-only segment reuses says.
        let words = ["zero", "one", "two", "four", "six", "ten"];
        let mut file = Vec::new();
        let mut text = Writer::new(true);
        let text_bytes = text_raw(&mut text, &words[..3]);
        let mut m = Writer::new(true);
        m.u32(5);
        m.object("/", None, None, &[]);
        m.object("/'be'", None, None, &[]);
        m.object(
            "/'be'/'i16'",
            Some(Some((2, 3))),
            None,
            &[("unit_string", &|w: &mut Writer| {
                w.u32(0x20).string("V");
            })],
        );
        m.object(
            "/'be'/'f64'",
            Some(Some((10, 3))),
            None,
            &[("wf_increment", &|w: &mut Writer| {
                w.u32(10).f64(0.002);
            })],
        );
        m.object("/'be'/'text'", Some(Some((0x20, 3))), Some(text_bytes), &[]);
        let raw_of = |from: usize| {
            let mut raw = Writer::new(true);
            (from..from + 3).for_each(|i| {
                raw.i16(q(i) as i16);
            });
            (from..from + 3).for_each(|i| {
                raw.f64(r(i));
            });
            text_raw(&mut raw, &words[from..from + 3]);
            raw.bytes
        };
        file.extend(segment(
            K_TOC_META_DATA | K_TOC_NEW_OBJ_LIST | K_TOC_RAW_DATA | K_TOC_BIG_ENDIAN,
            &m.bytes,
            &raw_of(0),
        ));
        file.extend(segment(K_TOC_RAW_DATA | K_TOC_BIG_ENDIAN, &[], &raw_of(3)));
        files.push((
            "big-endian.tdms",
            file,
            vec![
                ("be/i16", (0..6).map(|i| q(i).to_string()).collect()),
                ("be/f64", (0..6).map(|i| r(i).to_string()).collect()),
                ("be/text", words.iter().map(|w| (*w).to_owned()).collect()),
            ],
        ));
    }

    // Interleaved and big-endian: two channels value by value, two chunks.
    {
        let mut m = Writer::new(true);
        m.u32(2);
        m.object("/'il'/'a'", Some(Some((3, 4))), None, &[]);
        m.object("/'il'/'b'", Some(Some((10, 4))), None, &[]);
        let mut raw = Writer::new(true);
        for i in 0..8 {
            raw.i32(q(i)).f64(r(i));
        }
        let file = segment(
            K_TOC_META_DATA
                | K_TOC_NEW_OBJ_LIST
                | K_TOC_RAW_DATA
                | K_TOC_INTERLEAVED
                | K_TOC_BIG_ENDIAN,
            &m.bytes,
            &raw.bytes,
        );
        files.push((
            "interleaved-big-endian.tdms",
            file,
            vec![
                ("il/a", (0..8).map(|i| q(i).to_string()).collect()),
                ("il/b", (0..8).map(|i| r(i).to_string()).collect()),
            ],
        ));
    }

    for (name, bytes, truth) in &files {
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        let theirs = nptdms_values(dir.path(), &path);
        let tdms = TdmsFile::parse(bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
            .args(["daq-info", &path.display().to_string(), "--json"])
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let info: Value = serde_json::from_slice(&o.stdout).unwrap();
        for (channel, want) in truth {
            let id = tdms.find(channel).unwrap_or_else(|e| panic!("{name}: {e}"));
            let ours: Vec<String> = if tdms.is_text(id) {
                tdms.texts(id)
            } else {
                tdms.values(id)
                    .unwrap()
                    .iter()
                    .map(f64::to_string)
                    .collect()
            };
            assert_eq!(
                &ours, want,
                "{name} {channel}: dlw against what was written"
            );
            let npt: Vec<String> = theirs[*channel]["values"]
                .as_array()
                .unwrap_or_else(|| panic!("{name}: npTDMS has no {channel}: {theirs}"))
                .iter()
                .map(|v| match v {
                    Value::String(s) => s.clone(),
                    v => v.as_f64().unwrap().to_string(),
                })
                .collect();
            assert_eq!(
                &npt, want,
                "{name} {channel}: npTDMS against what was written"
            );
            let listed = info["channels"]
                .as_array()
                .unwrap()
                .iter()
                .find(|c| c["name"] == *channel)
                .unwrap_or_else(|| panic!("{name}: daq-info lists no {channel}: {info}"));
            assert_eq!(
                listed["length"].as_u64(),
                Some(want.len() as u64),
                "{listed}"
            );
            let shown = |v: &Value| match v {
                Value::String(s) => s.clone(),
                v => v.as_f64().unwrap().to_string(),
            };
            let first: Vec<String> = listed["first"]
                .as_array()
                .unwrap()
                .iter()
                .map(shown)
                .collect();
            let last: Vec<String> = listed["last"]
                .as_array()
                .unwrap()
                .iter()
                .map(shown)
                .collect();
            assert_eq!(first, want[..want.len().min(5)].to_vec(), "{listed}");
            assert_eq!(
                last,
                want[want.len().saturating_sub(2)..].to_vec(),
                "{listed}"
            );
        }
    }
    let info: Value = {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_dlw"))
            .args([
                "daq-info",
                &dir.path().join("big-endian.tdms").display().to_string(),
                "--json",
            ])
            .output()
            .unwrap();
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let i16 = &info["channels"][0];
    assert_eq!(i16["type"], "Int16");
    assert_eq!(i16["unit"], "V");
    assert_eq!(info["channels"][1]["increment_s"].as_f64(), Some(0.002));
    assert_eq!(info["channels"][2]["type"], "String");
}
