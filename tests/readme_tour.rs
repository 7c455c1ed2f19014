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

/// Commands with `--json` run after the tour, in its folder, on what the tour wrote: their JSON
/// output joins the tour's in the identity manifest below, so that a change of any command's
/// JSON shows there.
const JSON_RUNS: [&str; 13] = [
    "dlw inspect designs/joint-a.toml --json",
    "dlw inspect designs/joint-b.toml --json",
    "dlw inspect designs/joint-d.toml --json",
    "dlw explore designs/explore-example.toml -o json-explored --top 2 --json",
    "dlw fit --design designs/joint-d.toml char --validate rec -o json-fitted.toml --json",
    "dlw fit --design designs/joint-a.toml bench --model linear -o json-bench.toml --json",
    "dlw characterize --design designs/joint-d.toml char -o json-char --json",
    "dlw discover --design designs/joint-a.toml hidden -o json-discovered --json",
    "dlw estimate --config fitted.toml phantom --truth angles.csv -o json-estimates.csv --json",
    "dlw control --design designs/joint-d.toml --config d.toml --protocol random --filter ma:50 -o json-ctl --json",
    "dlw fluoro frames --baseline-s 0.5 -o json-angles.csv --json",
    "dlw import-recording --daq examples/bench/daq.csv --voltage AI0 --divider-ohm 99.6e3 --supply-v 5 --stroke AI2 --stroke-mm-per-v 0.5 --tracker examples/bench/aurora.csv -o json-bench --json",
    "dlw reproduce --short -o json-repro --json",
];

/// Runs one tour line in `dir`: `dlw …` with the built binary, anything else with `sh -c`.
/// `SOURCE_DATE_EPOCH` fixes the drawings' dates, so that the same input gives the same bytes.
fn run_line(dir: &Path, run: &str) -> std::process::Output {
    let mut command = if let Some(args) = run.strip_prefix("dlw ") {
        let mut c = Command::new(env!("CARGO_BIN_EXE_dlw"));
        c.args(args.split_whitespace());
        c
    } else {
        let mut c = Command::new("sh");
        c.arg("-c").arg(run);
        c
    };
    command
        .current_dir(dir)
        .env("SOURCE_DATE_EPOCH", "1764115200")
        .output()
        .unwrap()
}

/// Every line of the tour, in order, exits 0 and writes what it names (45 s unloaded); then
/// every file the tour and [`JSON_RUNS`] wrote, and what each printed, is the same to the byte
/// as the snapshot `readme_tour__tour_outputs.snap` holds (as SHA-256 digests, after the run's
/// wall-clock timings are masked). A refactoring that must not change behaviour is shown not
/// to by this snapshot staying as it is; a change that means to change an output updates it
/// (`INSTA_UPDATE=always cargo test --test readme_tour`, then review the diff).
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
    let mut printed = Vec::new();
    let lines = tour_lines(&readme);
    let runs = lines.iter().map(String::as_str).chain(JSON_RUNS);
    for (i, line) in runs.enumerate() {
        let mut run = line.to_owned();
        if !full && run.starts_with("dlw reproduce") && !run.contains("--short") {
            run.push_str(" --short");
        }
        let o = run_line(dir.path(), &run);
        if !o.status.success() {
            failures.push(format!(
                "`{run}` exited {:?}: {}",
                o.status.code(),
                String::from_utf8_lossy(&o.stderr)
            ));
            continue;
        }
        for f in outputs(line) {
            if !dir.path().join(&f).exists() {
                failures.push(format!("`{run}` did not write {f}"));
            }
        }
        printed.push((format!("stdout of line {:02}: {line}", i + 1), o.stdout));
    }
    assert!(failures.is_empty(), "{failures:#?}");
    if full {
        insta::assert_snapshot!("tour_outputs", manifest(dir.path(), &printed));
    }
}

/// One line per file under `dir` (the links to `designs/` and `examples/` left out) and per
/// printed output: its SHA-256 and its name, sorted by name.
fn manifest(dir: &Path, printed: &[(String, Vec<u8>)]) -> String {
    use sha2::{Digest, Sha256};
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let entry = entry.unwrap();
            let kind = entry.file_type().unwrap();
            if kind.is_symlink() {
                continue;
            } else if kind.is_dir() {
                stack.push(entry.path());
            } else {
                let name = entry
                    .path()
                    .strip_prefix(dir)
                    .unwrap()
                    .display()
                    .to_string();
                files.push((name, std::fs::read(entry.path()).unwrap()));
            }
        }
    }
    files.sort();
    let mut out = String::new();
    for (name, bytes) in files.iter().chain(printed) {
        let digest = Sha256::digest(mask_timings(bytes));
        let hex: String = digest.iter().map(|b| format!("{b:02x}")).collect();
        out.push_str(&format!("{hex}  {name}\n"));
    }
    out
}

/// The bytes with the run's own wall-clock timings masked: in JSON the values of the keys
/// `timings_s` (fit, an object) and `seconds` (reproduce, a number); in text, a number of
/// seconds after `in ` (`fitted … in 1.77 s`) or in parentheses (`report repro (8.4 s)`).
/// Everything else is kept to the byte, key order and spacing included.
fn mask_timings(bytes: &[u8]) -> Vec<u8> {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return bytes.to_vec();
    };
    let text = mask_json_value(&mask_json_value(text, "\"timings_s\":"), "\"seconds\":");
    let mut out = String::with_capacity(text.len());
    let mut rest = text.as_str();
    while let Some(i) = rest.find(" s") {
        let (head, tail) = rest.split_at(i);
        let number_start = head
            .char_indices()
            .rev()
            .find(|&(_, c)| !(c.is_ascii_digit() || c == '.'))
            .map_or(0, |(j, c)| j + c.len_utf8());
        let before = &head[..number_start];
        let timed = number_start < head.len() && (before.ends_with("in ") || before.ends_with('('));
        out.push_str(if timed { before } else { head });
        if timed {
            out.push('…');
        }
        out.push_str(" s");
        rest = &tail[2..];
    }
    out.push_str(rest);
    out.into_bytes()
}

/// `text` with the value after each `key` (a number, or an object without nested braces)
/// replaced by `…`.
fn mask_json_value(text: &str, key: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(key) {
        let (head, tail) = rest.split_at(i + key.len());
        out.push_str(head);
        let value = tail.trim_start();
        out.push_str(&tail[..tail.len() - value.len()]);
        let end = if value.starts_with('{') {
            value.find('}').map_or(value.len(), |j| j + 1)
        } else {
            value
                .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
                .unwrap_or(value.len())
        };
        out.push('…');
        rest = &value[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn timings_are_masked_and_nothing_else() {
    let masked = |s: &str| String::from_utf8(mask_timings(s.as_bytes())).unwrap();
    assert_eq!(
        masked("fitted 10 samples in 1.77 s\n"),
        "fitted 10 samples in … s\n"
    );
    assert_eq!(masked("report r (8.4 s)"), "report r (… s)");
    assert_eq!(masked("a rest of 4.2 s; 0.5 s"), "a rest of 4.2 s; 0.5 s");
    assert_eq!(masked("Joint A — 3 s"), "Joint A — 3 s");
    assert_eq!(
        masked(r#"{"seconds": 3.2, "duration_s": 1.0}"#),
        r#"{"seconds": …, "duration_s": 1.0}"#
    );
    assert_eq!(
        masked(r#"{"timings_s": {"fit": 1.5, "total": 2.0},"x":1}"#),
        r#"{"timings_s": …,"x":1}"#
    );
}
