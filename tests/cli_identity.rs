//! The commands the house moves (issue 32) touched, run on the shipped designs with their
//! outputs' SHA-256 pinned: the fabrication commands given a joint and a robot (build, program,
//! draw, import-dxf, program --from-dxf), the estimator configs (a robot's, one of its joints',
//! a BSN joint's), the robot's simulate, fit and estimate (with --json), daq-info on LabVIEW's
//! own files, and the refusals among them (exit code and message). The snapshot was taken from
//! the binary before the moves (commit 1e1b038) and is unchanged after them: what each command
//! prints, on stdout and stderr, and every byte it writes (`SOURCE_DATE_EPOCH` set, so the DXF
//! carries no wall-clock time).

use std::path::Path;
use std::process::Command;

/// Each command's arguments, run in order in one folder holding a copy of `designs/`.
const COMMANDS: &[&str] = &[
    "build designs/robot-bc.toml -o o/build-robot",
    "build designs/joint-a.toml -o o/build-a",
    "program designs/robot-bc.toml -o o/p.ngc --sheet o/p.md",
    "draw designs/robot-bc.toml --dxf o/r.dxf --svg o/r.svg",
    "draw designs/joint-b.toml --dxf o/b.dxf --svg o/b.svg --section o/bs.svg",
    "draw designs/robot-bc.toml --section o/rs.svg",
    "import-dxf o/r.dxf --design designs/robot-bc.toml",
    "import-dxf o/b.dxf --design designs/joint-b.toml",
    "import-dxf o/b.dxf",
    "program --from-dxf o/b.dxf --design designs/joint-b.toml -o o/pb.ngc --sheet o/pb.md",
    "program --from-dxf o/r.dxf --design designs/robot-bc.toml -o o/pr.ngc",
    "program --from-dxf o/b.dxf --design designs/joint-b.toml -o o/pbx.ngc --join-tolerance 0.5",
    "estimator-config designs/robot-bc.toml --gauge-factor 15 --r0-ohm 200000 -o o/rc.toml",
    "estimator-config designs/robot-bc.toml --joint 1 --gauge-factor 15 --r0-ohm 200000 -o o/rc1.toml",
    "estimator-config designs/robot-bc.toml --gauge-factor 15 --r0-ohm 200000 --joint 9 -o o/rc9.toml",
    "estimator-config designs/robot-bc.toml --joint 2 --gauge-factor 15 --r0-ohm 200000 -o o/rc2.json",
    "estimator-config designs/joint-c.toml --gauge-factor 15 --r0-ohm 200000 --second-gauge-factor 14 -o o/jb.toml",
    "estimator-config designs/joint-a.toml --gauge-factor 15 --r0-ohm 200000 --second-gauge-factor 14 -o o/ja.toml",
    "simulate --design designs/robot-bc.toml --protocol random --duration-s 120 -o o/rsim",
    "simulate --design designs/joint-a.toml --protocol random --duration-s 20 --noise realistic -o o/jsim",
    "fit --design designs/robot-bc.toml o/rsim -o o/rfit.toml --model linear",
    "fit --design designs/robot-bc.toml o/rsim -o o/rfit2.toml --json --model linear",
    "estimate --config o/rfit.toml o/rsim -o o/rest.csv",
    "estimate --config o/rfit.toml o/rsim -o o/rest2.csv --json",
    "estimate --config o/rc.toml o/rsim",
    "build designs/robot-bc.toml -o o/build-robot",
    "simulate --design designs/joint-a.toml --protocol random --duration-s 20 -o designs/joint-a.toml --force",
];

/// LabVIEW's own files (`../shared/real-files`), when present.
const REAL_FILES: &[&str] = &[
    "tdms-labview2010/type_01_int8_one_segment.tdms",
    "lvm/short.lvm",
];

fn sha(bytes: &[u8]) -> String {
    use sha2::{Digest, Sha256};
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// Every file under `dir`, sorted, as `SHA-256  path`.
fn files(dir: &Path, root: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            files(&path, root, out);
        } else {
            let name = path.strip_prefix(root).unwrap().display().to_string();
            out.push(format!("{}  {name}", sha(&std::fs::read(&path).unwrap())));
        }
    }
}

/// Runs `dlw args` in `dir` (`SOURCE_DATE_EPOCH` set) and adds its manifest lines: the exit
/// code and the arguments, then the SHA-256 of stdout and of stderr.
fn run(dir: &Path, n: usize, args: &[&str], lines: &mut Vec<String>) {
    let out = Command::new(env!("CARGO_BIN_EXE_dlw"))
        .args(args)
        .current_dir(dir)
        .env("SOURCE_DATE_EPOCH", "1700000000")
        .output()
        .unwrap();
    lines.push(format!(
        "{n} exit {} : {}",
        out.status.code().unwrap_or(-1),
        args.join(" ")
    ));
    lines.push(format!("{}  out.{n}.stdout", sha(&out.stdout)));
    lines.push(format!("{}  out.{n}.stderr", sha(&out.stderr)));
}

/// `dlw daq-info` on LabVIEW's own TDMS and LVM files, copied beside the run; skipped when
/// `../shared/real-files` is absent.
#[test]
fn daq_info_prints_what_it_did_before() {
    let real = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/real-files");
    if !real.is_dir() {
        eprintln!("skipped: {} is absent", real.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut lines = Vec::new();
    for (i, f) in REAL_FILES.iter().enumerate() {
        let name = Path::new(f).file_name().unwrap().to_str().unwrap();
        std::fs::copy(real.join(f), dir.path().join(name)).unwrap();
        run(dir.path(), 2 * i + 1, &["daq-info", name], &mut lines);
        run(
            dir.path(),
            2 * i + 2,
            &["daq-info", name, "--json"],
            &mut lines,
        );
    }
    insta::assert_snapshot!("daq_info_identity", lines.join("\n"));
}

#[test]
fn the_moved_commands_print_and_write_what_they_did_before() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = tempfile::tempdir().unwrap();
    copy_dir(&root.join("designs"), &dir.path().join("designs"));
    std::fs::create_dir(dir.path().join("o")).unwrap();
    let mut lines = Vec::new();
    for (i, c) in COMMANDS.iter().enumerate() {
        let args: Vec<&str> = c.split(' ').collect();
        run(dir.path(), i + 1, &args, &mut lines);
    }
    let mut written = Vec::new();
    files(&dir.path().join("o"), dir.path(), &mut written);
    written.sort();
    lines.extend(written);
    insta::assert_snapshot!("cli_identity", lines.join("\n"));
}
