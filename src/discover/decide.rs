//! The calibrated rule of a round ([`StageSearch::pick_calibrated`]): which candidate is
//! named, from the bootstrap of [`super::calibrate`], instead of the fixed margins (the
//! threshold's lead of [`super::CLEAR_RATIO`] over the runner-up, and nested evidence against a
//! 20-nat bar) that `--fast` keeps.
//!
//! 1. **Screen**: the best candidate must reach [`SCREEN_NATS`] (the old threshold).
//! 2. **Null**: the current model is simulated ([`StageSearch::bootstrap`]); on each copy every
//!    candidate is scored, and the largest evidence kept. A candidate is *credible* when its
//!    evidence beats that null by the rule; the best must be, or nothing is named (the
//!    calibration is kept for the report). After a named effect with a richer form it must
//!    beat it over that form too ([`Term::flexible`]; for `drift` and `gain_drift`, a change
//!    in time of any smooth form, the `unexplained` test's time spline), so that it does not
//!    take the named form's misfit.
//! 3. **Rivals**: each credible candidate `A`, best first, against every other credible `B`
//!    and every candidate under the screen that beats the null and imitates it
//!    ([`quiet_rival`]; at most [`MAX_RIVALS`]):
//!    `B`'s world (the model with `B`, fitted; a creep against a hysteresis or a saturation as
//!    a Prony series, on either side, and scored in that form too) is simulated and
//!    the evidence of `A` added after `B` measured on each copy. When the recording's exceeds it
//!    by the rule, `B` cannot produce what was seen. When it does not, `A`'s world is simulated
//!    for the evidence of `B` after `A`: if `A` cannot produce what was seen, `B` is the better
//!    name and is tried next; if it can, the two are `ambiguous` ([`Verdict::Neither`]).
//! 4. `A` is named when every rival is excluded. Two exceptions keep a simpler name: a
//!    saturation and a hysteresis that cannot be told apart are `saturation` (a hysteresis is
//!    a saturating curve with memory, and its memory is not shown), and a one-term creep left
//!    ambiguous is tried again in its best two-term form. When every credible candidate is
//!    excluded by a rival under the screen, that rival is tested the same way and named when
//!    nothing excludes it (its calibration's screen is then the rivals' one nat).
//! 5. **A change in time** ([`super::time_rival`]): a name a smooth change in time imitates
//!    (`drift`, `gain_drift`, `creep`), about to be given or left ambiguous, is tested against
//!    the `unexplained` test's time spline, both ways. A name the spline's world produces and
//!    whose own world cannot produce the spline's evidence is refused. An ambiguity among such
//!    names is declined when every one of them is refused so, and otherwise stands only when
//!    one of them shows what a sensitivity changing in time (the spline times the input)
//!    cannot produce; when it does not stand nothing is named (`declined`, with the test, or
//!    each contender's) and the channel is left to the `unexplained` test. An ambiguity with
//!    such a name among others stands only when one of its contenders shows what a change in
//!    time of the baseline and the sensitivity cannot produce (a `drift` or a `gain_drift`,
//!    which that change holds, over a sensitivity changing in time); otherwise it is declined
//!    the same way.

use super::calibrate::{
    separating_data, Calibration, Rivalry, Verdict, RIVAL_SCREEN_NATS, SCREEN_NATS,
};
use super::search::{Pick, StageSearch};
use super::terms::{Effect, Term};
use super::time_rival::{TimeRivalry, TIME_RIVALS};
use super::unexplained::GenericKind;
use super::{prefer_simpler, Ambiguity, Candidate};

/// At most this many rivals are simulated against a candidate (the most evidence first): each
/// costs a bootstrap.
pub const MAX_RIVALS: usize = 4;

/// Seeds of the tests of a round, so that every run of the same recording draws the same
/// copies (and a sensor's draws never depend on the plant).
fn seed(round: usize, test: u64, a: Effect, b: Effect) -> u64 {
    ((round as u64) << 40) ^ (test << 32) ^ ((a as u64) << 8) ^ (b as u64)
}

/// A name the calibrated rule gives: its calibration against the world without it, and the
/// rivals it was told from.
#[derive(Debug, Clone)]
pub(super) struct Calibrated {
    pub(super) calibration: Calibration,
    pub(super) rivals: Vec<Rivalry>,
    /// The test against a smooth change in time, for a name it imitates.
    pub(super) time: Option<TimeRivalry>,
}

/// What [`StageSearch::settle`] judges a candidate with: the round's scored candidates, the
/// credible ones, their evidence on the observed data and the null's calibration.
struct Settle<'a> {
    scored: &'a [Candidate],
    credible: &'a [&'a Candidate],
    /// Candidates that beat the null under the screen: rivals of the names they imitate
    /// ([`quiet_rival`]), and names themselves only when they exclude every credible
    /// candidate.
    quiet: &'a [&'a Candidate],
    observed_of: &'a dyn Fn(Effect) -> f64,
    null: &'a Calibration,
    round: usize,
}

impl StageSearch<'_, '_> {
    /// The round's verdict by the calibrated rule (module docs).
    pub(super) fn pick_calibrated(&self, mut scored: Vec<Candidate>, round: usize) -> Pick {
        prefer_simpler(&mut scored);
        let Some(top) = scored.first() else {
            return Pick::Nothing;
        };
        if top.evidence < SCREEN_NATS {
            return Pick::Nothing;
        }
        let groups = self.candidate_groups();
        let observed = self.observed_target();
        let Some(row) = self
            .evidences(
                &self.model,
                &groups.iter().map(|(_, g)| g.clone()).collect::<Vec<_>>(),
                std::slice::from_ref(&observed),
            )
            .and_then(|rows| rows.into_iter().next())
        else {
            return Pick::Nothing;
        };
        let observed_of = |e: Effect| {
            groups
                .iter()
                .position(|(g, _)| *g == e)
                .map_or(f64::NAN, |i| row[i])
        };
        // The fuller model whose residual the copies' noise (and, for a name a wander
        // imitates, their wander) is fitted to: with the top's shape refined when it is one a
        // wander imitates, so that its grid's coarseness is not taken for a wander.
        let fuller_term = if TIME_RIVALS.contains(&top.effect) {
            self.refine(top.clone()).term
        } else {
            top.term.clone()
        };
        let null = self.bootstrap(
            &self.model,
            &self.model.with(fuller_term),
            &groups.iter().map(|(_, g)| g.clone()).collect::<Vec<_>>(),
            observed_of(top.effect),
            SCREEN_NATS,
            seed(round, 1, top.effect, top.effect),
        );
        if !null.passed {
            return Pick::Declined(top.clone(), null, None, None);
        }
        // A name a change in time can produce, and whose world cannot produce the change, is
        // declined with that test.
        let refused = |refusal: Box<(Candidate, TimeRivalry)>| {
            let (c, t) = *refusal;
            let calibration =
                Calibration::of(observed_of(c.effect), null.null.clone(), SCREEN_NATS);
            Pick::Declined(c, calibration, Some(t), None)
        };
        let credible = self.credible(&scored, &observed_of, &null);
        if credible.is_empty() {
            // The top beat its copies but not over a named effect's richer form: what it
            // explains is that form's misfit.
            return Pick::Declined(top.clone(), null, None, self.over_richer(top));
        }
        // The screen is for speed, not a rule: a rival under it that beats the null can
        // produce what the name explains (a random-walk drift's `drift`, 17.7 nats, under its
        // `gain_drift`'s 24.7; a creep of six time constants' `creep`, 16.4, under the
        // `hysteresis`, 27.0, its lags drew), and is simulated as one against the names it
        // imitates ([`quiet_rival`], in `settle`).
        let quiet: Vec<&Candidate> = scored
            .iter()
            .filter(|c| {
                let e = observed_of(c.effect);
                e < SCREEN_NATS && e > RIVAL_SCREEN_NATS && e > null.bound_or_inf()
            })
            .collect();
        let settle = Settle {
            scored: &scored,
            credible: &credible,
            quiet: &quiet,
            observed_of: &observed_of,
            null: &null,
            round,
        };
        // A change in time the library lacks explains the name: no other name is tried on
        // this channel around it (a gain that fades, refused as `gain_drift`, was then named
        // `hysteresis`); the `unexplained` test follows.
        self.against_time_all(self.settle_all(&settle), &scored, round)
            .unwrap_or_else(refused)
    }

    /// The credible candidates, best first, each settled against its rivals: the first that
    /// none excludes is the verdict (named, or ambiguous with what would separate them); when
    /// every one is excluded, a rival under the screen that excluded them and that nothing
    /// left excludes; otherwise an ambiguity among them and their excluders.
    fn settle_all(&self, settle: &Settle) -> Pick {
        let mut excluded: Vec<Effect> = Vec::new();
        // The rivals that excluded a credible candidate: contenders of the ambiguity when
        // every credible one is excluded.
        let mut excluders: Vec<Effect> = Vec::new();
        // Their tests, reported with the rival when it is named.
        let mut exclusions: Vec<Rivalry> = Vec::new();
        for a in settle.credible {
            if excluded.contains(&a.effect) {
                continue;
            }
            match self.settle(a, settle, &excluded) {
                Ok(pick) => return with_exclusions(pick, a.effect, &exclusions),
                Err(by) => {
                    excluded.push(a.effect);
                    excluders.extend(by.iter().map(|t| t.rival));
                    exclusions.extend(by);
                }
            }
        }
        // Every credible candidate was excluded by a rival under the screen that beat the
        // null: that rival, tested in turn against the rivals not yet excluded, is named when
        // none excludes it. It beat its copies and showed what the names it excluded cannot
        // produce, the calibrated rule every name follows (the screen is for speed). A creep
        // of six time constants at ×8 (third generator, Joint A, seed 3) scored 17.5 nats in
        // its one-term form, excluded the `hysteresis` its lags drew (29.4), and was left
        // `ambiguous` with it.
        let excluders_under_screen = settle
            .quiet
            .iter()
            .filter(|c| excluders.contains(&c.effect) && !excluded.contains(&c.effect));
        for q in excluders_under_screen {
            if let Ok(pick) = self.settle(q, settle, &excluded) {
                return with_exclusions(pick, q.effect, &exclusions);
            }
        }
        // Every credible candidate was excluded by another: the data shows something none of
        // them alone produces.
        Pick::Ambiguous(Ambiguity {
            channel: self.channel,
            contenders: settle
                .credible
                .iter()
                .chain(
                    settle
                        .quiet
                        .iter()
                        .filter(|c| excluders.contains(&c.effect)),
                )
                .map(|c| (c.effect, c.evidence))
                .collect(),
            separate: Vec::new(),
            rivals: Vec::new(),
        })
    }

    /// A candidate's evidence over the richer forms of the effects named before it: the
    /// smaller, the one it fell short over; `None` when none is named.
    fn over_richer(&self, c: &Candidate) -> Option<f64> {
        let over_flexible = self
            .flexible_model()
            .and_then(|m| self.search.gain(&m, &c.term));
        let over_time = self
            .time_named()
            .then(|| self.over_time(c, None).map(|(e, _)| e))
            .flatten();
        over_flexible
            .into_iter()
            .chain(over_time)
            .min_by(f64::total_cmp)
    }

    /// A verdict's names against a smooth change in time ([`super::time_rival`]): a name
    /// about to be given keeps its test, or is refused; an ambiguity whose every contender a
    /// change in time imitates is refused when a change in time refuses every contender, or
    /// when none of them beats a sensitivity changing in time. `Err` holds the first refused
    /// candidate and its test (boxed: it is large).
    fn against_time_all(
        &self,
        pick: Pick,
        scored: &[Candidate],
        round: usize,
    ) -> Result<Pick, Box<(Candidate, TimeRivalry)>> {
        match pick {
            Pick::Clear(c, runner, Some(mut calibrated)) => match self.against_time(&c, round) {
                Some(t) if t.refuses() => Err(Box::new((c, t))),
                t => {
                    calibrated.time = t;
                    Ok(Pick::Clear(c, runner, Some(calibrated)))
                }
            },
            // An ambiguity among names a change in time imitates stands only when one of them
            // shows what a sensitivity changing in time, in any smooth form, cannot produce.
            // Otherwise the names the data did not tell apart are not told from a changing
            // sensitivity either, which none of them is: a gain cycling or wandering in time
            // was left `ambiguous` between `drift` and `creep` (third generator, ×0.5, seed
            // 9). Declined, with each contender's test, and the channel goes to the
            // `unexplained` test. (Against the baseline's change in time too, a linear drift
            // would never stand: the spline holds it.) An ambiguity whose every name a change
            // in time refuses is declined first, as a name is.
            Pick::Ambiguous(a)
                if !a.contenders.is_empty()
                    && a.contenders.iter().all(|(e, _)| TIME_RIVALS.contains(e)) =>
            {
                let Some(contenders) = contenders_of(&a, scored) else {
                    return Ok(Pick::Ambiguous(a));
                };
                // Every contender refused by a change in time (its world cannot produce the
                // spline's evidence): declined with the first refusal.
                let refusals: Vec<(Candidate, TimeRivalry)> = contenders
                    .iter()
                    .map_while(|c| {
                        self.against_time(c, round)
                            .filter(TimeRivalry::refuses)
                            .map(|t| ((*c).clone(), t))
                    })
                    .collect();
                if refusals.len() == contenders.len() {
                    if let Some(first) = refusals.into_iter().next() {
                        return Err(Box::new(first));
                    }
                }
                stands_or_declined(a, &contenders, GenericKind::Sensitivity, &|c| {
                    self.over_sensitivity(c, round)
                })
            }
            // An ambiguity with a name a change in time imitates among names it does not
            // stands only when one of them shows what a change in time of the baseline and the
            // sensitivity cannot produce: a random-walk drift was left `ambiguous` between
            // `creep` and `hysteresis` (third generator, ×2 of seed 10142, ×1 of 10241), a
            // slow lag and a loop each drawing part of the wander, neither the truth.
            Pick::Ambiguous(a) if a.contenders.iter().any(|(e, _)| TIME_RIVALS.contains(e)) => {
                let Some(contenders) = contenders_of(&a, scored) else {
                    return Ok(Pick::Ambiguous(a));
                };
                // A `drift` or a `gain_drift` is a change in time of the baseline or the
                // sensitivity, which the time spline holds: it is tested over a sensitivity
                // changing in time, as in an ambiguity among names a change in time imitates.
                let beyond = |c: &Candidate| match c.effect {
                    Effect::Drift | Effect::GainDrift => self.over_sensitivity(c, round),
                    _ => self.beyond_time(c, round),
                };
                stands_or_declined(a, &contenders, GenericKind::Time, &beyond)
            }
            pick => Ok(pick),
        }
    }

    /// The candidates whose evidence on the observed data clears the screen and the null's
    /// bound; after a named hysteresis, saturation or creep, over that effect's richer form
    /// too; after a named drift or gain drift, over a change in time of any smooth form.
    fn credible<'c>(
        &self,
        scored: &'c [Candidate],
        observed_of: &dyn Fn(Effect) -> f64,
        null: &Calibration,
    ) -> Vec<&'c Candidate> {
        let flexible = self.flexible_model();
        let time_named = self.time_named();
        scored
            .iter()
            .filter(|c| {
                let e = observed_of(c.effect);
                e >= SCREEN_NATS && e > null.bound_or_inf()
            })
            // After a named hysteresis or saturation, a candidate must show its evidence over
            // that effect's richer form too: what it explains must not be the named form's
            // misfit.
            .filter(|c| {
                flexible.as_ref().map_or(true, |m| {
                    self.search
                        .gain(m, &c.term)
                        .is_some_and(|e| e >= SCREEN_NATS && e > null.bound_or_inf())
                })
            })
            // After a named drift or gain drift, over a change in time of any smooth form (the
            // time spline): a gain cycling in time, named `gain_drift`, left a misfit that a
            // hysteresis's plays drew (third generator, seed 2, ×2 and ×4).
            .filter(|c| {
                !time_named
                    || self
                        .over_time(c, None)
                        .is_some_and(|(e, _)| e >= SCREEN_NATS && e > null.bound_or_inf())
            })
            .collect()
    }

    /// Candidate `a` tested against its rivals not yet excluded (the credible ones and those
    /// under the screen that beat the null): the verdict it settles (clear, or ambiguous with
    /// what would separate them), or `Err` with the tests of the rivals that exclude it.
    fn settle(
        &self,
        a: &Candidate,
        settle: &Settle,
        excluded: &[Effect],
    ) -> Result<Pick, Vec<Rivalry>> {
        let quiet = settle
            .quiet
            .iter()
            .filter(|b| quiet_rival(a.effect, b.effect));
        let rivals: Vec<&Candidate> = settle
            .credible
            .iter()
            .chain(quiet)
            .filter(|b| b.effect != a.effect && !excluded.contains(&b.effect))
            .take(MAX_RIVALS)
            .copied()
            .collect();
        let a_shapes = Term::shapes(a.effect, self.search.span_of(self.channel));
        let tests: Vec<Rivalry> = rivals
            .iter()
            .filter_map(|b| self.rival(a, &a_shapes, b, settle.round))
            .collect();
        let by: Vec<Rivalry> = tests
            .iter()
            .filter(|t| t.verdict == Verdict::Rival)
            .cloned()
            .collect();
        if !by.is_empty() {
            return Err(by);
        }
        // A rival under the screen, named when it excluded every credible candidate, cleared
        // the rivals' screen and the null's bound.
        let screen = if settle.quiet.iter().any(|c| c.effect == a.effect) {
            RIVAL_SCREEN_NATS
        } else {
            SCREEN_NATS
        };
        let calibration = Calibration::of(
            (settle.observed_of)(a.effect),
            settle.null.null.clone(),
            screen,
        );
        let ties: Vec<&Rivalry> = tests
            .iter()
            .filter(|t| t.verdict == Verdict::Neither)
            .collect();
        // A saturation and a hysteresis that cannot be told apart: the memory is not
        // shown, and the simpler name stands.
        let only_bends = !ties.is_empty()
            && ties.iter().all(|t| {
                matches!(
                    (t.effect, t.rival),
                    (Effect::Saturation, Effect::Hysteresis)
                        | (Effect::Hysteresis, Effect::Saturation)
                )
            });
        if ties.is_empty() || (only_bends && a.effect == Effect::Saturation) {
            return Ok(Pick::Clear(
                (*a).clone(),
                runner_up(settle.scored, a),
                Some(Calibrated {
                    calibration,
                    rivals: tests,
                    time: None,
                }),
            ));
        }
        if only_bends {
            // The hysteresis leads but its loop is not told from a saturation's curve:
            // name the saturation if it is credible (it is: it is the tie).
            if let Some(sat) = settle
                .credible
                .iter()
                .find(|c| c.effect == Effect::Saturation)
            {
                return Ok(Pick::Clear(
                    (*sat).clone(),
                    runner_up(settle.scored, sat),
                    Some(Calibrated {
                        calibration: Calibration::of(
                            (settle.observed_of)(Effect::Saturation),
                            settle.null.null.clone(),
                            SCREEN_NATS,
                        ),
                        rivals: tests,
                        time: None,
                    }),
                ));
            }
        }
        if let Some(pick) = self.settle_two_term(a, &ties, &rivals, &tests, &calibration, settle) {
            return Ok(pick);
        }
        let tau = match a.term {
            Term::Creep { tau_s, .. } => Some(tau_s),
            _ => None,
        };
        let mut contenders = vec![(a.effect, a.evidence)];
        contenders.extend(ties.iter().map(|t| (t.rival, t.rival_evidence)));
        Ok(Pick::Ambiguous(Ambiguity {
            channel: self.channel,
            contenders,
            separate: ties
                .iter()
                .map(|t| separating_data(t.effect, t.rival, tau))
                .collect(),
            rivals: ties.into_iter().cloned().collect(),
        }))
    }

    /// A one-term creep `a` left tied with `ties`: its best two-term form, tested again against
    /// those rivals, named when it wins every one (two terms may settle what one cannot);
    /// `None` for other candidates or when a tie remains.
    fn settle_two_term(
        &self,
        a: &Candidate,
        ties: &[&Rivalry],
        rivals: &[&Candidate],
        tests: &[Rivalry],
        calibration: &Calibration,
        settle: &Settle,
    ) -> Option<Pick> {
        let two = self.two_term(a)?;
        let shapes = Term::two_term_creeps();
        let again: Vec<Rivalry> = ties
            .iter()
            .filter_map(|t| {
                let b = rivals.iter().find(|b| b.effect == t.rival)?;
                self.rival(&two, &shapes, b, settle.round)
            })
            .collect();
        if !again.iter().all(|t| t.verdict == Verdict::Named) {
            return None;
        }
        let mut all: Vec<Rivalry> = tests
            .iter()
            .filter(|t| t.verdict != Verdict::Neither)
            .cloned()
            .collect();
        all.extend(again);
        Some(Pick::Clear(
            two,
            runner_up(settle.scored, a),
            Some(Calibrated {
                calibration: calibration.clone(),
                rivals: all,
                time: None,
            }),
        ))
    }

    /// The channel's model with each named effect that has a richer form ([`Term::flexible`])
    /// in that form; `None` when none has.
    fn flexible_model(&self) -> Option<super::model::StageModel> {
        let span = self.search.span_of(self.channel);
        let mut m = self.model.clone();
        let mut changed = false;
        for t in self.named_terms() {
            if let Some(f) = t.flexible(span) {
                m.terms.retain(|x| x != t);
                m.terms.push(f);
                changed = true;
            }
        }
        changed.then_some(m)
    }

    /// `a` (its shapes `a_shapes`) against the rival `b`, each simulated as the other's
    /// alternative; `None` when a model cannot be fitted.
    fn rival(
        &self,
        a: &Candidate,
        a_shapes: &[Term],
        b: &Candidate,
        round: usize,
    ) -> Option<Rivalry> {
        let span = self.search.span_of(self.channel);
        // A creep against a hysteresis or a saturation is simulated as a Prony series
        // ([`Term::flexible`], [`creep_against_curve`]): the other is added after the series,
        // so a curve or a loop stands only when no creep, of one time constant or many, can
        // produce what was seen, and a creep (scored in its own form) only when it explains
        // what no curve or loop does.
        let world = |c: &Candidate, other: &Candidate| {
            c.term
                .flexible(span)
                .filter(|_| creep_against_curve(c.effect, other.effect))
                .unwrap_or_else(|| c.term.clone())
        };
        let with_b = self.model.with(world(b, a));
        let with_a = self.model.with(world(a, b));
        let both = with_b.with(a.term.clone());
        let observed = self.observed_target();
        let beyond = |from: &super::model::StageModel, shapes: &[Term]| -> Option<f64> {
            self.evidences(from, &[shapes.to_vec()], std::slice::from_ref(&observed))
                .and_then(|rows| rows.first().map(|r| r[0]))
        };
        // A creep against a curve or a loop is scored in its richer form too, as it is simulated.
        let scored_as = |c: &Candidate, other: &Candidate, mut shapes: Vec<Term>| {
            if creep_against_curve(c.effect, other.effect) {
                shapes.extend(c.term.flexible(span));
            }
            shapes
        };
        let a_shapes = &scored_as(a, b, a_shapes.to_vec())[..];
        let a_after_b = beyond(&with_b, a_shapes)?;
        let beyond_rival = if a_after_b > RIVAL_SCREEN_NATS {
            self.bootstrap(
                &with_b,
                &both,
                &[a_shapes.to_vec()],
                a_after_b,
                RIVAL_SCREEN_NATS,
                seed(round, 2, a.effect, b.effect),
            )
        } else {
            Calibration::of(a_after_b, Vec::new(), RIVAL_SCREEN_NATS)
        };
        if beyond_rival.passed {
            return Some(Rivalry {
                effect: a.effect,
                rival: b.effect,
                evidence: a.evidence,
                rival_evidence: b.evidence,
                beyond_rival,
                beyond_effect: None,
                verdict: Verdict::Named,
            });
        }
        let b_shapes = scored_as(b, a, Term::shapes(b.effect, span));
        let b_after_a = beyond(&with_a, &b_shapes)?;
        let beyond_effect = if b_after_a > RIVAL_SCREEN_NATS {
            self.bootstrap(
                &with_a,
                &both,
                &[b_shapes],
                b_after_a,
                RIVAL_SCREEN_NATS,
                seed(round, 3, a.effect, b.effect),
            )
        } else {
            Calibration::of(b_after_a, Vec::new(), RIVAL_SCREEN_NATS)
        };
        let verdict = if beyond_effect.passed {
            Verdict::Rival
        } else {
            Verdict::Neither
        };
        Some(Rivalry {
            effect: a.effect,
            rival: b.effect,
            evidence: a.evidence,
            rival_evidence: b.evidence,
            beyond_rival,
            beyond_effect: Some(beyond_effect),
            verdict,
        })
    }
}

/// A name about to be given with the tests by which it excluded the candidates before it, told
/// from its side, among its rivals: the report says why they are not the name.
fn with_exclusions(pick: Pick, effect: Effect, exclusions: &[Rivalry]) -> Pick {
    match pick {
        Pick::Clear(c, runner, Some(mut calibrated)) => {
            calibrated.rivals.extend(
                exclusions
                    .iter()
                    .filter(|t| t.rival == effect)
                    .filter_map(seen_from_the_rival),
            );
            Pick::Clear(c, runner, Some(calibrated))
        }
        pick => pick,
    }
}

/// A rivalry the rival won, told from the rival's side: the rival named against the
/// candidate it excluded. `None` when the rival's test was not made.
fn seen_from_the_rival(t: &Rivalry) -> Option<Rivalry> {
    Some(Rivalry {
        effect: t.rival,
        rival: t.effect,
        evidence: t.rival_evidence,
        rival_evidence: t.evidence,
        beyond_rival: t.beyond_effect.clone()?,
        beyond_effect: Some(t.beyond_rival.clone()),
        verdict: Verdict::Named,
    })
}

/// The scored candidates of an ambiguity's contenders, in its order; `None` when one is missing.
fn contenders_of<'c>(a: &Ambiguity, scored: &'c [Candidate]) -> Option<Vec<&'c Candidate>> {
    a.contenders
        .iter()
        .map(|(e, _)| scored.iter().find(|c| c.effect == *e))
        .collect()
}

/// The ambiguity `a` when one of its `contenders` passes `test` (its evidence over the `rival`
/// against copies of the rival's world), or a test cannot be made; otherwise `Err` with the
/// first contender declined and the others' tests under `among`.
fn stands_or_declined(
    a: Ambiguity,
    contenders: &[&Candidate],
    rival: GenericKind,
    test: &dyn Fn(&Candidate) -> Option<Calibration>,
) -> Result<Pick, Box<(Candidate, TimeRivalry)>> {
    let mut tests = Vec::new();
    for &c in contenders {
        match test(c) {
            Some(t) if !t.passed => tests.push((c.clone(), t)),
            _ => return Ok(Pick::Ambiguous(a)),
        }
    }
    let (c, beyond_time) = tests.remove(0);
    Err(Box::new((
        c.clone(),
        TimeRivalry {
            effect: c.effect,
            beyond_time,
            time_beyond: None,
            verdict: Verdict::Neither,
            rival,
            among: tests.into_iter().map(|(c, t)| (c.effect, t)).collect(),
            lead: false,
            over_input: None,
        },
    )))
}

/// Whether `creep` is a creep and `other` a hysteresis or a saturation: then the creep's world
/// is a Prony series ([`Term::flexible`]) in their rivalry. A creep of several time
/// constants draws a loop on a cycling strain: the third generator's creep of six (2 s to
/// 200 s) was named `hysteresis` (×1 seed 12, ×4 and ×8 seed 3) against a creep of one. Not
/// against the lags or the drifts: the series' fast terms are the signed rate's lags
/// ([`Term::same_family`]), and its slow ones on a strain of positive mean draw a drift (a
/// simulated linear drift kept 1.1 of its 102.6 nats after one).
fn creep_against_curve(creep: Effect, other: Effect) -> bool {
    creep == Effect::Creep && matches!(other, Effect::Hysteresis | Effect::Saturation)
}

/// Whether a candidate `b` under the screen that beats the null is simulated as a rival of
/// `a`: between names a change in time imitates (`drift`, `gain_drift`, `creep`), and a creep
/// against a hysteresis or a saturation ([`creep_against_curve`]). Other pairs under the
/// screen were tried as rivals of every name and left true names `ambiguous` (a power-law
/// saturation against a `gain_drift` of 19.8 nats whose nested evidence was negative both
/// ways).
fn quiet_rival(a: Effect, b: Effect) -> bool {
    (TIME_RIVALS.contains(&a) && TIME_RIVALS.contains(&b)) || creep_against_curve(b, a)
}

/// The best candidate other than `a`, for the report.
fn runner_up(scored: &[Candidate], a: &Candidate) -> Option<(Effect, f64)> {
    scored
        .iter()
        .find(|c| c.effect != a.effect)
        .map(|c| (c.effect, c.evidence))
}
