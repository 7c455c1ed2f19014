//! The two claims of the paper's Section IV-C on the simulated bench: closed loop tracks a
//! relaxing, backlashed plant better than open loop, and it does so through the estimator
//! (a wrong sensor model makes it worse).

use dlw_estimator::{nominal_divider, EstimatorConfig, FilterConfig, JointConfig};
use dlw_geometry::NotchStyle;

use super::*;
use crate::sim::ProtocolKind;

/// Joint D with relaxation and backlash, the default linear UAN sensor (GF 15.3, R₀ 215 kΩ)
/// and the default noise.
fn scenario(duration_s: f64) -> Scenario {
    let mut sc = Scenario {
        protocol: Some(ProtocolKind::Random),
        duration_s: Some(duration_s),
        seed: 4,
        ..Scenario::default()
    };
    sc.plant.relaxation.enabled = true;
    sc.plant.relaxation.fraction = 0.15;
    sc.plant.backlash.enabled = true;
    sc.plant.backlash.width_mm = 0.1;
    sc
}

fn config(design: &Design, gauge_factor: f64) -> EstimatorConfig {
    let mut c = EstimatorConfig::nominal_linear(
        JointConfig::from_joint(&design.joint),
        gauge_factor,
        215e3,
        nominal_divider(),
    )
    .unwrap();
    c.output_filter = FilterConfig::MovingAverage { samples: 50 };
    c
}

fn joint_d() -> Design {
    Design::from_toml(include_str!("../../designs/joint-d.toml")).unwrap()
}

fn run(design: &Design, sc: Scenario, gauge_factor: f64) -> ControlRun {
    Control::new(
        design,
        sc,
        &DesiredSource::Protocol,
        config(design, gauge_factor),
        PAPER_GAINS,
        None,
    )
    .unwrap()
    .run()
    .unwrap()
}

#[test]
fn closed_loop_beats_open_loop_on_a_relaxing_plant() {
    let design = joint_d();
    let r = run(&design, scenario(200.0), 15.3);
    let [open, closed] = r.metrics;
    eprintln!("open {open:?}\nclosed {closed:?}");
    assert!(
        closed.actual_vs_desired_rmse_deg < 0.6 * open.actual_vs_desired_rmse_deg,
        "closed {closed:?} open {open:?}"
    );
    // Closed loop drives the sensed angle to the desired one.
    assert!(closed.sensed_vs_desired_rmse_deg < open.sensed_vs_desired_rmse_deg);
    // Without relaxation and backlash there is nothing for feedback to fix: open loop is
    // already as good as the sensor, and both stay within the noise.
    let mut plain = scenario(200.0);
    plain.plant = Default::default();
    let [o, _] = run(&design, plain, 15.3).metrics;
    assert!(o.actual_vs_desired_rmse_deg < 0.5, "{o:?}");
}

#[test]
fn a_wrong_sensor_model_makes_closed_loop_worse() {
    let design = joint_d();
    let right = run(&design, scenario(200.0), 15.3);
    let wrong = run(&design, scenario(200.0), 15.3 * 1.3);
    let (r, w) = (right.metrics[1], wrong.metrics[1]);
    eprintln!("right {r:?}\nwrong {w:?}");
    assert!(
        w.actual_vs_desired_rmse_deg > 2.0 * r.actual_vs_desired_rmse_deg,
        "right {r:?} wrong {w:?}"
    );
    // Open loop ignores the sensor: the same trajectory whatever the config.
    assert_eq!(right.traces[0].actual_deg, wrong.traces[0].actual_deg);
}

#[test]
fn refuses_bad_inputs_before_running() {
    let design = joint_d();
    let sc = scenario(1.0);
    let make = |config: EstimatorConfig, gains: Gains, mt: Option<f64>| {
        Control::new(
            &design,
            sc.clone(),
            &DesiredSource::Protocol,
            config,
            gains,
            mt,
        )
        .map(|_| ())
        .unwrap_err()
        .to_string()
    };
    let bad_kp = Gains {
        kp_mm_per_deg: -0.1,
        ..PAPER_GAINS
    };
    let e = make(config(&design, 15.3), bad_kp, None);
    assert!(e.contains("kp = -0.1") && e.contains("at least 0"), "{e}");
    let nan_ki = Gains {
        ki_mm_per_deg_s: f64::NAN,
        ..PAPER_GAINS
    };
    assert!(make(config(&design, 15.3), nan_ki, None).contains("ki = NaN"));
    let e = make(config(&design, 15.3), PAPER_GAINS, Some(0.0));
    assert!(e.contains("m_t = 0"), "{e}");
    // A BSN (two-sensor) config on the one-sensor Joint D.
    let c = crate::sim::test_design(NotchStyle::Bsn);
    let two = EstimatorConfig::nominal_linear(
        JointConfig::from_joint(&c.joint),
        1.28,
        74e3,
        nominal_divider(),
    )
    .unwrap();
    let e = make(two, PAPER_GAINS, None);
    assert!(
        e.contains("reads 2 sensors") && e.contains("Joint D") && e.contains("carries 1"),
        "{e}"
    );
}

/// The result's JSON has `dlw control --json`'s keys in its order, the output paths only once
/// written, and its summary and report section carry the run's numbers.
#[test]
fn result_serializes_summarizes_and_places_its_section() {
    use crate::analysis::{Analysis, Placement};
    let design = joint_d();
    let control = Control::new(
        &design,
        scenario(5.0),
        &DesiredSource::Protocol,
        config(&design, 15.3),
        PAPER_GAINS,
        None,
    )
    .unwrap();
    let run = control.run().unwrap();
    let mut result = ControlResult::new(control, run);
    let keys = |r: &ControlResult| -> Vec<String> {
        let text = crate::finite::to_json(r).unwrap();
        let json: serde_json::Map<String, serde_json::Value> = serde_json::from_str(&text).unwrap();
        // serde_json's map is sorted: read the order from the text.
        let mut keys: Vec<(usize, String)> = json
            .keys()
            .map(|k| (text.find(&format!("\n  \"{k}\"")).unwrap(), k.clone()))
            .collect();
        keys.sort();
        keys.into_iter().map(|(_, k)| k).collect()
    };
    let base = [
        "design",
        "samples",
        "duration_s",
        "sample_hz",
        "seed",
        "desired",
        "mt_deg_per_mm",
        "mt_source",
        "gains",
        "correction_limit_mm",
        "open_loop",
        "closed_loop",
        "paper",
    ];
    let mut expected: Vec<&str> = base.to_vec();
    expected.push("warnings");
    assert_eq!(keys(&result), expected);
    assert!(!result.summary().contains("report"));
    result.written_to(std::path::Path::new("out"));
    let mut expected: Vec<&str> = base.to_vec();
    expected.extend(["report", "csv", "warnings"]);
    assert_eq!(keys(&result), expected);
    let json = result.to_json().unwrap();
    assert_eq!(json["samples"], 2500);
    assert_eq!(
        json["paper"]["open_loop"]["actual_vs_desired_rmse_deg"],
        8.14
    );
    assert_eq!(json["report"], "out/report.html");

    let summary = result.summary();
    let open = result.run.metrics[0].actual_vs_desired_rmse_deg;
    assert!(
        summary.contains(&format!("actual vs desired    {open:>9.2}")),
        "{summary}"
    );
    assert!(summary.contains("  samples              out/control.csv"));

    let mut page = crate::report::Page::new("shared");
    result.add_to_page(
        &mut page,
        Placement {
            label: "Joint D",
            figure_prefix: "d",
        },
    );
    let alone = report::page(&result.control, &result.run);
    assert_eq!(page.blocks.len(), alone.blocks.len());
    let figures: Vec<&str> = page
        .blocks
        .iter()
        .filter_map(|b| match b {
            crate::report::Block::Figure { name, .. } => Some(name.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(
        figures,
        [
            "d-fig10a-open-loop",
            "d-fig10b-closed-loop",
            "d-tracking-error",
            "d-stroke"
        ]
    );
    assert!(page
        .blocks
        .contains(&crate::report::Block::Heading("Joint D: Setup".into())));
}
