//! A smooth change in time as the rival of the names it imitates (issue 31).
//!
//! `drift` is a baseline linear or settling in time, `gain_drift` a sensitivity linear in time,
//! `creep` a lag of tens of seconds of a strain whose mean is not zero: each has a slow part
//! that a baseline or a sensitivity wandering in time also has. The third generator's
//! random-walk drift was named `gain_drift` (its `drift` rival under the screen, and the copies
//! of the world without it carrying no wander), and a gain cycling at a random period was named
//! `creep`: no library rival could produce what was seen, but a smooth change in time could.
//!
//! So before one of [`TIME_RIVALS`] is named, the `unexplained` test's time kind (a penalized
//! spline in time, alone and times the input, its smoothing chosen by cross-validation over
//! the training blocks: [`super::unexplained`]) is simulated as its rival, both ways, as
//! [`super::decide`] tells two names apart:
//!
//! 1. **The effect beyond time.** The channel's model with the time spline, fitted, is
//!    simulated, and the effect's evidence added after the spline measured on each copy (its
//!    best grid shape on the training blocks, as on the recording). When the recording's
//!    exceeds the copies by the rule, a change in time cannot produce what was seen: the name
//!    stands.
//! 2. **Time beyond the effect.** Otherwise the model with the effect is simulated, and the
//!    spline's evidence added after the effect measured on each copy. When the recording's
//!    exceeds them, the effect's world cannot produce what was seen and a change in time can:
//!    the name is refused ([`Verdict::Rival`]) and the channel is left to the `unexplained`
//!    test. When neither world is excluded, the library's name stands: it is the simpler
//!    explanation (the spline holds every line in time, so a linear drift never shows
//!    evidence beyond it), as a saturation stands against a hysteresis whose memory is not
//!    shown.

use serde::Serialize;

use super::calibrate::{Calibration, Verdict, RIVAL_SCREEN_NATS};
use super::search::StageSearch;
use super::terms::{Effect, Term};
use super::unexplained::{Extra, GenericKind, Residuals};
use super::Candidate;

/// The names a smooth change in time is tested against before they are given: the effects
/// whose columns have a part slower than the time spline's knots.
pub const TIME_RIVALS: [Effect; 3] = [Effect::Drift, Effect::GainDrift, Effect::Creep];

/// A name against a smooth change in time, each simulated as the other's alternative.
#[derive(Debug, Clone, Serialize)]
pub struct TimeRivalry {
    /// The candidate.
    pub effect: Effect,
    /// The candidate's evidence added after the time spline, on the recording and on copies
    /// of the model with the spline (fitted): the world of a change in time.
    pub beyond_time: Calibration,
    /// The spline's evidence added after the candidate, on the recording and on copies of the
    /// model with the candidate, when it was needed.
    pub time_beyond: Option<Calibration>,
    /// `named`: time cannot produce what was seen; `rival`: the candidate cannot, time can
    /// (the name is refused); `neither`: the simpler library name stands, unless the name was
    /// left ambiguous (`among`).
    pub verdict: Verdict,
    /// The rival: a change in time of the baseline and the sensitivity ([`GenericKind::Time`]),
    /// or, for an ambiguity, of the sensitivity alone ([`GenericKind::Sensitivity`]).
    pub rival: GenericKind,
    /// When the name was left `ambiguous`, the other contenders, each with its evidence over
    /// the rival against the rival's world, none beating it: the ambiguity is declined
    /// ([`super::decide`]); empty otherwise.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub among: Vec<(Effect, Calibration)>,
    /// `beyond_time` is the candidate's lead over the rival, each alone over the model (a
    /// wandering baseline against a wandering sensitivity, [`super::wander`]), not its
    /// evidence added after the rival.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub lead: bool,
    /// A wandering baseline's evidence over the input's generic structure (a curve, memory,
    /// history: the `unexplained` test's other kinds), against copies of the model with that
    /// structure ([`super::wander`]); absent for the other names.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub over_input: Option<Calibration>,
}

impl TimeRivalry {
    /// Whether the name is refused.
    pub fn refuses(&self) -> bool {
        self.verdict == Verdict::Rival
    }

    /// The rival, in words.
    pub fn rival_name(&self) -> &'static str {
        match self.rival {
            GenericKind::Sensitivity => "a sensitivity changing in time",
            _ => "a change in time",
        }
    }

    /// The rivalry in one sentence, from its numbers.
    pub fn sentence(&self) -> String {
        let a = self.effect.name();
        let reach = |c: &Calibration| match (c.null_max, c.bound) {
            (Some(max), Some(bound)) => format!("reaches {max:.1} (bound {bound:.1})"),
            _ => format!("not simulated (under the {}-nat screen)", c.screen),
        };
        let rival = self.rival_name();
        let first = if self.lead {
            format!(
                "{a} alone leads {rival} alone by {:.1} nats, {rival}'s world {}",
                self.beyond_time.observed,
                reach(&self.beyond_time)
            )
        } else {
            format!(
                "{a} after {rival} {:.1} nats, its world {}",
                self.beyond_time.observed,
                reach(&self.beyond_time)
            )
        };
        let input = self.over_input.as_ref().map_or(String::new(), |c| {
            format!(
                "{a} after the input's structure (a curve, memory, history) {:.1} nats, that \
                 world {}; ",
                c.observed,
                reach(c)
            )
        });
        let first = format!("{input}{first}");
        let second = self.time_beyond.as_ref().map_or(String::new(), |c| {
            format!(
                "; {rival} after {a} {:.1} nats, {a}'s world {}",
                c.observed,
                reach(c)
            )
        });
        if !self.among.is_empty() {
            let others: Vec<String> = self
                .among
                .iter()
                .map(|(e, c)| {
                    format!(
                        "{} after it {:.1} nats, its world {}",
                        e.name(),
                        c.observed,
                        reach(c)
                    )
                })
                .collect();
            let names: Vec<&str> = self.among.iter().map(|(e, _)| e.name()).collect();
            return format!(
                "{first}; {}: {a} was left ambiguous with {}, and {rival} can produce what \
                 each of them explains: none is named",
                others.join("; "),
                names.join(" and ")
            );
        }
        let verdict = match self.verdict {
            Verdict::Named => format!("{rival} cannot produce what was seen"),
            Verdict::Rival => format!("{a} cannot produce what was seen, {rival} can"),
            Verdict::Neither => {
                format!("either can produce what was seen; {a}, the simpler, stands")
            }
        };
        format!("{first}{second}: {verdict}")
    }
}

/// Seeds of the time rivalry's two bootstraps.
fn seed(round: usize, test: u64, a: Effect) -> u64 {
    0x5EED_0000_0000_0000 ^ ((round as u64) << 40) ^ (test << 32) ^ (a as u64)
}

impl StageSearch<'_, '_> {
    /// `a` against a smooth change in time (module docs); `None` for a name not in
    /// [`TIME_RIVALS`], or when a model cannot be fitted.
    pub(super) fn against_time(&self, a: &Candidate, round: usize) -> Option<TimeRivalry> {
        if !TIME_RIVALS.contains(&a.effect) {
            return None;
        }
        let beyond_time = self.beyond_time(a, round)?;
        if beyond_time.passed {
            return Some(TimeRivalry {
                effect: a.effect,
                beyond_time,
                time_beyond: None,
                verdict: Verdict::Named,
                rival: GenericKind::Time,
                among: Vec::new(),
                lead: false,
                over_input: None,
            });
        }
        // The spline after the name as it would be written: its shape refined, so that what
        // the spline finds beyond it is not the grid's coarseness (a warm-up drift between
        // the settling grid's time constants left a smooth misfit, and was refused).
        let refined = self.refine(a.clone());
        let time_beyond = self.time_beyond(&refined, round)?;
        let verdict = if time_beyond.passed {
            Verdict::Rival
        } else {
            Verdict::Neither
        };
        Some(TimeRivalry {
            effect: a.effect,
            beyond_time,
            time_beyond: Some(time_beyond),
            verdict,
            rival: GenericKind::Time,
            among: Vec::new(),
            lead: false,
            over_input: None,
        })
    }

    /// The generic test over the designs `train` and `test` of a model of this channel.
    pub(super) fn time_test<'d>(
        &'d self,
        train: &'d super::model::Design,
        test: &'d super::model::Design,
    ) -> Residuals<'d> {
        let s = self.search;
        Residuals {
            train_design: train,
            test_design: test,
            data: &s.data,
            test_data: &s.test_data,
            train: &s.train,
            test: &s.test,
            noise: &s.noises[&self.channel],
            lags: s.lags,
            span: s.span_of(self.channel),
            holdout: s.holdout(),
        }
    }

    /// Step 1: `a`'s evidence (its best grid shape) over the model with the time spline,
    /// against copies of that model.
    pub(super) fn beyond_time(&self, a: &Candidate, round: usize) -> Option<Calibration> {
        self.over_time(a, Some(round)).and_then(|(_, c)| c)
    }

    /// `a`'s evidence (its best grid shape) over the model with the time spline, on the
    /// recording; with a `round`, also calibrated against copies of that model.
    pub(super) fn over_time(
        &self,
        a: &Candidate,
        round: Option<usize>,
    ) -> Option<(f64, Option<Calibration>)> {
        self.over_kind(a, round, GenericKind::Time)
    }

    /// `a`'s evidence (its best grid shape) over the model with a sensitivity changing in
    /// time of any smooth form ([`GenericKind::Sensitivity`]), against copies of that model.
    pub(super) fn over_sensitivity(&self, a: &Candidate, round: usize) -> Option<Calibration> {
        self.over_kind(a, Some(round), GenericKind::Sensitivity)
            .and_then(|(_, c)| c)
    }

    /// `a`'s evidence (its best grid shape) over the model with the spline of `kind`, on the
    /// recording; with a `round`, also calibrated against copies of that model.
    fn over_kind(
        &self,
        a: &Candidate,
        round: Option<usize>,
        kind: GenericKind,
    ) -> Option<(f64, Option<Calibration>)> {
        let s = self.search;
        let shapes = match a.term {
            Term::Creep {
                fast_tau_s: Some(_),
                ..
            } => vec![a.term.clone()],
            _ => Term::grid(a.effect, s.span_of(self.channel)),
        };
        let from = self.model.design(&s.data, &s.inputs.0);
        let from_test = self.model.design(&s.test_data, &s.inputs.1);
        let own = from.columns.len();
        // The shape's own columns: the model's with it, less the model's (they come last).
        let extra: Vec<Extra> = shapes
            .iter()
            .map(|t| {
                let m = self.model.with(t.clone());
                let cols = m.design(&s.data, &s.inputs.0).columns.split_off(own);
                let test = s
                    .holdout()
                    .then(|| m.design(&s.test_data, &s.inputs.1).columns.split_off(own));
                (cols, test)
            })
            .collect();
        let sets: Vec<Vec<usize>> = std::iter::once(vec![0, 1])
            .chain((0..shapes.len()).map(|k| vec![0, 1, 2 + k]))
            .collect();
        let r = self.time_test(&from, &from_test);
        let g = r.generic_of(&[kind], extra, sets)?;
        let prepared = g.prepare_sets()?;
        let alternatives: Vec<usize> = (1..prepared.len()).collect();
        let (e, _, world, fuller) = g.nested(&prepared, 0, &alternatives, &g.observed())?;
        let Some(round) = round else {
            return Some((e, None));
        };
        let calibration = if e > RIVAL_SCREEN_NATS {
            g.calibrate_by(
                &world,
                &fuller,
                e,
                RIVAL_SCREEN_NATS,
                seed(
                    round,
                    if kind == GenericKind::Sensitivity {
                        6
                    } else {
                        4
                    },
                    a.effect,
                ) ^ channel_seed(self),
                &|copy| {
                    g.nested(&prepared, 0, &alternatives, copy)
                        .map_or(f64::NAN, |x| x.0)
                },
            )
        } else {
            Calibration::of(e, Vec::new(), RIVAL_SCREEN_NATS)
        };
        Some((e, Some(calibration)))
    }

    /// Whether a `drift` or a `gain_drift` is named on the channel: a change in time of any
    /// smooth form (the time spline) is then their richer form, over which a later candidate
    /// must show its evidence ([`super::decide`]).
    pub(super) fn time_named(&self) -> bool {
        self.named_terms()
            .iter()
            .any(|t| matches!(t.effect(), Effect::Drift | Effect::GainDrift))
    }

    /// Step 2: the time spline's evidence over the model with `a`, against copies of that
    /// model.
    fn time_beyond(&self, a: &Candidate, round: usize) -> Option<Calibration> {
        let s = self.search;
        let with = self.model.with(a.term.clone());
        let train = with.design(&s.data, &s.inputs.0);
        let test = with.design(&s.test_data, &s.inputs.1);
        let r = self.time_test(&train, &test);
        let g = r.generic_of(&[GenericKind::Time], Vec::new(), vec![vec![0], vec![0, 1]])?;
        let prepared = g.prepare_sets()?;
        let (e, _, world, fuller) = g.nested(&prepared, 0, &[1], &g.observed())?;
        Some(if e > RIVAL_SCREEN_NATS {
            g.calibrate_by(
                &world,
                &fuller,
                e,
                RIVAL_SCREEN_NATS,
                seed(round, 5, a.effect) ^ channel_seed(self),
                &|copy| g.nested(&prepared, 0, &[1], copy).map_or(f64::NAN, |x| x.0),
            )
        } else {
            Calibration::of(e, Vec::new(), RIVAL_SCREEN_NATS)
        })
    }
}

/// The channel's part of a seed, so that no two channels draw alike.
fn channel_seed(search: &StageSearch) -> u64 {
    match search.channel {
        super::model::Stage::Plant => 0,
        super::model::Stage::Sensor(s) => (s.index() as u64 + 1) << 48,
    }
}
