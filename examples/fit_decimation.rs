//! The accuracy cost of `dlw fit`'s decimation (issue 7, Speed): fits PI (N = 10) and the
//! continuous PI to a simulated PI sensor (Joint A, characterization protocol) once with the
//! default decimation and once on every prefiltered sample (`decimation: Some(1)`), and evaluates
//! both fitted models on ALL prefiltered samples.
//!
//! `cargo run --release --example fit_decimation [DURATION_S]` (default 600 s); results in
//! `docs/performance.md`.

use std::time::Instant;

use dlw::design::Design;
use dlw::fit::{fit_sensor, FitOptions, ModelKind, PlayFit, PlayOrder};
use dlw::signal::{observe, Prefilter};
use dlw::sim::{plan, ProtocolKind, Recording, Scenario, SensorModelKind};
use dlw_estimator::SensorPlane;

fn rmse(fit: &PlayFit, strain: &[f64], ohm: &[f64]) -> f64 {
    let model = fit.predict(strain);
    let sum: f64 = model.iter().zip(ohm).map(|(m, r)| (m - r).powi(2)).sum();
    (sum / ohm.len() as f64).sqrt()
}

fn main() -> anyhow::Result<()> {
    let duration: f64 = std::env::args()
        .nth(1)
        .map(|a| a.parse())
        .transpose()?
        .unwrap_or(600.0);
    let design = Design::from_toml(include_str!("../designs/joint-a.toml"))?;
    let mut scenario = Scenario {
        protocol: Some(ProtocolKind::Characterization),
        duration_s: Some(duration),
        seed: 1,
        ..Scenario::default()
    };
    scenario.sensor1.model = SensorModelKind::Pi;
    let p = plan(&design, scenario, None)?;
    let recording = Recording {
        rig: p.rig(),
        samples: p.run()?.samples,
    };
    let prefilter = Prefilter::MovingAverage(100);
    let all = observe(
        &recording,
        &design.joint,
        SensorPlane::PlusYs,
        prefilter,
        Some(1),
    )?;
    println!(
        "{duration} s, {} samples, {} prefiltered samples for evaluation",
        recording.samples.time_s.len(),
        all.len()
    );
    for decimation in [None, Some(1)] {
        let options = FitOptions {
            model: ModelKind::Pi,
            order: PlayOrder::DEFAULT,
            prefilter,
            decimation,
        };
        let clock = Instant::now();
        let fit = fit_sensor(
            &recording,
            &design.joint,
            SensorPlane::PlusYs,
            &options,
            &|_| {},
        )?;
        let seconds = clock.elapsed().as_secs_f64();
        let pi = fit.pi.as_ref().map_err(|e| anyhow::anyhow!("{e}"))?;
        let cpi = fit
            .continuous_pi
            .as_ref()
            .map_err(|e| anyhow::anyhow!("{e}"));
        println!(
            "decimation {:>4} ({} samples fitted, {seconds:.2} s): PI RMSE on all samples {:.2} Ω (on fitted {:.2} Ω); continuous PI {}",
            fit.observations.decimation,
            fit.observations.len(),
            rmse(pi, &all.strain, &all.ohm),
            pi.rmse_ohm,
            match cpi {
                Ok(c) => format!("{:.2} Ω", rmse(c, &all.strain, &all.ohm)),
                Err(e) => e.to_string(),
            }
        );
    }
    Ok(())
}
