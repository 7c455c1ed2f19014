//! Stable-toolchain twins of the `cargo fuzz` targets (`fuzz/`, docs/fuzzing.md): random bytes
//! and mutated shipped files fed to the DXF importer, the design-file reader and the recording
//! reader, through the same entry points (`fuzz/src/entry.rs`, included here by path). Each
//! input must return (no panic) within [`TIME_LIMIT_S`] and allocate at most
//! [`ALLOC_LIMIT_BYTES`] at once. Those limits are hang and runaway-allocation detectors, as
//! libFuzzer's `-timeout` and `-malloc_limit_mb` are, set far above what any input takes; they
//! are not speed targets.
//!
//! Seeds: the shipped `designs/*.toml`, the DXF of every shipped design, and a short simulated
//! recording of Joints A and C. Mutations flip, insert, delete, duplicate and truncate bytes
//! and splice in tokens that matter to each format (huge and non-finite numbers, DXF group
//! codes and vertex counts, CSV headers, TOML brackets).
//!
//! `DLW_FUZZ_CASES` sets the cases per batch (default 128 per target, random bytes and mutated
//! seeds alike), `DLW_FUZZ_SECONDS` keeps running fresh batches from random seeds until that
//! much time has passed, and `DLW_FUZZ_SEED` (hex) replays a batch; the seed of every batch is
//! printed. Without either, one batch runs from a fixed seed, so `cargo test` is reproducible
//! and explores the same inputs every time. For example, ten minutes of the DXF target:
//!
//! ```sh
//! DLW_FUZZ_SECONDS=600 cargo test --release --test fuzz_inputs dxf -- --nocapture
//! ```

mod common;

#[path = "../fuzz/src/entry.rs"]
mod entry;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::time::{Duration, Instant};

use proptest::collection::vec;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestCaseError, TestRng, TestRunner};

/// Most time one input may take (s): a hang detector, far above any real input.
const TIME_LIMIT_S: f64 = 10.0;
/// Most memory one input may hold at once (bytes): a runaway-allocation detector.
const ALLOC_LIMIT_BYTES: usize = 256 << 20;

/// Counts this thread's live heap bytes and their peak, so each input's peak is its own even
/// with the targets running on parallel test threads.
struct Counting;

thread_local! {
    static LIVE: Cell<usize> = const { Cell::new(0) };
    static PEAK: Cell<usize> = const { Cell::new(0) };
}

fn note_alloc(size: usize) {
    let _ = LIVE.try_with(|live| {
        let now = live.get() + size;
        live.set(now);
        let _ = PEAK.try_with(|p| p.set(p.get().max(now)));
    });
}

fn note_free(size: usize) {
    let _ = LIVE.try_with(|live| live.set(live.get().saturating_sub(size)));
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note_alloc(layout.size());
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        note_free(layout.size());
        System.dealloc(ptr, layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note_free(layout.size());
        note_alloc(new_size);
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Runs `f`, returning whether it panicked, its time and the peak heap it added.
fn measure(f: impl FnOnce() -> bool) -> (Result<bool, String>, Duration, usize) {
    let base = LIVE.with(Cell::get);
    PEAK.with(|p| p.set(base));
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(f)).map_err(|e| {
        e.downcast_ref::<String>()
            .cloned()
            .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_else(|| "a panic".into())
    });
    let took = start.elapsed();
    (result, took, PEAK.with(Cell::get).saturating_sub(base))
}

/// One mutation of a seed; positions are fractions of the current length.
#[derive(Debug, Clone)]
enum Mutation {
    Flip(u32, u8),
    Insert(u32, Vec<u8>),
    Delete(u32, u16),
    Duplicate(u32, u16),
    Truncate(u32),
    Token(u32, &'static str),
}

const TOKENS: &[&str] = &[
    "1e308",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "-0",
    "0",
    "1e-320",
    "99999999999999999999",
    "4294967296",
    "-1",
    "\n",
    "\r\n",
    "=",
    "[",
    "]",
    "[[",
    "\"",
    ",",
    ",,",
    "\0",
    "#",
    "  0\r\nSECTION\r\n",
    "  0\r\nENDSEC\r\n",
    "  0\r\nEOF\r\n",
    "  0\r\nLWPOLYLINE\r\n",
    " 90\r\n2147483647\r\n",
    " 90\r\n-5\r\n",
    " 70\r\n1\r\n",
    " 10\r\n1e308\r\n",
    " 20\r\nnan\r\n",
    "  8\r\nNOTCHES\r\n",
    "  8\r\nTUBE\r\n",
    "1001\r\nDLW\r\n",
    "1070\r\n32767\r\n",
    "1040\r\n-1e300\r\n",
    "$INSUNITS\r\n 70\r\n1\r\n",
    "time_s,stroke_mm,angle_deg,v1_V\n",
    "v2_V",
    "divider_ohm = []",
    "notch_count = 1e9",
    "style = \"bsn\"",
    "[fabrication]\n",
    "pad_turns = 4000000000",
];

impl Mutation {
    fn apply(&self, b: &mut Vec<u8>) {
        let at = |f: u32, len: usize| (f as usize) % (len + 1);
        match self {
            Mutation::Flip(f, x) => {
                if !b.is_empty() {
                    let i = at(*f, b.len() - 1);
                    b[i] ^= x | 1;
                }
            }
            Mutation::Insert(f, bytes) => {
                let i = at(*f, b.len());
                b.splice(i..i, bytes.iter().copied());
            }
            Mutation::Delete(f, n) => {
                let i = at(*f, b.len());
                let j = (i + *n as usize).min(b.len());
                b.drain(i..j);
            }
            Mutation::Duplicate(f, n) => {
                let i = at(*f, b.len());
                let j = (i + *n as usize).min(b.len());
                let piece = b[i..j].to_vec();
                b.splice(j..j, piece);
            }
            Mutation::Truncate(f) => {
                let i = at(*f, b.len());
                b.truncate(i);
            }
            Mutation::Token(f, t) => {
                let i = at(*f, b.len());
                // Replace the token-sized run at i, or insert at the end.
                let j = (i + t.len()).min(b.len());
                b.splice(i..j, t.bytes());
            }
        }
    }
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<u32>(), any::<u8>()).prop_map(|(f, x)| Mutation::Flip(f, x)),
        (any::<u32>(), vec(any::<u8>(), 1..16)).prop_map(|(f, v)| Mutation::Insert(f, v)),
        (any::<u32>(), 1u16..512).prop_map(|(f, n)| Mutation::Delete(f, n)),
        (any::<u32>(), 1u16..2048).prop_map(|(f, n)| Mutation::Duplicate(f, n)),
        any::<u32>().prop_map(Mutation::Truncate),
        (any::<u32>(), proptest::sample::select(TOKENS)).prop_map(|(f, t)| Mutation::Token(f, t)),
    ]
}

/// A seed with 1 to 8 mutations.
fn mutated(seeds: Vec<Vec<u8>>) -> impl Strategy<Value = Vec<u8>> {
    let n = seeds.len();
    (0..n, vec(mutation(), 1..8)).prop_map(move |(i, ms)| {
        let mut b = seeds[i].clone();
        for m in &ms {
            m.apply(&mut b);
        }
        b
    })
}

fn env_u64(name: &str) -> Option<u64> {
    let v = std::env::var(name).ok()?;
    let v = v.trim();
    u64::from_str_radix(
        v.trim_start_matches("0x"),
        if name.ends_with("SEED") { 16 } else { 10 },
    )
    .ok()
}

/// What one target's run saw.
#[derive(Debug, Default)]
struct Stats {
    cases: u64,
    accepted: u64,
    slowest: Duration,
    peak_bytes: usize,
}

/// Feeds `target` random bytes and mutated `seeds` in batches (see the module docs), failing
/// on a panic, an input slower than [`TIME_LIMIT_S`] or one allocating more than
/// [`ALLOC_LIMIT_BYTES`].
fn fuzz(name: &str, seeds: Vec<Vec<u8>>, target: &dyn Fn(&[u8]) -> bool) -> Stats {
    fuzz_within(name, seeds, target, ALLOC_LIMIT_BYTES)
}

/// [`fuzz`] with another allocation limit (the harness's own test).
fn fuzz_within(
    name: &str,
    seeds: Vec<Vec<u8>>,
    target: &dyn Fn(&[u8]) -> bool,
    alloc_limit: usize,
) -> Stats {
    assert!(!seeds.is_empty());
    for s in &seeds {
        let (r, _, _) = measure(|| target(s));
        assert!(r.is_ok(), "{name}: a shipped seed panics: {r:?}");
    }
    let cases = env_u64("DLW_FUZZ_CASES").unwrap_or(64) as u32;
    // The fixed seed of a plain `cargo test` run.
    const CI_SEED: u64 = 0x00d1_f00d_5eed;
    let budget = env_u64("DLW_FUZZ_SECONDS").map(Duration::from_secs);
    let fixed_seed = env_u64("DLW_FUZZ_SEED");
    let start = Instant::now();
    let stats = std::cell::RefCell::new(Stats::default());
    let strategy = prop_oneof![vec(any::<u8>(), 0..4096), mutated(seeds)];
    for batch in 0u64.. {
        let seed = fixed_seed
            .or(if budget.is_none() {
                Some(CI_SEED)
            } else {
                None
            })
            .unwrap_or_else(|| {
                let t = std::time::SystemTime::now()
                    .duration_since(std::time::UNIX_EPOCH)
                    .map_or(0, |d| d.as_nanos() as u64);
                t ^ batch.wrapping_mul(0x9e37_79b9_7f4a_7c15)
            });
        let mut key = [0u8; 32];
        key[..8].copy_from_slice(&seed.to_le_bytes());
        // Shrinking is capped so a failure is reported in seconds; the batch seed replays it.
        let config = Config {
            cases: 2 * cases,
            failure_persistence: None,
            max_shrink_iters: 256,
            ..Config::default()
        };
        let mut runner =
            TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &key));
        let result = runner.run(&strategy, |input| {
            let (r, took, peak) = measure(|| target(&input));
            let mut s = stats.borrow_mut();
            s.cases += 1;
            s.slowest = s.slowest.max(took);
            s.peak_bytes = s.peak_bytes.max(peak);
            match r {
                Err(panic) => Err(TestCaseError::fail(format!("panicked: {panic}"))),
                Ok(_) if took.as_secs_f64() > TIME_LIMIT_S => Err(TestCaseError::fail(format!(
                    "took {took:?}, more than {TIME_LIMIT_S} s"
                ))),
                Ok(_) if peak > alloc_limit => Err(TestCaseError::fail(format!(
                    "held {peak} bytes at once, more than {alloc_limit}"
                ))),
                Ok(ok) => {
                    s.accepted += u64::from(ok);
                    Ok(())
                }
            }
        });
        if let Err(e) = result {
            panic!("{name}: batch seed {seed:016x} (DLW_FUZZ_SEED={seed:x} replays it): {e}");
        }
        eprintln!("{name}: batch {batch} seed {seed:016x} ok");
        if fixed_seed.is_some() || !budget.is_some_and(|b| start.elapsed() < b) {
            break;
        }
    }
    let s = stats.into_inner();
    eprintln!(
        "{name}: {} inputs in {:.1} s, {} accepted, slowest {:?}, peak heap {} KiB",
        s.cases,
        start.elapsed().as_secs_f64(),
        s.accepted,
        s.slowest,
        s.peak_bytes / 1024
    );
    s
}

fn shipped_designs() -> Vec<std::path::PathBuf> {
    common::designs::shipped()
}

#[test]
fn dxf_importer_survives_random_and_mutated_drawings() {
    let seeds: Vec<Vec<u8>> = shipped_designs()
        .iter()
        .map(|p| {
            let checked =
                dlw::rules::check_file(dlw::design::DesignFile::read(p).unwrap()).unwrap();
            let clearance = checked.design.file.fabrication.clearance_mm();
            dlw::drawing::layout_to_dxf(&checked.layout, clearance).unwrap()
        })
        .collect();
    assert!(
        seeds.iter().all(|s| entry::dxf_import(s)),
        "the shipped drawings read back"
    );
    let s = fuzz("dxf_import", seeds, &entry::dxf_import);
    assert!(s.cases > 0);
}

#[test]
fn design_reader_survives_random_and_mutated_designs() {
    let seeds: Vec<Vec<u8>> = shipped_designs()
        .iter()
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    assert!(
        seeds.iter().all(|s| entry::design_file(s)),
        "the shipped designs pass"
    );
    let s = fuzz("design_file", seeds, &entry::design_file);
    assert!(s.cases > 0);
}

#[test]
fn recording_reader_survives_random_and_mutated_recordings() {
    let work = tempfile::tempdir().unwrap();
    let mut seeds = Vec::new();
    for (i, design) in ["joint-a.toml", "joint-c.toml"].iter().enumerate() {
        let out = work.path().join(format!("rec{i}"));
        let o = common::dlw(&[
            "simulate",
            "--design",
            &common::shipped_design(design),
            "--protocol",
            "random",
            "--seed",
            "1",
            "--duration-s",
            "0.2",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let mut seed = std::fs::read(out.join("rig.toml")).unwrap();
        seed.push(0);
        seed.extend(std::fs::read(out.join("data.csv")).unwrap());
        seeds.push(seed);
    }
    let dir = work.path().join("input");
    std::fs::create_dir(&dir).unwrap();
    assert!(
        seeds.iter().all(|s| entry::recording(s, &dir)),
        "the simulated recordings read back"
    );
    let s = fuzz("recording", seeds, &|data| {
        entry::recording(data, Path::new(&dir))
    });
    assert!(s.cases > 0);
}

/// TDMS seeds built from NI's format description: a segment with metadata (a float channel
/// with waveform properties, an i16 with a linear scale), a non-interleaved raw data chunk
/// repeated twice, then an interleaved segment reusing the layout.
fn tdms_seeds() -> Vec<Vec<u8>> {
    fn string(s: &str) -> Vec<u8> {
        let mut b = (s.len() as u32).to_le_bytes().to_vec();
        b.extend(s.as_bytes());
        b
    }
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
    let float = |name: &str, v: f64| {
        [
            string(name),
            10u32.to_le_bytes().to_vec(),
            v.to_le_bytes().to_vec(),
        ]
        .concat()
    };
    let text =
        |name: &str, v: &str| [string(name), 0x20u32.to_le_bytes().to_vec(), string(v)].concat();
    let mut meta = 2u32.to_le_bytes().to_vec();
    for (name, code, props) in [
        ("a", 10u32, vec![float("wf_increment", 0.002)]),
        (
            "b",
            2,
            vec![
                text("NI_Scale[0]_Scale_Type", "Linear"),
                float("NI_Scale[0]_Linear_Slope", 0.01),
                float("NI_Scale[0]_Linear_Y_Intercept", 1.5),
            ],
        ),
    ] {
        meta.extend(string(&format!("/'g'/'{name}'")));
        meta.extend(20u32.to_le_bytes());
        meta.extend(code.to_le_bytes());
        meta.extend(1u32.to_le_bytes());
        meta.extend(4u64.to_le_bytes());
        meta.extend((props.len() as u32).to_le_bytes());
        meta.extend(props.concat());
    }
    let chunk: Vec<u8> = (0..4)
        .flat_map(|i| f64::from(i).to_le_bytes())
        .chain((0..4i16).flat_map(|i| (i * 100).to_le_bytes()))
        .collect();
    let mut first = segment(0b1110, &meta, &[chunk.clone(), chunk].concat());
    let rows: Vec<u8> = (0..4)
        .flat_map(|i| {
            [
                f64::from(i).to_le_bytes().to_vec(),
                (i as i16).to_le_bytes().to_vec(),
            ]
            .concat()
        })
        .collect();
    let second = segment((1 << 3) | (1 << 5), &[], &rows);
    let one = first.clone();
    first.extend(second);
    vec![one, first]
}

#[test]
fn tdms_reader_survives_random_and_mutated_files() {
    let seeds = tdms_seeds();
    assert!(seeds.iter().all(|s| entry::tdms(s)), "the seeds read");
    let s = fuzz("tdms", seeds, &entry::tdms);
    assert!(s.cases > 0);
}

#[test]
fn lvm_reader_survives_random_and_mutated_files() {
    let mut seeds = Vec::new();
    for (sep, decimal, sep_name) in [("\t", ".", "Tab"), (",", ".", "Comma"), ("\t", ",", "Tab")] {
        let mut text = format!(
            "LabVIEW Measurement{sep}\nSeparator{sep}{sep_name}\nDecimal_Separator{sep}{decimal}\n\
             ***End_of_Header***{sep}\n\nChannels{sep}2\nSamples{sep}120{sep}120\n\
             X0{sep}0{sep}0\nDelta_X{sep}0{decimal}5{sep}0{decimal}5\n***End_of_Header***\n\
             X_Value{sep}A{sep}B{sep}Comment\n"
        );
        for i in 0..120 {
            let t = if sep_name == "Comma" {
                format!("{}", i as f64 * 0.5)
            } else {
                String::new()
            };
            text += &format!("{t}{sep}{i}{decimal}25{sep}-{i}\n");
        }
        seeds.push(text.into_bytes());
    }
    assert!(seeds.iter().all(|s| entry::lvm(s)), "the seeds read");
    let s = fuzz("lvm", seeds, &entry::lvm);
    assert!(s.cases > 0);
}

/// The harness itself can fail: a target that panics on some inputs, one that hoards memory.
#[test]
fn the_harness_catches_panics_and_hoarding() {
    // The deliberate panics would each print a message and backtrace; their payloads are
    // reported through the run's result instead.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let seeds = vec![b"seed".to_vec()];
    let panics = catch_unwind(|| {
        fuzz("panics", seeds.clone(), &|d: &[u8]| {
            assert!(d.len() < 8, "long input");
            true
        })
    });
    assert!(panics.is_err(), "a panicking target fails the run");
    let hoards = catch_unwind(|| {
        let limit = 1 << 20;
        fuzz_within(
            "hoards",
            seeds.clone(),
            &|d: &[u8]| {
                if d.len() > 100 {
                    let v = vec![1u8; limit + 1];
                    return v[d.len() % v.len()] == 1;
                }
                true
            },
            limit,
        )
    });
    std::panic::set_hook(hook);
    assert!(
        hoards.is_err(),
        "a target that allocates past the limit fails the run"
    );
}

/// Found by these tests and by `cargo fuzz run dxf_import` (docs/fuzzing.md): the `dxf` crate
/// (0.6.2) panics in its header reader on a date out of chrono's range, so `dlw import-dxf`
/// panicked (exit 101) on this 100-byte file instead of refusing it. The importer now catches
/// the reader's panic and reports a broken file.
#[test]
fn a_header_date_out_of_range_is_refused_not_a_panic() {
    for value in ["1e308", "1e10"] {
        let dxf = format!(
            "  0\r\nSECTION\r\n  2\r\nHEADER\r\n  9\r\n$TDCREATE\r\n 40\r\n{value}\r\n  0\r\nENDSEC\r\n  0\r\nEOF\r\n"
        );
        let (r, _, _) = measure(|| entry::dxf_import(dxf.as_bytes()));
        assert_eq!(r, Ok(false), "$TDCREATE = {value}");
    }
}
