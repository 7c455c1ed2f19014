//! A baseline wandering in time, named `drift` (issue 31).
//!
//! The library's `drift` is a baseline linear or settling in time. A baseline that follows a
//! random walk (the third generator's drift; the simulator's drift has one too) is neither: its linear drift's evidence was under the screen or under its copies, and the
//! channel was flagged `unexplained` (time: "the baseline or the sensitivity changes with
//! time") without a name, in 10 or 11 of 12 seeds at every size from ×0.5 to ×8.
//!
//! So when a sensor's rounds end with nothing left ambiguous and no `drift` or `gain_drift`
//! named, the `unexplained` test's time spline (cubic B-splines with knots every
//! [`super::unexplained::TIME_KNOT_S`], second-difference penalty, smoothing chosen by
//! cross-validation over the training blocks) is split into its two halves, and each is
//! tested as the other's rival, the way [`super::time_rival`] tells a name from a change in
//! time, in four tests, each a bootstrap:
//!
//! 1. **The wandering baseline over the model**: its held-out evidence, at least
//!    [`THRESHOLD_NATS`], and beating copies of the channel's model simulated without it (the
//!    calibration of every name).
//! 2. **It over the input's structure**: its evidence added after the `unexplained` test's
//!    other kinds (a curve of any shape, memory, history) and the richer forms of the effects
//!    named on the channel ([`Term::flexible`], as every later name must beat them), against
//!    copies of the model with them. A Preisach loop's misfit follows the input's slow
//!    history, and a spline in time fitted some of it: without this test the third
//!    generator's hysteresis ×8 of seed 1 was named `hysteresis`, then `drift` (28.3 nats;
//!    over the input's structure 5.9, against copies reaching 14.9). Without the richer forms
//!    its creep ×8 of seed 10214 (six time constants, 2 s to 200 s) was named `creep`, then
//!    `drift` (22.6 nats; 30.6 over the input's structure against a bound of 6.5).
//! 3. **Its lead over a wandering sensitivity**: the baseline alone's evidence over the model
//!    less the sensitivity alone's (the spline times the input), against copies of the model
//!    with the wandering sensitivity fitted. A wandering sensitivity cannot produce that lead
//!    when the observed beats them. The nested form (the baseline's evidence added after the
//!    sensitivity) was tried first: on the random-walk drift ×2 of seed 1 it read 33.6 nats
//!    against copies reaching 66.8 (the model with both splines pays for its extra columns on
//!    the held-out samples), where the lead reads 107.6 against copies reaching 46.8.
//! 4. **A wandering sensitivity over it**: the other way round, against copies of the model
//!    with the wandering baseline fitted. This must not beat them: a sensitivity that also
//!    wanders is more than a drift, and the channel is left to the `unexplained` test.
//!
//! Only then is `drift` named, in the form [`Term::Wander`] (the same splines, the first left
//! out, fitted with the model), and the scenario gets a drift of the path's mean rate and
//! a random walk of its steps' spread ([`super::scenario::wander_rate_and_walk`]). A separate
//! holdout recording is never given one: a wander in one recording's time says nothing of
//! another's. `--fast` applies the screens alone: the baseline over the model, over the input's
//! structure and its lead at least [`THRESHOLD_NATS`], a wandering sensitivity over it under.
//!
//! Not tried after an ambiguity. Tried with the other contenders' shapes added to test 2, it
//! settled none of the four third-generator drift/creep ambiguities it was run on (seed 5 at
//! ×1: a lead of 3.8 nats over a wandering sensitivity, which added 4.4 after it; seed 7 at
//! ×1: 10.3 nats over the input's structure and the creep), so it was not kept.

use super::calibrate::{Calibration, Verdict, RIVAL_SCREEN_NATS};
use super::model::Stage;
use super::search::StageSearch;
use super::terms::{Effect, Term};
use super::time_rival::TimeRivalry;
use super::unexplained::{time_knot_s, Extra, Generic, GenericKind, Residuals, SetFit, Target};
use super::THRESHOLD_NATS;

/// A wandering baseline that passed its three tests (module docs).
pub(super) struct Wander {
    /// The baseline's evidence over the channel's model (nats).
    pub evidence: f64,
    /// Its calibration against copies of the model without it (absent with `--fast`).
    pub calibration: Option<Calibration>,
    /// Its tests against a wandering sensitivity, both ways.
    pub time: TimeRivalry,
    /// The named form.
    pub term: Term,
}

/// The seed of one of the four bootstraps of a channel.
fn seed(round: usize, test: u64, channel: Stage) -> u64 {
    let ch = match channel {
        Stage::Plant => 0,
        Stage::Sensor(s) => s.index() as u64 + 1,
    };
    0x0A4D_E500_0000_0000 ^ ((round as u64) << 40) ^ (test << 32) ^ (ch << 48)
}

impl StageSearch<'_, '_> {
    /// A wandering baseline on this channel after its rounds, if it passes the tests of the
    /// module docs; `None` otherwise, on the plant, with a holdout, or when the model already
    /// has a `drift` or a `gain_drift` (named, or from the base scenario).
    pub(super) fn wander(&self, round: usize, fast: bool) -> Option<Wander> {
        let s = self.search;
        // A drift or a gain drift in the model, named or given by a base scenario (`--scenario`):
        // a change in time is already part of it, and the scenario has one drift to write.
        let in_time = self
            .model
            .terms
            .iter()
            .any(|t| matches!(t.effect(), Effect::Drift | Effect::GainDrift));
        if !matches!(self.channel, Stage::Sensor(_)) || s.holdout() || in_time {
            return None;
        }
        let train = self.model.design(&s.data, &s.inputs.0);
        let test = self.model.design(&s.test_data, &s.inputs.1);
        let richer = self.richer_columns(train.columns.len());
        let r = self.time_test(&train, &test);
        let g = wander_generic(&r, richer)?;
        let prepared = g.prepare_sets()?;
        let observed = g.observed();
        // The evidence of set `to` over set `from`, with the fits of both.
        let step =
            |from: usize, to: usize, target: &Target| g.nested(&prepared, from, &[to], target);
        let (evidence, _, world, fuller) = step(0, 1, &observed)?;
        if evidence.is_nan() || evidence < THRESHOLD_NATS {
            return None;
        }
        // The baseline's lead over the sensitivity, each alone over the model.
        let lead = |target: &Target| -> Option<(f64, SetFit)> {
            let (b, ..) = step(0, 1, target)?;
            let (s, _, _, s_fit) = step(0, 2, target)?;
            Some((b - s, s_fit))
        };
        let (beyond, b_world) = lead(&observed)?;
        let (.., b_fuller) = step(2, 3, &observed)?;
        let (sensitivity, _, s_world, s_fuller) = step(1, 3, &observed)?;
        let (beyond_input, _, i_world, i_fuller) = step(4, 5, &observed)?;
        let term = Term::Wander {
            knot_s: time_knot_s(&s.data),
        };
        if fast {
            let passed = beyond >= THRESHOLD_NATS
                && beyond_input >= THRESHOLD_NATS
                && sensitivity < THRESHOLD_NATS;
            let screened = |e| Calibration::of(e, Vec::new(), THRESHOLD_NATS);
            return passed.then(|| Wander {
                evidence,
                calibration: None,
                time: rivalry(
                    screened(beyond),
                    screened(sensitivity),
                    screened(beyond_input),
                ),
                term,
            });
        }
        let calibrated =
            |e: f64, w, f, test, screen, statistic: &(dyn Fn(&Target) -> f64 + Sync)| {
                if e > screen {
                    g.calibrate_by(w, f, e, screen, seed(round, test, self.channel), statistic)
                } else {
                    Calibration::of(e, Vec::new(), screen)
                }
            };
        let nested = |from, to| move |copy: &Target| step(from, to, copy).map_or(f64::NAN, |x| x.0);
        let calibration = calibrated(evidence, &world, &fuller, 1, THRESHOLD_NATS, &nested(0, 1));
        if !calibration.passed {
            return None;
        }
        let screen = RIVAL_SCREEN_NATS;
        let over_input = calibrated(beyond_input, &i_world, &i_fuller, 4, screen, &nested(4, 5));
        if !over_input.passed {
            return None;
        }
        let beyond_time = calibrated(beyond, &b_world, &b_fuller, 2, screen, &|copy| {
            lead(copy).map_or(f64::NAN, |x| x.0)
        });
        if !beyond_time.passed {
            return None;
        }
        let time_beyond = calibrated(sensitivity, &s_world, &s_fuller, 3, screen, &nested(1, 3));
        if time_beyond.passed {
            return None;
        }
        Some(Wander {
            evidence,
            calibration: Some(calibration),
            time: rivalry(beyond_time, time_beyond, over_input),
            term,
        })
    }

    /// The columns of the richer forms of the effects named on the channel (a creep's Prony
    /// series, a hysteresis's finer plays: [`Term::flexible`]) beyond the model's `own`, as
    /// every later name must beat them ([`super::decide`]): a creep of many time constants
    /// named in one or two leaves a slow misfit a spline in time fits.
    fn richer_columns(&self, own: usize) -> Vec<Extra> {
        let s = self.search;
        let span = s.span_of(self.channel);
        self.named_terms()
            .iter()
            .filter_map(|t| t.flexible(span))
            .map(|f| {
                let m = self.model.with(f);
                (m.design(&s.data, &s.inputs.0).columns.split_off(own), None)
            })
            .collect()
    }
}

/// The generic test of the four tests: groups 0 the model, 1 the wandering baseline, 2 the
/// wandering sensitivity, 3-5 the structure of the input the `unexplained` test looks for (a
/// curve, memory, history), then the named effects' `richer` forms; sets 0 the model, 1 with
/// the baseline, 2 with the sensitivity, 3 with both, 4 with the input's structure, 5 with it
/// and the baseline.
fn wander_generic<'r>(r: &'r Residuals<'r>, richer: Vec<Extra>) -> Option<Generic<'r>> {
    let input: Vec<usize> = [0, 3, 4, 5]
        .into_iter()
        .chain(6..6 + richer.len())
        .collect();
    let with_baseline: Vec<usize> = [0, 1]
        .into_iter()
        .chain(input[1..].iter().copied())
        .collect();
    r.generic_of(
        &[
            GenericKind::Baseline,
            GenericKind::Sensitivity,
            GenericKind::Curve,
            GenericKind::Memory,
            GenericKind::History,
        ],
        richer,
        vec![
            vec![0],
            vec![0, 1],
            vec![0, 2],
            vec![0, 1, 2],
            input,
            with_baseline,
        ],
    )
}

/// The wandering baseline's tests as a rivalry with a wandering sensitivity: its lead over it
/// (`beyond_time`), the sensitivity after it (`time_beyond`) and it over the input's structure.
fn rivalry(
    beyond_time: Calibration,
    time_beyond: Calibration,
    over_input: Calibration,
) -> TimeRivalry {
    TimeRivalry {
        effect: Effect::Drift,
        beyond_time,
        time_beyond: Some(time_beyond),
        verdict: Verdict::Named,
        rival: GenericKind::Sensitivity,
        among: Vec::new(),
        lead: true,
        over_input: Some(over_input),
    }
}
