//! `dlw::calibrate` recovers known parameters: a bench at a point chosen here is reproduced,
//! its numbers become the targets, and the calibration, started from the ideal bench's design
//! of experiments, lands back on the point within each parameter's identifiability.
//!
//! Which parameters these metrics identify (docs/experiments.md): the ADC's correlated noise
//! sets Joint C's errors (its sensors give 0.3-0.6 mV per degree, Joints A and B 7-9); Joint A's
//! hysteresis share sets the gap between its linear and PI estimates; Joint D's relaxation sets
//! Table VI's open loop. The tracker's white noise is in the search but not identified: it adds
//! in quadrature to errors of several degrees (at this size the 2 s average's smoothing of the
//! fast ramps dominates), so 0.3° or 0.6° of it moves no RMSE by more than the tolerance
//! (measured: truth 0.55 of its range, recovered 0.92). Not identified either (and left out
//! here): the ADC noise's correlation time against its size (only their combination survives
//! the 2 s average), the temperature wander against a sensor's coefficient (only the product
//! reaches the resistance), the tracker's correlated error against its time constant.
//!
//! About 150 s in release on two loaded cores (22 short evaluations), too long for CI's debug
//! build: it runs with `DLW_CALIBRATE_RECOVERY=1` (`cargo test --release --test
//! calibrate_recovery`). Measured: ADC correlated noise 0.349 (truth 0.35), Joint A's
//! hysteresis share 0.636 (0.75), Joint D's relaxation 0.638 (0.6); objective 7.9 against
//! 2109 at the ideal bench's point.

use dlw::calibrate::{Calibration, Knob, Metric, Options, Scope, Space, Target};

/// The recovery runs short (every timing a fifth, one repetition): each evaluation a few
/// tenths of a second in release.
const SCALE: f64 = 0.2;

fn space() -> Space {
    let keep = |k: Knob, s: Scope| {
        matches!(
            (k, s),
            (Knob::TrackerWhiteDeg, _)
                | (Knob::AdcCorrelatedV, _)
                | (Knob::HysteresisShare, Scope::Sensor('A', 1))
                | (Knob::NoisePpm | Knob::NoiseTauS, Scope::Sensor('A', 1))
                | (Knob::NoisePpm | Knob::NoiseTauS, Scope::Sensor('C', 2))
                | (Knob::RelaxationFraction, Scope::Plant('D'))
        )
    };
    Space {
        parameters: Space::paper()
            .parameters
            .into_iter()
            .filter(|p| keep(p.knob, p.scope))
            .collect(),
    }
}

#[test]
fn the_calibration_recovers_the_parameters_of_a_known_bench() {
    if std::env::var_os("DLW_CALIBRATE_RECOVERY").is_none() {
        eprintln!("skipped: set DLW_CALIBRATE_RECOVERY=1 (about 2 min in release)");
        return;
    }
    for truth in &TRUTHS {
        recover(truth);
    }
}

/// Reproduces the bench at `truth`, calibrates from its numbers, and checks every identified
/// parameter comes back within [`IDENTIFIED_WITHIN`].
fn recover(truth: &[(&str, f64)]) {
    let options = Options {
        design_points: 20,
        rounds: 3,
        local_points: 3,
        full_checks: 1,
        seed: 5,
        duration_scale: SCALE,
        side_conditions: false,
    };
    let space = space();
    let names: Vec<String> = space.parameters.iter().map(|p| p.name()).collect();
    let truth_u: Vec<f64> = names
        .iter()
        .map(|n| {
            truth
                .iter()
                .find(|(name, _)| name == n)
                .unwrap_or_else(|| panic!("no truth for {n}"))
                .1
        })
        .collect();
    let c = Calibration::new(space, options).unwrap();
    let measured = c.run(&truth_u, 1).unwrap();
    let all = Metric::all();
    let targets: Vec<Target> = Metric::TARGETS
        .into_iter()
        .filter_map(|metric| {
            let k = all.iter().position(|m| *m == metric)?;
            Some(Target {
                metric,
                paper: measured.values[k]?,
                tolerance: 0.05,
            })
        })
        .collect();
    assert_eq!(targets.len(), Metric::TARGETS.len(), "{measured:?}");
    let mut c = c.with_targets(targets);
    c.design().unwrap();
    for round in 0..options.rounds {
        c.round(round).unwrap();
    }
    let best = c.best().unwrap().clone();
    let ideal = c.space.ideal();
    let at_ideal = c.objective(&c.run(&ideal, 1).unwrap());
    let found = c.objective(&best);
    eprintln!("objective {found} (ideal point {at_ideal})");
    for (i, name) in names.iter().enumerate() {
        eprintln!(
            "{name}: truth {:.3}, recovered {:.3} ({:+.3}), ideal {:.3}",
            truth_u[i],
            best.u[i],
            best.u[i] - truth_u[i],
            ideal[i]
        );
    }
    assert!(found < 0.05 * at_ideal, "{found} against {at_ideal}");
    for (i, name) in names.iter().enumerate() {
        if NOT_IDENTIFIED.contains(&name.as_str()) {
            continue;
        }
        assert!(
            (best.u[i] - truth_u[i]).abs() < IDENTIFIED_WITHIN,
            "{name}: recovered {:.3}, truth {:.3} (ideal {:.3})",
            best.u[i],
            truth_u[i],
            ideal[i]
        );
    }
}

/// Two known benches, by parameter: each one's point in the unit box (a share of each range;
/// the correlation times on a log scale). The second puts every parameter on the other side
/// of the first, most of them far from the ideal bench, so a parameter the search leaves at
/// the ideal value cannot pass both by sitting near a truth.
const TRUTHS: [[(&str, f64); 8]; 2] = [
    [
        ("tracker_white_deg", 0.55),
        ("adc_correlated_v", 0.35),
        ("A.sensor1.hysteresis_share", 0.75),
        // 5000 ppm with a 12 s correlation time.
        ("A.sensor1.noise_ppm", 0.5),
        ("A.sensor1.noise_tau_s", 0.6),
        // 3000 ppm with a 4.2 s correlation time.
        ("C.sensor2.noise_ppm", 0.3),
        ("C.sensor2.noise_tau_s", 0.4),
        ("D.relaxation_fraction", 0.6),
    ],
    [
        ("tracker_white_deg", 0.25),
        ("adc_correlated_v", 0.7),
        ("A.sensor1.hysteresis_share", 0.3),
        // 8000 ppm with a 1 s correlation time.
        ("A.sensor1.noise_ppm", 0.8),
        ("A.sensor1.noise_tau_s", 0.13),
        // 7000 ppm with a 45 s correlation time.
        ("C.sensor2.noise_ppm", 0.7),
        ("C.sensor2.noise_tau_s", 0.85),
        ("D.relaxation_fraction", 0.3),
    ],
];

/// How close (in the unit box, a share of each parameter's range) an identified parameter
/// comes back.
const IDENTIFIED_WITHIN: f64 = 0.15;

/// Searched but not identified by these metrics (see the module doc).
const NOT_IDENTIFIED: [&str; 1] = ["tracker_white_deg"];

/// `dlw calibrate --start`: the start point joins the design, is the first point checked at
/// full size, and the result is the best full-size check, so never worse at full size than the
/// start. On a space of two parameters at a fiftieth of the paper's timings (9 s in the
/// test profile on two loaded cores); code that ignores the start fails the first two
/// asserts, code that returns the last check instead of the best fails the third whenever
/// they differ.
#[test]
fn a_start_point_is_evaluated_checked_first_and_the_result_is_the_best_full_check() {
    let space = Space {
        parameters: Space::paper()
            .parameters
            .into_iter()
            .filter(|p| {
                matches!(
                    (p.knob, p.scope),
                    (Knob::AdcCorrelatedV, _) | (Knob::RelaxationFraction, Scope::Plant('D'))
                )
            })
            .collect(),
    };
    assert_eq!(space.len(), 2);
    let options = Options {
        design_points: 3,
        rounds: 1,
        local_points: 1,
        full_checks: 1,
        seed: 3,
        duration_scale: 0.02,
        side_conditions: false,
    };
    // Off the design's strata and away from the ideal point.
    let start = vec![0.93, 0.071];
    let mut c = Calibration::new(space, options)
        .unwrap()
        .with_start(start.clone());
    let result = c.run_all(&|_| {}).unwrap();
    assert!(
        c.evaluations.iter().any(|e| e.u == start),
        "the start was not evaluated short-sized"
    );
    assert_eq!(c.full[0].u, start, "the start is the first full-size check");
    assert_eq!(c.full.len(), 1 + options.full_checks);
    let best = c
        .full
        .iter()
        .min_by(|a, b| c.objective_full(a).total_cmp(&c.objective_full(b)))
        .unwrap();
    eprintln!(
        "full checks: {:?}",
        c.full
            .iter()
            .map(|e| (e.u.clone(), c.objective_full(e)))
            .collect::<Vec<_>>()
    );
    assert_eq!(
        result.u, best.u,
        "the result is not the best full-size check"
    );
    assert!(c.objective_full(&result) <= c.objective_full(&c.full[0]));
}
