//! `cargo +nightly fuzz run lvm`: any bytes as the importer's DAQ file (docs/fuzzing.md).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = dlw_fuzz::entry::lvm(data);
});
