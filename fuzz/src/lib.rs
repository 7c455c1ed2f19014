//! The entry points the fuzz targets drive, shared with the stable proptest twins in
//! `tests/fuzz_inputs.rs` (which include `entry.rs` by path).

pub mod entry;
