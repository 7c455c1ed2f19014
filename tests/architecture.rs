//! The module graph's rules (issue 32, `docs/architecture.md`), checked on the code itself with
//! `scripts/deps.py` (the graph from the `crate::` paths) and `scripts/long_fns.py`:
//! no two modules use each other, the shared floor uses nothing above it, fabrication never uses
//! the sensing side and the sensing side uses only the design from it, no analysis borrows a
//! signal helper from `fit`, and no function in `src/` is longer than 120 lines.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

const SHARED: &[&str] = &[
    "stats", "fixed", "finite", "limits", "output", "report", "sensor",
];
const FABRICATION: &[&str] = &[
    "design", "layout", "process", "machine", "drawing", "rules", "toolpath", "post", "sheet",
    "job", "robot", "build",
];
/// The laser job's side of fabrication: what no sensing module may reach, even through others.
const LASER_JOB: &[&str] = &["post", "sheet", "job", "build"];
/// Above both sides: they join a design to what the sensing side predicts of it.
const ABOVE_BOTH: &[&str] = &["cli", "explore"];
/// What the sensing side may use from fabrication: the design file it was made from.
const SENSING_USES_FROM_FABRICATION: &[&str] = &["design", "layout", "robot"];

fn script(name: &str, args: &[&str]) -> (bool, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = Command::new("python3")
        .arg(root.join("scripts").join(name))
        .args(args)
        .output()
        .expect("python3 runs");
    (
        out.status.success(),
        String::from_utf8(out.stdout).expect("UTF-8"),
    )
}

fn graph() -> (BTreeMap<String, Vec<String>>, serde_json::Value) {
    let (ok, text) = script("deps.py", &["--json"]);
    assert!(ok, "deps.py failed");
    let json: serde_json::Value = serde_json::from_str(&text).expect("deps.py's JSON");
    let modules = serde_json::from_value(json["modules"].clone()).expect("modules");
    (modules, json)
}

#[test]
fn no_module_uses_one_that_uses_it_back() {
    let (modules, json) = graph();
    assert!(
        modules.len() > 20,
        "deps.py found {} modules",
        modules.len()
    );
    assert_eq!(
        json["cycles"],
        serde_json::json!([]),
        "modules that use each other"
    );
}

#[test]
fn floors_use_only_what_is_below_or_beside_them() {
    let (modules, _) = graph();
    let mut wrong = Vec::new();
    for (module, uses) in &modules {
        for used in uses {
            let (m, u) = (module.as_str(), used.as_str());
            let shared = |x: &str| SHARED.contains(&x);
            let fab = |x: &str| FABRICATION.contains(&x);
            if ABOVE_BOTH.contains(&m) || shared(u) {
                continue;
            }
            if shared(m) {
                wrong.push(format!("shared {m} uses {u}"));
            } else if fab(m) && !fab(u) {
                wrong.push(format!("fabrication's {m} uses sensing's {u}"));
            } else if !fab(m) && fab(u) && !SENSING_USES_FROM_FABRICATION.contains(&u) {
                wrong.push(format!("sensing's {m} uses fabrication's {u}"));
            }
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

/// A robot's description sits below the job and its fabrication (`build`) above it, so the
/// sensing side, which reads robots, never reaches the programs and setup sheets.
#[test]
fn the_sensing_side_never_reaches_the_laser_job() {
    let (modules, _) = graph();
    let sensing = modules.keys().filter(|m| {
        !FABRICATION.contains(&m.as_str())
            && !SHARED.contains(&m.as_str())
            && !ABOVE_BOTH.contains(&m.as_str())
    });
    let mut wrong = Vec::new();
    for start in sensing {
        let mut seen = std::collections::BTreeSet::new();
        let mut stack = vec![start.clone()];
        while let Some(m) = stack.pop() {
            for used in modules.get(&m).into_iter().flatten() {
                if seen.insert(used.clone()) {
                    stack.push(used.clone());
                }
            }
        }
        for m in LASER_JOB.iter().filter(|m| seen.contains(**m)) {
            wrong.push(format!("{start} reaches {m}"));
        }
    }
    assert!(wrong.is_empty(), "{wrong:#?}");
}

#[test]
fn no_analysis_borrows_signal_helpers_from_fit() {
    let helpers = [
        "observe",
        "Observations",
        "cycles",
        "phases",
        "fit_linear",
        "LinearFit",
        "TURN_THRESHOLD",
        "Prefilter",
        "Cycle",
        "Phase",
    ];
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut found = Vec::new();
    let mut stack = vec![src.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("src is readable") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                if !path.ends_with("fit") {
                    stack.push(path);
                }
                continue;
            }
            let text = std::fs::read_to_string(&path).expect("UTF-8 source");
            let code: String = text
                .lines()
                .map(|l| l.split("//").next().unwrap_or(""))
                .collect::<Vec<_>>()
                .join("\n");
            for (at, _) in code.match_indices("fit::") {
                let rest = &code[at + "fit::".len()..];
                // `fit::name` or a `fit::{a, b::c}` group.
                let names = match rest.strip_prefix('{') {
                    Some(group) => &group[..group.find('}').unwrap_or(group.len())],
                    None => rest,
                };
                let first_only = !rest.starts_with('{');
                let tokens = names
                    .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                    .filter(|t| !t.is_empty());
                let tokens: Vec<&str> = if first_only {
                    tokens.take(1).collect()
                } else {
                    tokens.collect()
                };
                for t in tokens {
                    if helpers.contains(&t) {
                        found.push(format!("{}: fit::{t}", path.display()));
                    }
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "signal helpers taken from fit: {found:#?}"
    );
}

#[test]
fn no_function_in_src_is_longer_than_120_lines() {
    let (ok, text) = script("long_fns.py", &[]);
    assert!(ok, "functions longer than 120 lines:\n{text}");
}
