//! `cargo +nightly fuzz run recording`: any bytes as a recording folder, `rig.toml` NUL
//! `data.csv` (docs/fuzzing.md).
#![no_main]

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

/// One folder per fuzzing process, rewritten for every input.
static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();

fuzz_target!(|data: &[u8]| {
    let dir = DIR.get_or_init(|| tempfile::tempdir().expect("a temporary folder"));
    let _ = dlw_fuzz::entry::recording(data, dir.path());
});
