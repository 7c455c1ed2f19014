//! `cargo +nightly fuzz run design_file`: any bytes as a design file (docs/fuzzing.md).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = dlw_fuzz::entry::design_file(data);
});
