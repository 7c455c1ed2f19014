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
