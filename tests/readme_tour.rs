//! The README's tour as a test: every line of the `sh` block under `## Tour` runs, in order, in
//! one temporary folder, with the built `dlw`; each must exit 0 and write the files it names
//! (after `-o`, `--report`, `--sheet`, `--dxf`, `--svg`, `--section`, `--overlay`, or a shell
//! `>` redirect).
//!
//! The README's own lines run unchanged, `dlw reproduce` at full size included (45 s for the
//! whole tour in the dev profile, unloaded). `DLW_TOUR_SHORT=1` gives `dlw reproduce` `--short`
//! for a quicker local run.

use std::path::Path;
use std::process::Command;

/// The options whose value is a file or folder the line writes.
const OUTPUT_FLAGS: [&str; 7] = [
    "-o",
    "--report",
    "--sheet",
    "--dxf",
    "--svg",
    "--section",
    "--overlay",
];

/// The lines of the first `sh` block after `## Tour`, comments and blank lines dropped.
fn tour_lines(readme: &str) -> Vec<String> {
    let after = readme
        .split_once("## Tour")
        .expect("the README has a ## Tour section")
        .1;
    let block = after
        .split_once("```sh\n")
        .expect("the tour has an sh block")
        .1
        .split_once("```")
        .expect("the tour's block is closed")
        .0;
    block
        .lines()
        .map(strip_comment)
        .filter(|l| !l.is_empty())
        .map(str::to_owned)
        .collect()
}

/// A line without its trailing `# comment` (a `#` at the start or after whitespace, outside
/// quotes).
fn strip_comment(line: &str) -> &str {
    let mut quote = None;
    let mut prev_space = true;
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '\'' | '"') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '#') if prev_space => return line[..i].trim(),
            _ => {}
        }
        prev_space = c.is_whitespace();
    }
    line.trim()
}

/// The files and folders a line says it writes.
fn outputs(line: &str) -> Vec<String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let mut out: Vec<String> = words
        .windows(2)
        .filter(|w| OUTPUT_FLAGS.contains(&w[0]) || w[0] == ">")
        .map(|w| w[1].to_owned())
        .collect();
    if words.first() == Some(&"cp") {
        out.extend(words.last().map(|s| (*s).to_owned()));
    }
    out
}

#[test]
fn the_tour_extracts_lines_and_their_outputs() {
    let lines = tour_lines("## Tour\n\n```sh\n# c\nprintf 'a # b' > x.toml  # c\ndlw draw d.toml --dxf a.dxf --svg a.svg # x\n```\n");
    assert_eq!(
        lines,
        [
            "printf 'a # b' > x.toml",
            "dlw draw d.toml --dxf a.dxf --svg a.svg"
        ]
    );
    assert_eq!(outputs(&lines[0]), ["x.toml"]);
    assert_eq!(outputs(&lines[1]), ["a.dxf", "a.svg"]);
}

/// Every line of the tour, in order, exits 0 and writes what it names (45 s unloaded).
#[test]
fn every_tour_line_runs_and_writes_its_outputs() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let full = std::env::var_os("DLW_TOUR_SHORT").is_none();
    let dir = tempfile::tempdir().unwrap();
    std::os::unix::fs::symlink(root.join("designs"), dir.path().join("designs")).unwrap();
    // The example bench's DAQ file and tracker log (`examples/bench/`), read by the tour.
    std::os::unix::fs::symlink(root.join("examples"), dir.path().join("examples")).unwrap();
    let mut failures = Vec::new();
    for line in tour_lines(&readme) {
        let mut run = line.clone();
        if !full && run.starts_with("dlw reproduce") && !run.contains("--short") {
            run.push_str(" --short");
        }
        let o = if let Some(args) = run.strip_prefix("dlw ") {
            Command::new(env!("CARGO_BIN_EXE_dlw"))
                .args(args.split_whitespace())
                .current_dir(dir.path())
                .output()
                .unwrap()
        } else {
            Command::new("sh")
                .arg("-c")
                .arg(&run)
                .current_dir(dir.path())
                .output()
                .unwrap()
        };
        if !o.status.success() {
            failures.push(format!(
                "`{run}` exited {:?}: {}",
                o.status.code(),
                String::from_utf8_lossy(&o.stderr)
            ));
            continue;
        }
        for f in outputs(&line) {
            if !dir.path().join(&f).exists() {
                failures.push(format!("`{run}` did not write {f}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
