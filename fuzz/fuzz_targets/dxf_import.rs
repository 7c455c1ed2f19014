//! `cargo +nightly fuzz run dxf_import`: any bytes as a DXF drawing (docs/fuzzing.md).
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = dlw_fuzz::entry::dxf_import(data);
});
