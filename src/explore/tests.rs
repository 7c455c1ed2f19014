//! Explorer tests on small grids built in memory (`tests/explore_cli.rs` runs the command).

use super::*;

fn spec_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("designs")
}

fn try_load(text: &str) -> Result<Exploration, ExploreError> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("spec.toml");
    let text = text.replace(
        "BASE",
        &spec_dir().join("joint-d.toml").display().to_string(),
    );
    let text = text.replace(
        "TUBES",
        &spec_dir().join("tubes.toml").display().to_string(),
    );
    std::fs::write(&path, text).unwrap();
    Exploration::load(&path, &dir.path().join("out/x.toml"))
}

fn load(text: &str) -> Exploration {
    try_load(text).unwrap()
}

const SMALL: &str = r#"
base = "BASE"
tubes = "TUBES"
gauge_factor = 15.3
r0_ohm = 215e3
[vary]
tube = ["paper-1.6", "paper-2.5", "od2.0-id1.6"]
notch_arc_mm = { from = 2.0, to = 5.6, step = 0.4 }
notch_count = [6, 8, 10, 12]
notch_width_mm = [0.3, 0.5, 0.7]
[constraints]
min_range_deg = 15
[objectives]
maximize = ["sensitivity_ohm_per_deg", "range_deg"]
minimize = ["tendon_force_per_deg_n"]
"#;

/// The front equals a brute-force O(n²) computation written here.
#[test]
fn front_matches_brute_force_on_a_small_grid() {
    let x = load(SMALL);
    let screen = x.screen(&|_| {});
    let feasible = x.check_rules(&screen, &|_| {}).unwrap();
    assert!(feasible.len() > 20, "{}", feasible.len());
    let mut got = x.front(&feasible);
    got.sort_unstable();
    let score = |c: &Candidate| {
        [
            c.metrics.sensitivity_ohm_per_deg,
            c.metrics.range_deg,
            -c.metrics.tendon_force_per_deg_n,
        ]
    };
    let mut want = Vec::new();
    for (i, a) in feasible.iter().enumerate() {
        let sa = score(a);
        let beaten = feasible.iter().any(|b| {
            let sb = score(b);
            sb.iter().zip(&sa).all(|(y, x)| y >= x) && sb.iter().zip(&sa).any(|(y, x)| y > x)
        });
        if !beaten {
            want.push(i);
        }
    }
    assert_eq!(got, want);
    assert!(got.len() < feasible.len());
}

/// Every candidate the screen keeps meets the constraints, and every one it drops fails one
/// (or is refused by the geometry).
#[test]
fn screen_splits_by_the_constraints() {
    let x = load(SMALL);
    let screen = x.screen(&|_| {});
    assert_eq!(screen.evaluated, x.candidate_count());
    for c in &screen.survivors {
        let m = &c.metrics;
        assert!(
            m.closing_deg >= 15.0 && m.material_limit_deg >= 15.0 && m.saturation_limit_deg >= 15.0
        );
        assert!(m.range_deg >= 15.0);
    }
    let kept = screen.survivors.len() as u64;
    assert!(kept > 0 && kept + screen.geometry_refused < screen.evaluated);
}

#[test]
fn nothing_feasible_names_the_binding_constraint() {
    let x = load(&SMALL.replace("min_range_deg = 15", "min_range_deg = 200"));
    let screen = x.screen(&|_| {});
    let err = x.check_rules(&screen, &|_| {}).unwrap_err().to_string();
    assert!(err.starts_with("no candidate is feasible: the binding constraint is material strain within backbone_strain_limit = 0.03 up to min_range_deg = 200°"), "{err}");
}

#[test]
fn empty_lists_are_refused_before_any_work() {
    for (from, to) in [
        (
            r#"tube = ["paper-1.6", "paper-2.5", "od2.0-id1.6"]"#,
            "tube = []",
        ),
        ("[vary]", "[vary]\nstyle = []"),
    ] {
        let err = try_load(&SMALL.replace(from, to)).unwrap_err().to_string();
        assert!(err.contains("= [] must hold at least one value"), "{err}");
    }
    let err = try_load(&SMALL.replace("paper-1.6", "paper-9"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("\"paper-9\" is not in the catalogue") && err.contains("paper-2.5"),
        "{err}"
    );
}

/// Candidates that meet every constraint but all break a design rule: the message names the
/// rule (here the sensor's arms, 0.1 mm apart, closer than the clearance).
#[test]
fn all_breaking_a_rule_names_the_rule() {
    let x = load(&SMALL.replace("[vary]", "[vary]\nsensor_arc_mm = [0.1]"));
    let screen = x.screen(&|_| {});
    assert!(!screen.survivors.is_empty());
    let err = x.check_rules(&screen, &|_| {}).unwrap_err().to_string();
    assert!(
        err.contains("candidates that meet the constraints break a design rule"),
        "{err}"
    );
    assert!(
        err.contains("from sensor 1 arm (clearance 0.080 mm required)"),
        "{err}"
    );
}
