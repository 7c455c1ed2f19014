//! The discovery report: the noise model, where each channel disagreed, the candidates' scores
//! round by round, the named effects, the gaps before and after, and per channel the held-out
//! overlay and residuals before and after (through the shared `report` layer), added to a page
//! by [`super::DiscoverResult`]'s [`crate::analysis::Analysis::add_to_page`].

use crate::analysis::Placement;
use crate::report::{Chart, Page, Series, SeriesStyle, Table, PALETTE};

use super::calibrate::{Calibration, Rivalry, COPIES, FALSE_NAME_RATE, MORE_COPIES, SCREEN_NATS};
use super::model::Stage;
use super::time_rival::TimeRivalry;
use super::{Discovery, Outcome, CLEAR_RATIO, THRESHOLD_NATS};

/// Adds the discovery's sections to `page`, placed by `at`.
pub fn add_sections(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    intro_section(page, outcome);
    result_section(page, outcome, at);
    calibration_section(page, outcome, at);
    out_of_range_text(page, outcome);
    unexplained_section(page, outcome, at);
    gap_section(page, outcome, at);
    noise_section(page, outcome, at);
    candidates_section(page, outcome, at);
    for c in &outcome.channels {
        channel_section(page, c, at);
    }
}

/// What is compared, how an effect is named, and the samples.
fn intro_section(page: &mut Page, outcome: &Outcome) {
    page.text(format!(
        "Each channel is compared on its own: the plant (stroke → tracker angle) and each sensor \
         (tracker angle → resistance). The base model is calibrated on the training blocks, the \
         noise model is an autoregressive process frozen from the rest at the start, and every \
         candidate effect is scored by its held-out gain in whitened log-likelihood (nats). A \
         sensor's candidates are built from the tracker angle smoothed with the tracker's own \
         noise model, never from the plant model. {} The named effect's shape is then refined and \
         the search repeats on what remains. {} samples at {:.0} Hz after block averaging.",
        if outcome.calibrated {
            "An effect is named when its evidence beats copies of the recording simulated \
             without it, and every rival name it is told from (below, under Calibration)."
                .to_owned()
        } else {
            format!(
                "With --fast, an effect is named when its evidence exceeds {THRESHOLD_NATS} and \
                 {CLEAR_RATIO} times the runner-up's on its channel, or, where a rival comes \
                 closer, when it still clears {THRESHOLD_NATS} added after the rival and the \
                 rival no longer does added after it."
            )
        },
        outcome.samples,
        1.0 / outcome.dt_s
    ));
}

/// The named effects, or why none is, and each ambiguity with what would separate it.
fn result_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    page.heading(at.titled("Result"));
    if outcome.discovered.is_empty() {
        page.text(if !outcome.ambiguous.is_empty() {
            "Nothing named clearly.".to_owned()
        } else if outcome.declined.is_empty() {
            "Nothing named: no candidate buys enough held-out evidence.".to_owned()
        } else {
            format!(
                "Nothing named: {} candidate(s) cleared the screen and were declined; why is \
                 given below.",
                outcome.declined.len()
            )
        });
    }
    let mut named = Table::new([
        "order",
        "effect",
        "channel",
        "evidence",
        "runner-up",
        "parameters",
    ]);
    for (i, d) in outcome.discovered.iter().enumerate() {
        named.row([
            (i + 1).to_string(),
            d.effect.name().to_owned(),
            d.channel.name(),
            format!("{:.1}", d.evidence),
            d.runner_up
                .map_or("–".into(), |(e, v)| format!("{} ({v:.1})", e.name())),
            d.parameters
                .iter()
                .map(|(k, v)| format!("{k} = {v:.4}"))
                .collect::<Vec<_>>()
                .join(", "),
        ]);
    }
    if !outcome.discovered.is_empty() {
        page.table(named);
    }
    for a in &outcome.ambiguous {
        page.text(format!(
            "Ambiguous on {}: {} — none beats the others clearly; the disagreement is shown below.{}",
            a.channel.name(),
            a.contenders
                .iter()
                .map(|(e, v)| format!("{} ({v:.1})", e.name()))
                .collect::<Vec<_>>()
                .join(", "),
            a.rivals
                .iter()
                .zip(&a.separate)
                .map(|(r, s)| format!(" {} against {}: {}. To tell them apart: {s}.", r.effect.name(), r.rival.name(), r.sentence()))
                .collect::<String>()
        ));
    }
}

/// What the generic regressors still find after the named effects.
fn unexplained_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    if !outcome.unexplained.is_empty() {
        page.heading(at.titled("What the library does not explain"));
        page.text(format!(
            "After the named effects, generic regressors (a curve of any shape, plays, lags, \
             time) still buy at least {} nats of held-out evidence on these channels: a real \
             effect outside the simulator's library, or one of another form.",
            super::unexplained::UNEXPLAINED_NATS
        ));
        let mut table = Table::new(["channel", "evidence", "where", "by kind"]);
        for u in &outcome.unexplained {
            table.row([
                u.channel.name(),
                format!("{:.1}", u.evidence),
                u.place.to_owned(),
                u.by_kind
                    .iter()
                    .map(|(k, e)| format!("{k:?} {e:.1}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            ]);
        }
        page.table(table);
    }
}

/// The held-out gap before and after each named effect.
fn gap_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    page.heading(at.titled("Gap between simulation and measurement (held out)"));
    let mut gaps = Table::new([
        "channel",
        "on",
        "before",
        "after each named effect",
        "after",
        "after / noise at rest",
        "in degrees of estimate",
    ]);
    for g in &outcome.gaps {
        gaps.row([
            g.channel.name(),
            g.on.to_owned(),
            format!("{:.4} {}", g.before, g.unit),
            g.steps
                .iter()
                .map(|(e, v)| format!("+{}: {v:.4}", e.name()))
                .collect::<Vec<_>>()
                .join(", "),
            format!("{:.4} {}", g.after, g.unit),
            rest_ratio(g).map_or("–".into(), |r| format!("{r:.1}")),
            match (g.before_deg, g.after_deg) {
                (Some(b), Some(a)) => format!("{b:.3}° → {a:.3}°"),
                _ => "–".into(),
            },
        ]);
    }
    page.table(gaps);
    let ratios: Vec<String> = outcome
        .gaps
        .iter()
        .filter_map(|g| rest_ratio(g).map(|r| format!("{r:.1} on {}", g.channel.name())))
        .collect();
    if !ratios.is_empty() {
        page.text(format!(
            "After the named effects, the held-out gap is this many times the noise at rest: {}. \
             The noise over a whole run can wander more than over the rest it is frozen from, so \
             a ratio above 1 names nothing by itself; where nothing is named or flagged, it is the \
             size of what, if anything, the tests could not tell from that noise.",
            ratios.join(", ")
        ));
    }
}

/// A channel's held-out gap after the named effects over its noise at rest; `None` when the
/// rest shows no noise.
fn rest_ratio(g: &super::Gap) -> Option<f64> {
    (g.noise_floor > 0.0 && g.after.is_finite()).then(|| g.after / g.noise_floor)
}

/// The noise model frozen from the rest, per channel.
fn noise_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    page.heading(at.titled("Noise model (frozen from the rest)"));
    let mut noise = Table::new(["channel", "σ at rest", "AR coefficients φ"]);
    for c in &outcome.channels {
        noise.row([
            c.channel.name(),
            format!("{:.4} {}", c.noise.sigma, c.channel.unit()),
            c.noise
                .phi
                .iter()
                .map(|p| format!("{p:.3}"))
                .collect::<Vec<_>>()
                .join(", "),
        ]);
    }
    page.table(noise);
}

/// Every round's candidates.
fn candidates_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    page.heading(at.titled("Candidates"));
    let mut cands = Table::new(["round", "channel", "effect", "shape", "evidence"]);
    for c in &outcome.candidates {
        cands.row([
            (c.round + 1).to_string(),
            c.channel.name(),
            c.effect.name().to_owned(),
            c.shape.clone(),
            format!("{:.1}", c.evidence),
        ]);
    }
    page.table(cands);
    page.text(
        "Each candidate's shape is its best point on the search grid; a named effect's width, \
         strain or time constant is then refined between the grid points (its parameters \
         under Result). A creep may be named with two time constants (fast_tau_s and \
         fast_fraction): in that form when it settles a near tie the one-term creep leads, or \
         when its second term adds the threshold over the first, or less that beats copies of \
         the one-term model; its evidence under Result is then that form's.",
    );
}

/// A sentence for each candidate declined because a fitted value is outside the simulator's
/// range.
fn out_of_range_text(page: &mut Page, outcome: &Outcome) {
    for d in &outcome.declined {
        if let Some(r) = &d.out_of_range {
            page.text(format!(
                "{} on {} was not named: {}. The channel was tested for what the library cannot \
                 explain instead.",
                d.effect.name(),
                d.channel.name(),
                r.sentence()
            ));
        }
    }
}

/// Each name's calibration (and each declined candidate's): the evidence observed against the
/// copies simulated without it, the rival tests, and a figure of both.
fn calibration_section(page: &mut Page, outcome: &Outcome, at: Placement<'_>) {
    // Each test, its calibration, and whether a name was given (a candidate a change in time
    // refused beat its copies and is still not named).
    let tests: Vec<(String, &Calibration, bool)> = outcome
        .discovered
        .iter()
        .filter_map(|d| {
            let c = d.calibration.as_ref()?;
            Some((
                format!("{} on {}", d.effect.name(), d.channel.name()),
                c,
                true,
            ))
        })
        .chain(outcome.declined.iter().filter_map(|d| {
            Some((
                format!(
                    "{} on {} (not named{})",
                    d.effect.name(),
                    d.channel.name(),
                    match (&d.out_of_range, d.over_richer) {
                        (Some(_), _) => ": a fitted value out of range".to_owned(),
                        (None, Some(v)) => format!(
                            ": {v:.1} nats over the richer form of the effect named before it"
                        ),
                        (None, None) => String::new(),
                    }
                ),
                d.calibration.as_ref()?,
                false,
            ))
        }))
        .collect();
    if tests.is_empty() {
        return;
    }
    page.heading(at.titled("Calibration of each name"));
    page.text(format!(
        "Each name is calibrated on this recording: the channel's model without the effect, \
         fitted here, is simulated {COPIES} times (up to {MORE_COPIES} when the first copies leave \
         it close) on the recording's own input, with noise fitted to the residual of the model \
         with the effect; every candidate is scored on each copy as on the recording, and the \
         largest evidence kept. A name needs the {SCREEN_NATS}-nat screen, more evidence than \
         every copy, and more than the copies' one-sided prediction bound at a {} % false-name \
         rate. Between rival names, each is simulated as the other's alternative, and one is \
         named only when the other cannot produce what was seen.",
        100.0 * FALSE_NAME_RATE
    ));
    let mut table = Table::new([
        "test",
        "observed (nats)",
        "copies",
        "null mean ± sd",
        "null largest",
        "bound",
        "p",
        "verdict",
    ]);
    for (name, c, named) in &tests {
        table.row([
            name.clone(),
            format!("{:.1}", c.observed),
            c.null.len().to_string(),
            match (c.null_mean, c.null_sd) {
                (Some(m), Some(s)) => format!("{m:.1} ± {s:.1}"),
                _ => "–".to_owned(),
            },
            c.null_max.map_or("–".to_owned(), |v| format!("{v:.1}")),
            c.bound.map_or("–".to_owned(), |v| format!("{v:.1}")),
            format!("{:.3}", c.p_value),
            if *named { "named" } else { "not named" }.to_owned(),
        ]);
    }
    page.table(table);
    // A name given under the screen, as the rival that excluded every name over it.
    for d in &outcome.discovered {
        if let Some(c) = d.calibration.as_ref().filter(|c| c.screen < SCREEN_NATS) {
            page.text(format!(
                "{} on {} read {:.1} nats, under the {SCREEN_NATS}-nat screen: it is named as \
                 the rival that excluded every name over the screen (the rival tests below), \
                 at the rivals' {}-nat screen and the same bound.",
                d.effect.name(),
                d.channel.name(),
                c.observed,
                c.screen
            ));
        }
    }
    rival_table(page, outcome);
    calibration_figure(page, &tests, at);
}

/// The rival tests of every name, and the tests against a change in time of names and of the
/// candidates it refused.
fn rival_table(page: &mut Page, outcome: &Outcome) {
    let rivals: Vec<(&Discovery, &Rivalry)> = outcome
        .discovered
        .iter()
        .flat_map(|d| d.rivals.iter().map(move |r| (d, r)))
        .collect();
    // The tests against a change in time, of names and of candidates it refused.
    let in_time: Vec<(String, &TimeRivalry)> = outcome
        .discovered
        .iter()
        .filter_map(|d| {
            let t = d.time.as_ref()?;
            Some((format!("{} on {}", d.effect.name(), d.channel.name()), t))
        })
        .chain(outcome.declined.iter().filter_map(|d| {
            let t = d.time.as_ref()?;
            Some((
                format!("{} on {} (not named)", d.effect.name(), d.channel.name()),
                t,
            ))
        }))
        .collect();
    if !rivals.is_empty() || !in_time.is_empty() {
        let mut table = Table::new(["named", "rival", "what the two worlds produce"]);
        for (d, r) in &rivals {
            table.row([
                format!("{} on {}", d.effect.name(), d.channel.name()),
                r.rival.name().to_owned(),
                r.sentence(),
            ]);
        }
        for (name, t) in &in_time {
            table.row([name.clone(), t.rival_name().to_owned(), t.sentence()]);
        }
        page.table(table);
    }
}

/// The figure of [`calibration_section`]: each test's copies, its bound and the observation.
fn calibration_figure(page: &mut Page, tests: &[(String, &Calibration, bool)], at: Placement<'_>) {
    // Evidence spans orders of magnitude between a copy and a clear effect: a signed
    // log scale keeps both in view.
    let squash = |e: f64| e.signum() * (1.0 + e.abs()).log10();
    let mut chart = Chart::new(
        "Observed evidence against the copies simulated without the effect",
        "test (as in the table above)",
        "evidence, sign·log10(1 + |nats|)",
    );
    let mut copies = Vec::new();
    let mut observed = Vec::new();
    let mut bounds = Vec::new();
    for (i, (_, c, _)) in tests.iter().enumerate() {
        let x = (i + 1) as f64;
        let k = c.null.len().max(1) as f64;
        copies.extend(
            c.null
                .iter()
                .enumerate()
                .map(|(j, v)| (x - 0.25 + 0.5 * j as f64 / k, squash(*v))),
        );
        observed.push((x, squash(c.observed)));
        if let Some(b) = c.bound {
            bounds.push(vec![(x - 0.35, squash(b)), (x + 0.35, squash(b))]);
        }
    }
    // Headroom above every point for the legend: it sat in the upper left over the first
    // test's observation, which is usually the largest (a clear name's).
    let ys = copies
        .iter()
        .chain(&observed)
        .chain(bounds.iter().flatten())
        .map(|p| p.1)
        .filter(|y| y.is_finite());
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
        (a.min(y), b.max(y))
    });
    if lo.is_finite() && hi.is_finite() {
        let span = (hi - lo).max(1.0);
        chart.y_range = Some((lo - 0.05 * span, hi + 0.4 * span));
    }
    let mut dots = Series::dots("copies simulated without the effect", copies, PALETTE[0]);
    dots.style = SeriesStyle::Dots(3);
    chart.push(dots);
    for (i, b) in bounds.into_iter().enumerate() {
        let label = if i == 0 {
            "bound at the stated rate"
        } else {
            ""
        };
        chart.push(Series::reference(label, b, PALETTE[7]));
    }
    let mut seen = Series::dots("observed on the recording", observed, PALETTE[3]);
    seen.style = SeriesStyle::Dots(6);
    chart.push(seen);
    page.figure(
        at.figure_name("calibration"),
        chart,
        "Each test's copies (spread across its slot), its bound, and the evidence observed on \
         the recording: a name is given where the observation stands above every copy and the \
         bound.",
    );
}

fn channel_section(page: &mut Page, c: &super::StageReport, at: Placement<'_>) {
    let name = c.channel.name();
    let unit = match c.channel {
        Stage::Plant => "angle (°)",
        Stage::Sensor(_) => "resistance (kΩ)",
    };
    let scale = match c.channel {
        Stage::Plant => 1.0,
        Stage::Sensor(_) => 1e-3,
    };
    page.heading(at.titled(&format!("Channel {name}")));
    let mut places = Table::new([
        "situation",
        "share of held-out samples",
        "RMS there / RMS overall (base model)",
    ]);
    for p in &c.places {
        places.row([
            p.situation.to_owned(),
            format!("{:.0} %", 100.0 * p.share),
            format!("{:.2}", p.ratio),
        ]);
    }
    page.text(format!(
        "Where the base model disagrees on {name}: the residual's RMS in each situation over its RMS on all held-out samples (above 1: the disagreement gathers there)."
    ));
    page.table(places);
    let held = |v: &[f64]| -> Vec<(f64, f64)> {
        c.time_s
            .iter()
            .zip(v)
            .zip(&c.held_out)
            .filter(|(_, h)| **h)
            .map(|((t, y), _)| (*t, y * scale))
            .collect()
    };
    let overlay = Chart::new(
        format!("{name}: measured and simulated (held-out samples)"),
        "time (s)",
        unit,
    )
    .with(Series::dots("measured", held(&c.measured), PALETTE[7]))
    .with(Series::dots("base model", held(&c.before), PALETTE[0]))
    .with(Series::dots(
        "with named effects",
        held(&c.after),
        PALETTE[2],
    ));
    page.figure(at.figure_name(&format!("overlay-{name}")), overlay, "Measured against the calibrated base model and the model with the named effects, on the held-out blocks only (the gaps between them are the training blocks).");
    let diff = |m: &[f64]| -> Vec<f64> { c.measured.iter().zip(m).map(|(y, p)| y - p).collect() };
    let residual = Chart::new(
        format!("{name}: residual before and after (held-out samples)"),
        "time (s)",
        format!("measured − model, {unit}"),
    )
    .with(Series::dots(
        "base model",
        held(&diff(&c.before)),
        PALETTE[0],
    ))
    .with(Series::dots(
        "with named effects",
        held(&diff(&c.after)),
        PALETTE[2],
    ));
    page.figure(
        at.figure_name(&format!("residual-{name}")),
        residual,
        "The residual before and after; what remains after should look like the noise at rest.",
    );
}
