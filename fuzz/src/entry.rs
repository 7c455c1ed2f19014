//! What each fuzz target feeds its input to: the same public entry points the `dlw` commands
//! use. Each returns whether the input was accepted; the harness only cares that it returns
//! (no panic, no hang, bounded memory). Shared by `fuzz/fuzz_targets/*` (cargo fuzz) and
//! `tests/fuzz_inputs.rs` (proptest, stable), so both exercise exactly the same code.

use std::path::Path;

/// `dlw import-dxf` / `dlw program --from-dxf`: the bytes as a DXF drawing.
pub fn dxf_import(data: &[u8]) -> bool {
    dlw::drawing::layout_from_dxf(data).is_ok()
}

/// Every command's first step on a design file: TOML → `DesignFile` → the design rules, which
/// build the design and its layout (`rules::check_file`).
pub fn design_file(data: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(data) else {
        return false;
    };
    match dlw::design::DesignFile::from_toml(text) {
        Ok(file) => dlw::rules::check_file(file).is_ok(),
        Err(_) => false,
    }
}

/// Splits a recording input into `rig.toml` and `data.csv` at the first NUL byte.
pub fn split_recording(data: &[u8]) -> (&[u8], &[u8]) {
    match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[]),
    }
}

/// `dlw estimate`'s reader, `Recording::read`, on a folder holding the input's two files
/// (`rig.toml` NUL `data.csv`), written into `dir`.
pub fn recording(data: &[u8], dir: &Path) -> bool {
    let (rig, csv) = split_recording(data);
    if std::fs::write(dir.join("rig.toml"), rig).is_err()
        || std::fs::write(dir.join("data.csv"), csv).is_err()
    {
        return false;
    }
    dlw::sim::Recording::read(dir).is_ok()
}

/// `dlw import-recording --daq-format tdms`: the bytes as a TDMS file, every channel's values
/// and waveform read.
pub fn tdms(data: &[u8]) -> bool {
    let Ok(file) = dlw::import::tdms::TdmsFile::parse(data) else {
        return false;
    };
    let mut all = true;
    for name in file.channel_names() {
        match file.find(&name) {
            Ok(id) => {
                let _ = file.waveform(id);
                all &= file.values(id).is_ok();
            }
            Err(_) => all = false,
        }
    }
    all
}

/// `dlw import-recording --daq-format lvm`: the bytes as a LabVIEW measurement file, channels
/// `A` and `B` asked for.
pub fn lvm(data: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(data) else {
        return false;
    };
    dlw::import::lvm::daq_table(text, &["A", "B"], None, None).is_ok()
}
