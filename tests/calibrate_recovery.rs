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
        eprintln!("skipped: set DLW_CALIBRATE_RECOVERY=1 (about 150 s in release)");
        return;
    }
    let options = Options {
        design_points: 12,
        rounds: 3,
        local_points: 3,
        full_checks: 1,
        seed: 5,
        duration_scale: SCALE,
        side_conditions: false,
    };
    let space = space();
    let names: Vec<String> = space.parameters.iter().map(|p| p.name()).collect();
    let truth_u = vec![0.55, 0.35, 0.75, 0.6];
    let c = Calibration::new(space, options).unwrap();
    let truth = c.run(&truth_u, 1).unwrap();
    let all = Metric::all();
    let targets: Vec<Target> = Metric::TARGETS
        .into_iter()
        .filter_map(|metric| {
            let k = all.iter().position(|m| *m == metric)?;
            Some(Target {
                metric,
                paper: truth.values[k]?,
                tolerance: 0.05,
            })
        })
        .collect();
    assert_eq!(targets.len(), Metric::TARGETS.len(), "{truth:?}");
    let mut c = c.with_targets(targets);
    c.design().unwrap();
    for round in 0..options.rounds {
        c.round(round).unwrap();
    }
    let best = c.best().unwrap().clone();
    let ideal = c.space.ideal();
    let at_ideal = c.objective(&c.run(&ideal, 1).unwrap());
    let found = c.objective(&best);
    eprintln!(
        "truth {truth_u:?}\nbest  {:?}\nobjective {found} (ideal point {at_ideal})",
        best.u
    );
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

/// How close (in the unit box, a share of each parameter's range) an identified parameter
/// comes back.
const IDENTIFIED_WITHIN: f64 = 0.15;

/// Searched but not identified by these metrics (see the module doc).
const NOT_IDENTIFIED: [&str; 1] = ["tracker_white_deg"];
